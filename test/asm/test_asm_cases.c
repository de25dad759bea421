/*
 * test_asm_cases.c - assembles every .p file in test/asm/cases with pruasm (-V3)
 * and checks the words against the "// expect:" lines in the file, or the
 * first error against its "// expect-error:" line. The expectations were
 * checked against pasm 0.87, so CI without pasm still checks real bytes.
 */
#include "check_run.h"

#include <check.h>
#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "asm_test_util.h"

#define MAX_WORDS 16384

struct expect {
    uint32_t words[MAX_WORDS];
    size_t n;
    char error[512]; /* empty: success expected */
};

static void parse_expect(const char *text, struct expect *e) {
    e->n = 0;
    e->error[0] = 0;
    for (const char *p = text; (p = strstr(p, "// expect")) != NULL; p++) {
        if (!strncmp(p, "// expect-error: ", 17)) {
            size_t len = strcspn(p + 17, "\n");
            snprintf(e->error, sizeof e->error, "%.*s", (int)len, p + 17);
        } else if (!strncmp(p, "// expect: ", 11)) {
            const char *q = p + 11;
            char *end;
            for (;;) {
                unsigned long w = strtoul(q, &end, 16);
                if (end == q || e->n == MAX_WORDS)
                    break;
                e->words[e->n++] = (uint32_t)w;
                q = end;
                if (*q == '\n')
                    break;
            }
        }
    }
}

static int check_case(const char *dir, const char *name) {
    static struct expect e;
    char path[2048];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    char *text = asm_read(path, NULL);
    ck_assert_ptr_nonnull(text);
    parse_expect(text, &e);
    free(text);
    ck_assert_msg(e.n || e.error[0], "%s has no expect lines", name);

    const char *inc[] = {dir};
    struct pruasm_options opt = {.core = 3, .include_dirs = inc, .ninclude_dirs = 1};
    struct pruasm_image img;
    struct pruasm_diag diag = {0};
    int rc = pruasm_assemble_file(&opt, path, &img, &diag);
    if (e.error[0]) {
        ck_assert_msg(rc != 0, "%s: should fail", name);
        ck_assert_msg(!strcmp(diag.first_error, e.error), "%s: error '%s', want '%s'", name,
                      diag.first_error, e.error);
        return 1;
    }
    ck_assert_msg(rc == 0, "%s: %s", name, diag.first_error);
    ck_assert_msg(img.nwords == e.n, "%s: %zu words, want %zu", name, img.nwords, e.n);
    for (size_t i = 0; i < e.n; i++)
        ck_assert_msg(img.words[i] == e.words[i], "%s: word %zu is %08x, want %08x", name, i,
                      (unsigned)img.words[i], (unsigned)e.words[i]);
    pruasm_image_free(&img);
    return 1;
}

START_TEST(cases_match_expectations) {
    const char *src = getenv("TEST_SRC_DIR");
    ck_assert_ptr_nonnull(src);
    char dir[1024];
    snprintf(dir, sizeof dir, "%s/test/asm/cases", src);
    DIR *d = opendir(dir);
    ck_assert_msg(d != NULL, "cannot open %s", dir);
    int n = 0;
    struct dirent *ent;
    while ((ent = readdir(d)) != NULL) {
        size_t len = strlen(ent->d_name);
        if (len > 2 && !strcmp(ent->d_name + len - 2, ".p"))
            n += check_case(dir, ent->d_name);
    }
    closedir(d);
    ck_assert_int_ge(n, 5);
}
END_TEST

static Suite *suite(void) {
    Suite *s = suite_create("asm_cases");
    TCase *tc = tcase_create("cases");
    tcase_add_test(tc, cases_match_expectations);
    suite_add_tcase(s, tc);
    return s;
}

int main(void) {
    return check_run(suite());
}
