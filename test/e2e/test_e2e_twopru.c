/*
 * End-to-end: two encoders on the two PRUs of one PRU-ICSS
 * (emulator/core/pruss.h). Each PRU runs the image built for it
 * (biss_master.bin, biss_master_pru1.bin: its own CONTROL block, GPCFG and
 * scratch-pad bank), each with its own line, encoder, configuration and
 * results; PRU0 owns the IEP (BISS_TRIG_IEP), PRU1 follows its period
 * (BISS_TRIG_IEP_FOLLOW). Both run under strict mode, the scratch-pad rule
 * (spad: PRU1 on PRU0's bank in the same cycle) included, and PRU1 must
 * never have stalled for PRU0 on a bank. Every published frame of each is
 * checked against its own encoder model, the MA half periods at both
 * master pins are exact, and the frames of the two start on the same PRU
 * cycle.
 */
#include "check_run.h"
#include "e2e_util.h"

#include "biss/biss_shm.h"
#include "pruasm.h"

#include <check.h>
#include <stdlib.h>

#define PERIOD  10000u /* IEP counts: 50 us */
#define MATCHED 40u    /* frame starts compared */

struct pair {
    struct e2e_run r[2];
};

/* Strict mode for both cores: every rule the firmware keeps to (all but
 * mvi: MVIW stays, docs/silicon-assumptions.md A3), in the clocked code of
 * the faster line at least (window: the longer half period). */
static void strict_params(struct pru_params *pp, unsigned longest_half) {
    pru_params_default(pp);
    pp->strict = PRU_STRICT_ALL & ~PRU_STRICT_MVI;
    pp->strict_window = longest_half;
}

/* The two benches of one PRU-ICSS, with cable[i] metres on PRU i's line;
 * no firmware started yet. */
static void pair_open(struct pair *p, enum pru_soc soc, const char *profile0, const char *profile1,
                      const double cable[2], const struct pru_params *pp) {
    struct bench_config cfg[2];
    const char *profile[2] = {profile0, profile1};
    for (unsigned i = 0; i < 2; i++) {
        bench_config_default(&cfg[i]);
        cfg[i].soc = soc;
        cfg[i].pru = *pp;
        ck_assert_int_eq(profile_by_name(profile[i], &cfg[i].link), 0);
        scenario_set_cable(&cfg[i].link, cable[i]);
        cfg[i].link.seed = 11 + i;
    }
    struct bench *b[2];
    char err[256];
    ck_assert_msg(bench_new_pair(cfg, b, err, sizeof err) == 0, "%s", err);
    for (unsigned i = 0; i < 2; i++) {
        p->r[i].b = b[i];
        ck_assert_uint_eq(bench_config(b[i])->pru_index, i);
    }
}

/* Each PRU with the image built for it, under strict mode and the data-RAM
 * contention `contend` (NULL: none). */
static void pair_new(struct pair *p, enum pru_soc soc, const char *profile0, const char *profile1,
                     unsigned longest_half, const char *contend) {
    struct pru_params pp;
    strict_params(&pp, longest_half);
    char err[200];
    if (contend)
        ck_assert_msg(pru_contend_parse(contend, &pp, err, sizeof err) == 0, "%s", err);
    pair_open(p, soc, profile0, profile1, (const double[2]){5, 25} /* line delays differ */, &pp);
    for (unsigned i = 0; i < 2; i++) {
        e2e_start_firmware(&p->r[i]);
        fw_check_attach(&p->r[i].fc, p->r[i].b);
    }
}

static void pair_free(struct pair *p) {
    bench_free(p->r[1].b); /* PRU1's first: PRU0's bench owns the PRU-ICSS */
    bench_free(p->r[0].b);
}

/* Runs both (running either bench runs the PRU-ICSS) by step_ps until
 * each has published n more frames, at most max_ps. */
static void pair_run(struct pair *p, uint64_t n, int64_t step_ps, int64_t max_ps,
                     void (*each)(struct pair *p, void *ctx), void *ctx) {
    uint64_t want[2] = {p->r[0].fc.publications + n, p->r[1].fc.publications + n};
    struct bench *b = p->r[0].b;
    int64_t end = pru_time_ps(bench_core(b)) + max_ps;
    while ((p->r[0].fc.publications < want[0] || p->r[1].fc.publications < want[1]) &&
           pru_time_ps(bench_core(b)) < end) {
        ck_assert_int_eq(bench_run_until(b, pru_time_ps(bench_core(b)) + step_ps), PRU_STOP_LIMIT);
        if (each)
            each(p, ctx);
    }
    ck_assert_uint_ge(p->r[0].fc.publications, want[0]);
    ck_assert_uint_ge(p->r[1].fc.publications, want[1]);
}

static void configure(struct pair *p, unsigned half0, unsigned half1) {
    static const enum biss_trigger trigger[2] = {BISS_TRIGGER_IEP, BISS_TRIGGER_IEP_FOLLOW};
    const unsigned half[2] = {half0, half1};
    for (unsigned i = 0; i < 2; i++) {
        struct biss_config *c = &p->r[i].fc.cfg;
        c->trigger = trigger[i];
        c->iep_period_ns = PERIOD * 5u; /* the follower's: the owner's, the checks time by it */
        c->proc_limit = 1000;
        ck_assert_int_eq(fw_check_configure(&p->r[i].fc, half[i]), 0);
    }
    /* training frames, the IEP set up, the first periods */
    pair_run(p, 3, 5 * SIM_PS_PER_US, 10 * SIM_PS_PER_MS, NULL, NULL);
    for (unsigned i = 0; i < 2; i++) {
        struct biss_shm_status st = bench_fw_status(p->r[i].b);
        ck_assert_uint_eq(st.state, BISS_STATE_RUNNING);
        ck_assert_uint_eq(st.cfg_error, BISS_CFGERR_NONE);
        bench_reset_stats(p->r[i].b);
        fw_check_restart(&p->r[i].fc, UINT64_MAX);
    }
}

/* The frame starts of both, as the steps see them (one frame a step at
 * most: a step is far shorter than a period). */
struct starts {
    int64_t t[2][MATCHED + 8];
    unsigned n[2];
};

static void note_starts(struct pair *p, void *ctx) {
    struct starts *s = ctx;
    for (unsigned i = 0; i < 2; i++) {
        int64_t t = bench_frame_start_ps(p->r[i].b);
        unsigned k = s->n[i];
        if (t >= 0 && (k == 0 || s->t[i][k - 1] != t) && k < MATCHED + 8)
            s->t[i][s->n[i]++] = t;
    }
}

static void check_pair_at(struct pair *p, unsigned half0, unsigned half1, uint32_t period) {
    struct starts s = {.n = {0, 0}};
    pair_run(p, MATCHED, 5 * SIM_PS_PER_US, 20 * SIM_PS_PER_MS, note_starts, &s);
    /* the same frames on both, each started on the same PRU cycle: the same
     * IEP count (5 ns each) read by both */
    ck_assert_uint_ge(s.n[0], MATCHED - 1);
    ck_assert_uint_eq(s.n[0], s.n[1]);
    for (unsigned k = 0; k < s.n[0]; k++) {
        int64_t d = s.t[0][k] - s.t[1][k];
        ck_assert_msg(llabs(d) <= PRU_PS_PER_CYCLE, "frame %u: PRU0 at %lld ps, PRU1 at %lld ps", k,
                      (long long)s.t[0][k], (long long)s.t[1][k]);
        if (k > 0) /* one IEP period apart (CMP0 + 1 counts: TIMING.md) */
            ck_assert_int_le(llabs(s.t[0][k] - s.t[0][k - 1] - period * PRU_PS_PER_CYCLE),
                             PRU_PS_PER_CYCLE);
    }
    unsigned half[2] = {half0, half1};
    for (unsigned i = 0; i < 2; i++) {
        /* each image keeps to its own bank: PRU1 never waited for PRU0 */
        ck_assert_uint_eq(pru_spad_collisions(bench_core(p->r[i].b)), 0);
        const struct bench_stats *st = bench_stats(p->r[i].b);
        ck_assert_uint_gt(st->half_periods, 100);
        ck_assert_int_eq(st->half_min_ps, (int64_t)half[i] * PRU_PS_PER_CYCLE);
        ck_assert_int_eq(st->half_max_ps, (int64_t)half[i] * PRU_PS_PER_CYCLE);
        const struct fw_check *fc = &p->r[i].fc;
        ck_assert_uint_ge(fc->frames, MATCHED - 1);
        ck_assert_uint_eq(fc->mismatches, 0);
        ck_assert_uint_eq(fc->crc_errors, 0);
        ck_assert_uint_eq(fc->half, half[i]);
    }
}

static void check_pair(struct pair *p, unsigned half0, unsigned half1) {
    check_pair_at(p, half0, half1, PERIOD);
}

/* After the first frames of a new configuration: the counts start afresh. */
static void settle(struct pair *p) {
    pair_run(p, 5, 5 * SIM_PS_PER_US, 10 * SIM_PS_PER_MS, NULL, NULL);
    for (unsigned i = 0; i < 2; i++) {
        bench_reset_stats(p->r[i].b);
        fw_check_restart(&p->r[i].fc, UINT64_MAX);
    }
}

/* profile0 on PRU0 at half0 and profile1 on PRU1 at half1, read together
 * (contend: the host's data-RAM reads, or NULL) and checked. */
static void read_pair(enum pru_soc soc, const char *profile0, const char *profile1, unsigned half0,
                      unsigned half1, const char *contend) {
    struct pair p;
    pair_new(&p, soc, profile0, profile1, half0 > half1 ? half0 : half1, contend);
    configure(&p, half0, half1);
    check_pair(&p, half0, half1);
    pair_free(&p);
}

/* Two different encoders (one slave of 12 bits + CRC6; a chain with a
 * CRC16 slave) at the same rate, on every PRU-ICSS: two axes per AM335x,
 * four per AM437x (each of its PRU-ICSS with its own IEP). */
static const enum pru_soc socs[] = {PRU_SOC_AM335X, PRU_SOC_AM437X_ICSS0, PRU_SOC_AM437X_ICSS1};

START_TEST(test_two_encoders_same_rate) {
    read_pair(socs[_i], "tidep0022-test-encoder", "hengstler-ad38", 10, 10, NULL);
}
END_TEST

/* Each PRU at its own rate (its own GPCFG divider): starts still match. */
START_TEST(test_two_encoders_own_rates) {
    read_pair(PRU_SOC_AM335X, "posital-kit-layout-biss-c", "tidep0022-test-encoder", 20, 10, NULL);
}
END_TEST

/* A chain on PRU0 and a single encoder on PRU1 at 5 MHz: the slaves'
 * bits of the two lines are read at different times. The slaves' results
 * wait in the scratch pad, whose banks both PRUs share: with one bank for
 * both, the other PRU would overwrite them here (a CRC error on every
 * frame of the chain), so this pair shows that each PRU keeps to its own. */
START_TEST(test_chain_and_single) {
    read_pair(PRU_SOC_AM335X, "hengstler-ad38", "posital-kit-layout-biss-c", 20, 20, NULL);
}
END_TEST

/* The host reading both PRUs' data RAMs: the loads before a frame stall,
 * on each PRU differently, but IEP_START reads the count after them and
 * waits from it, so the frames of both still start on the same count. */
START_TEST(test_two_encoders_contended) {
    static const char *const specs[] = {"4,3", "2,8,random:7"};
    read_pair(PRU_SOC_AM335X, "tidep0022-test-encoder", "hengstler-ad38", 10, 10, specs[_i]);
}
END_TEST

/* The AD38 on both lines at 5 m, PRU0's firmware on PRU0 and PRU1's image
 * assembled with PRU0's scratch-pad bank (-DXFR_BANK=10) on PRU1: both
 * store their slaves' results in the same bank. */
static void same_bank_open(struct pair *p, const struct pru_params *pp) {
    pair_open(p, PRU_SOC_AM335X, "hengstler-ad38", "hengstler-ad38", (const double[2]){5, 5}, pp);
    e2e_start_firmware(&p->r[0]);
    const char *defs[] = {"PRU_NUM=1", "XFR_BANK=10"};
    struct pruasm_options opt = {.core = 3, .defines = defs, .ndefines = 2};
    struct pruasm_image img;
    struct pruasm_diag diag = {0};
    ck_assert_msg(pruasm_assemble_file(&opt, FIRMWARE_SOURCE, &img, &diag) == 0, "%s",
                  diag.first_error);
    ck_assert_int_eq(bench_fw_start(p->r[1].b, img.words, img.nwords * 4), 0);
    pruasm_image_free(&img);
}

/* The same encoder and cable on both lines at the same rate, frames on the
 * same cycle: the two PRUs store each slave's result in the same cycle.
 * With their own banks nothing collides and both read right; PRU1's image
 * assembled with PRU0's bank (-DXFR_BANK=10) meets PRU0 there, and strict
 * mode's spad rule stops PRU1 at that XOUT: the rule the tests above run
 * under does catch a shared bank. */
START_TEST(test_same_line_both) {
    read_pair(PRU_SOC_AM335X, "hengstler-ad38", "hengstler-ad38", 10, 10, NULL);

    struct pair p;
    struct pru_params pp;
    pru_params_default(&pp);
    pp.strict = PRU_STRICT_SPAD;
    pp.strict_everywhere = 1;
    same_bank_open(&p, &pp);
    struct biss_config c[2];
    for (unsigned i = 0; i < 2; i++) {
        bench_fw_config(p.r[i].b, &c[i]);
        c[i].freq_hz = 10000000;
        c[i].proc_limit = 1000;
    }
    c[0].trigger = BISS_TRIGGER_IEP;
    c[0].iep_period_ns = PERIOD * 5u;
    c[1].trigger = BISS_TRIGGER_IEP_FOLLOW;
    ck_assert_int_eq(bench_fw_configure(p.r[0].b, &c[0], 0), 0);
    ck_assert_int_eq(bench_fw_configure(p.r[1].b, &c[1], 0), 0);
    struct bench *b = p.r[0].b;
    ck_assert_int_eq(bench_run_until(b, pru_time_ps(bench_core(b)) + 5 * SIM_PS_PER_MS),
                     PRU_STOP_FAULT);
    const struct pru_fault *f = pru_get_fault(bench_core(p.r[1].b));
    ck_assert_int_eq(f->cause, PRU_FAULT_STRICT);
    ck_assert_uint_eq(f->rule, PRU_STRICT_SPAD);
    ck_assert_int_eq(pru_get_fault(bench_core(b))->cause, PRU_FAULT_NONE);
    pair_free(&p);
}
END_TEST

/* What a run of the pair leaves: each PRU's time, instructions, bank
 * stalls and checked frames, and its status and results in data RAM. */
struct pair_end {
    int64_t cycles[2];
    uint64_t insns[2], stalls[2], frames[2], publications[2], mismatches[2];
    int64_t half_min[2], half_max[2];
    uint8_t dram[2][1024];
};

/* test_same_line_both's pair without strict mode: PRU1's image on PRU0's
 * bank, PRU1 stalling whenever both store a result there in one cycle;
 * run ahead (run_ahead 1) or cycle by cycle, with the fast-forward (ff)
 * or without, for 3 ms after the configuration. */
static void same_bank_run(bool ahead, bool ff, struct pair_end *e) {
    struct pair p;
    struct pru_params pp;
    pru_params_default(&pp);
    pp.run_ahead = ahead;
    pp.fast_forward = ff;
    same_bank_open(&p, &pp);
    static const enum biss_trigger trigger[2] = {BISS_TRIGGER_IEP, BISS_TRIGGER_IEP_FOLLOW};
    for (unsigned i = 0; i < 2; i++) {
        fw_check_attach(&p.r[i].fc, p.r[i].b);
        p.r[i].fc.cfg.trigger = trigger[i];
        p.r[i].fc.cfg.iep_period_ns = PERIOD * 5u;
        p.r[i].fc.cfg.proc_limit = 1000;
        ck_assert_int_eq(fw_check_configure(&p.r[i].fc, 10), 0);
    }
    struct bench *b = p.r[0].b;
    for (int k = 0; k < 600; k++) /* the bench's steps: a quarter period */
        ck_assert_int_eq(bench_run_until(b, pru_time_ps(bench_core(b)) + 5 * SIM_PS_PER_US),
                         PRU_STOP_LIMIT);
    for (unsigned i = 0; i < 2; i++) {
        struct pru_core *c = bench_core(p.r[i].b);
        const struct bench_stats *st = bench_stats(p.r[i].b);
        e->cycles[i] = pru_cycles(c);
        e->insns[i] = pru_instructions(c);
        e->stalls[i] = pru_spad_collisions(c);
        e->frames[i] = p.r[i].fc.frames;
        e->publications[i] = p.r[i].fc.publications;
        e->mismatches[i] = p.r[i].fc.mismatches;
        e->half_min[i] = st->half_min_ps;
        e->half_max[i] = st->half_max_ps;
        ck_assert_int_eq(pru_host_read(c, 0x4A300000u + 0x2000u * i, e->dram[i], sizeof e->dram[i]),
                         0);
    }
    pair_free(&p);
}

/* The two-PRU run ahead where the PRUs do interact: on one scratch-pad
 * bank PRU1 stalls for PRU0 (cross-PRU events in the clocked code of
 * both), and every stall, instruction, frame and byte of their results
 * is as cycle by cycle. */
START_TEST(test_same_bank_run_ahead) {
    struct pair_end turns, ahead, ahead_ff;
    same_bank_run(false, true, &turns);
    same_bank_run(true, false, &ahead);
    same_bank_run(true, true, &ahead_ff);
    ck_assert_uint_gt(turns.stalls[1], 10); /* they met on the bank */
    ck_assert_uint_eq(turns.stalls[0], 0);
    ck_assert_uint_gt(turns.publications[0], 40);
    ck_assert_uint_gt(turns.publications[1], 40);
    const struct pair_end *e[2] = {&ahead, &ahead_ff};
    for (unsigned k = 0; k < 2; k++) {
        for (unsigned i = 0; i < 2; i++) {
            ck_assert_int_eq(e[k]->cycles[i], turns.cycles[i]);
            ck_assert_uint_eq(e[k]->insns[i], turns.insns[i]);
            ck_assert_uint_eq(e[k]->stalls[i], turns.stalls[i]);
            ck_assert_uint_eq(e[k]->frames[i], turns.frames[i]);
            ck_assert_uint_eq(e[k]->publications[i], turns.publications[i]);
            ck_assert_uint_eq(e[k]->mismatches[i], turns.mismatches[i]);
            ck_assert_int_eq(e[k]->half_min[i], turns.half_min[i]);
            ck_assert_int_eq(e[k]->half_max[i], turns.half_max[i]);
            ck_assert_mem_eq(e[k]->dram[i], turns.dram[i], sizeof turns.dram[i]);
        }
    }
}
END_TEST

/* A follower configured before the owner: no period kept; once the
 * owner has set the IEP up, the follower works out its thresholds for that
 * period (IEP_PERIOD) and both read every period together. */
START_TEST(test_follower_before_owner) {
    struct pair p;
    pair_new(&p, PRU_SOC_AM335X, "tidep0022-test-encoder", "hengstler-ad38", 10, NULL);
    p.r[1].fc.cfg.trigger = BISS_TRIGGER_IEP_FOLLOW;
    p.r[1].fc.cfg.iep_period_ns = PERIOD * 5u; /* the owner's: the checks time by it */
    p.r[1].fc.cfg.proc_limit = 1000;
    ck_assert_int_eq(fw_check_configure(&p.r[1].fc, 10), 0);
    struct bench *b = p.r[0].b;
    ck_assert_int_eq(bench_run_until(b, pru_time_ps(bench_core(b)) + 2 * SIM_PS_PER_MS),
                     PRU_STOP_LIMIT);
    ck_assert_uint_eq(bench_fw_status(p.r[1].b).state, BISS_STATE_RUNNING);
    /* no period to keep: frames, if any (while the free count is low enough
     * for IEP_START's wait), are flagged */
    ck_assert(p.r[1].fc.frames == 0 || (p.r[1].fc.last_flags & BISS_RF_IEP_LATE));
    p.r[0].fc.cfg.trigger = BISS_TRIGGER_IEP;
    p.r[0].fc.cfg.iep_period_ns = PERIOD * 5u;
    p.r[0].fc.cfg.proc_limit = 1000;
    ck_assert_int_eq(fw_check_configure(&p.r[0].fc, 10), 0);
    settle(&p);
    check_pair(&p, 10, 10);
    pair_free(&p);
}
END_TEST

/* The owner configured anew with another period while the follower reads:
 * the follower takes the new period (its thresholds worked out again) and
 * both read every period of it together. */
START_TEST(test_owner_new_period) {
    static const uint32_t periods[] = {13000, 7000};
    struct pair p;
    pair_new(&p, PRU_SOC_AM335X, "tidep0022-test-encoder", "hengstler-ad38", 10, NULL);
    configure(&p, 10, 10);
    check_pair(&p, 10, 10);
    for (unsigned i = 0; i < 2; i++) {
        p.r[0].fc.cfg.trigger = BISS_TRIGGER_IEP;
        p.r[0].fc.cfg.iep_period_ns = periods[i] * 5u;
        p.r[0].fc.cfg.proc_limit = 1000;
        ck_assert_int_eq(fw_check_configure(&p.r[0].fc, 10), 0);
        settle(&p);
        check_pair_at(&p, 10, 10, periods[i]);
    }
    pair_free(&p);
}
END_TEST

/* PRU0's data RAM as a host reads it, whichever bench's core is asked. */
static int pru0_read(void *ctx, uint32_t off, void *buf, size_t n) {
    struct bench *b = ctx;
    return pru_host_read(bench_core(b), pru_soc_base(bench_config(b)->soc) + off, buf, n);
}

/* PRU1 alone on a PRU-ICSS (PRU0 idle), free-running: the line on PRU1's
 * pins, GPCFG1, data RAM1. */
START_TEST(test_pru1_alone) {
    struct e2e_run r;
    struct bench_config cfg;
    bench_config_default(&cfg);
    ck_assert_int_eq(profile_by_name("hengstler-ad38", &cfg.link), 0);
    cfg.pru_index = 1;
    char err[256];
    r.b = bench_new(&cfg, err, sizeof err);
    ck_assert_msg(r.b != NULL, "%s", err);
    e2e_start_firmware(&r);
    fw_check_attach(&r.fc, r.b);
    ck_assert_uint_eq(e2e_run_frames(&r, 10, 1000, 200), 200);
    ck_assert_uint_eq(r.fc.mismatches, 0);
    ck_assert_uint_eq(r.fc.crc_errors, 0);
    ck_assert_int_eq(bench_stats(r.b)->half_max_ps, 10 * PRU_PS_PER_CYCLE);
    ck_assert_int_eq(bench_stats(r.b)->half_min_ps, 10 * PRU_PS_PER_CYCLE);
    /* PRU0's data RAM untouched: the firmware used its own */
    struct biss_proto_io pru0 = {.read = pru0_read, .ctx = r.b};
    struct biss_shm_status st0;
    ck_assert_int_eq(biss_proto_status_get(&pru0, &st0), 0);
    ck_assert_uint_eq(st0.magic, 0);
    ck_assert_uint_eq(bench_fw_status(r.b).magic, BISS_MAGIC);
    uint32_t built_for = 0; /* the image says which PRU it was built for */
    struct biss_proto_io io = bench_fw_io(r.b);
    ck_assert_int_eq(biss_proto_fw_pru_get(&io, &built_for), 0);
    ck_assert_uint_eq(built_for, 1);
    e2e_free(&r);
}
END_TEST

int main(void) {
    Suite *s = suite_create("e2e_twopru");
    TCase *tc = tcase_create("twopru");
    tcase_set_timeout(tc, 600);
    tcase_add_loop_test(tc, test_two_encoders_same_rate, 0, (int)(sizeof socs / sizeof socs[0]));
    tcase_add_test(tc, test_two_encoders_own_rates);
    tcase_add_test(tc, test_chain_and_single);
    tcase_add_loop_test(tc, test_two_encoders_contended, 0, 2);
    tcase_add_test(tc, test_same_line_both);
    tcase_add_test(tc, test_pru1_alone);
    tcase_add_test(tc, test_follower_before_owner);
    tcase_add_test(tc, test_owner_new_period);
    tcase_add_test(tc, test_same_bank_run_ahead);
    suite_add_tcase(s, tc);
    return check_run(s);
}
