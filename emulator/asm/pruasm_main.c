/*
 * pruasm_main.c - the `pruasm` command: pasm 0.87's command line, messages,
 * exit status and output files, on top of the pruasm library (a usage error
 * in the tools' one form instead of pasm's: README "Conventions"). Output files
 * are written to temporary names and renamed into place only when all of
 * them succeeded, so a failed run never leaves a partial file behind.
 */
#include "pruasm.h"
#include "safe_file.h"

#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#define MAX_DEFINES   8
#define NAME_MAX_LEN  128 /* pasm's limit for -D names */
#define VALUE_MAX_LEN 256
#define MAX_OUTPUTS   8

enum {
    OUT_BIN = 1 << 0,
    OUT_BIB = 1 << 1,
    OUT_CARRAY = 1 << 2,
    OUT_IMG = 1 << 3,
    OUT_LST = 1 << 4,
    OUT_TXT = 1 << 5,
    OUT_FB = 1 << 6,
    OUT_DBG = 1 << 7,
};

struct cli {
    const char *prog;
    const char *infile, *outfile;
    unsigned outputs;
    int core;
    int big_endian;
    const char *defines[MAX_DEFINES];
    size_t ndefines;
    const char **incdirs;
    size_t nincdirs;
    const char *array_name;
};

static void usage(FILE *fp, const char *prog) {
    fprintf(fp,
            "Usage: %s [-V#EBbcmLldfz] [-Idir] [-Dname=value] [-Cname] InFile [OutFileBase]\n\n"
            "    V# - core version: V1, V2 or V3 (default V3; -X = V2)\n"
            "    b  - little-endian binary <base>.bin\n"
            "    B  - big-endian binary <base>.bib\n"
            "    c  - C array <base>_bin.h (the default when no output is chosen)\n"
            "    m  - image <base>.img, one hex word per line\n"
            "    L  - annotated source listing <base>.txt\n"
            "    l  - listing <base>.lst\n"
            "    f  - FreeBasic array <base>.bi\n"
            "    z  - accepted for compatibility (no debug messages)\n"
            "    d  - pView debugger file <base>.dbg\n"
            "    E  - assemble for a big-endian core\n"
            "    x, V0 - not supported (the legacy V0 core)\n"
            "    I  - directory searched by #include <file>: -Idir\n"
            "    D  - define an equate: -Dname (value 1) or -Dname=value (at most 8)\n"
            "    C  - name of the C/FreeBasic array: -Cname (default PRUcode)\n\n"
            "Output files are written in the current directory, named after InFile\n"
            "up to its first '.', or OutFileBase. Exit status 0 on success, 1 on an\n"
            "error in the source or a file, 2 on bad usage.\n",
            prog);
}

#define EXIT_USAGE 2

/* A usage error in the tools' one form: "pruasm: MESSAGE" and the way to
 * the help; returns EXIT_USAGE. */
__attribute__((format(printf, 2, 3))) static int bad_usage(const struct cli *o, const char *fmt,
                                                           ...) {
    va_list ap;
    va_start(ap, fmt);
    fprintf(stderr, "%s: ", o->prog);
    vfprintf(stderr, fmt, ap);
    va_end(ap);
    fprintf(stderr, "\nTry '%s --help' for more information.\n", o->prog);
    return EXIT_USAGE;
}

/* One "-..." argument, pasm style: letters may be grouped; I, D and C take
 * the rest of the argument. Returns 0, or the exit status on error. */
static int parse_flags(struct cli *o, const char *arg) {
    if (arg[1] == '-' || arg[1] == '\0') /* --help and --version are taken before */
        return bad_usage(o, "unknown option '%s'", arg);
    for (const char *p = arg + 1; *p; p++) {
        switch (*p) {
        case 'I': {
            const char **n = realloc(o->incdirs, (o->nincdirs + 1) * sizeof *n);
            if (!n)
                return 1;
            o->incdirs = n;
            o->incdirs[o->nincdirs++] = p + 1;
            return 0;
        }
        case 'D': {
            if (o->ndefines == MAX_DEFINES)
                return bad_usage(o, "-D: at most %d equates", MAX_DEFINES);
            size_t n = strcspn(p + 1, "=");
            if (n >= NAME_MAX_LEN)
                return bad_usage(o, "-D%s: name longer than %d characters", p + 1,
                                 NAME_MAX_LEN - 1);
            if (p[1 + n] == '=' && strlen(p + 2 + n) >= VALUE_MAX_LEN)
                return bad_usage(o, "-D%s: value longer than %d characters", p + 1,
                                 VALUE_MAX_LEN - 1);
            o->defines[o->ndefines++] = p + 1;
            return 0;
        }
        case 'C':
            if (strlen(p + 1) >= VALUE_MAX_LEN)
                return bad_usage(o, "-C%s: longer than %d characters", p + 1, VALUE_MAX_LEN - 1);
            o->array_name = p + 1;
            return 0;
        case 'V':
            p++;
            if (*p < '0' || *p > '3')
                return bad_usage(o, "-V: expected a core version, 1..3");
            if (o->core)
                return bad_usage(o, "one core version: -V once, not with -X or -x");
            if (*p == '0')
                return bad_usage(o, "-V0: the legacy V0 core is not supported");
            o->core = *p - '0';
            break;
        case 'x':
            return bad_usage(o, "-x: the legacy V0 core is not supported");
        case 'X':
            if (o->core)
                return bad_usage(o, "one core version: -X once, not with -V or -x");
            o->core = 2;
            break;
        case 'E':
            o->big_endian = 1;
            break;
        case 'd':
            o->outputs |= OUT_DBG;
            break;
        case 'b':
            o->outputs |= OUT_BIN;
            break;
        case 'B':
            o->outputs |= OUT_BIB;
            break;
        case 'c':
            o->outputs |= OUT_CARRAY;
            break;
        case 'm':
            o->outputs |= OUT_IMG;
            break;
        case 'l':
            o->outputs |= OUT_LST;
            break;
        case 'L':
            o->outputs |= OUT_TXT;
            break;
        case 'f':
            o->outputs |= OUT_FB;
            break;
        case 'z':
            break;
        default:
            return bad_usage(o, "unknown option '-%c'", *p);
        }
    }
    return 0;
}

static int parse_args(struct cli *o, int argc, char **argv) {
    if (argc < 2)
        return bad_usage(o, "no InFile given");
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--help") || !strcmp(argv[i], "-h")) {
            usage(stdout, o->prog);
            exit(0);
        }
    }
    for (int i = 1; i < argc; i++) {
        if (argv[i][0] == '-')
            continue;
        if (!o->infile)
            o->infile = argv[i];
        else if (!o->outfile)
            o->outfile = argv[i];
        else
            return bad_usage(o, "unexpected argument '%s' (InFile [OutFileBase])", argv[i]);
    }
    for (int i = 1; i < argc; i++) {
        if (argv[i][0] == '-') {
            int rc = parse_flags(o, argv[i]);
            if (rc)
                return rc;
        }
    }
    if (!o->infile)
        return bad_usage(o, "no InFile given");
    return 0;
}

/* The output base name: OutFileBase, or the source's base name up to its
 * first '.'. Returns 0, or EXIT_USAGE after printing why not. */
static int output_base(const struct cli *o, char *base, size_t max) {
    if (o->outfile) {
        if (strlen(o->outfile) > 256 - 5)
            return bad_usage(o, "OutFileBase: longer than %d characters", 256 - 5);
        for (const char *p = o->outfile; *p; p++) {
            if (*p == '.') {
                if (p[1] == '.') {
                    p++;
                } else {
                    return bad_usage(o, "OutFileBase '%s': expected a base name, no '.'",
                                     o->outfile);
                }
            }
        }
        snprintf(base, max, "%s", o->outfile);
        return 0;
    }
    const char *name = o->infile;
    size_t n = strlen(name);
    while (n > 1 && name[n - 1] == '/')
        n--;
    size_t start = n;
    while (start > 0 && name[start - 1] != '/')
        start--;
    size_t k = 0;
    while (start + k < n && name[start + k] != '.' && k + 1 < max) {
        base[k] = name[start + k];
        k++;
    }
    base[k] = 0;
    return 0;
}

static void print_message(void *ctx, enum pruasm_level level, const char *file, unsigned line,
                          const char *text) {
    (void)ctx;
    FILE *fp = level == PRUASM_NOTE ? stdout : stderr;
    static const char *const tag[] = {"Note: ", "Warning: ", "Error: ", "Fatal Error: ", ""};
    if (level == PRUASM_PLAIN) {
        fprintf(fp, "%s\n", text);
        return;
    }
    if (file)
        fprintf(fp, "%s:%u: %s%s\n", file, line, tag[level], text);
    else
        fprintf(fp, "%s%s\n\n", tag[level], text);
}

/* Output files staged (safe_file.h: a temporary file beside each, put in
 * place only when all were written; never over what is not a regular
 * file). */
struct staged {
    struct safe_file f[MAX_OUTPUTS];
    char final[MAX_OUTPUTS][300];
    int n;
};

static int stage(struct staged *s, const char *base, const char *suffix, const void *data,
                 size_t len) {
    if (!data)
        return -1;
    int i = s->n;
    char err[PATH_MAX + 128];
    snprintf(s->final[i], sizeof s->final[i], "%s%s", base, suffix);
    if (safe_file_open(&s->f[i], s->final[i], err, sizeof err) != 0) {
        fprintf(stderr, "Error: Unable to open output file: %s (%s)\n\n", s->final[i], err);
        return -1;
    }
    s->n++;
    if (fwrite(data, 1, len, s->f[i].f) != len || fflush(s->f[i].f) != 0) {
        fprintf(stderr, "Error: File write error: %s\n\n", s->final[i]);
        return -1;
    }
    return 0;
}

static int write_outputs(const struct cli *o, const char *base, const struct pruasm_image *img) {
    struct staged s = {0};
    int rc = 0;
    size_t len = 0;
    char *text;
    unsigned char *bin;
    if (!rc && (o->outputs & OUT_CARRAY)) {
        text = pruasm_format_c_array(img, o->array_name, &len);
        rc = stage(&s, base, "_bin.h", text, len);
        free(text);
    }
    if (!rc && (o->outputs & OUT_FB)) {
        text = pruasm_format_fb_array(img, o->array_name, &len);
        rc = stage(&s, base, ".bi", text, len);
        free(text);
    }
    if (!rc && (o->outputs & OUT_IMG)) {
        text = pruasm_format_img(img, &len);
        rc = stage(&s, base, ".img", text, len);
        free(text);
    }
    if (!rc && (o->outputs & OUT_DBG))
        rc = stage(&s, base, ".dbg", img->debug_file, img->debug_file_len);
    if (!rc && (o->outputs & OUT_TXT))
        rc = stage(&s, base, ".txt", img->source_listing, strlen(img->source_listing));
    if (!rc && (o->outputs & OUT_BIN)) {
        bin = pruasm_format_bin(img, 0, &len);
        rc = stage(&s, base, ".bin", bin, len);
        free(bin);
    }
    if (!rc && (o->outputs & OUT_BIB)) {
        bin = pruasm_format_bin(img, 1, &len);
        rc = stage(&s, base, ".bib", bin, len);
        free(bin);
    }
    if (!rc && (o->outputs & OUT_LST))
        rc = stage(&s, base, ".lst", img->listing, strlen(img->listing));
    /* all written: each put in place; a failed run leaves the old ones */
    for (int i = 0; i < s.n; i++) {
        char err[PATH_MAX + 128];
        if (rc) {
            safe_file_abort(&s.f[i]);
        } else if (safe_file_close(&s.f[i], err, sizeof err) != 0) {
            fprintf(stderr, "Error: File write error: %s (%s)\n\n", s.final[i], err);
            rc = -1;
        }
    }
    return rc;
}

int main(int argc, char **argv) {
    if (argc == 2 && strcmp(argv[1], "--version") == 0) { /* the project's (CMakeLists.txt) */
        printf("%s %s\n", "pruasm", BISS_VERSION);
        return 0;
    }
    struct cli o = {0};
    const char *slash = strrchr(argv[0], '/');
    o.prog = slash ? slash + 1 : argv[0];

    printf("\n\npruasm - PRU Assembler (pasm 0.87 dialect)\n\n");
    int rc = parse_args(&o, argc, argv);
    if (rc) {
        free(o.incdirs);
        return rc;
    }
    char base[300];
    rc = output_base(&o, base, sizeof base);
    if (!rc && access(o.infile, R_OK)) {
        fprintf(stderr, "Fatal Error: Can't open source file '%s'\n\n", o.infile);
        rc = 1;
    }
    if (rc) {
        free(o.incdirs);
        return rc;
    }
    if (!(o.outputs & (OUT_BIN | OUT_BIB | OUT_CARRAY | OUT_IMG | OUT_FB | OUT_DBG))) {
        printf("Note: Using default output '-c' (C array *_bin.h)\n\n");
        o.outputs |= OUT_CARRAY;
    }
    fflush(stdout);

    struct pruasm_options opt = {
        .core = o.core,
        .big_endian = o.big_endian,
        .defines = o.defines,
        .ndefines = o.ndefines,
        .include_dirs = o.incdirs,
        .ninclude_dirs = o.nincdirs,
        .want_listing = (o.outputs & OUT_LST) != 0,
        .want_source_listing = (o.outputs & OUT_TXT) != 0,
        .want_debug_file = (o.outputs & OUT_DBG) != 0,
    };
    struct pruasm_diag diag = {.emit = print_message};
    struct pruasm_image img;
    rc = pruasm_assemble_file(&opt, o.infile, &img, &diag);
    fflush(stderr);
    printf("\nPass %d : %d Error(s), %d Warning(s)\n\n", diag.pass, diag.errors, diag.warnings);
    if (rc == 0) {
        printf("Writing Code Image of %zu word(s)\n\n", img.nwords);
        fflush(stdout);
        rc = write_outputs(&o, base, &img) ? 1 : 0;
        pruasm_image_free(&img);
    } else {
        rc = 1;
    }
    free(o.incdirs);
    return rc;
}
