/* The safety checks through libbiss on the emulator (the real firmware
 * image): a host that polls reads a frame now and then, and the life
 * counter is judged by the frame numbers in between, so the frames it did
 * not read are no fault; the scenario files' faults are flagged and
 * counted. */
#include "libbiss-emu.h"

#include "check_run.h"

#include <check.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#ifndef SCENARIO_DIR
#error "SCENARIO_DIR must name test/scenarios"
#endif

#define READS 60

static biss_t *open_scenario(const char *file, uint32_t freq) {
    struct biss_open_params p;
    biss_open_params_default(&p);
    p.target = BISS_TARGET_EMU;
    p.scenario_file = file;
    biss_t *h;
    int rc = biss_emu_open(&p, &h);
    ck_assert_msg(rc == BISS_OK, "open %s: %s", file, biss_strerror(rc));
    struct biss_config c;
    biss_config_default(&c);
    c.freq_hz = freq;
    ck_assert_int_eq(biss_config_from_emu(h, &c), BISS_OK); /* the scenario's checks too */
    rc = biss_configure(h, &c);
    ck_assert_msg(rc == BISS_OK, "configure: %s", biss_strerror(rc));
    return h;
}

/* Reads a frame, lets about 1 ms pass (some 15..60 frames), and again;
 * returns the OR of the safety flags from frame `from` on, and fails if
 * any came before it. */
static uint32_t poll(biss_t *h, uint32_t from, uint32_t *gaps) {
    struct biss_sample s;
    uint32_t last = 0, flags = 0;
    *gaps = 0;
    for (int i = 0; i < READS; i++) {
        ck_assert_int_eq(biss_wait_sample(h, last, 100, &s), BISS_OK);
        if (s.frame < from) {
            ck_assert_msg(!(s.safety & BISS_SAFE_FAULTS), "frame %u flagged 0x%x before the fault",
                          s.frame, s.safety);
        } else {
            flags |= s.safety;
        }
        *gaps += last && s.frame - last > 1;
        last = s.frame;
        ck_assert_int_eq(biss_run_ms(h, 1), BISS_OK);
    }
    return flags;
}

START_TEST(test_polled_healthy) {
    biss_t *h = open_scenario(SCENARIO_DIR "/safety-two-channel.json", 10000000);
    uint32_t gaps;
    ck_assert_uint_eq(poll(h, UINT32_MAX, &gaps), 0);
    ck_assert_uint_ge(gaps, READS - 2); /* the host did skip frames */
    struct biss_safety_stats st;
    ck_assert_int_eq(biss_get_safety_stats(h, &st), BISS_OK);
    ck_assert_uint_ge(st.lc_checked[0], READS - 2);
    ck_assert_uint_eq(st.lc_checked[1], st.lc_checked[0]);
    ck_assert_uint_ge(st.pair_checked[0], READS - 1);
    ck_assert_uint_eq(st.lc_frozen[0] + st.lc_skipped[0] + st.lc_frozen[1] + st.lc_skipped[1], 0);
    ck_assert_uint_eq(st.pair_disagree[0], 0);
    biss_close(h);
}
END_TEST

/* AD38's counter frozen from frame 200: every frame read after it is
 * flagged (the one whose gap spans frame 200 may read as a jump), the
 * frames before are not. */
START_TEST(test_polled_frozen) {
    biss_t *h = open_scenario(SCENARIO_DIR "/safety-frozen.json", 5000000);
    uint32_t gaps;
    uint32_t f = poll(h, 200, &gaps);
    ck_assert_uint_ne(f & BISS_SAFE_LC_FROZEN, 0);
    struct biss_safety_stats st;
    ck_assert_int_eq(biss_get_safety_stats(h, &st), BISS_OK);
    ck_assert_uint_gt(st.lc_frozen[2], 10);
    ck_assert_uint_le(st.lc_skipped[2], 1);
    biss_close(h);
}
END_TEST

START_TEST(test_polled_skip_and_disagree) {
    const char *file = _i ? SCENARIO_DIR "/safety-disagree.json" : SCENARIO_DIR "/safety-skip.json";
    biss_t *h = open_scenario(file, 10000000);
    uint32_t gaps;
    uint32_t f = poll(h, 200, &gaps);
    struct biss_safety_stats st;
    ck_assert_int_eq(biss_get_safety_stats(h, &st), BISS_OK);
    if (_i) {
        ck_assert_uint_eq(f & BISS_SAFE_FAULTS, BISS_SAFE_DISAGREE);
        ck_assert_uint_gt(st.pair_disagree[0], 10);
    } else {
        /* skipping by 2 a frame over a gap of d frames moved 2d, not d */
        ck_assert_uint_ne(f & BISS_SAFE_LC_SKIP, 0);
        ck_assert_uint_gt(st.lc_skipped[1], 10);
        ck_assert_uint_eq(st.lc_skipped[0] + st.lc_frozen[0], 0);
        ck_assert_uint_eq(st.pair_disagree[0], 0);
    }
    biss_close(h);
}
END_TEST

/* The same check with two channels of one CRC: a specific error. */
START_TEST(test_configure_refuses_one_crc) {
    biss_t *h = open_scenario(SCENARIO_DIR "/safety-two-channel.json", 10000000);
    struct biss_config c;
    ck_assert_int_eq(biss_get_config(h, &c), BISS_OK);
    c.slave[1].crc_start = c.slave[0].crc_start;
    ck_assert_int_eq(biss_configure(h, &c), BISS_E_SAFETY_CRC);
    c.pair[0].distinct_crc = false;
    c.slave[1].crc_start = 0x5A5A;
    c.slave[0].life_bits = 9; /* only 6 below nW */
    ck_assert_int_eq(biss_configure(h, &c), BISS_E_SAFETY_LIFE);
    biss_close(h);
}
END_TEST

/* ---- every check on every trigger, on both PRUs ---------------------- */

#define FAULT_FRAME 40
#define LAST_FRAME  120
#define PERIOD_NS   100000

/* The two-channel encoder with its faults from FAULT_FRAME: slave 1's life
 * counter skips, its position jumps by 1000 counts (the speed check's and
 * the pair's fault); or (ew) slave 0 sets nE from the start. The checks:
 * both life counters, the pair, slave 1's top speed (it moves 65 536
 * counts/s). */
static const char *const faulty[2] = {
    "{\"profile\": \"biss-safety-two-channel\", \"biss\": {\"slaves\": [{}, "
    "{\"life_counter_fault\": \"skip\", \"life_counter_fault_frame\": 40, "
    "\"position_fault_offset\": 1000, \"position_fault_frame\": 60}]}, "
    "\"checks\": {\"life_counter\": [0, 1], \"pairs\": [{\"a\": 0, \"b\": 1, \"shift_b\": 4, "
    "\"tolerance\": 16}], \"max_speed\": [{\"slave\": 1, \"counts_per_s\": 80000}]}}",
    "{\"profile\": \"biss-safety-two-channel\", \"biss\": {\"slaves\": [{\"error\": true}]}}",
};

static const char *scenario_file(char *path, size_t n, const char *json) {
    snprintf(path, n, "/tmp/biss-safety-XXXXXX");
    int fd = mkstemp(path);
    ck_assert_int_ge(fd, 0);
    ck_assert_int_eq(write(fd, json, strlen(json)), (ssize_t)strlen(json));
    close(fd);
    return path;
}

/* The channel under test on PRU `pru`, the default encoder on the other. */
static void open_two(unsigned pru, const char *file, biss_t *h[2]) {
    struct biss_open_params p[2];
    for (unsigned i = 0; i < 2; i++) {
        biss_open_params_default(&p[i]);
        p[i].target = BISS_TARGET_EMU;
        p[i].profile = "tidep0022-test-encoder";
    }
    p[pru].scenario_file = file;
    int rc = biss_emu_open_pair(p, h);
    ck_assert_msg(rc == BISS_OK, "open pair: %s", biss_strerror(rc));
}

static int configure(biss_t *h, enum biss_trigger t, uint32_t period_ns, bool ew) {
    struct biss_config c;
    biss_config_default(&c);
    c.freq_hz = 10000000;
    ck_assert_int_eq(biss_config_from_emu(h, &c), BISS_OK);
    c.trigger = t;
    c.iep_period_ns = period_ns;
    c.slave[0].ew_static = ew;
    return biss_configure(h, &c);
}

/* Every frame up to LAST_FRAME read (host trigger: each asked for);
 * fails on a fault flagged before frame `from`; returns the flags after. */
static uint32_t read_all(biss_t *h, bool host, uint32_t from) {
    struct biss_sample s;
    uint32_t after = 0, flags = 0;
    while (after < LAST_FRAME) {
        if (host) { /* (pending: the training frame came before the last one's frame) */
            int rc = biss_trigger(h);
            ck_assert_msg(rc == BISS_OK || (rc == BISS_E_TRIGGER_PENDING && after == 1), "%s",
                          biss_strerror(rc));
        }
        ck_assert_int_eq(biss_wait_sample(h, after, 5, &s), BISS_OK);
        ck_assert_msg(s.frame == after + 1 || after == 0, "frame %u after %u", s.frame, after);
        if (s.frame < from) {
            ck_assert_msg(!(s.safety & BISS_SAFE_FAULTS), "frame %u flagged 0x%x", s.frame,
                          s.safety);
        } else {
            flags |= s.safety;
        }
        after = s.frame;
    }
    return flags;
}

static const enum biss_trigger triggers[4] = {BISS_TRIGGER_HOST, BISS_TRIGGER_FREERUN,
                                              BISS_TRIGGER_IEP, BISS_TRIGGER_IEP_FOLLOW};

/* _i: PRU (bit 2), trigger (bits 1..0): the life counter, the pair and the
 * speed check each fire from their fault on, and nothing before; then the
 * nE/nW check on a slave that sets nE fires on every frame. Following,
 * the other PRU owns the IEP; otherwise it stays unconfigured. */
START_TEST(test_every_check_every_trigger) {
    unsigned pru = (unsigned)_i >> 2;
    enum biss_trigger t = triggers[_i & 3];
    bool follow = t == BISS_TRIGGER_IEP_FOLLOW, host = t == BISS_TRIGGER_HOST;
    uint32_t period = t == BISS_TRIGGER_IEP ? PERIOD_NS : 0;
    for (unsigned ew = 0; ew < 2; ew++) {
        char path[64];
        biss_t *h[2];
        open_two(pru, scenario_file(path, sizeof path, faulty[ew]), h);
        if (follow) {
            ck_assert_int_eq(configure(h[1 - pru], BISS_TRIGGER_IEP, PERIOD_NS, false), BISS_OK);
        }
        int rc = configure(h[pru], t, period, ew);
        ck_assert_msg(rc == BISS_OK, "PRU%u %s: %s", pru, biss_trigger_name(t), biss_strerror(rc));
        uint32_t f = read_all(h[pru], host, ew ? 0 : FAULT_FRAME);
        struct biss_safety_stats st;
        ck_assert_int_eq(biss_get_safety_stats(h[pru], &st), BISS_OK);
        if (ew) {
            ck_assert_uint_eq(f & BISS_SAFE_FAULTS, BISS_SAFE_EW_SET);
            ck_assert_uint_ge(st.ew_set[0], LAST_FRAME - 2); /* all but the training frame */
            ck_assert_uint_eq(st.ew_set[0], st.ew_checked[0]);
        } else {
            ck_assert_uint_eq(f & BISS_SAFE_FAULTS,
                              BISS_SAFE_LC_SKIP | BISS_SAFE_DISAGREE | BISS_SAFE_POS_JUMP);
            ck_assert_uint_ge(st.lc_skipped[1], 10);
            ck_assert_uint_eq(st.lc_skipped[0] + st.lc_frozen[0], 0);
            ck_assert_uint_ge(st.pair_disagree[0], 10);
            /* the jump once, then the new position taken (two frames agree) */
            ck_assert_uint_eq(st.pos_jumped[1], 1);
            ck_assert_uint_eq(st.pos_resync[1], 1);
            ck_assert_uint_ge(st.pos_checked[1], LAST_FRAME - 4);
        }
        biss_close(h[0]);
        biss_close(h[1]);
        unlink(path);
    }
}
END_TEST

/* The ring reader and the newest-sample read on one handle (a servo loop
 * reading every frame, a monitor now and then): each judged in its own
 * frame order, so a healthy encoder is never flagged, whichever read runs
 * ahead, and every frame the ring gives is judged; the counts take each
 * frame once, in frame order (a ring frame older than the newest read is
 * judged, not counted: biss_link_check's rule). _i: IEP trigger (the speed
 * check times frames by their numbers) or free-running (by timestamps). */
#define RING_MAX 256
static uint32_t newest_counted, counted_lc;

static void judged(const struct biss_sample *s, bool ring, uint32_t first) {
    ck_assert_msg(!(s->safety & BISS_SAFE_FAULTS) && !s->misframed, "%s frame %u flagged 0x%x%s",
                  ring ? "ring" : "newest", s->frame, s->safety, s->misframed ? ", misframed" : "");
    if (ring && s->frame > first + 2) {
        ck_assert_msg((s->slave[0].safety & BISS_SAFE_LC_CHECKED) &&
                          (s->slave[1].safety & BISS_SAFE_POS_CHECKED),
                      "ring frame %u not judged (0x%x, 0x%x)", s->frame, s->slave[0].safety,
                      s->slave[1].safety);
    }
    if (s->frame > newest_counted) {
        newest_counted = s->frame;
        counted_lc += (s->slave[0].safety & BISS_SAFE_LC_CHECKED) != 0;
    }
}

START_TEST(test_ring_and_newest_on_one_handle) {
    char path[64];
    biss_t *h[2];
    const char *healthy =
        "{\"profile\": \"biss-safety-two-channel\", \"checks\": {\"life_counter\": [0, 1], "
        "\"pairs\": [{\"a\": 0, \"b\": 1, \"shift_b\": 4, \"tolerance\": 16}], "
        "\"max_speed\": [{\"slave\": 1, \"counts_per_s\": 80000}]}}";
    open_two(0, scenario_file(path, sizeof path, healthy), h);
    bool iep = _i == 0;
    ck_assert_int_eq(
        configure(h[0], iep ? BISS_TRIGGER_IEP : BISS_TRIGGER_FREERUN, iep ? PERIOD_NS : 0, false),
        BISS_OK);
    static struct biss_sample ring[RING_MAX];
    struct biss_sample s;
    uint32_t ring_frames = 0, newest_reads = 0, first = 0, last_ring = 0;
    newest_counted = counted_lc = 0;
    for (int round = 0; round < 12; round++) {
        ck_assert_int_eq(biss_run_ms(h[0], 1), BISS_OK); /* 10 frames (IEP), ~45 (free) */
        if (round % 2) { /* the newest frame first: ahead of every frame the ring holds */
            ck_assert_int_eq(biss_read_sample(h[0], &s), BISS_OK);
            judged(&s, false, first);
            newest_reads++;
        }
        unsigned n;
        uint32_t lost;
        ck_assert_int_eq(biss_ring_read(h[0], ring, RING_MAX, &n, &lost), BISS_OK);
        ck_assert_uint_eq(lost, 0);
        for (unsigned i = 0; i < n; i++) {
            first = first ? first : ring[i].frame;
            ck_assert(last_ring == 0 || ring[i].frame == last_ring + 1);
            last_ring = ring[i].frame;
            judged(&ring[i], true, first);
        }
        ring_frames += n;
    }
    ck_assert_uint_ge(ring_frames, 100);
    ck_assert_uint_ge(newest_reads, 6);
    struct biss_safety_stats st;
    ck_assert_int_eq(biss_get_safety_stats(h[0], &st), BISS_OK);
    ck_assert_uint_eq(st.lc_checked[0], counted_lc);
    ck_assert_uint_lt(st.lc_checked[0], ring_frames); /* the newest reads skipped some */
    ck_assert_uint_eq(st.lc_skipped[0] + st.lc_frozen[0] + st.lc_skipped[1] + st.lc_frozen[1], 0);
    ck_assert_uint_eq(st.pair_disagree[0] + st.pos_jumped[1], 0);
    biss_close(h[0]);
    biss_close(h[1]);
    unlink(path);
}
END_TEST

/* Following, the speed check counts frames in the owner's period; the
 * owner may take another at any time. The follower takes it from the
 * owner's accepted block as it reads (before, it judged 400 us frames by
 * 100 us and refused every position from there on), judges no frame pair
 * that may lie across the change, and still catches a jump after it. */
START_TEST(test_follower_takes_the_owners_new_period) {
    char path[64];
    biss_t *h[2];
    const char *jump_late =
        "{\"profile\": \"biss-safety-two-channel\", \"biss\": {\"slaves\": [{}, "
        "{\"position_fault_offset\": 1000, \"position_fault_frame\": 300}]}, "
        "\"checks\": {\"max_speed\": [{\"slave\": 1, \"counts_per_s\": 80000}]}}";
    open_two(1, scenario_file(path, sizeof path, jump_late), h);
    ck_assert_int_eq(configure(h[0], BISS_TRIGGER_IEP, PERIOD_NS, false), BISS_OK);
    ck_assert_int_eq(configure(h[1], BISS_TRIGGER_IEP_FOLLOW, 0, false), BISS_OK);
    static struct biss_sample ring[RING_MAX];
    uint32_t last = 0, judged_frames = 0, jumped_at = 0;
    bool newest_jumped = false;
    for (int round = 0; round < 50 && last < 340; round++) {
        if (round == 10 || round == 25) { /* 400 us, then 50 us */
            uint32_t period = round == 10 ? 4 * PERIOD_NS : PERIOD_NS / 2;
            ck_assert_int_eq(configure(h[0], BISS_TRIGGER_IEP, period, false), BISS_OK);
        }
        ck_assert_int_eq(biss_run_ms(h[0], 1), BISS_OK);
        struct biss_sample s;
        ck_assert_int_eq(biss_read_sample(h[1], &s), BISS_OK);
        /* (the newest reads see the jump once, at their first read from frame 300 on) */
        ck_assert_msg(!s.misframed || (s.frame >= 300 && !newest_jumped),
                      "newest frame %u misframed (0x%x)", s.frame, s.safety);
        newest_jumped = newest_jumped || s.misframed;
        unsigned n;
        uint32_t lost;
        ck_assert_int_eq(biss_ring_read(h[1], ring, RING_MAX, &n, &lost), BISS_OK);
        ck_assert_uint_eq(lost, 0);
        for (unsigned i = 0; i < n; i++) {
            const struct biss_sample *f = &ring[i];
            ck_assert(last == 0 || f->frame == last + 1);
            last = f->frame;
            if (f->slave[1].safety & BISS_SAFE_POS_JUMP) {
                ck_assert_msg(jumped_at == 0 && f->frame == 300, "frame %u refused", f->frame);
                jumped_at = f->frame;
            }
            ck_assert(f->misframed == (f->frame == 300));
            /* judged, but for the first frames and those read in the round a
             * new period was seen and the one after (they may lie across it) */
            bool near = round == 0 || round == 10 || round == 11 || round == 25 || round == 26;
            ck_assert_msg(near || (f->slave[1].safety & BISS_SAFE_POS_CHECKED),
                          "frame %u not judged (round %d)", f->frame, round);
            judged_frames += (f->slave[1].safety & BISS_SAFE_POS_CHECKED) != 0;
        }
    }
    ck_assert_uint_ge(last, 340);
    ck_assert_uint_eq(jumped_at, 300);
    ck_assert_uint_ge(judged_frames, last - 30);
    struct biss_config c;
    ck_assert_int_eq(biss_get_config(h[1], &c), BISS_OK);
    ck_assert_uint_eq(c.iep_period_ns, PERIOD_NS / 2);
    struct biss_safety_stats st;
    ck_assert_int_eq(biss_get_safety_stats(h[1], &st), BISS_OK);
    ck_assert_uint_eq(st.pos_jumped[1], 1);
    ck_assert_uint_eq(st.pos_resync[1], 1);
    biss_close(h[0]);
    biss_close(h[1]);
    unlink(path);
}
END_TEST

/* A speed check with no time to judge by refuses to be configured:
 * following no channel that owns the IEP (and given no period), or on the
 * timestamps while the other channel's IEP trigger restarts the count;
 * following, a period given must be the owner's. */
START_TEST(test_speed_check_without_time_refused) {
    char path[64];
    biss_t *h[2];
    open_two(1, scenario_file(path, sizeof path, faulty[0]), h);
    ck_assert_int_eq(configure(h[1], BISS_TRIGGER_IEP_FOLLOW, 0, false), BISS_E_SAFETY_SPEED);
    ck_assert_int_eq(configure(h[0], BISS_TRIGGER_IEP, PERIOD_NS, false), BISS_OK);
    ck_assert_int_eq(configure(h[1], BISS_TRIGGER_FREERUN, 0, false), BISS_E_SAFETY_SPEED);
    ck_assert_int_eq(configure(h[1], BISS_TRIGGER_HOST, 0, false), BISS_E_SAFETY_SPEED);
    ck_assert_int_eq(configure(h[1], BISS_TRIGGER_IEP_FOLLOW, 2 * PERIOD_NS, false),
                     BISS_E_IEP_PERIOD);
    ck_assert_int_eq(configure(h[1], BISS_TRIGGER_IEP_FOLLOW, 0, false), BISS_OK);
    struct biss_config c;
    ck_assert_int_eq(biss_get_config(h[1], &c), BISS_OK);
    ck_assert_uint_eq(c.iep_period_ns, PERIOD_NS); /* the owner's */
    biss_close(h[0]);
    biss_close(h[1]);
    unlink(path);
}
END_TEST

int main(void) {
    Suite *s = suite_create("safety_emu");
    TCase *tc = tcase_create("polled");
    tcase_set_timeout(tc, 300);
    tcase_add_test(tc, test_polled_healthy);
    tcase_add_test(tc, test_polled_frozen);
    tcase_add_loop_test(tc, test_polled_skip_and_disagree, 0, 2);
    tcase_add_test(tc, test_configure_refuses_one_crc);
    tcase_add_loop_test(tc, test_every_check_every_trigger, 0, 8);
    tcase_add_test(tc, test_speed_check_without_time_refused);
    tcase_add_test(tc, test_follower_takes_the_owners_new_period);
    tcase_add_loop_test(tc, test_ring_and_newest_on_one_handle, 0, 2);
    suite_add_tcase(s, tc);
    return check_run(s);
}
