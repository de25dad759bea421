/*
 * Check suite: IEP timer (count, increments, compensation, compares, reset
 * on CMP0, status write-1-to-clear, overflow) and its event to R31[30],
 * against exact cycles and against a plain per-tick reference model.
 */
#include "check_run.h"
#include "core_test_util.h"

#include <stdlib.h>

#define IEP    (0x4A300000u + 0x2E000u)
#define INTC   (0x4A300000u + 0x20000u)
#define G_CFG  0x00u
#define G_ST   0x04u
#define COMPN  0x08u
#define COUNT  0x0Cu
#define CCFG   0x40u
#define CST    0x44u
#define CMP(n) (0x48u + 4u * (n))

static uint32_t rd(struct pru_core *c, uint32_t ofs) {
    uint32_t v = 0;
    ck_assert_int_eq(pru_host_read32(c, IEP + ofs, &v), 0);
    return v;
}

static void wr(struct pru_core *c, uint32_t ofs, uint32_t v) {
    ck_assert_int_eq(pru_host_write32(c, IEP + ofs, v), 0);
}

static void at(struct pru_core *c, int64_t cycle) {
    pru_run_until_cycle(c, cycle);
    ck_assert_int_eq(pru_cycles(c), cycle);
}

START_TEST(count_default_increments) {
    struct pru_core *c = pru_core_new(PRU_SOC_AM335X, NULL);
    ck_assert_uint_eq(rd(c, G_CFG), 0x550);
    wr(c, G_CFG, 0x551); /* enable, increment 5 */
    at(c, 100);
    ck_assert_uint_eq(rd(c, COUNT), 500);
    wr(c, G_CFG, 0x550); /* freeze */
    at(c, 200);
    ck_assert_uint_eq(rd(c, COUNT), 500);
    wr(c, COUNT, 7); /* plain write */
    wr(c, G_CFG, 0x111);
    at(c, 210);
    ck_assert_uint_eq(rd(c, COUNT), 17);
    pru_core_free(c);
}
END_TEST

/* PRU view: an enabling store lands at the next boundary; ticks follow. */
START_TEST(count_seen_by_pru) {
    uint32_t w[16];
    unsigned n = 0;
    mov32(w, &n, 1, 0x111);
    w[n++] = burst(PRU_OP_SBCO, 4 * 1, 26, G_CFG, 4); /* c=2 */
    w[n++] = burst(PRU_OP_LBCO, 4 * 2, 26, COUNT, 4); /* c=3: 0 */
    w[n++] = burst(PRU_OP_LBCO, 4 * 3, 26, COUNT, 4); /* c=6: 3 */
    w[n++] = halt();
    struct pru_core *c = run_prog(w, n);
    ck_assert_uint_eq(pru_reg(c, 2), 0);
    ck_assert_uint_eq(pru_reg(c, 3), 3);
    ck_assert_int_eq(pru_cycles(c), 10);
    pru_core_free(c);
}
END_TEST

START_TEST(cmp0_reset_period) {
    struct pru_core *c = pru_core_new(PRU_SOC_AM335X, NULL);
    wr(c, CMP(0), 9);
    wr(c, CCFG, 3); /* CMP0 enabled, reset on CMP0 */
    wr(c, G_CFG, 0x111);
    for (int64_t x = 1; x < 60; x++) {
        at(c, x);
        ck_assert_uint_eq(rd(c, COUNT), (uint32_t)(x % 10));
        ck_assert_uint_eq(rd(c, CST), x >= 9 ? 1u : 0u);
    }
    /* increment 5, CMP0 = 10: 0 5 10 0 5 10 ... (period CMP0/inc + 1) */
    wr(c, G_CFG, 0x550);
    wr(c, COUNT, 0);
    wr(c, CMP(0), 10);
    wr(c, CST, 1);
    int64_t t0 = pru_cycles(c);
    wr(c, G_CFG, 0x551);
    for (int64_t x = 1; x < 20; x++) {
        at(c, t0 + x);
        ck_assert_uint_eq(rd(c, COUNT), (uint32_t)(5 * (x % 3)));
    }
    pru_core_free(c);
}
END_TEST

/* pru_iep_view: the state a read in a later cycle would see, leaving the
 * IEP where it was; a cycle the IEP is already past gives that later one. */
START_TEST(view_leaves_the_iep) {
    struct pru_core *c = pru_core_new(PRU_SOC_AM335X, NULL);
    wr(c, CMP(0), 9);
    wr(c, CCFG, 3);
    wr(c, G_CFG, 0x111);
    at(c, 5);
    struct pru_iep_view v;
    pru_iep_view(c, 37, &v);
    ck_assert_int_eq(v.cycle, 37);
    ck_assert_uint_eq(v.count, 7);
    ck_assert_uint_eq(v.inc, 1);
    ck_assert_uint_eq(v.cmp0, 9);
    ck_assert(v.cmp0_resets);
    ck_assert_uint_eq(rd(c, COUNT), 5); /* not moved on to 37 */
    pru_iep_view(c, 2, &v);
    ck_assert_int_eq(v.cycle, 5);
    ck_assert_uint_eq(v.count, 5);
    wr(c, CCFG, 2); /* CMP0 on, no reset */
    at(c, 8);
    pru_iep_view(c, 8, &v);
    ck_assert(!v.cmp0_resets);
    pru_core_free(c);
}
END_TEST

START_TEST(status_w1c_sets_again) {
    struct pru_core *c = pru_core_new(PRU_SOC_AM335X, NULL);
    wr(c, CMP(1), 5);
    wr(c, CCFG, 1u << 2);
    wr(c, G_CFG, 0x111);
    at(c, 4);
    ck_assert_uint_eq(rd(c, CST), 0);
    at(c, 5);
    ck_assert_uint_eq(rd(c, CST), 2);
    at(c, 20);
    wr(c, CST, 2);
    ck_assert_uint_eq(rd(c, CST), 0);
    at(c, 21); /* COUNT still >= CMP1 */
    ck_assert_uint_eq(rd(c, CST), 2);
    wr(c, CST, 0); /* writing 0 changes nothing */
    ck_assert_uint_eq(rd(c, CST), 2);
    pru_core_free(c);
}
END_TEST

START_TEST(overflow_flag) {
    struct pru_core *c = pru_core_new(PRU_SOC_AM335X, NULL);
    wr(c, COUNT, 0xFFFFFFF0u);
    wr(c, G_CFG, 0x551);
    at(c, 3);
    ck_assert_uint_eq(rd(c, COUNT), 0xFFFFFFFFu);
    ck_assert_uint_eq(rd(c, G_ST), 0);
    at(c, 4);
    ck_assert_uint_eq(rd(c, COUNT), 4);
    ck_assert_uint_eq(rd(c, G_ST), 1);
    wr(c, G_ST, 1);
    ck_assert_uint_eq(rd(c, G_ST), 0);
    pru_core_free(c);
}
END_TEST

START_TEST(compensation) {
    struct pru_core *c = pru_core_new(PRU_SOC_AM335X, NULL);
    wr(c, COMPN, 3);
    wr(c, G_CFG, 0x211); /* CMP_INC 2, DEFAULT_INC 1 */
    static const uint32_t expect[] = {0, 2, 4, 6, 7, 8, 9};
    for (int64_t x = 0; x < 7; x++) {
        at(c, x);
        ck_assert_uint_eq(rd(c, COUNT), expect[x]);
    }
    ck_assert_uint_eq(rd(c, COMPN), 0);
    pru_core_free(c);
}
END_TEST

/* Plain reference: one tick at a time, exactly as docs/pru-facts.md §6 reads. */
struct ref {
    uint32_t cfg, compen, count, ccfg, cst, gst, cmp[8];
};

static void ref_tick(struct ref *r) {
    if ((r->ccfg & 1) && (r->ccfg & 2) && r->count >= r->cmp[0]) {
        r->count = 0;
    } else {
        uint32_t inc = r->compen ? (r->cfg >> 8) & 15 : (r->cfg >> 4) & 15;
        if (r->compen)
            r->compen--;
        if ((uint64_t)r->count + inc > 0xFFFFFFFFu)
            r->gst = 1;
        r->count += inc;
    }
    for (int n = 0; n < 8; n++)
        if ((r->ccfg >> (n + 1)) & 1 && r->count >= r->cmp[n])
            r->cst |= 1u << n;
}

START_TEST(random_against_reference) {
    srand(12345);
    for (int round = 0; round < 40; round++) {
        struct pru_core *c = pru_core_new(PRU_SOC_AM335X, NULL);
        struct ref r = {0};
        r.cfg = 1u | (uint32_t)(rand() % 16) << 4 | (uint32_t)(rand() % 16) << 8;
        r.compen = (uint32_t)(rand() % 50);
        r.ccfg = (uint32_t)rand() & 0x1ff;
        r.count = rand() % 4 ? 0 : 0xFFFFFF00u;
        for (int n = 0; n < 8; n++)
            r.cmp[n] = (uint32_t)(rand() % 3000);
        for (int n = 0; n < 8; n++)
            wr(c, CMP(n), r.cmp[n]);
        wr(c, COUNT, r.count);
        wr(c, COMPN, r.compen);
        wr(c, CCFG, r.ccfg);
        wr(c, G_CFG, r.cfg);
        int64_t now = 0;
        for (int step = 0; step < 30; step++) {
            int64_t dt = rand() % 400;
            for (int64_t i = 0; i < dt; i++)
                ref_tick(&r);
            now += dt;
            at(c, now);
            ck_assert_uint_eq(rd(c, COUNT), r.count);
            ck_assert_uint_eq(rd(c, CST), r.cst);
            ck_assert_uint_eq(rd(c, G_ST), r.gst);
            ck_assert_uint_eq(rd(c, COMPN), r.compen);
            if (rand() % 3 == 0) {
                uint32_t clr = (uint32_t)rand() & 0xff;
                wr(c, CST, clr);
                r.cst &= ~clr;
            }
        }
        pru_core_free(c);
    }
}
END_TEST

/* wbs r31.t30 on an IEP compare through the INTC; fast-forward exact. */
START_TEST(iep_event_wakes_poll_loop) {
    for (int ff = 0; ff < 2; ff++) {
        struct pru_params p;
        pru_params_default(&p);
        p.fast_forward = ff;
        struct pru_core *c = pru_core_new(PRU_SOC_AM335X, &p);
        const uint32_t w[] = {qbi(PRU_OP_QBBC, 0, R(31), 30), halt()};
        pru_load_image(c, w, sizeof w);
        pru_host_write32(c, INTC + 0x10, 1); /* GER */
        pru_host_write32(c, INTC + 0x28, 7); /* EISR: event 7 */
        pru_host_write32(c, INTC + 0x34, 0); /* host 0 (maps are 0 by reset) */
        wr(c, CMP(1), 100000);
        wr(c, CCFG, 1u << 2);
        wr(c, G_CFG, 0x111);
        pru_start(c);
        ck_assert_int_eq(pru_run(c, 1000000), PRU_STOP_HALT);
        ck_assert_int_eq(pru_cycles(c), 100002);
        ck_assert_uint_eq(pru_instructions(c), 100002);
        ck_assert_uint_eq(pru_reg(c, 31) >> 30, 1);
        if (ff)
            ck_assert_uint_gt(pru_ff_skipped(c), 90000);
        else
            ck_assert_uint_eq(pru_ff_skipped(c), 0);
        pru_core_free(c);
    }
}
END_TEST

/* Polling CMP_STATUS with a load: skip whole iterations, exact result. */
START_TEST(iep_status_poll_fast_forward) {
    int64_t cyc[2];
    uint64_t ins[2];
    for (int ff = 0; ff < 2; ff++) {
        struct pru_params p;
        pru_params_default(&p);
        p.fast_forward = ff;
        struct pru_core *c = pru_core_new(PRU_SOC_AM335X, &p);
        const uint32_t w[] = {burst(PRU_OP_LBCO, 4 * 2, 26, CST, 4), qbi(PRU_OP_QBBC, -1, R(2), 3),
                              alui(PRU_OP_ADD, R(3), R(3), 1), halt()};
        pru_load_image(c, w, sizeof w);
        wr(c, CMP(3), 54321);
        wr(c, CCFG, 1u << 4);
        wr(c, G_CFG, 0x111);
        pru_start(c);
        ck_assert_int_eq(pru_run(c, 1000000), PRU_STOP_HALT);
        cyc[ff] = pru_cycles(c);
        ins[ff] = pru_instructions(c);
        ck_assert_uint_eq(pru_reg(c, 2), 8);
        if (ff)
            ck_assert_uint_gt(pru_ff_skipped(c), 10000);
        pru_core_free(c);
    }
    ck_assert_int_eq(cyc[0], cyc[1]);
    ck_assert_uint_eq(ins[0], ins[1]);
    /* the hit is at boundary 54321; the load issued at or after it sees it */
    ck_assert_int_ge(cyc[0], 54321 + 5);
    ck_assert_int_le(cyc[0], 54321 + 4 + 5);
}
END_TEST

Suite *iep_suite(void) {
    Suite *s = suite_create("core_iep");
    TCase *t = tcase_create("iep");
    tcase_add_test(t, count_default_increments);
    tcase_add_test(t, count_seen_by_pru);
    tcase_add_test(t, cmp0_reset_period);
    tcase_add_test(t, view_leaves_the_iep);
    tcase_add_test(t, status_w1c_sets_again);
    tcase_add_test(t, overflow_flag);
    tcase_add_test(t, compensation);
    tcase_add_test(t, random_against_reference);
    tcase_add_test(t, iep_event_wakes_poll_loop);
    tcase_add_test(t, iep_status_poll_fast_forward);
    suite_add_tcase(s, t);
    return s;
}

int main(void) {
    return check_run(iep_suite());
}
