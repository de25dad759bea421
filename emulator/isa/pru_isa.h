/*
 * pru_isa.h - the one PRU core V3 instruction table.
 *
 * The assembler dispatches, gates and encodes from it, the
 * disassembler/tracer prints from it and the emulator decodes from it. Encodings: docs/pru-facts.md
 * §1.
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

/* Fixed-bit masks of the list below. */
#define PRU_M_F1  0xfe000000u /* bits 31:25: format 1 op, format 2 sub-op */
#define PRU_M_F4  0xf8000000u /* bits 31:27: quick branches, bit tests */
#define PRU_M_F6  0xf0000000u /* bits 31:28: burst transfers */
#define PRU_M_XFR 0xff804000u /* bits 31:23 and 14: XFR kind and S */

/*
 * PRU_INSN_LIST(X): every mnemonic pasm 0.87 knows, one row each, and the
 * only place an instruction is named. The op enum, the names, the decoder,
 * the encoder, the disassembler, the assembler's dispatch and core gating
 * and the emulator's decoded kinds all come from it.
 *
 *   X(ID, name, fmt, match, mask, min_core, max_core, form)
 *
 * ID        PRU_OP_<ID>
 * name      the mnemonic as pasm spells it (lower case; any case is accepted)
 * fmt       PRU_FMT_<fmt>: the operand layout in the word; PSEUDO rows have
 *           no word of their own (the assembler expands them into other
 *           rows), and their match/mask are 0
 * match     the value of the fixed bits; mask: which bits are fixed
 * min_core, max_core
 *           the pasm core versions (-V) that have it; the emulator is a V3
 *           core, so only rows with max_core 3 decode
 * form      PRU_FORM_<form>: the assembler's operand syntax
 *
 * Layouts and versions: docs/pru-facts.md §1.1-§1.8; pseudo-instructions
 * §2.9. The rows that only touch registers come first (the emulator's fast
 * loop switches over them), then the other V3 rows, then the rest; NOP0..NOPF
 * stay together.
 */
#define PRU_INSN_LIST(X)                                                                           \
    /* format 1: bits 28:25 are the ALU op */                                                      \
    X(ADD, "add", ALU, 0x00000000u, PRU_M_F1, 0, 3, ALU)                                           \
    X(ADC, "adc", ALU, 0x02000000u, PRU_M_F1, 0, 3, ALU)                                           \
    X(SUB, "sub", ALU, 0x04000000u, PRU_M_F1, 0, 3, ALU)                                           \
    X(SUC, "suc", ALU, 0x06000000u, PRU_M_F1, 0, 3, ALU)                                           \
    X(LSL, "lsl", ALU, 0x08000000u, PRU_M_F1, 0, 3, ALU)                                           \
    X(LSR, "lsr", ALU, 0x0a000000u, PRU_M_F1, 0, 3, ALU)                                           \
    X(RSB, "rsb", ALU, 0x0c000000u, PRU_M_F1, 0, 3, ALU)                                           \
    X(RSC, "rsc", ALU, 0x0e000000u, PRU_M_F1, 0, 3, ALU)                                           \
    X(AND, "and", ALU, 0x10000000u, PRU_M_F1, 0, 3, ALU)                                           \
    X(OR, "or", ALU, 0x12000000u, PRU_M_F1, 0, 3, ALU)                                             \
    X(XOR, "xor", ALU, 0x14000000u, PRU_M_F1, 0, 3, ALU)                                           \
    X(NOT, "not", ALU, 0x16000000u, PRU_M_F1, 0, 3, NOT)                                           \
    X(MIN, "min", ALU, 0x18000000u, PRU_M_F1, 0, 3, ALU)                                           \
    X(MAX, "max", ALU, 0x1a000000u, PRU_M_F1, 0, 3, ALU)                                           \
    X(CLR, "clr", ALU, 0x1c000000u, PRU_M_F1, 0, 3, CLRSET)                                        \
    X(SET, "set", ALU, 0x1e000000u, PRU_M_F1, 0, 3, CLRSET)                                        \
    /* format 101 (pasm V3): NOP0..NOPF, ALU layout */                                             \
    X(NOP0, "nop0", ALU, 0xa0000000u, PRU_M_F1, 3, 3, ALU)                                         \
    X(NOP1, "nop1", ALU, 0xa2000000u, PRU_M_F1, 3, 3, ALU)                                         \
    X(NOP2, "nop2", ALU, 0xa4000000u, PRU_M_F1, 3, 3, ALU)                                         \
    X(NOP3, "nop3", ALU, 0xa6000000u, PRU_M_F1, 3, 3, ALU)                                         \
    X(NOP4, "nop4", ALU, 0xa8000000u, PRU_M_F1, 3, 3, ALU)                                         \
    X(NOP5, "nop5", ALU, 0xaa000000u, PRU_M_F1, 3, 3, ALU)                                         \
    X(NOP6, "nop6", ALU, 0xac000000u, PRU_M_F1, 3, 3, ALU)                                         \
    X(NOP7, "nop7", ALU, 0xae000000u, PRU_M_F1, 3, 3, ALU)                                         \
    X(NOP8, "nop8", ALU, 0xb0000000u, PRU_M_F1, 3, 3, ALU)                                         \
    X(NOP9, "nop9", ALU, 0xb2000000u, PRU_M_F1, 3, 3, ALU)                                         \
    X(NOPA, "nopa", ALU, 0xb4000000u, PRU_M_F1, 3, 3, ALU)                                         \
    X(NOPB, "nopb", ALU, 0xb6000000u, PRU_M_F1, 3, 3, ALU)                                         \
    X(NOPC, "nopc", ALU, 0xb8000000u, PRU_M_F1, 3, 3, ALU)                                         \
    X(NOPD, "nopd", ALU, 0xba000000u, PRU_M_F1, 3, 3, ALU)                                         \
    X(NOPE, "nope", ALU, 0xbc000000u, PRU_M_F1, 3, 3, ALU)                                         \
    X(NOPF, "nopf", ALU, 0xbe000000u, PRU_M_F1, 3, 3, ALU)                                         \
    /* format 2: bits 28:25 are the sub-op */                                                      \
    X(JMP, "jmp", JMP, 0x20000000u, PRU_M_F1 | 0xffu, 0, 3, JMP)                                   \
    X(JAL, "jal", JAL, 0x22000000u, PRU_M_F1, 0, 3, JAL)                                           \
    X(LDI, "ldi", LDI, 0x24000000u, 0xff000000u, 0, 3, LDI) /* bit 24 always 0 */                  \
    X(LMBD, "lmbd", ALU, 0x26000000u, PRU_M_F1, 1, 3, ALU)                                         \
    /* format 4 */                                                                                 \
    X(QBGT, "qbgt", QB, 0x60000000u, PRU_M_F4, 0, 3, QB)                                           \
    X(QBGE, "qbge", QB, 0x70000000u, PRU_M_F4, 0, 3, QB)                                           \
    X(QBLT, "qblt", QB, 0x48000000u, PRU_M_F4, 0, 3, QB)                                           \
    X(QBLE, "qble", QB, 0x58000000u, PRU_M_F4, 0, 3, QB)                                           \
    X(QBEQ, "qbeq", QB, 0x50000000u, PRU_M_F4, 0, 3, QB)                                           \
    X(QBNE, "qbne", QB, 0x68000000u, PRU_M_F4, 0, 3, QB)                                           \
    X(QBA, "qba", QBA, 0x78000000u, PRU_M_F4, 0, 3, QBA)                                           \
    /* format 5 */                                                                                 \
    X(QBBS, "qbbs", QBB, 0xd0000000u, PRU_M_F4, 0, 3, QBB)                                         \
    X(QBBC, "qbbc", QBB, 0xc8000000u, PRU_M_F4, 0, 3, QBB)                                         \
    /* format 2, the rest */                                                                       \
    X(HALT, "halt", NONE, 0x2a000000u, 0xffffffffu, 1, 3, NONE)                                    \
    /* MVIx: bits 20:18 zero, size in 17:16 */                                                     \
    X(MVIB, "mvib", MVI, 0x2c000000u, PRU_M_F1 | 0x001f0000u, 1, 3, MVI)                           \
    X(MVIW, "mviw", MVI, 0x2c010000u, PRU_M_F1 | 0x001f0000u, 1, 3, MVI)                           \
    X(MVID, "mvid", MVI, 0x2c020000u, PRU_M_F1 | 0x001f0000u, 1, 3, MVI)                           \
    X(XIN, "xin", XFR, 0x2e800000u, PRU_M_XFR, 2, 3, XFR)                                          \
    X(XOUT, "xout", XFR, 0x2f000000u, PRU_M_XFR, 2, 3, XFR)                                        \
    X(XCHG, "xchg", XFR, 0x2f800000u, PRU_M_XFR, 2, 3, XFR)                                        \
    X(SXIN, "sxin", XFR, 0x2e804000u, PRU_M_XFR, 3, 3, XFR)                                        \
    X(SXOUT, "sxout", XFR, 0x2f004000u, PRU_M_XFR, 3, 3, XFR)                                      \
    X(SXCHG, "sxchg", XFR, 0x2f804000u, PRU_M_XFR, 3, 3, XFR)                                      \
    /* LOOP: bit 15 ILOOP, bits 14:8 zero */                                                       \
    X(LOOP, "loop", LOOP, 0x30000000u, PRU_M_F1 | 0xff00u, 3, 3, LOOP)                             \
    X(ILOOP, "iloop", LOOP, 0x30008000u, PRU_M_F1 | 0xff00u, 3, 3, LOOP)                           \
    /* SLP: only bit 23 (wake on event) is free */                                                 \
    X(SLP, "slp", SLP, 0x3e000000u, 0xff7fffffu, 1, 3, SLP)                                        \
    /* format 6 */                                                                                 \
    X(SBCO, "sbco", BURST, 0x80000000u, PRU_M_F6, 0, 3, BURST_CO)                                  \
    X(LBCO, "lbco", BURST, 0x90000000u, PRU_M_F6, 0, 3, BURST_CO)                                  \
    X(SBBO, "sbbo", BURST, 0xe0000000u, PRU_M_F6, 0, 3, BURST_BO)                                  \
    X(LBBO, "lbbo", BURST, 0xf0000000u, PRU_M_F6, 0, 3, BURST_BO)                                  \
    /* machine instructions of older cores only: no V3 word */                                     \
    X(SCAN, "scan", ALU, 0x28000000u, PRU_M_F1, 1, 1, SCAN) /* format 2 sub-op 4 */                \
    X(LFC, "lfc", PSEUDO, 0, 0, 0, 0, NONE)                 /* V0 (legacy core) */                 \
    X(STC, "stc", PSEUDO, 0, 0, 0, 0, NONE)                 /* V0 (legacy core) */                 \
    /* pseudo-instructions (docs/pru-facts.md §2.9) */                                            \
    X(MOV, "mov", PSEUDO, 0, 0, 0, 3, MOV)                                                         \
    X(CALL, "call", PSEUDO, 0, 0, 0, 3, CALL)                                                      \
    X(RET, "ret", PSEUDO, 0, 0, 0, 3, RET)                                                         \
    X(WBS, "wbs", PSEUDO, 0, 0, 0, 3, WAIT)                                                        \
    X(WBC, "wbc", PSEUDO, 0, 0, 0, 3, WAIT)                                                        \
    X(ZERO, "zero", PSEUDO, 0, 0, 1, 3, ZERO_FILL)                                                 \
    X(FILL, "fill", PSEUDO, 0, 0, 2, 3, ZERO_FILL)

/* Every row of PRU_INSN_LIST. */
enum pru_op {
#define PRU_X_ENUM(id, name, fmt, match, mask, min_core, max_core, form) PRU_OP_##id,
    PRU_INSN_LIST(PRU_X_ENUM)
#undef PRU_X_ENUM
        PRU_OP_COUNT
};

/* Operand layouts in the word. Each row has exactly one. */
enum pru_fmt {
    PRU_FMT_ALU,    /* rd, rs1, op2 (reg or imm8): format 1, NOPn, LMBD, SCAN */
    PRU_FMT_JMP,    /* op2 (reg or imm16) */
    PRU_FMT_JAL,    /* rd, op2 (reg or imm16) */
    PRU_FMT_LDI,    /* rd, imm16 */
    PRU_FMT_NONE,   /* HALT */
    PRU_FMT_SLP,    /* wake flag (imm 0/1) */
    PRU_FMT_MVI,    /* dst, src with pointer modes */
    PRU_FMT_XFR,    /* device, rx/start byte, length code */
    PRU_FMT_LOOP,   /* end offset, count (reg or imm 1..256) */
    PRU_FMT_QB,     /* branch offset, rs1, op2 (reg or imm8) */
    PRU_FMT_QBA,    /* branch offset */
    PRU_FMT_QBB,    /* branch offset, rs1, bit (reg or imm) */
    PRU_FMT_BURST,  /* rx/start byte, base reg or Cn, offset (reg or imm8), length code */
    PRU_FMT_PSEUDO, /* no word of its own */
};

/* The assembler's operand syntax of a row (emulator/asm/asm_insn.c). */
enum pru_form {
    PRU_FORM_ALU,       /* rd, rs1, op2(255) */
    PRU_FORM_NOT,       /* rd, rs1 [, op2(255)] */
    PRU_FORM_CLRSET,    /* rd, rs1, op2 | rd, rs.tN | rd, op2(31) | rd.tN */
    PRU_FORM_LDI,       /* rd, imm16 */
    PRU_FORM_MOV,       /* rd, rs | rd, imm (one or two LDI) */
    PRU_FORM_SCAN,      /* rd, op2(255) */
    PRU_FORM_MVI,       /* dst, src with pointers; AND without */
    PRU_FORM_NONE,      /* no operands */
    PRU_FORM_SLP,       /* 0 | 1 */
    PRU_FORM_BURST_BO,  /* rx, rbase, offset, length */
    PRU_FORM_BURST_CO,  /* rx, cN, offset, length */
    PRU_FORM_XFR,       /* device, rx, length */
    PRU_FORM_ZERO_FILL, /* start, length */
    PRU_FORM_JMP,       /* target */
    PRU_FORM_JAL,       /* rd, target */
    PRU_FORM_CALL,      /* target */
    PRU_FORM_RET,       /* no operands: JMP to the call register */
    PRU_FORM_LOOP,      /* end label, count */
    PRU_FORM_QB,        /* label, rs1, op2(255) */
    PRU_FORM_QBA,       /* label */
    PRU_FORM_QBB,       /* label, rs, bit | label, rs.tN */
    PRU_FORM_WAIT,      /* rs, bit | rs.tN: a bit test branching to itself */
};

/* MVIx addressing modes of each side. */
enum pru_mvi_mode {
    PRU_MVI_DIRECT = 0,  /* rX */
    PRU_MVI_IND = 1,     /* *rX */
    PRU_MVI_POSTINC = 2, /* *rX++ */
    PRU_MVI_PREDEC = 3,  /* *--rX */
};

/* One row of PRU_INSN_LIST. */
struct pru_opinfo {
    const char *name; /* lower-case mnemonic as pasm spells it */
    uint8_t fmt;      /* enum pru_fmt */
    uint8_t form;     /* enum pru_form */
    uint8_t min_core; /* lowest pasm core version (-V) that has it */
    uint8_t max_core; /* highest */
    uint32_t match;   /* value of the fixed bits */
    uint32_t mask;    /* which bits are fixed by the opcode */
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

/* Whether a row has a word on a V3 core (the emulator's instructions). */
static inline int pru_op_decodes(unsigned op) {
    return op < PRU_OP_COUNT && pru_optable[op].fmt != PRU_FMT_PSEUDO &&
           pru_optable[op].max_core >= 3;
}

/* Whether a V3 instruction only reads and writes registers, carry and PC
 * (ALU, NOPn, LMBD, LDI, jumps, quick branches, bit tests). */
static inline int pru_op_register_only(unsigned op) {
    switch (pru_optable[op].fmt) {
    case PRU_FMT_ALU:
    case PRU_FMT_JMP:
    case PRU_FMT_JAL:
    case PRU_FMT_LDI:
    case PRU_FMT_QB:
    case PRU_FMT_QBA:
    case PRU_FMT_QBB:
        return pru_op_decodes(op);
    default:
        return 0;
    }
}

/* Decode a word. Returns 0, or -1 if it is no valid V3 instruction. */
int pru_decode(uint32_t word, struct pru_insn *out);

/* Encode; the inverse of pru_decode(). Fields are masked to their widths. */
uint32_t pru_encode(const struct pru_insn *in);

/* Look up a mnemonic of any row, pseudo-instructions included
 * (case-insensitive). Returns the op or -1. */
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
 * branch/jump/loop targets as absolute word addresses; assembled at pc, the
 * text gives the same word back. An instruction pasm's syntax cannot
 * express (such as a LOOP ending 1 word ahead, MVIx without a pointer, a
 * QBA with stray operand bits) is written ".codeword 0x... // text".
 * Returns the length written (like snprintf) or, for an invalid word,
 * writes ".codeword 0x..." and returns a negative length.
 */
int pru_disasm(uint32_t word, uint32_t pc, char *buf, size_t size);

#endif
