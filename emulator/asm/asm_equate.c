/*
 * asm_equate.c - #define equates: creation, #undef, and the word-by-word
 * expansion pasm applies to every source line (recursively, never inside
 * quotes, never re-expanding an equate inside itself).
 */
#include "asm_ctx.h"

#include <stdlib.h>
#include <string.h>

#define EQUATE_DATA_MAX 256 /* pasm's limit for -D and creation values */

struct asm_equate {
    int busy; /* being expanded: stops self-recursion */
    char *data;
};

static void equate_free(void *p) {
    struct asm_equate *e = p;
    if (e) {
        free(e->data);
        free(e);
    }
}

static int equate_add(struct asm_ctx *c, const struct asm_file *f, const char *name,
                      const char *value) {
    struct asm_equate *e = calloc(1, sizeof *e);
    if (e)
        e->data = strdup(value);
    if (!e || !e->data || asm_sym_put(&c->equates, name, e)) {
        equate_free(e);
        asm_report(c, f, REP_ERROR, "Memory allocation failed");
        return -1;
    }
    return 0;
}

int asm_equate_create(struct asm_ctx *c, const struct asm_file *f, const char *name,
                      const char *value) {
    if (!asm_check_name(c, f, name))
        return -1;
    if (strlen(name) >= ASM_TOKEN_MAX) {
        asm_report(c, f, REP_ERROR, "Equate name '%s' too long", name);
        return -1;
    }
    if (strlen(value) >= EQUATE_DATA_MAX) {
        asm_report(c, f, REP_ERROR, "Equate data '%s' too long", value);
        return -1;
    }
    return equate_add(c, f, name, value);
}

void asm_equate_define(struct asm_ctx *c, const struct asm_file *f, const char *s) {
    char name[ASM_TOKEN_MAX];
    int n = 0;
    while (*s == ' ' || *s == '\t')
        s++;
    if (!asm_label_char(*s, 1)) {
        asm_report(c, f, REP_ERROR, "Illegal label");
        return;
    }
    for (;;) {
        name[n++] = *s++;
        if (!*s || *s == ' ' || *s == '\t')
            break;
        if (!asm_label_char(*s, 0)) {
            asm_report(c, f, REP_ERROR, "Illegal #define");
            return;
        }
        if (n >= ASM_TOKEN_MAX - 1) {
            asm_report(c, f, REP_ERROR, "Label too long");
            return;
        }
    }
    name[n] = 0;
    /* An existing equate fails here too: pasm 0.87 never replaces one. */
    if (!asm_check_name(c, f, name))
        return;
    while (*s == ' ' || *s == '\t')
        s++;
    equate_add(c, f, name, *s ? s : "1");
}

void asm_equate_undef(struct asm_ctx *c, const struct asm_file *f, const char *s) {
    char name[ASM_TOKEN_MAX];
    int n = 0;
    while (*s == ' ' || *s == '\t')
        s++;
    if (!asm_label_char(*s, 1)) {
        asm_report(c, f, REP_ERROR, "Illegal label");
        return;
    }
    for (;;) {
        name[n++] = *s++;
        if (!*s)
            break;
        if (*s == ' ' || *s == '\t') {
            asm_report(c, f, REP_ERROR, "Unexpected additional characters on line");
            return;
        }
        if (!asm_label_char(*s, 0)) {
            asm_report(c, f, REP_ERROR, "Illegal name");
            return;
        }
        if (n >= ASM_TOKEN_MAX - 1) {
            asm_report(c, f, REP_ERROR, "Label too long");
            return;
        }
    }
    name[n] = 0;
    int found;
    asm_sym_get(&c->equates, name, &found);
    if (!found) {
        asm_report(c, f, REP_WARN1, "Undef attempt on undfined '%s'", name);
        return;
    }
    equate_free(asm_sym_del(&c->equates, name));
}

int asm_equate_defined(struct asm_ctx *c, const char *name) {
    int found;
    asm_sym_get(&c->equates, name, &found);
    return found;
}

void asm_equate_clear(struct asm_ctx *c) {
    asm_sym_clear(&c->equates, equate_free);
}

static int put(struct asm_ctx *c, const struct asm_file *f, char *dst, int *idx, int max, char ch) {
    if (*idx >= max - 1) {
        asm_report(c, f, REP_ERROR, "Line too long");
        return 0;
    }
    dst[(*idx)++] = ch;
    return 1;
}

enum { W_READY, W_NONLABEL, W_QUOTED, W_LABEL };

int asm_equate_expand(struct asm_ctx *c, const struct asm_file *f, const char *src, char *dst,
                      int *idx, int max) {
    char word[ASM_TOKEN_MAX];
    int wn = 0, state = W_READY;
    for (const char *p = src;;) {
        char ch = *p++;
        if (state == W_READY) {
            if (ch == '"') {
                state = W_QUOTED;
            } else if (asm_label_char(ch, 1)) {
                state = W_LABEL;
                wn = 0;
                word[wn++] = ch;
                continue;
            } else if (asm_label_char(ch, 0)) {
                state = W_NONLABEL; /* a number: its letters are not names */
            }
        } else if (state == W_NONLABEL) {
            if (ch == '"')
                state = W_QUOTED;
            else if (!asm_label_char(ch, 0))
                state = W_READY;
        } else if (state == W_LABEL) {
            if (wn < ASM_TOKEN_MAX - 1 && asm_label_char(ch, 0)) {
                word[wn++] = ch;
                continue;
            }
            state = ch == '"' ? W_QUOTED : W_READY;
            word[wn] = 0;
            struct asm_equate *e = asm_sym_get(&c->equates, word, NULL);
            if (e && !e->busy) {
                if (c->equate_nest >= ASM_EQUATE_NEST_MAX) {
                    asm_report(c, f, REP_ERROR, "Equate '%s' nested too deeply", word);
                    return 0;
                }
                e->busy = 1;
                c->equate_nest++;
                int ok = asm_equate_expand(c, f, e->data, dst, idx, max);
                c->equate_nest--;
                e->busy = 0;
                if (!ok)
                    return 0;
            } else {
                for (int i = 0; i < wn; i++)
                    if (!put(c, f, dst, idx, max, word[i]))
                        return 0;
            }
        } else if (ch == '"') {
            state = W_READY;
        }
        if (!ch) {
            if (state == W_QUOTED)
                asm_report(c, f, REP_ERROR, "Non-terminated string");
            break;
        }
        if (!put(c, f, dst, idx, max, ch))
            return 0;
    }
    return 1;
}
