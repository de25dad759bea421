/*
 * pru_isa.c - the instruction table and the word <-> struct pru_insn codec.
 *
 * Bit layouts are those of docs/pru-facts.md §1 (formats 1, 2, 4,
 * 5, 6 and pasm's format 101 for NOPn). Decoding is strict: bits that every
 * layout keeps at zero must be zero, so that encode(decode(w)) == w.
 */
#include "pru_isa.h"

#include <ctype.h>
#include <string.h>

const struct pru_opinfo pru_optable[PRU_OP_COUNT] = {
#define PRU_X_ROW(id, nm, f, m, k, lo, hi, fo)                                                     \
    [PRU_OP_##id] = {.name = nm,                                                                   \
                     .fmt = PRU_FMT_##f,                                                           \
                     .form = PRU_FORM_##fo,                                                        \
                     .min_core = lo,                                                               \
                     .max_core = hi,                                                               \
                     .match = m,                                                                   \
                     .mask = k},
    PRU_INSN_LIST(PRU_X_ROW)
#undef PRU_X_ROW
};

static uint32_t bits(uint32_t w, unsigned hi, unsigned lo) {
    return (w >> lo) & ((1u << (hi - lo + 1)) - 1u);
}

static int find_op(uint32_t word) {
    for (int op = 0; op < PRU_OP_COUNT; op++) {
        if (pru_op_decodes(op) && (word & pru_optable[op].mask) == pru_optable[op].match) {
            return op;
        }
    }
    return -1;
}

/* op2 of formats 1, 4, 5, 6 and LOOP: imm8 or a register field in 23:16. */
static void decode_op2_8(uint32_t w, struct pru_insn *in) {
    in->io = bits(w, 24, 24);
    if (in->io) {
        in->imm = bits(w, 23, 16);
    } else {
        in->rs2sel = bits(w, 23, 21);
        in->rs2 = bits(w, 20, 16);
    }
}

static uint32_t encode_op2_8(const struct pru_insn *in) {
    if (in->io) {
        return (1u << 24) | ((uint32_t)(in->imm & 0xff) << 16);
    }
    return ((uint32_t)(in->rs2sel & 7) << 21) | ((uint32_t)(in->rs2 & 31) << 16);
}

/* JMP/JAL target: imm16 in 23:8, or a register field in 23:16 (15:8 zero). */
static int decode_op2_16(uint32_t w, struct pru_insn *in) {
    in->io = bits(w, 24, 24);
    if (in->io) {
        in->imm = bits(w, 23, 8);
        return 0;
    }
    in->rs2sel = bits(w, 23, 21);
    in->rs2 = bits(w, 20, 16);
    return bits(w, 15, 8) == 0 ? 0 : -1;
}

static uint32_t encode_op2_16(const struct pru_insn *in) {
    if (in->io) {
        return (1u << 24) | ((uint32_t)in->imm << 8);
    }
    return ((uint32_t)(in->rs2sel & 7) << 21) | ((uint32_t)(in->rs2 & 31) << 16);
}

static void decode_rs1(uint32_t w, struct pru_insn *in) {
    in->rs1sel = bits(w, 15, 13);
    in->rs1 = bits(w, 12, 8);
}

static void decode_rd(uint32_t w, struct pru_insn *in) {
    in->rdsel = bits(w, 7, 5);
    in->rd = bits(w, 4, 0);
}

static uint32_t encode_rs1(const struct pru_insn *in) {
    return ((uint32_t)(in->rs1sel & 7) << 13) | ((uint32_t)(in->rs1 & 31) << 8);
}

static uint32_t encode_rd(const struct pru_insn *in) {
    return ((uint32_t)(in->rdsel & 7) << 5) | (uint32_t)(in->rd & 31);
}

/* Signed 10-bit branch offset split over 26:25 and 7:0. */
static int16_t decode_broff(uint32_t w) {
    int v = (int)((bits(w, 26, 25) << 8) | bits(w, 7, 0));
    return (int16_t)(v >= 512 ? v - 1024 : v);
}

static uint32_t encode_broff(int broff) {
    uint32_t v = (uint32_t)broff & 0x3ffu;
    return ((v >> 8) << 25) | (v & 0xffu);
}

int pru_decode(uint32_t w, struct pru_insn *in) {
    memset(in, 0, sizeof(*in));
    int op = find_op(w);
    if (op < 0) {
        return -1;
    }
    in->op = (uint8_t)op;
    switch (pru_optable[op].fmt) {
    case PRU_FMT_ALU:
        decode_op2_8(w, in);
        decode_rs1(w, in);
        decode_rd(w, in);
        return 0;
    case PRU_FMT_JMP:
        return decode_op2_16(w, in);
    case PRU_FMT_JAL:
        decode_rd(w, in);
        return decode_op2_16(w, in);
    case PRU_FMT_LDI:
        in->imm = bits(w, 23, 8);
        decode_rd(w, in);
        return 0;
    case PRU_FMT_NONE:
        return 0;
    case PRU_FMT_SLP:
        in->flag = bits(w, 23, 23);
        return 0;
    case PRU_FMT_MVI:
        in->mvi_size = bits(w, 17, 16);
        in->mvi_dmode = bits(w, 24, 23);
        in->mvi_smode = bits(w, 22, 21);
        decode_rs1(w, in);
        decode_rd(w, in);
        return 0;
    case PRU_FMT_XFR:
        in->dev = bits(w, 22, 15);
        in->len = bits(w, 13, 7);
        in->rxbyte = bits(w, 6, 5);
        in->rx = bits(w, 4, 0);
        return 0;
    case PRU_FMT_LOOP:
        decode_op2_8(w, in);
        in->flag = op == PRU_OP_ILOOP;
        in->loop_end = bits(w, 7, 0);
        return 0;
    case PRU_FMT_QB:
    case PRU_FMT_QBA:
    case PRU_FMT_QBB:
        decode_op2_8(w, in);
        decode_rs1(w, in);
        in->broff = decode_broff(w);
        return 0;
    case PRU_FMT_BURST:
        decode_op2_8(w, in);
        in->len = (uint8_t)((bits(w, 27, 25) << 4) | (bits(w, 15, 13) << 1) | bits(w, 7, 7));
        in->base = bits(w, 12, 8);
        in->rxbyte = bits(w, 6, 5);
        in->rx = bits(w, 4, 0);
        return 0;
    case PRU_FMT_PSEUDO:
        break;
    }
    return -1;
}

uint32_t pru_encode(const struct pru_insn *in) {
    if (in->op >= PRU_OP_COUNT) {
        return 0;
    }
    /* SCAN (core V1) shares the ALU layout and encodes like the V3 rows. */
    const struct pru_opinfo *info = &pru_optable[in->op];
    uint32_t w = info->match;
    switch (info->fmt) {
    case PRU_FMT_ALU:
        return w | encode_op2_8(in) | encode_rs1(in) | encode_rd(in);
    case PRU_FMT_JMP:
        return w | encode_op2_16(in);
    case PRU_FMT_JAL:
        return w | encode_op2_16(in) | encode_rd(in);
    case PRU_FMT_LDI:
        return w | ((uint32_t)in->imm << 8) | encode_rd(in);
    case PRU_FMT_NONE:
        return w;
    case PRU_FMT_SLP:
        return w | ((uint32_t)(in->flag & 1) << 23);
    case PRU_FMT_MVI:
        return w | ((uint32_t)(in->mvi_dmode & 3) << 23) | ((uint32_t)(in->mvi_smode & 3) << 21) |
               encode_rs1(in) | encode_rd(in);
    case PRU_FMT_XFR:
        return w | ((uint32_t)in->dev << 15) | ((uint32_t)(in->len & 0x7f) << 7) |
               ((uint32_t)(in->rxbyte & 3) << 5) | (uint32_t)(in->rx & 31);
    case PRU_FMT_LOOP:
        return w | encode_op2_8(in) | in->loop_end;
    case PRU_FMT_QB:
    case PRU_FMT_QBA:
    case PRU_FMT_QBB:
        return w | encode_op2_8(in) | encode_rs1(in) | encode_broff(in->broff);
    case PRU_FMT_BURST: {
        uint32_t len = in->len & 0x7fu;
        return w | ((len >> 4) << 25) | (((len >> 1) & 7) << 13) | ((len & 1) << 7) |
               encode_op2_8(in) | ((uint32_t)(in->base & 31) << 8) |
               ((uint32_t)(in->rxbyte & 3) << 5) | (uint32_t)(in->rx & 31);
    }
    case PRU_FMT_PSEUDO:
        break;
    }
    return 0;
}

int pru_op_lookup(const char *name) {
    char low[8];
    size_t n = 0;
    for (; name[n] != '\0'; n++) {
        if (n == sizeof(low) - 1) {
            return -1; /* longer than any mnemonic */
        }
        low[n] = (char)tolower((unsigned char)name[n]);
    }
    low[n] = '\0';
    if (n == 0) {
        return -1;
    }
    for (int op = 0; op < PRU_OP_COUNT; op++) {
        if (strcmp(pru_optable[op].name, low) == 0) {
            return op;
        }
    }
    return -1;
}
