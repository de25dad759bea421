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

static enum pd_kind alu_kind(unsigned op) {
    static const uint8_t k[] = {K_ADD, K_ADC, K_SUB, K_SUC, K_LSL, K_LSR, K_RSB, K_RSC,
                                K_AND, K_OR,  K_XOR, K_NOT, K_MIN, K_MAX, K_CLR, K_SET};
    return (enum pd_kind)k[op - PRU_OP_ADD];
}

static enum pd_kind branch_kind(unsigned op) {
    switch (op) {
    case PRU_OP_QBGT:
        return K_QBGT;
    case PRU_OP_QBGE:
        return K_QBGE;
    case PRU_OP_QBLT:
        return K_QBLT;
    case PRU_OP_QBLE:
        return K_QBLE;
    case PRU_OP_QBEQ:
        return K_QBEQ;
    case PRU_OP_QBNE:
        return K_QBNE;
    case PRU_OP_QBBS:
        return K_QBBS;
    case PRU_OP_QBBC:
        return K_QBBC;
    default:
        return K_QBA;
    }
}

static void decode_into(struct pd *d, const struct pru_insn *in, uint32_t pc) {
    unsigned op = in->op;
    if (op <= PRU_OP_SET) {
        d->kind = (uint8_t)alu_kind(op);
        set_dst(d, in->rd, in->rdsel);
        set_rs1(d, in->rs1, in->rs1sel);
        set_op2(d, in);
        if (op == PRU_OP_SET && in->rs1 == 31) {
            /* DOC quirk: R31 as the source of SET reads as zero */
            d->rs1 = ZERO_REG;
            d->flags &= (uint8_t)~PD_READS_R31;
            if (!in->io && in->rs2 == 31)
                d->flags |= PD_READS_R31;
        }
        return;
    }
    if (op >= PRU_OP_NOP0 && op <= PRU_OP_NOPF) {
        d->kind = K_NOP;
        return;
    }
    switch (op) {
    case PRU_OP_LMBD:
        d->kind = K_LMBD;
        set_dst(d, in->rd, in->rdsel);
        set_rs1(d, in->rs1, in->rs1sel);
        set_op2(d, in);
        return;
    case PRU_OP_JMP:
    case PRU_OP_JAL:
        d->kind = op == PRU_OP_JMP ? K_JMP : K_JAL;
        if (op == PRU_OP_JAL)
            set_dst(d, in->rd, in->rdsel);
        set_op2(d, in);
        return;
    case PRU_OP_LDI:
        d->kind = K_LDI;
        set_dst(d, in->rd, in->rdsel);
        d->imm = in->imm;
        return;
    case PRU_OP_HALT:
        d->kind = K_HALT;
        return;
    case PRU_OP_SLP:
        d->kind = K_SLP;
        return;
    case PRU_OP_MVIB:
    case PRU_OP_MVIW:
    case PRU_OP_MVID:
        d->kind = K_MVI;
        return;
    case PRU_OP_XIN:
    case PRU_OP_XOUT:
    case PRU_OP_XCHG:
    case PRU_OP_SXIN:
    case PRU_OP_SXOUT:
    case PRU_OP_SXCHG:
        d->kind = K_XFR;
        return;
    case PRU_OP_LOOP:
    case PRU_OP_ILOOP:
        d->kind = K_LOOP;
        set_op2(d, in);
        if (in->io)
            d->imm = in->imm + 1u; /* encoded as count - 1 */
        d->target = pc + in->loop_end;
        return;
    case PRU_OP_QBBS:
    case PRU_OP_QBBC:
    case PRU_OP_QBGT:
    case PRU_OP_QBGE:
    case PRU_OP_QBLT:
    case PRU_OP_QBLE:
    case PRU_OP_QBEQ:
    case PRU_OP_QBNE:
    case PRU_OP_QBA:
        d->kind = (uint8_t)branch_kind(op);
        if (op != PRU_OP_QBA) {
            set_rs1(d, in->rs1, in->rs1sel);
            set_op2(d, in);
        }
        d->target = (uint32_t)(pc + (uint32_t)(int32_t)in->broff) & 0xffffu;
        return;
    case PRU_OP_LBBO:
    case PRU_OP_SBBO:
    case PRU_OP_LBCO:
    case PRU_OP_SBCO:
        d->kind = op == PRU_OP_LBBO   ? K_LBBO
                  : op == PRU_OP_SBBO ? K_SBBO
                  : op == PRU_OP_LBCO ? K_LBCO
                                      : K_SBCO;
        set_op2(d, in);
        if ((op == PRU_OP_LBBO || op == PRU_OP_SBBO) && in->base == 31)
            d->flags |= PD_READS_R31;
        if (in->len < 124 && 4u * in->rx + in->rxbyte + in->len + 1u <= 120u) {
            d->burst_bytes = (uint8_t)(in->len + 1u);
            d->burst_rf = (uint8_t)(4u * in->rx + in->rxbyte);
        }
        return;
    default:
        d->kind = K_BAD; /* SCAN (V1 only) */
        return;
    }
}

void predecode_word(struct pru_core *c, uint32_t pc) {
    struct pd *d = &c->pd[pc];
    memset(d, 0, sizeof *d);
    struct pru_insn in;
    if (pru_decode(c->iram0[pc], &in) != 0) {
        d->kind = K_BAD;
        d->fast = K_SLOW;
        return;
    }
    d->in = in;
    decode_into(d, &in, pc);
    d->fast = d->kind > K_QBBC           ? K_SLOW
              : d->flags == 0            ? d->kind
              : d->flags == PD_READS_R31 ? K_R31_READ
                                         : K_SLOW;
}

void predecode_all(struct pru_core *c) {
    for (uint32_t pc = 0; pc < c->iram_words; pc++)
        predecode_word(c, pc);
}
