/*
 * asm_expr.c - pasm's expression evaluator: 32-bit unsigned values, unary
 * - and ~, binary * / % + - << >> & ^ | with pasm's precedence table
 * (equal precedence evaluates left to right), parentheses, numbers in
 * decimal/0x/0b/octal, labels (0 in pass 1 when not yet known) and &Rn.
 */
#include "asm_ctx.h"

#include <ctype.h>
#include <stdio.h>
#include <string.h>

#define MAX_TERMS 32

enum { OP_MUL = 1, OP_DIV, OP_MOD, OP_ADD, OP_SUB, OP_SHL, OP_SHR, OP_AND, OP_XOR, OP_OR };
static const unsigned char prec[] = {99, 1, 1, 1, 2, 2, 3, 3, 4, 5, 6};

static int expression(struct asm_ctx *c, const struct asm_file *f, char *s, uint32_t *out,
                      int *pidx);

int asm_reg_offset(struct asm_ctx *c, const char *s, uint32_t *out) {
    (void)c;
    const unsigned char *p = (const unsigned char *)s;
    if (toupper(*p++) != 'R' || !isdigit(*p))
        return 0;
    unsigned reg = 0, width = 32, offset = 0;
    while (isdigit(*p)) {
        reg = reg * 10 + (*p++ - '0');
        if (reg > 31)
            return 0;
    }
    while (*p) {
        if (*p++ != '.')
            return 0;
        int kind = toupper(*p++);
        if ((kind != 'W' && kind != 'B') || !isdigit(*p))
            return 0;
        unsigned v = 0;
        while (isdigit(*p)) {
            v = v * 10 + (*p++ - '0');
            if (v > 1000)
                return 0;
        }
        unsigned w = kind == 'W' ? 16 : 8;
        if (v * 8 + w > width)
            return 0;
        width = w;
        offset += v;
    }
    *out = reg * 4 + offset;
    return 1;
}

/* Returns 1 with a value, 0 for none (end, or an unknown label in pass 2),
 * -1 on a syntax error. */
static int get_value(struct asm_ctx *c, const struct asm_file *f, char *s, int *pidx,
                     uint32_t *val) {
    int i = *pidx, rc = 1;
    uint32_t t = 0;
    while (s[i] == ' ' || s[i] == '\t')
        i++;
    char ch = s[i];
    if (!ch)
        return 0;

    if (asm_label_char(ch, 1) || ch == '.' || ch == '&') {
        char name[ASM_TOKEN_MAX];
        int n = 0;
        do {
            if (n < ASM_TOKEN_MAX - 1)
                name[n++] = s[i];
            i++;
        } while (asm_label_char(s[i], 0) || s[i] == '.');
        name[n] = 0;
        *pidx = i;
        if ((asm_token_type(name) & TOK_REG_ADDR) && asm_reg_offset(c, name + 1, &t)) {
            *val = t;
            return 1;
        }
        if (!asm_label_find(c, name, val)) {
            if (c->pass == 1) {
                *val = 0;
                return 1;
            }
            asm_report(c, f, REP_ERROR, "Not found: '%s'", name);
            return 0;
        }
        return 1;
    }
    if (ch == '-' || ch == '~') {
        i++;
        int r = get_value(c, f, s, &i, &t);
        if (r < 0)
            rc = r;
        else
            t = ch == '-' ? 0u - t : ~t;
        goto done;
    }
    if (ch == '(') {
        int j = ++i, depth = 1;
        for (;; j++) {
            if (!s[j]) {
                rc = -1;
                goto done;
            }
            if (s[j] == '(')
                depth++;
            if (s[j] == ')' && --depth == 0)
                break;
        }
        s[j] = 0;
        int k = 0;
        /* pasm evaluates the inside without a source location. */
        if (expression(c, NULL, s + i, &t, &k) < 0) {
            i += k;
            rc = -1;
        } else {
            i = j + 1;
        }
        goto done;
    }
    if (ch < '0' || ch > '9') {
        rc = -1;
        goto done;
    }
    unsigned base = 10;
    t = (uint32_t)(ch - '0');
    i++;
    if (t == 0) {
        if (s[i] == 'x') {
            base = 16;
            i++;
        } else if (s[i] == 'b') {
            base = 2;
            i++;
        } else {
            base = 8;
        }
    }
    for (;; i++) {
        unsigned d;
        ch = s[i];
        if (ch >= '0' && ch <= '9')
            d = (unsigned)(ch - '0');
        else if (ch >= 'a' && ch <= 'f')
            d = (unsigned)(ch - 'a' + 10);
        else if (ch >= 'A' && ch <= 'F')
            d = (unsigned)(ch - 'A' + 10);
        else
            break;
        if (d >= base) {
            rc = -1;
            goto done;
        }
        t = t * base + d;
    }
done:
    *val = t;
    *pidx = i;
    return rc;
}

static int get_op(char *s, int *pidx, unsigned *op) {
    int i = *pidx, rc = 1;
    while (s[i] == ' ' || s[i] == '\t')
        i++;
    switch (s[i]) {
    case 0:
        return 0;
    case '*':
        *op = OP_MUL;
        break;
    case '/':
        *op = OP_DIV;
        break;
    case '%':
        *op = OP_MOD;
        break;
    case '+':
        *op = OP_ADD;
        break;
    case '-':
        *op = OP_SUB;
        break;
    case '<':
    case '>':
        if (s[i + 1] != s[i])
            rc = -1;
        *op = s[i] == '<' ? OP_SHL : OP_SHR;
        i++;
        break;
    case '&':
        *op = OP_AND;
        break;
    case '^':
        *op = OP_XOR;
        break;
    case '|':
        *op = OP_OR;
        break;
    default:
        rc = -1;
    }
    if (rc == 1)
        i++;
    *pidx = i;
    return rc;
}

static int apply(struct asm_ctx *c, const struct asm_file *f, unsigned op, uint32_t a, uint32_t b,
                 uint32_t *r) {
    switch (op) {
    case OP_MUL:
        *r = a * b;
        break;
    case OP_DIV:
    case OP_MOD:
        if (!b) {
            if (c->pass == 2) {
                asm_report(c, f, REP_ERROR, op == OP_DIV ? "Divide by zero" : "Mod by zero");
                return -1;
            }
            *r = 0;
        } else {
            *r = op == OP_DIV ? a / b : a % b;
        }
        break;
    case OP_ADD:
        *r = a + b;
        break;
    case OP_SUB:
        *r = a - b;
        break;
    /* x86 shifts use the count modulo 32; pasm's results follow that. */
    case OP_SHL:
        *r = a << (b & 31);
        break;
    case OP_SHR:
        *r = a >> (b & 31);
        break;
    case OP_AND:
        *r = a & b;
        break;
    case OP_XOR:
        *r = a ^ b;
        break;
    default:
        *r = a | b;
        break;
    }
    return 0;
}

static int expression(struct asm_ctx *c, const struct asm_file *f, char *s, uint32_t *out,
                      int *pidx) {
    uint32_t val[MAX_TERMS];
    unsigned ops[MAX_TERMS];
    int nv = 0, no = 0, idx = 0, r = 0;
    while (nv < MAX_TERMS) {
        r = get_value(c, f, s, &idx, &val[nv]);
        if (!r)
            break;
        if (r < 0) {
            *pidx = idx;
            return -1;
        }
        nv++;
        r = get_op(s, &idx, &ops[no]);
        if (!r)
            break;
        if (r < 0) {
            *pidx = idx;
            return -1;
        }
        no++;
    }
    if (r) {
        asm_report(c, f, REP_ERROR, "Max term count exceeded");
        return -1;
    }
    *pidx = idx;
    if (no >= nv || !nv)
        return -1;
    while (no) {
        int m = 0;
        for (int i = 1; i < no; i++)
            if (prec[ops[i]] < prec[ops[m]])
                m = i;
        if (apply(c, f, ops[m], val[m], val[m + 1], &val[m]))
            return -1;
        memmove(&val[m + 1], &val[m + 2], (size_t)(nv - m - 2) * sizeof val[0]);
        memmove(&ops[m], &ops[m + 1], (size_t)(no - m - 1) * sizeof ops[0]);
        no--;
        nv--;
    }
    *out = val[0];
    return 0;
}

int asm_expr(struct asm_ctx *c, const struct asm_file *f, const char *s, uint32_t *out) {
    char tmp[ASM_LINE_MAX];
    int idx = 0;
    snprintf(tmp, sizeof tmp, "%s", s);
    return expression(c, f, tmp, out, &idx);
}
