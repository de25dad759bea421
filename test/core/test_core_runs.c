/*
 * Check suite: straight runs (pru_params.straight_run; predecode.c
 * set_run(), exec.c RUN_ENTER) give exactly what running their
 * instructions one by one does.
 *
 * The predecode gives every word the length of the run of single-cycle
 * register-only instructions without a branch (and R31 reads of them)
 * from it on (struct pd .run) and what the fast loop dispatches on (.go):
 * the first of a run of two or more, a quick branch forward, a pair of the
 * firmware's clocked bit loop run as one, a call from far below (which
 * runs as one with its routine's JMP if that returns). Here:
 * - a program shaped like the firmware's bit loop gets the runs, pairs and
 *   forward branches it should, and random IRAM writes leave every word's
 *   run and dispatch those of the whole image predecoded anew;
 * - random programs of runs (ALU ops on fields, the pairs and the carry
 *   chain of three with their operands aliased or not, calls of routines
 *   of one JMP that returns or goes elsewhere, R31 reads of inputs that
 *   change every cycle, forward branches, countdown loops, LOOPs whose end
 *   falls inside a run)
 *   run in random chunks of cycles (so the cycle limit falls inside runs)
 *   with straight runs on, off and without the fast loop: after every
 *   chunk the registers, carry, PC, cycles and instructions agree.
 */
#include "check_run.h"
#include "core_priv.h" /* struct pd: .run and .go */
#include "core_test_util.h"
#include "test_rng.h"

#include <stdbool.h>
#include <stdio.h>

static uint64_t rng_state;

static uint32_t rnd(void) {
    return test_rng_next(&rng_state);
}

/* The firmware's bit loop (pru_fw/, the clocked half periods; its R30
 * writes and delay call left out): the sample shifted in from R31, the
 * CRC, the half periods' cycles taken from r12. */
#define BIT_WORDS 19u
static void make_bit_loop(uint32_t *w) {
    const uint32_t loop[BIT_WORDS] = {
        /* 0 */ alu(PRU_OP_LSL, R(2), R(31), B0(10)), /* R31 read, first of a run of 5 */
        /* 1 */ alu(PRU_OP_ADD, R(3), R(2), R(2)),    /* with 2, 3: PD_PAIR_ADD_ADC2 */
        /* 2 */ alu(PRU_OP_ADC, R(4), R(4), R(4)),
        /* 3 */ alu(PRU_OP_ADC, R(5), R(5), R(5)),
        /* 4 */ alu(PRU_OP_XOR, R(3), R(6), R(2)), /* with 5: PD_PAIR_XOR_QBBS */
        /* 5 */ qbi(PRU_OP_QBBS, 3, R(3), 31),
        /* 6 */ alui(PRU_OP_LSL, R(6), R(6), 1),
        /* 7 */ qba(3),
        /* 8 */ alui(PRU_OP_LSL, R(6), R(6), 1), /* with 9: PD_PAIR_LSL_XOR */
        /* 9 */ alu(PRU_OP_XOR, R(6), R(6), R(8)),
        /* 10 */ alui(PRU_OP_MIN, B0(11), R(12), 2), /* with 11: PD_PAIR_MIN_SUB */
        /* 11 */ alu(PRU_OP_SUB, R(12), R(12), B0(11)),
        /* 12 */ alui(PRU_OP_MIN, B1(11), R(12), 2), /* with 13: PD_PAIR_MIN_SUB */
        /* 13 */ alu(PRU_OP_SUB, R(12), R(12), B1(11)),
        /* 14 */ alui(PRU_OP_SUB, B0(7), B0(7), 1),
        /* 15 */ qbi(PRU_OP_QBEQ, 2, W0(9), 0),
        /* 16 */ halt(),
        /* 17 */ qbi(PRU_OP_QBNE, -17, B0(7), 0),
        /* 18 */ halt(),
    };
    memcpy(w, loop, sizeof loop);
}

static struct pru_core *loaded(const uint32_t *w, size_t n, int straight_run, int fast_loop) {
    struct pru_params p;
    pru_params_default(&p);
    p.straight_run = straight_run;
    p.fast_loop = fast_loop;
    return core_loaded(&p, w, n);
}

START_TEST(bit_loop_predecoded) {
    uint32_t w[BIT_WORDS];
    make_bit_loop(w);
    struct pru_core *c = loaded(w, BIT_WORDS, 1, 1);
    static const uint16_t run[BIT_WORDS] = {5, 4, 3, 2, 1, 0, 1, 0, 7, 6,
                                            5, 4, 3, 2, 1, 0, 0, 0, 0};
    for (unsigned pc = 0; pc < BIT_WORDS; pc++)
        ck_assert_msg(c->pd[pc].run == run[pc], "word %u: run %u, not %u", pc, c->pd[pc].run,
                      run[pc]);
    ck_assert_uint_eq(c->pd[0].go, PD_RUN_R31);
    ck_assert_uint_eq(c->pd[1].go, PD_PAIR_ADD_ADC2);
    ck_assert_uint_eq(c->pd[2].go, PD_RUN + PD_PLACE_adc32);
    ck_assert_uint_eq(c->pd[4].go, PD_PAIR_XOR_QBBS);
    ck_assert_uint_eq(c->pd[5].go, PD_FORWARD + PD_PLACE_qbbs32i);
    ck_assert_uint_eq(c->pd[6].go, PD_LSL32I); /* a run of one */
    ck_assert_uint_eq(c->pd[7].go, PD_FORWARD + PD_PLACE_qba);
    ck_assert_uint_eq(c->pd[8].go, PD_PAIR_LSL_XOR);
    ck_assert_uint_eq(c->pd[9].go, PD_RUN + PD_PLACE_xor32);
    ck_assert_uint_eq(c->pd[10].go, PD_PAIR_MIN_SUB);
    ck_assert_uint_eq(c->pd[11].go, PD_RUN + PD_PLACE_sub32b);
    ck_assert_uint_eq(c->pd[12].go, PD_PAIR_MIN_SUB);
    ck_assert_uint_eq(c->pd[14].go, PD_SUBBBI); /* the run's last */
    ck_assert_uint_eq(c->pd[15].go, PD_FORWARD + PD_PLACE_qbeqwi);
    ck_assert_uint_eq(c->pd[17].go, PD_QBNEBI);         /* backward */
    ck_assert_uint_eq(c->pd[c->iram_words].go, PD_END); /* one past IRAM */
    pru_core_free(c);
}
END_TEST

/* Pairs whose operands are not the firmware's are not run as one. */
START_TEST(pairs_need_their_operands) {
    const uint32_t w[] = {
        alui(PRU_OP_MIN, B0(11), R(12), 2),
        alu(PRU_OP_SUB, R(12), R(12), B1(11)), /* b1 */
        alui(PRU_OP_MIN, B0(12), R(12), 2),
        alu(PRU_OP_SUB, R(12), R(12), B0(12)), /* B is A */
        alui(PRU_OP_MIN, B0(11), R(12), 2),
        alu(PRU_OP_SUB, R(13), R(12), B0(11)), /* rd */
        alui(PRU_OP_LSL, R(6), R(6), 1),
        alu(PRU_OP_XOR, R(6), R(7), R(6)), /* rs1 */
        alu(PRU_OP_XOR, R(3), R(6), R(2)),
        qbi(PRU_OP_QBBS, -1, R(3), 31), /* backward */
        alu(PRU_OP_XOR, R(3), R(6), R(2)),
        qbi(PRU_OP_QBBS, 2, R(4), 31), /* rs1 */
        halt(),
        halt(),
        alu(PRU_OP_ADD, R(3), R(2), R(2)),
        alu(PRU_OP_ADC, R(4), R(4), R(4)),
        alu(PRU_OP_ADD, R(5), R(5), R(5)), /* no ADC */
        alu(PRU_OP_ADD, R(3), R(2), R(2)),
        alu(PRU_OP_ADC, R(4), R(4), R(4)),
        alu(PRU_OP_ADC, W0(5), W0(5), W0(5)), /* a field */
        alui(PRU_OP_ADD, R(3), R(2), 1),      /* an immediate */
        alu(PRU_OP_ADC, R(4), R(4), R(4)),
        alu(PRU_OP_ADC, R(5), R(5), R(5)),
        halt(),
    };
    struct pru_core *c = loaded(w, sizeof w / sizeof w[0], 1, 1);
    for (unsigned pc = 0; pc < sizeof w / sizeof w[0]; pc++)
        ck_assert_msg(c->pd[pc].go < PD_PAIR_MIN_SUB, "word %u: a pair (%u)", pc, c->pd[pc].go);
    pru_core_free(c);
}
END_TEST

/* A call from FF_MAX_BODY words or more below is PD_PAIR_CALL_RET; one
 * from nearer, or of a target past IRAM, is not; run as one or not, the
 * calls of a one-JMP routine give what the single steps give, also with
 * a LOOP ending at the return and with the JMP going elsewhere. */
START_TEST(call_return_as_one) {
    uint32_t w[40];
    for (unsigned i = 0; i < 40; i++)
        w[i] = alui(PRU_OP_ADD, R(7), R(7), 1);
    w[0] = qba(3);
    w[1] = jmpr(R(5));    /* the routine */
    w[2] = jmpr(W0(6));   /* a JMP elsewhere: r6 = 26 */
    w[3] = jali(R(5), 1); /* near: not as one */
    w[4] = ldi(R(6), 26);
    w[5] = qba(6);                            /* to 11 */
    w[6] = alu(PRU_OP_ADD, R(9), R(9), R(5)); /* a routine that is no JMP, ... */
    w[7] = jmpr(R(5));                        /* ... whose op2 is the link */
    w[8] = loopi(2, 2);                       /* its end a routine's JMP */
    w[9] = qba(23);                           /* to 32 */
    w[10] = jmpr(R(5));
    w[20] = jali(W0(5), 1);                  /* as one */
    w[21] = loopi(3, 2);                     /* ... */
    w[22] = alui(PRU_OP_ADD, R(8), R(8), 1); /* ... */
    w[23] = jali(R(5), 1);                   /* as one, the return the LOOP's end */
    w[24] = jali(R(5), 2);                   /* to 26: 25 skipped */
    w[25] = qba(-17);                        /* to 8 */
    w[26] = jali(W2(5), 1);                  /* r5 = 27 << 16 | 25: to 25 */
    w[30] = jali(R(5), 50);                  /* past IRAM: not as one */
    w[32] = jali(R(5), 10);                  /* the LOOP's end: not as one */
    w[33] = jali(R(5), 6);
    w[34] = halt();
    enum { ONE_RUN, CHUNKS, OFF, GENERAL_PATH, CORES };
    struct pru_core *c[CORES] = {loaded(w, 40, 1, 1), loaded(w, 40, 1, 1), loaded(w, 40, 0, 1),
                                 loaded(w, 40, 0, 0)};
    ck_assert_uint_eq(c[0]->pd[3].go, PD_JALI);
    ck_assert_uint_eq(c[0]->pd[20].go, PD_PAIR_CALL_RET);
    ck_assert_uint_eq(c[0]->pd[23].go, PD_PAIR_CALL_RET);
    ck_assert_uint_eq(c[0]->pd[24].go, PD_PAIR_CALL_RET);
    ck_assert_uint_eq(c[0]->pd[26].go, PD_PAIR_CALL_RET);
    ck_assert_uint_eq(c[0]->pd[30].go, PD_JALI);
    for (unsigned m = 0; m < CORES; m++) {
        pru_start(c[m]);
        /* CHUNKS: limits 1 to 3 cycles on, between a call and its return */
        for (unsigned k = 0; k < 1000 && !pru_halted(c[m]); k++)
            pru_run_until_cycle(c[m], pru_cycles(c[m]) + (m == CHUNKS ? 1 + k % 3 : 1000));
        ck_assert(pru_halted(c[m]));
    }
    for (unsigned m = 1; m < CORES; m++) {
        for (unsigned i = 0; i < 32; i++)
            ck_assert_uint_eq(pru_reg(c[0], i), pru_reg(c[m], i));
        ck_assert_uint_eq(pru_pc(c[0]), pru_pc(c[m]));
        ck_assert_int_eq(pru_cycles(c[0]), pru_cycles(c[m]));
        ck_assert_uint_eq(pru_instructions(c[0]), pru_instructions(c[m]));
    }
    ck_assert_uint_eq(pru_reg(c[0], 8), 2); /* the LOOPs ran twice */
    ck_assert_uint_eq(pru_reg(c[0], 7), 9); /* 11 .. 19, once */
    ck_assert_uint_eq(pru_reg(c[0], 9), 34);
    ck_assert_uint_eq(pru_reg(c[0], 5), 34);
    ck_assert_int_eq(pru_cycles(c[0]), 38);
    for (unsigned m = 0; m < CORES; m++)
        pru_core_free(c[m]);
}
END_TEST

/* A random word for the IRAM writes: straight, a branch, an R31 read, a
 * HALT, one of a pair or of a carry chain. */
static uint32_t rnd_word(void) {
    switch (rnd() % 7) {
    case 5: /* of a carry chain */
        return alu(rnd() % 2 ? PRU_OP_ADD : PRU_OP_ADC, R(1 + rnd() % 3), R(1 + rnd() % 3), R(2));
    case 0:
        return halt();
    case 1:
        return qbi(qb_ops[rnd() % N_QB_OPS], (int)(rnd() % 5) - 2, R(1 + rnd() % 3), rnd() % 4);
    case 2:
        return alu(PRU_OP_AND, R(1 + rnd() % 3), R(31), R(2));
    case 3:
        return rnd() % 2 ? alui(PRU_OP_MIN, B0(11), R(12), 2)
                         : alu(PRU_OP_SUB, R(12), R(12), B0(11));
    default:
        return alu(alu_ops[rnd() % N_ALU_OPS], R(1 + rnd() % 3), R(1 + rnd() % 3), R(2));
    }
}

START_TEST(iram_writes_keep_runs) {
    rng_state = 0x2545F4914F6CDD1Dull;
    enum { WORDS = 64 };
    uint32_t w[WORDS];
    for (unsigned i = 0; i < WORDS; i++)
        w[i] = rnd_word();
    struct pru_core *c = loaded(w, WORDS, 1, 1);
    uint32_t iram = pru_soc_base(PRU_SOC_AM335X) + 0x34000u; /* PRU0 IRAM, host view */
    /* a carry chain made and unmade by its last word: the run stays */
    const uint32_t chain[4] = {alu(PRU_OP_ADD, R(1), R(2), R(2)), alu(PRU_OP_ADC, R(3), R(3), R(3)),
                               alu(PRU_OP_ADC, R(4), R(4), R(4)), alu(PRU_OP_ADD, R(5), R(5), 0)};
    for (unsigned i = 0; i < 4; i++)
        ck_assert_int_eq(pru_host_write32(c, iram + 4 * (40 + i), chain[i]), 0);
    ck_assert_uint_eq(c->pd[40].go, PD_PAIR_ADD_ADC2);
    ck_assert_int_eq(pru_host_write32(c, iram + 4 * 42, alu(PRU_OP_XOR, R(4), R(4), R(4))), 0);
    ck_assert_uint_eq(c->pd[40].go, PD_RUN + PD_PLACE_add32);
    for (unsigned i = 0; i < 4; i++) /* as they were */
        ck_assert_int_eq(pru_host_write32(c, iram + 4 * (40 + i), w[40 + i]), 0);
    for (unsigned rep = 0; rep < 2000; rep++) {
        unsigned at = rnd() % 4 ? rnd() % 12 + 20 : rnd() % WORDS; /* often one stretch */
        w[at] = rnd_word();
        ck_assert_int_eq(pru_host_write32(c, iram + 4 * at, w[at]), 0);
        if (rep % 10)
            continue;
        struct pru_core *fresh = loaded(w, WORDS, 1, 1);
        for (unsigned pc = 0; pc <= WORDS; pc++) {
            ck_assert_msg(c->pd[pc].run == fresh->pd[pc].run, "write %u: word %u run %u, anew %u",
                          rep, pc, c->pd[pc].run, fresh->pd[pc].run);
            ck_assert_msg(c->pd[pc].go == fresh->pd[pc].go, "write %u: word %u go %u, anew %u", rep,
                          pc, c->pd[pc].go, fresh->pd[pc].go);
        }
        pru_core_free(fresh);
    }
    pru_core_free(c);
}
END_TEST

/* Inputs that change every cycle: an R31 read in a run must be made in its
 * own cycle. */
static uint32_t inputs_at(void *ctx, int64_t t_ps) {
    (void)ctx;
    uint64_t k = (uint64_t)(t_ps / PRU_PS_PER_CYCLE);
    return (uint32_t)(k * 0x9E3779B1u ^ (k >> 3)) & 0x3fffffffu;
}

/* A field r1..r8 (any of them), or r12 (the pair's counter). */
static unsigned rnd_field(void) {
    unsigned reg = rnd() % 5 ? 1 + rnd() % 8 : 12;
    return rnd() % 3 ? R(reg) : ((rnd() % 7) << 5) | reg;
}

/* One straight instruction into w at *n. */
static void straight(uint32_t *w, unsigned *n) {
    switch (rnd() % 10) {
    case 0:
        w[(*n)++] = ldi(rnd_field(), rnd() & 0xffffu);
        break;
    case 1: /* an R31 read of it */
        w[(*n)++] = alu(rnd() % 2 ? PRU_OP_XOR : PRU_OP_ADD, rnd_field(), R(31), rnd_field());
        break;
    case 2:
        w[(*n)++] = alu(PRU_OP_AND, R(0), R(0), R(0)); /* a pad */
        break;
    case 3:
        w[(*n)++] = alui(alu_ops[rnd() % N_ALU_OPS], rnd_field(), rnd_field(), rnd() % 256);
        break;
    default:
        w[(*n)++] = alu(alu_ops[rnd() % N_ALU_OPS], rnd_field(), rnd_field(), rnd_field());
        break;
    }
}

/* One of the firmware's pairs, its registers drawn so that they alias now
 * and then. */
static void pair(uint32_t *w, unsigned *n) {
    unsigned a = 1 + rnd() % 8, b = 1 + rnd() % 8, x = 1 + rnd() % 8;
    switch (rnd() % 4) {
    case 2: /* the carry chain, or nearly (its last no ADC) */
        w[(*n)++] = alu(PRU_OP_ADD, R(a), R(b), rnd() % 2 ? R(x) : ((rnd() % 7) << 5) | x);
        w[(*n)++] = rnd() % 2 ? alu(PRU_OP_ADC, R(x), R(x), R(a))
                              : alui(PRU_OP_ADC, R(b), R(a), rnd() % 256);
        w[(*n)++] = alu(rnd() % 4 ? PRU_OP_ADC : PRU_OP_ADD, R(1 + rnd() % 8), R(1 + rnd() % 8),
                        R(1 + rnd() % 8));
        break;
    case 0: {
        if (b == a)
            b = a % 8 + 1;
        unsigned field = ((rnd() % 4) << 5) | b; /* rB.b0..b3 */
        w[(*n)++] = alui(PRU_OP_MIN, field, R(a), rnd() % 4);
        w[(*n)++] = alu(PRU_OP_SUB, R(a), R(a), field);
        break;
    }
    case 1:
        w[(*n)++] = alui(PRU_OP_LSL, R(a), R(b), rnd() % 32);
        w[(*n)++] = rnd() % 2 ? alu(PRU_OP_XOR, R(x), R(a), R(rnd() % 2 ? a : b))
                              : alui(PRU_OP_XOR, R(x), R(a), rnd() % 256);
        break;
    default: /* the branch over up to 3 straight ones */
        w[(*n)++] = alu(PRU_OP_XOR, R(a), R(b), R(x));
        unsigned skip = rnd() % 4;
        w[(*n)++] = qbi(PRU_OP_QBBS, 1 + (int)skip, R(a), rnd() % 32);
        for (unsigned i = 0; i < skip; i++)
            straight(w, n);
        break;
    }
}

/* The routines at the program's start (make_program()): word y (1..8) is
 * jmp r<y>; word CALL_PAD a pad before jmp r9 (no JMP at the target). */
#define CALL_PAD      9u
#define ROUTINE_WORDS 11u

/* A call of a routine: r<y> the address past the word after the call
 * (where the JMP goes unless the link write makes it the return), the
 * link r<x>, its low or high half, x often y. */
static void call(uint32_t *w, unsigned *n) {
    if (rnd() % 5 == 0) {
        w[(*n)++] = jali(W0(9), CALL_PAD); /* (B3(9): a countdown's) */
        return;
    }
    unsigned y = 1 + rnd() % 8, x = rnd() % 4 ? y : 1 + rnd() % 8;
    unsigned link = rnd() % 3 ? R(x) : rnd() % 2 ? W0(x) : W2(x);
    unsigned past = *n + 3;
    w[(*n)++] = ldi(R(y), past);
    w[(*n)++] = jali(link, y);
    straight(w, n); /* skipped unless it returns */
}

/* Whatever comes next in a random program: mostly straight, pairs,
 * branches forward; outside a loop's body also a countdown or a LOOP. */
static void item(uint32_t *w, unsigned *n, bool in_loop);

static void items(uint32_t *w, unsigned *n, unsigned k) {
    for (unsigned i = 0; i < k; i++)
        item(w, n, true);
}

static void item(uint32_t *w, unsigned *n, bool in_loop) {
    unsigned r = rnd() % (in_loop ? 18 : 22);
    if (r >= 16 && (r < 18 || !in_loop)) {
        call(w, n);
        return;
    }
    if (r >= 18)
        r -= 2;
    if (r < 10) {
        straight(w, n);
    } else if (r < 14) {
        pair(w, n);
    } else if (r < 16) { /* a branch forward over straight ones */
        unsigned skip = rnd() % 4;
        w[(*n)++] = rnd() % 2
                        ? qbi(qb_ops[rnd() % N_QB_OPS], 1 + (int)skip, rnd_field(), rnd() % 4)
                        : qb(qb_ops[rnd() % N_QB_OPS], 1 + (int)skip, rnd_field(), rnd_field());
        for (unsigned i = 0; i < skip; i++)
            straight(w, n);
    } else if (r < 18) { /* a countdown over straight ones and pairs */
        w[(*n)++] = ldi(B3(9), 1 + rnd() % 4);
        unsigned top = *n;
        items(w, n, 1 + rnd() % 4);
        w[(*n)++] = alui(PRU_OP_SUB, B3(9), B3(9), 1);
        w[*n] = qbi(PRU_OP_QBNE, -(int)(*n - top), B3(9), 0);
        (*n)++;
    } else { /* a LOOP whose end lies inside a run: straight ones after it */
        unsigned at = (*n)++;
        items(w, n, 1 + rnd() % 5);
        w[at] = loopi(*n - at, 1 + rnd() % 4);
        straight(w, n);
        straight(w, n);
    }
}

#define WORDS    600u
#define PROGRAMS 300u

static void make_program(uint32_t *w) {
    for (unsigned i = 0; i < WORDS; i++)
        w[i] = halt();
    w[0] = qba(ROUTINE_WORDS);
    for (unsigned y = 1; y <= 8; y++)
        w[y] = jmpr(R(y));
    w[CALL_PAD] = alu(PRU_OP_AND, R(0), R(0), R(0));
    w[CALL_PAD + 1] = jmpr(R(9));
    unsigned n = ROUTINE_WORDS;
    while (n < WORDS - 80)
        item(w, &n, false);
}

enum mode { RUNS_ON, RUNS_OFF, GENERAL, MODES };

static struct pru_core *core_for(const uint32_t *w, enum mode m, uint32_t seed,
                                 const struct pru_pins *pins) {
    struct pru_core *c = loaded(w, WORDS, m == RUNS_ON, m != GENERAL);
    pru_set_pins(c, pins);
    pru_start(c);
    seed_regs(c, seed, 8);
    return c;
}

/* Chunks a program may take (its bound: work, not wall-clock time). */
#define MAX_CHUNKS 20000u

START_TEST(random_runs_match) {
    rng_state = 0x9E3779B97F4A7C15ull;
    static uint32_t w[WORDS];
    const struct pru_pins pins = {.inputs_at = inputs_at};
    unsigned firsts = 0, pairs = 0, calls = 0, chains = 0;
    for (unsigned prog = 0; prog < PROGRAMS; prog++) {
        make_program(w);
        struct pru_core *c[MODES];
        uint32_t seed = rnd();
        for (unsigned m = 0; m < MODES; m++)
            c[m] = core_for(w, (enum mode)m, seed, &pins);
        for (unsigned pc = 0; pc < WORDS; pc++) {
            firsts += c[RUNS_ON]->pd[pc].go >= PD_RUN && c[RUNS_ON]->pd[pc].go <= PD_RUN_R31;
            pairs += c[RUNS_ON]->pd[pc].go >= PD_PAIR_MIN_SUB;
            calls += c[RUNS_ON]->pd[pc].go == PD_PAIR_CALL_RET;
            chains += c[RUNS_ON]->pd[pc].go == PD_PAIR_ADD_ADC2;
        }
        /* mostly short: the limit inside a run */
        run_same_chunks(c, MODES, prog, MAX_CHUNKS, rnd, 6, 200);
        for (unsigned m = 0; m < MODES; m++)
            pru_core_free(c[m]);
    }
    /* the programs had runs and pairs to take */
    printf("runs: %u firsts of runs, %u pairs (%u calls, %u carry chains) in %u programs\n", firsts,
           pairs, calls, chains, PROGRAMS);
    ck_assert_uint_gt(firsts, 20u * PROGRAMS);
    ck_assert_uint_gt(pairs, 5u * PROGRAMS);
    ck_assert_uint_gt(calls, 3u * PROGRAMS);
    ck_assert_uint_gt(chains, 2u * PROGRAMS);
}
END_TEST

static Suite *runs_suite(void) {
    Suite *s = suite_create("core_runs");
    TCase *t = tcase_create("runs");
    tcase_set_timeout(t, 0); /* none: bounded by its work (MAX_CHUNKS) */
    tcase_add_test(t, bit_loop_predecoded);
    tcase_add_test(t, pairs_need_their_operands);
    tcase_add_test(t, call_return_as_one);
    tcase_add_test(t, iram_writes_keep_runs);
    tcase_add_test(t, random_runs_match);
    suite_add_tcase(s, t);
    return s;
}

int main(void) {
    return check_run(runs_suite());
}
