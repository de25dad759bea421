/*
 * predecode.c - turns each IRAM word, once, into the compact form the
 * execute loop runs (struct pd). Redone for a word whenever IRAM changes.
 */
#include "core_priv.h"

#include <string.h>

#define ZERO_REG 32u

static void set_dst(struct pd *d, unsigned reg, unsigned sel) {
    d->rd = (uint8_t)reg;
    d->rdsh = (uint8_t)pru_sel_shift(sel);
    d->rdmask = pru_sel_mask(sel);
    d->rdw = (uint8_t)pru_sel_width(sel);
    if (reg == 30)
        d->flags |= PD_WRITES_R30;
    if (reg == 31)
        d->flags |= PD_WRITES_R31;
}

static void set_rs1(struct pd *d, unsigned reg, unsigned sel) {
    d->rs1 = (uint8_t)reg;
    d->rs1sh = (uint8_t)pru_sel_shift(sel);
    d->rs1mask = pru_sel_mask(sel);
    if (reg == 31)
        d->flags |= PD_READS_R31;
}

/* op2: a register field, or an immediate read through the zero register. */
static void set_op2(struct pd *d, const struct pru_insn *in) {
    if (in->io) {
        d->rs2 = ZERO_REG;
        d->rs2sh = 0;
        d->rs2mask = 0;
        d->imm = in->imm;
    } else {
        d->rs2 = in->rs2;
        d->rs2sh = (uint8_t)pru_sel_shift(in->rs2sel);
        d->rs2mask = pru_sel_mask(in->rs2sel);
        d->imm = 0;
        if (in->rs2 == 31)
            d->flags |= PD_READS_R31;
    }
}

static void decode_into(struct pd *d, const struct pru_insn *in, uint32_t pc) {
    unsigned op = in->op;
    d->kind = (uint8_t)op;
    switch ((enum pru_fmt)pru_optable[op].fmt) {
    case PRU_FMT_ALU:
        if (op >= PRU_OP_NOP0 && op <= PRU_OP_NOPF) {
            d->kind = PRU_OP_NOP0; /* no operand is read or written */
            return;
        }
        set_dst(d, in->rd, in->rdsel);
        set_rs1(d, in->rs1, in->rs1sel);
        set_op2(d, in);
        if (op == PRU_OP_SET && in->rs1 == 31) {
            /* DOC quirk (docs/pru-facts.md §1.3): R31 as the source of SET reads as zero */
            d->rs1 = ZERO_REG;
            d->flags &= (uint8_t)~PD_READS_R31;
            if (!in->io && in->rs2 == 31)
                d->flags |= PD_READS_R31;
        }
        return;
    case PRU_FMT_JAL:
        set_dst(d, in->rd, in->rdsel);
        set_op2(d, in);
        return;
    case PRU_FMT_JMP:
        set_op2(d, in);
        return;
    case PRU_FMT_LDI:
        set_dst(d, in->rd, in->rdsel);
        d->imm = in->imm;
        return;
    case PRU_FMT_LOOP:
        set_op2(d, in);
        if (in->io)
            d->imm = in->imm + 1u; /* encoded as count - 1 */
        d->target = pc + in->loop_end;
        return;
    case PRU_FMT_QB:
    case PRU_FMT_QBB:
        set_rs1(d, in->rs1, in->rs1sel);
        set_op2(d, in);
        d->target = (uint32_t)(pc + (uint32_t)(int32_t)in->broff) & 0xffffu;
        return;
    case PRU_FMT_QBA:
        d->target = (uint32_t)(pc + (uint32_t)(int32_t)in->broff) & 0xffffu;
        return;
    case PRU_FMT_BURST:
        set_op2(d, in);
        if ((pru_optable[op].match >> 28) & 1u)
            d->flags |= PD_BURST_LOAD;
        if (pru_optable[op].form == PRU_FORM_BURST_CO)
            d->flags |= PD_BURST_CBASE;
        if (pru_optable[op].form == PRU_FORM_BURST_BO && in->base == 31)
            d->flags |= PD_READS_R31;
        if (in->len < 124 && 4u * in->rx + in->rxbyte + in->len + 1u <= 120u) {
            d->burst_bytes = (uint8_t)(in->len + 1u);
            d->burst_rf = (uint8_t)(4u * in->rx + in->rxbyte);
        }
        return;
    case PRU_FMT_NONE: /* HALT */
    case PRU_FMT_SLP:
    case PRU_FMT_MVI:
    case PRU_FMT_XFR: /* these read their fields from d->in */
        return;
    case PRU_FMT_PSEUDO:
        break;
    }
    d->kind = PD_BAD;
}

/* The fast loop's kind for register-only op `kind` with d's operands: its
 * whole-register form (PD_ADD32 ...), or the op; with the threaded dispatch
 * of the fast loop, an immediate op2 has forms of its own too (PD_ADD32I
 * ...). */
static uint8_t fast_form(const struct pd *d, uint8_t kind) {
    bool rs1 = d->rs1sh == 0 && d->rs1mask == 0xffffffffu;
    bool rd = d->rdsh == 0 && d->rdmask == 0xffffffffu;
    bool imm = d->rs2 == ZERO_REG;
    bool rdb = d->rdmask == 0xffu, rs1b = d->rs1mask == 0xffu, rs1w = d->rs1mask == 0xffffu;
    bool op2b = !imm && d->rs2mask == 0xffu;
    bool op2w = imm || (d->rs2sh == 0 && d->rs2mask == 0xffffffffu); /* whole or immediate */
    switch (kind) {
    case PRU_OP_ADD:
        return rs1 && rd ? (imm ? PD_ADD32I : PD_ADD32) : kind;
    case PRU_OP_SUB:
        if (rs1 && rd)
            return imm ? PD_SUB32I : op2b ? PD_SUB32B : PD_SUB32;
        return imm ? (rdb && rs1b ? PD_SUBBBI : PD_SUBI) : kind;
    case PRU_OP_QBNE:
        if (rs1)
            return imm ? PD_QBNE32I : PD_QBNE32;
        return imm ? (rs1b ? PD_QBNEBI : rs1w ? PD_QBNEWI : PD_QBNEI) : kind;
    case PRU_OP_QBEQ:
        if (rs1)
            return imm ? PD_QBEQ32I : PD_QBEQ32;
        return imm ? (rs1b ? PD_QBEQBI : rs1w ? PD_QBEQWI : PD_QBEQI) : kind;
    case PRU_OP_MIN:
        return imm ? (rdb && rs1 ? PD_MINB32I : PD_MINI) : kind;
    case PRU_OP_JAL:
        return imm ? PD_JALI : kind;
    case PRU_OP_QBBS:
        return rs1 ? (imm ? PD_QBBS32I : PD_QBBS32) : kind;
    case PRU_OP_QBBC:
        return rs1 ? (imm ? PD_QBBC32I : PD_QBBC32) : kind;
    case PRU_OP_ADC:
        return rs1 && rd && op2w ? PD_ADC32 : kind;
    case PRU_OP_AND:
        return rs1 && rd && op2w ? PD_AND32 : kind;
    case PRU_OP_OR:
        return rs1 && rd && op2w ? PD_OR32 : kind;
    case PRU_OP_XOR:
        return rs1 && rd && op2w ? PD_XOR32 : kind;
    case PRU_OP_LSL:
        return rs1 && rd && op2w ? (imm ? PD_LSL32I : PD_LSL32) : kind;
    case PRU_OP_LSR:
        return rs1 && rd && op2w ? (imm ? PD_LSR32I : PD_LSR32) : kind;
    case PRU_OP_LDI:
        return rd ? PD_LDI32 : kind;
    default:
        return kind;
    }
}

/* MVI loading through a register pointer into a field, both of r0..r29
 * (PD_MVI_LD), or PD_SLOW. Pointer and destination below r30: no pin or
 * event effect, and no R31 value is read before its refresh. */
static uint8_t mvi_form(struct pd *d, const struct pru_insn *in) {
    if (in->mvi_smode == PRU_MVI_DIRECT || in->mvi_dmode != PRU_MVI_DIRECT || in->rs1 >= 30 ||
        in->rd >= 30)
        return PD_SLOW;
    unsigned size = 1u << in->mvi_size;
    d->rs1 = in->rs1;
    d->rs1sh = (uint8_t)pru_sel_shift(in->rs1sel);
    d->rs1mask = pru_sel_mask(in->rs1sel);
    d->rd = in->rd;
    d->rdsh = (uint8_t)pru_sel_shift(in->rdsel);
    d->rdmask = pru_sel_mask(in->rdsel);
    d->imm = size == 4 ? 0xffffffffu : (1u << (8u * size)) - 1u;
    d->rdw = (uint8_t)size;
    d->rs2 = (uint8_t)(in->mvi_smode == PRU_MVI_PREDEC ? size : 0);
    d->rs2sh = (uint8_t)(in->mvi_smode == PRU_MVI_POSTINC ? size : 0);
    return PD_MVI_LD;
}

/* XIN/XOUT of a scratch-pad bank, ZERO or FILL, of a fixed length within
 * r0..r29 (PD_XFR_FIXED), or PD_SLOW. */
static uint8_t xfr_form(struct pd *d, const struct pru_insn *in) {
    unsigned op = in->op, dev = in->dev;
    bool xin = op == PRU_OP_XIN || op == PRU_OP_SXIN,
         xout = op == PRU_OP_XOUT || op == PRU_OP_SXOUT;
    unsigned start = 4u * in->rx + in->rxbyte;
    if (in->len >= 124 || start + in->len + 1u > 120u)
        return PD_SLOW;
    if (!((xin || xout) && dev >= 10 && dev <= 12) && !(xin && (dev == 254 || dev == 255)))
        return PD_SLOW;
    d->imm = in->len + 1u;
    d->target = start;
    return PD_XFR_FIXED;
}

/* The fast loop's kind for an ALU instruction or LDI writing R30. */
static uint8_t r30_form(const struct pd *d) {
    if (d->kind != PRU_OP_XOR)
        return PD_R30_WRITE;
    bool same = d->rs1 == d->rd && d->rs1sh == d->rdsh && d->rs1mask == d->rdmask;
    bool bytes = d->rdmask == 0xffu && d->rs2 != ZERO_REG && d->rs2mask == 0xffu;
    return same && bytes ? PD_R30_XORB : PD_R30_XOR;
}

/* The place of fast kind `fast` in PD_STRAIGHT_KINDS, or -1 if a straight
 * run has none of it. */
static int straight(uint8_t fast) {
    switch (fast) {
#define PLACE_CASE(label, kind)                                                                    \
    case kind:                                                                                     \
        return PD_PLACE_##label;
        PD_STRAIGHT_KINDS(PLACE_CASE)
    default:
        return -1;
    }
}

/* The place of fast kind `fast` in PD_QUICK_KINDS, or -1. */
static int quick(uint8_t fast) {
    switch (fast) {
        PD_QUICK_KINDS(PLACE_CASE)
#undef PLACE_CASE
    default:
        return -1;
    }
}

/* The firmware's pair (PD_PAIR_*) that the word at pc begins, or 0. */
static uint8_t pair(const struct pru_core *c, uint32_t pc) {
    const struct pd *d = &c->pd[pc], *n = &c->pd[pc + 1];
    if (d->fast == PD_MINB32I && n->fast == PD_SUB32B && n->rs1 == d->rs1 && n->rd == d->rs1 &&
        n->rs2 == d->rd && n->rs2sh == d->rdsh && d->rd != d->rs1)
        return PD_PAIR_MIN_SUB;
    if (d->fast == PD_LSL32I && n->fast == PD_XOR32 && n->rs1 == d->rd)
        return PD_PAIR_LSL_XOR;
    if (d->fast == PD_XOR32 && n->fast == PD_QBBS32I && n->rs1 == d->rd && n->target > pc + 1)
        return PD_PAIR_XOR_QBBS;
    if (d->fast == PD_ADD32 && n->fast == PD_ADC32 && n[1].fast == PD_ADC32)
        return PD_PAIR_ADD_ADC2; /* (n is not the word past IRAM: n[1] is there) */
    return 0;
}

/* The straight run from word pc on (from the word after it) and the fast
 * loop's dispatch (.go; a run of one is not worth its check). Returns
 * whether the run changed. */
static bool set_run(struct pru_core *c, uint32_t pc) {
    struct pd *d = &c->pd[pc];
    int place = straight(d->fast), q = quick(d->fast);
    bool r31 = d->fast == PD_R31_READ && straight(d->inner) >= 0;
    uint32_t run = place >= 0 || r31 ? 1u + c->pd[pc + 1].run : 0u;
    uint16_t old = d->run;
    d->run = (uint16_t)(run < UINT16_MAX ? run : UINT16_MAX);
    bool first = run >= 2 && run < UINT16_MAX; /* (the run's end known) */
    uint8_t p = pair(c, pc);
    if (p == PD_PAIR_XOR_QBBS || (p && first))
        d->go = p;
    else if (first)
        d->go = (uint8_t)(r31 ? PD_RUN_R31 : PD_RUN + place);
    else if (q >= 0 && d->target > pc)
        d->go = (uint8_t)(PD_FORWARD + q);
    else if (d->fast == PD_JALI && (d->imm & 0xffffu) < c->iram_words &&
             (d->imm & 0xffffu) + FF_MAX_BODY <= pc)
        d->go = PD_PAIR_CALL_RET; /* (what the routine is: looked at as it runs) */
    else
        d->go = d->fast;
    return d->run != old;
}

static void decode_word(struct pru_core *c, uint32_t pc) {
    struct pd *d = &c->pd[pc];
    c->iram_gen++; /* what ff.c decoded from IRAM may be out of date */
    memset(d, 0, sizeof *d);
    struct pru_insn in;
    if (pru_decode(c->iram0[pc], &in) != 0) {
        d->kind = PD_BAD;
        d->fast = PD_SLOW;
        return;
    }
    d->in = in;
    decode_into(d, &in, pc);
    d->fast = d->kind == PD_BAD || !pru_op_register_only(d->kind) ? PD_SLOW
              : d->flags == 0                                     ? fast_form(d, d->kind)
              : d->flags == PD_READS_R31                          ? PD_R31_READ
                                                                  : PD_SLOW;
    if (d->fast == PD_R31_READ)
        d->inner = fast_form(d, d->kind);
    /* a branch out of IRAM faults: exec_one() takes it, the fast loop
     * checks only the targets of JMP and JAL */
    enum pru_fmt f = d->kind == PD_BAD ? PRU_FMT_PSEUDO : (enum pru_fmt)pru_optable[d->kind].fmt;
    if (d->fast == PD_SLOW && d->flags == PD_WRITES_R30 && (f == PRU_FMT_ALU || f == PRU_FMT_LDI) &&
        pru_op_register_only(d->kind))
        d->fast = r30_form(d); /* a clocked loop's MA edges */
    if ((f == PRU_FMT_QB || f == PRU_FMT_QBA || f == PRU_FMT_QBB) && d->target >= c->iram_words)
        d->fast = PD_SLOW;
    if (f == PRU_FMT_MVI)
        d->fast = mvi_form(d, &in);
    if (f == PRU_FMT_XFR)
        d->fast = xfr_form(d, &in);
    /* Two PRUs: every instruction the fast loop does not run as register
     * work (or an R30 write: each PRU its own pins) is a cross-PRU event */
    bool xpru = d->fast == PD_SLOW || d->fast == PD_R31_READ || d->fast == PD_MVI_LD ||
                d->fast == PD_XFR_FIXED;
    if (c->pru0->pru1 && xpru) {
        d->xfast = d->fast;
        d->fast = PD_XPRU;
    }
}

void predecode_word(struct pru_core *c, uint32_t pc) {
    decode_word(c, pc);
    /* the runs of this word and of the straight words before it, as far
     * back as they change, and the dispatch of the two before it (a
     * PD_PAIR_ADD_ADC2 reads two words on) */
    set_run(c, pc);
    for (uint32_t k = 1; k <= pc; k++)
        if (!set_run(c, pc - k) && k >= 2)
            break;
}

void predecode_all(struct pru_core *c) {
    for (uint32_t pc = 0; pc < c->iram_words; pc++)
        decode_word(c, pc);
    /* one past the last word: the fast loop leaves there, so that it never
     * compares pc with the end of IRAM after a straight-line instruction */
    struct pd *end = &c->pd[c->iram_words];
    memset(end, 0, sizeof *end);
    end->kind = PD_BAD;
    end->fast = PD_END;
    end->go = PD_END;
    for (uint32_t pc = c->iram_words; pc-- > 0;)
        set_run(c, pc);
}
