/*
 * pru_isa.h - the one PRU core V3 instruction table.
 *
 * The assembler encodes from it, the disassembler/tracer prints from it and
 * the emulator decodes from it. Encodings: docs/pru-facts.md §1.
 *
 * A PRU instruction is one 32-bit word. pru_decode() turns a word into a
 * struct pru_insn; pru_encode() is its exact inverse for every word that
 * decodes (encode(decode(w)) == w), so the two can be tested against each
 * other over the whole word space.
 */
#ifndef PRU_ISA_H
#define PRU_ISA_H

#include <stddef.h>
#include <stdint.h>

/* Field selectors of an 8-bit register operand: (sel << 5) | reg. */
enum pru_sel {
    PRU_SEL_B0 = 0,
    PRU_SEL_B1 = 1,
    PRU_SEL_B2 = 2,
    PRU_SEL_B3 = 3,
    PRU_SEL_W0 = 4,
    PRU_SEL_W1 = 5,
    PRU_SEL_W2 = 6,
    PRU_SEL_R = 7, /* whole 32-bit register */
};

/* Every machine instruction (pseudo-instructions such as MOV, CALL, WBS,
 * ZERO live in the assembler and expand to these). */
enum pru_op {
    /* format 1, bits 28:25 = ALU op */
    PRU_OP_ADD,
    PRU_OP_ADC,
    PRU_OP_SUB,
    PRU_OP_SUC,
    PRU_OP_LSL,
    PRU_OP_LSR,
    PRU_OP_RSB,
    PRU_OP_RSC,
    PRU_OP_AND,
    PRU_OP_OR,
    PRU_OP_XOR,
    PRU_OP_NOT,
    PRU_OP_MIN,
    PRU_OP_MAX,
    PRU_OP_CLR,
    PRU_OP_SET,
    /* format "101" (pasm V3): NOP0..NOPF, ALU layout */
    PRU_OP_NOP0,
    PRU_OP_NOP1,
    PRU_OP_NOP2,
    PRU_OP_NOP3,
    PRU_OP_NOP4,
    PRU_OP_NOP5,
    PRU_OP_NOP6,
    PRU_OP_NOP7,
    PRU_OP_NOP8,
    PRU_OP_NOP9,
    PRU_OP_NOPA,
    PRU_OP_NOPB,
    PRU_OP_NOPC,
    PRU_OP_NOPD,
    PRU_OP_NOPE,
    PRU_OP_NOPF,
    /* format 2 (SCAN is core V1 only and has no place in a V3 table) */
    PRU_OP_JMP,
    PRU_OP_JAL,
    PRU_OP_LDI,
    PRU_OP_LMBD,
    PRU_OP_HALT,
    PRU_OP_MVIB,
    PRU_OP_MVIW,
    PRU_OP_MVID,
    PRU_OP_XIN,
    PRU_OP_XOUT,
    PRU_OP_XCHG,
    PRU_OP_SXIN,
    PRU_OP_SXOUT,
    PRU_OP_SXCHG,
    PRU_OP_LOOP,
    PRU_OP_ILOOP,
    PRU_OP_SLP,
    /* format 4 */
    PRU_OP_QBGT,
    PRU_OP_QBGE,
    PRU_OP_QBLT,
    PRU_OP_QBLE,
    PRU_OP_QBEQ,
    PRU_OP_QBNE,
    PRU_OP_QBA,
    /* format 5 */
    PRU_OP_QBBS,
    PRU_OP_QBBC,
    /* format 6 */
    PRU_OP_SBCO,
    PRU_OP_LBCO,
    PRU_OP_SBBO,
    PRU_OP_LBBO,
    PRU_OP_COUNT
};

/* Operand layouts. Each op has exactly one. */
enum pru_fmt {
    PRU_FMT_ALU,   /* rd, rs1, op2 (reg or imm8): format 1, NOPn, LMBD */
    PRU_FMT_JMP,   /* op2 (reg or imm16) */
    PRU_FMT_JAL,   /* rd, op2 (reg or imm16) */
    PRU_FMT_LDI,   /* rd, imm16 */
    PRU_FMT_NONE,  /* HALT */
    PRU_FMT_SLP,   /* wake flag (imm 0/1) */
    PRU_FMT_MVI,   /* dst, src with pointer modes */
    PRU_FMT_XFR,   /* device, rx/start byte, length code */
    PRU_FMT_LOOP,  /* end offset, count (reg or imm 1..256) */
    PRU_FMT_QB,    /* branch offset, rs1, op2 (reg or imm8) */
    PRU_FMT_QBA,   /* branch offset */
    PRU_FMT_QBB,   /* branch offset, rs1, bit (reg or imm) */
    PRU_FMT_BURST, /* rx/start byte, base reg or Cn, offset (reg or imm8), length code */
};

/* MVIx addressing modes of each side. */
enum pru_mvi_mode {
    PRU_MVI_DIRECT = 0,  /* rX */
    PRU_MVI_IND = 1,     /* *rX */
    PRU_MVI_POSTINC = 2, /* *rX++ */
    PRU_MVI_PREDEC = 3,  /* *--rX */
};

/* One row of the table. */
struct pru_opinfo {
    const char *name; /* lower-case mnemonic as pasm spells it */
    enum pru_fmt fmt;
    uint32_t match;   /* value of the fixed bits */
    uint32_t mask;    /* which bits are fixed by the opcode */
    uint8_t min_core; /* lowest pasm core version (-V) that has it */
};

extern const struct pru_opinfo pru_optable[PRU_OP_COUNT];

/*
 * A decoded instruction. Which members are meaningful depends on the op's
 * format (see enum pru_fmt); the others are zero after pru_decode().
 */
struct pru_insn {
    uint8_t op;        /* enum pru_op */
    uint8_t rd, rdsel; /* destination register/field (ALU, JAL, LDI, MVI dst) */
    uint8_t rs1, rs1sel;
    uint8_t io; /* 1: op2 is the immediate `imm`; 0: op2 is rs2/rs2sel */
    uint8_t rs2, rs2sel;
    uint16_t imm;     /* imm8 / imm16 / bit number / LOOP count-1 / burst offset */
    int16_t broff;    /* QBxx, QBBx: branch offset in words, -512..511 */
    uint8_t loop_end; /* LOOP: end address - LOOP address, 0..255 */
    uint8_t len;      /* burst/XFR length code: 0..123 = bytes-1, 124..127 = r0.b0..b3 */
    uint8_t rx;       /* burst/XFR register number */
    uint8_t rxbyte;   /* burst/XFR start byte 0..3 */
    uint8_t base;     /* xBBO base register, xBCO constant-table index */
    uint8_t dev;      /* XFR device ID */
    uint8_t flag;     /* ILOOP: 1; SLP: wake-on-event; (S-XFR is its own op) */
    uint8_t mvi_size; /* MVI: 0 byte, 1 word, 2 dword */
    uint8_t mvi_dmode, mvi_smode; /* enum pru_mvi_mode */
};

/* Decode a word. Returns 0, or -1 if it is no valid V3 instruction. */
int pru_decode(uint32_t word, struct pru_insn *out);

/* Encode; the inverse of pru_decode(). Fields are masked to their widths. */
uint32_t pru_encode(const struct pru_insn *in);

/* Look up a mnemonic (case-insensitive). Returns the op or -1. */
int pru_op_lookup(const char *name);

/* Byte count of a burst/XFR length code given R0 (codes 124..127 read R0.b0..b3). */
static inline unsigned pru_len_bytes(unsigned len_code, uint32_t r0) {
    return len_code < 124 ? len_code + 1 : (r0 >> (8 * (len_code - 124))) & 0xff;
}

/* Field geometry of a selector: bit offset and width. */
static inline unsigned pru_sel_shift(unsigned sel) {
    static const uint8_t shift[8] = {0, 8, 16, 24, 0, 8, 16, 0};
    return shift[sel & 7];
}
static inline unsigned pru_sel_width(unsigned sel) {
    static const uint8_t width[8] = {8, 8, 8, 8, 16, 16, 16, 32};
    return width[sel & 7];
}
static inline uint32_t pru_sel_mask(unsigned sel) {
    unsigned w = pru_sel_width(sel);
    return w == 32 ? 0xffffffffu : ((1u << w) - 1u);
}

/* Register operand text such as "r2.w1" (buf of at least 8 bytes). */
const char *pru_reg_name(unsigned reg, unsigned sel, char *buf);

/*
 * Disassemble one word at word address pc into buf, in pasm syntax with
 * branch/jump/loop targets as absolute word addresses. Returns the length
 * written (like snprintf) or, for an invalid word, writes ".codeword 0x..."
 * and returns a negative length.
 */
int pru_disasm(uint32_t word, uint32_t pc, char *buf, size_t size);

#endif
