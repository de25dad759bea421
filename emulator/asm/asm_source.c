/*
 * asm_source.c - source files and the preprocessor: reading lines with
 * comment and continuation rules, # directives, conditional assembly and
 * #include, in the order pasm applies them.
 */
#include "asm_ctx.h"
#include "read_file.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <unistd.h>

/* POSIX dirname()/basename() semantics without modifying the argument. */
static int split_path(const char *path, char *dir, size_t dmax, char *base, size_t bmax) {
    size_t n = strlen(path);
    while (n > 1 && path[n - 1] == '/')
        n--;
    size_t slash = n;
    while (slash > 0 && path[slash - 1] != '/')
        slash--;
    size_t blen = n - slash;
    if (blen >= bmax)
        return -2;
    memcpy(base, path + slash, blen);
    base[blen] = 0;
    if (slash == 0) {
        snprintf(dir, dmax, ".");
        return 0;
    }
    size_t dlen = slash;
    while (dlen > 1 && path[dlen - 1] == '/')
        dlen--;
    if (dlen >= dmax)
        return -1;
    memcpy(dir, path, dlen);
    dir[dlen] = 0;
    return 0;
}

/* Resolve #include <name> against the -I directories (pasm: first readable). */
static int search_include(struct asm_ctx *c, const char *name, char *out, size_t max) {
    const struct pruasm_options *o = c->opt;
    for (size_t i = 0; o && i < o->ninclude_dirs; i++) {
        char dir[ASM_DIR_MAX * 2];
        snprintf(dir, sizeof dir, "%s", o->include_dirs[i]);
        size_t dl = strlen(dir);
        while (dl > 0 && dir[dl - 1] == '/')
            dir[--dl] = 0;
        if (dl + strlen(name) + 2 > max)
            return 1;
        snprintf(out, max, "%s/%s", dir, name);
        if (access(out, R_OK) == 0)
            return 0;
    }
    return -1;
}

struct asm_file *asm_file_open(struct asm_ctx *c, struct asm_file *parent, const char *path,
                               int search_include_dirs) {
    char found[ASM_DIR_MAX];
    if (c->open_files == ASM_MAX_OPEN) {
        asm_report(c, parent, REP_FATAL, "Too many open files");
        return NULL;
    }
    if (search_include_dirs && path[0] != '/' && path[0] != '.') {
        int r = search_include(c, path, found, sizeof found);
        if (r < 0) {
            asm_report(c, parent, REP_FATAL, "Could not find '%s' in include paths", path);
            return NULL;
        }
        if (r > 0) {
            asm_report(c, parent, REP_FATAL, "Absolute pathname too long in [include-dirs]/'%s'",
                       path);
            return NULL;
        }
        path = found;
    }
    char dir[ASM_DIR_MAX], name[ASM_NAME_MAX];
    if (strlen(path) >= ASM_DIR_MAX) {
        asm_report(c, parent, REP_FATAL, "Dirname too long in '%s'", path);
        return NULL;
    }
    int r = split_path(path, dir, sizeof dir, name, sizeof name);
    if (r == -1) {
        asm_report(c, parent, REP_FATAL, "Dirname too long in '%s'", path);
        return NULL;
    }
    if (r == -2) {
        asm_report(c, parent, REP_FATAL, "base filename too long in '%s'", path);
        return NULL;
    }

    /* The same file (same name and directory, not currently open) keeps its
     * record, so file numbers in the listings are stable across passes. */
    unsigned i;
    for (i = 0; i < c->nfiles; i++)
        if (!c->files[i].in_use && !strcmp(c->files[i].name, name) && !strcmp(c->files[i].dir, dir))
            break;
    if (i == c->nfiles) {
        if (c->nfiles == ASM_MAX_FILES) {
            asm_report(c, parent, REP_FATAL, "Max source files exceeded");
            return NULL;
        }
        c->nfiles++;
    }
    struct asm_file *f = &c->files[i];
    char *keep = f->text;
    size_t keep_len = f->len;
    memset(f, 0, sizeof *f);
    snprintf(f->name, sizeof f->name, "%s", name);
    snprintf(f->dir, sizeof f->dir, "%s", dir);
    f->index = i;
    f->line = 1;
    f->cc_depth_in = c->cc_depth;
    f->text = keep;
    f->len = keep_len;

    if (!f->text) {
        if (i == 0 && c->main_text) {
            f->len = strlen(c->main_text);
            f->text = malloc(f->len + 1);
            if (f->text)
                memcpy(f->text, c->main_text, f->len + 1);
        } else {
            if (read_file(path, ASM_FILE_MAX, &f->text, &f->len) == READ_FILE_TOO_BIG) {
                asm_report(c, parent, REP_FATAL, "Source file '%s' is too large", path);
                return NULL;
            }
        }
        if (!f->text) {
            asm_report(c, parent, REP_FATAL, "Can't open source file '%s'", path);
            return NULL;
        }
    }
    f->in_use = 1;
    c->open_files++;
    if (c->open_files > 10)
        asm_report(c, parent, REP_WARN1, "%d open files - possible #include recursion",
                   c->open_files);
    return f;
}

void asm_file_close(struct asm_ctx *c, struct asm_file *f) {
    c->open_files--;
    f->in_use = 0;
}

#define CH_EOF (-1)
#define CH_FF  (-2) /* byte 0xff: pasm reads it as a signed char, i.e. as EOF */

/* One character, carriage returns dropped; CH_EOF at the end. Lines are
 * counted when the character after a newline is read, as pasm does, so a
 * statement's line is the line it ends on. */
static int read_char(struct asm_file *f) {
    for (;;) {
        if (f->pos >= f->len)
            return CH_EOF;
        int ch = (unsigned char)f->text[f->pos++];
        if (ch == '\r')
            continue;
        if (f->last == '\n')
            f->line++;
        f->last = ch;
        return ch == 0xff ? CH_FF : ch;
    }
}

/* Does ch end a line? (0xff does, and at the start of a line it ends the
 * file, exactly like the end of the file does in pasm.) */
static int line_end(int ch) {
    return ch == 0 || ch == CH_EOF || ch == CH_FF || ch == '\n';
}

/* Read one logical line with comments removed. Returns 0 on error. */
static int read_text_line(struct asm_ctx *c, struct asm_file *f, char *dst, int max, int *plen,
                          int *peof) {
    int ch;
    *plen = 0;
    *peof = 0;
    do
        ch = read_char(f);
    while (ch == ' ' || ch == '\t' || ch == '\n');

    int idx = 0, comment = 0, quote = 0, cont = 0;
    for (;;) {
        if (ch == '"')
            quote ^= 1;
        if (quote)
            comment = 0;
        if ((comment && ch == '/') || (!quote && ch == ';')) {
            if (ch == '/' && idx > 0)
                idx--;
            while (!line_end(ch))
                ch = read_char(f);
            break;
        } else if (comment && ch == '*') {
            if (idx > 0)
                idx--;
            for (;;) {
                /* pasm's scan also stops at a 0xff byte, so "\xff/" ends
                 * a comment too. */
                while (ch != CH_EOF && ch != CH_FF && ch != '*')
                    ch = read_char(f);
                if (ch == CH_EOF) {
                    /* pasm loops forever here; an error is kinder. */
                    asm_report(c, f, REP_ERROR, "Unterminated /* comment");
                    *plen = 0;
                    *peof = 1;
                    dst[0] = 0;
                    return 0;
                }
                ch = read_char(f);
                if (ch == '/')
                    break;
            }
            ch = read_char(f);
            comment = 0;
            continue;
        } else if (cont && ch == '\n') {
            if (idx > 0)
                idx--;
            ch = read_char(f);
            cont = 0;
            continue;
        }
        comment = ch == '/';
        cont = ch == '\\';
        if (line_end(ch))
            break;
        if (idx >= max - 1) {
            /* Like pasm, the rest of the line is read as further lines. */
            asm_report(c, f, REP_ERROR, "Line too long");
            return 0;
        }
        dst[idx++] = (char)ch;
        ch = read_char(f);
    }
    while (idx > 0 && (dst[idx - 1] == ' ' || dst[idx - 1] == '\t'))
        idx--;
    dst[idx] = 0;
    if (quote)
        asm_report(c, f, REP_ERROR, "Open Quotes");
    *plen = idx;
    *peof = !idx && (ch == CH_EOF || ch == CH_FF);
    return 1;
}

/* Read a name operand of #ifdef/#ifndef/#undef into name. Returns 0 on error. */
static int directive_name(struct asm_ctx *c, const struct asm_file *f, const char *s, char *name) {
    while (*s == ' ' || *s == '\t')
        s++;
    if (!asm_label_char(*s, 1)) {
        asm_report(c, f, REP_ERROR, "Illegal label");
        return 0;
    }
    int n = 0;
    for (;;) {
        name[n++] = *s++;
        if (!*s)
            break;
        if (*s == ' ' || *s == '\t') {
            asm_report(c, f, REP_ERROR, "Unexpected additional characters on line");
            return 0;
        }
        if (!asm_label_char(*s, 0)) {
            asm_report(c, f, REP_ERROR, "Illegal name");
            return 0;
        }
        if (n >= ASM_TOKEN_MAX - 1) {
            asm_report(c, f, REP_ERROR, "Label too long");
            return 0;
        }
    }
    name[n] = 0;
    return 1;
}

static int cc_false(const struct asm_ctx *c) {
    return c->cc_depth && !(c->cc_flags[c->cc_depth - 1] & 1);
}

static int do_ifdef(struct asm_ctx *c, const struct asm_file *f, const char *s, int want_defined) {
    if (c->cc_depth == ASM_CC_MAX) {
        asm_report(c, f, REP_ERROR, "Conditional nesting limit exceeded");
        return 0;
    }
    if (cc_false(c)) {
        c->cc_flags[c->cc_depth++] = 0; /* only tracks nesting */
        return 1;
    }
    char name[ASM_TOKEN_MAX];
    if (!directive_name(c, f, s, name))
        return 0;
    int defined = asm_equate_defined(c, name);
    c->cc_flags[c->cc_depth++] = (defined == want_defined) ? 1 : 0;
    return 1;
}

static int do_else(struct asm_ctx *c, const struct asm_file *f, const char *s) {
    if (*s) {
        asm_report(c, f, REP_ERROR, "Unexpected additional characters on line");
        return 0;
    }
    unsigned depth = c->cc_depth;
    if (depth == 0 || depth > sizeof(c->cc_flags) || (c->cc_flags[depth - 1] & 2)) {
        asm_report(c, f, REP_ERROR, "Multiple #else or use without corresponding #if");
        return 0;
    }
    uint8_t *fl = &c->cc_flags[depth - 1];
    *fl = (uint8_t)((*fl | 2) ^ 1);
    for (unsigned i = 0; i + 1 < c->cc_depth; i++)
        if (!(c->cc_flags[i] & 1))
            *fl &= (uint8_t)~1;
    return 1;
}

static int do_endif(struct asm_ctx *c, const struct asm_file *f, const char *s) {
    if (*s) {
        asm_report(c, f, REP_ERROR, "Unexpected additional characters on line");
        return 0;
    }
    if (!c->cc_depth) {
        asm_report(c, f, REP_ERROR, "#endif without corresponding #if");
        return 0;
    }
    c->cc_depth--;
    return 1;
}

static int do_include(struct asm_ctx *c, struct asm_file *f, const char *s) {
    char path[ASM_DIR_MAX];
    int idx = 0, term;
    while (*s == ' ' || *s == '\t')
        s++;
    if (*s == '"') {
        term = '"';
        idx = snprintf(path, sizeof path, "%s/", f->dir);
        if (idx >= (int)sizeof path)
            idx = (int)sizeof path - 1;
    } else if (*s == '<') {
        term = '>';
    } else {
        asm_report(c, f, REP_ERROR, "Expected \" or < after #include");
        return 0;
    }
    s++;
    if (*s == '/' || *s == '\\')
        idx = 0; /* absolute path */
    int start = idx;
    for (;;) {
        char ch = *s++;
        if (ch == ':' && idx > 0) {
            /* pasm takes "x:" as a DOS drive letter: the name restarts there */
            path[0] = path[idx - 1];
            idx = start = 1;
        }
        if (ch == term)
            break;
        if (!ch) {
            asm_report(c, f, REP_ERROR, "Bad filename in #include");
            return 0;
        }
        if (idx >= ASM_DIR_MAX - 1) {
            asm_report(c, f, REP_ERROR, "Filename too long in #include");
            return 0;
        }
        path[idx++] = ch;
    }
    path[idx] = 0;
    if (*s) {
        asm_report(c, f, REP_ERROR, "Expected EOL after '%s'", path);
        return 0;
    }
    if (idx == start) {
        asm_report(c, f, REP_ERROR, "Null filename in #include");
        return 0;
    }
    struct asm_file *inc = asm_file_open(c, f, path, term == '>');
    if (!inc)
        return 0;
    int rc = asm_process_file(c, inc);
    asm_file_close(c, inc);
    return rc || c->pass != 2;
}

/* Handle a line starting with '#'. Returns 1 when done, 0 on error. */
static int directive(struct asm_ctx *c, struct asm_file *f, const char *src) {
    char word[ASM_TOKEN_MAX];
    int idx = 1, n = 0;
    char ch = src[idx++];
    if (!((ch >= 'A' && ch <= 'Z') || (ch >= 'a' && ch <= 'z'))) {
        asm_report(c, f, REP_ERROR, "Expected {a-z} after #");
        return 0;
    }
    word[n++] = ch;
    while (n < ASM_TOKEN_MAX - 1) {
        ch = src[idx++];
        if (ch == ' ' || ch == '\t' || !ch)
            break;
        word[n++] = ch;
    }
    word[n] = 0;
    if (!ch)
        idx--;
    const char *rest = src + idx;

    if (!strcasecmp(word, "ifdef"))
        return do_ifdef(c, f, rest, 1);
    if (!strcasecmp(word, "ifndef"))
        return do_ifdef(c, f, rest, 0);
    if (!strcasecmp(word, "else"))
        return do_else(c, f, rest);
    if (!strcasecmp(word, "endif"))
        return do_endif(c, f, rest);
    if (cc_false(c))
        return 1;
    if (!strcasecmp(word, "error")) {
        asm_report(c, f, REP_ERROR, "%s", rest);
        return 1;
    }
    if (!strcasecmp(word, "warn")) {
        asm_report(c, f, REP_WARN1, "%s", rest);
        return 1;
    }
    if (!strcasecmp(word, "note")) {
        asm_report(c, f, REP_NOTE, "%s", rest);
        return 1;
    }
    if (!strcasecmp(word, "include"))
        return do_include(c, f, rest);
    if (!strcasecmp(word, "define")) {
        asm_equate_define(c, f, rest);
        return 1;
    }
    if (!strcasecmp(word, "undef")) {
        asm_equate_undef(c, f, rest);
        return 1;
    }
    asm_report(c, f, REP_ERROR, "Unknown # directive");
    return 0;
}

int asm_get_line(struct asm_ctx *c, struct asm_file *f, char *dst, int max) {
    char *raw = malloc(ASM_RAW_LINE_MAX);
    if (!raw) {
        asm_report(c, f, REP_FATAL, "Memory allocation failed");
        return -1;
    }
    int rc;
    for (;;) {
        int len, eof;
        do {
            if (!read_text_line(c, f, raw, ASM_RAW_LINE_MAX, &len, &eof)) {
                rc = eof ? 0 : -1;
                goto out;
            }
        } while (!len && !eof);
        if (!len && eof) {
            if (f->cc_depth_in != c->cc_depth)
                asm_report(c, f, REP_ERROR, "#endif mismatch in file");
            rc = 0;
            goto out;
        }
        if (raw[0] == '#') {
            if (!directive(c, f, raw)) {
                rc = -1;
                goto out;
            }
            continue;
        }
        if (cc_false(c))
            continue;
        int idx = 0;
        if (!asm_equate_expand(c, f, raw, dst, &idx, max)) {
            /* pasm ends the file here (reported as its end); matching
             * that keeps the later messages identical. */
            rc = 0;
            goto out;
        }
        dst[idx] = 0;
        rc = idx;
        goto out;
    }
out:
    free(raw);
    return rc;
}

int asm_process_file(struct asm_ctx *c, struct asm_file *f) {
    char *src = malloc(ASM_LINE_MAX);
    if (!src) {
        asm_report(c, f, REP_FATAL, "Memory allocation failed");
        return 0;
    }
    int rc = 1;
    for (;;) {
        if (c->fatal || c->errors >= ASM_MAX_ERRORS) {
            asm_report_abort(c);
            rc = 0;
            break;
        }
        int n = asm_get_line(c, f, src, ASM_LINE_MAX);
        if (n == 0)
            break;
        if (n < 0)
            continue;
        /* In pass 2 pasm stops a file at its first bad statement. */
        if (!asm_process_line(c, f, src) && c->pass == 2) {
            rc = 0;
            break;
        }
    }
    free(src);
    return rc;
}
