/*
 * End-to-end: the firmware under the emulator's strict mode and under
 * data-RAM contention (issue 10 items 9 and 10; emulator/core/TIMING.md),
 * and under either reading of the scratch pad's register shift.
 *
 * The clocked periods use no LOOP, load or store no data RAM (results go to
 * the scratch pad by XOUT, busy clocks and the timestamp wait in registers
 * and bank 1, docs/silicon-assumptions.md "Plan for item 9"), and keep one
 * construct strict mode knows: MVIW, the next slave's record
 * (docs/silicon-assumptions.md A3, why it stays). So every run below is
 * under every rule but mvi, in stop mode: a LOOP, a load or a store coming
 * back into a clocked period stops the core with PRU_FAULT_STRICT and fails
 * the run; strict_log_first_frame lists exactly the MVIW sites.
 */
#include "e2e_util.h"

#include "biss/biss_shm.h"
#include "fw_cd.h"
#include "pru_isa.h"

#include "check_run.h"

#include <check.h>
#include <stdio.h>
#include <string.h>

#define STRICT_KEPT (PRU_STRICT_ALL & ~PRU_STRICT_MVI) /* MVIW stays (A3) */

static const char *const profiles[] = {"tidep0022-test-encoder", "posital-kit-layout-biss-c",
                                       "hengstler-ad38", "generic", "ssi"};
#define N_PROFILES (sizeof profiles / sizeof profiles[0])
/* the short entries of the delay routine, long ones (H - 11 = 4 n + 2 + r
 * for r = 0..3) and the slow rates (768: every profile's frames stay under
 * e2e_run_frames' 1 ms each) */
static const unsigned halves[] = {10, 12, 14, 15, 16, 18, 20, 21, 24, 25, 50, 100, 768};
#define N_HALVES (sizeof halves / sizeof halves[0])

static void fault_text(struct e2e_run *r, char *buf, size_t n) {
    const struct pru_fault *f = pru_get_fault(bench_core(r->b));
    char dis[96] = "";
    if (f->cause == PRU_FAULT_STRICT)
        pru_disasm(f->word, f->pc, dis, sizeof dis);
    snprintf(buf, n, "fault cause %d rule %s at pc 0x%04x: %s", (int)f->cause,
             f->rule ? pru_strict_rule_name(f->rule) : "-", f->pc, dis);
}

/* Up to n frames of profile at H under params (e2e_run_frames allows 1 ms
 * of simulated time a frame), at least need of them: all valid and right,
 * MA half periods exactly H, no fault. */
static void run_frames(const char *profile, unsigned half, const struct pru_params *p, uint64_t n,
                       uint64_t need) {
    struct e2e_run r;
    struct bench *b = e2e_bench(&r, profile, 2, p);
    uint64_t got = e2e_run_frames(&r, half, 1000, n);
    char why[200];
    fault_text(&r, why, sizeof why);
    ck_assert_msg(got >= need, "%s H=%u: %llu of %llu frames (%s)", profile, half,
                  (unsigned long long)got, (unsigned long long)n, why);
    ck_assert_int_eq(pru_get_fault(bench_core(b))->cause, PRU_FAULT_NONE);
    ck_assert_uint_eq(r.fc.crc_errors, 0);
    ck_assert_uint_eq(r.fc.mismatches, 0);
    ck_assert_int_eq(bench_stats(b)->half_min_ps, (int64_t)half * PRU_PS_PER_CYCLE);
    ck_assert_int_eq(bench_stats(b)->half_max_ps, (int64_t)half * PRU_PS_PER_CYCLE);
    e2e_free(&r);
}

static void run_exact(const char *profile, unsigned half, const struct pru_params *p, uint64_t n) {
    run_frames(profile, half, p, n, n);
}

/* Clocked code is what runs between two MA edges at most H apart: the
 * window is the run's half period (the default, 1024, would count the
 * publication between frames as clocked for a slave whose timeout ends
 * within 1024 cycles of its last clock, as AD38's adaptive one does). */
static struct pru_params strict_params(unsigned half) {
    struct pru_params p;
    pru_params_default(&p);
    p.strict = STRICT_KEPT;
    p.strict_window = half;
    return p;
}

/* ---- strict mode ---------------------------------------------------------- */

/* Every profile (one and several slaves, with and without CRC, SSI) at
 * every kind of delay: no LOOP, no load, no store in any clocked period. */
START_TEST(strict_every_profile) {
    unsigned half = halves[_i % N_HALVES];
    struct pru_params p = strict_params(half);
    run_exact(profiles[_i / N_HALVES], half, &p, 20);
}
END_TEST

/* The largest half period: the most turns of the delay routine (252). */
START_TEST(strict_h1024) {
    struct pru_params p = strict_params(1024);
    run_exact("tidep0022-test-encoder", 1024, &p, 20);
    run_frames("hengstler-ad38", 1024, &p, 10, 5); /* frames over 1 ms: fewer */
}
END_TEST

/* One line per violation site in the order first seen: rule, instruction,
 * executions. */
static void hits_text(struct pru_core *c, char *out, size_t size) {
    const struct pru_strict_hit *h;
    uint64_t lost;
    size_t n = pru_strict_hits(c, &h, &lost);
    ck_assert_uint_eq(lost, 0);
    size_t len = 0;
    out[0] = 0;
    for (size_t i = 0; i < n; i++) {
        char dis[96];
        pru_disasm(h[i].word, h[i].pc, dis, sizeof dis);
        int k = snprintf(out + len, size - len, "%s %s x%llu\n", pru_strict_rule_name(h[i].rule),
                         dis, (unsigned long long)h[i].count);
        ck_assert_int_lt(k, (int)(size - len));
        len += (size_t)k;
    }
}

/* Every rule, logged, over the first valid frame (frame 2; frame 1 trains)
 * of the three-slave AD38 chain: only the MVIW of LOAD_RECORD, the CDS
 * period's (slave 0's record) and the switch's after slaves 0 and 1 (the
 * last slave's switch, which loads the end record, makes no MA edge after
 * its first: not clocked). */
static const char expect_ad38[] = "mvi mviw r7.w0, *r1.b0++ x1\n"
                                  "mvi mviw r7.w2, *r1.b0++ x1\n"
                                  "mvi mviw r8.w2, *r1.b0++ x1\n"
                                  "mvi mviw r6.w2, *r1.b0++ x1\n"
                                  "mvi mviw r7.w0, *r1.b0++ x2\n"
                                  "mvi mviw r7.w2, *r1.b0++ x2\n"
                                  "mvi mviw r8.w2, *r1.b0++ x2\n"
                                  "mvi mviw r6.w2, *r1.b0++ x2\n";

START_TEST(strict_log_first_frame) {
    static const unsigned h[] = {10, 15, 100};
    struct pru_params p = strict_params(h[_i]);
    p.strict = PRU_STRICT_ALL;
    p.strict_log = 1;
    struct e2e_run r;
    struct bench *b = e2e_bench(&r, "hengstler-ad38", 2, &p);
    r.fc.cfg.trigger = BISS_TRIGGER_FREERUN;
    r.fc.cfg.proc_limit = 1000;
    e2e_configure(&r, h[_i]); /* 15: no whole number of Hz */
    /* frame by frame until the first valid one; the log is cleared at each
     * publication before it (a frame's violations are logged at the MA edge
     * that closes their period, all before its publication) */
    uint64_t seen = r.fc.publications;
    int64_t end = pru_time_ps(bench_core(b)) + 5 * SIM_PS_PER_MS;
    while (r.fc.frames == 0 && pru_time_ps(bench_core(b)) < end) {
        ck_assert_int_eq(bench_run_until(b, pru_time_ps(bench_core(b)) + 200 * 1000),
                         PRU_STOP_LIMIT);
        if (r.fc.publications != seen && r.fc.frames == 0) {
            seen = r.fc.publications;
            pru_strict_clear(bench_core(b));
        }
    }
    ck_assert_uint_eq(r.fc.frames, 1);
    ck_assert_uint_eq(bench_fw_status(b).frames, 2);
    static char got[4096];
    hits_text(bench_core(b), got, sizeof got);
    ck_assert_str_eq(got, expect_ad38);
    e2e_free(&r);
}
END_TEST

/* Register access and commands under strict mode (control frames: CDM 1
 * frames, WAIT steps, IDA checks) at 10 and 1 MHz. */
static biss_cd_err run_cd(struct e2e_run *r, const biss_cd_prog *p, struct fw_cd *cd) {
    fw_cd_issue(cd, r->b, p, 10);
    int64_t end = pru_time_ps(bench_core(r->b)) + 500 * SIM_PS_PER_MS;
    while (!fw_cd_poll(cd) && pru_time_ps(bench_core(r->b)) < end) {
        int rc = bench_run_until(r->b, pru_time_ps(bench_core(r->b)) + 20 * SIM_PS_PER_US);
        char why[200];
        fault_text(r, why, sizeof why);
        ck_assert_msg(rc == PRU_STOP_LIMIT, "%s", why);
    }
    ck_assert_msg(cd->done, "the control frame did not end");
    return cd->err;
}

START_TEST(strict_control_frames) {
    static const unsigned h[] = {10, 100};
    static const uint8_t serial[] = {0x00, 0xd9, 0x01, 0x32}; /* TIDEP0022 Table 11 */
    struct pru_params p = strict_params(h[_i]);
    struct e2e_run r;
    struct bench *b = e2e_bench(&r, "tidep0022-test-encoder", 10, &p);
    ck_assert_uint_eq(e2e_run_frames(&r, h[_i], 1000, 10), 10);
    fw_check_restart(&r.fc, UINT64_MAX);
    static biss_cd_prog prog;
    struct fw_cd cd;
    ck_assert_int_eq(biss_cd_build_read(&prog, 0, 0x44, 4), BISS_CD_OK);
    ck_assert_int_eq(run_cd(&r, &prog, &cd), BISS_CD_OK);
    ck_assert_uint_eq(cd.result.good_bytes, 4);
    for (unsigned i = 0; i < 4; i++)
        ck_assert_uint_eq(cd.result.byte[i].data, serial[i]);
    ck_assert_uint_gt(r.fc.frames, 0);
    ck_assert_uint_eq(r.fc.mismatches, 0);
    ck_assert_uint_eq(r.fc.crc_errors, 0);
    ck_assert_int_eq(bench_stats(b)->half_min_ps, (int64_t)h[_i] * PRU_PS_PER_CYCLE);
    ck_assert_int_eq(bench_stats(b)->half_max_ps, (int64_t)h[_i] * PRU_PS_PER_CYCLE);
    e2e_free(&r);

    b = e2e_bench(&r, "hengstler-ad38", 2, &p);
    ck_assert_uint_eq(e2e_run_frames(&r, h[_i], 1000, 10), 10);
    fw_check_restart(&r.fc, UINT64_MAX);
    ck_assert_int_eq(biss_cd_build_command(&prog, 0x03, 3, true), BISS_CD_OK);
    ck_assert_int_eq(run_cd(&r, &prog, &cd), BISS_CD_OK);
    ck_assert_uint_eq(cd.result.ida, 0x03);
    link_model *l = bench_link(b);
    ck_assert_int_eq(link_biss(l)->ctrl[1].last_cmd, 3);
    ck_assert_int_eq(link_biss(l)->ctrl[2].last_cmd, 3);
    ck_assert_uint_eq(r.fc.mismatches, 0);
    ck_assert_uint_eq(r.fc.crc_errors, 0);
    ck_assert_int_eq(bench_stats(b)->half_min_ps, (int64_t)h[_i] * PRU_PS_PER_CYCLE);
    ck_assert_int_eq(bench_stats(b)->half_max_ps, (int64_t)h[_i] * PRU_PS_PER_CYCLE);
    e2e_free(&r);
}
END_TEST

/* ---- contention ------------------------------------------------------------ */

/* A host reading the data RAM (random, every K cycles on average, S stall
 * cycles on a PRU access that meets it): the PRU's loads and stores outside
 * the clocked periods stall, MA half periods stay exactly H, and every
 * frame is right, as without contention. */
static void contended(const char *profile, unsigned half, const char *spec, uint64_t n) {
    struct pru_params p = strict_params(half);
    char err[200];
    ck_assert_int_eq(pru_contend_parse(spec, &p, err, sizeof err), 0);
    struct e2e_run r;
    struct bench *b = e2e_bench(&r, profile, 2, &p);
    ck_assert_uint_eq(e2e_run_frames(&r, half, 1000, n), n);
    uint64_t hits, stall;
    pru_contend_stats(bench_core(b), &hits, &stall);
    printf("%s H=%u --contend %s: %llu stalls (%llu cycles), half %lld..%lld ps\n", profile, half,
           spec, (unsigned long long)hits, (unsigned long long)stall,
           (long long)bench_stats(b)->half_min_ps, (long long)bench_stats(b)->half_max_ps);
    ck_assert_uint_eq(r.fc.crc_errors, 0);
    ck_assert_uint_eq(r.fc.mismatches, 0);
    ck_assert_uint_gt(hits, 0); /* the host did meet the PRU */
    ck_assert_int_eq(bench_stats(b)->half_min_ps, (int64_t)half * PRU_PS_PER_CYCLE);
    ck_assert_int_eq(bench_stats(b)->half_max_ps, (int64_t)half * PRU_PS_PER_CYCLE);
    e2e_free(&r);
}

static const char *const contend_specs[] = {"40,1", "4,3", "2,8,random:7"};
#define N_SPECS (sizeof contend_specs / sizeof contend_specs[0])
static const unsigned contend_halves[] = {10, 15, 100};
#define N_CHALVES (sizeof contend_halves / sizeof contend_halves[0])

START_TEST(contention_exact) {
    unsigned i = (unsigned)_i;
    contended(profiles[i % N_PROFILES], contend_halves[(i / N_PROFILES) % N_CHALVES],
              contend_specs[i / (N_PROFILES * N_CHALVES)], 100);
}
END_TEST

START_TEST(contention_h1024) {
    contended("tidep0022-test-encoder", 1024, "4,3", 20);
    contended("hengstler-ad38", 768, "4,3", 10);
}
END_TEST

/* ---- the scratch pad's register shift --------------------------------------- */

/* TI documents the shift's amount (R0[4:0] registers), not its direction,
 * nor whether ZERO/FILL follow it: the firmware finds the direction at
 * configuration and runs ZERO/FILL only with R0[4:0] = 0. Every reading
 * the emulator offers gives the same, right results for chains of one to
 * three slaves. */
START_TEST(xfr_shift_readings) {
    struct pru_params p = strict_params(10);
    p.xfr_shift_sub = _i & 1;
    p.xfr_shift_fill = (_i >> 1) & 1;
    for (unsigned k = 0; k < N_PROFILES; k++)
        run_exact(profiles[k], 10, &p, 20);
    p.strict_window = 25;
    run_exact("hengstler-ad38", 25, &p, 20);
}
END_TEST

static Suite *strict_suite(void) {
    Suite *s = suite_create("e2e_strict");
    TCase *t = tcase_create("strict");
    tcase_set_timeout(t, 600);
    tcase_add_loop_test(t, strict_every_profile, 0, (int)(N_HALVES * N_PROFILES));
    tcase_add_test(t, strict_h1024);
    tcase_add_loop_test(t, strict_log_first_frame, 0, 3);
    tcase_add_loop_test(t, strict_control_frames, 0, 2);
    suite_add_tcase(s, t);
    t = tcase_create("contention");
    tcase_set_timeout(t, 600);
    tcase_add_loop_test(t, contention_exact, 0, (int)(N_PROFILES * N_CHALVES * N_SPECS));
    tcase_add_test(t, contention_h1024);
    suite_add_tcase(s, t);
    t = tcase_create("xfr_shift");
    tcase_set_timeout(t, 600);
    tcase_add_loop_test(t, xfr_shift_readings, 0, 4);
    suite_add_tcase(s, t);
    return s;
}

int main(void) {
    return check_run(strict_suite());
}
