/*
 * pruasm.h - the pasm-compatible PRU assembler as a library.
 *
 * Assembles pasm 0.87 dialect source (docs/pru-facts.md §2) into
 * PRU instruction words, in process. The `pruasm` command line tool is a thin
 * wrapper around these calls; the emulator tests and the bench use them to
 * assemble source text without touching the file system.
 *
 *     struct pruasm_image img;
 *     struct pruasm_diag diag = {0};
 *     if (pruasm_assemble_string(NULL, "t.p", ".origin 0\nhalt\n", &img, &diag) == 0) {
 *         ... img.words[0 .. img.nwords-1] ...
 *         pruasm_image_free(&img);
 *     } else {
 *         fprintf(stderr, "%s\n", diag.first_error);
 *     }
 *
 * Everything is reentrant: no global state, one call = one assembly.
 */
#ifndef PRUASM_H
#define PRUASM_H

#include <stddef.h>
#include <stdint.h>

/* Severity of a message, as pasm prints it. */
enum pruasm_level {
    PRUASM_NOTE,    /* "Note: "        (stdout in pasm) */
    PRUASM_WARNING, /* "Warning: "     (stderr) */
    PRUASM_ERROR,   /* "Error: "       (stderr) */
    PRUASM_FATAL,   /* "Fatal Error: " (stderr) */
    PRUASM_PLAIN,   /* a bare line printed as is: "Aborting...", "Error: Offset changed..." */
};

/* What to assemble and how. A NULL options pointer means all defaults. */
struct pruasm_options {
    int core;                   /* pasm -V: 1, 2 or 3; 0 means 3 (V0 is not supported) */
    const char *const *defines; /* "NAME" or "NAME=value", like -D */
    size_t ndefines;
    const char *const *include_dirs; /* searched by #include <file>, like -I */
    size_t ninclude_dirs;
    int want_listing;        /* fill pruasm_image.listing (the -l .lst text) */
    int want_source_listing; /* fill pruasm_image.source_listing (the -L .txt text) */
    int want_debug_file;     /* fill pruasm_image.debug_file (the -d pView .dbg file) */
    int big_endian;          /* pasm -E: assemble for a big-endian core */
};

/* The result of a successful assembly. Free with pruasm_image_free(). */
struct pruasm_image {
    uint32_t *words; /* code words from address 0; gaps are 0 */
    size_t nwords;
    int32_t entry_point;       /* .entrypoint, else the first .origin, else 8 */
    char *listing;             /* NUL-terminated .lst text, or NULL */
    char *source_listing;      /* NUL-terminated .txt text, or NULL */
    unsigned char *debug_file; /* .dbg bytes, or NULL */
    size_t debug_file_len;
};

/*
 * Where messages go. Zero-initialise it; set `emit` to see every message as
 * it happens (file is NULL and line 0 for messages without a location).
 * Counts and the first error's full text ("file:line: Error: text") are
 * filled in either way.
 */
struct pruasm_diag {
    void (*emit)(void *ctx, enum pruasm_level level, const char *file, unsigned line,
                 const char *text);
    void *ctx;
    int errors;
    int warnings;
    int pass; /* the last pass run (1 or 2); pasm reports it */
    char first_error[512];
};

/*
 * Assemble the file at `path` (its #include "..." files are read relative to
 * its directory). Returns 0 and fills `out`, or -1 on any error or when no
 * code was produced (first_error is then "No code generated"); `out` then
 * holds nothing to free. `diag` may be NULL.
 */
int pruasm_assemble_file(const struct pruasm_options *opt, const char *path,
                         struct pruasm_image *out, struct pruasm_diag *diag);

/*
 * Assemble source text held in memory. `name` is the file name used in
 * messages and listings (its directory, if any, is where #include "..." looks;
 * none means the current directory).
 */
int pruasm_assemble_string(const struct pruasm_options *opt, const char *name, const char *text,
                           struct pruasm_image *out, struct pruasm_diag *diag);

/* Release what a successful assembly allocated; safe on a zeroed image. */
void pruasm_image_free(struct pruasm_image *img);

/* pasm's -c, -f, -m and -b/-B outputs, byte for byte, in a malloc'd buffer
 * (*len gets its size). `array_name` is the -C name (NULL for "PRUcode").
 * They return NULL when out of memory. */
char *pruasm_format_c_array(const struct pruasm_image *img, const char *array_name, size_t *len);
char *pruasm_format_fb_array(const struct pruasm_image *img, const char *array_name, size_t *len);
char *pruasm_format_img(const struct pruasm_image *img, size_t *len);
unsigned char *pruasm_format_bin(const struct pruasm_image *img, int big_endian, size_t *len);

#endif
