/* Check suite for the IEP frames' judgement (emulator/bench/iep_track.h):
 * frames planted with their periods and flags, the starts and the flags in
 * either order, as the bench delivers them. */
#include "biss/biss_shm.h"
#include "iep_track.h"

#include "check_run.h"

#include <check.h>
#include <string.h>

#define P   1000  /* the period, cycles */
#define ON  37000 /* ps after the period's start: a frame on its count */
#define OFF 41000 /* one late */

struct planted {
    int64_t period_no; /* the period the frame began in */
    int64_t phase_ps;
    uint32_t flags;
};

/* Frames 0..n-1, starts first (flags_first 0) or flags first. */
static struct iep_track run(const struct planted *f, unsigned n, int flags_first) {
    struct iep_track t;
    memset(&t, 0, sizeof t);
    for (unsigned k = 0; k < n; k++) {
        if (flags_first) {
            iep_track_flags(&t, k, f[k].flags);
        }
        iep_track_start(&t, k, f[k].period_no * P, P, f[k].phase_ps);
        if (!flags_first) {
            iep_track_flags(&t, k, f[k].flags);
        }
    }
    return t;
}

START_TEST(every_period_on_its_count) {
    struct planted f[100];
    for (unsigned k = 0; k < 100; k++) {
        f[k] = (struct planted){k, ON, BISS_RF_VALID};
    }
    struct iep_track t = run(f, 100, _i);
    ck_assert_uint_eq(t.judged, 100);
    ck_assert_uint_eq(t.late, 0);
    ck_assert_uint_eq(t.unflagged_off, 0);
    ck_assert_uint_eq(t.unflagged_skips, 0);
}
END_TEST

/* A period without a frame, neither neighbour flagged: found; with the
 * frame after it flagged (it came late) or the one before (it ran into
 * it): not. */
START_TEST(a_skipped_period) {
    struct planted f[] = {{0, ON, BISS_RF_VALID},
                          {1, ON, BISS_RF_VALID},
                          {3, ON, BISS_RF_VALID},
                          {4, ON, BISS_RF_VALID}};
    struct iep_track t = run(f, 4, _i);
    ck_assert_uint_eq(t.unflagged_skips, 1);
    f[2].flags |= BISS_RF_IEP_LATE;
    f[2].phase_ps = OFF;
    t = run(f, 4, _i);
    ck_assert_uint_eq(t.unflagged_skips, 0);
    ck_assert_uint_eq(t.late, 1);
    ck_assert_uint_eq(t.unflagged_off, 0);
    f[2] = (struct planted){3, ON, BISS_RF_VALID};
    f[1].flags |= BISS_RF_IEP_LATE;
    t = run(f, 4, _i);
    ck_assert_uint_eq(t.unflagged_skips, 0);
    f[1].flags = BISS_RF_VALID;
    f[2].period_no = 5; /* three periods without a frame */
    f[3].period_no = 6;
    t = run(f, 4, _i);
    ck_assert_uint_eq(t.unflagged_skips, 3);
}
END_TEST

/* An unflagged frame at another time in its period than the first
 * unflagged one; a training frame sets no reference. */
START_TEST(an_unflagged_late_frame) {
    struct planted f[] = {{0, OFF, BISS_RF_TRAINING},
                          {1, ON, BISS_RF_VALID},
                          {2, OFF, BISS_RF_VALID},
                          {3, ON, BISS_RF_VALID}};
    struct iep_track t = run(f, 4, _i);
    ck_assert_uint_eq(t.unflagged_off, 1);
    f[2].flags |= BISS_RF_IEP_LATE;
    t = run(f, 4, _i);
    ck_assert_uint_eq(t.unflagged_off, 0);
}
END_TEST

/* A frame with only one part (its start before the measured frames, or
 * its publication after them) is not judged, nor its pair. */
START_TEST(half_known_frames) {
    struct iep_track t;
    memset(&t, 0, sizeof t);
    iep_track_start(&t, 0, 0, P, ON);
    iep_track_flags(&t, 1, BISS_RF_VALID);
    iep_track_start(&t, 5, 5 * P, P, ON);
    iep_track_flags(&t, 5, BISS_RF_VALID);
    ck_assert_uint_eq(t.judged, 1);
    ck_assert_uint_eq(t.unflagged_skips, 0);
    /* a slot reused by a frame IEP_TRACK_FRAMES later starts afresh */
    iep_track_start(&t, 5 + IEP_TRACK_FRAMES, (5 + IEP_TRACK_FRAMES) * P, P, ON);
    ck_assert_uint_eq(t.judged, 1);
    iep_track_flags(&t, 5 + IEP_TRACK_FRAMES, BISS_RF_VALID);
    ck_assert_uint_eq(t.judged, 2);
}
END_TEST

int main(void) {
    Suite *s = suite_create("iep_track");
    TCase *tc = tcase_create("judge");
    tcase_add_loop_test(tc, every_period_on_its_count, 0, 2);
    tcase_add_loop_test(tc, a_skipped_period, 0, 2);
    tcase_add_loop_test(tc, an_unflagged_late_frame, 0, 2);
    tcase_add_test(tc, half_known_frames);
    suite_add_tcase(s, tc);
    return check_run(s);
}
