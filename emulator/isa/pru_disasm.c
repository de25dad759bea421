/*
 * pru_disasm.c - one instruction word to pasm-syntax text.
 *
 * Targets are printed as absolute word addresses, which pasm accepts in
 * place of labels, so the output reassembles to the same word (checked over
 * the encoding space by test/asm/test_asm_roundtrip.c). Words pasm's syntax
 * cannot produce become ".codeword" lines with the instruction as a comment.
 */
#include "pru_isa.h"

#include <stdarg.h>
#include <stdio.h>

static const char *const sel_suffix[8] = {".b0", ".b1", ".b2", ".b3", ".w0", ".w1", ".w2", ""};

const char *pru_reg_name(unsigned reg, unsigned sel, char *buf) {
    snprintf(buf, 8, "r%u%s", reg & 31u, sel_suffix[sel & 7u]);
    return buf;
}

/* A register-file byte operand (burst/XFR): register plus start byte. */
static const char *rx_name(unsigned reg, unsigned byte, char *buf) {
    return pru_reg_name(reg, byte == 0 ? PRU_SEL_R : byte, buf);
}

static const char *num(unsigned v, char *buf) {
    snprintf(buf, 12, v < 10 ? "%u" : "0x%x", v);
    return buf;
}

static const char *op2_text(const struct pru_insn *in, char *buf) {
    return in->io ? num(in->imm, buf) : pru_reg_name(in->rs2, in->rs2sel, buf);
}

/* Burst/XFR byte count: a number of bytes or the R0 byte that holds it. */
static const char *len_text(unsigned code, char *buf) {
    if (code >= 124) {
        snprintf(buf, 12, "b%u", (code - 124) & 3u);
        return buf;
    }
    snprintf(buf, 12, "%u", code + 1);
    return buf;
}

static const char *target(uint32_t pc, int off, char *buf) {
    return num((pc + (uint32_t)off) & 0xffffu, buf);
}

static const char *mvi_operand(unsigned reg, unsigned sel, unsigned mode, char *buf) {
    static const char *const pre[4] = {"", "*", "*", "*--"};
    char r[8];
    snprintf(buf, 16, "%s%s%s", pre[mode & 3], pru_reg_name(reg, sel, r),
             mode == PRU_MVI_POSTINC ? "++" : "");
    return buf;
}

static int fmt_xfr(const struct pru_insn *in, const char *name, char *buf, size_t size) {
    char a[16], b[16];
    if (in->op == PRU_OP_XIN && in->dev >= 254) {
        /* ZERO and FILL are XIN from the pseudo devices 255 and 254. */
        unsigned addr = in->rx * 4u + in->rxbyte;
        return snprintf(buf, size, "%s %s, %s",
                        pru_optable[in->dev == 255 ? PRU_OP_ZERO : PRU_OP_FILL].name, num(addr, a),
                        len_text(in->len, b));
    }
    return snprintf(buf, size, "%s %u, %s, %s", name, in->dev, rx_name(in->rx, in->rxbyte, a),
                    len_text(in->len, b));
}

static int in_range(uint32_t pc, int off) {
    int64_t t = (int64_t)pc + off;
    return t >= 0 && t <= 0xffff;
}

/*
 * Whether pasm's syntax can produce this decoded word: what its operand
 * checks refuse (docs/pru-facts.md §1.4-§1.7, §2.4) and the pseudo forms it
 * writes in one way only.
 */
static int pasm_can_write(const struct pru_insn *in, uint32_t pc) {
    switch (pru_optable[in->op].fmt) {
    case PRU_FMT_LOOP: /* the end must lie 2..255 words ahead */
        return in->loop_end >= 2 && in_range(pc, in->loop_end);
    case PRU_FMT_MVI: { /* pointers are r1.b0..r1.b3; no pointer at all is an AND */
        int dptr = in->mvi_dmode != PRU_MVI_DIRECT, sptr = in->mvi_smode != PRU_MVI_DIRECT;
        if (!dptr && !sptr)
            return 0;
        if (dptr && (in->rd != 1 || in->rdsel > PRU_SEL_B3))
            return 0;
        return !sptr || (in->rs1 == 1 && in->rs1sel <= PRU_SEL_B3);
    }
    case PRU_FMT_XFR: /* device 0..253, never r31; ZERO/FILL within the register file */
        if (in->dev >= 254) {
            unsigned start = in->rx * 4u + in->rxbyte;
            return in->op == PRU_OP_XIN && in->len < 124 && start + in->len + 1u <= 124;
        }
        return in->rx != 31;
    case PRU_FMT_QBA: /* pasm writes QBA with IO set, immediate 0, rs1 r0.b0 */
        return in->io && in->imm == 0 && in->rs1 == 0 && in->rs1sel == 0 && in_range(pc, in->broff);
    case PRU_FMT_QBB: /* bit numbers 0..31 */
        return (!in->io || in->imm <= 31) && in_range(pc, in->broff);
    case PRU_FMT_QB:
        return in_range(pc, in->broff);
    default:
        return 1;
    }
}

static int write_insn(const struct pru_insn *in, uint32_t pc, char *buf, size_t size);

int pru_disasm(uint32_t word, uint32_t pc, char *buf, size_t size) {
    struct pru_insn in;
    if (pru_decode(word, &in) != 0) {
        return -snprintf(buf, size, ".codeword 0x%08x", word);
    }
    if (pasm_can_write(&in, pc)) {
        return write_insn(&in, pc, buf, size);
    }
    char text[64];
    write_insn(&in, pc, text, sizeof text);
    return snprintf(buf, size, ".codeword 0x%08x // %s", word, text);
}

static int write_insn(const struct pru_insn *insn, uint32_t pc, char *buf, size_t size) {
    struct pru_insn in = *insn;
    const char *name = pru_optable[in.op].name;
    char a[16], b[16], c[16], d[16];
    switch (pru_optable[in.op].fmt) {
    case PRU_FMT_ALU:
        if (in.op == PRU_OP_NOT && in.io && in.imm == 0) {
            return snprintf(buf, size, "%s %s, %s", name, pru_reg_name(in.rd, in.rdsel, a),
                            pru_reg_name(in.rs1, in.rs1sel, b));
        }
        return snprintf(buf, size, "%s %s, %s, %s", name, pru_reg_name(in.rd, in.rdsel, a),
                        pru_reg_name(in.rs1, in.rs1sel, b), op2_text(&in, c));
    case PRU_FMT_JMP:
        return snprintf(buf, size, "%s %s", name, op2_text(&in, a));
    case PRU_FMT_JAL:
        return snprintf(buf, size, "%s %s, %s", name, pru_reg_name(in.rd, in.rdsel, a),
                        op2_text(&in, b));
    case PRU_FMT_LDI:
        return snprintf(buf, size, "%s %s, %s", name, pru_reg_name(in.rd, in.rdsel, a),
                        num(in.imm, b));
    case PRU_FMT_NONE:
        return snprintf(buf, size, "%s", name);
    case PRU_FMT_SLP:
        return snprintf(buf, size, "%s %u", name, in.flag);
    case PRU_FMT_MVI:
        return snprintf(buf, size, "%s %s, %s", name, mvi_operand(in.rd, in.rdsel, in.mvi_dmode, a),
                        mvi_operand(in.rs1, in.rs1sel, in.mvi_smode, b));
    case PRU_FMT_XFR:
        return fmt_xfr(&in, name, buf, size);
    case PRU_FMT_LOOP:
        if (in.io) {
            snprintf(b, sizeof(b), "%u", in.imm + 1u);
        } else {
            pru_reg_name(in.rs2, in.rs2sel, b);
        }
        return snprintf(buf, size, "%s %s, %s", name, target(pc, in.loop_end, a), b);
    case PRU_FMT_QB:
    case PRU_FMT_QBB:
        return snprintf(buf, size, "%s %s, %s, %s", name, target(pc, in.broff, a),
                        pru_reg_name(in.rs1, in.rs1sel, b), op2_text(&in, c));
    case PRU_FMT_QBA:
        return snprintf(buf, size, "%s %s", name, target(pc, in.broff, a));
    case PRU_FMT_BURST: {
        int is_co = pru_optable[in.op].form == PRU_FORM_BURST_CO;
        if (is_co) {
            snprintf(b, sizeof(b), "c%u", in.base);
        } else {
            pru_reg_name(in.base, PRU_SEL_R, b);
        }
        return snprintf(buf, size, "%s %s, %s, %s, %s", name, rx_name(in.rx, in.rxbyte, a), b,
                        op2_text(&in, c), len_text(in.len, d));
    }
    case PRU_FMT_PSEUDO:
        break;
    }
    return snprintf(buf, size, "%s", name);
}
