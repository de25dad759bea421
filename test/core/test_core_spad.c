/*
 * The scratch pad's register shift (CFG SPP XFR_SHIFT_EN; emulator/core/
 * TIMING.md "Scratch pad: the XFR register shift"): R0[4:0] moves the bank
 * side of XIN/XOUT by whole registers, up or down (xfr_shift_sub), modulo
 * 32; bank registers 30 and 31 do not exist; ZERO/FILL move only with
 * xfr_shift_fill.
 */
#include "core_test_util.h"

#include "check_run.h"

#define REG(c, n) pru_reg((c), (n))

#define CFG_SPP_ADDR 0x4A326034u /* AM335x PRU-ICSS CFG + 0x34 */

/* Runs w with SPP = spp under the shift parameters; returns the core. */
static struct pru_core *run_spad(const uint32_t *w, size_t n, uint32_t spp, int sub, int fill,
                                 enum pru_stop want) {
    struct pru_params p;
    pru_params_default(&p);
    p.xfr_shift_sub = sub;
    p.xfr_shift_fill = fill;
    struct pru_core *c = core_loaded(&p, w, n);
    ck_assert_int_eq(pru_host_write32(c, CFG_SPP_ADDR, spp), 0);
    pru_start(c);
    ck_assert_int_eq(pru_run(c, 1000), want);
    return c;
}

/* r4..r6 = 0xA, 0xB, 0xC out with R0 = shift, then r0 = 0 and the bank's
 * registers 1..12 read back, unshifted, into r1..r12. */
static struct pru_core *out_then_dump(unsigned shift, uint32_t spp, int sub) {
    const uint32_t w[] = {
        ldi(R(4), 0xA),
        ldi(R(5), 0xB),
        ldi(R(6), 0xC),
        ldi(R(0), shift),
        xfr(PRU_OP_XOUT, 10, 16, 12),
        ldi(R(0), 0),
        xfr(PRU_OP_XIN, 10, 4, 48), /* bank r1..r12 -> r1..r12 */
        halt(),
    };
    return run_spad(w, sizeof w / sizeof w[0], spp, sub, 0, PRU_STOP_HALT);
}

START_TEST(shift_off_without_spp) {
    struct pru_core *c = out_then_dump(3, 0, 0);
    ck_assert_uint_eq(REG(c, 4), 0xA);
    ck_assert_uint_eq(REG(c, 6), 0xC);
    ck_assert_uint_eq(REG(c, 7), 0); /* nothing moved */
    pru_core_free(c);
}
END_TEST

START_TEST(shift_up_by_default) {
    struct pru_core *c = out_then_dump(3, 2, 0);
    ck_assert_uint_eq(REG(c, 4), 0); /* bank r4..r6 untouched */
    ck_assert_uint_eq(REG(c, 7), 0xA);
    ck_assert_uint_eq(REG(c, 8), 0xB);
    ck_assert_uint_eq(REG(c, 9), 0xC);
    ck_assert_int_eq(pru_cycles(c), 8); /* one cycle each, HALT too */
    pru_core_free(c);
}
END_TEST

START_TEST(shift_down_and_modulo_32) {
    struct pru_core *c = out_then_dump(3, 2, 1); /* down 3: bank r1..r3 */
    ck_assert_uint_eq(REG(c, 1), 0xA);
    ck_assert_uint_eq(REG(c, 3), 0xC);
    ck_assert_uint_eq(REG(c, 4), 0);
    pru_core_free(c);
    c = out_then_dump(29, 2, 1); /* down 29 = up 3 (mod 32): the firmware's step */
    ck_assert_uint_eq(REG(c, 7), 0xA);
    ck_assert_uint_eq(REG(c, 9), 0xC);
    pru_core_free(c);
}
END_TEST

/* XIN with the same R0 meets what XOUT wrote, either way. */
START_TEST(shift_in_meets_out) {
    const uint32_t w[] = {
        ldi(R(4), 0x1234),
        ldi(R(0), 2),
        xfr(PRU_OP_XOUT, 10, 16, 4),
        ldi(R(4), 0),
        ldi(R(0), 2),
        xfr(PRU_OP_XIN, 10, 16, 4),
        halt(),
    };
    for (int sub = 0; sub < 2; sub++) {
        struct pru_core *c = run_spad(w, sizeof w / sizeof w[0], 2, sub, 0, PRU_STOP_HALT);
        ck_assert_uint_eq(REG(c, 4), 0x1234);
        pru_core_free(c);
    }
}
END_TEST

/* Past bank register 29 there is no register: a fault, not a wrap. */
START_TEST(shift_past_the_bank_faults) {
    const uint32_t w[] = {ldi(R(0), 26), xfr(PRU_OP_XOUT, 10, 16, 12), halt()};
    struct pru_core *c = run_spad(w, sizeof w / sizeof w[0], 2, 0, 0, PRU_STOP_FAULT);
    ck_assert_int_eq(pru_get_fault(c)->cause, PRU_FAULT_BURST);
    pru_core_free(c);
}
END_TEST

/* FILL moves with the shift only under xfr_shift_fill. */
START_TEST(fill_follows_only_when_asked) {
    const uint32_t w[] = {ldi(R(0), 2), xfr(PRU_OP_XIN, 254, 16, 4), halt()};
    for (int fill = 0; fill < 2; fill++) {
        struct pru_core *c = run_spad(w, sizeof w / sizeof w[0], 2, 0, fill, PRU_STOP_HALT);
        ck_assert_uint_eq(REG(c, 4), fill ? 0 : 0xffffffffu);
        ck_assert_uint_eq(REG(c, 6), fill ? 0xffffffffu : 0);
        pru_core_free(c);
    }
}
END_TEST

static Suite *spad_suite(void) {
    Suite *s = suite_create("core_spad");
    TCase *t = tcase_create("shift");
    tcase_add_test(t, shift_off_without_spp);
    tcase_add_test(t, shift_up_by_default);
    tcase_add_test(t, shift_down_and_modulo_32);
    tcase_add_test(t, shift_in_meets_out);
    tcase_add_test(t, shift_past_the_bank_faults);
    tcase_add_test(t, fill_follows_only_when_asked);
    suite_add_tcase(s, t);
    return s;
}

int main(void) {
    return check_run(spad_suite());
}
