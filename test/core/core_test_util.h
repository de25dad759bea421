/*
 * core_test_util.h - building PRU programs from pru_encode() for the core
 * suites, and running them.
 *
 * Register operands are pasm operand bytes: (sel << 5) | reg, made with
 * R(n), B0(n)..B3(n), W0(n)..W2(n).
 */
#ifndef CORE_TEST_UTIL_H
#define CORE_TEST_UTIL_H

#include "pru_core.h"
#include "pru_isa.h"
#include "test_rng.h"

#include <check.h>
#include <string.h>

#define R(n)  ((7u << 5) | (n))
#define B0(n) ((0u << 5) | (n))
#define B1(n) ((1u << 5) | (n))
#define B2(n) ((2u << 5) | (n))
#define B3(n) ((3u << 5) | (n))
#define W0(n) ((4u << 5) | (n))
#define W1(n) ((5u << 5) | (n))
#define W2(n) ((6u << 5) | (n))

static inline uint32_t enc(struct pru_insn in) {
    return pru_encode(&in);
}

/* ALU (and LMBD, NOPn) with a register or an immediate op2 */
static inline uint32_t alu(int op, unsigned d, unsigned s1, unsigned s2) {
    return enc((struct pru_insn){.op = (uint8_t)op,
                                 .rd = d & 31,
                                 .rdsel = d >> 5,
                                 .rs1 = s1 & 31,
                                 .rs1sel = s1 >> 5,
                                 .rs2 = s2 & 31,
                                 .rs2sel = s2 >> 5});
}
static inline uint32_t alui(int op, unsigned d, unsigned s1, unsigned imm) {
    return enc((struct pru_insn){.op = (uint8_t)op,
                                 .rd = d & 31,
                                 .rdsel = d >> 5,
                                 .rs1 = s1 & 31,
                                 .rs1sel = s1 >> 5,
                                 .io = 1,
                                 .imm = (uint16_t)imm});
}
static inline uint32_t ldi(unsigned d, unsigned imm) {
    return enc(
        (struct pru_insn){.op = PRU_OP_LDI, .rd = d & 31, .rdsel = d >> 5, .imm = (uint16_t)imm});
}
/* MVIB/MVIW/MVID: d and s as R()/B0().. with the pointer modes. */
static inline uint32_t mvi(int op, unsigned dmode, unsigned d, unsigned smode, unsigned s) {
    return enc((struct pru_insn){.op = (uint8_t)op,
                                 .mvi_dmode = (uint8_t)dmode,
                                 .mvi_smode = (uint8_t)smode,
                                 .rd = d & 31,
                                 .rdsel = d >> 5,
                                 .rs1 = s & 31,
                                 .rs1sel = s >> 5,
                                 .mvi_size = (uint8_t)(op - PRU_OP_MVIB)});
}

static inline uint32_t halt(void) {
    return 0x2A000000u;
}
static inline uint32_t slp(int wake) {
    return wake ? 0x3E800000u : 0x3E000000u;
}
static inline uint32_t jmpi(unsigned target) {
    return enc((struct pru_insn){.op = PRU_OP_JMP, .io = 1, .imm = (uint16_t)target});
}
static inline uint32_t jmpr(unsigned s) {
    return enc((struct pru_insn){.op = PRU_OP_JMP, .rs2 = s & 31, .rs2sel = s >> 5});
}
static inline uint32_t jali(unsigned d, unsigned target) {
    return enc((struct pru_insn){
        .op = PRU_OP_JAL, .rd = d & 31, .rdsel = d >> 5, .io = 1, .imm = (uint16_t)target});
}
/* quick branches: offset in words from this instruction */
static inline uint32_t qb(int op, int off, unsigned s1, unsigned s2) {
    return enc((struct pru_insn){.op = (uint8_t)op,
                                 .broff = (int16_t)off,
                                 .rs1 = s1 & 31,
                                 .rs1sel = s1 >> 5,
                                 .rs2 = s2 & 31,
                                 .rs2sel = s2 >> 5});
}
static inline uint32_t qbi(int op, int off, unsigned s1, unsigned imm) {
    return enc((struct pru_insn){.op = (uint8_t)op,
                                 .broff = (int16_t)off,
                                 .rs1 = s1 & 31,
                                 .rs1sel = s1 >> 5,
                                 .io = 1,
                                 .imm = (uint16_t)imm});
}
static inline uint32_t qba(int off) {
    return enc((struct pru_insn){.op = PRU_OP_QBA, .broff = (int16_t)off, .io = 1});
}
static inline uint32_t loopi(unsigned end_off, unsigned count) {
    return enc((struct pru_insn){
        .op = PRU_OP_LOOP, .loop_end = (uint8_t)end_off, .io = 1, .imm = (uint16_t)(count - 1)});
}
static inline uint32_t loopr(unsigned end_off, unsigned s) {
    return enc((struct pru_insn){
        .op = PRU_OP_LOOP, .loop_end = (uint8_t)end_off, .rs2 = s & 31, .rs2sel = s >> 5});
}
/* bursts: rx byte address (4*reg + byte), base register or Cn, imm offset, bytes */
static inline uint32_t burst(int op, unsigned rxaddr, unsigned base, unsigned off, unsigned bytes) {
    return enc((struct pru_insn){.op = (uint8_t)op,
                                 .rx = (uint8_t)(rxaddr / 4),
                                 .rxbyte = (uint8_t)(rxaddr % 4),
                                 .base = (uint8_t)base,
                                 .io = 1,
                                 .imm = (uint16_t)off,
                                 .len = (uint8_t)(bytes - 1)});
}
/* burst with a register offset and a length code (124..127 = r0.b0..b3) */
static inline uint32_t burstr(int op, unsigned rxaddr, unsigned base, unsigned offreg,
                              unsigned lencode) {
    return enc((struct pru_insn){.op = (uint8_t)op,
                                 .rx = (uint8_t)(rxaddr / 4),
                                 .rxbyte = (uint8_t)(rxaddr % 4),
                                 .base = (uint8_t)base,
                                 .rs2 = offreg & 31,
                                 .rs2sel = offreg >> 5,
                                 .len = (uint8_t)lencode});
}
static inline uint32_t xfr(int op, unsigned dev, unsigned rxaddr, unsigned bytes) {
    return enc((struct pru_insn){.op = (uint8_t)op,
                                 .dev = (uint8_t)dev,
                                 .rx = (uint8_t)(rxaddr / 4),
                                 .rxbyte = (uint8_t)(rxaddr % 4),
                                 .len = (uint8_t)(bytes - 1)});
}
/* mov r, imm32 as pasm does it (two LDIs) */
static inline void mov32(uint32_t *w, unsigned *n, unsigned reg, uint32_t v) {
    w[(*n)++] = ldi(W2(reg), v >> 16);
    w[(*n)++] = ldi(W0(reg), v & 0xffff);
}

/* An AM335x core with parameters p (NULL: the defaults) and the program
 * loaded, not started. */
static inline struct pru_core *core_loaded(const struct pru_params *p, const uint32_t *w,
                                           size_t n) {
    struct pru_core *c = pru_core_new(PRU_SOC_AM335X, p);
    ck_assert_ptr_nonnull(c);
    ck_assert_int_eq(pru_load_image(c, w, n * 4), 0);
    return c;
}

/* A core with the program loaded, started, not yet run. */
static inline struct pru_core *core_with(enum pru_soc soc, const uint32_t *w, size_t n) {
    struct pru_core *c = pru_core_new(soc, NULL);
    ck_assert_ptr_nonnull(c);
    ck_assert_int_eq(pru_load_image(c, w, n * 4), 0);
    pru_start(c);
    return c;
}

/* r0..r29 from the random stream seed: three in four below `small`, the
 * rest any value (the random-program suites start each core alike). */
static inline void seed_regs(struct pru_core *c, uint32_t seed, uint32_t small) {
    uint64_t st = seed | 1u;
    for (unsigned i = 0; i < 30; i++)
        pru_set_reg(c, i, test_rng_next(&st) % 4 ? test_rng_next(&st) % small : test_rng_next(&st));
}

/* Run a program on an AM335x PRU0 until HALT (asserted). */
static inline struct pru_core *run_prog(const uint32_t *w, size_t n) {
    struct pru_core *c = core_with(PRU_SOC_AM335X, w, n);
    ck_assert_int_eq(pru_run(c, 10000000), PRU_STOP_HALT);
    return c;
}

#define RUN(...)                                                                                   \
    ({                                                                                             \
        const uint32_t prog_[] = {__VA_ARGS__};                                                    \
        run_prog(prog_, sizeof prog_ / sizeof prog_[0]);                                           \
    })

/* The register-only ALU ops and the quick branches, for the tests that
 * build random instructions of them. */
static const int alu_ops[] = {PRU_OP_ADD, PRU_OP_ADC, PRU_OP_SUB, PRU_OP_SUC, PRU_OP_RSB,
                              PRU_OP_RSC, PRU_OP_LSL, PRU_OP_LSR, PRU_OP_AND, PRU_OP_OR,
                              PRU_OP_XOR, PRU_OP_NOT, PRU_OP_MIN, PRU_OP_MAX, PRU_OP_CLR,
                              PRU_OP_SET, PRU_OP_LMBD};
static const int qb_ops[] = {PRU_OP_QBGT, PRU_OP_QBGE, PRU_OP_QBLT, PRU_OP_QBLE,
                             PRU_OP_QBEQ, PRU_OP_QBNE, PRU_OP_QBBS, PRU_OP_QBBC};
#define N_ALU_OPS (sizeof alu_ops / sizeof alu_ops[0])
#define N_QB_OPS  (sizeof qb_ops / sizeof qb_ops[0])

/* Cores c[1..n-1] are where c[0] is (registers, carry, pc, cycles,
 * instructions, fault): the same program run different ways, after
 * program prog's chunk that ended at cycle end. */
static inline void same_core_state(struct pru_core *const *c, unsigned n, unsigned prog,
                                   int64_t end) {
    for (unsigned m = 1; m < n; m++) {
        for (unsigned i = 0; i < 32; i++)
            ck_assert_msg(pru_reg(c[0], i) == pru_reg(c[m], i),
                          "program %u, cycle %lld: r%u 0x%08x, mode %u 0x%08x", prog,
                          (long long)end, i, pru_reg(c[0], i), m, pru_reg(c[m], i));
        ck_assert_msg(pru_carry(c[0]) == pru_carry(c[m]), "program %u, cycle %lld: carry %d/%d",
                      prog, (long long)end, pru_carry(c[0]), pru_carry(c[m]));
        ck_assert_msg(pru_pc(c[0]) == pru_pc(c[m]), "program %u, cycle %lld: pc %u/%u", prog,
                      (long long)end, pru_pc(c[0]), pru_pc(c[m]));
        ck_assert_int_eq(pru_cycles(c[0]), pru_cycles(c[m]));
        ck_assert_uint_eq(pru_instructions(c[0]), pru_instructions(c[m]));
        ck_assert_int_eq(pru_get_fault(c[0])->cause, pru_get_fault(c[m])->cause);
    }
}

/* Runs cores c[0..n-1] (one program, run different ways) in the same random
 * chunks of cycles, mostly of at most `most_short`, one in four of at most
 * `most_long` (rnd: the suite's generator), until they stop other than at
 * the limit or max_chunks chunks have run, comparing them after each
 * chunk; the program must have halted. Returns the chunks run. */
static inline unsigned run_same_chunks(struct pru_core *const *c, unsigned n, unsigned prog,
                                       unsigned max_chunks, uint32_t (*rnd)(void),
                                       unsigned most_short, unsigned most_long) {
    unsigned chunks = 0;
    for (; chunks < max_chunks; chunks++) {
        int64_t end = pru_cycles(c[0]) + 1 + rnd() % (rnd() % 4 ? most_short : most_long);
        enum pru_stop s0 = pru_run_until_cycle(c[0], end);
        for (unsigned m = 1; m < n; m++)
            ck_assert_int_eq(pru_run_until_cycle(c[m], end), s0);
        same_core_state(c, n, prog, end);
        if (s0 != PRU_STOP_LIMIT)
            break;
    }
    ck_assert_msg(pru_halted(c[0]), "program %u did not halt (%u chunks)", prog, chunks);
    return chunks;
}

#endif
