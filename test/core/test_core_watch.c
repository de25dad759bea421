/*
 * Check suite: the store watch (pru_set_store_watch) knows when the store
 * was made. Inside the callback pru_cycles() is the cycle the store was
 * issued in and pru_pc() its address, on every path of the execute loop:
 * the threaded fast loop keeps its cycle and pc in registers, and a watch
 * that read the core's copies there saw them as of the last time the loop
 * synced out (up to a whole run of register instructions stale).
 *
 * A store after a straight run of ALU instructions, and in a loop, against
 * cycles counted by hand; then random programs (ALU ops, forward branches,
 * countdown loops the fast-forward skips, LOOPs, loads, stores of every
 * length around the watched byte through a register and a constant-table
 * base) run with the defaults, with every instruction the general way
 * (fast_loop 0) and traced: each hit's cycle, pc and the stored word
 * agree, hit for hit.
 */
#include "check_run.h"
#include "core_test_util.h"
#include "test_rng.h"

#include <stdbool.h>
#include <stdio.h>

#define WATCH    0x104u /* the watched byte */
#define BASE     0x100u /* r1, and C24 (own data RAM, block BASE >> 8) */
#define CTBIR0   (0x4A300000u + PRU_OFS_CTRL0 + 0x20u) /* C24's block index, bits 7:0 */
#define MAX_HITS 4096u

struct hit {
    int64_t cycle;
    uint32_t pc, word;
};

struct watch_log {
    struct pru_core *c;
    unsigned n;
    struct hit h[MAX_HITS];
};

static void on_store(void *ctx, uint32_t addr) {
    struct watch_log *log = ctx;
    ck_assert_uint_eq(addr, WATCH);
    ck_assert_uint_lt(log->n, MAX_HITS);
    struct hit *h = &log->h[log->n++];
    h->cycle = pru_cycles(log->c);
    h->pc = pru_pc(log->c);
    ck_assert_int_eq(pru_host_read(log->c, 0x4A300000u + WATCH, &h->word, 4), 0);
}

/* Runs w on an AM335x PRU0 with params p (NULL: defaults), optionally
 * traced to /dev/null, until HALT; the watch's hits into log. */
static void run_logged(const uint32_t *w, size_t n, const struct pru_params *p, bool traced,
                       struct watch_log *log) {
    struct pru_core *c = pru_core_new(PRU_SOC_AM335X, p);
    ck_assert_ptr_nonnull(c);
    ck_assert_int_eq(pru_load_image(c, w, n * 4), 0);
    ck_assert_int_eq(pru_host_write32(c, CTBIR0, BASE >> 8), 0);
    pru_start(c);
    log->c = c;
    log->n = 0;
    pru_set_store_watch(c, WATCH, on_store, log);
    FILE *f = traced ? fopen("/dev/null", "w") : NULL;
    if (traced) {
        ck_assert_ptr_nonnull(f);
        pru_set_trace(c, f);
    }
    enum pru_stop why = pru_run(c, 10000000);
    if (why != PRU_STOP_HALT)
        pru_print_fault(c, stderr);
    ck_assert_int_eq(why, PRU_STOP_HALT);
    pru_set_trace(c, NULL);
    if (f)
        fclose(f);
    pru_core_free(c);
}

/* A store after 30 one-cycle instructions: issued in cycle 32 at pc 32. */
START_TEST(store_after_straight_run) {
    uint32_t w[40];
    unsigned n = 0;
    w[n++] = ldi(R(1), BASE);
    w[n++] = ldi(R(2), 0x5a5a);
    for (unsigned i = 0; i < 30; i++)
        w[n++] = alui(PRU_OP_ADD, R(3), R(3), 1);
    w[n++] = burst(PRU_OP_SBBO, 4 * 2, 1, WATCH - BASE, 4);
    w[n++] = halt();
    static struct watch_log log;
    run_logged(w, n, NULL, false, &log);
    ck_assert_uint_eq(log.n, 1);
    ck_assert_int_eq(log.h[0].cycle, 32);
    ck_assert_uint_eq(log.h[0].pc, 32);
    ck_assert_uint_eq(log.h[0].word, 0x5a5a);
}
END_TEST

/* A store in a countdown loop of 5 turns: each turn 4 cycles (SUB, ADD,
 * SBBO of 4 bytes, QBNE), the store at the third. */
START_TEST(store_in_a_loop) {
    uint32_t w[16];
    unsigned n = 0;
    w[n++] = ldi(R(1), BASE);
    w[n++] = ldi(R(4), 5);
    w[n++] = alui(PRU_OP_SUB, R(4), R(4), 1); /* pc 2: the loop's top */
    w[n++] = alui(PRU_OP_ADD, R(2), R(2), 3);
    w[n++] = burst(PRU_OP_SBBO, 4 * 2, 1, WATCH - BASE, 4);
    w[n++] = qbi(PRU_OP_QBNE, -3, R(4), 0);
    w[n++] = halt();
    static struct watch_log log;
    run_logged(w, n, NULL, false, &log);
    ck_assert_uint_eq(log.n, 5);
    for (unsigned k = 0; k < 5; k++) {
        ck_assert_int_eq(log.h[k].cycle, 2 + 4 * (int64_t)k + 2);
        ck_assert_uint_eq(log.h[k].pc, 4);
        ck_assert_uint_eq(log.h[k].word, 3 * (k + 1));
    }
}
END_TEST

static uint64_t rng_state;

static uint32_t rnd(void) {
    return test_rng_next(&rng_state);
}

/* r2..r9: what the random instructions compute on and store. */
static unsigned rnd_reg(void) {
    return 2 + rnd() % 8;
}

static uint32_t rnd_alu(void) {
    return rnd() % 2 ? alu(alu_ops[rnd() % N_ALU_OPS], R(rnd_reg()), R(rnd_reg()), R(rnd_reg()))
                     : alui(alu_ops[rnd() % N_ALU_OPS], R(rnd_reg()), R(rnd_reg()), rnd() % 256);
}

/* A store of 1..8 bytes from r2.. at BASE + 0..8: covering the watched
 * byte about half the time. Through r1 or through C24 (run_logged points
 * it at BASE). */
static uint32_t rnd_store(void) {
    unsigned len = 1 + rnd() % 8, off = rnd() % 9;
    return rnd() % 2 ? burst(PRU_OP_SBBO, 4 * rnd_reg(), 1, off, len)
                     : burst(PRU_OP_SBCO, 4 * rnd_reg(), 24, off, len);
}

#define PROG_WORDS 600u

/* A random program that halts: blocks of ALU runs, forward branches,
 * countdown loops, LOOPs, loads and stores. */
static unsigned make_program(uint32_t *w) {
    unsigned n = 0;
    w[n++] = ldi(R(1), BASE);
    while (n < PROG_WORDS - 24) {
        switch (rnd() % 6) {
        case 0: { /* a run of ALU instructions, long enough to stay in the fast loop */
            unsigned k = 1 + rnd() % 12;
            for (unsigned i = 0; i < k; i++)
                w[n++] = rnd_alu();
            break;
        }
        case 1: /* a forward branch over 1..3 instructions */
            w[n] = qb(qb_ops[rnd() % N_QB_OPS], 2 + (int)(rnd() % 3), R(rnd_reg()), R(rnd_reg()));
            n++;
            for (unsigned i = 0; i < 3; i++)
                w[n++] = rnd() % 3 ? rnd_alu() : rnd_store();
            break;
        case 2: { /* a countdown of 1..40 turns, a store in it now and then */
            w[n++] = ldi(R(10), 1 + rnd() % 40);
            unsigned top = n;
            w[n++] = alui(PRU_OP_SUB, R(10), R(10), 1);
            if (rnd() % 2)
                w[n++] = rnd() % 2 ? rnd_store() : alu(PRU_OP_AND, R(0), R(0), R(0));
            w[n] = qbi(PRU_OP_QBNE, (int)top - (int)n, R(10), 0);
            n++;
            break;
        }
        case 3: { /* LOOP of 1..6 turns over 1..3 instructions */
            unsigned body = 1 + rnd() % 3;
            w[n++] = loopi(body + 1, 1 + rnd() % 6);
            for (unsigned i = 0; i < body; i++)
                w[n++] = rnd() % 3 ? rnd_alu() : rnd_store();
            break;
        }
        case 4: /* a load: several cycles */
            w[n++] = burst(PRU_OP_LBBO, 4 * rnd_reg(), 1, rnd() % 16, 1 + rnd() % 8);
            break;
        default:
            w[n++] = rnd_store();
            break;
        }
    }
    w[n++] = halt();
    return n;
}

static bool same_hit(const struct hit *a, const struct hit *b) {
    return a->cycle == b->cycle && a->pc == b->pc && a->word == b->word;
}

START_TEST(random_programs_agree) {
    rng_state = 0x2545F4914F6CDD1Dull;
    static uint32_t w[PROG_WORDS];
    static struct watch_log log[3];
    struct pru_params general;
    pru_params_default(&general);
    general.fast_loop = 0;
    unsigned hits = 0;
    for (unsigned prog = 0; prog < 200; prog++) {
        unsigned n = make_program(w);
        run_logged(w, n, NULL, false, &log[0]);
        run_logged(w, n, &general, false, &log[1]);
        run_logged(w, n, NULL, true, &log[2]);
        for (unsigned m = 1; m < 3; m++) {
            ck_assert_uint_eq(log[m].n, log[0].n);
            for (unsigned k = 0; k < log[0].n; k++)
                ck_assert_msg(same_hit(&log[0].h[k], &log[m].h[k]),
                              "program %u, hit %u: fast loop cycle %lld pc %u word 0x%x, "
                              "%s cycle %lld pc %u word 0x%x",
                              prog, k, (long long)log[0].h[k].cycle, log[0].h[k].pc,
                              log[0].h[k].word, m == 1 ? "general" : "traced",
                              (long long)log[m].h[k].cycle, log[m].h[k].pc, log[m].h[k].word);
        }
        hits += log[0].n;
    }
    ck_assert_uint_gt(hits, 2000); /* the programs did store over the watched byte */
}
END_TEST

int main(void) {
    Suite *s = suite_create("core_watch");
    TCase *t = tcase_create("watch");
    tcase_add_test(t, store_after_straight_run);
    tcase_add_test(t, store_in_a_loop);
    tcase_add_test(t, random_programs_agree);
    suite_add_tcase(s, t);
    return check_run(s);
}
