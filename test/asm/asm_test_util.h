/*
 * asm_test_util.h - helpers shared by the pruasm Check suites.
 */
#ifndef ASM_TEST_UTIL_H
#define ASM_TEST_UTIL_H

#include <stddef.h>
#include <stdint.h>

#include "pruasm.h"

/* Assemble `src` (V3) as file "t.p"; returns pruasm's result. The caller
 * frees img when it returns 0. first_error is in diag. */
int asm_text(const char *src, struct pruasm_image *img, struct pruasm_diag *diag);

/* Assemble and require success; returns the word count, words in out. */
size_t asm_words(const char *src, uint32_t *out, size_t max);

/* Assemble and require failure; returns diag.first_error (static buffer). */
const char *asm_error(const char *src);

/* A fresh empty directory under the build tree, removed when the test
 * process exits; returns its path. */
const char *asm_tmpdir(const char *tag);

/* Write a file (path relative to dir); aborts the test on failure. */
void asm_write(const char *dir, const char *name, const char *text);

/* Read a whole file into a malloc'd buffer (NUL-terminated); NULL if absent. */
char *asm_read(const char *path, size_t *len);

#endif
