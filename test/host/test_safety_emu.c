/* The safety checks through libbiss on the emulator (the real firmware
 * image): a host that polls reads a frame now and then, and the life
 * counter is judged by the frame numbers in between, so the frames it did
 * not read are no fault; the scenario files' faults are flagged and
 * counted. */
#include "libbiss-emu.h"

#include "check_run.h"

#include <check.h>
#include <string.h>

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

int main(void) {
    Suite *s = suite_create("safety_emu");
    TCase *tc = tcase_create("polled");
    tcase_set_timeout(tc, 300);
    tcase_add_test(tc, test_polled_healthy);
    tcase_add_test(tc, test_polled_frozen);
    tcase_add_loop_test(tc, test_polled_skip_and_disagree, 0, 2);
    tcase_add_test(tc, test_configure_refuses_one_crc);
    suite_add_tcase(s, tc);
    return check_run(s);
}
