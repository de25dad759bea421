/*
 * The encoder firmware (pru_slave/) on PRU1 against the C slave model
 * (emulator/slave/biss_slave.h) on the same MA waveform: SL bit by bit.
 */
#include "check_run.h"
#include "slave_fw_rig.h"

#include "scenario.h"

#include <check.h>
#include <stdio.h>

#define US SIM_PS_PER_US

/* A profile with its motion made per frame (the firmware's). */
static biss_chain_cfg chain_of(const char *profile) {
    scenario sc;
    ck_assert_int_eq(profile_by_name(profile, &sc), 0);
    for (unsigned i = 0; i < sc.biss.n; i++) {
        sc.biss.s[i].speed_cps = 0;
        sc.biss.s[i].counts_per_frame = 3 + 1000 * i;
    }
    return sc.biss;
}

static void expect_same(struct rig *r) {
    char what[200];
    unsigned d = rig_compare(r, what, sizeof what);
    ck_assert_msg(d == 0, "%u differences; first: %s", d, what);
}

__attribute__((unused)) static void try_half(unsigned half) {
    biss_chain_cfg c = chain_of("hengstler-ad38");
    c.busy_ps = 0;
    c.timeout_mode = BISS_TIMEOUT_FIXED;
    c.timeout_ps = 20 * US;
    struct rig r;
    rig_open(&r, &c, NULL);
    rig_add_n(&r, 10, half, 140, NULL, 40 * US);
    rig_run(&r);
    char what[200];
    unsigned d = rig_compare(&r, what, sizeof what);
    sim_ps lo, hi;
    unsigned n;
    rig_latency(&r, &lo, &hi, &n);
    printf("H=%u: %u differences (%s), latency %lld..%lld ps\n", half, d, what, (long long)lo,
           (long long)hi);
    rig_close(&r);
}

/* The first time after `edge` at which SL rises and stays high to `end`. */
static sim_ps sl_high_after(waveform *w, sim_ps edge, sim_ps end) {
    sim_ps t = edge, last = -1;
    for (;;) {
        sim_ps n = waveform_next_after(w, t);
        if (n == SIM_NEVER || n > end)
            break;
        t = n;
        if (waveform_level_at(w, n))
            last = n;
        else
            last = -1;
    }
    return last < 0 ? -1 : last - edge;
}

static void timeouts(const char *profile, unsigned half, int cdm, unsigned clocks) {
    biss_chain_cfg c = chain_of(profile);
    struct rig r;
    rig_open(&r, &c, NULL);
    rig_add_n(&r, 4, half, clocks, (const int[]){cdm, cdm, cdm, cdm}, 60 * US);
    rig_run(&r);
    for (unsigned k = 0; k < 4; k++) {
        sim_ps last = r.frames[k].rise[clocks - 1];
        sim_ps edge = cdm ? last + (sim_ps)half * 5000 : last;
        sim_ps end = last + 60 * US;
        printf(
            "%s H=%u cdm=%d frame %u: SL high %lld ps (fw) %lld ps (model) after the last edge\n",
            profile, half, cdm, k, (long long)sl_high_after(&r.sl, edge, end),
            (long long)sl_high_after(&r.sl_m, edge, end));
    }
    struct biss_slv_status st = rig_status(&r);
    printf("  work %u pad %u timeout %u\n", st.work, st.work_pad, st.timeout);
    rig_close(&r);
}

__attribute__((unused)) static void trace_end(const char *profile) {
    biss_chain_cfg c = chain_of(profile);
    c.timeout_mode = BISS_TIMEOUT_FIXED;
    c.timeout_ps = 20 * US;
    struct rig r;
    rig_open(&r, &c, NULL);
    rig_add_n(&r, 2, 10, 140, NULL, 30 * US);
    sim_ps last = r.frames[1].rise[139];
    rig_run_fw_until(&r, last);
    FILE *f = fopen("/tmp/slv/trace.txt", "w");
    pru_set_trace(r.core, f);
    rig_run_fw_until(&r, last + 25 * US);
    pru_set_trace(r.core, NULL);
    fclose(f);
    rig_close(&r);
}

START_TEST(explore) {

    timeouts("tidep0022-test-encoder", 10, 0, 30);
    timeouts("tidep0022-test-encoder", 10, 1, 30);
    timeouts("tidep0022-test-encoder", 100, 1, 30);
    timeouts("hengstler-ad38", 10, 0, 140);
    timeouts("hengstler-ad38", 10, 1, 140);
    timeouts("hengstler-ad38", 100, 0, 140);
    timeouts("hengstler-ad38", 100, 1, 140);
}
END_TEST

START_TEST(test_default_encoder_10mhz) {
    biss_chain_cfg c = chain_of("tidep0022-test-encoder");
    struct rig r;
    rig_open(&r, &c, NULL);
    rig_add_n(&r, 20, 10, 30, NULL, 40 * US);
    rig_run(&r);
    for (unsigned k = 0; k < 3; k++) {
        const biss_frame_record *m = rig_model_record(&r, k);
        printf("frame %u rec frame %u word %016llx model pos %llx nE %d nW %d\n", k,
               r.frames[k].rec.frame, (unsigned long long)r.frames[k].rec.word[0],
               (unsigned long long)m->s[0].position, m->s[0].nE, m->s[0].nW);
    }
    expect_same(&r);
    sim_ps lo, hi;
    unsigned n;
    rig_latency(&r, &lo, &hi, &n);
    printf("latency %lld..%lld ps over %u edges\n", (long long)lo, (long long)hi, n);
    rig_close(&r);
}
END_TEST

int main(void) {
    Suite *s = suite_create("slave_fw");
    TCase *tc = tcase_create("frames");
    tcase_add_test(tc, test_default_encoder_10mhz);
    tcase_add_test(tc, explore);
    suite_add_tcase(s, tc);
    return check_run(s);
}
