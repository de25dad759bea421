/* default_image: which firmware image a program takes when none is named,
 * for programs in the build tree, in an installed tree (prefix /usr/local,
 * firmware in /lib/firmware) put down under a DESTDIR, and at the corners:
 * the image absent, a relative path reaching above the root, a build
 * directory that is only a prefix of the program's, a path too long. */
#include "check_run.h"
#include "default_image.h"

#include <check.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

static char root[] = "/tmp/default_image_XXXXXX";
static char path[PATH_MAX];

static const struct default_image d = {
    .build_dir = "/src/build",
    .build_image = "/src/build/pru_fw/x.bin",
    .bin_to_image = "../../../lib/firmware/x.bin", /* /usr/local/bin -> /lib/firmware */
    .installed = "/lib/firmware/x.bin",
};

static void setup(void) {
    ck_assert_ptr_nonnull(mkdtemp(root));
}

static void teardown(void) {
    char cmd[64];
    snprintf(cmd, sizeof cmd, "rm -rf %s", root);
    ck_assert_int_eq(system(cmd), 0);
    strcpy(root, "/tmp/default_image_XXXXXX");
}

static void put_image(void) {
    snprintf(path, sizeof path, "%s/lib", root);
    ck_assert_int_eq(mkdir(path, 0700), 0);
    snprintf(path, sizeof path, "%s/lib/firmware", root);
    ck_assert_int_eq(mkdir(path, 0700), 0);
    snprintf(path, sizeof path, "%s/lib/firmware/x.bin", root);
    FILE *f = fopen(path, "w");
    ck_assert_ptr_nonnull(f);
    fclose(f);
}

START_TEST(test_build_tree) {
    char buf[PATH_MAX];
    ck_assert_str_eq(default_image_for("/src/build/host/bissctl", &d, buf, sizeof buf),
                     d.build_image);
    /* build-arm is not inside build */
    ck_assert_str_eq(default_image_for("/src/build-arm/host/bissctl", &d, buf, sizeof buf),
                     d.installed);
}
END_TEST

/* DESTDIR=<root>: <root>/usr/local/bin/x takes <root>/lib/firmware/x.bin */
START_TEST(test_destdir_tree) {
    char exe[PATH_MAX], buf[PATH_MAX];
    put_image();
    snprintf(exe, sizeof exe, "%s/usr/local/bin/bissctl", root);
    const char *got = default_image_for(exe, &d, buf, sizeof buf);
    ck_assert_ptr_eq(got, buf);
    ck_assert_str_eq(got, path);
}
END_TEST

START_TEST(test_image_absent) {
    char exe[PATH_MAX], buf[PATH_MAX];
    snprintf(exe, sizeof exe, "%s/usr/local/bin/bissctl", root);
    ck_assert_str_eq(default_image_for(exe, &d, buf, sizeof buf), d.installed);
}
END_TEST

/* installed in /usr/local/bin: the relative path is the absolute one */
START_TEST(test_real_prefix) {
    char buf[PATH_MAX];
    const char *got = default_image_for("/usr/local/bin/bissctl", &d, buf, sizeof buf);
    ck_assert_str_eq(got, d.installed);
}
END_TEST

/* more "../" than the program's path has directories */
START_TEST(test_above_root) {
    char buf[PATH_MAX];
    ck_assert_str_eq(default_image_for("/bin/bissctl", &d, buf, sizeof buf), d.installed);
    ck_assert_str_eq(default_image_for("/bissctl", &d, buf, sizeof buf), d.installed);
}
END_TEST

START_TEST(test_too_long) {
    static char exe[PATH_MAX + 16];
    memset(exe, 'a', sizeof exe - 1);
    exe[0] = '/';
    char buf[PATH_MAX];
    ck_assert_str_eq(default_image_for(exe, &d, buf, sizeof buf), d.installed);
    /* a candidate longer than the caller's buffer is not taken */
    char small[8];
    put_image();
    snprintf(exe, sizeof exe, "%s/usr/local/bin/bissctl", root);
    ck_assert_str_eq(default_image_for(exe, &d, small, sizeof small), d.installed);
}
END_TEST

int main(void) {
    Suite *s = suite_create("default_image");
    TCase *tc = tcase_create("default_image");
    tcase_add_checked_fixture(tc, setup, teardown);
    tcase_add_test(tc, test_build_tree);
    tcase_add_test(tc, test_destdir_tree);
    tcase_add_test(tc, test_image_absent);
    tcase_add_test(tc, test_real_prefix);
    tcase_add_test(tc, test_above_root);
    tcase_add_test(tc, test_too_long);
    suite_add_tcase(s, tc);
    return check_run(s);
}
