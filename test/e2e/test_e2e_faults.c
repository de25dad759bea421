/* End-to-end: faults that really happen on a BiSS line, scheduled in the
 * future as they come on a running machine, and noise. The firmware must
 * ride through glitches, report a lost slave and recover, and never publish
 * a wrong position as valid. */
#include "e2e_util.h"

#include "biss/biss_shm.h"
#include "scenario_json.h"

#include "check_run.h"

#include <check.h>
#include <math.h>

#ifndef SCENARIO_DIR
#error "SCENARIO_DIR must name test/scenarios"
#endif

#define MS SIM_PS_PER_MS

static struct bench *bench_for(struct e2e_run *r, const char *file) {
    scenario sc;
    char err[512];
    ck_assert_msg(scenario_load_file(file, &sc, err, sizeof err) == 0, "%s", err);
    return e2e_bench_scenario(r, &sc, NULL);
}

static sim_ps now(struct e2e_run *r) {
    return pru_time_ps(bench_core(r->b));
}

static void run_to(struct e2e_run *r, sim_ps t) {
    ck_assert_int_eq(bench_run_until(r->b, t), PRU_STOP_LIMIT);
}

/* ---- glitches keep coming for as long as the line runs (they stopped
 * after about one when the event queue cancelled the wrong events) ---- */
START_TEST(test_glitches_keep_coming) {
    struct e2e_run r;
    scenario sc;
    ck_assert_int_eq(profile_by_name("tidep0022-test-encoder", &sc), 0);
    sc.sl_line.glitch_rate_hz = 100000;
    e2e_bench_scenario(&r, &sc, NULL);
    ck_assert_uint_gt(e2e_run_frames(&r, 10, 1000, 100), 90);
    link_model *l = bench_link(r.b);
    uint64_t before = l->sl_line.glitches;
    sim_ps t0 = now(&r);
    run_to(&r, t0 + 20 * MS);
    /* Poisson, mean 2000 in 20 ms: within 5 sigma */
    uint64_t n = l->sl_line.glitches - before;
    ck_assert_uint_gt(n, 2000 - 224);
    ck_assert_uint_lt(n, 2000 + 224);
    e2e_free(&r);
}
END_TEST

/* ---- SL stuck low from a time in the future until a later one: no slave
 * reported within about a millisecond, valid frames again afterwards, no
 * wrong position ever ---- */
START_TEST(test_stuck_low_scheduled) {
    struct e2e_run r;
    scenario sc;
    ck_assert_int_eq(profile_by_name("tidep0022-test-encoder", &sc), 0);
    const sim_ps at = 5 * MS, until = 9 * MS;
    sc.sl_line.fault = _i ? LINE_STUCK_HIGH : LINE_STUCK_LOW;
    sc.sl_line.fault_at_ps = at;
    sc.sl_line.fault_until_ps = until;
    e2e_bench_scenario(&r, &sc, NULL);
    ck_assert_uint_eq(e2e_run_frames(&r, 10, 1000, 50), 50);
    ck_assert_int_lt(now(&r), at);
    fw_check_restart(&r.fc, UINT64_MAX);
    run_to(&r, at);
    uint64_t good = r.fc.frames;
    ck_assert_uint_gt(good, 50);
    ck_assert_uint_eq(r.fc.no_slave, 0);
    run_to(&r, at + 1200 * SIM_PS_PER_US); /* reported within 1.2 ms */
    ck_assert_uint_ge(r.fc.no_slave, 1);
    run_to(&r, until);
    ck_assert_uint_ge(r.fc.no_slave, 3);
    ck_assert_uint_le(r.fc.frames, good + 1); /* the frame under way when it broke */
    ck_assert_uint_eq(bench_fw_status(r.b).state, BISS_STATE_RUNNING);
    run_to(&r, until + 3 * MS);
    ck_assert_uint_gt(r.fc.frames, good + 50);
    ck_assert_uint_eq(r.fc.mismatches, 0);
    e2e_free(&r);
}
END_TEST

/* ---- noise: the scenarios scripts/bench-noise runs for 10^6 frames ----
 * Each scenario has the host's nE/nW check on (its encoder never sets
 * them: "checks": {"ew_static": [0]}), which must never refuse a good
 * frame, and its speed check (50 000 counts/s, checked at 60 000:
 * "max_speed"), which refuses a good frame only now and then (4 in 10^6
 * with glitches on both lines: a position taken when an MA glitch, not the
 * master, started the slave's frame, or the first good frame after a wrong
 * position within reach became the reference). */
static const struct noise_case {
    const char *file;
    double min_good;        /* share of publications valid with a good CRC */
    unsigned wrong_per_1e4; /* wrong positions passed as valid, at most */
    uint64_t frames;        /* 0: twice E2E_FRAMES */
    uint64_t min_misframed; /* frames the nE/nW and the speed check refused, at least each */
} noise[] = {
    {SCENARIO_DIR "/noise-sl-10khz.json", 0.95, 0, 0, 0},
    {SCENARIO_DIR "/noise-sl-100khz.json", 0.85, 0, 0, 0},
    {SCENARIO_DIR "/noise-sl-30khz-jitter.json", 0.90, 0, 0, 0},
    /* a glitch every 1.4 us on average: frames started in the slave's
     * timeout once lost the slave for good (every frame then read an idle
     * line); now the frames go on, a few wrong ones pass the CRC6 */
    {SCENARIO_DIR "/noise-sl-700khz.json", 0.50, 2, 0, 0},
    /* glitches on MA too: an extra clock makes the encoder send every later
     * bit one period early, which only the CRC6 and the host's checks see.
     * About 1 in 2500 frames is caught by each (in 10^6 frames 421 by the
     * nE/nW check, 353 by the speed check, and 6 wrong left; 581 wrong
     * without them): 30 000 frames in both builds, so that both fire */
    {SCENARIO_DIR "/noise-both-30khz-jitter.json", 0.85, 1, 30000, 1},
    /* the same with a CRC16 (0x190D9): it sees every such frame (0 wrong in
     * 10^6 with or without the host's checks, which never fire) */
    {SCENARIO_DIR "/noise-both-30khz-jitter-crc16.json", 0.80, 0, 30000, 0},
};

START_TEST(test_noise_never_valid_and_wrong) {
    const struct noise_case *c = &noise[_i];
    struct e2e_run r;
    bench_for(&r, c->file);
    ck_assert_msg(r.fc.cfg.slave[0].ew_static, "%s: no nE/nW check", c->file);
    ck_assert_msg(r.fc.cfg.slave[0].max_speed == 60000.0, "%s: no speed check", c->file);
    uint64_t frames = c->frames ? c->frames : 2 * e2e_frames(10000);
    uint64_t got = e2e_run_frames(&r, 10, 1000, frames);
    ck_assert_uint_eq(got, frames);
    /* at most wrong_per_1e4 in 10^4, rounded up: the sanitizer build's 600
     * frames would otherwise allow none where 2 in 10^4 are allowed (the
     * 700 kHz case passes some 0.7 in 10^4: 23 and 22 in 3 x 10^5 frames of
     * three seeds, before and after the stores left the clocked periods) */
    ck_assert_uint_le(r.fc.mismatches, (frames * c->wrong_per_1e4 + 9999) / 10000);
    double good = (double)(r.fc.frames - r.fc.crc_errors) / (double)r.fc.publications;
    ck_assert_msg(good >= c->min_good, "%s: %.4f of the frames good", c->file, good);
    ck_assert_uint_le(r.fc.ack_jump_good, r.fc.ack_jumps);
    ck_assert_uint_eq(r.fc.no_slave, 0);
    /* the host's checks: they fire where MA is disturbed; every frame the
     * nE/nW check refused had a wrong word, and the speed check refused at
     * most 1 good frame in 10^4 (rounded up) */
    const struct biss_safety_stats *st = &r.fc.safety.stats;
    ck_assert_msg(st->ew_set[0] >= c->min_misframed && st->pos_jumped[0] >= c->min_misframed,
                  "%s: %u misframed by nE/nW, %u by speed", c->file, st->ew_set[0],
                  st->pos_jumped[0]);
    ck_assert_uint_le(r.fc.misframed, (uint64_t)st->ew_set[0] + st->pos_jumped[0]);
    ck_assert_uint_ge(r.fc.misframed, st->ew_set[0]);
    ck_assert_uint_le(r.fc.misframed_good, (frames + 9999) / 10000);
    ck_assert_uint_ge(st->pos_checked[0], r.fc.frames / 2);
    e2e_free(&r);
}
END_TEST

int main(void) {
    Suite *s = suite_create("e2e_faults");
    TCase *tc = tcase_create("faults");
    tcase_set_timeout(tc, 600);
    tcase_add_test(tc, test_glitches_keep_coming);
    tcase_add_loop_test(tc, test_stuck_low_scheduled, 0, 2);
    tcase_add_loop_test(tc, test_noise_never_valid_and_wrong, 0,
                        (int)(sizeof noise / sizeof noise[0]));
    suite_add_tcase(s, tc);
    return check_run(s);
}
