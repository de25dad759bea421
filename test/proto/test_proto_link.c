/* Link quality (proto/biss_link.c) on samples made here: the eye of a
 * frame from its ACK and the bit-grid flag, frames that give none, the
 * warning's blocks (set at once, held for the next whole block, dropped
 * after a clean one), a frame read twice or an older one, the counts, and
 * the command-line spelling. */
#include "biss_proto.h"

#include "check_run.h"

#include <check.h>
#include <string.h>

/* A valid frame n with this ACK position against the average. */
static struct biss_sample frame(uint32_t n, unsigned raw, unsigned avg) {
    struct biss_sample s;
    memset(&s, 0, sizeof s);
    s.frame = n;
    s.valid = true;
    s.delay.raw = (uint16_t)raw;
    s.delay.avg = (uint16_t)avg;
    return s;
}

START_TEST(test_eye_from_the_ack_and_the_grid) {
    struct biss_sample s = frame(1, 40, 40);
    ck_assert_int_eq(biss_link_eye(&s), 4); /* the ACK where the average has it */
    s = frame(1, 41, 40);
    ck_assert_int_eq(biss_link_eye(&s), 3); /* an eighth off: its rounding */
    s = frame(1, 38, 40);
    ck_assert_int_eq(biss_link_eye(&s), 2);
    s = frame(1, 44, 40);
    ck_assert_int_eq(biss_link_eye(&s), 0); /* half a bit: an ACK jump */
    s = frame(1, 60, 40);
    ck_assert_int_eq(biss_link_eye(&s), 0);
    /* refused off the grid: an edge within 2/8 before a sample point or 1/8 after */
    s = frame(1, 40, 40);
    s.valid = false;
    s.off_grid = true;
    ck_assert_int_eq(biss_link_eye(&s), BISS_LINK_EYE_OFF_GRID);
    s.delay.raw = 43;
    ck_assert_int_eq(biss_link_eye(&s), 1); /* the ACK says less */
    /* a CRC error or an ACK jump still measured the ACK */
    s = frame(1, 41, 40);
    s.valid = false;
    s.ack_jump = true;
    ck_assert_int_eq(biss_link_eye(&s), 3);
}
END_TEST

START_TEST(test_frames_without_an_eye) {
    struct biss_sample s = frame(1, 40, 40);
    s.valid = false;
    ck_assert_int_eq(biss_link_eye(&s), -1); /* no slave, aborted */
    s.training = true;
    ck_assert_int_eq(biss_link_eye(&s), -1);
    struct biss_link_state st;
    biss_link_init(&st, 0, 0);
    biss_link_check(&st, &s);
    ck_assert_int_eq(s.link_eye, -1);
    ck_assert_uint_eq(st.stats.frames, 0);
}
END_TEST

START_TEST(test_warning_blocks) {
    struct biss_link_state st;
    biss_link_init(&st, 10, 2); /* two marginal frames in a block of 10 */
    uint32_t n = 0;
    struct biss_sample s;
    for (int i = 0; i < 4; i++) { /* block 1: frames 1..4 clean */
        s = frame(++n, 40, 40);
        biss_link_check(&st, &s);
        ck_assert(!s.link_warning);
    }
    s = frame(++n, 38, 40); /* frame 5: one marginal, under the count */
    biss_link_check(&st, &s);
    ck_assert(!s.link_warning && s.link_eye == 2);
    s = frame(++n, 40, 40);
    s.off_grid = true; /* frame 6: the second: the warning at once */
    s.valid = false;
    biss_link_check(&st, &s);
    ck_assert(s.link_warning);
    for (int i = 0; i < 4; i++) { /* frames 7..10, the block's end */
        s = frame(++n, 40, 40);
        biss_link_check(&st, &s);
        ck_assert(s.link_warning);
    }
    ck_assert_uint_eq(st.stats.last_block_marginal, 2);
    for (int i = 0; i < 10; i++) { /* block 2 clean: held through it */
        s = frame(++n, 40, 40);
        biss_link_check(&st, &s);
        ck_assert_msg(s.link_warning || i == 9, "frame %u", n);
    }
    ck_assert_uint_eq(st.stats.last_block_marginal, 0);
    s = frame(++n, 41, 40); /* block 3: the last whole block was clean */
    biss_link_check(&st, &s);
    ck_assert(!s.link_warning);
    ck_assert_uint_eq(st.stats.frames, n);
    ck_assert_uint_eq(st.stats.marginal, 2);
    ck_assert_uint_eq(st.stats.off_grid, 1);
    ck_assert_uint_eq(st.stats.eye[2], 2);
    ck_assert_uint_eq(st.stats.eye[3], 1);
    ck_assert_uint_eq(st.stats.eye[4], n - 3);
    ck_assert_uint_eq(st.stats.eye_min, 2);
    ck_assert_uint_eq(st.stats.eye_sum, 4 * (n - 3) + 3 + 2 + 2);
    ck_assert_uint_eq(st.stats.warnings, 15); /* frames 6..20 */
}
END_TEST

START_TEST(test_read_twice_counts_once) {
    struct biss_link_state st;
    biss_link_init(&st, 0, 0); /* the defaults: 1 in 10000 */
    ck_assert_uint_eq(st.window, BISS_LINK_WINDOW);
    ck_assert_uint_eq(st.warn, BISS_LINK_WARN);
    struct biss_sample s = frame(7, 37, 40);
    biss_link_check(&st, &s);
    ck_assert(s.link_warning && s.link_eye == 1);
    struct biss_sample again = s;
    biss_link_check(&st, &again);
    ck_assert(again.link_warning && again.link_eye == 1);
    ck_assert_uint_eq(st.stats.frames, 1);
    ck_assert_uint_eq(st.stats.marginal, 1);
    ck_assert_uint_eq(st.stats.warnings, 1);
    /* an older frame (a second reader on the handle): its eye, no count */
    struct biss_sample old = frame(5, 30, 40);
    biss_link_check(&st, &old);
    ck_assert(old.link_eye == 0 && old.link_warning);
    ck_assert_uint_eq(st.stats.frames, 1);
    ck_assert_uint_eq(st.stats.eye[0], 0);
    /* the frame number wraps: still newer */
    biss_link_init(&st, 0, 0);
    struct biss_sample a = frame(0xffffffffu, 40, 40), b = frame(1, 40, 40);
    biss_link_check(&st, &a);
    biss_link_check(&st, &b);
    ck_assert_uint_eq(st.stats.frames, 2);
}
END_TEST

/* 2^32 - 1 frames judged, all of eye 4: the next ones start the counts
 * again, together, and the mean stays 4 (eye_sum over a wrapped frames
 * count made it 2^32 times that). */
START_TEST(test_counts_past_2_to_the_32) {
    struct biss_link_state st;
    biss_link_init(&st, 0, 0);
    st.stats.frames = UINT32_MAX - 1;
    st.stats.eye[4] = UINT32_MAX - 1;
    st.stats.eye_sum = 4 * (uint64_t)(UINT32_MAX - 1);
    for (uint32_t n = 1; n <= 3; n++) {
        struct biss_sample s = frame(n, 40, 40);
        biss_link_check(&st, &s);
        ck_assert_int_eq(s.link_eye, 4);
        ck_assert_double_eq(biss_link_eye_mean(&st.stats), 4.0);
    }
    ck_assert_uint_eq(st.stats.frames, 2);
    ck_assert_uint_eq(st.stats.eye[4], 2);
    ck_assert_uint_eq(st.stats.eye_sum, 8);
    ck_assert_uint_eq(st.stats.marginal, 0);
    struct biss_sample m = frame(4, 38, 40); /* eye 2: marginal */
    biss_link_check(&st, &m);
    ck_assert_uint_eq(st.stats.marginal, 1);
    ck_assert_double_eq_tol(biss_link_eye_mean(&st.stats), 10.0 / 3, 1e-12);
}
END_TEST

START_TEST(test_command_line_spelling) {
    uint32_t k = 0, n = 0;
    ck_assert_int_eq(biss_link_parse("3", &k, &n), BISS_OK);
    ck_assert(k == 3 && n == BISS_LINK_WINDOW);
    ck_assert_int_eq(biss_link_parse("2,500", &k, &n), BISS_OK);
    ck_assert(k == 2 && n == 500);
    ck_assert_int_eq(biss_link_parse("4294967295,4294967295", &k, &n), BISS_OK);
    ck_assert(k == 4294967295u && n == 4294967295u);
    const char *bad[] = {"",      "0", "1,0", "-1",         "1,-5",         " 1", "1,",
                         "1,2,3", "x", "1x",  "4294967296", "1,4294967296", "+1"};
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        k = n = 99;
        ck_assert_msg(biss_link_parse(bad[i], &k, &n) == BISS_E_INVAL, "'%s'", bad[i]);
        ck_assert(k == 99 && n == 99); /* nothing written */
    }
    ck_assert_int_eq(biss_link_parse(NULL, &k, &n), BISS_E_INVAL);
}
END_TEST

int main(void) {
    Suite *s = suite_create("link");
    TCase *tc = tcase_create("link");
    tcase_add_test(tc, test_eye_from_the_ack_and_the_grid);
    tcase_add_test(tc, test_frames_without_an_eye);
    tcase_add_test(tc, test_warning_blocks);
    tcase_add_test(tc, test_read_twice_counts_once);
    tcase_add_test(tc, test_counts_past_2_to_the_32);
    tcase_add_test(tc, test_command_line_spelling);
    suite_add_tcase(s, tc);
    return check_run(s);
}
