/*
 * test_asm_cmake.c - the image built by pru_assemble_image()
 * (cmake/PruAssemble.cmake) holds exactly the words the case file expects
 * (little-endian, 4 bytes per word), whichever assembler built it.
 */
#include "check_run.h"

#include <check.h>
#include <stdlib.h>
#include <string.h>

#include "asm_test_util.h"

START_TEST(image_matches_case) {
    size_t len;
    unsigned char *bin = (unsigned char *)asm_read(IMAGE_FILE, &len);
    ck_assert_msg(bin != NULL, "%s was not built", IMAGE_FILE);
    char *text = asm_read(CASE_FILE, NULL);
    ck_assert_ptr_nonnull(text);
    size_t n = 0;
    for (const char *p = text; (p = strstr(p, "// expect: ")) != NULL;) {
        p += 11;
        char *end;
        for (;;) {
            unsigned long w = strtoul(p, &end, 16);
            if (end == p)
                break;
            ck_assert_uint_lt(n * 4 + 3, len);
            uint32_t got = (uint32_t)bin[4 * n] | (uint32_t)bin[4 * n + 1] << 8 |
                           (uint32_t)bin[4 * n + 2] << 16 | (uint32_t)bin[4 * n + 3] << 24;
            ck_assert_msg(got == w, "word %zu is %08x, want %08lx", n, (unsigned)got, w);
            n++;
            p = end;
            if (*p == '\n')
                break;
        }
    }
    ck_assert_uint_gt(n, 0);
    ck_assert_uint_eq(len, n * 4);
    free(bin);
    free(text);
}
END_TEST

int main(void) {
    Suite *s = suite_create("asm_cmake");
    TCase *tc = tcase_create("image");
    tcase_add_test(tc, image_matches_case);
    suite_add_tcase(s, tc);
    return check_run(s);
}
