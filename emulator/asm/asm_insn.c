/*
 * asm_insn.c - instruction statements: operand forms, pasm's checks and
 * messages, pseudo-instructions (MOV, CALL, RET, WBS/WBC, ZERO/FILL, MVIx
 * without pointers) and the words they become, via pru_encode().
 */
#include "asm_ctx.h"
#include "pru_isa.h"

#include <string.h>

typedef char term_t[ASM_TOKEN_MAX];

/* One statement being assembled. */
struct stmt {
    struct asm_ctx *c;
    struct asm_file *f;
    int n; /* terms, mnemonic included */
    term_t *t;
};

static int fail(struct stmt *s, const char *msg) {
    asm_report(s->c, s->f, REP_ERROR, "%s", msg);
    return 0;
}

static void emit(struct stmt *s, const struct pru_insn *in) {
    asm_gen(s->c, s->f, s->n, s->t, pru_encode(in));
}

static int is_reg(const char *term) {
    return (asm_token_type(term) & TOK_REG_BASE) != 0;
}

/* A register or an immediate in lo..hi, as pasm decides between them. */
static int reg_or_imm(struct stmt *s, int num, struct asm_arg *a, uint32_t lo, uint32_t hi) {
    if (is_reg(s->t[num]))
        return asm_get_reg(s->c, s->f, num, s->t[num], a, 0, 0);
    return asm_get_imm(s->c, s->f, num, s->t[num], a, lo, hi);
}

/* Fill op2 (register field or imm) of an instruction. */
static void set_op2(struct pru_insn *in, const struct asm_arg *a) {
    if (a->type == ARG_REG) {
        in->io = 0;
        in->rs2 = (uint8_t)a->value;
        in->rs2sel = (uint8_t)a->field;
    } else {
        in->io = 1;
        in->imm = (uint16_t)a->value;
    }
}

static void emit_alu(struct stmt *s, int op, const struct asm_arg *rd, const struct asm_arg *rs1,
                     const struct asm_arg *op2) {
    struct pru_insn in = {0};
    in.op = (uint8_t)op;
    in.rd = (uint8_t)rd->value;
    in.rdsel = (uint8_t)rd->field;
    in.rs1 = (uint8_t)rs1->value;
    in.rs1sel = (uint8_t)rs1->field;
    set_op2(&in, op2);
    emit(s, &in);
}

/* ADD..MAX, NOT, LMBD, NOPn: Rd, Rs1, OP(255) (NOT also Rd, Rs1). */
static int alu(struct stmt *s, int op) {
    struct asm_arg a[3];
    if (pru_optable[op].form == PRU_FORM_NOT) {
        if (s->n != 3 && s->n != 4)
            return fail(s, "Expected 2 or 3 operands on NOT");
    } else if (s->n != 4) {
        return fail(s, "Expected 3 operands");
    }
    if (!asm_get_reg(s->c, s->f, 1, s->t[1], &a[0], 0, 0) ||
        !asm_get_reg(s->c, s->f, 2, s->t[2], &a[1], 0, 0))
        return 0;
    if (s->n == 4) {
        if (!reg_or_imm(s, 3, &a[2], 0, 255))
            return 0;
    } else {
        a[2] = (struct asm_arg){.type = ARG_IMM, .value = 0};
    }
    emit_alu(s, op, &a[0], &a[1], &a[2]);
    return 1;
}

/* CLR/SET: Rd, Rs, OP(255) | Rd, Rs.tN | Rd, OP(31) | Rd.tN */
static int clr_set(struct stmt *s, int op) {
    struct asm_arg a[3];
    if (s->n < 2 || s->n > 4)
        return fail(s, "Expected 1 to 3 operands");
    if (s->n == 4)
        return alu(s, op);
    if (s->n == 2) {
        if (!asm_get_reg(s->c, s->f, 1, s->t[1], &a[0], 1, 0))
            return 0;
        if (a[0].type != ARG_REGBIT)
            return fail(s, "Single operand mode must specify .T field");
        a[0].type = ARG_REG;
        a[1] = a[0];
        a[2] = (struct asm_arg){.type = ARG_IMM, .value = a[0].bit};
    } else {
        if (!asm_get_reg(s->c, s->f, 1, s->t[1], &a[0], 0, 0))
            return 0;
        if (is_reg(s->t[2])) {
            if (!asm_get_reg(s->c, s->f, 2, s->t[2], &a[1], 1, 0))
                return 0;
        } else if (!asm_get_imm(s->c, s->f, 2, s->t[2], &a[1], 0, 31)) {
            return 0;
        }
        if (a[1].type == ARG_REGBIT) {
            a[1].type = ARG_REG;
            a[2] = (struct asm_arg){.type = ARG_IMM, .value = a[1].bit};
        } else {
            a[2] = a[1];
            a[1] = a[0];
        }
    }
    emit_alu(s, op, &a[0], &a[1], &a[2]);
    return 1;
}

static void emit_ldi(struct stmt *s, unsigned reg, unsigned field, uint32_t value) {
    struct pru_insn in = {0};
    in.op = PRU_OP_LDI;
    in.rd = (uint8_t)reg;
    in.rdsel = (uint8_t)field;
    in.imm = (uint16_t)value;
    emit(s, &in);
}

static int ldi(struct stmt *s, int op) {
    struct asm_arg rd, v;
    if (s->n != 3)
        return fail(s, "Expected 2 operands");
    if (!asm_get_reg(s->c, s->f, 1, s->t[1], &rd, 0, 0) ||
        !asm_get_imm(s->c, s->f, 2, s->t[2], &v, 0, 65535))
        return 0;
    (void)op;
    emit_ldi(s, rd.value, rd.field, v.value);
    return 1;
}

/* MOV: a register source is AND Rd, Rs, Rs; an immediate becomes LDI, split
 * into two (upper half first) for a 32-bit destination above 0xFFFF. */
static int mov(struct stmt *s, int op) {
    struct asm_arg rd, v;
    (void)op;
    if (s->n != 3)
        return fail(s, "Expected 2 operands");
    if (is_reg(s->t[2])) {
        if (!asm_get_reg(s->c, s->f, 1, s->t[1], &rd, 0, 0) ||
            !asm_get_reg(s->c, s->f, 2, s->t[2], &v, 0, 0))
            return 0;
        emit_alu(s, PRU_OP_AND, &rd, &v, &v);
        return 1;
    }
    if (!asm_get_reg(s->c, s->f, 1, s->t[1], &rd, 0, 0))
        return 0;
    uint32_t max = rd.field <= PRU_SEL_B3 ? 255u : rd.field <= PRU_SEL_W2 ? 65535u : 0xFFFFFFFFu;
    if (!asm_get_imm(s->c, s->f, 2, s->t[2], &v, 0, max))
        return 0;
    if (rd.field == PRU_SEL_R && v.value > 0xFFFF) {
        emit_ldi(s, rd.value, PRU_SEL_W2, v.value >> 16);
        rd.field = PRU_SEL_W0;
        v.value &= 0xFFFF;
    }
    emit_ldi(s, rd.value, rd.field, v.value);
    return 1;
}

static int scan(struct stmt *s, int op) {
    struct asm_arg rd, op2;
    if (s->n != 3)
        return fail(s, "Expected 2 operands");
    if (!asm_get_reg(s->c, s->f, 1, s->t[1], &rd, 0, 0))
        return 0;
    if (rd.field != PRU_SEL_R)
        return fail(s, "Register fields not allowed on operand 1");
    if (!reg_or_imm(s, 2, &op2, 0, 255))
        return 0;
    /* SCAN has the ALU layout with the register as both rd and rs1 */
    emit_alu(s, op, &rd, &rd, &op2);
    return 1;
}

/* A "*&addr" MVI operand: a register field from a register-file address. */
static int mvi_addr(struct stmt *s, int num, struct asm_arg *a, unsigned size) {
    if (!asm_get_imm(s->c, s->f, num, s->t[num] + 1, a, 0, 127))
        return 0;
    uint32_t addr = a->value, off = addr & 3;
    if (addr + size > 128) {
        asm_report(s->c, s->f, REP_ERROR, "Operand %d, field extends past register file", num);
        return 0;
    }
    if ((size == 2 && off == 3) || (size == 4 && off != 0)) {
        asm_report(s->c, s->f, REP_ERROR, "Operand %d, this field alignment not supported", num);
        return 0;
    }
    a->type = ARG_REG;
    a->value = addr / 4;
    a->field = asm_field_at(s->c, off, size);
    return 1;
}

/* MVI operand with pointer syntax; mode gets enum pru_mvi_mode. */
static int mvi_operand(struct stmt *s, int num, struct asm_arg *a, unsigned size, unsigned *mode) {
    unsigned t = asm_token_type(s->t[num]);
    if (t == (TOK_REG_PTR | TOK_REG_ADDR)) {
        *mode = PRU_MVI_DIRECT;
        return mvi_addr(s, num, a, size);
    }
    int skip = 0;
    char term = 0;
    *mode = PRU_MVI_DIRECT;
    if ((t & TOK_REG_PTR) && !(t & TOK_REG_ADDR)) {
        *mode = PRU_MVI_IND;
        skip = 1;
        if (t & TOK_REG_POSTINC) {
            *mode = PRU_MVI_POSTINC;
            term = '+';
        } else if (t & TOK_REG_PREDEC) {
            *mode = PRU_MVI_PREDEC;
            skip = 3;
        }
    }
    return asm_get_reg(s->c, s->f, num, s->t[num] + skip, a, 0, term);
}

static int mvi(struct stmt *s, int op) {
    unsigned size = op == PRU_OP_MVIB ? 1 : op == PRU_OP_MVIW ? 2 : 4;
    struct asm_arg a[2];
    if (s->n == 4)
        return fail(s, "3 operand mode not supported on this core");
    if (s->n != 3)
        return fail(s, "Expected 2 operands");

    /* Without a pointer this is a move: AND with the source cut to size. */
    int plain = 1;
    for (int i = 1; i <= 2 && plain; i++) {
        unsigned t = asm_token_type(s->t[i]);
        if (t == (TOK_REG_PTR | TOK_REG_ADDR)) {
            if (!mvi_addr(s, i, &a[i - 1], size))
                return 0;
        } else if (t == TOK_REG_BASE) {
            if (!asm_get_reg(s->c, s->f, i, s->t[i], &a[i - 1], 0, 0))
                return 0;
        } else {
            plain = 0;
        }
    }
    if (plain) {
        if (size == 1 && (a[1].field == PRU_SEL_W0 || a[1].field == PRU_SEL_R))
            a[1].field = PRU_SEL_B0;
        else if (size == 1 && a[1].field == PRU_SEL_W2)
            a[1].field = PRU_SEL_B2;
        else if (size == 2 && a[1].field == PRU_SEL_R)
            a[1].field = PRU_SEL_W0;
        emit_alu(s, PRU_OP_AND, &a[0], &a[1], &a[1]);
        return 1;
    }

    if (s->c->core < CORE_V2)
        return fail(s, "This form of MVIx illegal with specified core version");
    unsigned dmode, smode;
    if (!mvi_operand(s, 1, &a[0], size, &dmode) || !mvi_operand(s, 2, &a[1], size, &smode))
        return 0;
    if ((dmode && (a[0].value != 1 || a[0].field > PRU_SEL_B3)) ||
        (smode && (a[1].value != 1 || a[1].field > PRU_SEL_B3)))
        return fail(s, "RegFile pointers must be R1.b0 through R1.b3");
    if (!dmode && !smode)
        return fail(s, "No indirection specified (use MOV)");
    struct pru_insn in = {0};
    in.op = (uint8_t)op;
    in.rd = (uint8_t)a[0].value;
    in.rdsel = (uint8_t)a[0].field;
    in.rs1 = (uint8_t)a[1].value;
    in.rs1sel = (uint8_t)a[1].field;
    in.mvi_dmode = (uint8_t)dmode;
    in.mvi_smode = (uint8_t)smode;
    in.mvi_size = (uint8_t)(size / 2);
    emit(s, &in);
    return 1;
}

/* HALT; the V0-only rows (LFC, STC) never get here (core gating). */
static int no_operands(struct stmt *s, int op) {
    if (s->n != 1)
        return fail(s, "Expected no operands");
    struct pru_insn in = {.op = (uint8_t)op};
    emit(s, &in);
    return 1;
}

static int slp(struct stmt *s, int op) {
    struct asm_arg a;
    if (s->n != 2)
        return fail(s, "Expected 1 operand");
    if (!asm_get_imm(s->c, s->f, 1, s->t[1], &a, 0, 1))
        return 0;
    struct pru_insn in = {.op = (uint8_t)op, .flag = (uint8_t)a.value};
    emit(s, &in);
    if (s->c->core < CORE_V3)
        asm_gen(s->c, s->f, s->n, s->t, 0x10000000u); /* pre-V3 cores need a trailing no-op */
    return 1;
}

/* Length operand of burst and XFR: bn or an immediate count 1..124. */
static int length_code(struct stmt *s, int num, unsigned *len) {
    struct asm_arg a;
    if (is_reg(s->t[num])) {
        if (!asm_get_r0byte(s->c, s->f, num, s->t[num], &a))
            return 0;
        *len = 124 + a.value;
    } else {
        if (!asm_get_imm(s->c, s->f, num, s->t[num], &a, 1, 124))
            return 0;
        *len = a.value - 1;
    }
    return 1;
}

/* First operand of burst/XFR: a register (start byte from its field) or a
 * register-file byte address. */
static void set_rx(struct stmt *s, struct pru_insn *in, const struct asm_arg *a) {
    if (a->type == ARG_IMM) {
        in->rx = (uint8_t)((a->value >> 2) & 31);
        in->rxbyte = (uint8_t)(a->value & 3);
    } else {
        in->rx = (uint8_t)a->value;
        in->rxbyte = (uint8_t)asm_field_start(s->c, a->field);
    }
}

static int burst(struct stmt *s, int op) {
    struct asm_arg rx, base, off;
    unsigned len;
    if (s->n != 5)
        return fail(s, "Expected 4 operands");
    if (!reg_or_imm(s, 1, &rx, 0, 127))
        return 0;
    if (pru_optable[op].form == PRU_FORM_BURST_BO) {
        if (!asm_get_reg(s->c, s->f, 2, s->t[2], &base, 0, 0))
            return 0;
        if (base.field != PRU_SEL_R)
            return fail(s, "Register fields not allowed on operand 2");
    } else if (!asm_get_const(s->c, s->f, 2, s->t[2], &base)) {
        return 0;
    }
    if (!reg_or_imm(s, 3, &off, 0, 255) || !length_code(s, 4, &len))
        return 0;
    struct pru_insn in = {0};
    in.op = (uint8_t)op;
    set_rx(s, &in, &rx);
    in.base = (uint8_t)base.value;
    set_op2(&in, &off);
    in.len = (uint8_t)len;
    emit(s, &in);
    return 1;
}

static int xfr(struct stmt *s, int op) {
    struct asm_arg dev, rx;
    unsigned len;
    if (s->n != 4)
        return fail(s, "Expected 3 operands");
    if (!asm_get_imm(s->c, s->f, 1, s->t[1], &dev, 0, 253))
        return 0;
    if (is_reg(s->t[2])) {
        if (!asm_get_reg(s->c, s->f, 2, s->t[2], &rx, 0, 0))
            return 0;
        if (rx.value == 31)
            return fail(s, "Operand 2 R31 is illegal");
    } else if (!asm_get_imm(s->c, s->f, 2, s->t[2], &rx, 0, 123)) {
        return 0;
    }
    if (!length_code(s, 3, &len))
        return 0;
    struct pru_insn in = {0};
    in.op = (uint8_t)op;
    in.dev = (uint8_t)dev.value;
    set_rx(s, &in, &rx);
    in.len = (uint8_t)len;
    emit(s, &in);
    return 1;
}

/* ZERO before V2: clear the bytes with LDI #0 words, widest field first. */
static void zero_by_ldi(struct stmt *s, uint32_t addr, uint32_t len) {
    while (len) {
        unsigned off = addr & 3;
        unsigned size = off == 0 && len >= 4 ? 4 : off < 3 && len >= 2 ? 2 : 1;
        emit_ldi(s, addr / 4, asm_field_at(s->c, off, size), 0);
        addr += size;
        len -= size;
    }
}

/* ZERO/FILL start, length: XIN from device 255/254 on V2+. */
static int zero_fill(struct stmt *s, int op) {
    int is_zero = op == PRU_OP_ZERO;
    struct asm_arg start, len;
    if (s->n != 3)
        return fail(s, "Expected 2 operands");
    if (!asm_get_imm(s->c, s->f, 1, s->t[1], &start, 0, 123) ||
        !asm_get_imm(s->c, s->f, 2, s->t[2], &len, 0, 124))
        return 0;
    if (start.value + len.value > 124)
        return fail(s, is_zero ? "Clear length exceeds register file length"
                               : "Length exceeds register file length");
    if (!len.value)
        return fail(s, is_zero ? "Zero length clear" : "Zero length fill");
    /* ZERO is one XIN word where the core has XIN, else LDI words */
    if (is_zero && s->c->core < pru_optable[PRU_OP_XIN].min_core) {
        zero_by_ldi(s, start.value, len.value);
        return 1;
    }
    struct pru_insn in = {0};
    in.op = PRU_OP_XIN;
    in.dev = is_zero ? 255 : 254;
    in.rx = (uint8_t)((start.value >> 2) & 31);
    in.rxbyte = (uint8_t)(start.value & 3);
    in.len = (uint8_t)(len.value - 1);
    emit(s, &in);
    return 1;
}

static void emit_jump(struct stmt *s, int op, const struct asm_arg *rd, const struct asm_arg *t) {
    struct pru_insn in = {0};
    in.op = (uint8_t)op;
    if (rd) {
        in.rd = (uint8_t)rd->value;
        in.rdsel = (uint8_t)rd->field;
    }
    set_op2(&in, t);
    emit(s, &in);
}

static int jal(struct stmt *s, int op) {
    struct asm_arg rd, t;
    if (s->n != 3)
        return fail(s, "Expected 2 operands");
    if (!asm_get_reg(s->c, s->f, 1, s->t[1], &rd, 0, 0) || !reg_or_imm(s, 2, &t, 0, 65535))
        return 0;
    emit_jump(s, op, &rd, &t);
    return 1;
}

static struct asm_arg call_register(const struct stmt *s) {
    struct asm_arg r = {.type = ARG_REG};
    r.value = s->c->retreg;
    r.field = s->c->retfield;
    return r;
}

/* RET: JMP to the call register. */
static int ret(struct stmt *s, int op) {
    (void)op;
    if (s->n != 1)
        return fail(s, "Expected no operands");
    struct asm_arg callreg = call_register(s);
    emit_jump(s, PRU_OP_JMP, NULL, &callreg);
    return 1;
}

/* JMP target | CALL target (JAL with the call register). */
static int jmp_call(struct stmt *s, int op) {
    struct asm_arg t;
    if (s->n != 2)
        return fail(s, "Expected 1 operand");
    if (!reg_or_imm(s, 1, &t, 0, 65535))
        return 0;
    if (op == PRU_OP_CALL) {
        struct asm_arg callreg = call_register(s);
        emit_jump(s, PRU_OP_JAL, &callreg, &t);
    } else {
        emit_jump(s, op, NULL, &t);
    }
    return 1;
}

/* Branch target operand: word offset from here. The range is checked in
 * pass 2 only, when every label is known. */
static int branch_offset(struct stmt *s, int num, int lo, int hi, const char *range_msg, int *out) {
    uint32_t v;
    if (asm_expr(s->c, s->f, s->t[num], &v) < 0) {
        asm_report(s->c, s->f, REP_ERROR, "Operand %d error in expression", num);
        return 0;
    }
    int off = (int)v - s->c->code_offset;
    if (s->c->pass == 2 && (off < lo || off > hi)) {
        asm_report(s->c, s->f, REP_ERROR, "Operand %d %s", num, range_msg);
        return 0;
    }
    *out = off;
    return 1;
}

/* The 10 bits pasm stores, as the signed value pru_insn.broff holds. */
static int16_t broff10(int off) {
    int v = off & 0x3ff;
    return (int16_t)(v >= 512 ? v - 1024 : v);
}

static int loop(struct stmt *s, int op) {
    struct asm_arg cnt;
    int off;
    if (s->n != 3)
        return fail(s, "Expected 2 operands");
    if (!branch_offset(s, 1, 2, 255, "invalid loop termination point", &off))
        return 0;
    if (is_reg(s->t[2])) {
        if (!asm_get_reg(s->c, s->f, 2, s->t[2], &cnt, 0, 0))
            return 0;
    } else {
        if (!asm_get_imm(s->c, s->f, 2, s->t[2], &cnt, 0, 256))
            return 0;
        if (!cnt.value)
            return fail(s, "Null loop count");
        cnt.value--;
    }
    struct pru_insn in = {0};
    in.op = (uint8_t)op;
    in.flag = op == PRU_OP_ILOOP;
    in.loop_end = (uint8_t)(off & 0xff);
    set_op2(&in, &cnt);
    emit(s, &in);
    return 1;
}

static void emit_branch(struct stmt *s, int op, int off, const struct asm_arg *rs1,
                        const struct asm_arg *op2) {
    struct pru_insn in = {0};
    in.op = (uint8_t)op;
    in.broff = broff10(off);
    in.rs1 = (uint8_t)rs1->value;
    in.rs1sel = (uint8_t)rs1->field;
    set_op2(&in, op2);
    emit(s, &in);
}

static int qb(struct stmt *s, int op) {
    struct asm_arg rs1, op2;
    int off;
    if (s->n != 4)
        return fail(s, "Expected 3 operands");
    if (!branch_offset(s, 1, -512, 511, "relative jump out of range", &off) ||
        !asm_get_reg(s->c, s->f, 2, s->t[2], &rs1, 0, 0) || !reg_or_imm(s, 3, &op2, 0, 255))
        return 0;
    emit_branch(s, op, off, &rs1, &op2);
    return 1;
}

static int qba(struct stmt *s, int op) {
    int off;
    if (s->n != 2)
        return fail(s, "Expected 1 operand");
    if (!branch_offset(s, 1, -512, 511, "relative jump out of range", &off))
        return 0;
    struct asm_arg zero = {.type = ARG_IMM, .value = 0};
    struct asm_arg r0 = {.type = ARG_REG, .value = 0, .field = 0};
    emit_branch(s, op, off, &r0, &zero);
    return 1;
}

/* Bit operand(s) of QBBS/QBBC/WBS/WBC starting at term `num`. */
static int bit_test_operands(struct stmt *s, int num, struct asm_arg *rs1, struct asm_arg *bit) {
    if (!asm_get_reg(s->c, s->f, num, s->t[num], rs1, 1, 0))
        return 0;
    if (s->n == num + 1) {
        if (rs1->type != ARG_REGBIT)
            return fail(s, "Two operand mode must specify .T field");
        rs1->type = ARG_REG;
        *bit = (struct asm_arg){.type = ARG_IMM, .value = rs1->bit};
        return 1;
    }
    if (rs1->type != ARG_REG)
        return fail(s, "Three operand mode may not use .T field");
    if (is_reg(s->t[num + 1]))
        return asm_get_reg(s->c, s->f, num + 1, s->t[num + 1], bit, 0, 0);
    return asm_get_imm(s->c, s->f, num + 1, s->t[num + 1], bit, 0, 31);
}

static int qbb(struct stmt *s, int op) {
    struct asm_arg rs1, bit;
    int off;
    if (s->n != 3 && s->n != 4)
        return fail(s, "Expected 2 to 3 operands");
    if (!branch_offset(s, 1, -512, 511, "relative jump out of range", &off) ||
        !bit_test_operands(s, 2, &rs1, &bit))
        return 0;
    emit_branch(s, op, off, &rs1, &bit);
    return 1;
}

/* WBS waits for a set bit: branch to itself while it is clear (and WBC
 * the other way round). */
static int wait_bit(struct stmt *s, int op) {
    int wait_set = op == PRU_OP_WBS;
    struct asm_arg rs1, bit;
    if (s->n < 2 || s->n > 3)
        return fail(s, "Expected 1 to 2 operands");
    if (!bit_test_operands(s, 1, &rs1, &bit))
        return 0;
    emit_branch(s, wait_set ? PRU_OP_QBBC : PRU_OP_QBBS, 0, &rs1, &bit);
    return 1;
}

/* The parser of each operand form of the instruction list (pru_isa.h). */
static int (*const form_parser[])(struct stmt *, int op) = {
    [PRU_FORM_ALU] = alu,
    [PRU_FORM_NOT] = alu,
    [PRU_FORM_CLRSET] = clr_set,
    [PRU_FORM_LDI] = ldi,
    [PRU_FORM_MOV] = mov,
    [PRU_FORM_SCAN] = scan,
    [PRU_FORM_MVI] = mvi,
    [PRU_FORM_NONE] = no_operands,
    [PRU_FORM_SLP] = slp,
    [PRU_FORM_BURST_BO] = burst,
    [PRU_FORM_BURST_CO] = burst,
    [PRU_FORM_XFR] = xfr,
    [PRU_FORM_ZERO_FILL] = zero_fill,
    [PRU_FORM_JMP] = jmp_call,
    [PRU_FORM_JAL] = jal,
    [PRU_FORM_CALL] = jmp_call,
    [PRU_FORM_RET] = ret,
    [PRU_FORM_LOOP] = loop,
    [PRU_FORM_QB] = qb,
    [PRU_FORM_QBA] = qba,
    [PRU_FORM_QBB] = qbb,
    [PRU_FORM_WAIT] = wait_bit,
};

int asm_instruction(struct asm_ctx *c, struct asm_file *f, int nterms,
                    char terms[][ASM_TOKEN_MAX]) {
    struct stmt s = {c, f, nterms, terms};
    int op = pru_op_lookup(terms[0]);
    if (op < 0)
        return fail(&s, "Invalid opcode");
    const struct pru_opinfo *row = &pru_optable[op];
    /* pasm checks the core version before the operands */
    if (c->core < row->min_core || c->core > row->max_core)
        return fail(&s, "Instruction illegal with specified core version");
    return form_parser[row->form](&s, op);
}
