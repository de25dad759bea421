/*
 * asm_report.c - messages (pasm's pass rules for which appear when) and a
 * small growing text buffer used by the listings.
 */
#include "asm_ctx.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static void deliver(struct asm_ctx *c, const char *name, unsigned line, enum asm_rep level,
                    const char *fmt, va_list ap) {
    /* pasm shows pass-1 warnings and notes once (pass 1) and WARN2 only in
     * pass 2, so a message never appears twice. */
    if (c->pass == 1 && level == REP_WARN2)
        return;
    if (c->pass == 2 && (level == REP_NOTE || level == REP_WARN1))
        return;

    char text[600];
    vsnprintf(text, sizeof text, fmt, ap);

    enum pruasm_level out = PRUASM_NOTE;
    const char *tag = "Note: ";
    switch (level) {
    case REP_FATAL:
        out = PRUASM_FATAL;
        tag = "Fatal Error: ";
        c->fatal = 1;
        c->errors++;
        break;
    case REP_ERROR:
        out = PRUASM_ERROR;
        tag = "Error: ";
        c->errors++;
        break;
    case REP_WARN1:
    case REP_WARN2:
        out = PRUASM_WARNING;
        tag = "Warning: ";
        c->warnings++;
        break;
    case REP_NOTE:
        break;
    }

    struct pruasm_diag *d = c->diag;
    if (!d)
        return;
    d->errors = c->errors;
    d->warnings = c->warnings;
    if ((out == PRUASM_ERROR || out == PRUASM_FATAL) && !d->first_error[0]) {
        /* Truncation of very long texts is fine here. */
        int n;
        if (name)
            n = snprintf(d->first_error, sizeof d->first_error, "%s:%u: %s%s", name, line, tag,
                         text);
        else
            n = snprintf(d->first_error, sizeof d->first_error, "%s%s", tag, text);
        if (n >= (int)sizeof d->first_error)
            d->first_error[sizeof d->first_error - 1] = 0;
    }
    if (d->emit)
        d->emit(d->ctx, out, name, name ? line : 0, text);
}

void asm_report(struct asm_ctx *c, const struct asm_file *f, enum asm_rep level, const char *fmt,
                ...) {
    va_list ap;
    va_start(ap, fmt);
    deliver(c, f ? f->name : NULL, f ? f->line : 0, level, fmt, ap);
    va_end(ap);
}

void asm_report_at(struct asm_ctx *c, const char *name, unsigned line, enum asm_rep level,
                   const char *fmt, ...) {
    va_list ap;
    va_start(ap, fmt);
    deliver(c, name, line, level, fmt, ap);
    va_end(ap);
}

void asm_report_plain_error(struct asm_ctx *c, const char *text) {
    c->errors++;
    struct pruasm_diag *d = c->diag;
    if (!d)
        return;
    d->errors = c->errors;
    if (!d->first_error[0])
        snprintf(d->first_error, sizeof d->first_error, "%s", text);
    if (d->emit)
        d->emit(d->ctx, PRUASM_PLAIN, NULL, 0, text);
}

void asm_report_abort(struct asm_ctx *c) {
    if (c->aborted)
        return;
    c->aborted = 1;
    if (c->diag && c->diag->emit)
        c->diag->emit(c->diag->ctx, PRUASM_PLAIN, NULL, 0, "Aborting...");
}

void asm_buf_put(struct asm_buf *b, const char *s, size_t n) {
    if (b->failed)
        return;
    if (b->len + n + 1 > b->cap) {
        size_t ncap = b->cap ? b->cap : 4096;
        while (ncap < b->len + n + 1)
            ncap *= 2;
        char *p = realloc(b->data, ncap);
        if (!p) {
            b->failed = 1;
            return;
        }
        b->data = p;
        b->cap = ncap;
    }
    memcpy(b->data + b->len, s, n);
    b->len += n;
    b->data[b->len] = 0;
}

void asm_buf_printf(struct asm_buf *b, const char *fmt, ...) {
    char tmp[1024];
    va_list ap;
    va_start(ap, fmt);
    int n = vsnprintf(tmp, sizeof tmp, fmt, ap);
    va_end(ap);
    if (n < 0)
        return;
    if ((size_t)n < sizeof tmp) {
        asm_buf_put(b, tmp, (size_t)n);
        return;
    }
    char *big = malloc((size_t)n + 1);
    if (!big) {
        b->failed = 1;
        return;
    }
    va_start(ap, fmt);
    vsnprintf(big, (size_t)n + 1, fmt, ap);
    va_end(ap);
    asm_buf_put(b, big, (size_t)n);
    free(big);
}

void asm_buf_free(struct asm_buf *b) {
    free(b->data);
    b->data = NULL;
    b->len = b->cap = 0;
    b->failed = 0;
}
