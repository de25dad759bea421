/* Check suite for the bench: the clocking test image drives MA through the
 * line into the slave model; the bench's measurements must match the
 * image's exact timing and the models' delays. */
#include "bench.h"
#include "biss/biss_shm.h"
#include "bench_fw.h"
#include "pruasm.h"

#include "check_run.h"

#include <check.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static char src_dir[512];

/* test/bench/<file> assembled with HALF, CLOCKS, FRAMES and GAP. */
static struct pruasm_image assemble_frames(const char *file, unsigned half, unsigned clocks,
                                           unsigned frames, unsigned gap) {
    char path[600], d1[32], d2[32], d3[32], d4[32];
    snprintf(path, sizeof(path), "%s/test/bench/%s", src_dir, file);
    snprintf(d1, sizeof(d1), "HALF=%u", half);
    snprintf(d2, sizeof(d2), "CLOCKS=%u", clocks);
    snprintf(d3, sizeof(d3), "FRAMES=%u", frames);
    snprintf(d4, sizeof(d4), "GAP=%u", gap);
    const char *defs[] = {d1, d2, d3, d4};
    struct pruasm_options opt = {.core = 3, .defines = defs, .ndefines = 4};
    struct pruasm_image img;
    struct pruasm_diag diag = {0};
    ck_assert_msg(pruasm_assemble_file(&opt, path, &img, &diag) == 0, "%s", diag.first_error);
    return img;
}

static struct pruasm_image assemble_clock(unsigned half, unsigned clocks, unsigned frames,
                                          unsigned gap) {
    return assemble_frames("clock_frames.p", half, clocks, frames, gap);
}

static struct bench *bench_with_image(struct bench_config *cfg, struct pruasm_image *img) {
    char err[200];
    struct bench *b = bench_new(cfg, err, sizeof(err));
    ck_assert_msg(b != NULL, "%s", err);
    ck_assert_int_eq(bench_start_image(b, img->words, img->nwords * 4), 0);
    return b;
}

/* 10 frames at 10 MHz: every half period is 10 cycles, every frame is
 * closed by the slave, the frame period is the image's exact loop time. */
START_TEST(test_clocked_frames_exact_timing) {
    struct pruasm_image img = assemble_clock(10, 30, 10, 8000);
    struct bench_config cfg;
    bench_config_default(&cfg);
    struct bench *b = bench_with_image(&cfg, &img);
    enum pru_stop why = bench_run_until(b, 2 * SIM_PS_PER_MS);
    ck_assert_int_eq(why, PRU_STOP_HALT);
    bench_run_until(b, pru_time_ps(bench_core(b)) + 100 * SIM_PS_PER_US);
    const struct bench_stats *st = bench_stats(b);
    ck_assert_uint_eq(st->frames, 10);
    ck_assert_uint_eq(st->frames_started, 10);
    ck_assert_uint_eq(st->ma_edges_master, 10 * 60);
    ck_assert_uint_eq(st->ma_edges_slave, 10 * 60);
    ck_assert_int_eq(st->half_min_ps, 10 * 5000);
    ck_assert_int_eq(st->half_max_ps, 10 * 5000);
    ck_assert_uint_eq(st->half_periods, 10 * 59);
    /* frame loop: 30 clocks of 20 cycles, mov 1, gap 8000, sub+qbne 2, mov 1 */
    int64_t period = (30 * 20 + 1 + 8000 + 2 + 1) * 5000;
    ck_assert_uint_eq(st->periods, 9);
    ck_assert_int_eq(st->period_min_ps, period);
    ck_assert_int_eq(st->period_max_ps, period);
    /* the slave saw complete frames with valid records */
    const biss_frame_record *r = biss_slave_record(link_biss(bench_link(b)), 9);
    ck_assert_ptr_nonnull(r);
    ck_assert(r->acked && r->started && r->complete);
    bench_free(b);
    pruasm_image_free(&img);
}
END_TEST

/* The fast path "ma-ahead" (bench_config ma_ahead): the slave takes a
 * frame's clock edges when the core drives them. A run that ends where
 * every edge has arrived measures what the event order gives; one that
 * halts with an edge taken ahead still on the cable does not, and says so
 * (bench_ahead_overrun), so that biss-sim runs it again without. */
static void run_both(const char *file, struct bench *b[2], enum pru_stop why[2]) {
    struct pruasm_image img = assemble_frames(file, 10, 30, 4, 8000);
    for (int i = 0; i < 2; i++) {
        struct bench_config cfg;
        bench_config_default(&cfg);
        cfg.ma_ahead = i;
        b[i] = bench_with_image(&cfg, &img);
        why[i] = bench_run_until(b[i], 2 * SIM_PS_PER_MS);
    }
    pruasm_image_free(&img);
}

START_TEST(test_ma_ahead_exact_or_overrun) {
    struct bench *b[2];
    enum pru_stop why[2];
    run_both("clock_frames.p", b, why); /* halts in the gap after its frames */
    ck_assert_int_eq(why[0], PRU_STOP_HALT);
    ck_assert_int_eq(why[1], PRU_STOP_HALT);
    ck_assert_int_gt(bench_link(b[1])->ahead_last, 0); /* edges were taken ahead */
    ck_assert_int_eq(bench_link(b[0])->ahead_last, 0);
    ck_assert(!bench_ahead_overrun(b[0]) && !bench_ahead_overrun(b[1]));
    const struct bench_stats *s0 = bench_stats(b[0]), *s1 = bench_stats(b[1]);
    ck_assert_uint_eq(s1->ma_edges_slave, s0->ma_edges_slave);
    ck_assert_uint_eq(s1->half_periods, s0->half_periods);
    ck_assert_uint_eq(s1->frames, 4);
    ck_assert_uint_eq(s1->frames, s0->frames);
    for (int i = 0; i < 2; i++) {
        bench_free(b[i]);
    }
    run_both("halt_in_frame.src", b, why); /* halts right after a rise */
    ck_assert_int_eq(why[1], PRU_STOP_HALT);
    ck_assert(!bench_ahead_overrun(b[0]) && bench_ahead_overrun(b[1]));
    /* the edge on the cable: the event order leaves it short of the slave */
    ck_assert_uint_eq(bench_stats(b[1])->ma_edges_slave, bench_stats(b[0])->ma_edges_slave + 1);
    for (int i = 0; i < 2; i++) {
        bench_free(b[i]);
    }
}
END_TEST

/* The fast path "ahead-batch": the edges taken ahead measured in batches
 * (link_batch_ahead) of at most 1, 2, 5 or the bench's own number, or
 * one by one (0), or none taken ahead: the same measurements and the same
 * capture, with the run in short steps and a capture, a reset and a
 * frame limit set between them (the limit in a frame's clocks, at its
 * number: its later edges are not measured). */
START_TEST(test_ahead_batches_measure_alike) {
    struct pruasm_image img = assemble_clock(10, 30, 6, 8000);
    static const uint64_t max[] = {UINT64_MAX, 0, 1, 2, 5, 2048}; /* UINT64_MAX: not ahead */
    struct bench_stats st[6];
    sim_ps cap[6][2];
    for (int i = 0; i < 6; i++) {
        struct bench_config cfg;
        bench_config_default(&cfg);
        cfg.ma_ahead = i > 0;
        struct bench *b = bench_with_image(&cfg, &img);
        if (i > 0) {
            link_batch_ahead(bench_link(b), max[i]);
        }
        bench_capture_frame(b, 0);
        /* frame k's clocks from about 43.02k us for 3 us, then its gap */
        enum pru_stop why = PRU_STOP_LIMIT;
        for (sim_ps t = SIM_PS_PER_US / 2; why == PRU_STOP_LIMIT; t += SIM_PS_PER_US) {
            why = bench_run_until(b, t);
            if (t == 60 * SIM_PS_PER_US + SIM_PS_PER_US / 2) {
                bench_reset_stats(b); /* in frame 1's */
            }
            if (t == 87 * SIM_PS_PER_US + SIM_PS_PER_US / 2) {
                ck_assert_uint_eq(bench_current_frame(b), 2);
                bench_set_frame_limit(b, 2); /* in frame 2's clocks */
            }
        }
        ck_assert_int_eq(why, PRU_STOP_HALT);
        bench_run_until(b, pru_time_ps(bench_core(b)) + 100 * SIM_PS_PER_US);
        ck_assert(!bench_ahead_overrun(b));
        if (i > 0) {
            ck_assert_int_gt(bench_link(b)->ahead_last, 0);
        }
        waveform *pins[4];
        ck_assert_int_eq(bench_capture_get(b, pins, &cap[i][0], &cap[i][1]), 0);
        st[i] = *bench_stats(b);
        bench_free(b);
    }
    /* frame 2's clocks up to 87.5 us: about 29 of its 59 half periods */
    ck_assert_uint_gt(st[0].half_periods, 20);
    ck_assert_uint_lt(st[0].half_periods, 40);
    for (int i = 1; i < 6; i++) {
        ck_assert_uint_eq(st[i].frames, st[0].frames);
        ck_assert_uint_eq(st[i].frames_started, st[0].frames_started);
        ck_assert_uint_eq(st[i].half_periods, st[0].half_periods);
        ck_assert_int_eq(st[i].half_min_ps, st[0].half_min_ps);
        ck_assert_int_eq(st[i].half_max_ps, st[0].half_max_ps);
        ck_assert_uint_eq(st[i].periods, st[0].periods);
        ck_assert_int_eq(st[i].period_min_ps, st[0].period_min_ps);
        ck_assert_int_eq(st[i].period_max_ps, st[0].period_max_ps);
        ck_assert(st[i].period_sum_ps == st[0].period_sum_ps);
        ck_assert_uint_eq(st[i].ma_edges_master, st[0].ma_edges_master);
        ck_assert_uint_eq(st[i].ma_edges_slave, st[0].ma_edges_slave);
        ck_assert_int_eq(cap[i][0], cap[0][0]);
        ck_assert_int_eq(cap[i][1], cap[0][1]);
    }
    pruasm_image_free(&img);
}
END_TEST

/* The SL answer reaches the master one round trip after the MA edge that
 * caused it: check the ACK edge on a 100 m cable. */
START_TEST(test_round_trip_on_long_cable) {
    struct pruasm_image img = assemble_clock(100, 30, 1, 8000);
    struct bench_config cfg;
    bench_config_default(&cfg);
    scenario_set_cable(&cfg.link, 100.0);
    struct bench *b = bench_with_image(&cfg, &img);
    ck_assert_int_eq(bench_open_vcd(b, "bench_round_trip.vcd", 1), 0);
    bench_run_until(b, 200 * SIM_PS_PER_US);
    ck_assert_int_eq(bench_close_vcd(b), 0);
    const biss_frame_record *r = biss_slave_record(link_biss(bench_link(b)), 0);
    ck_assert_ptr_nonnull(r);
    ck_assert(r->complete);
    /* ACK at the slave = 2nd rising edge at the slave + output delay; the
     * 2nd rising MA edge leaves the master at 1 + 3 * 100 cycles (set r30,
     * mov, then low-high-low half periods) plus the GPO delay. */
    double ma_delay = line_nominal_delay_ps(&cfg.link.ma_line);
    double rt = bench_round_trip_ps(b);
    ck_assert(rt > 2 * 100 * 5000.0); /* 100 m each way at 5 ns/m */
    ck_assert(r->ack_ps > 0);
    ck_assert(ma_delay > 500000.0 && ma_delay < 700000.0);
    bench_free(b);
    pruasm_image_free(&img);
}
END_TEST

START_TEST(test_bad_config_is_refused) {
    struct bench_config cfg;
    bench_config_default(&cfg);
    cfg.ma_bit = 31;
    char err[200] = "";
    ck_assert_ptr_null(bench_new(&cfg, err, sizeof(err)));
    ck_assert(strstr(err, "ma_bit") != NULL);
    bench_config_default(&cfg);
    cfg.link.biss.n = 0;
    ck_assert_ptr_null(bench_new(&cfg, err, sizeof(err)));
    ck_assert(err[0] != '\0');
}
END_TEST

/* The rates the firmware clocks (biss_shm.h: BISS_MIN_HALF..BISS_MAX_HALF,
 * H = a * b for the 8x shift clock) and the names of its refusals. */
START_TEST(test_fw_rates_and_error_names) {
    static const unsigned good[] = {10, 12, 16, 20, 50, 100, 125, 500, 1024};
    for (size_t i = 0; i < sizeof good / sizeof good[0]; i++) {
        ck_assert_msg(biss_proto_half_problem(good[i]) == NULL, "H = %u", good[i]);
    }
    ck_assert_ptr_nonnull(strstr(biss_proto_half_problem(5), "faster than"));
    ck_assert_ptr_nonnull(strstr(biss_proto_half_problem(9), "faster than"));
    ck_assert_ptr_nonnull(strstr(biss_proto_half_problem(1025), "slower than"));
    /* 11 is prime and 1000 has no factor pair within 2..32; 62 = 2 x 31 has one */
    ck_assert_ptr_nonnull(strstr(biss_proto_half_problem(11), "no exact 8x shift clock"));
    ck_assert_ptr_nonnull(strstr(biss_proto_half_problem(1000), "no exact 8x shift clock"));
    ck_assert_ptr_null(biss_proto_half_problem(62));
    ck_assert_str_eq(biss_proto_cfg_error_text(BISS_CFGERR_HALF),
                     "BISS_CFGERR_HALF: MA half period out of range or no exact 8x shift clock "
                     "for it");
    for (uint32_t e = BISS_CFGERR_NSLAVES; e <= BISS_CFGERR_SSI; e++) {
        ck_assert_msg(!strncmp(biss_proto_cfg_error_text(e), "BISS_CFGERR_", 12), "code %u", e);
    }
    ck_assert_str_eq(biss_proto_cfg_error_text(99), "an error code the header does not define");
}
END_TEST

int main(void) {
    const char *d = getenv("TEST_SRC_DIR");
    snprintf(src_dir, sizeof(src_dir), "%s", d ? d : ".");
    Suite *s = suite_create("bench");
    TCase *tc = tcase_create("bench");
    tcase_set_timeout(tc, 60);
    tcase_add_test(tc, test_clocked_frames_exact_timing);
    tcase_add_test(tc, test_round_trip_on_long_cable);
    tcase_add_test(tc, test_ma_ahead_exact_or_overrun);
    tcase_add_test(tc, test_ahead_batches_measure_alike);
    tcase_add_test(tc, test_bad_config_is_refused);
    tcase_add_test(tc, test_fw_rates_and_error_names);
    suite_add_tcase(s, tc);
    return check_run(s);
}
