/*
 * asm_line.c - one statement: split it into label and terms, define the
 * label, apply structure substitution, and hand it to the dot-command,
 * macro or instruction handler. Also the code emitter and name rules.
 */
#include "asm_ctx.h"

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int asm_label_char(int ch, int first) {
    if ((ch >= 'A' && ch <= 'Z') || (ch >= 'a' && ch <= 'z') || ch == '_')
        return 1;
    return !first && ch >= '0' && ch <= '9';
}

int asm_label_find(struct asm_ctx *c, const char *name, uint32_t *value) {
    int found;
    void *v = asm_sym_get(&c->labels, name, &found);
    if (found)
        *value = (uint32_t)(uintptr_t)v;
    return found;
}

int asm_check_name(struct asm_ctx *c, const struct asm_file *f, const char *name) {
    uint32_t dummy;
    const char *what = NULL;
    if (asm_token_type(name) != TOK_UNRESERVED) {
        asm_report(c, f, REP_ERROR, "Illegal use of reserved word '%s'", name);
        return 0;
    }
    if (asm_label_find(c, name, &dummy))
        what = "a label";
    else if (asm_equate_defined(c, name))
        what = "an equate";
    else if (asm_struct_exists(c, name))
        what = "a structure or scope";
    else if (asm_macro_exists(c, name))
        what = "a macro";
    if (what) {
        asm_report(c, f, REP_ERROR, "'%s' is already %s", name, what);
        return 0;
    }
    return 1;
}

static void label_create(struct asm_ctx *c, const struct asm_file *f, const char *name, int value) {
    if (strlen(name) >= ASM_TOKEN_MAX) {
        asm_report(c, f, REP_ERROR, "Label too long");
        return;
    }
    if (!asm_check_name(c, f, name))
        return;
    if (c->nlabels == c->label_cap) {
        size_t cap = c->label_cap ? 2 * c->label_cap : 64;
        char **p = realloc(c->label_order, cap * sizeof *p);
        if (!p) {
            asm_report(c, f, REP_FATAL, "Memory allocation failed");
            return;
        }
        c->label_order = p;
        c->label_cap = cap;
    }
    char *copy = strdup(name);
    if (!copy || asm_sym_put(&c->labels, name, (void *)(uintptr_t)(uint32_t)value)) {
        free(copy);
        asm_report(c, f, REP_FATAL, "Memory allocation failed");
        return;
    }
    c->label_order[c->nlabels++] = copy;
}

int asm_validate_offset(struct asm_ctx *c, const struct asm_file *f) {
    if (c->code_offset == -1) {
        c->code_offset = 8;
        if (c->entry_point < 0)
            c->entry_point = 8;
        asm_report(c, f, REP_WARN1, "Using default code origin of 8");
    }
    if (c->code_offset >= ASM_MAX_WORDS) {
        asm_report(c, f, REP_FATAL, "Max program size exceeded");
        return 0;
    }
    return 1;
}

void asm_gen(struct asm_ctx *c, const struct asm_file *f, int nterms, char terms[][ASM_TOKEN_MAX],
             uint32_t word) {
    if (!asm_validate_offset(c, f))
        return;
    if (c->pass == 2 && c->opt && c->opt->want_listing) {
        asm_buf_printf(&c->listing, "%s(%5u) : 0x%04x = 0x%08x :     %-8s ", f->name, f->line,
                       (unsigned)c->code_offset, (unsigned)word, terms[0]);
        for (int i = 1; i < nterms; i++)
            asm_buf_printf(&c->listing, i > 1 ? ", %s" : "%s", terms[i]);
        if (word == 0xFFFFFFFFu)
            asm_buf_printf(&c->listing, "  // *** ERROR ***");
        asm_buf_put(&c->listing, "\n", 1);
    }
    int a = c->code_offset++;
    c->words[a] = word;
    c->info[a].file = (uint16_t)f->index;
    c->info[a].line = f->line;
    c->info[a].written = 1;
}

static int is_param_start(char ch) {
    return asm_label_char(ch, 0) || (ch && strchr(".#-(\"&*", ch));
}

int asm_parse_stmt(struct asm_ctx *c, const struct asm_file *f, const char *src,
                   struct asm_stmt *st) {
    size_t i = 0;
    char ch;
    st->has_label = 0;
    st->dot = 0;
    st->nterms = 0;
again:
    ch = src[i++];
    if (!asm_label_char(ch, 1) && ch != '.') {
        asm_report(c, f, REP_ERROR, "Syntax error in Cmd/Opcode");
        return 0;
    }
    int n = 0;
    while (asm_label_char(ch, 0) || ch == '.') {
        if (n >= ASM_TOKEN_MAX - 1) {
            asm_report(c, f, REP_ERROR, "Cmd/Opcode too long");
            return 0;
        }
        st->term[0][n++] = ch;
        ch = src[i++];
    }
    st->term[0][n] = 0;
    if (ch == ':') {
        if (st->has_label) {
            asm_report(c, f, REP_ERROR, "Two labels found on the same line");
            return 0;
        }
        st->has_label = 1;
        memcpy(st->label, st->term[0], (size_t)n + 1);
        if (!src[i])
            return 1;
        while (src[i] == ' ' || src[i] == '\t')
            i++;
        goto again;
    }
    if (ch != ' ' && ch != 0 && ch != '\t') {
        asm_report(c, f, REP_ERROR, "Syntax error in Cmd/Opcode");
        return 0;
    }
    int np = 0;
    while (ch) {
        np++;
        if (np == ASM_MAX_TERMS) {
            asm_report(c, f, REP_ERROR, "Too many parameters on line");
            return 0;
        }
        while (ch == ' ' || ch == '\t')
            ch = src[i++];
        if (!is_param_start(ch)) {
            asm_report(c, f, REP_ERROR, "Syntax error in parameter %d", np);
            return 0;
        }
        char *t = st->term[np];
        n = 0;
        /* A first operand starting with '.' ends at white space (dot-command
         * style), and that white space then separates operands. */
        int dotword = np == 1 && ch == '.';
        while (ch && ch != ',' && !(dotword && (ch == ' ' || ch == '\t'))) {
            if (n >= ASM_TOKEN_MAX - 1) {
                asm_report(c, f, REP_ERROR, "Parameter %d too long", np);
                return 0;
            }
            t[n++] = ch;
            ch = src[i++];
        }
        if (dotword && (ch == ' ' || ch == '\t'))
            ch = ',';
        t[n] = 0;
        while (n && (t[n - 1] == ' ' || t[n - 1] == '\t'))
            t[--n] = 0;
        if (ch == ',') {
            ch = src[i++];
        } else if (ch) {
            asm_report(c, f, REP_ERROR, "Syntax error in parameter %d", np);
            return 0;
        }
    }
    st->nterms = np + 1;
    st->dot = st->term[0][0] == '.';
    return 1;
}

int asm_process_line(struct asm_ctx *c, struct asm_file *f, const char *line) {
    struct asm_stmt st;
    char gen[2 * ASM_TOKEN_MAX]; /* what .proc or .ret produce */
    const char *src = line;
    for (;;) {
        if (!asm_parse_stmt(c, f, src, &st))
            return 0;
        if (st.has_label) {
            if (!asm_validate_offset(c, f))
                return 0;
            if (c->pass == 1)
                label_create(c, f, st.label, c->code_offset);
            if (c->pass == 2 && c->opt && c->opt->want_listing)
                asm_buf_printf(&c->listing, "%s(%5u) : 0x%04x = Label      : %s:\n", f->name,
                               f->line, (unsigned)c->code_offset, st.label);
        }
        if (!st.nterms)
            return 1;
        int is_macro = asm_macro_exists(c, st.term[0]);
        if (!is_macro) {
            for (int i = 0; i < st.nterms; i++) {
                if (asm_struct_param(c, f, i, st.term[i]) < 0) {
                    asm_report(c, f, REP_ERROR, "Error in struct parsing parameter %d", i);
                    return 0;
                }
            }
        }
        if (st.dot) {
            int rc = asm_dot_command(c, f, st.nterms, st.term, gen, sizeof gen);
            if (rc < 0)
                return 0;
            if (rc == 0)
                return 1;
            src = gen; /* the command produced a statement: assemble it */
            continue;
        }
        if (is_macro)
            return asm_macro_expand(c, f, st.nterms, st.term);
        if (!asm_instruction(c, f, st.nterms, st.term)) {
            /* Keep the addresses of both passes in step. */
            asm_gen(c, f, st.nterms, st.term, 0xFFFFFFFFu);
            return 0;
        }
        return 1;
    }
}
