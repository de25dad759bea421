/* biss_image_pru.c - the PRU a firmware image was assembled for, read from
 * its instruction words before it runs (biss_proto.h).
 *
 * The image stores PRU_NUM to BISS_ST_PRU at start-up (pru_fw/startup.p:
 * the value a host reads back once the magic is there). Run on the wrong
 * PRU it never gets that far intact: its CONTROL block address (C28
 * through CTPPR0) is the other PRU's, so its private area lands on the
 * shared block, ST_PRU included. So the value is taken from the words
 * themselves: the straight-line start-up is followed from address 0, the
 * registers that LDI sets are known (any other write makes its bytes
 * unknown), up to the first store through C24 (the PRU's own data RAM) at
 * BISS_ST_PRU; what that store writes there is the image's PRU. Register
 * names, the order of the start-up and what else it does may change; a
 * branch before that store, or a value not known there, says nothing. The
 * words are decoded by the one instruction table (emulator/isa). */
#include "biss_proto.h"

#include "pru_isa.h"

#include <string.h>

/* How far the start-up may run before it publishes ST_PRU. */
#define MAX_STEPS 256

/* The register file as bytes: byte 4r + b is r<r>.b<b>. */
struct regs {
    uint8_t value[128];
    uint8_t known[128];
};

static void forget(struct regs *r, unsigned from, unsigned bytes) {
    for (unsigned i = from; i < from + bytes && i < sizeof r->known; i++) {
        r->known[i] = 0;
    }
}

/* Register field (reg, sel) as a byte range of the file. */
static void field(unsigned reg, unsigned sel, unsigned *from, unsigned *bytes) {
    *from = 4 * (reg & 31) + pru_sel_shift(sel) / 8;
    *bytes = pru_sel_width(sel) / 8;
}

/* LDI: the 16-bit value into the field, zero-extended to a whole register. */
static void load_immediate(struct regs *r, const struct pru_insn *in) {
    unsigned from, bytes;
    field(in->rd, in->rdsel, &from, &bytes);
    uint32_t v = in->imm;
    for (unsigned i = 0; i < bytes; i++) {
        r->value[from + i] = (uint8_t)(v >> (8 * i));
        r->known[from + i] = 1;
    }
}

/* The bytes a burst or XFR writes: from rx.rxbyte on, len bytes (a length
 * from R0: up to the end of the file). */
static void forget_burst(struct regs *r, const struct pru_insn *in) {
    unsigned bytes = in->len < 124 ? in->len + 1u : sizeof r->known;
    forget(r, 4u * in->rx + in->rxbyte, bytes);
}

/* What an instruction that does not branch writes. */
static void execute(struct regs *r, const struct pru_insn *in) {
    unsigned from, bytes;
    switch (pru_optable[in->op].fmt) {
    case PRU_FMT_LDI:
        load_immediate(r, in);
        return;
    case PRU_FMT_ALU:
        field(in->rd, in->rdsel, &from, &bytes);
        forget(r, from, bytes);
        return;
    case PRU_FMT_MVI:
        /* through a pointer: anywhere */
        forget(r, 0, in->mvi_dmode == PRU_MVI_DIRECT ? 0 : sizeof r->known);
        field(in->rd, in->rdsel, &from, &bytes);
        forget(r, from, bytes);
        return;
    case PRU_FMT_BURST:
        if (in->op == PRU_OP_LBBO || in->op == PRU_OP_LBCO) {
            forget_burst(r, in);
        }
        return;
    case PRU_FMT_XFR:
        if (in->op != PRU_OP_XOUT && in->op != PRU_OP_SXOUT) {
            forget_burst(r, in);
        }
        return;
    default:
        return; /* LOOP (its body follows in line), NOPn */
    }
}

/* The 4 bytes a store writes at BISS_ST_PRU, if it covers them and they
 * are known: 1 and *v, else 0. */
static int st_pru_value(const struct regs *r, const struct pru_insn *in, uint32_t *v) {
    unsigned bytes = in->len < 124 ? in->len + 1u : 0;
    if (!in->io || in->imm > BISS_ST_PRU || in->imm + bytes < BISS_ST_PRU + 4u) {
        return 0;
    }
    unsigned at = 4u * in->rx + in->rxbyte + (BISS_ST_PRU - in->imm);
    *v = 0;
    for (unsigned i = 0; i < 4; i++) {
        if (at + i >= sizeof r->known || !r->known[at + i]) {
            return 0;
        }
        *v |= (uint32_t)r->value[at + i] << (8 * i);
    }
    return 1;
}

int biss_image_pru(const void *image, size_t bytes) {
    struct regs r;
    memset(&r, 0, sizeof r);
    const uint8_t *p = image;
    for (size_t pc = 0; pc < bytes / 4 && pc < MAX_STEPS; pc++) {
        uint32_t w = (uint32_t)p[4 * pc] | (uint32_t)p[4 * pc + 1] << 8 |
                     (uint32_t)p[4 * pc + 2] << 16 | (uint32_t)p[4 * pc + 3] << 24;
        struct pru_insn in;
        if (pru_decode(w, &in) != 0) {
            return -1;
        }
        if (in.op == PRU_OP_SBCO && in.base == 24) {
            uint32_t v;
            if (in.io && in.imm <= BISS_ST_PRU && in.imm + in.len + 1u > BISS_ST_PRU) {
                return st_pru_value(&r, &in, &v) && v <= 1 ? (int)v : -1;
            }
            continue;
        }
        switch (pru_optable[in.op].fmt) {
        case PRU_FMT_JMP:
        case PRU_FMT_JAL:
        case PRU_FMT_QB:
        case PRU_FMT_QBA:
        case PRU_FMT_QBB:
        case PRU_FMT_NONE: /* HALT */
        case PRU_FMT_SLP:
            return -1; /* no straight line to the store */
        default:
            execute(&r, &in);
        }
    }
    return -1;
}
