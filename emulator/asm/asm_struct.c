/*
 * asm_struct.c - .struct/.u8/.u16/.u32/.ends declarations, .assign of a
 * structure onto registers, .enter/.leave/.using scopes, and the operand
 * rewriting that turns Name.field into a register and SIZE()/OFFSET() into
 * numbers.
 */
#include "asm_ctx.h"
#include "pru_isa.h"

#include <ctype.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define STRUCT_MAX_ELEM 64
#define REGNAME_MAX     16

struct asm_struct {
    int nelem;
    unsigned total;
    unsigned offset[STRUCT_MAX_ELEM], size[STRUCT_MAX_ELEM];
    char elem[STRUCT_MAX_ELEM][ASM_TOKEN_MAX];
};

struct asm_assign {
    struct asm_assign *next;
    char name[ASM_TOKEN_MAX];
    char base[REGNAME_MAX]; /* register of the first element */
    struct asm_struct layout;
    char reg[STRUCT_MAX_ELEM][REGNAME_MAX];
};

struct asm_scope {
    struct asm_scope *next, *parent;
    int open;
    char name[ASM_TOKEN_MAX];
    struct asm_assign *assigns;
};

static struct asm_scope *scope_find(struct asm_ctx *c, const char *name) {
    for (struct asm_scope *s = c->scopes; s; s = s->next)
        if (!strcmp(s->name, name))
            return s;
    return NULL;
}

static struct asm_assign *assign_find(struct asm_ctx *c, const char *name) {
    for (struct asm_scope *s = c->scopes; s; s = s->next)
        if (s->open)
            for (struct asm_assign *a = s->assigns; a; a = a->next)
                if (!strcmp(a->name, name))
                    return a;
    return NULL;
}

int asm_struct_exists(struct asm_ctx *c, const char *name) {
    int found;
    asm_sym_get(&c->structs, name, &found);
    return found || assign_find(c, name) || scope_find(c, name);
}

static struct asm_scope *scope_create(struct asm_ctx *c, const struct asm_file *f,
                                      const char *name) {
    if (f && !asm_check_name(c, f, name))
        return NULL;
    if (strlen(name) >= ASM_TOKEN_MAX) {
        asm_report(c, f, REP_ERROR, "Scope name too long");
        return NULL;
    }
    struct asm_scope *s = calloc(1, sizeof *s);
    if (!s) {
        asm_report(c, f, REP_FATAL, "Memory allocation failed");
        return NULL;
    }
    snprintf(s->name, sizeof s->name, "%s", name);
    s->open = 1;
    s->parent = c->scope_cur;
    s->next = c->scopes;
    c->scopes = s;
    c->scope_cur = s;
    return s;
}

void asm_struct_init(struct asm_ctx *c) {
    scope_create(c, NULL, "_ROOT_");
}

void asm_struct_clear(struct asm_ctx *c) {
    while (c->scopes) {
        struct asm_scope *s = c->scopes;
        c->scopes = s->next;
        while (s->assigns) {
            struct asm_assign *a = s->assigns;
            s->assigns = a->next;
            free(a);
        }
        free(s);
    }
    c->scope_cur = NULL;
    asm_sym_clear(&c->structs, free);
    c->struct_open = NULL;
}

int asm_scope_enter(struct asm_ctx *c, const struct asm_file *f, const char *name) {
    return scope_create(c, f, name) ? 0 : -1;
}

static void scope_close(struct asm_ctx *c, struct asm_scope *s) {
    s->open = 0;
    while (c->scope_cur && !c->scope_cur->open)
        c->scope_cur = c->scope_cur->parent;
}

int asm_scope_leave(struct asm_ctx *c, const struct asm_file *f, const char *name) {
    struct asm_scope *s = scope_find(c, name);
    if (!s) {
        asm_report(c, f, REP_ERROR, "Scope name undefined");
        return -1;
    }
    if (!s->open) {
        asm_report(c, f, REP_ERROR, "Scope is not open");
        return -1;
    }
    scope_close(c, s);
    return 0;
}

int asm_scope_using(struct asm_ctx *c, const struct asm_file *f, const char *name) {
    struct asm_scope *s = scope_find(c, name);
    if (!s) {
        asm_report(c, f, REP_ERROR, "Scope name undefined");
        return -1;
    }
    if (s->open) {
        asm_report(c, f, REP_ERROR, "Scope is already open");
        return -1;
    }
    s->open = 1;
    c->scope_cur = s;
    return 0;
}

int asm_struct_new(struct asm_ctx *c, const struct asm_file *f, const char *name) {
    if (c->struct_open) {
        asm_report(c, f, REP_ERROR, "Structure can not be nested");
        return -1;
    }
    if (!asm_check_name(c, f, name))
        return -1;
    if (strlen(name) >= ASM_TOKEN_MAX) {
        asm_report(c, f, REP_ERROR, "Structure name too long");
        return -1;
    }
    struct asm_struct *s = calloc(1, sizeof *s);
    if (!s || asm_sym_put(&c->structs, name, s)) {
        free(s);
        asm_report(c, f, REP_FATAL, "Memory allocation failed");
        return -1;
    }
    c->struct_open = s;
    return 0;
}

int asm_struct_end(struct asm_ctx *c, const struct asm_file *f) {
    if (!c->struct_open) {
        asm_report(c, f, REP_ERROR, "Structure .struct/.ends mismatch");
        return -1;
    }
    int empty = !c->struct_open->nelem;
    c->struct_open = NULL;
    if (empty) {
        asm_report(c, f, REP_ERROR, "Structure must have at least 1 element");
        return -1;
    }
    return 0;
}

int asm_struct_add(struct asm_ctx *c, const struct asm_file *f, const char *name, unsigned size) {
    struct asm_struct *s = c->struct_open;
    if (!s) {
        asm_report(c, f, REP_ERROR, "Can not add element - missing .struct");
        return -1;
    }
    if (strlen(name) >= ASM_TOKEN_MAX) {
        asm_report(c, f, REP_ERROR, "Element name too long");
        return -1;
    }
    if (asm_token_type(name) != TOK_UNRESERVED) {
        asm_report(c, f, REP_ERROR, "Illegal use of reserved word '%s'", name);
        return 0;
    }
    if (s->nelem == STRUCT_MAX_ELEM) {
        asm_report(c, f, REP_ERROR, "Max element count (%d) exceeded", STRUCT_MAX_ELEM);
        return -1;
    }
    for (int i = 0; i < s->nelem; i++) {
        if (!strcmp(name, s->elem[i])) {
            asm_report(c, f, REP_ERROR, "Duplicate element name");
            return -1;
        }
    }
    snprintf(s->elem[s->nelem], ASM_TOKEN_MAX, "%s", name);
    s->offset[s->nelem] = s->total;
    s->size[s->nelem] = size;
    s->total += size;
    s->nelem++;
    return 0;
}

/* The register name for `size` bytes at register-file byte `off`. */
static int regname(struct asm_ctx *c, const struct asm_file *f, unsigned elem, char *out,
                   unsigned off, unsigned size) {
    if (off % 4 + size > 4) {
        asm_report(c, f, REP_ERROR, "Register alignment error on element %u", elem);
        return -1;
    }
    if (size == 4)
        snprintf(out, REGNAME_MAX, "R%u", off / 4);
    else
        snprintf(out, REGNAME_MAX, size == 2 ? "R%u.w%u" : "R%u.b%u", off / 4, off % 4);
    return 0;
}

int asm_struct_assign(struct asm_ctx *c, const struct asm_file *f, const char *sname,
                      const char *rs_text, const char *re_text, const char *name) {
    struct asm_arg rs, re;
    char tmp[REGNAME_MAX];
    if (c->struct_open) {
        asm_report(c, f, REP_ERROR, "Cannot assign while defining a structure");
        return -1;
    }
    if (!c->scope_cur) {
        asm_report(c, f, REP_ERROR, "Cannot assign outside of a scope");
        return -1;
    }
    int check_end = strcmp(re_text, "*") != 0;
    if (!asm_get_reg(c, f, 2, rs_text, &rs, 0, 0))
        return -1;
    if (check_end && !asm_get_reg(c, f, 3, re_text, &re, 0, 0))
        return -1;
    struct asm_struct *st = asm_sym_get(&c->structs, sname, NULL);
    if (!st) {
        asm_report(c, f, REP_ERROR, "Structure '%s' not defined", sname);
        return -1;
    }
    unsigned start = rs.value * 4 + pru_sel_shift(rs.field) / 8;
    if (check_end) {
        unsigned end = re.value * 4 + (pru_sel_shift(re.field) + pru_sel_width(re.field)) / 8;
        unsigned want = start + st->total;
        if (want != end) {
            unsigned sz = !(want & 3) ? 4 : !(want & 1) ? 2 : 1;
            regname(c, f, 0, tmp, want - sz, sz);
            asm_report(c, f, REP_ERROR, "Range error, parameter 3 should be '%s'", tmp);
            return -1;
        }
    }
    unsigned off = start;
    for (int i = 0; i < st->nelem; i++) {
        if (regname(c, f, (unsigned)i + 1, tmp, off, st->size[i]) < 0)
            return -1;
        off += st->size[i];
    }
    if (!asm_check_name(c, f, name))
        return -1;
    if (strlen(name) >= ASM_TOKEN_MAX) {
        asm_report(c, f, REP_ERROR, "Structure name too long");
        return -1;
    }
    struct asm_assign *a = calloc(1, sizeof *a);
    if (!a) {
        asm_report(c, f, REP_FATAL, "Memory allocation failed");
        return -1;
    }
    snprintf(a->name, sizeof a->name, "%s", name);
    a->layout = *st;
    off = start;
    for (int i = 0; i < st->nelem; i++) {
        regname(c, f, (unsigned)i + 1, a->reg[i], off, st->size[i]);
        off += st->size[i];
    }
    snprintf(a->base, sizeof a->base, "%s", a->reg[0]);
    a->next = c->scope_cur->assigns;
    c->scope_cur->assigns = a;
    return 0;
}

/* Register replacing "Name" or "Name.field", or NULL. */
static const char *assigned_reg(struct asm_ctx *c, const char *cand) {
    char name[ASM_TOKEN_MAX];
    snprintf(name, sizeof name, "%s", cand);
    char *dot = strchr(name, '.');
    if (dot)
        *dot++ = 0;
    struct asm_assign *a = assign_find(c, name);
    if (!a)
        return NULL;
    if (!dot)
        return a->base;
    for (int i = 0; i < a->layout.nelem; i++)
        if (!strcmp(dot, a->layout.elem[i]))
            return a->reg[i];
    return NULL;
}

/* Size or offset of a .bN/.wN part of a field of `size` bytes at `offset`. */
static int subfield(const char *ext, unsigned size, unsigned offset, int want_size, uint32_t *out) {
    if (strlen(ext) > 2)
        return -1;
    int kind = toupper((unsigned char)ext[0]);
    unsigned v = (unsigned)(ext[1] - '0'); /* pasm reads one digit, unchecked */
    unsigned w = kind == 'B' ? 1 : kind == 'W' ? 2 : 0;
    if (!w || v + w > size)
        return -1;
    *out = want_size ? w : offset + v;
    return 0;
}

static int layout_value(const struct asm_struct *s, const char *field, const char *ext,
                        int want_size, uint32_t *out) {
    if (!field[0]) {
        *out = want_size ? s->total : 0;
        return 0;
    }
    for (int i = 0; i < s->nelem; i++) {
        if (!strcmp(field, s->elem[i])) {
            if (ext)
                return subfield(ext, s->size[i], s->offset[i], want_size, out);
            *out = want_size ? s->size[i] : s->offset[i];
            return 0;
        }
    }
    return -1;
}

/* SIZE()/OFFSET() of an assignment, a structure type, or (SIZE) a register. */
static int size_offset(struct asm_ctx *c, const struct asm_file *f, const char *arg, int want_size,
                       uint32_t *out) {
    char name[ASM_TOKEN_MAX], field[ASM_TOKEN_MAX] = "";
    char *ext = NULL;
    snprintf(name, sizeof name, "%s", arg);
    char *dot = strchr(name, '.');
    if (dot) {
        *dot = 0;
        snprintf(field, sizeof field, "%s", dot + 1);
        char *d2 = strchr(field, '.');
        if (d2) {
            *d2 = 0;
            ext = d2 + 1;
        }
    }
    struct asm_assign *a = assign_find(c, name);
    struct asm_struct *s = asm_sym_get(&c->structs, name, NULL);
    int rc = a   ? layout_value(&a->layout, field, ext, want_size, out)
             : s ? layout_value(s, field, ext, want_size, out)
                 : -1;
    if (rc == 0)
        return 0;

    /* pasm also accepts a register here, giving its field width (for
     * OFFSET too). Its parser reports a bad register as usual. */
    struct asm_arg r;
    if (asm_get_reg(c, f, 1, arg, &r, 0, 0)) {
        *out = pru_sel_width(r.field) / 8;
        return 0;
    }
    return -1;
}

static int put(char *dst, size_t *n, char ch) {
    if (*n >= 2 * ASM_TOKEN_MAX - 1)
        return -1;
    dst[(*n)++] = ch;
    return 0;
}

/* SIZE(x)/OFFSET(x) at src[*i] (just after the keyword); appends " value ". */
static int size_offset_term(struct asm_ctx *c, const struct asm_file *f, const char *src, size_t *i,
                            int want_size, char *dst, size_t *n) {
    char name[ASM_TOKEN_MAX];
    while (src[*i] == ' ' || src[*i] == '\t')
        (*i)++;
    if (src[*i] != '(') {
        asm_report(c, f, REP_ERROR, "Missing '(' on SIZE/OFFSET");
        return -1;
    }
    (*i)++;
    while (src[*i] == ' ' || src[*i] == '\t')
        (*i)++;
    size_t k = 0;
    while (k < ASM_TOKEN_MAX - 1 && (asm_label_char(src[*i + k], 0) || src[*i + k] == '.')) {
        name[k] = src[*i + k];
        k++;
    }
    if (!k) {
        asm_report(c, f, REP_ERROR, "Malformed SIZE/OFFSET operand");
        return -1;
    }
    name[k] = 0;
    *i += k;
    while (src[*i] == ' ' || src[*i] == '\t')
        (*i)++;
    if (src[*i] != ')') {
        asm_report(c, f, REP_ERROR, "Missing ')' on SIZE/OFFSET");
        return -1;
    }
    (*i)++;
    uint32_t v;
    if (size_offset(c, f, name, want_size, &v) < 0) {
        asm_report(c, f, REP_ERROR, "Illegal SIZE/OFFSET operand '%s'", name);
        return -1;
    }
    char num[24];
    snprintf(num, sizeof num, " %d ", (int)v);
    for (char *p = num; *p; p++)
        if (put(dst, n, *p))
            return -1;
    return 0;
}

int asm_struct_param(struct asm_ctx *c, const struct asm_file *f, int idx, char *term) {
    char out[2 * ASM_TOKEN_MAX];
    size_t n = 0, i = 0;
    (void)idx;
    while (term[i]) {
        if (term[i] >= '0' && term[i] <= '9') {
            /* a number, letters and all */
            do {
                if (put(out, &n, term[i++]))
                    return -1;
            } while (asm_label_char(term[i], 0));
            continue;
        }
        if (!asm_label_char(term[i], 1)) {
            if (put(out, &n, term[i++]))
                return -1;
            continue;
        }
        /* A candidate name: identifier with at most one '.' part. */
        char cand[ASM_TOKEN_MAX];
        size_t k = 1;
        int dots = 0;
        cand[0] = term[i];
        for (; k < ASM_TOKEN_MAX - 1; k++) {
            char ch = term[i + k];
            if (ch == '.') {
                if (dots++)
                    break;
            } else if (!asm_label_char(ch, 0)) {
                break;
            }
            cand[k] = ch;
        }
        cand[k] = 0;
        if (!strcmp(cand, "SIZE") || !strcmp(cand, "OFFSET")) {
            i += k;
            if (size_offset_term(c, f, term, &i, cand[0] == 'S', out, &n))
                return -1;
            continue;
        }
        const char *rep = assigned_reg(c, cand);
        if (!rep)
            rep = cand;
        for (const char *p = rep; *p; p++)
            if (put(out, &n, *p))
                return -1;
        i += k;
        /* Further '.' parts are field selectors on the result. */
        if (term[i] == '.') {
            do {
                if (put(out, &n, term[i++]))
                    return -1;
            } while (asm_label_char(term[i], 0) || term[i] == '.');
        }
    }
    out[n] = 0;
    if (n >= ASM_TOKEN_MAX)
        return -1;
    memcpy(term, out, n + 1);
    return 0;
}
