/*
 * End-to-end: the firmware image in the emulator reads every encoder
 * profile (BiSS-C, and SSI with the line delay given) at 1, 2, 5 and 10 MHz
 * over 0..100 m of cable. Where the line model says
 * the link carries the rate (line_usable), every frame must be right:
 * positions equal to what the encoders sent, no CRC error, MA half periods
 * exactly H, the line delay within one bit/8 (and one PRU cycle: biss_shm.h)
 * of the model's. Where it does
 * not, the firmware may fail frames but must never pass a wrong word as
 * right (an SSI word, which has no CRC, excepted). Frames per cell: E2E_FRAMES (default 10000).
 */
#include "e2e_util.h"

#include "biss/biss_shm.h"
#include "sim_report.h"

#include "check_run.h"

#include <check.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

static const char *const profiles[] = {"tidep0022-test-encoder", "posital-kit-layout-biss-c",
                                       "hengstler-ad38", "generic", "ssi"};
static const unsigned halves[] = {10, 20, 50, 100}; /* 10, 5, 2, 1 MHz */
static const double cables[] = {0, 2, 15, 25, 40, 65, 100};
#define NP (sizeof(profiles) / sizeof(profiles[0]))
#define NH (sizeof(halves) / sizeof(halves[0]))
#define NC (sizeof(cables) / sizeof(cables[0]))

static int usable(struct bench *b, unsigned half) {
    const scenario *sc = &bench_link(b)->sc;
    sim_ps h = (sim_ps)half * SIM_PS_PER_PRU_CYCLE;
    return line_usable(&sc->ma_line, h) && line_usable(&sc->sl_line, h);
}

START_TEST(test_cell) {
    const char *profile = profiles[_i / (NH * NC)];
    unsigned half = halves[(_i / NC) % NH];
    double cable = cables[_i % NC];
    struct e2e_run r;
    struct bench *b = e2e_bench(&r, profile, cable, NULL);
    uint64_t want = e2e_frames(10000);
    if (!usable(b, half)) {
        /* not a link: whatever happens, no wrong word is passed as right;
         * except from an SSI encoder: without a CRC nobody can tell */
        if (bench_link(b)->sc.model == &slave_model_ssi) {
            e2e_free(&r);
            return;
        }
        struct biss_config c;
        bench_fw_config(b, &c);
        c.trigger = BISS_TRIGGER_FREERUN;
        c.proc_limit = 1000;
        ck_assert_int_eq(bench_fw_configure(b, &c, half), 0);
        e2e_run_publications(&r, 200, 50 * SIM_PS_PER_MS);
        ck_assert_uint_eq(r.fc.mismatches, 0);
        e2e_free(&r);
        return;
    }
    uint64_t got = e2e_run_frames(&r, half, 1000, want);
    const struct bench_stats *st = bench_stats(b);
    ck_assert_msg(got == want, "%s H=%u %.0f m: %llu of %llu frames", profile, half, cable,
                  (unsigned long long)got, (unsigned long long)want);
    ck_assert_uint_eq(r.fc.crc_errors, 0);
    ck_assert_uint_eq(r.fc.mismatches, 0);
    ck_assert_uint_eq(r.fc.unmatched, 0);
    ck_assert_int_eq(st->half_min_ps, (int64_t)half * PRU_PS_PER_CYCLE);
    ck_assert_int_eq(st->half_max_ps, (int64_t)half * PRU_PS_PER_CYCLE);
    double bit8_ns = half / 4.0 * 5.0;
    double model_ns = bench_round_trip_ps(b) / 1000.0;
    ck_assert_msg(fabs(sim_fw_line_delay_ns(&r.fc) - model_ns) <=
                      bit8_ns + PRU_PS_PER_CYCLE / 1000.0,
                  "%s H=%u %.0f m: line delay %.1f ns, model %.1f ns", profile, half, cable,
                  sim_fw_line_delay_ns(&r.fc), model_ns);
    e2e_free(&r);
}
END_TEST

int main(void) {
    Suite *s = suite_create("e2e_matrix");
    TCase *tc = tcase_create("matrix");
    tcase_set_timeout(tc, 600);
    tcase_add_loop_test(tc, test_cell, 0, (int)(NP * NH * NC));
    suite_add_tcase(s, tc);
    return check_run(s);
}
