/*
 * Check suite: the fast loop's predecoded kinds against the general path.
 *
 * The fast loop (pru_params.fast_loop, exec.c run_fast) runs register-only
 * instructions through kinds chosen at predecode time by operand shape:
 * whole registers, byte and word fields, an immediate op2 (core_priv.h,
 * PD_ADD32 ...). With fast_loop = 0 every instruction goes through the
 * general path (exec_simple() on the instruction's own op), which reads and
 * writes every operand through its shift and mask. Here every register-only
 * op runs with every operand shape (destination, rs1 and op2 each a whole
 * register or a random field, op2 also an immediate) on random register
 * values, fields, aliasing and carry, once each way: both must leave the
 * same registers, carry, PC, counts and fault. The same for the MVI loads
 * and the fixed-length XIN/XOUT/ZERO/FILL the fast loop runs in kinds of
 * their own (PD_MVI_LD, PD_XFR_FIXED), with random scratch pads and
 * register shifts, whose banks must then agree too.
 */
#include "check_run.h"
#include "core_priv.h" /* the scratch-pad banks, set and compared in place */
#include "core_test_util.h"
#include "test_rng.h"

#include <stdbool.h>
#include <stdio.h>

#define CARRY_REG 29u /* `add r29, r29, r29` sets the carry first */
#define NREGS     32u /* r0..r30 random but r29 (the carry's); r31: the inputs */
#define PROG_LEN  8u  /* carry set-up, the instruction, halts to branch to */

static uint64_t rng_state;

static uint32_t rnd(void) {
    return test_rng_next(&rng_state);
}

/* A register value with the edge cases of bytes and words likely. */
static uint32_t rnd_value(void) {
    static const uint8_t edge[] = {0x00, 0xff, 0x7f, 0x80, 0x01, 0xfe};
    if (rnd() % 2)
        return rnd();
    uint32_t v = 0;
    for (unsigned b = 0; b < 4; b++)
        v |= (uint32_t)(rnd() % 3 ? edge[rnd() % sizeof edge] : rnd() & 0xffu) << (8 * b);
    return v;
}

/* A register: one of the first four often, so that operands alias; now
 * and then R30 (a destination tells the pins) or, as a source, R31 (the
 * inputs: PD_R31_READ). */
static unsigned rnd_reg(bool src) {
    if (rnd() % 8 == 0)
        return src && rnd() % 2 ? 31 : 30;
    unsigned r = rnd() % 2 ? rnd() % 4 : rnd() % 29;
    return r;
}

/* An operand byte (core_test_util.h): a whole register, or a random field. */
static unsigned operand_of(bool whole, bool src) {
    unsigned sel = whole ? PRU_SEL_R : rnd() % PRU_SEL_R; /* b0..b3, w0..w2 */
    return (sel << 5) | rnd_reg(src);
}
#define operand(whole) operand_of((whole), true)
#define dest(whole)    operand_of((whole), false)

static uint8_t rnd_imm8(void) {
    static const uint8_t edge[] = {0, 1, 2, 7, 8, 15, 16, 31, 32, 0x7f, 0x80, 0xff};
    return rnd() % 2 ? (uint8_t)rnd() : edge[rnd() % sizeof edge];
}

/* How an operand is built: whole register, field, or (op2 only) immediate. */
enum shape { WHOLE, FIELD, IMM };

/* One random case of the instruction word `w` at PC 1 (CASE_*). */
struct kcase {
    uint32_t word;
    uint32_t regs[NREGS];
    int carry;
    /* XFR cases: CFG SPP, the shift parameters, the banks' bytes */
    bool spad;
    uint32_t spp;
    int shift_sub, shift_fill;
    uint8_t bank[3][SPAD_BYTES];
};

#define CFG_SPP_ADDR 0x4A326034u /* AM335x PRU-ICSS CFG + 0x34 */

/* The value of field `opnd` (an operand byte) in regs. */
static uint32_t field_of(const uint32_t *regs, unsigned opnd) {
    unsigned sel = opnd >> 5;
    return (regs[opnd & 31u] >> pru_sel_shift(sel)) & pru_sel_mask(sel);
}

/* Sets field `opnd` of regs to v. */
static void set_field(uint32_t *regs, unsigned opnd, uint32_t v) {
    unsigned sel = opnd >> 5, sh = pru_sel_shift(sel);
    uint32_t m = pru_sel_mask(sel);
    regs[opnd & 31u] = (regs[opnd & 31u] & ~(m << sh)) | ((v & m) << sh);
}

/* Runs the case with the fast loop on or off; returns the core (halted
 * or faulted). */
static struct pru_core *run_case(const struct kcase *k, int fast_loop) {
    struct pru_params p;
    pru_params_default(&p);
    p.fast_loop = fast_loop;
    p.xfr_shift_sub = k->shift_sub;
    p.xfr_shift_fill = k->shift_fill;
    uint32_t w[PROG_LEN];
    w[0] = alu(PRU_OP_ADD, R(CARRY_REG), R(CARRY_REG), R(CARRY_REG));
    w[1] = k->word;
    for (unsigned i = 2; i < PROG_LEN; i++)
        w[i] = halt();
    struct pru_core *c = core_loaded(&p, w, sizeof w / sizeof w[0]);
    if (k->spad) {
        ck_assert_int_eq(pru_host_write32(c, CFG_SPP_ADDR, k->spp), 0);
        memcpy(c->spad, k->bank, sizeof k->bank);
    }
    pru_start(c);
    for (unsigned i = 0; i < 31; i++)
        pru_set_reg(c, i, k->regs[i]);
    pru_set_reg(c, CARRY_REG, k->carry ? 0x80000000u : 0);
    pru_set_inputs(c, k->regs[31]);
    enum pru_stop s = pru_run(c, 100);
    ck_assert_msg(s == PRU_STOP_HALT || s == PRU_STOP_FAULT, "word 0x%08x: stop %d", k->word, s);
    return c;
}

static unsigned compared;

static void check_case(const struct kcase *k) {
    struct pru_core *fast = run_case(k, 1);
    struct pru_core *gen = run_case(k, 0);
    char dis[96];
    pru_disasm(k->word, 1, dis, sizeof dis);
    for (unsigned i = 0; i < 31; i++)
        ck_assert_msg(pru_reg(fast, i) == pru_reg(gen, i),
                      "%s (0x%08x, carry %d): r%u fast 0x%08x, general 0x%08x", dis, k->word,
                      k->carry, i, pru_reg(fast, i), pru_reg(gen, i));
    ck_assert_msg(pru_carry(fast) == pru_carry(gen), "%s: carry fast %d, general %d", dis,
                  pru_carry(fast), pru_carry(gen));
    ck_assert_msg(pru_pc(fast) == pru_pc(gen), "%s: pc fast %u, general %u", dis, pru_pc(fast),
                  pru_pc(gen));
    ck_assert_int_eq(pru_cycles(fast), pru_cycles(gen));
    ck_assert_uint_eq(pru_instructions(fast), pru_instructions(gen));
    ck_assert_int_eq(pru_get_fault(fast)->cause, pru_get_fault(gen)->cause);
    for (unsigned b = 0; b < 3; b++)
        ck_assert_msg(memcmp(fast->spad[b], gen->spad[b], SPAD_BYTES) == 0,
                      "%s (0x%08x): scratch-pad bank %u differs", dis, k->word, b);
    pru_core_free(fast);
    pru_core_free(gen);
    compared++;
}

static void rnd_regs(struct kcase *k) {
    memset(k, 0, sizeof *k);
    for (unsigned i = 0; i < NREGS; i++)
        k->regs[i] = rnd_value();
    k->carry = (int)(rnd() & 1u);
}

#define REPEAT 24u /* random cases per op and operand shape */

START_TEST(alu_kinds_match_general_path) {
    rng_state = 0x9E3779B97F4A7C15ull;
    compared = 0;
    for (unsigned o = 0; o < N_ALU_OPS; o++)
        for (unsigned shape = 0; shape < 12; shape++)
            for (unsigned n = 0; n < REPEAT; n++) {
                enum shape rd = shape & 1u ? FIELD : WHOLE;
                enum shape rs1 = shape & 2u ? FIELD : WHOLE;
                enum shape op2 = (enum shape)(shape >> 2);
                struct kcase k;
                rnd_regs(&k);
                unsigned d = dest(rd == WHOLE), s1 = operand(rs1 == WHOLE);
                if (rd == rs1 && rnd() % 4 == 0)
                    s1 = d; /* sub r7.b0, r7.b0, 1 */
                k.word = op2 == IMM ? alui(alu_ops[o], d, s1, rnd_imm8())
                                    : alu(alu_ops[o], d, s1, operand(op2 == WHOLE));
                check_case(&k);
            }
    ck_assert_uint_eq(compared, N_ALU_OPS * 12u * REPEAT);
}
END_TEST

START_TEST(ldi_kinds_match_general_path) {
    rng_state = 0xD1B54A32D192ED03ull;
    for (unsigned n = 0; n < 8u * REPEAT; n++) {
        struct kcase k;
        rnd_regs(&k);
        k.word = ldi(dest(n % 2 == 0), rnd() & 0xffffu);
        check_case(&k);
    }
}
END_TEST

START_TEST(branch_kinds_match_general_path) {
    rng_state = 0x2545F4914F6CDD1Dull;
    for (unsigned o = 0; o < N_QB_OPS; o++)
        for (unsigned shape = 0; shape < 6; shape++)
            for (unsigned n = 0; n < REPEAT; n++) {
                enum shape rs1 = shape & 1u ? FIELD : WHOLE;
                enum shape op2 = (enum shape)(shape >> 1);
                struct kcase k;
                rnd_regs(&k);
                unsigned s1 = operand(rs1 == WHOLE);
                int off = 1 + (int)(rnd() % (PROG_LEN - 2)); /* to one of the halts */
                if (op2 == IMM) {
                    k.word = qbi(qb_ops[o], off, s1, rnd_imm8());
                } else {
                    unsigned s2 = operand(op2 == WHOLE);
                    if (rnd() % 4 == 0) /* equal operands */
                        set_field(k.regs, s2, field_of(k.regs, s1));
                    k.word = qb(qb_ops[o], off, s1, s2);
                }
                check_case(&k);
            }
    /* QBA, JMP and JAL, immediate and register targets */
    for (unsigned n = 0; n < 8u * REPEAT; n++) {
        struct kcase k;
        rnd_regs(&k);
        unsigned target = 2 + rnd() % (PROG_LEN - 2);
        unsigned t = operand(n % 3 == 0);
        set_field(k.regs, t, target);
        switch (n % 5) {
        case 0:
            k.word = qba((int)target - 1);
            break;
        case 1:
            k.word = jmpi(target);
            break;
        case 2:
            k.word = jmpr(t);
            break;
        case 3:
            k.word = jali(dest(n % 2 == 0), target);
            break;
        default:
            k.word = enc((struct pru_insn){.op = PRU_OP_JAL,
                                           .rd = (uint8_t)(rnd_reg(false)),
                                           .rdsel = (uint8_t)(rnd() % 8),
                                           .rs2 = t & 31,
                                           .rs2sel = t >> 5});
            break;
        }
        check_case(&k);
    }
}
END_TEST

/* A random byte field (b0..b3) of register reg. */
static unsigned byte_of(unsigned reg) {
    return ((rnd() % 4u) << 5) | reg;
}

/*
 * The firmware's own field forms, which have kinds of their own that read
 * and write bytes and half-words of the register file in place (core_priv.h
 * PD_MINB32I ...), each on many random values: rarely drawn above.
 */
START_TEST(field_forms_match_general_path) {
    rng_state = 0xB5AD4ECEDA1CE2A9ull;
    for (unsigned n = 0; n < 64u * REPEAT; n++) {
        struct kcase k;
        rnd_regs(&k);
        unsigned a = rnd_reg(true), b = rnd_reg(true);
        unsigned fa = byte_of(a), fb = byte_of(b);
        unsigned wa = ((4u + rnd() % 3u) << 5) | a; /* w0..w2 */
        switch (n % 8) {
        case 0: /* xor r30.b0, r30.b0, r11.b1: an MA edge */
            fa = byte_of(30);
            k.word = alu(PRU_OP_XOR, fa, fa, fb);
            break;
        case 1: /* min r11.b0, r12, 2 */
            k.word = alui(PRU_OP_MIN, byte_of(rnd_reg(false)), R(a), rnd_imm8());
            break;
        case 2: /* sub r12, r12, r11.b0 */
            a = rnd_reg(false);
            k.word = alu(PRU_OP_SUB, R(a), rnd() % 2 ? R(a) : R(b), fb);
            break;
        case 3: /* sub r7.b0, r7.b0, 1 */
            fa = byte_of(rnd_reg(false));
            k.word = alui(PRU_OP_SUB, fa, rnd() % 2 ? fa : byte_of(b), rnd_imm8());
            break;
        case 4:
            k.word = qbi(rnd() % 2 ? PRU_OP_QBNE : PRU_OP_QBEQ, 1 + (int)(rnd() % 6), fa,
                         rnd() % 2 ? field_of(k.regs, fa) : rnd_imm8());
            break;
        case 5:
            k.word = qbi(rnd() % 2 ? PRU_OP_QBNE : PRU_OP_QBEQ, 1 + (int)(rnd() % 6), wa,
                         rnd() % 2 ? field_of(k.regs, wa) & 0xffu : rnd_imm8());
            break;
        case 6: /* a byte written over a register of any value */
            k.word = alui(PRU_OP_MIN, fa, R(b), rnd_imm8());
            break;
        default: /* xor r30.b0, r30.b0, r30.b1 and other R30 XORs */
            k.word = alu(PRU_OP_XOR, byte_of(30), byte_of(30), rnd() % 2 ? byte_of(30) : fb);
            break;
        }
        check_case(&k);
    }
}
END_TEST

/* A register-file byte address for an MVI pointer: anywhere, often at the
 * end (R30, R31, a read that wraps past byte 127), now and then far out
 * of the register file (a word or whole-register pointer). */
static uint32_t rnd_rf_addr(void) {
    switch (rnd() % 8) {
    case 0:
        return 116u + rnd() % 12u;
    case 1:
        return rnd_value();
    case 2:
        return 0xfffffffcu + rnd() % 4u; /* + size wraps 32 bits */
    default:
        return rnd() % 128u;
    }
}

/*
 * MVIB/W/D loads through a register pointer (the firmware's `mviw r7.w0,
 * *r1.b0++`: PD_MVI_LD) with every pointer mode and size, the pointer and
 * the destination random fields, aliasing each other now and then, R30 and
 * R31 among them (the general way); and the other MVI forms, which take
 * the general way in both runs.
 */
START_TEST(mvi_loads_match_general_path) {
    rng_state = 0x6A09E667F3BCC909ull;
    for (unsigned n = 0; n < 64u * REPEAT; n++) {
        struct kcase k;
        rnd_regs(&k);
        int op = PRU_OP_MVIB + (int)(rnd() % 3u);
        unsigned smode = 1u + rnd() % 3u; /* IND, POSTINC, PREDEC */
        unsigned dmode = rnd() % 8u == 0 ? rnd() % 4u : PRU_MVI_DIRECT;
        unsigned ptr = rnd() % 2 ? B0(1) : operand_of(rnd() % 3 == 0, false);
        unsigned dst = rnd() % 4 == 0 ? ((rnd() % 8u) << 5) | (ptr & 31u) : dest(rnd() % 4 == 0);
        set_field(k.regs, ptr, rnd_rf_addr());
        if (dmode != PRU_MVI_DIRECT)
            set_field(k.regs, dst, rnd_rf_addr());
        k.word = mvi(op, dmode, dst, smode, ptr);
        check_case(&k);
    }
}
END_TEST

/*
 * XIN/XOUT/SXIN/SXOUT on the three banks and ZERO/FILL, of fixed lengths
 * (PD_XFR_FIXED when within r0..r29), random banks, with and without the
 * register shift (SPP XFR_SHIFT_EN, R0[4:0] small or not, up or down,
 * ZERO/FILL moved or not): shifts past bank register 29 fault. Also XCHG,
 * lengths read from R0 and other devices, the general way in both runs.
 */
START_TEST(xfr_forms_match_general_path) {
    static const int ops[] = {PRU_OP_XIN, PRU_OP_XOUT, PRU_OP_SXIN, PRU_OP_SXOUT, PRU_OP_XCHG};
    rng_state = 0xBB67AE8584CAA73Bull;
    for (unsigned n = 0; n < 64u * REPEAT; n++) {
        struct kcase k;
        rnd_regs(&k);
        k.spad = true;
        k.spp = rnd() % 2 ? 2u : 0u;
        k.shift_sub = (int)(rnd() % 2);
        k.shift_fill = (int)(rnd() % 2);
        for (unsigned b = 0; b < 3; b++)
            for (unsigned i = 0; i < SPAD_BYTES; i++)
                k.bank[b][i] = (uint8_t)rnd();
        if (rnd() % 2)
            k.regs[0] = (k.regs[0] & ~0x1fu) | rnd() % 4u;
        int op = ops[rnd() % 5u];
        unsigned dev = 10u + rnd() % 3u;
        if (rnd() % 6 == 0) {
            op = PRU_OP_XIN;
            dev = rnd() % 4 == 0 ? 9u : 254u + rnd() % 2u;
        }
        unsigned start = rnd() % 120u;
        unsigned len = 1u + rnd() % (rnd() % 8 == 0 ? 128u - start : 120u - start);
        if (rnd() % 4 == 0)
            len = 1u + rnd() % 12u;
        k.word = xfr(op, dev, start, len);
        if (rnd() % 16 == 0) /* the length from r0.b1 */
            k.word = (k.word & ~(0x7fu << 7)) | (125u << 7);
        check_case(&k);
    }
}
END_TEST

Suite *kinds_suite(void) {
    Suite *s = suite_create("core_kinds");
    TCase *t = tcase_create("fast_vs_general");
    tcase_set_timeout(t, 120);
    tcase_add_test(t, alu_kinds_match_general_path);
    tcase_add_test(t, ldi_kinds_match_general_path);
    tcase_add_test(t, branch_kinds_match_general_path);
    tcase_add_test(t, field_forms_match_general_path);
    tcase_add_test(t, mvi_loads_match_general_path);
    tcase_add_test(t, xfr_forms_match_general_path);
    suite_add_tcase(s, t);
    return s;
}

int main(void) {
    return check_run(kinds_suite());
}
