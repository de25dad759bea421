/* read_file: whole files of any size up to the limit, NUL-terminated, and
 * each way of failing with its own code. */
#include "check_run.h"
#include "read_file.h"

#include <check.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

static char path[] = "/tmp/read_file_XXXXXX";

static void write_bytes(size_t n) {
    FILE *f = fopen(path, "wb");
    ck_assert_ptr_nonnull(f);
    for (size_t i = 0; i < n; i++) {
        fputc('a' + (int)(i % 26), f);
    }
    fclose(f);
}

static void setup(void) {
    int fd = mkstemp(path);
    ck_assert_int_ge(fd, 0);
    close(fd);
}

static void teardown(void) {
    unlink(path);
    strcpy(path, "/tmp/read_file_XXXXXX");
}

/* Sizes around the buffer's growth steps: every byte, in order, then a NUL. */
START_TEST(test_sizes) {
    static const size_t sizes[] = {0, 1, 4095, 4096, 4097, 8191, 8192, 100000};
    write_bytes(sizes[_i]);
    char *b;
    size_t len;
    ck_assert_int_eq(read_file(path, 1u << 20, &b, &len), READ_FILE_OK);
    ck_assert_uint_eq(len, sizes[_i]);
    for (size_t i = 0; i < len; i++) {
        ck_assert_int_eq(b[i], 'a' + (int)(i % 26));
    }
    ck_assert_int_eq(b[len], '\0');
    free(b);
}
END_TEST

/* The file must be shorter than max. */
START_TEST(test_limit) {
    char *b;
    size_t len;
    write_bytes(9999);
    ck_assert_int_eq(read_file(path, 10000, &b, &len), READ_FILE_OK);
    free(b);
    write_bytes(10000);
    ck_assert_int_eq(read_file(path, 10000, &b, &len), READ_FILE_TOO_BIG);
    ck_assert_ptr_null(b);
}
END_TEST

START_TEST(test_missing_and_unreadable) {
    char *b;
    size_t len;
    ck_assert_int_eq(read_file("/nonexistent/file", 100, &b, &len), READ_FILE_OPEN);
    ck_assert_ptr_null(b);
    /* a directory opens but cannot be read */
    ck_assert_int_eq(read_file("/tmp", 100, &b, &len), READ_FILE_IO);
    ck_assert_ptr_null(b);
}
END_TEST

int main(void) {
    Suite *s = suite_create("read_file");
    TCase *tc = tcase_create("read_file");
    tcase_add_checked_fixture(tc, setup, teardown);
    tcase_add_loop_test(tc, test_sizes, 0, 8);
    tcase_add_test(tc, test_limit);
    tcase_add_test(tc, test_missing_and_unreadable);
    suite_add_tcase(s, tc);
    return check_run(s);
}
