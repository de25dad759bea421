/*
 * Check suite: strict mode (each rule: a program that breaks it stops with
 * that rule at that PC, one that does not runs; clocked scope from R30
 * changes; the log) and data-RAM contention (the stall arithmetic).
 * emulator/core/TIMING.md, "Strict mode" and "Contention mode".
 */
#include "check_run.h"
#include "core_test_util.h"

static struct pru_core *core_params(const struct pru_params *p, const uint32_t *w, size_t n) {
    struct pru_core *c = pru_core_new(PRU_SOC_AM335X, p);
    ck_assert_ptr_nonnull(c);
    ck_assert_int_eq(pru_load_image(c, w, n * 4), 0);
    pru_start(c);
    return c;
}

/* Runs w with the rules everywhere; returns the stop. */
static enum pru_stop run_strict(unsigned rules, const uint32_t *w, size_t n,
                                struct pru_core **out) {
    struct pru_params p;
    pru_params_default(&p);
    p.strict = rules;
    p.strict_everywhere = 1;
    *out = core_params(&p, w, n);
    return pru_run(*out, 100000);
}

#define N(a) (sizeof(a) / sizeof((a)[0]))

static void expect_fault(unsigned rules, const uint32_t *w, size_t n, unsigned rule, uint32_t pc) {
    struct pru_core *c;
    ck_assert_int_eq(run_strict(rules, w, n, &c), PRU_STOP_FAULT);
    const struct pru_fault *f = pru_get_fault(c);
    ck_assert_int_eq(f->cause, PRU_FAULT_STRICT);
    ck_assert_str_eq(pru_strict_rule_name(f->rule), pru_strict_rule_name(rule));
    ck_assert_uint_eq(f->pc, pc);
    ck_assert_uint_eq(f->word, w[pc]);
    ck_assert_uint_eq(pru_pc(c), pc); /* the instruction did not run */
    pru_core_free(c);
}

static void expect_halt(unsigned rules, const uint32_t *w, size_t n) {
    struct pru_core *c;
    ck_assert_int_eq(run_strict(rules, w, n, &c), PRU_STOP_HALT);
    pru_core_free(c);
}

START_TEST(loop_one_instruction_body) {
    const uint32_t bad[] = {loopi(2, 3), alui(PRU_OP_ADD, R(1), R(1), 1), halt()};
    const uint32_t good[] = {loopi(3, 3), alui(PRU_OP_ADD, R(1), R(1), 1),
                             alui(PRU_OP_ADD, R(1), R(1), 1), halt()};
    expect_fault(PRU_STRICT_ALL, bad, N(bad), PRU_STRICT_LOOP1, 0);
    expect_halt(PRU_STRICT_ALL, good, N(good));
    expect_halt(PRU_STRICT_ALL & ~PRU_STRICT_LOOP1, bad, N(bad)); /* switched off */
}
END_TEST

START_TEST(loop_count_zero) {
    const uint32_t bad[] = {ldi(R(2), 0), loopr(3, W0(2)), alui(PRU_OP_ADD, R(1), R(1), 1),
                            alui(PRU_OP_ADD, R(1), R(1), 1), halt()};
    const uint32_t good[] = {ldi(R(2), 2), loopr(3, W0(2)), alui(PRU_OP_ADD, R(1), R(1), 1),
                             alui(PRU_OP_ADD, R(1), R(1), 1), halt()};
    expect_fault(PRU_STRICT_ALL, bad, N(bad), PRU_STRICT_LOOP0, 1);
    expect_halt(PRU_STRICT_ALL, good, N(good));
    expect_halt(PRU_STRICT_ALL & ~PRU_STRICT_LOOP0, bad, N(bad));
}
END_TEST

START_TEST(loop_count_field) {
    /* r2.b1 and r2.w2: the two readings of the count differ (A2e); r2 and
     * r2.w0 agree */
    const uint32_t b1[] = {ldi(R(2), 0x0102), loopr(3, B1(2)), alui(PRU_OP_ADD, R(1), R(1), 1),
                           alui(PRU_OP_ADD, R(1), R(1), 1), halt()};
    const uint32_t w2[] = {ldi(W2(2), 1), loopr(3, W2(2)), alui(PRU_OP_ADD, R(1), R(1), 1),
                           alui(PRU_OP_ADD, R(1), R(1), 1), halt()};
    const uint32_t w0[] = {ldi(R(2), 2), loopr(3, W0(2)), alui(PRU_OP_ADD, R(1), R(1), 1),
                           alui(PRU_OP_ADD, R(1), R(1), 1), halt()};
    const uint32_t whole[] = {ldi(R(2), 2), loopr(3, R(2)), alui(PRU_OP_ADD, R(1), R(1), 1),
                              alui(PRU_OP_ADD, R(1), R(1), 1), halt()};
    expect_fault(PRU_STRICT_ALL, b1, N(b1), PRU_STRICT_LOOPFIELD, 1);
    expect_fault(PRU_STRICT_ALL, w2, N(w2), PRU_STRICT_LOOPFIELD, 1);
    expect_halt(PRU_STRICT_ALL, w0, N(w0));
    expect_halt(PRU_STRICT_ALL, whole, N(whole));
    expect_halt(PRU_STRICT_LOOP1 | PRU_STRICT_LOOP0, b1, N(b1));
}
END_TEST

START_TEST(mvi_any) {
    const uint32_t bad[] = {
        ldi(R(1), 8), mvi(PRU_OP_MVIW, PRU_MVI_DIRECT, W0(3), PRU_MVI_POSTINC, B0(1)), halt()};
    const uint32_t good[] = {ldi(R(1), 8), alu(PRU_OP_OR, W0(3), W0(2), W0(2)), halt()};
    expect_fault(PRU_STRICT_ALL, bad, N(bad), PRU_STRICT_MVI, 1);
    expect_halt(PRU_STRICT_ALL, good, N(good));
    expect_halt(PRU_STRICT_DRAM, bad, N(bad));
}
END_TEST

START_TEST(dram_load_store) {
    /* own data RAM, the other PRU's (0x2000), shared RAM (0x10000) */
    const uint32_t st[] = {ldi(R(2), 0x10), burst(PRU_OP_SBBO, 4, 2, 0, 4), halt()};
    const uint32_t other[] = {ldi(R(2), 0x2000), burst(PRU_OP_LBBO, 4, 2, 4, 4), halt()};
    const uint32_t shared[] = {ldi(W2(2), 1), burst(PRU_OP_LBBO, 4, 2, 0, 8), halt()};
    /* IEP COUNT through c26 is no data RAM; XOUT to a scratch pad neither */
    const uint32_t good[] = {burst(PRU_OP_LBCO, 4, 26, 0xc, 4), xfr(PRU_OP_XOUT, 10, 4, 4), halt()};
    expect_fault(PRU_STRICT_ALL, st, N(st), PRU_STRICT_DRAM, 1);
    expect_fault(PRU_STRICT_ALL, other, N(other), PRU_STRICT_DRAM, 1);
    expect_fault(PRU_STRICT_ALL, shared, N(shared), PRU_STRICT_DRAM, 1);
    expect_halt(PRU_STRICT_ALL, good, N(good));
    expect_halt(PRU_STRICT_MVI, st, N(st));
}
END_TEST

/* Clocked scope: a store between two R30 changes 3 cycles apart is caught
 * (reported at the store's PC and cycle, the core stopped after the second
 * change); with a window of 2 cycles, or after the last change, it is not. */
START_TEST(clocked_scope_from_r30) {
    const uint32_t w[] = {
        alui(PRU_OP_SET, R(30), R(30), 0), /* 0: edge at cycle 0 */
        burst(PRU_OP_SBBO, 4, 2, 0, 4),    /* 1: cycle 1 */
        alui(PRU_OP_ADD, R(1), R(1), 1),   /* 2 */
        alui(PRU_OP_CLR, R(30), R(30), 0), /* 3: edge at cycle 3 */
        burst(PRU_OP_SBBO, 4, 2, 4, 4),    /* 4: after the last edge */
        halt(),
    };
    struct pru_params p;
    pru_params_default(&p);
    p.strict = PRU_STRICT_ALL;
    struct pru_core *c = core_params(&p, w, N(w));
    ck_assert_int_eq(pru_run(c, 1000), PRU_STOP_FAULT);
    const struct pru_fault *f = pru_get_fault(c);
    ck_assert_int_eq(f->cause, PRU_FAULT_STRICT);
    ck_assert_uint_eq(f->rule, PRU_STRICT_DRAM);
    ck_assert_uint_eq(f->pc, 1);
    ck_assert_int_eq(f->cycle, 1);
    ck_assert_int_eq(f->edge_from, 0);
    ck_assert_int_eq(f->edge_to, 3);
    ck_assert_uint_eq(pru_pc(c), 4); /* stopped right after the closing edge */
    pru_core_free(c);

    p.strict_window = 2;
    c = core_params(&p, w, N(w));
    ck_assert_int_eq(pru_run(c, 1000), PRU_STOP_HALT);
    const struct pru_strict_hit *h;
    ck_assert_uint_eq(pru_strict_hits(c, &h, NULL), 0);
    pru_core_free(c);
}
END_TEST

/* Clocked scope from input edges (pru_strict_inputs): a store between two
 * changes of a watched R31 bit, as the program reads them, is caught as
 * between two R30 changes; unwatched (the default), the same run halts. */
START_TEST(clocked_scope_from_inputs) {
    const uint32_t w[] = {
        alu(PRU_OP_AND, R(1), R(31), R(31)), /* 0: bit 1 low */
        alu(PRU_OP_AND, R(1), R(31), R(31)), /* 1: high: an edge at cycle 1 */
        burst(PRU_OP_SBBO, 4, 2, 0, 4),      /* 2 */
        alu(PRU_OP_AND, R(1), R(31), R(31)), /* 3: low: an edge at cycle 3 */
        halt(),
    };
    struct pru_params p;
    pru_params_default(&p);
    p.strict = PRU_STRICT_ALL;
    for (int watched = 0; watched <= 1; watched++) {
        struct pru_core *c = core_params(&p, w, N(w));
        if (watched) {
            pru_strict_inputs(c, 1u << 1);
        }
        ck_assert_int_eq(pru_run_until_cycle(c, 1), PRU_STOP_LIMIT);
        pru_set_inputs(c, 1u << 1);
        ck_assert_int_eq(pru_run_until_cycle(c, 3), PRU_STOP_LIMIT);
        pru_set_inputs(c, 1u << 2); /* bit 2 is not watched */
        enum pru_stop why = pru_run(c, 100);
        if (!watched) {
            ck_assert_int_eq(why, PRU_STOP_HALT);
        } else {
            ck_assert_int_eq(why, PRU_STOP_FAULT);
            const struct pru_fault *f = pru_get_fault(c);
            ck_assert_uint_eq(f->rule, PRU_STRICT_DRAM);
            ck_assert_uint_eq(f->pc, 2);
            ck_assert_int_eq(f->edge_from, 1);
            ck_assert_int_eq(f->edge_to, 3);
        }
        pru_core_free(c);
    }
}
END_TEST

/* The log: every (pc, rule) once with its count, and the run goes on. */
START_TEST(log_counts) {
    const uint32_t w[] = {
        ldi(R(3), 5),
        alui(PRU_OP_XOR, R(30), R(30), 1), /* 1: top, an edge every 4 cycles */
        burst(PRU_OP_SBBO, 4, 2, 0, 4),    /* 2 */
        alui(PRU_OP_SUB, R(3), R(3), 1),   /* 3 */
        qbi(PRU_OP_QBNE, -3, R(3), 0),     /* 4 */
        alui(PRU_OP_XOR, R(30), R(30), 1), /* 5: closes the last window */
        halt(),
    };
    struct pru_params p;
    pru_params_default(&p);
    p.strict = PRU_STRICT_ALL;
    p.strict_log = 1;
    struct pru_core *c = core_params(&p, w, N(w));
    ck_assert_int_eq(pru_run(c, 1000), PRU_STOP_HALT);
    const struct pru_strict_hit *h;
    uint64_t lost;
    ck_assert_uint_eq(pru_strict_hits(c, &h, &lost), 1);
    ck_assert_uint_eq(lost, 0);
    ck_assert_uint_eq(h[0].pc, 2);
    ck_assert_uint_eq(h[0].rule, PRU_STRICT_DRAM);
    ck_assert_uint_eq(h[0].count, 5);
    ck_assert_int_eq(h[0].first_cycle, 2);
    pru_core_free(c);
}
END_TEST

START_TEST(parse_rules) {
    unsigned r;
    const char *bad = NULL;
    ck_assert_int_eq(pru_strict_parse(NULL, &r, &bad), 0);
    ck_assert_uint_eq(r, PRU_STRICT_ALL);
    ck_assert_int_eq(pru_strict_parse("loop1,dram", &r, &bad), 0);
    ck_assert_uint_eq(r, PRU_STRICT_LOOP1 | PRU_STRICT_DRAM);
    ck_assert_int_eq(pru_strict_parse("loop0,loopfield,mvi", &r, &bad), 0);
    ck_assert_uint_eq(r, PRU_STRICT_LOOP0 | PRU_STRICT_LOOPFIELD | PRU_STRICT_MVI);
    ck_assert_int_eq(pru_strict_parse("loop1,lop", &r, &bad), -1);
    ck_assert_str_eq(bad, "lop");
    ck_assert_int_eq(pru_strict_parse("loop1,", &r, &bad), -1);

    struct pru_params p;
    char err[200];
    pru_params_default(&p);
    ck_assert_int_eq(pru_contend_parse("40,1", &p, err, sizeof err), 0);
    ck_assert_uint_eq(p.contend_period, 40);
    ck_assert_uint_eq(p.contend_stall, 1);
    ck_assert_int_eq(p.contend_random, 1);
    ck_assert_uint_eq(p.contend_seed, 1);
    ck_assert_int_eq(pru_contend_parse("4,3,periodic:2", &p, err, sizeof err), 0);
    ck_assert_int_eq(p.contend_random, 0);
    ck_assert_uint_eq(p.contend_phase, 2);
    ck_assert_int_eq(pru_contend_parse("4,3,random:77", &p, err, sizeof err), 0);
    ck_assert_uint_eq(p.contend_seed, 77);
    ck_assert_int_eq(pru_contend_parse("4,3,periodic:4", &p, err, sizeof err), -1);
    ck_assert_int_eq(pru_contend_parse("0,3", &p, err, sizeof err), -1);
    ck_assert_int_eq(pru_contend_parse("4", &p, err, sizeof err), -1);
    ck_assert_int_eq(pru_contend_parse("4,3,sometimes", &p, err, sizeof err), -1);
    ck_assert_ptr_nonnull(strstr(err, "periodic or random"));
}
END_TEST

/*
 * Contention, periodic K = 4, S = 3, phase 0: host accesses at cycles 0, 4,
 * 8, ... A store (1 cycle) at cycle 1 misses; at 4 it meets one and ends at
 * 8, where the next store meets one again (ends 12); a load (3 cycles) at
 * 12 meets 12 (ends 18); one at 18 covers 18..20, meets 20 (ends 24); HALT
 * at 24. Without contention the same program takes 13 cycles.
 */
START_TEST(contention_stall_arithmetic) {
    const uint32_t w[] = {
        ldi(R(2), 0),                      /* 0 */
        burst(PRU_OP_SBBO, 4, 2, 0, 4),    /* 1: misses */
        ldi(R(3), 0),                      /* 2 */
        ldi(R(3), 0),                      /* 3 */
        burst(PRU_OP_SBBO, 4, 2, 0, 4),    /* 4: meets 4 -> 4 cycles */
        burst(PRU_OP_SBBO, 4, 2, 0, 4),    /* 8: meets 8 -> 4 cycles */
        burst(PRU_OP_LBBO, 8, 2, 0, 4),    /* 12: 3 cycles, meets 12 -> 6 */
        burst(PRU_OP_LBBO, 8, 2, 0, 4),    /* 18: 18..20 meets 20 -> 6 */
        burst(PRU_OP_LBCO, 8, 26, 0xc, 4), /* 24: IEP, not contended: 3 */
        halt(),                            /* 27 */
    };
    struct pru_params p;
    pru_params_default(&p);
    struct pru_core *c = core_params(&p, w, N(w));
    ck_assert_int_eq(pru_run(c, 1000), PRU_STOP_HALT);
    ck_assert_int_eq(pru_cycles(c), 16);
    pru_core_free(c);

    ck_assert_int_eq(pru_contend_parse("4,3,periodic", &p, NULL, 0), 0);
    c = core_params(&p, w, N(w));
    ck_assert_int_eq(pru_run(c, 1000), PRU_STOP_HALT);
    ck_assert_int_eq(pru_cycles(c), 28);
    uint64_t n, stall;
    pru_contend_stats(c, &n, &stall);
    ck_assert_uint_eq(n, 4);
    ck_assert_uint_eq(stall, 12);
    pru_core_free(c);

    /* phase 1: host at 1, 5, 9, ...: the store at 1 meets it (ends 5); 5
     * (ldi), 6 (ldi), store at 7 misses, store at 8 misses, load at 9
     * meets 9 (ends 15), load at 15..17 meets 17 (ends 21), IEP 21..23,
     * HALT at 24 */
    ck_assert_int_eq(pru_contend_parse("4,3,periodic:1", &p, NULL, 0), 0);
    c = core_params(&p, w, N(w));
    ck_assert_int_eq(pru_run(c, 1000), PRU_STOP_HALT);
    ck_assert_int_eq(pru_cycles(c), 25);
    pru_core_free(c);
}
END_TEST

/* Random: a pure function of seed and cycle, about 1/K of the accesses. */
START_TEST(contention_random) {
    const uint32_t w[] = {
        ldi(R(3), 1000),
        burst(PRU_OP_SBBO, 4, 2, 0, 4),
        alui(PRU_OP_SUB, R(3), R(3), 1),
        qbi(PRU_OP_QBNE, -2, R(3), 0),
        halt(),
    };
    struct pru_params p;
    pru_params_default(&p);
    ck_assert_int_eq(pru_contend_parse("10,2,random:5", &p, NULL, 0), 0);
    uint64_t n[2], stall[2];
    int64_t cyc[2];
    for (int i = 0; i < 2; i++) {
        struct pru_core *c = core_params(&p, w, N(w));
        ck_assert_int_eq(pru_run(c, 100000), PRU_STOP_HALT);
        pru_contend_stats(c, &n[i], &stall[i]);
        cyc[i] = pru_cycles(c);
        pru_core_free(c);
    }
    ck_assert_uint_eq(n[0], n[1]);
    ck_assert_int_eq(cyc[0], cyc[1]);
    ck_assert_uint_eq(stall[0], 2 * n[0]);
    ck_assert_uint_ge(n[0], 50);
    ck_assert_uint_le(n[0], 150);
    ck_assert_int_eq(cyc[0], 2 + 3000 + (int64_t)stall[0]);
}
END_TEST

static Suite *strict_suite(void) {
    Suite *s = suite_create("core_strict");
    TCase *t = tcase_create("strict");
    tcase_add_test(t, loop_one_instruction_body);
    tcase_add_test(t, loop_count_zero);
    tcase_add_test(t, loop_count_field);
    tcase_add_test(t, mvi_any);
    tcase_add_test(t, dram_load_store);
    tcase_add_test(t, clocked_scope_from_r30);
    tcase_add_test(t, clocked_scope_from_inputs);
    tcase_add_test(t, log_counts);
    tcase_add_test(t, parse_rules);
    suite_add_tcase(s, t);
    t = tcase_create("contention");
    tcase_add_test(t, contention_stall_arithmetic);
    tcase_add_test(t, contention_random);
    suite_add_tcase(s, t);
    return s;
}

int main(void) {
    return check_run(strict_suite());
}
