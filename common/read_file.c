/* read_file.c - see read_file.h. */
#include "read_file.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>

/* Grows the buffer by doubling, one byte spare for the NUL. */
static read_file_err read_all(FILE *f, size_t max, char **buf, size_t *len) {
    size_t cap = 4096, n = 0;
    char *b = malloc(cap);
    for (;;) {
        if (!b) {
            return READ_FILE_NOMEM;
        }
        size_t got = fread(b + n, 1, cap - 1 - n, f);
        n += got;
        if (n >= max) {
            free(b);
            return READ_FILE_TOO_BIG;
        }
        if (n < cap - 1) {
            if (ferror(f)) {
                free(b);
                return READ_FILE_IO;
            }
            break; /* end of file */
        }
        char *nb = realloc(b, cap * 2);
        if (!nb) {
            free(b);
        }
        b = nb;
        cap *= 2;
    }
    b[n] = '\0';
    *buf = b;
    *len = n;
    return READ_FILE_OK;
}

read_file_err read_file(const char *path, size_t max, char **buf, size_t *len) {
    *buf = NULL;
    *len = 0;
    FILE *f = fopen(path, "rb");
    if (!f) {
        return READ_FILE_OPEN;
    }
    read_file_err e = read_all(f, max, buf, len);
    int saved = errno; /* why a read failed (EISDIR for a directory) */
    fclose(f);
    errno = saved;
    return e;
}
