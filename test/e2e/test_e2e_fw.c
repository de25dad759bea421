/*
 * End-to-end: the firmware's behaviour beyond the matrix — across the
 * emulator's uncertain timing parameters, with bad configurations written
 * raw, processing time at and over the limit, a disconnected and
 * reconnected slave, the three triggers and a rate change at run time.
 */
#include "e2e_util.h"

#include "biss/biss_shm.h"

#include "check_run.h"

#include <check.h>
#include <stdlib.h>

static uint64_t frames_per_case(void) {
    uint64_t n = e2e_frames(10000) / 20;
    return n < 50 ? 50 : n;
}

/* ---- uncertain parameters: shift-clock phase and divider pattern, input
 * synchronizer and output delay (emulator/core/TIMING.md) ---- */
START_TEST(test_uncertain_parameters) {
    static const int64_t phases[] = {0, 1250, 2500, 3750, 9000};
    static const int64_t gpi[] = {0, 5000, 10000, 15000};
    static const unsigned halves[] = {10, 50};
    struct pru_params p;
    pru_params_default(&p);
    p.shift_phase_ps = phases[_i % 5];
    p.gpi_delay_ps = gpi[(_i / 5) % 4];
    p.shift_frac = (_i / 20) % 2 ? PRU_FRAC_CYCLE : PRU_FRAC_EXACT;
    p.gpo_delay_ps = (_i / 40) % 2 ? 2500 : 0;
    unsigned half = halves[(_i / 80) % 2];
    struct e2e_run r;
    struct bench *b = e2e_bench(&r, _i % 2 ? "hengstler-ad38" : "tidep0022-test-encoder", 10, &p);
    uint64_t n = frames_per_case() / 4;
    ck_assert_uint_eq(e2e_run_frames(&r, half, 1000, n), n);
    ck_assert_uint_eq(r.fc.crc_errors, 0);
    ck_assert_uint_eq(r.fc.mismatches, 0);
    ck_assert_int_eq(bench_stats(b)->half_min_ps, (int64_t)half * PRU_PS_PER_CYCLE);
    ck_assert_int_eq(bench_stats(b)->half_max_ps, (int64_t)half * PRU_PS_PER_CYCLE);
    e2e_free(&r);
}
END_TEST

/* ---- the raw line delay at 4 MHz: 6.25 cycles per sample, so the frame
 * start takes 25 phases against the shift clock. The ACK edge lies at the
 * same time in every frame, so the raw ACK position of every frame is one
 * of two neighbours, whatever the phase: also when the edge falls just
 * before a window's oldest sample and the one-period ACK (shortened by the
 * line's rise/fall skew) ends before its newest, which then reads the start
 * bit ---- */
START_TEST(test_raw_delay_every_shift_phase) {
    struct pru_params p;
    pru_params_default(&p);
    p.shift_phase_ps = (int64_t)_i * 1250;
    struct e2e_run r;
    e2e_bench(&r, "tidep0022-test-encoder", 2, &p);
    ck_assert_uint_eq(e2e_run_frames(&r, 25, 1000, 10), 10);
    ck_assert_uint_eq(r.fc.mismatches, 0);
    ck_assert_msg(r.fc.delay_raw_max - r.fc.delay_raw_min <= 1,
                  "shift phase %d ps: raw ACK positions %u..%u", _i * 1250, r.fc.delay_raw_min,
                  r.fc.delay_raw_max);
    e2e_free(&r);
}
END_TEST

/* ---- data words of every awkward width: 1, 31, 32, 33, 63 and 64 bits,
 * with and without nE/nW, the position starting just below its top so the
 * high bits move. Every word as sent, CRC right, nE/nW as sent. ---- */
static const struct {
    unsigned pos_bits;
    bool ew;
} widths[] = {{1, false},  {29, true}, {30, true}, {32, false}, {31, true},
              {33, false}, {61, true}, {62, true}, {63, false}, {64, false}};

START_TEST(test_data_word_widths) {
    scenario sc;
    ck_assert_int_eq(profile_by_name("generic", &sc), 0);
    scenario_set_cable(&sc, 10.0);
    biss_slave_cfg *c = &sc.biss.s[0];
    c->pos_bits = widths[_i].pos_bits;
    c->has_err = c->has_warn = widths[_i].ew;
    c->warning = widths[_i].ew; /* nW active: a 0 among the ones */
    uint64_t top = c->pos_bits >= 64 ? ~0ull : (1ull << c->pos_bits) - 1u;
    c->pos0 = top - 20; /* wraps through all ones to zero during the run */
    c->speed_cps = 1e6;
    struct e2e_run r;
    e2e_bench_scenario(&r, &sc, NULL);
    ck_assert_uint_eq(e2e_run_frames(&r, 20, 1000, 100), 100);
    ck_assert_msg(r.fc.mismatches == 0 && r.fc.crc_errors == 0,
                  "%u position bits%s: %llu mismatches, %llu CRC errors", c->pos_bits,
                  widths[_i].ew ? " + nE/nW" : "", (unsigned long long)r.fc.mismatches,
                  (unsigned long long)r.fc.crc_errors);
    ck_assert_uint_eq(r.fc.unmatched, 0);
    if (widths[_i].ew) { /* nE high (no error), nW low (warning) in the last frame */
        ck_assert(r.fc.status[0] & BISS_RS_NE);
        ck_assert(!(r.fc.status[0] & BISS_RS_NW));
    }
    e2e_free(&r);
}
END_TEST

/* ---- configurations the host library would refuse, written raw ---- */
struct bad_cfg {
    uint32_t off, value, bytes;
    uint32_t want_error;
};

static const struct bad_cfg bad[] = {
    {BISS_CFG_NSLAVES, 0, 1, BISS_CFGERR_NSLAVES},
    {BISS_CFG_NSLAVES, 9, 1, BISS_CFGERR_NSLAVES},
    {BISS_CFG_HALF, 9, 2, BISS_CFGERR_HALF},    /* above 10 MHz */
    {BISS_CFG_HALF, 11, 2, BISS_CFGERR_HALF},   /* 9.09 MHz: no exact 8x clock */
    {BISS_CFG_HALF, 1000, 2, BISS_CFGERR_HALF}, /* 100 kHz: 1000 = 8 x 125 */
    {BISS_CFG_HALF, 1025, 2, BISS_CFGERR_HALF},
    {BISS_CFG_TRIGGER, 3, 1, BISS_CFGERR_TRIGGER},
    {BISS_CFG_SLAVE0 + BISS_CFG_S_DATA_BITS, 0, 1, BISS_CFGERR_DATA_BITS},
    {BISS_CFG_SLAVE0 + BISS_CFG_S_DATA_BITS, 65, 1, BISS_CFGERR_DATA_BITS},
    {BISS_CFG_SLAVE0 + BISS_CFG_S_CRC_BITS, 17, 1, BISS_CFGERR_CRC_BITS},
    {BISS_CFG_SLAVE0 + BISS_CFG_S_EW_SHIFT, 13, 1, BISS_CFGERR_EW}, /* nE past bit 13 */
};

START_TEST(test_bad_config_is_flagged) {
    struct e2e_run r;
    struct bench *b = e2e_bench(&r, "tidep0022-test-encoder", 2, NULL);
    /* first a good one, running */
    ck_assert_uint_eq(e2e_run_frames(&r, 10, 1000, 20), 20);
    uint32_t seq = e2e_dram32(b, BISS_CFG_SEQ);
    /* the good block again, with one field broken */
    struct fw_settings s = {.half = 10, .trigger = BISS_TRIG_FREERUN, .proc_limit = 1000};
    ck_assert_int_eq(fw_config_write(b, &s), 0);
    e2e_put(b, bad[_i].off, bad[_i].value, bad[_i].bytes);
    e2e_put(b, BISS_CFG_SEQ, seq + 2, 4);
    uint64_t pubs = r.fc.publications;
    ck_assert_int_eq(bench_run_until(b, pru_time_ps(bench_core(b)) + 2 * SIM_PS_PER_MS),
                     PRU_STOP_LIMIT); /* no fault, no halt: it goes on */
    ck_assert_uint_eq(e2e_dram32(b, BISS_ST_CFG_ACK), seq + 2);
    ck_assert_uint_eq(e2e_dram32(b, BISS_ST_CFG_ERROR), bad[_i].want_error);
    ck_assert_uint_eq(e2e_dram32(b, BISS_ST_STATE), BISS_STATE_CFG_ERROR);
    ck_assert_uint_le(r.fc.publications, pubs + 1); /* no frames on a refused config */
    /* and a good configuration brings it back */
    uint64_t frames = r.fc.frames;
    fw_check_restart(&r.fc, UINT64_MAX);
    ck_assert_uint_eq(e2e_run_frames(&r, 20, 1000, 20), 20);
    ck_assert_uint_eq(e2e_dram32(b, BISS_ST_CFG_ERROR), BISS_CFGERR_NONE);
    ck_assert_uint_eq(r.fc.mismatches, 0);
    (void)frames;
    e2e_free(&r);
}
END_TEST

/* ---- processing time: the AD38 chain is busy 2.4 us, 24 clocks at
 * 10 MHz (23 after the ACK's own): a limit of 23 passes, 22 aborts ---- */
START_TEST(test_processing_time_limit) {
    struct e2e_run r;
    struct bench *b = e2e_bench(&r, "hengstler-ad38", 2, NULL);
    ck_assert_uint_eq(e2e_run_frames(&r, 10, 23, 100), 100);
    ck_assert_uint_eq(r.fc.proc_clocks_max, 23);
    ck_assert_uint_eq(r.fc.proc_errors, 0);
    ck_assert_uint_eq(r.fc.mismatches, 0);
    struct fw_settings s = {.half = 10, .trigger = BISS_TRIG_FREERUN, .proc_limit = 22};
    e2e_configure(&r, &s);
    fw_check_restart(&r.fc, UINT64_MAX);
    e2e_run_publications(&r, 20, 20 * SIM_PS_PER_MS);
    ck_assert_uint_ge(r.fc.proc_errors, 19); /* all but the training */
    ck_assert_uint_eq(r.fc.frames, 0);
    ck_assert_uint_ge(e2e_dram32(b, BISS_ST_PROC_ERRORS), 19);
    e2e_free(&r);
}
END_TEST

/* ---- a slave that goes away (SL stuck low, or open: reads high) and
 * comes back: reported as no slave, retried, never halted ---- */
START_TEST(test_disconnect_and_reconnect) {
    static const line_fault faults[] = {LINE_STUCK_LOW, LINE_STUCK_HIGH, LINE_OPEN};
    struct e2e_run r;
    struct bench *b = e2e_bench(&r, "tidep0022-test-encoder", 10, NULL);
    ck_assert_uint_eq(e2e_run_frames(&r, 10, 1000, 50), 50);
    link_model *l = bench_link(b);
    sim_ps t = pru_time_ps(bench_core(b));
    line_dir_set_fault(_i == 2 ? &l->ma_line : &l->sl_line, t, faults[_i]);
    fw_check_restart(&r.fc, UINT64_MAX);
    ck_assert_int_eq(bench_run_until(b, t + 5 * SIM_PS_PER_MS), PRU_STOP_LIMIT);
    ck_assert_uint_gt(r.fc.no_slave, 0);
    ck_assert_uint_eq(r.fc.mismatches, 0);
    ck_assert_uint_eq(e2e_dram32(b, BISS_ST_STATE), BISS_STATE_RUNNING);
    /* reconnected: valid frames again */
    line_dir_set_fault(_i == 2 ? &l->ma_line : &l->sl_line, t + 5 * SIM_PS_PER_MS, LINE_OK);
    uint64_t before = r.fc.frames;
    ck_assert_int_eq(bench_run_until(b, t + 10 * SIM_PS_PER_MS), PRU_STOP_LIMIT);
    ck_assert_uint_gt(r.fc.frames, before + 50);
    ck_assert_uint_eq(r.fc.mismatches, 0);
    e2e_free(&r);
}
END_TEST

/* ---- triggers: host (one frame per CMD_TRIGGER), IEP (exact period) ---- */
START_TEST(test_host_trigger) {
    struct e2e_run r;
    struct bench *b = e2e_bench(&r, "tidep0022-test-encoder", 2, NULL);
    struct fw_settings s = {.half = 10, .trigger = BISS_TRIG_HOST, .proc_limit = 1000};
    ck_assert_int_eq(fw_config_write(b, &s), 0);
    ck_assert_int_eq(bench_run_until(b, 2 * SIM_PS_PER_MS), PRU_STOP_LIMIT);
    ck_assert_uint_eq(r.fc.training, 1);
    ck_assert_uint_eq(r.fc.frames, 0); /* nothing without a trigger */
    for (unsigned i = 1; i <= 5; i++) {
        e2e_put(b, BISS_CMD_TRIGGER, 1, 4);
        ck_assert_int_eq(bench_run_until(b, pru_time_ps(bench_core(b)) + SIM_PS_PER_MS),
                         PRU_STOP_LIMIT);
        ck_assert_uint_eq(r.fc.frames, i);
        ck_assert_uint_eq(e2e_dram32(b, BISS_CMD_TRIGGER), 0); /* cleared */
    }
    ck_assert_uint_eq(r.fc.mismatches, 0);
    e2e_free(&r);
}
END_TEST

START_TEST(test_iep_trigger_period) {
    struct e2e_run r;
    struct bench *b = e2e_bench(&r, "hengstler-ad38", 2, NULL);
    struct fw_settings s = {
        .half = 10, .trigger = BISS_TRIG_IEP, .iep_period = 10000, .proc_limit = 1000};
    ck_assert_int_eq(fw_config_write(b, &s), 0);
    e2e_run_publications(&r, 3, 10 * SIM_PS_PER_MS);
    bench_reset_stats(b);
    fw_check_restart(&r.fc, UINT64_MAX);
    e2e_run_publications(&r, 40, 10 * SIM_PS_PER_MS);
    const struct bench_stats *st = bench_stats(b);
    ck_assert_uint_ge(st->periods, 38);
    /* every period the same, and the IEP period (CMP0 + 1 counts, see
     * TIMING.md) to within the compare's reset tick */
    ck_assert_int_eq(st->period_min_ps, st->period_max_ps);
    ck_assert_int_ge(st->period_min_ps, 10000 * PRU_PS_PER_CYCLE);
    ck_assert_int_le(st->period_min_ps, 10001 * PRU_PS_PER_CYCLE);
    ck_assert_uint_eq(r.fc.mismatches, 0);
    ck_assert_uint_eq(r.fc.crc_errors, 0);
    e2e_free(&r);
}
END_TEST

/* ---- rate change between frames: a new configuration, a training frame,
 * then every frame right at the new rate ---- */
START_TEST(test_rate_change) {
    static const unsigned halves[] = {10, 50, 20, 100, 10};
    struct e2e_run r;
    struct bench *b = e2e_bench(&r, "posital-kit-layout-biss-c", 10, NULL);
    for (size_t i = 0; i < sizeof(halves) / sizeof(halves[0]); i++) {
        fw_check_restart(&r.fc, UINT64_MAX);
        ck_assert_uint_eq(e2e_run_frames(&r, halves[i], 1000, 100), 100);
        ck_assert_uint_eq(r.fc.mismatches, 0);
        ck_assert_uint_eq(r.fc.crc_errors, 0);
        ck_assert_uint_eq(r.fc.half, halves[i]);
        ck_assert_int_eq(bench_stats(b)->half_max_ps, (int64_t)halves[i] * PRU_PS_PER_CYCLE);
    }
    e2e_free(&r);
}
END_TEST

int main(void) {
    Suite *s = suite_create("e2e_fw");
    TCase *tc = tcase_create("fw");
    tcase_set_timeout(tc, 600);
    tcase_add_loop_test(tc, test_uncertain_parameters, 0, 160);
    tcase_add_loop_test(tc, test_raw_delay_every_shift_phase, 0, 25);
    tcase_add_loop_test(tc, test_data_word_widths, 0, (int)(sizeof(widths) / sizeof(widths[0])));
    tcase_add_loop_test(tc, test_bad_config_is_flagged, 0, (int)(sizeof(bad) / sizeof(bad[0])));
    tcase_add_test(tc, test_processing_time_limit);
    tcase_add_loop_test(tc, test_disconnect_and_reconnect, 0, 3);
    tcase_add_test(tc, test_host_trigger);
    tcase_add_test(tc, test_iep_trigger_period);
    tcase_add_test(tc, test_rate_change);
    suite_add_tcase(s, tc);
    return check_run(s);
}
