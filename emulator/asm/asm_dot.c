/*
 * asm_dot.c - dot commands: .origin, .entrypoint, .setcallreg, .codeword,
 * the legacy .main/.end/.proc/.ret, and the front ends of the structure,
 * scope and macro commands.
 */
#include "asm_ctx.h"
#include "pru_isa.h"

#include <ctype.h>
#include <stdio.h>
#include <string.h>
#include <strings.h>

static const char *const dot_commands[] = {
    ".main",  ".end",   ".proc",  ".ret",    ".origin", ".entrypoint", ".struct",
    ".ends",  ".u32",   ".u16",   ".u8",     ".assign", ".setcallreg", ".enter",
    ".leave", ".using", ".macro", ".mparam", ".endm",   ".codeword",
};

int asm_is_dot_command(const char *word) {
    for (size_t i = 0; i < sizeof dot_commands / sizeof dot_commands[0]; i++)
        if (!strcasecmp(word, dot_commands[i]))
            return 1;
    return 0;
}

static int operands(struct asm_ctx *c, const struct asm_file *f, int nterms, int want) {
    if (nterms == want + 1)
        return 1;
    if (want == 0)
        asm_report(c, f, REP_ERROR, "Expected no operands");
    else if (want == 1)
        asm_report(c, f, REP_ERROR, "Expected 1 operand");
    else
        asm_report(c, f, REP_ERROR, "Expected %d operands", want);
    return 0;
}

/* .main "name": only checks the name against the source file's. */
static int dot_main(struct asm_ctx *c, const struct asm_file *f, const char *arg) {
    const char *p = arg, *n = f->name;
    int quote = 0;
    if (*p == '"') {
        quote++;
        p++;
    }
    while (*p && *p != '"') {
        if (toupper((unsigned char)*p) != toupper((unsigned char)*n))
            goto mismatch;
        p++;
        n++;
    }
    if (*n && *n != '.')
        goto mismatch;
    if (*p == '"') {
        quote--;
        p++;
    }
    if (*p) {
        asm_report(c, f, REP_ERROR, "Trailing characters on name");
        return -1;
    }
    if (quote) {
        asm_report(c, f, REP_ERROR, "Unbalanced quotes on name");
        return -1;
    }
    return 0;
mismatch:
    asm_report(c, f, REP_WARN1, ".main name '%s' doesn't match '%s'", arg, f->name);
    return 0;
}

static int dot_value(struct asm_ctx *c, const struct asm_file *f, const char *arg, const char *what,
                     int *out) {
    uint32_t v;
    if (asm_expr(c, f, arg, &v) < 0) {
        asm_report(c, f, REP_ERROR, "Error in processing %s value", what);
        return -1;
    }
    *out = (int)v;
    return 0;
}

static int dot_origin(struct asm_ctx *c, const struct asm_file *f, const char *arg) {
    int v;
    if (dot_value(c, f, arg, ".origin", &v))
        return -1;
    if (v < c->code_offset) {
        asm_report(c, f, REP_ERROR, ".origin value is less than current offset");
        return -1;
    }
    if (v > ASM_MAX_WORDS) {
        /* pasm would index past its image; treat like running out of room. */
        asm_report(c, f, REP_FATAL, "Max program size exceeded");
        return -1;
    }
    if (c->code_offset >= 0)
        asm_report(c, f, REP_WARN1, "Resetting .origin value after use");
    if (c->entry_point < 0)
        c->entry_point = v;
    c->code_offset = v;
    return 0;
}

static int dot_setcallreg(struct asm_ctx *c, const struct asm_file *f, const char *arg) {
    struct asm_arg r;
    if (c->pass == 1 && c->retreg_set) {
        asm_report(c, f, REP_ERROR, ".setcallreg redefinition");
        return -1;
    }
    if (c->code_offset >= 0) {
        asm_report(c, f, REP_ERROR, "Can not use .setcallreg after code generation");
        return -1;
    }
    if (!asm_get_reg(c, f, 1, arg, &r, 0, 0))
        return -1;
    if ((r.field == PRU_SEL_W0 || r.field == PRU_SEL_W1 || r.field == PRU_SEL_W2) && r.value < 31) {
        c->retreg = r.value;
        c->retfield = r.field;
        c->retreg_set = 1;
        return 0;
    }
    asm_report(c, f, REP_ERROR, "Register field must be r0 to r30 and 16 bits wide");
    return -1;
}

int asm_dot_command(struct asm_ctx *c, struct asm_file *f, int nterms, char terms[][ASM_TOKEN_MAX],
                    char *out, int max) {
    const char *cmd = terms[0];
    if (!asm_is_dot_command(cmd)) {
        asm_report(c, f, REP_ERROR, "Unrecognized dot command");
        return -1;
    }
    if (!strcasecmp(cmd, ".main"))
        return operands(c, f, nterms, 1) ? dot_main(c, f, terms[1]) : -1;
    if (!strcasecmp(cmd, ".end"))
        return operands(c, f, nterms, 0) ? 0 : -1;
    if (!strcasecmp(cmd, ".proc")) {
        if (!operands(c, f, nterms, 1))
            return -1;
        return snprintf(out, (size_t)max, ".%s:", terms[1]);
    }
    if (!strcasecmp(cmd, ".ret")) {
        if (!operands(c, f, nterms, 0))
            return -1;
        if (c->retreg_set) {
            asm_report(c, f, REP_ERROR, ".ret incompatible with .setcallreg, use ret");
            return -1;
        }
        if (c->core > CORE_V1) {
            asm_report(c, f, REP_ERROR, ".ret illegal with specified core version, use ret");
            return -1;
        }
        return snprintf(out, (size_t)max, "jmp     r30.w0");
    }
    if (!strcasecmp(cmd, ".origin"))
        return operands(c, f, nterms, 1) ? dot_origin(c, f, terms[1]) : -1;
    if (!strcasecmp(cmd, ".entrypoint")) {
        int v;
        if (!operands(c, f, nterms, 1) || dot_value(c, f, terms[1], ".entrypoint", &v))
            return -1;
        if (c->have_entry) {
            asm_report(c, f, REP_ERROR, "Multiple .entrypoint declarations");
            return -1;
        }
        c->entry_point = v;
        c->have_entry = 1;
        return 0;
    }
    if (!strcasecmp(cmd, ".struct"))
        return operands(c, f, nterms, 1) ? asm_struct_new(c, f, terms[1]) : -1;
    if (!strcasecmp(cmd, ".ends"))
        return operands(c, f, nterms, 0) ? asm_struct_end(c, f) : -1;
    if (!strcasecmp(cmd, ".u32") || !strcasecmp(cmd, ".u16") || !strcasecmp(cmd, ".u8")) {
        unsigned size = cmd[2] == '3' ? 4 : cmd[2] == '1' ? 2 : 1;
        return operands(c, f, nterms, 1) ? asm_struct_add(c, f, terms[1], size) : -1;
    }
    if (!strcasecmp(cmd, ".assign")) {
        if (!operands(c, f, nterms, 4))
            return -1;
        return asm_struct_assign(c, f, terms[1], terms[2], terms[3], terms[4]);
    }
    if (!strcasecmp(cmd, ".setcallreg"))
        return operands(c, f, nterms, 1) ? dot_setcallreg(c, f, terms[1]) : -1;
    if (!strcasecmp(cmd, ".enter"))
        return operands(c, f, nterms, 1) ? asm_scope_enter(c, f, terms[1]) : -1;
    if (!strcasecmp(cmd, ".leave"))
        return operands(c, f, nterms, 1) ? asm_scope_leave(c, f, terms[1]) : -1;
    if (!strcasecmp(cmd, ".using"))
        return operands(c, f, nterms, 1) ? asm_scope_using(c, f, terms[1]) : -1;
    if (!strcasecmp(cmd, ".macro"))
        return operands(c, f, nterms, 1) ? asm_macro_define(c, f, terms[1]) : -1;
    if (!strcasecmp(cmd, ".mparam") || !strcasecmp(cmd, ".endm")) {
        asm_report(c, f, REP_ERROR, "%s can not be used outside of macro", cmd);
        return -1;
    }
    /* .codeword */
    int v;
    if (!operands(c, f, nterms, 1) || dot_value(c, f, terms[1], ".codeword", &v))
        return -1;
    asm_gen(c, f, nterms, terms, (uint32_t)v);
    return 0;
}
