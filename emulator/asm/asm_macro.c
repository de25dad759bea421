/*
 * asm_macro.c - .macro/.mparam/.endm: a body is read (through the
 * preprocessor) when defined; each use substitutes parameters word by word,
 * renames the body's labels to _<label>_<macro id>_<use count>_ as pasm
 * does, and assembles the lines at the point of use.
 */
#include "asm_ctx.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#define MACRO_MAX_ARGS   8
#define MACRO_MAX_LINES  128
#define MACRO_MAX_LABELS 32

struct asm_macro {
    char name[ASM_TOKEN_MAX];
    char source[ASM_NAME_MAX]; /* file it was defined in */
    int in_use;                /* being defined or expanded: no recursion */
    int id, nargs, required, nlabels, uses, nlines;
    char arg[MACRO_MAX_ARGS][ASM_TOKEN_MAX];
    char def[MACRO_MAX_ARGS][ASM_TOKEN_MAX];
    char label[MACRO_MAX_LABELS][ASM_TOKEN_MAX];
    char line[MACRO_MAX_LINES][ASM_MACRO_LINE_MAX];
    unsigned lineno[MACRO_MAX_LINES];
};

int asm_macro_exists(struct asm_ctx *c, const char *name) {
    int found;
    asm_sym_get(&c->macros, name, &found);
    return found;
}

void asm_macro_clear(struct asm_ctx *c) {
    asm_sym_clear(&c->macros, free);
    c->macro_id = 0;
}

/* Parse one ".mparam" entry: name or name=default. */
static int add_arg(struct asm_ctx *c, const struct asm_file *f, struct asm_macro *m,
                   const char *text) {
    if (m->nargs == MACRO_MAX_ARGS) {
        asm_report(c, f, REP_ERROR, "Too many macro arguments");
        return -1;
    }
    size_t i = 0, n = 0;
    char *name = m->arg[m->nargs], *def = m->def[m->nargs];
    while (text[i] == ' ' || text[i] == '\t')
        i++;
    while (text[i] && text[i] != ' ' && text[i] != '\t' && text[i] != '=') {
        if (n == ASM_TOKEN_MAX - 1) {
            asm_report(c, f, REP_ERROR, "Macro argument name too long");
            return -1;
        }
        if (!asm_label_char(text[i], n == 0)) {
            asm_report(c, f, REP_ERROR, "Illegal character in macro argument name");
            return -1;
        }
        name[n++] = text[i++];
    }
    name[n] = 0;
    if (!n)
        goto syntax;
    for (int k = 0; k < m->nargs; k++) {
        if (!strcmp(m->arg[k], name)) {
            asm_report(c, f, REP_ERROR, "Duplicate macro argument name '%s'", name);
            return -1;
        }
    }
    while (text[i] == ' ' || text[i] == '\t')
        i++;
    if (text[i] == '=') {
        i++;
        while (text[i] == ' ' || text[i] == '\t')
            i++;
        n = 0;
        while (text[i] && text[i] != ' ' && text[i] != '\t' && text[i] != '=') {
            if (n == ASM_TOKEN_MAX - 1) {
                asm_report(c, f, REP_ERROR, "Macro argument value too long");
                return -1;
            }
            if (!asm_label_char(text[i], 0) && text[i] != '.')
                goto syntax;
            def[n++] = text[i++];
        }
        def[n] = 0;
        if (!n)
            goto syntax;
        m->nargs++;
    } else {
        def[0] = 0;
        if (m->nargs > m->required) {
            asm_report(c, f, REP_ERROR, "Optional macro arguments must be listed last");
            return -1;
        }
        m->nargs++;
        m->required++;
    }
    if (text[i]) {
    syntax:
        asm_report(c, f, REP_ERROR, "Syntax error in macro argument '%s' around character %d", text,
                   (int)i + 1);
        return -1;
    }
    return 0;
}

int asm_macro_define(struct asm_ctx *c, struct asm_file *f, const char *name) {
    if (!asm_check_name(c, f, name))
        return -1;
    if (strlen(name) >= ASM_TOKEN_MAX) {
        asm_report(c, f, REP_ERROR, "Macro name too long");
        return -1;
    }
    struct asm_macro *m = calloc(1, sizeof *m);
    if (!m || asm_sym_put(&c->macros, name, m)) {
        free(m);
        asm_report(c, f, REP_FATAL, "Memory allocation failed");
        return -1;
    }
    snprintf(m->name, sizeof m->name, "%s", name);
    snprintf(m->source, sizeof m->source, "%s", f->name);
    m->in_use = 1;
    m->id = c->macro_id++;

    char src[ASM_MACRO_LINE_MAX];
    struct asm_stmt st;
    for (;;) {
        if (c->fatal || c->errors >= ASM_MAX_ERRORS)
            return -1;
        int n = asm_get_line(c, f, src, sizeof src);
        if (n == 0) {
            asm_report(c, f, REP_ERROR, "Missing .endm on macro");
            return -1;
        }
        if (n < 0 || !asm_parse_stmt(c, f, src, &st))
            continue;
        if (st.has_label) {
            if (m->nlabels == MACRO_MAX_LABELS)
                asm_report(c, f, REP_ERROR, "Macro contains too many labels");
            else
                snprintf(m->label[m->nlabels++], ASM_TOKEN_MAX, "%s", st.label);
        }
        if (st.nterms && st.dot) {
            /* pasm drops other dot commands inside a macro body. */
            if (!strcasecmp(st.term[0], ".mparam")) {
                if (st.nterms == 1)
                    asm_report(c, f, REP_ERROR, "Expected at least 1 parameter on .mparam");
                for (int i = 1; i < st.nterms; i++)
                    add_arg(c, f, m, st.term[i]);
            } else if (!strcasecmp(st.term[0], ".macro")) {
                asm_report(c, f, REP_ERROR, "Macro definitions may not be nested");
            } else if (!strcasecmp(st.term[0], ".endm")) {
                m->in_use = 0;
                return 0;
            }
            continue;
        }
        if (m->nlines == MACRO_MAX_LINES) {
            asm_report(c, f, REP_ERROR, "Macro line count exceeded");
            continue;
        }
        snprintf(m->line[m->nlines], ASM_MACRO_LINE_MAX, "%s", src);
        m->lineno[m->nlines++] = f->line;
    }
}

/* Append s to dst (capacity max); returns -1 if it did not fit. */
static int append(char *dst, size_t max, const char *s) {
    size_t n = strlen(dst), k = strlen(s);
    if (n + k >= max)
        return -1;
    memcpy(dst + n, s, k + 1);
    return 0;
}

/* The replacement of one identifier of a macro line. */
static const char *substitute(const struct asm_macro *m, const char *word, int nterms,
                              char terms[][ASM_TOKEN_MAX], char *buf, size_t max) {
    for (int i = 0; i < m->nargs; i++)
        if (!strcmp(word, m->arg[i]))
            return i + 1 >= nterms ? m->def[i] : terms[i + 1];
    for (int i = 0; i < m->nlabels; i++) {
        if (!strcmp(word, m->label[i])) {
            snprintf(buf, max, "_%s_%d_%d_", m->label[i], m->id, m->uses);
            return buf;
        }
    }
    return word;
}

/* Build expansion line k into out. Returns 0, or -1 if it grew too long. */
static int expand_line(struct asm_ctx *c, const struct asm_macro *m, int k, int nterms,
                       char terms[][ASM_TOKEN_MAX], char *out) {
    char word[ASM_TOKEN_MAX], buf[ASM_TOKEN_MAX + 32], one[2] = {0, 0};
    size_t wn = 0;
    (void)c;
    out[0] = 0;
    for (const char *p = m->line[k];; p++) {
        char ch = *p;
        if (!wn && asm_label_char(ch, 1)) {
            word[wn++] = ch;
            continue;
        }
        if (wn && asm_label_char(ch, 0)) {
            if (wn == ASM_TOKEN_MAX - 1)
                return -2;
            word[wn++] = ch;
            continue;
        }
        if (wn) {
            word[wn] = 0;
            wn = 0;
            if (append(out, ASM_MACRO_LINE_MAX,
                       substitute(m, word, nterms, terms, buf, sizeof buf)))
                return -1;
        }
        if (!ch)
            return 0;
        one[0] = ch;
        if (append(out, ASM_MACRO_LINE_MAX, one))
            return -1;
    }
}

int asm_macro_expand(struct asm_ctx *c, struct asm_file *f, int nterms,
                     char terms[][ASM_TOKEN_MAX]) {
    struct asm_macro *m = asm_sym_get(&c->macros, terms[0], NULL);
    if (!m)
        return 0;
    if (m->in_use) {
        asm_report(c, f, REP_ERROR, "Illegal recursive use of macro '%s'", terms[0]);
        return 0;
    }
    if (m->required >= nterms) {
        asm_report(c, f, REP_ERROR, "Expected at least %d arguments on '%s'", m->required,
                   terms[0]);
        return 0;
    }
    if (m->nargs < nterms - 1) {
        asm_report(c, f, REP_ERROR, "Expected no more than %d arguments on '%s'", m->nargs,
                   terms[0]);
        return 0;
    }
    if (c->macro_nest >= ASM_MACRO_NEST_MAX) {
        asm_report(c, f, REP_ERROR, "Macros nested too deeply at '%s'", terms[0]);
        return 0;
    }
    m->uses++;
    m->in_use = 1;
    c->macro_nest++;
    int ok = 1;
    char src[ASM_MACRO_LINE_MAX];
    for (int k = 0; k < m->nlines && ok; k++) {
        int r = expand_line(c, m, k, nterms, terms, src);
        if (r == -2) {
            asm_report(c, f, REP_ERROR, "Term too long in macro assembly text");
            ok = 0;
        } else if (r < 0) {
            asm_report(c, f, REP_ERROR, "Macro expansion too long");
            ok = 0;
        } else if (src[0] && !asm_process_line(c, f, src)) {
            /* Name the macro line; pasm uses the macro's file only when it
             * differs from the current one. */
            if (strcmp(f->name, m->source))
                asm_report_at(c, m->source, m->lineno[k], REP_ERROR,
                              "(While expanding line %u in macro '%s': ``%s'')", m->lineno[k],
                              m->name, src);
            else
                asm_report(c, f, REP_ERROR, "(While expanding line %u in macro '%s': ``%s'')",
                           m->lineno[k], m->name, src);
            ok = 0;
        }
    }
    c->macro_nest--;
    m->in_use = 0;
    return ok;
}
