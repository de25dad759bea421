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

#define F1 0xfe000000u /* bits 31:25 fixed: format 1, format 2 sub-op */
#define F4 0xf8000000u /* bits 31:27 fixed: quick branches */
#define F6 0xf0000000u /* bits 31:28 fixed: burst transfers */

const struct pru_opinfo pru_optable[PRU_OP_COUNT] = {
    [PRU_OP_ADD] = {"add", PRU_FMT_ALU, 0x00000000u, F1, 0},
    [PRU_OP_ADC] = {"adc", PRU_FMT_ALU, 0x02000000u, F1, 0},
    [PRU_OP_SUB] = {"sub", PRU_FMT_ALU, 0x04000000u, F1, 0},
    [PRU_OP_SUC] = {"suc", PRU_FMT_ALU, 0x06000000u, F1, 0},
    [PRU_OP_LSL] = {"lsl", PRU_FMT_ALU, 0x08000000u, F1, 0},
    [PRU_OP_LSR] = {"lsr", PRU_FMT_ALU, 0x0a000000u, F1, 0},
    [PRU_OP_RSB] = {"rsb", PRU_FMT_ALU, 0x0c000000u, F1, 0},
    [PRU_OP_RSC] = {"rsc", PRU_FMT_ALU, 0x0e000000u, F1, 0},
    [PRU_OP_AND] = {"and", PRU_FMT_ALU, 0x10000000u, F1, 0},
    [PRU_OP_OR] = {"or", PRU_FMT_ALU, 0x12000000u, F1, 0},
    [PRU_OP_XOR] = {"xor", PRU_FMT_ALU, 0x14000000u, F1, 0},
    [PRU_OP_NOT] = {"not", PRU_FMT_ALU, 0x16000000u, F1, 0},
    [PRU_OP_MIN] = {"min", PRU_FMT_ALU, 0x18000000u, F1, 0},
    [PRU_OP_MAX] = {"max", PRU_FMT_ALU, 0x1a000000u, F1, 0},
    [PRU_OP_CLR] = {"clr", PRU_FMT_ALU, 0x1c000000u, F1, 0},
    [PRU_OP_SET] = {"set", PRU_FMT_ALU, 0x1e000000u, F1, 0},
    [PRU_OP_NOP0] = {"nop0", PRU_FMT_ALU, 0xa0000000u, F1, 3},
    [PRU_OP_NOP1] = {"nop1", PRU_FMT_ALU, 0xa2000000u, F1, 3},
    [PRU_OP_NOP2] = {"nop2", PRU_FMT_ALU, 0xa4000000u, F1, 3},
    [PRU_OP_NOP3] = {"nop3", PRU_FMT_ALU, 0xa6000000u, F1, 3},
    [PRU_OP_NOP4] = {"nop4", PRU_FMT_ALU, 0xa8000000u, F1, 3},
    [PRU_OP_NOP5] = {"nop5", PRU_FMT_ALU, 0xaa000000u, F1, 3},
    [PRU_OP_NOP6] = {"nop6", PRU_FMT_ALU, 0xac000000u, F1, 3},
    [PRU_OP_NOP7] = {"nop7", PRU_FMT_ALU, 0xae000000u, F1, 3},
    [PRU_OP_NOP8] = {"nop8", PRU_FMT_ALU, 0xb0000000u, F1, 3},
    [PRU_OP_NOP9] = {"nop9", PRU_FMT_ALU, 0xb2000000u, F1, 3},
    [PRU_OP_NOPA] = {"nopa", PRU_FMT_ALU, 0xb4000000u, F1, 3},
    [PRU_OP_NOPB] = {"nopb", PRU_FMT_ALU, 0xb6000000u, F1, 3},
    [PRU_OP_NOPC] = {"nopc", PRU_FMT_ALU, 0xb8000000u, F1, 3},
    [PRU_OP_NOPD] = {"nopd", PRU_FMT_ALU, 0xba000000u, F1, 3},
    [PRU_OP_NOPE] = {"nope", PRU_FMT_ALU, 0xbc000000u, F1, 3},
    [PRU_OP_NOPF] = {"nopf", PRU_FMT_ALU, 0xbe000000u, F1, 3},
    [PRU_OP_JMP] = {"jmp", PRU_FMT_JMP, 0x20000000u, F1 | 0xffu, 0},
    [PRU_OP_JAL] = {"jal", PRU_FMT_JAL, 0x22000000u, F1, 0},
    /* LDI: bit 24 is always 0 */
    [PRU_OP_LDI] = {"ldi", PRU_FMT_LDI, 0x24000000u, 0xff000000u, 0},
    [PRU_OP_LMBD] = {"lmbd", PRU_FMT_ALU, 0x26000000u, F1, 1},
    [PRU_OP_HALT] = {"halt", PRU_FMT_NONE, 0x2a000000u, 0xffffffffu, 1},
    /* MVIx: bits 20:18 zero, size in 17:16 */
    [PRU_OP_MVIB] = {"mvib", PRU_FMT_MVI, 0x2c000000u, F1 | 0x001f0000u, 1},
    [PRU_OP_MVIW] = {"mviw", PRU_FMT_MVI, 0x2c010000u, F1 | 0x001f0000u, 1},
    [PRU_OP_MVID] = {"mvid", PRU_FMT_MVI, 0x2c020000u, F1 | 0x001f0000u, 1},
    /* XFR: bits 24:23 kind, bit 14 S */
    [PRU_OP_XIN] = {"xin", PRU_FMT_XFR, 0x2e800000u, 0xff804000u, 2},
    [PRU_OP_XOUT] = {"xout", PRU_FMT_XFR, 0x2f000000u, 0xff804000u, 2},
    [PRU_OP_XCHG] = {"xchg", PRU_FMT_XFR, 0x2f800000u, 0xff804000u, 2},
    [PRU_OP_SXIN] = {"sxin", PRU_FMT_XFR, 0x2e804000u, 0xff804000u, 3},
    [PRU_OP_SXOUT] = {"sxout", PRU_FMT_XFR, 0x2f004000u, 0xff804000u, 3},
    [PRU_OP_SXCHG] = {"sxchg", PRU_FMT_XFR, 0x2f804000u, 0xff804000u, 3},
    /* LOOP: bit 15 ILOOP, bits 14:8 zero */
    [PRU_OP_LOOP] = {"loop", PRU_FMT_LOOP, 0x30000000u, F1 | 0xff00u, 3},
    [PRU_OP_ILOOP] = {"iloop", PRU_FMT_LOOP, 0x30008000u, F1 | 0xff00u, 3},
    /* SLP: only bit 23 (wake on event) is free */
    [PRU_OP_SLP] = {"slp", PRU_FMT_SLP, 0x3e000000u, 0xff7fffffu, 1},
    [PRU_OP_QBGT] = {"qbgt", PRU_FMT_QB, 0x60000000u, F4, 0},
    [PRU_OP_QBGE] = {"qbge", PRU_FMT_QB, 0x70000000u, F4, 0},
    [PRU_OP_QBLT] = {"qblt", PRU_FMT_QB, 0x48000000u, F4, 0},
    [PRU_OP_QBLE] = {"qble", PRU_FMT_QB, 0x58000000u, F4, 0},
    [PRU_OP_QBEQ] = {"qbeq", PRU_FMT_QB, 0x50000000u, F4, 0},
    [PRU_OP_QBNE] = {"qbne", PRU_FMT_QB, 0x68000000u, F4, 0},
    [PRU_OP_QBA] = {"qba", PRU_FMT_QBA, 0x78000000u, F4, 0},
    [PRU_OP_QBBS] = {"qbbs", PRU_FMT_QBB, 0xd0000000u, F4, 0},
    [PRU_OP_QBBC] = {"qbbc", PRU_FMT_QBB, 0xc8000000u, F4, 0},
    [PRU_OP_SBCO] = {"sbco", PRU_FMT_BURST, 0x80000000u, F6, 0},
    [PRU_OP_LBCO] = {"lbco", PRU_FMT_BURST, 0x90000000u, F6, 0},
    [PRU_OP_SBBO] = {"sbbo", PRU_FMT_BURST, 0xe0000000u, F6, 0},
    [PRU_OP_LBBO] = {"lbbo", PRU_FMT_BURST, 0xf0000000u, F6, 0},
};

static uint32_t bits(uint32_t w, unsigned hi, unsigned lo) {
    return (w >> lo) & ((1u << (hi - lo + 1)) - 1u);
}

static int find_op(uint32_t word) {
    for (int op = 0; op < PRU_OP_COUNT; op++) {
        if ((word & pru_optable[op].mask) == pru_optable[op].match) {
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
    }
    return -1;
}

uint32_t pru_encode(const struct pru_insn *in) {
    if (in->op >= PRU_OP_COUNT) {
        return 0;
    }
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
