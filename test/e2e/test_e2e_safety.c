/* End-to-end: the host's BiSS Safety checks (proto/biss_safety.c) on every
 * frame the firmware publishes, against encoder models with injected
 * faults: a life counter that freezes or skips from a frame on, and the
 * second position word of a two-channel encoder that disagrees. Healthy
 * runs flag nothing; each fault is flagged from its frame on and counted,
 * and no other check fires. */
#include "e2e_util.h"

#include "check_run.h"

#include <check.h>

#define HALF_5MHZ  20
#define HALF_10MHZ 10

static uint64_t nframes(void) {
    return e2e_frames(2000);
}

/* The AD38 chain with its life counter (slave 2) checked. */
static scenario ad38(void) {
    scenario sc;
    ck_assert_int_eq(profile_by_name("hengstler-ad38", &sc), 0);
    sc.checks.life[2] = true;
    return sc;
}

/* The two-channel encoder: both life counters and the pair checked (the
 * 20-bit safety word shifted by 4 to the 24-bit control word's counts). */
static scenario two_channel(void) {
    scenario sc;
    ck_assert_int_eq(profile_by_name("biss-safety-two-channel", &sc), 0);
    sc.checks.life[0] = sc.checks.life[1] = true;
    sc.checks.npairs = 1;
    sc.checks.pair[0].a = 0;
    sc.checks.pair[0].b = 1;
    sc.checks.pair[0].shift_b = 4;
    sc.checks.pair[0].tolerance = 16;
    sc.checks.pair[0].distinct_crc = true;
    return sc;
}

static void run(struct e2e_run *r, const scenario *sc, unsigned half) {
    e2e_bench_scenario(r, sc, NULL);
    uint64_t n = nframes();
    ck_assert_uint_eq(e2e_run_frames(r, half, 1000, n), n);
    /* the models' words were read right: the checks judged true data */
    ck_assert_uint_eq(r->fc.mismatches, 0);
    ck_assert_uint_eq(r->fc.crc_errors, 0);
}

/* Frames the checks saw from frame `from` on, up to the last judged. */
static uint64_t frames_from(const struct e2e_run *r, uint32_t from) {
    return (uint64_t)(r->fc.safety.last_frame - from + 1);
}

START_TEST(test_healthy_runs_flag_nothing) {
    struct e2e_run r;
    scenario sc = _i ? two_channel() : ad38();
    run(&r, &sc, _i ? HALF_10MHZ : HALF_5MHZ);
    const struct biss_safety_stats *st = &r.fc.safety.stats;
    uint64_t n = nframes();
    ck_assert_uint_eq(r.fc.safety_faults, 0);
    for (unsigned i = 0; i < 3; i++) {
        ck_assert_uint_eq(st->lc_frozen[i] + st->lc_skipped[i], 0);
        /* every frame but the first (nothing to compare with) */
        ck_assert_uint_eq(st->lc_checked[i], sc.checks.life[i] ? n - 1 : 0);
    }
    ck_assert_uint_eq(st->pair_checked[0], _i ? n : 0);
    ck_assert_uint_eq(st->pair_disagree[0], 0);
    if (_i) {
        /* the coarse word trails the fine one by less than one of its counts */
        ck_assert_int_ge(st->pair_last_diff[0], 0);
        ck_assert_int_lt(st->pair_last_diff[0], 16);
    }
    e2e_free(&r);
}
END_TEST

/* AD38's life counter frozen (_i 0) or skipping (_i 1) from frame N. */
START_TEST(test_life_counter_fault) {
    struct e2e_run r;
    scenario sc = ad38();
    uint32_t at = (uint32_t)(nframes() / 2);
    sc.biss.s[2].lc_fault = _i ? BISS_LC_FAULT_SKIP : BISS_LC_FAULT_FROZEN;
    sc.biss.s[2].lc_fault_frame = at;
    run(&r, &sc, HALF_5MHZ);
    const struct biss_safety_stats *st = &r.fc.safety.stats;
    ck_assert_uint_eq(r.fc.safety_first_fault, at);
    ck_assert_uint_eq(r.fc.safety_faults, frames_from(&r, at));
    ck_assert_uint_eq(st->lc_frozen[2], _i ? 0 : frames_from(&r, at));
    ck_assert_uint_eq(st->lc_skipped[2], _i ? frames_from(&r, at) : 0);
    ck_assert_uint_eq(st->lc_checked[2], nframes() - 1);
    e2e_free(&r);
}
END_TEST

/* The safety word off by 3 of its counts (48 of the control word's) from
 * frame N: the pair disagrees from there on, the life counters stay right. */
START_TEST(test_position_disagreement) {
    struct e2e_run r;
    scenario sc = two_channel();
    uint32_t at = (uint32_t)(nframes() / 2);
    sc.biss.s[1].pos_fault_offset = 3;
    sc.biss.s[1].pos_fault_frame = at;
    run(&r, &sc, HALF_10MHZ);
    const struct biss_safety_stats *st = &r.fc.safety.stats;
    ck_assert_uint_eq(r.fc.safety_first_fault, at);
    ck_assert_uint_eq(st->pair_disagree[0], frames_from(&r, at));
    ck_assert_uint_eq(st->pair_checked[0], nframes());
    ck_assert_int_le(st->pair_last_diff[0], -48 + 15);
    ck_assert_int_ge(st->pair_last_diff[0], -48);
    ck_assert_uint_eq(st->lc_frozen[0] + st->lc_skipped[0] + st->lc_frozen[1] + st->lc_skipped[1],
                      0);
    e2e_free(&r);
}
END_TEST

/* The two channels' CRCs must differ for the pair check: the same start
 * value is refused before anything runs. */
START_TEST(test_channels_with_one_crc_refused) {
    struct e2e_run r;
    scenario sc = two_channel();
    sc.biss.s[1].crc_start = sc.biss.s[0].crc_start;
    e2e_bench_scenario(&r, &sc, NULL);
    ck_assert_int_eq(biss_safety_config_check(&r.fc.cfg), BISS_E_SAFETY_CRC);
    sc.checks.pair[0].distinct_crc = false; /* two encoders that happen to share one */
    e2e_free(&r);
    e2e_bench_scenario(&r, &sc, NULL);
    ck_assert_int_eq(biss_safety_config_check(&r.fc.cfg), BISS_OK);
    e2e_free(&r);
}
END_TEST

int main(void) {
    Suite *s = suite_create("e2e_safety");
    TCase *tc = tcase_create("safety");
    tcase_set_timeout(tc, 600);
    tcase_add_loop_test(tc, test_healthy_runs_flag_nothing, 0, 2);
    tcase_add_loop_test(tc, test_life_counter_fault, 0, 2);
    tcase_add_test(tc, test_position_disagreement);
    tcase_add_test(tc, test_channels_with_one_crc_refused);
    suite_add_tcase(s, tc);
    return check_run(s);
}
