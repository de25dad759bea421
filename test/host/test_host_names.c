/* libbiss's names for its targets, loaders and triggers, and a text of its
 * own for every error code (host/lib/biss_error.c). */
#include "libbiss.h"

#include "check_run.h"

#include <check.h>
#include <string.h>

START_TEST(test_names_and_texts) {
    enum biss_target t;
    ck_assert_int_eq(biss_target_from_name("am437x-icss0", &t), BISS_OK);
    ck_assert_int_eq(t, BISS_TARGET_AM437X_ICSS0);
    /* TIDEP0022's PRU-ICSS; ICSS1 (PRU Ethernet on the IDK) by its name */
    ck_assert_int_eq(biss_target_from_name("am437x", &t), BISS_OK);
    ck_assert_int_eq(t, BISS_TARGET_AM437X_ICSS0);
    ck_assert_int_eq(biss_target_from_name("am437x-icss1", &t), BISS_OK);
    ck_assert_int_eq(t, BISS_TARGET_AM437X_ICSS1);
    enum biss_loader l;
    ck_assert_int_eq(biss_loader_from_name("remoteproc", &l), BISS_OK);
    ck_assert_int_eq(l, BISS_LOADER_REMOTEPROC);
    ck_assert_int_eq(biss_loader_from_name("devmem", &l), BISS_OK);
    ck_assert_int_eq(l, BISS_LOADER_DEVMEM);
    ck_assert_int_eq(biss_loader_from_name("uio", &l), BISS_E_INVAL);
    ck_assert_int_eq(biss_target_from_name("pi", &t), BISS_E_TARGET);
    enum biss_trigger tr;
    ck_assert_int_eq(biss_trigger_from_name("iep", &tr), BISS_OK);
    ck_assert_int_eq(tr, BISS_TRIGGER_IEP);
    ck_assert_int_eq(biss_trigger_from_name("sometimes", &tr), BISS_E_TRIGGER);
    /* every code has its own text (the lowest so far: BISS_E_SAFETY_SPEED;
     * the loops go further, so a new code is checked too) */
    ck_assert_str_ne(biss_strerror(BISS_E_SAFETY_SPEED), "unknown error");
    for (int e = 0; e >= -200; e--) {
        const char *s = biss_strerror(e);
        ck_assert_ptr_nonnull(s);
        if (strcmp(s, "unknown error") == 0) {
            continue; /* a gap in the numbering */
        }
        for (int f = e - 1; f >= -200; f--) {
            if (strcmp(biss_strerror(f), "unknown error") != 0) {
                ck_assert_str_ne(s, biss_strerror(f));
            }
        }
    }
    ck_assert_str_eq(biss_strerror(-1000), "unknown error");
}
END_TEST

int main(void) {
    Suite *s = suite_create("host_names");
    TCase *tc = tcase_create("names");
    tcase_add_test(tc, test_names_and_texts);
    suite_add_tcase(s, tc);
    return check_run(s);
}
