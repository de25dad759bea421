/*
 * Check suite: semantics and cycle cost of every PRU instruction in the
 * core emulator (docs/pru-facts.md §1 and §3).
 */
#include "check_run.h"
#include "core_test_util.h"

#include <stdlib.h>

#define REG(c, n) pru_reg((c), (n))

START_TEST(add_carry_byte_field) {
    /* r1 = 0xAAF0; add r1.b0, r1.b0, 0x20 -> 0xAA10, carry from bit 8 */
    struct pru_core *c = RUN(ldi(R(1), 0xAAF0), alui(PRU_OP_ADD, B0(1), B0(1), 0x20),
                             alui(PRU_OP_ADC, R(2), R(2), 0), halt());
    ck_assert_uint_eq(REG(c, 1), 0xAA10);
    ck_assert_uint_eq(REG(c, 2), 1); /* old carry added */
    ck_assert_int_eq(pru_carry(c), 0);
    ck_assert_int_eq(pru_cycles(c), 4);
    ck_assert_uint_eq(pru_instructions(c), 4);
    pru_core_free(c);
}
END_TEST

START_TEST(add_carry_word_and_full) {
    uint32_t w[16];
    unsigned n = 0;
    mov32(w, &n, 1, 0xFFFFFFFFu);
    w[n++] = alui(PRU_OP_ADD, R(2), R(1), 1);   /* 0, carry 1 */
    w[n++] = alui(PRU_OP_ADC, R(3), R(3), 5);   /* 6 */
    w[n++] = alui(PRU_OP_ADD, W0(4), W0(1), 1); /* 0xFFFF + 1 -> 0, carry 1 */
    w[n++] = alui(PRU_OP_ADC, W1(5), W0(5), 0); /* 0 + 0 + 1 in w1 -> 0x100 */
    w[n++] = alui(PRU_OP_ADD, B1(6), W0(1), 1); /* 0x10000 truncated to b1 = 0, bit 8 = 0 */
    w[n++] = halt();
    struct pru_core *c = run_prog(w, n);
    ck_assert_uint_eq(REG(c, 2), 0);
    ck_assert_uint_eq(REG(c, 3), 6);
    ck_assert_uint_eq(REG(c, 4), 0);
    ck_assert_uint_eq(REG(c, 5), 0x100);
    ck_assert_uint_eq(REG(c, 6), 0);
    ck_assert_int_eq(pru_carry(c), 0); /* 0x10000: bit 8 clear */
    pru_core_free(c);
}
END_TEST

START_TEST(sub_not_borrow) {
    struct pru_core *c;
    /* 5 - 3: no borrow -> carry 1 */
    c = RUN(ldi(R(1), 5), alui(PRU_OP_SUB, R(2), R(1), 3), halt());
    ck_assert_uint_eq(REG(c, 2), 2);
    ck_assert_int_eq(pru_carry(c), 1);
    pru_core_free(c);
    /* 3 - 5: borrow -> carry 0 */
    c = RUN(ldi(R(1), 3), alui(PRU_OP_SUB, R(2), R(1), 5), halt());
    ck_assert_uint_eq(REG(c, 2), 0xFFFFFFFEu);
    ck_assert_int_eq(pru_carry(c), 0);
    pru_core_free(c);
    /* docs/pru-facts.md §1.3: dest .b0, rs1 = 0x180 (.w0), op2 = 1 -> 0x7F, carry 0 */
    c = RUN(ldi(R(4), 0x180), alui(PRU_OP_SUB, B0(3), W0(4), 1), halt());
    ck_assert_uint_eq(REG(c, 3), 0x7F);
    ck_assert_int_eq(pru_carry(c), 0);
    pru_core_free(c);
    /* byte dest, 0x10 - 0x20 borrows within 8 bits -> 0xF0, carry 0 */
    c = RUN(ldi(R(4), 0x10), alui(PRU_OP_SUB, B1(3), B0(4), 0x20), halt());
    ck_assert_uint_eq(REG(c, 3), 0xF000);
    ck_assert_int_eq(pru_carry(c), 0);
    pru_core_free(c);
}
END_TEST

/*
 * The fast loop runs ADD/SUB/QBNE/QBEQ/QBBS/QBBC on whole registers
 * through their own predecoded kinds (ADD/SUB/QBNE/QBEQ with an immediate
 * op2 through others again); single steps run every instruction
 * through the generic path. Both must give the same registers, carries
 * (captured by ADC r0 after each op) and counts.
 */
static const uint32_t *whole_register_prog(unsigned *n) {
    static uint32_t w[64];
    *n = 0;
    mov32(w, n, 1, 0xFFFFFFFFu);
    mov32(w, n, 2, 1);
    w[(*n)++] = alu(PRU_OP_ADD, R(3), R(1), R(2)); /* 0, carry 1 */
    w[(*n)++] = alui(PRU_OP_ADC, R(20), R(0), 0);
    w[(*n)++] = alui(PRU_OP_ADD, R(4), R(1), 1); /* 0, carry 1 */
    w[(*n)++] = alui(PRU_OP_ADC, R(21), R(0), 0);
    w[(*n)++] = alu(PRU_OP_ADD, R(5), R(2), R(2)); /* 2, carry 0 */
    w[(*n)++] = alui(PRU_OP_ADC, R(22), R(0), 0);
    w[(*n)++] = alu(PRU_OP_SUB, R(6), R(2), R(1)); /* 2, borrow: carry 0 */
    w[(*n)++] = alui(PRU_OP_ADC, R(23), R(0), 0);
    w[(*n)++] = alui(PRU_OP_SUB, R(7), R(1), 1); /* 0xFFFFFFFE, carry 1 */
    w[(*n)++] = alui(PRU_OP_ADC, R(24), R(0), 0);
    w[(*n)++] = alu(PRU_OP_SUB, R(8), R(2), W0(2)); /* 0, carry 1 */
    w[(*n)++] = alui(PRU_OP_ADC, R(25), R(0), 0);
    w[(*n)++] = alui(PRU_OP_SUB, R(16), R(2), 5); /* 0xFFFFFFFC, borrow: carry 0 */
    w[(*n)++] = alui(PRU_OP_ADC, R(26), R(0), 0);
    w[(*n)++] = alui(PRU_OP_ADD, R(17), R(2), 7); /* 8, carry 0 */
    w[(*n)++] = alui(PRU_OP_ADC, R(27), R(0), 0);
    w[(*n)++] = qb(PRU_OP_QBNE, 2, R(3), R(2)); /* taken */
    w[(*n)++] = ldi(R(11), 1);
    w[(*n)++] = qbi(PRU_OP_QBEQ, 2, R(4), 0); /* taken */
    w[(*n)++] = ldi(R(12), 1);
    w[(*n)++] = qbi(PRU_OP_QBBS, 2, R(1), 31); /* taken */
    w[(*n)++] = ldi(R(13), 1);
    w[(*n)++] = qbi(PRU_OP_QBBC, 2, R(2), 0); /* not taken */
    w[(*n)++] = ldi(R(14), 1);
    w[(*n)++] = qbi(PRU_OP_QBNE, 2, R(2), 1); /* not taken */
    w[(*n)++] = ldi(R(15), 1);
    w[(*n)++] = ldi(R(9), 5);
    w[(*n)++] = alui(PRU_OP_SUB, R(9), R(9), 1); /* a countdown: backward QBNE */
    w[(*n)++] = qbi(PRU_OP_QBNE, -1, R(9), 0);
    w[(*n)++] = halt();
    return w;
}

START_TEST(whole_register_kinds_match_stepping) {
    unsigned n;
    const uint32_t *w = whole_register_prog(&n);
    struct pru_core *fast = run_prog(w, n);
    struct pru_core *step = core_with(PRU_SOC_AM335X, w, n);
    int guard = 1000;
    while (pru_step(step) == PRU_STOP_STEP && --guard > 0)
        ;
    ck_assert_int_gt(guard, 0);
    const uint32_t want[16] = {0, 0xFFFFFFFFu, 1, 0, 0, 2, 2, 0xFFFFFFFEu, 0, 0, 0, 0, 0, 0, 1, 1};
    for (unsigned i = 0; i < 16; i++)
        ck_assert_msg(REG(fast, i) == want[i], "r%u = 0x%x", i, REG(fast, i));
    const uint32_t carries[8] = {1, 1, 0, 0, 1, 1, 0, 0};
    for (unsigned i = 0; i < 8; i++)
        ck_assert_uint_eq(REG(fast, 20 + i), carries[i]);
    ck_assert_uint_eq(REG(fast, 16), 0xFFFFFFFCu);
    ck_assert_uint_eq(REG(fast, 17), 8);
    for (unsigned i = 0; i < 31; i++)
        ck_assert_uint_eq(REG(fast, i), REG(step, i));
    ck_assert_int_eq(pru_carry(fast), pru_carry(step));
    ck_assert_int_eq(pru_cycles(fast), pru_cycles(step));
    ck_assert_uint_eq(pru_instructions(fast), pru_instructions(step));
    pru_core_free(fast);
    pru_core_free(step);
}
END_TEST

START_TEST(suc_rsb_rsc) {
    /* set carry (5-3), suc 10-4-0 = 6; clear carry (3-5), suc 10-4-1 = 5 */
    struct pru_core *c =
        RUN(ldi(R(1), 5), alui(PRU_OP_SUB, R(9), R(1), 3), ldi(R(2), 10),
            alui(PRU_OP_SUC, R(3), R(2), 4), ldi(R(1), 3), alui(PRU_OP_SUB, R(9), R(1), 5),
            alui(PRU_OP_SUC, R(4), R(2), 4), alui(PRU_OP_RSB, R(5), R(2), 7), /* 7 - 10 */
            alui(PRU_OP_RSC, R(6), R(1), 9), /* carry 0 from rsb: 9 - 3 - 1 = 5 */
            halt());
    ck_assert_uint_eq(REG(c, 3), 6);
    ck_assert_uint_eq(REG(c, 4), 5);
    ck_assert_uint_eq(REG(c, 5), (uint32_t)-3);
    ck_assert_uint_eq(REG(c, 6), 5);
    ck_assert_int_eq(pru_carry(c), 1);
    pru_core_free(c);
}
END_TEST

START_TEST(logic_does_not_touch_carry) {
    struct pru_core *c = RUN(ldi(R(1), 5), alui(PRU_OP_SUB, R(9), R(1), 3), /* carry 1 */
                             ldi(R(2), 0xF0F0), alui(PRU_OP_AND, R(3), R(2), 0x3C),
                             alui(PRU_OP_OR, R(4), R(2), 0x0F), alui(PRU_OP_XOR, R(5), R(2), 0xFF),
                             alu(PRU_OP_NOT, R(6), R(2), R(0)), alui(PRU_OP_MIN, R(7), R(2), 9),
                             alui(PRU_OP_MAX, R(8), R(1), 9), alui(PRU_OP_LSL, R(10), R(2), 4),
                             alui(PRU_OP_LSR, R(11), R(2), 4), halt());
    ck_assert_uint_eq(REG(c, 3), 0x30);
    ck_assert_uint_eq(REG(c, 4), 0xF0FF);
    ck_assert_uint_eq(REG(c, 5), 0xF00F);
    ck_assert_uint_eq(REG(c, 6), 0xFFFF0F0Fu);
    ck_assert_uint_eq(REG(c, 7), 9);
    ck_assert_uint_eq(REG(c, 8), 9);
    ck_assert_uint_eq(REG(c, 10), 0xF0F00);
    ck_assert_uint_eq(REG(c, 11), 0xF0F);
    ck_assert_int_eq(pru_carry(c), 1);
    pru_core_free(c);
}
END_TEST

START_TEST(shift_amount_masked) {
    struct pru_core *c =
        RUN(ldi(R(1), 3), alui(PRU_OP_LSL, R(2), R(1), 33),      /* 33 & 31 = 1 */
            ldi(R(3), 0x22), alu(PRU_OP_LSR, R(4), R(2), B0(3)), /* 0x22 & 31 = 2 */
            alui(PRU_OP_LSL, B1(5), R(1), 7),                    /* 0x180 truncated to b1 -> 0x80 */
            halt());
    ck_assert_uint_eq(REG(c, 2), 6);
    ck_assert_uint_eq(REG(c, 4), 1);
    ck_assert_uint_eq(REG(c, 5), 0x8000);
    pru_core_free(c);
}
END_TEST

START_TEST(clr_set_and_r31_source) {
    struct pru_core *c = pru_core_new(PRU_SOC_AM335X, NULL);
    const uint32_t w[] = {ldi(R(1), 0xFF),
                          alui(PRU_OP_CLR, R(2), R(1), 37),  /* bit 5 */
                          alui(PRU_OP_SET, R(3), R(1), 40),  /* bit 8 */
                          alui(PRU_OP_SET, R(4), R(31), 3),  /* R31 source reads 0 */
                          alui(PRU_OP_OR, R(5), R(31), 0),   /* but OR reads the inputs */
                          alui(PRU_OP_SET, B1(6), B0(1), 2), /* field to field */
                          halt()};
    pru_load_image(c, w, sizeof w);
    pru_set_inputs(c, 0x00FF00);
    pru_start(c);
    ck_assert_int_eq(pru_run(c, 1000), PRU_STOP_HALT);
    ck_assert_uint_eq(REG(c, 2), 0xDF);
    ck_assert_uint_eq(REG(c, 3), 0x1FF);
    ck_assert_uint_eq(REG(c, 4), 8);
    ck_assert_uint_eq(REG(c, 5), 0x00FF00);
    ck_assert_uint_eq(REG(c, 6), 0xFF00);
    pru_core_free(c);
}
END_TEST

START_TEST(lmbd_cases) {
    struct pru_core *c =
        RUN(ldi(R(1), 0x0410), alui(PRU_OP_LMBD, R(2), R(1), 1), /* 10 */
            alui(PRU_OP_LMBD, R(3), R(0), 1),                    /* none: 32 */
            alui(PRU_OP_LMBD, R(4), B0(1), 0),                   /* 0x10 in b0: highest 0 = 7 */
            ldi(B0(5), 0xFF), alui(PRU_OP_LMBD, R(6), B0(5), 0), /* none in the field: 32 */
            alui(PRU_OP_LMBD, R(7), R(1), 0x3),                  /* op2 bit 0 only */
            halt());
    ck_assert_uint_eq(REG(c, 2), 10);
    ck_assert_uint_eq(REG(c, 3), 32);
    ck_assert_uint_eq(REG(c, 4), 7);
    ck_assert_uint_eq(REG(c, 6), 32);
    ck_assert_uint_eq(REG(c, 7), 10);
    pru_core_free(c);
}
END_TEST

START_TEST(ldi_fields_and_nop) {
    struct pru_core *c = RUN(ldi(R(1), 0xFFFF), ldi(B1(1), 0x1AB), ldi(W1(2), 0x1234),
                             alu(PRU_OP_NOP3, R(1), R(2), R(3)), halt());
    ck_assert_uint_eq(REG(c, 1), 0xABFF);
    ck_assert_uint_eq(REG(c, 2), 0x123400);
    ck_assert_int_eq(pru_cycles(c), 5);
    pru_core_free(c);
}
END_TEST

START_TEST(jmp_jal_ret) {
    /* 0: jal r30.w0, 4 ; 1: ldi r2, 7 ; 2: halt ; 3: - ; 4: ldi r1, 1 ; 5: jmp r30.w0 */
    struct pru_core *c =
        RUN(jali(W0(30), 4), ldi(R(2), 7), halt(), halt(), ldi(R(1), 1), jmpr(W0(30)));
    ck_assert_uint_eq(REG(c, 1), 1);
    ck_assert_uint_eq(REG(c, 2), 7);
    ck_assert_uint_eq(REG(c, 30), 1);
    ck_assert_uint_eq(pru_pc(c), 2);
    ck_assert_int_eq(pru_cycles(c), 5);
    ck_assert_uint_eq(pru_instructions(c), 5);
    pru_core_free(c);
}
END_TEST

/* Each QB condition taken and not taken: r9 collects a bit per taken branch. */
START_TEST(qb_conditions) {
    static const int ops[] = {PRU_OP_QBGT, PRU_OP_QBGE, PRU_OP_QBLT,
                              PRU_OP_QBLE, PRU_OP_QBEQ, PRU_OP_QBNE};
    /* op2 vs rs1 for (op2, rs1) = (5,3), (3,3), (3,5) */
    static const unsigned expect[6][3] = {{1, 0, 0}, {1, 1, 0}, {0, 0, 1},
                                          {0, 1, 1}, {0, 1, 0}, {1, 0, 1}};
    static const unsigned rs1v[3] = {3, 3, 5}, op2v[3] = {5, 3, 3};
    for (int i = 0; i < 6; i++) {
        for (int j = 0; j < 3; j++) {
            struct pru_core *c =
                RUN(ldi(R(1), rs1v[j]), qbi(ops[i], 2, R(1), op2v[j]), ldi(R(9), 1), halt());
            ck_assert_uint_eq(REG(c, 9), expect[i][j] ? 0 : 1);
            ck_assert_int_eq(pru_cycles(c), expect[i][j] ? 3 : 4);
            pru_core_free(c);
        }
    }
    /* register op2, unsigned compare on fields */
    struct pru_core *c = RUN(ldi(R(1), 0xFF00), ldi(R(2), 0x01), qb(PRU_OP_QBGT, 2, B1(1), B0(2)),
                             ldi(R(9), 1), halt());
    ck_assert_uint_eq(REG(c, 9), 1); /* 1 > 0xFF is false */
    pru_core_free(c);
}
END_TEST

START_TEST(qbb_bits) {
    struct pru_core *c =
        RUN(ldi(R(1), 0x8000), qbi(PRU_OP_QBBS, 2, R(1), 15), ldi(R(8), 1), /* taken */
            qbi(PRU_OP_QBBC, 2, R(1), 47), ldi(R(9), 1),                    /* bit 15: not */
            ldi(R(3), 14), qb(PRU_OP_QBBC, 2, R(1), B0(3)), ldi(R(10), 1),  /* bit 14 clear */
            halt());
    ck_assert_uint_eq(REG(c, 8), 0);
    ck_assert_uint_eq(REG(c, 9), 1);
    ck_assert_uint_eq(REG(c, 10), 0);
    pru_core_free(c);
}
END_TEST

/* Offsets at the ends of the signed 10-bit range: +511 and -512. */
START_TEST(qb_offset_range_ends) {
    uint32_t *w = calloc(1024, 4);
    w[0] = qba(511);
    w[511] = ldi(R(1), 1);
    w[512] = jmpi(700);
    w[700] = qbi(PRU_OP_QBEQ, -512, R(0), 0);
    w[188] = ldi(R(2), 2);
    w[189] = halt();
    struct pru_core *c = run_prog(w, 1024);
    ck_assert_uint_eq(REG(c, 1), 1);
    ck_assert_uint_eq(REG(c, 2), 2);
    ck_assert_uint_eq(pru_pc(c), 189);
    ck_assert_int_eq(pru_cycles(c), 6);
    pru_core_free(c);
    free(w);
}
END_TEST

START_TEST(loop_immediate_register_zero) {
    struct pru_core *c;
    /* loop 5: body once per iteration, no overhead per iteration */
    c = RUN(loopi(2, 5), alui(PRU_OP_ADD, R(1), R(1), 1), halt());
    ck_assert_uint_eq(REG(c, 1), 5);
    ck_assert_int_eq(pru_cycles(c), 1 + 5 + 1);
    ck_assert_uint_eq(pru_instructions(c), 7);
    pru_core_free(c);
    /* register count: 16 LS bits of the field (0x10003 -> 3) */
    c = RUN(ldi(W2(2), 1), ldi(W0(2), 3), loopr(3, R(2)), alui(PRU_OP_ADD, R(1), R(1), 1),
            alui(PRU_OP_ADD, R(3), R(3), 2), halt());
    ck_assert_uint_eq(REG(c, 1), 3);
    ck_assert_uint_eq(REG(c, 3), 6);
    ck_assert_int_eq(pru_cycles(c), 2 + 1 + 6 + 1);
    pru_core_free(c);
    /* byte field count */
    c = RUN(ldi(R(2), 0x0402), loopr(2, B1(2)), alui(PRU_OP_ADD, R(1), R(1), 1), halt());
    ck_assert_uint_eq(REG(c, 1), 4);
    pru_core_free(c);
    /* zero register count jumps straight to the end */
    c = RUN(loopr(2, R(2)), alui(PRU_OP_ADD, R(1), R(1), 1), halt());
    ck_assert_uint_eq(REG(c, 1), 0);
    ck_assert_int_eq(pru_cycles(c), 2);
    ck_assert_uint_eq(pru_instructions(c), 2);
    pru_core_free(c);
    /* 256 iterations (imm 255 encoded) */
    c = RUN(loopi(2, 256), alui(PRU_OP_ADD, R(1), R(1), 1), halt());
    ck_assert_uint_eq(REG(c, 1), 256);
    pru_core_free(c);
}
END_TEST

START_TEST(loads_and_stores_cost) {
    uint32_t w[32];
    unsigned n = 0;
    mov32(w, &n, 1, 0x11223344u);
    mov32(w, &n, 2, 0x55667788u);
    w[n++] = burst(PRU_OP_SBCO, 4 * 1, 24, 0x10, 8);     /* 2 cycles */
    w[n++] = burst(PRU_OP_LBCO, 4 * 3, 24, 0x10, 8);     /* 2 + 2 */
    w[n++] = burst(PRU_OP_LBCO, 4 * 5 + 1, 24, 0x11, 2); /* r5.b1.. = 0x33 0x22: 2 + 1 */
    w[n++] = ldi(R(6), 0x2000);
    w[n++] = burst(PRU_OP_SBBO, 4 * 1, 6, 0, 4); /* to PRU1 data RAM: 1 */
    w[n++] = burst(PRU_OP_LBBO, 4 * 7, 6, 0, 4); /* 3 */
    w[n++] = halt();
    struct pru_core *c = run_prog(w, n);
    ck_assert_uint_eq(REG(c, 3), 0x11223344u);
    ck_assert_uint_eq(REG(c, 4), 0x55667788u);
    ck_assert_uint_eq(REG(c, 5), 0x00223300u);
    ck_assert_uint_eq(REG(c, 7), 0x11223344u);
    ck_assert_int_eq(pru_cycles(c), 4 + 2 + 4 + 3 + 1 + 1 + 3 + 1);
    uint32_t v;
    ck_assert_int_eq(pru_host_read32(c, 0x4A300010u, &v), 0);
    ck_assert_uint_eq(v, 0x11223344u);
    ck_assert_int_eq(pru_host_read32(c, 0x4A302000u, &v), 0);
    ck_assert_uint_eq(v, 0x11223344u);
    pru_core_free(c);
}
END_TEST

START_TEST(burst_r0_count_and_regoffset) {
    /* r0.b1 = 6 bytes, offset in r2.w0 */
    struct pru_core *c = pru_core_new(PRU_SOC_AM335X, NULL);
    const uint32_t w[] = {ldi(R(0), 0x0600), ldi(R(2), 0x40),
                          burstr(PRU_OP_LBBO, 4 * 4, 3, W0(2), 125), halt()};
    pru_load_image(c, w, sizeof w);
    const uint8_t data[8] = {1, 2, 3, 4, 5, 6, 7, 8};
    pru_host_write(c, 0x4A300040u, data, 8);
    pru_start(c);
    ck_assert_int_eq(pru_run(c, 100), PRU_STOP_HALT);
    ck_assert_uint_eq(REG(c, 4), 0x04030201u);
    ck_assert_uint_eq(REG(c, 5), 0x0605u);
    ck_assert_int_eq(pru_cycles(c), 2 + (2 + 2) + 1);
    pru_core_free(c);
}
END_TEST

START_TEST(constant_table_programmable) {
    /* CTPPR0 = 0x100 makes C28 the shared RAM; CTBIR0 C24 block 1 -> 0x100 */
    uint32_t w[32];
    unsigned n = 0;
    mov32(w, &n, 1, 0x22000u);
    w[n++] = ldi(R(2), 0x100);
    w[n++] = burst(PRU_OP_SBBO, 4 * 2, 1, 0x28, 4); /* CTPPR0 */
    w[n++] = ldi(R(2), 0x1);
    w[n++] = burst(PRU_OP_SBBO, 4 * 2, 1, 0x20, 4); /* CTBIR0 */
    w[n++] = ldi(R(3), 0xBEEF);
    w[n++] = burst(PRU_OP_SBCO, 4 * 3, 28, 4, 4);
    w[n++] = burst(PRU_OP_SBCO, 4 * 3, 24, 8, 4);
    w[n++] = burst(PRU_OP_LBCO, 4 * 4, 4, 0, 4); /* C4 = CFG: REVID */
    w[n++] = halt();
    struct pru_core *c = run_prog(w, n);
    uint32_t v;
    pru_host_read32(c, 0x4A310004u, &v);
    ck_assert_uint_eq(v, 0xBEEF);
    pru_host_read32(c, 0x4A300108u, &v);
    ck_assert_uint_eq(v, 0xBEEF);
    pru_host_read32(c, 0x4A326000u, &v);
    ck_assert_uint_eq(REG(c, 4), v);
    pru_core_free(c);
}
END_TEST

START_TEST(xfr_scratch_zero_fill) {
    struct pru_params p;
    pru_params_default(&p);
    for (int swap = 0; swap < 2; swap++) {
        p.xchg_swaps = swap;
        struct pru_core *c = pru_core_new(PRU_SOC_AM335X, &p);
        const uint32_t w[] = {
            ldi(R(2), 0x1111),
            ldi(R(3), 0x2222),
            xfr(PRU_OP_XOUT, 10, 8, 8), /* bank 0 r2..r3 */
            xfr(PRU_OP_XIN, 255, 8, 8), /* zero &r2, 8 */
            alu(PRU_OP_OR, R(6), R(2), R(3)),
            xfr(PRU_OP_XIN, 10, 8, 8),   /* back from bank 0 */
            xfr(PRU_OP_XIN, 254, 16, 4), /* fill &r4, 4 */
            xfr(PRU_OP_XIN, 11, 20, 4),  /* bank 1 is empty */
            ldi(R(7), 0x3333),
            xfr(PRU_OP_XCHG, 10, 28, 4), /* r7 <-> bank 0 r7 slot (0) */
            ldi(R(8), 0x4444),
            xfr(PRU_OP_XIN, 10, 28, 4),
            halt(),
        };
        pru_load_image(c, w, sizeof w);
        pru_set_reg(c, 5, 0x5555);
        pru_start(c);
        ck_assert_int_eq(pru_run(c, 100), PRU_STOP_HALT);
        ck_assert_uint_eq(REG(c, 6), 0);
        ck_assert_uint_eq(REG(c, 2), 0x1111);
        ck_assert_uint_eq(REG(c, 3), 0x2222);
        ck_assert_uint_eq(REG(c, 4), 0xFFFFFFFFu);
        ck_assert_uint_eq(REG(c, 5), 0);
        /* swap: the bank got 0x3333; like XIN: the bank stays 0 */
        ck_assert_uint_eq(REG(c, 7), swap ? 0x3333 : 0);
        ck_assert_int_eq(pru_cycles(c), 13); /* one cycle each */
        pru_core_free(c);
    }
}
END_TEST

START_TEST(mvi_pointer_forms) {
    /* r1.b0 points at r4 (byte 16) */
    struct pru_core *c =
        RUN(ldi(R(1), 16), ldi(R(4), 0xABCD), ldi(W2(4), 0x1234),
            mvi(PRU_OP_MVIB, PRU_MVI_DIRECT, R(2), PRU_MVI_IND, B0(1)),     /* r2 = 0xCD */
            mvi(PRU_OP_MVIW, PRU_MVI_DIRECT, R(3), PRU_MVI_POSTINC, B0(1)), /* r3 = 0xABCD, p=18 */
            ldi(R(14), 0x7777),
            mvi(PRU_OP_MVID, PRU_MVI_PREDEC, B1(1), PRU_MVI_DIRECT, R(14)),  /* r1.b1: 0-4 = 252 */
            ldi(B1(1), 40),                                                  /* r10 */
            mvi(PRU_OP_MVID, PRU_MVI_POSTINC, B1(1), PRU_MVI_DIRECT, R(14)), /* r10 = 0x7777 */
            halt());
    ck_assert_uint_eq(REG(c, 2), 0xCD);
    ck_assert_uint_eq(REG(c, 3), 0xABCD);
    ck_assert_uint_eq(REG(c, 1) & 0xff, 18);
    ck_assert_uint_eq(REG(c, 10), 0x7777);
    ck_assert_uint_eq((REG(c, 1) >> 8) & 0xff, 44);
    ck_assert_int_eq(pru_cycles(c), 10); /* one cycle each */
    /* (the predecrement wrote r31 at 252 & 0x7f = 124: an R31 event write) */
    pru_core_free(c);
}
END_TEST

/* ILOOP behaves like LOOP; the S-variants of XFR like the plain ones. */
START_TEST(iloop_and_s_xfr) {
    uint32_t il = enc((struct pru_insn){.op = PRU_OP_ILOOP, .loop_end = 2, .io = 1, .imm = 2});
    struct pru_core *c =
        RUN(il, alui(PRU_OP_ADD, R(1), R(1), 1), ldi(R(2), 0x5A), xfr(PRU_OP_SXOUT, 11, 8, 4),
            ldi(R(2), 0), xfr(PRU_OP_SXIN, 11, 8, 4), halt());
    ck_assert_uint_eq(REG(c, 1), 3);
    ck_assert_uint_eq(REG(c, 2), 0x5A);
    ck_assert_int_eq(pru_cycles(c), 1 + 3 + 5);
    pru_core_free(c);
}
END_TEST

Suite *insn_suite(void) {
    Suite *s = suite_create("core_insn");
    TCase *t = tcase_create("alu");
    tcase_add_test(t, add_carry_byte_field);
    tcase_add_test(t, add_carry_word_and_full);
    tcase_add_test(t, whole_register_kinds_match_stepping);
    tcase_add_test(t, sub_not_borrow);
    tcase_add_test(t, suc_rsb_rsc);
    tcase_add_test(t, logic_does_not_touch_carry);
    tcase_add_test(t, shift_amount_masked);
    tcase_add_test(t, clr_set_and_r31_source);
    tcase_add_test(t, lmbd_cases);
    tcase_add_test(t, ldi_fields_and_nop);
    suite_add_tcase(s, t);
    t = tcase_create("flow");
    tcase_add_test(t, jmp_jal_ret);
    tcase_add_test(t, qb_conditions);
    tcase_add_test(t, qbb_bits);
    tcase_add_test(t, qb_offset_range_ends);
    tcase_add_test(t, loop_immediate_register_zero);
    tcase_add_test(t, iloop_and_s_xfr);
    suite_add_tcase(s, t);
    t = tcase_create("mem");
    tcase_add_test(t, loads_and_stores_cost);
    tcase_add_test(t, burst_r0_count_and_regoffset);
    tcase_add_test(t, constant_table_programmable);
    tcase_add_test(t, xfr_scratch_zero_fill);
    tcase_add_test(t, mvi_pointer_forms);
    suite_add_tcase(s, t);
    return s;
}

int main(void) {
    return check_run(insn_suite());
}
