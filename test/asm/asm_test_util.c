/*
 * asm_test_util.c - helpers shared by the pruasm Check suites.
 */
#include "asm_test_util.h"

#include <check.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

int asm_text(const char *src, struct pruasm_image *img, struct pruasm_diag *diag) {
    struct pruasm_options opt = {.core = 3};
    return pruasm_assemble_string(&opt, "t.p", src, img, diag);
}

size_t asm_words(const char *src, uint32_t *out, size_t max) {
    struct pruasm_image img;
    struct pruasm_diag diag = {0};
    int rc = asm_text(src, &img, &diag);
    ck_assert_msg(rc == 0, "assembly failed: %s\n--- source:\n%s", diag.first_error, src);
    ck_assert_int_le(img.nwords, max);
    memcpy(out, img.words, img.nwords * sizeof *out);
    size_t n = img.nwords;
    pruasm_image_free(&img);
    return n;
}

const char *asm_error(const char *src) {
    static char text[512];
    struct pruasm_image img;
    struct pruasm_diag diag = {0};
    int rc = asm_text(src, &img, &diag);
    ck_assert_msg(rc != 0, "assembly should have failed:\n%s", src);
    ck_assert_ptr_null(img.words);
    snprintf(text, sizeof text, "%s", diag.first_error);
    return text;
}

static char made[8][1024]; /* directories to remove when the test exits */
static int nmade;

static void remove_dirs(void) {
    for (int i = 0; i < nmade; i++) {
        char cmd[1100];
        snprintf(cmd, sizeof cmd, "rm -rf '%.1000s'", made[i]);
        if (system(cmd) != 0)
            fprintf(stderr, "could not remove %s\n", made[i]);
    }
}

const char *asm_tmpdir(const char *tag) {
    static char path[1024];
    const char *bin = getenv("TEST_BIN_DIR");
    snprintf(path, sizeof path, "%s/asm-tmp-%s-%d", bin ? bin : "/tmp", tag, (int)getpid());
    char cmd[1100];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", path);
    ck_assert_int_eq(system(cmd), 0);
    ck_assert_int_eq(mkdir(path, 0700), 0);
    if (nmade < 8) {
        if (!nmade)
            atexit(remove_dirs);
        snprintf(made[nmade++], sizeof made[0], "%s", path);
    }
    return path;
}

void asm_write(const char *dir, const char *name, const char *text) {
    char path[1200];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    FILE *fp = fopen(path, "wb");
    ck_assert_ptr_nonnull(fp);
    ck_assert_int_eq(fwrite(text, 1, strlen(text), fp), strlen(text));
    ck_assert_int_eq(fclose(fp), 0);
}

char *asm_read(const char *path, size_t *len) {
    FILE *fp = fopen(path, "rb");
    if (!fp)
        return NULL;
    fseek(fp, 0, SEEK_END);
    long n = ftell(fp);
    fseek(fp, 0, SEEK_SET);
    char *buf = malloc((size_t)n + 1);
    ck_assert_ptr_nonnull(buf);
    ck_assert_int_eq(fread(buf, 1, (size_t)n, fp), (size_t)n);
    fclose(fp);
    buf[n] = 0;
    if (len)
        *len = (size_t)n;
    return buf;
}
