/*
 * End-to-end: a slave that keeps SL low (the last slave undefined after a
 * broken frame or a disconnect, biss_slave_lose_sync). The firmware's
 * training waits for SL high and would never see it; like iC-MB4's INIT
 * (two MA pulses, SL not tested first) it clocks the slave back, flags
 * that publication (BISS_RF_SL_INIT with NO_SLAVE), trains, and valid
 * frames follow, every MA half period still exactly H.
 */
#include "e2e_util.h"

#include "biss/biss_shm.h"

#include "check_run.h"

#include <check.h>

START_TEST(test_sl_stuck_low_brought_back_by_init) {
    static const unsigned halves[] = {10, 100};
    unsigned half = halves[_i];
    struct e2e_run r;
    struct bench *b = e2e_bench(&r, "tidep0022-test-encoder", 10, NULL);
    ck_assert_uint_eq(e2e_run_frames(&r, half, 1000, 20), 20);
    link_model *l = bench_link(b);
    struct pru_core *core = bench_core(b);
    sim_ps t = pru_time_ps(core);
    biss_slave_lose_sync(link_biss(l), t);
    fw_check_restart(&r.fc, UINT64_MAX);
    /* the flags of every publication, until valid frames come again */
    uint32_t flags_seen = 0;
    uint64_t pubs = 0;
    while (r.fc.frames < 20 && pru_time_ps(core) < t + 30 * SIM_PS_PER_MS) {
        ck_assert_int_eq(bench_run_until(b, pru_time_ps(core) + 5 * SIM_PS_PER_US), PRU_STOP_LIMIT);
        if (r.fc.publications != pubs) {
            pubs = r.fc.publications;
            flags_seen |= r.fc.last_flags;
        }
    }
    ck_assert_msg(r.fc.frames >= 20, "no valid frames after SL went low (flags 0x%x)", flags_seen);
    ck_assert(flags_seen & BISS_RF_SL_INIT);
    ck_assert(flags_seen & BISS_RF_TRAINING);
    ck_assert(!link_biss(l)->lost);
    ck_assert_uint_eq(r.fc.mismatches, 0);
    ck_assert_uint_eq(bench_fw_status(b).state, BISS_STATE_RUNNING);
    ck_assert_int_eq(bench_stats(b)->half_min_ps, (int64_t)half * PRU_PS_PER_CYCLE);
    ck_assert_int_eq(bench_stats(b)->half_max_ps, (int64_t)half * PRU_PS_PER_CYCLE);
    e2e_free(&r);
}
END_TEST

int main(void) {
    Suite *s = suite_create("e2e_init");
    TCase *tc = tcase_create("init");
    tcase_set_timeout(tc, 600);
    tcase_add_loop_test(tc, test_sl_stuck_low_brought_back_by_init, 0, 2);
    suite_add_tcase(s, tc);
    return check_run(s);
}
