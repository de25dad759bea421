/*
 * asm_token.c - what a word is (mnemonic, directive, register-shaped
 * reserved word) and the operand parsers: registers with nested field
 * selectors and .tN bits, immediates, constant-table entries, b0..b3.
 */
#include "asm_ctx.h"
#include "pru_isa.h"

#include <ctype.h>
#include <string.h>

/* Every mnemonic pasm 0.87 knows, any core version, is a reserved word:
 * the rows of the instruction list (pru_isa.h). */
int asm_is_mnemonic(const char *word) {
    return pru_op_lookup(word) >= 0;
}

unsigned asm_token_type(const char *w) {
    if (asm_is_mnemonic(w))
        return TOK_OPCODE;
    if (asm_is_dot_command(w) || !strcmp(w, "SIZE") || !strcmp(w, "OFFSET"))
        return TOK_DIRECTIVE;

    /* [*][&|--](B|C|R|T|W)d[d][.(B|C|R|T|W)d[d]]...[++] is register-shaped. */
    unsigned flags;
    size_t i = 0;
    if (w[0] == '*') {
        flags = TOK_REG_PTR;
        i++;
        if (w[i] == '&') {
            flags |= TOK_REG_ADDR;
            i++;
        } else {
            flags |= TOK_REG_BASE;
            if (w[i] == '-') {
                if (w[i + 1] != '-')
                    return TOK_UNRESERVED;
                i += 2;
                flags |= TOK_REG_PREDEC;
            }
        }
    } else if (w[0] == '&') {
        flags = TOK_REG_ADDR;
        i++;
    } else {
        flags = TOK_REG_BASE;
    }
    int state = 0;
    for (;;) {
        int ch = toupper((unsigned char)w[i++]);
        switch (state) {
        case 0:
            if (!strchr("BCRTW", ch) || !ch)
                return TOK_UNRESERVED;
            state = 1;
            break;
        case 1:
            if (!isdigit(ch))
                return TOK_UNRESERVED;
            state = 2;
            break;
        default:
            if (isdigit(ch)) {
                if (++state > 3)
                    return TOK_UNRESERVED;
            } else if (ch == '.') {
                state = 0;
            } else if (!ch || ch == ' ' || ch == '\t') {
                return flags;
            } else if (ch == '+') {
                if (flags & (TOK_REG_ADDR | TOK_REG_PREDEC))
                    return TOK_UNRESERVED;
                if (w[i] != '+' || w[i + 1] != 0)
                    return TOK_UNRESERVED;
                return flags | TOK_REG_POSTINC;
            } else {
                return TOK_UNRESERVED;
            }
        }
    }
}

/* Digits at *p (at most a sane number of them); -1 if none. */
static long digits(const unsigned char **p) {
    if (!isdigit(**p))
        return -1;
    long v = 0;
    while (isdigit(**p)) {
        if (v < 100000)
            v = v * 10 + (**p - '0');
        (*p)++;
    }
    return v;
}

static int bad_reg(struct asm_ctx *c, const struct asm_file *f, int num, const char *src) {
    asm_report(c, f, REP_ERROR, "Operand %d '%s' invalid register or register mode", num, src);
    return 0;
}

int asm_get_reg(struct asm_ctx *c, const struct asm_file *f, int num, const char *src,
                struct asm_arg *a, int bit_ok, char term) {
    const unsigned char *p = (const unsigned char *)src;
    if (toupper(*p++) != 'R')
        return bad_reg(c, f, num, src);
    long reg = digits(&p);
    if (reg < 0 || reg > 31)
        return bad_reg(c, f, num, src);
    long width = 32, offset = 0, bit = -1;
    for (;;) {
        if (*p == (unsigned char)term)
            break;
        if (*p++ != '.')
            return bad_reg(c, f, num, src);
        int kind = toupper(*p++);
        if (kind != 'T' && kind != 'W' && kind != 'B')
            return bad_reg(c, f, num, src);
        long v = digits(&p);
        if (v < 0)
            return bad_reg(c, f, num, src);
        if (kind == 'W' || kind == 'B') {
            long w = kind == 'W' ? 16 : 8;
            if (v * 8 + w > width)
                return bad_reg(c, f, num, src);
            width = w;
            offset += v;
        } else {
            if (!bit_ok) {
                asm_report(c, f, REP_ERROR, "Operand %d use of .T field not allowed here", num);
                return 0;
            }
            if (v >= width || *p != (unsigned char)term)
                return bad_reg(c, f, num, src);
            bit = v;
        }
    }
    a->type = ARG_REG;
    a->value = (uint32_t)reg;
    if (width == 32)
        a->field = PRU_SEL_R;
    else if (width == 16)
        a->field = PRU_SEL_W0 + (unsigned)offset;
    else
        a->field = PRU_SEL_B0 + (unsigned)offset;
    if (bit >= 0) {
        a->type = ARG_REGBIT;
        a->bit = (unsigned)bit;
    }
    return 1;
}

int asm_get_imm(struct asm_ctx *c, const struct asm_file *f, int num, const char *src,
                struct asm_arg *a, uint32_t lo, uint32_t hi) {
    unsigned t = asm_token_type(src);
    if (t != TOK_UNRESERVED && !(t & TOK_REG_ADDR)) {
        asm_report(c, f, REP_ERROR, "Operand %d reserved word '%s' not legal here", num, src);
        return 0;
    }
    if (*src == '#')
        src++; /* legacy immediate marker */
    uint32_t v;
    if (asm_expr(c, f, src, &v) < 0) {
        asm_report(c, f, REP_ERROR, "Operand %d error in expression", num);
        return 0;
    }
    a->type = ARG_IMM;
    a->value = v;
    a->field = 0;
    if (v < lo || v > hi) {
        asm_report(c, f, REP_ERROR, "Operand %d immediate value out of range (%d-%d)", num, (int)lo,
                   (int)hi);
        return 0;
    }
    return 1;
}

/* "<letter><number>" with nothing after it and number <= max, else -1. */
static long letter_number(const char *src, int letter, long max) {
    const unsigned char *p = (const unsigned char *)src;
    if (toupper(*p++) != letter)
        return -1;
    long v = digits(&p);
    if (v < 0 || *p || v > max)
        return -1;
    return v;
}

int asm_get_const(struct asm_ctx *c, const struct asm_file *f, int num, const char *src,
                  struct asm_arg *a) {
    long v = letter_number(src, 'C', 31);
    if (v < 0) {
        asm_report(c, f, REP_ERROR, "Operand %d invalid constant table entry '%s'", num, src);
        return 0;
    }
    a->type = ARG_CONST;
    a->value = (uint32_t)v;
    a->field = 0;
    return 1;
}

int asm_get_r0byte(struct asm_ctx *c, const struct asm_file *f, int num, const char *src,
                   struct asm_arg *a) {
    long v = letter_number(src, 'B', 3);
    if (v < 0) {
        asm_report(c, f, REP_ERROR, "Operand %d invalid byte count '%s'", num, src);
        return 0;
    }
    a->type = ARG_R0BYTE;
    a->value = (uint32_t)v;
    a->field = 0;
    return 1;
}

unsigned asm_field_start(const struct asm_ctx *c, unsigned field) {
    unsigned off = pru_sel_shift(field) / 8, size = pru_sel_width(field) / 8;
    return c->big_endian ? 4 - off - size : off;
}

unsigned asm_field_at(const struct asm_ctx *c, unsigned off, unsigned size) {
    if (c->big_endian)
        off = 4 - off - size;
    return size == 4 ? PRU_SEL_R : size == 2 ? PRU_SEL_W0 + off : PRU_SEL_B0 + off;
}
