/*
 * Check suite: leaf calls (pru_params.leaf_call, leaf.h leaf_call()) give
 * exactly what running the routine does.
 *
 * A call from far below of a routine of single-cycle register-only
 * instructions returning through the link field is replayed from a memo of
 * the bytes (and carry) it read first and the bytes it wrote. Here random
 * small routines (ALU ops on byte, word and whole fields, the link's
 * neighbours r10.b0/b1, the carry, pads, forward branches, a countdown whose
 * branch back is taken or not) are called again and again from random
 * programs whose inputs change between calls, some calls inside a LOOP
 * ending at the return; and routines that must be refused (a taken branch
 * back, the link read or written, a store, an R30 write, an R31 read, a
 * return through another field). Each program runs in random chunks of
 * cycles with the leaf calls on, off, and without the fast loop: after
 * every chunk the registers, carry, PC, cycles and instructions agree.
 */
#include "check_run.h"
#include "core_priv.h" /* leaf_hits: the replays were made */
#include "core_test_util.h"
#include "test_rng.h"

#include <stdbool.h>
#include <stdio.h>

#define LINK     W2(10) /* the firmware's RET_LEAF */
#define ROUTINES 4u
#define ROUT_AT  1u  /* routine i at ROUT_AT + i * ROUT_LEN */
#define ROUT_LEN 16u /* words a routine may take */
#define MAIN     80u /* far above the routines */
#define WORDS    400u

static uint64_t rng_state;

static uint32_t rnd(void) {
    return test_rng_next(&rng_state);
}

/* A field the routines use: r1..r5 (any field), r10.b0/b1 (the link's
 * neighbours), r6.b3 (a countdown). */
static unsigned rnd_field(void) {
    switch (rnd() % 8) {
    case 0:
        return rnd() % 2 ? B0(10) : B1(10);
    case 1:
        return R(1 + rnd() % 5);
    default:
        return ((rnd() % 7) << 5) | (1 + rnd() % 5);
    }
}

/* What makes a routine one that must be refused (REFUSE_*), or none. */
enum refuse {
    REFUSE_NONE,
    REFUSE_READS_LINK,  /* reads r10.w1 (a byte of the link) */
    REFUSE_WRITES_LINK, /* writes r10.b2 */
    REFUSE_STORE,       /* SBBO */
    REFUSE_R30,         /* writes R30 */
    REFUSE_R31,         /* reads R31 */
    REFUSE_KINDS,
};

/* Routine i into w (its words from ROUT_AT + i * ROUT_LEN): n random
 * instructions, perhaps a countdown at its top (taken back while r6.b3 > 1
 * at the call), perhaps something it must be refused for, and the return. */
static void make_routine(uint32_t *w, unsigned at, enum refuse why, bool countdown, bool branches) {
    unsigned n = 1 + rnd() % 8, k = 0;
    uint32_t body[ROUT_LEN];
    if (countdown) {
        body[k++] = alui(PRU_OP_SUB, B3(6), B3(6), 1);
        body[k++] = alu(PRU_OP_AND, R(0), R(0), R(0)); /* a pad */
        body[k++] = qbi(PRU_OP_QBNE, -2, B3(6), 0);
    }
    for (unsigned i = 0; i < n; i++) {
        unsigned left = n - i; /* instructions after this one, the return included */
        switch (rnd() % (branches ? 8 : 2)) {
        case 0:
            body[k++] = alu(PRU_OP_AND, R(0), R(0), R(0));
            break;
        case 1:
            body[k++] = ldi(rnd_field(), rnd() & 0xffffu);
            break;
        case 2: /* a forward branch, at most onto the return */
            body[k++] = rnd() % 2 ? qbi(qb_ops[rnd() % N_QB_OPS], 1 + (int)(rnd() % left),
                                        rnd_field(), rnd() % 3)
                                  : qb(qb_ops[rnd() % N_QB_OPS], 1 + (int)(rnd() % left),
                                       rnd_field(), rnd_field());
            break;
        default:
            body[k++] = rnd() % 3
                            ? alu(alu_ops[rnd() % N_ALU_OPS], rnd_field(), rnd_field(), rnd_field())
                            : alui(alu_ops[rnd() % N_ALU_OPS], rnd_field(), rnd_field(), rnd() % 4);
            break;
        }
        if (why != REFUSE_NONE && i == n / 2) {
            /* replaces this instruction: a branch never lands past the return */
            k--;
            body[k++] = why == REFUSE_READS_LINK    ? alu(PRU_OP_ADD, B0(1), W1(10), B0(2))
                        : why == REFUSE_WRITES_LINK ? alui(PRU_OP_ADD, B2(10), B2(10), 0)
                        : why == REFUSE_STORE       ? burst(PRU_OP_SBBO, 4, 7, 0, 4)
                        : why == REFUSE_R30         ? alu(PRU_OP_XOR, B0(30), B0(30), B0(1))
                                                    : alu(PRU_OP_AND, B0(1), B0(31), B0(2));
        }
    }
    body[k++] = jmpr(LINK);
    ck_assert_uint_le(k, ROUT_LEN);
    memcpy(w + at, body, k * sizeof *w);
}

/* Something that changes a routine's inputs, from few values so that they
 * come back. */
static void perturb(uint32_t *w, unsigned *n) {
    switch (rnd() % 5) {
    case 0: /* the carry: bit 31 of r8 shifted out */
        w[(*n)++] = ldi(W2(8), rnd() % 2 ? 0x8000u : 0);
        w[(*n)++] = alu(PRU_OP_ADD, R(8), R(8), R(8));
        break;
    case 1:
        w[(*n)++] = ldi(B3(6), 1 + rnd() % 3); /* the countdown's turns */
        break;
    case 2:
        w[(*n)++] = ldi(rnd_field(), rnd() % 3);
        break;
    case 3:
        w[(*n)++] = alui(PRU_OP_XOR, B1(10), B1(10), 1);
        break;
    default:
        break;
    }
}

/* A call of routine at `to`: JAL with an immediate, or through r9.w0. */
static void call(uint32_t *w, unsigned *n, unsigned to) {
    if (rnd() % 2) {
        w[(*n)++] = ldi(W0(9), to);
        w[(*n)++] = enc((struct pru_insn){
            .op = PRU_OP_JAL, .rd = 10, .rdsel = PRU_SEL_W2, .rs2 = 9, .rs2sel = PRU_SEL_W0});
    } else {
        w[(*n)++] = jali(LINK, to);
    }
}

/* A random program: the routines, then calls of them with changing
 * inputs, some of them the end of a LOOP's body. */
static void make_program(uint32_t *w, bool refusing) {
    for (unsigned i = 0; i < WORDS; i++)
        w[i] = halt();
    w[0] = jmpi(MAIN);
    for (unsigned i = 0; i < ROUTINES; i++) {
        enum refuse why =
            refusing && i == 0 ? (enum refuse)(1 + rnd() % (REFUSE_KINDS - 1)) : REFUSE_NONE;
        make_routine(w, ROUT_AT + i * ROUT_LEN, why, rnd() % 3 == 0, true);
    }
    unsigned n = MAIN;
    mov32(w, &n, 7, 0x100); /* the store's address */
    w[n++] = ldi(B3(6), 1);
    while (n < WORDS - 12) {
        unsigned to = ROUT_AT + (rnd() % ROUTINES) * ROUT_LEN;
        if (rnd() % 6 == 0) { /* LOOP 3 times over a perturbation and the call */
            unsigned top = n++;
            perturb(w, &n);
            call(w, &n, to);
            w[top] = loopi(n - top, 3);
        } else {
            perturb(w, &n);
            call(w, &n, to);
        }
    }
}

enum mode { LEAF_ON, LEAF_OFF, GENERAL, MODES };

static struct pru_core *core_for(const uint32_t *w, enum mode m, uint32_t seed) {
    struct pru_params p;
    pru_params_default(&p);
    p.leaf_call = m == LEAF_ON;
    p.fast_loop = m != GENERAL;
    struct pru_core *c = core_loaded(&p, w, WORDS);
    pru_start(c);
    seed_regs(c, seed, 4);
    return c;
}

/* Chunks a program may take: one that has not halted by then fails (the
 * suite's bound is its work, PROGRAMS programs of at most MAX_CHUNKS
 * chunks, not a wall-clock time, which a loaded machine would overrun). */
#define MAX_CHUNKS 10000u

/* Runs program w each way in the same random chunks of cycles (of at most
 * `most`); returns the leaf calls replayed. */
static uint64_t compare_runs(const uint32_t *w, unsigned prog, unsigned most) {
    struct pru_core *c[MODES];
    uint32_t seed = rnd();
    for (unsigned m = 0; m < MODES; m++)
        c[m] = core_for(w, (enum mode)m, seed);
    run_same_chunks(c, MODES, prog, MAX_CHUNKS, rnd, most / 10, most);
    uint64_t hits = c[LEAF_ON]->leaf_hits;
    ck_assert_uint_eq(c[LEAF_OFF]->leaf_hits, 0);
    for (unsigned m = 0; m < MODES; m++)
        pru_core_free(c[m]);
    return hits;
}

#define PROGRAMS 300u

START_TEST(random_leaf_routines_match) {
    rng_state = 0x9E3779B97F4A7C15ull;
    static uint32_t w[WORDS];
    uint64_t hits = 0;
    unsigned with_hits = 0;
    for (unsigned prog = 0; prog < PROGRAMS; prog++) {
        make_program(w, prog % 2 == 1);
        uint64_t h = compare_runs(w, prog, 400);
        hits += h;
        with_hits += h > 0;
    }
    /* the replays were made, in most programs */
    ck_assert_uint_gt(with_hits, PROGRAMS / 2);
    printf("leaf: %llu replays in %u of %u programs\n", (unsigned long long)hits, with_hits,
           PROGRAMS);
    ck_assert_uint_gt(hits, 10u * PROGRAMS);
}
END_TEST

/* Each kind of refusal alone: the routine is never replayed, and the
 * results are those of running it. */
START_TEST(refused_routines_not_replayed) {
    rng_state = 0xD1B54A32D192ED03ull;
    static uint32_t w[WORDS];
    for (unsigned why = REFUSE_READS_LINK; why < REFUSE_KINDS; why++)
        for (unsigned rep = 0; rep < 10; rep++) {
            for (unsigned i = 0; i < WORDS; i++)
                w[i] = halt();
            w[0] = jmpi(MAIN);
            make_routine(w, ROUT_AT, (enum refuse)why, false, false);
            unsigned n = MAIN;
            mov32(w, &n, 7, 0x100);
            while (n < WORDS - 12) {
                perturb(w, &n);
                call(w, &n, ROUT_AT);
            }
            ck_assert_uint_eq(compare_runs(w, why * 100 + rep, 400), 0);
        }
}
END_TEST

/* The firmware's delay tail at 5 MHz (pru_fw/config.p DLY_L3, one turn):
 * replayed at every call (the first records it), with the cycles it takes. */
START_TEST(firmware_delay_replayed) {
    static uint32_t w[WORDS];
    for (unsigned i = 0; i < WORDS; i++)
        w[i] = halt();
    w[0] = jmpi(MAIN);
    unsigned k = ROUT_AT;
    for (unsigned i = 0; i < 3; i++)
        w[k++] = alu(PRU_OP_AND, R(0), R(0), R(0));
    w[k++] = alu(PRU_OP_AND, B1(10), B3(9), B3(9)); /* mov r10.b1, r9.b3 */
    w[k++] = alui(PRU_OP_SUB, B1(10), B1(10), 1);
    w[k++] = alu(PRU_OP_AND, R(0), R(0), R(0));
    w[k++] = alu(PRU_OP_AND, R(0), R(0), R(0));
    w[k++] = qbi(PRU_OP_QBNE, -3, B1(10), 0);
    w[k++] = jmpr(LINK);
    unsigned n = MAIN;
    w[n++] = ldi(B3(9), 1);
    w[n++] = ldi(W0(9), ROUT_AT);
    for (unsigned i = 0; i < 50; i++) {
        w[n++] = alui(PRU_OP_ADD, R(2), R(2), 1); /* changes nothing it reads */
        w[n++] = enc((struct pru_insn){
            .op = PRU_OP_JAL, .rd = 10, .rdsel = PRU_SEL_W2, .rs2 = 9, .rs2sel = PRU_SEL_W0});
    }
    rng_state = 0x5DEECE66Dull;
    ck_assert_uint_eq(compare_runs(w, 0, 1000000), 50);
}
END_TEST

/* A routine read through field `in` by a loop of 1000 calls, r2 counted up
 * before each: the results are those of running it, and `in`'s changes
 * decide the recordings. Returns the core's records and replays. */
static void count_records(unsigned in, uint64_t *records, uint64_t *hits) {
    static uint32_t w[WORDS];
    for (unsigned i = 0; i < WORDS; i++)
        w[i] = halt();
    w[0] = jmpi(MAIN);
    w[ROUT_AT] = alui(PRU_OP_ADD, B0(3), in, 1);
    w[ROUT_AT + 1] = jmpr(LINK);
    unsigned n = MAIN;
    w[n++] = ldi(R(5), 1000);
    unsigned top = n;
    w[n++] = alui(PRU_OP_ADD, R(2), R(2), 1);
    w[n++] = jali(LINK, ROUT_AT);
    w[n++] = alui(PRU_OP_SUB, R(5), R(5), 1);
    w[n] = qbi(PRU_OP_QBNE, (int)top - (int)n, R(5), 0);
    rng_state = 0x2545F4914F6CDD1Dull;
    compare_runs(w, in, 400);
    struct pru_core *c = core_for(w, LEAF_ON, 7);
    ck_assert_int_eq(pru_run(c, 100000), PRU_STOP_HALT);
    ck_assert_uint_eq(c->r[5], 0);
    *records = c->leaf_records;
    *hits = c->leaf_hits;
    pru_core_free(c);
}

/* Inputs that change at every call (all of r2, a counter): recorded a few
 * times, not 1000 (leaf.c leaf_other: the recordings that did not repay
 * themselves back off; the firmware's bit-grid check in its delay tails
 * reads samples so). Inputs that change every 256 calls (r2.b1): each
 * record repays itself, so each change is recorded at once, and all the
 * other calls are replayed. */
START_TEST(changing_inputs_recorded_seldom) {
    uint64_t records, hits;
    count_records(R(2), &records, &hits);
    ck_assert_uint_le(records, 8);
    count_records(B1(2), &records, &hits);
    ck_assert_uint_eq(records, 1000 / 256 + 1);
    ck_assert_uint_eq(hits, 1000);
}
END_TEST

static Suite *leaf_suite(void) {
    Suite *s = suite_create("core_leaf");
    TCase *t = tcase_create("leaf");
    tcase_set_timeout(t, 0); /* none: bounded by its work (MAX_CHUNKS) */
    tcase_add_test(t, random_leaf_routines_match);
    tcase_add_test(t, refused_routines_not_replayed);
    tcase_add_test(t, firmware_delay_replayed);
    tcase_add_test(t, changing_inputs_recorded_seldom);
    suite_add_tcase(s, t);
    return s;
}

int main(void) {
    return check_run(leaf_suite());
}
