/*
 * Check suite: the fast-forward's skips (emulator/core/ff.c, TIMING.md
 * "Fast-forward") give exactly the cycles, instructions and registers of
 * running every instruction: counted polls (on a register or a field of
 * one), polls on one R31 bit of a
 * shift-mode input, LOOP delays, countdown loops; and loops that look alike but are not
 * skippable run as they are.
 */
#include "check_run.h"
#include "core_priv.h" /* ff_decoded: the bodies decoded */
#include "core_test_util.h"

#include <stdint.h>

#define BASE   0x00000000u /* AM335x PRU0 local view */
#define GPCFG0 (BASE + 0x26008u)

/* One input edge: SL high from 0, low from t_fall (INT64_MAX: never). */
struct edge_in {
    int64_t t_fall;
};

static uint32_t in_at(void *ctx, int64_t t) {
    const struct edge_in *e = ctx;
    return t < e->t_fall ? 1u : 0u;
}

static int64_t in_next(void *ctx, int64_t t) {
    const struct edge_in *e = ctx;
    return t < e->t_fall ? e->t_fall : INT64_MAX;
}

enum path { ALL, NO_COUNTED, NO_R31_BITS, NO_LOOP_DELAY, NO_COUNT_LOOP, NONE, PATHS };

static struct pru_core *ff_core(enum path p, struct edge_in *in) {
    struct pru_params prm;
    pru_params_default(&prm);
    prm.fast_forward = p != NONE;
    prm.ff_counted = p != NO_COUNTED;
    prm.ff_r31_bits = p != NO_R31_BITS;
    prm.ff_loop_delay = p != NO_LOOP_DELAY;
    prm.ff_count_loop = p != NO_COUNT_LOOP;
    struct pru_core *c = pru_core_new(PRU_SOC_AM335X, &prm);
    ck_assert_ptr_nonnull(c);
    if (in) {
        struct pru_pins pins = {.ctx = in, .inputs_at = in_at, .next_input_change = in_next};
        pru_set_pins(c, &pins);
    }
    return c;
}

struct outcome {
    int64_t cycles;
    uint64_t insns, skipped;
    uint32_t r2;
};

/* The program's first words: GPCFG0 to shift mode at 80 MHz. Returns how
 * many. */
static unsigned shift_mode_80mhz(uint32_t *prog) {
    prog[0] = ldi(R(1), 2u | 3u << 3);
    prog[1] = burst(PRU_OP_SBCO, 4 * 1, 4, 8, 4); /* GPCFG0 */
    return 2;
}

/* Shift mode at 80 MHz (the firmware's 8x clock at 10 MHz: 2.5 cycles a
 * sample, so Cnt_16 pulses every 40 cycles once SB is set), then a poll
 * with a time-out on R31 bit 0 low: qbbc DONE, r31, 0; sub r2, r2, 1;
 * qbne POLL, r2, 0 (once bit 0 shows the high level); or with `field`, on
 * the newest 4 samples all low through and r1.b3, r31.b0, 15 (as the
 * firmware waits for SL idle); with `field` 2, the same test counted down
 * by 4 until the count goes below 0: sub r2, r2, 4; qbbc POLL, r2, 31 (the
 * firmware's IEP_POLL). */
static struct outcome counted_poll(enum path p, int64_t t_fall, unsigned count, int field) {
    struct edge_in in = {t_fall};
    struct pru_core *c = ff_core(p, &in);
    uint32_t prog[16];
    unsigned n = shift_mode_80mhz(prog);
    prog[n++] = ldi(R(2), count);
    prog[n++] = qbi(PRU_OP_QBBC, 0, R(31), 0); /* until the high level is sampled */
    if (field) { /* the newest 4 samples low: and r1.b3, r31.b0, 15; qbeq DONE, r1.b3, 0 */
        prog[n++] = alui(PRU_OP_AND, B3(1), B0(31), 15);
        prog[n++] = qbi(PRU_OP_QBEQ, 3, B3(1), 0);
        prog[n++] = alui(PRU_OP_SUB, R(2), R(2), field == 2 ? 4 : 1);
        prog[n++] = field == 2 ? qbi(PRU_OP_QBBC, -3, R(2), 31) : qbi(PRU_OP_QBNE, -3, R(2), 0);
    } else {
        prog[n++] = qbi(PRU_OP_QBBC, 3, R(31), 0);
        prog[n++] = alui(PRU_OP_SUB, R(2), R(2), 1);
        prog[n++] = qbi(PRU_OP_QBNE, -2, R(2), 0);
    }
    prog[n++] = halt();
    pru_load_image(c, prog, n * 4);
    pru_start(c);
    ck_assert_int_eq(pru_run(c, 10000000), PRU_STOP_HALT);
    struct outcome o = {pru_cycles(c), pru_instructions(c), pru_ff_skipped(c), pru_reg(c, 2)};
    pru_core_free(c);
    return o;
}

static void same(const struct outcome *a, const struct outcome *b, const char *what, int64_t t) {
    ck_assert_msg(a->cycles == b->cycles && a->insns == b->insns && a->r2 == b->r2,
                  "%s, fall at %lld ps: %lld cycles %llu insns r2=%u vs %lld %llu %u", what,
                  (long long)t, (long long)a->cycles, (unsigned long long)a->insns, a->r2,
                  (long long)b->cycles, (unsigned long long)b->insns, b->r2);
}

/* The fall at every quarter ns over two shift periods: the poll ends on the
 * same cycle with every fast path, without each, and without any (a shift
 * edge between the fall and the next cycle boundary must not be missed). */
START_TEST(counted_poll_exact) {
    for (int field = 0; field < 3; field++) {
        for (int64_t t = 20000000; t < 20000000 + 25000; t += 250) {
            struct outcome ref = counted_poll(NONE, t, 60000, field);
            ck_assert_uint_eq(ref.skipped, 0);
            for (enum path p = ALL; p < NONE; p++) {
                struct outcome o = counted_poll(p, t, 60000, field);
                same(&o, &ref, field ? "field poll, a fast path off" : "fast path off", t);
            }
            struct outcome all = counted_poll(ALL, t, 60000, field);
            struct outcome no_counted = counted_poll(NO_COUNTED, t, 60000, field);
            struct outcome no_bits = counted_poll(NO_R31_BITS, t, 60000, field);
            /* 20 us of polling at 3 or 4 cycles a turn: nearly all skipped */
            ck_assert_uint_gt(all.skipped, 900);
            ck_assert_uint_eq(no_counted.skipped, 0); /* r2 changes every turn */
            ck_assert_uint_lt(no_bits.skipped, all.skipped);
        }
    }
}
END_TEST

/* No fall: the counter ends the poll, on the same cycle with r2 = 0; or,
 * counted down by 4 to below 0, with r2 = -4 .. -1 (counts that are a
 * multiple of the step and not; one step, none left). */
START_TEST(counted_poll_times_out) {
    struct outcome ref = counted_poll(NONE, INT64_MAX, 5000, 0);
    struct outcome all = counted_poll(ALL, INT64_MAX, 5000, 0);
    same(&all, &ref, "time-out", INT64_MAX);
    ck_assert_uint_eq(all.r2, 0);
    ck_assert_uint_gt(all.skipped, 4900);
    static const unsigned counts[] = {20000, 20001, 20003, 4, 3, 0};
    for (unsigned i = 0; i < sizeof counts / sizeof counts[0]; i++) {
        ref = counted_poll(NONE, INT64_MAX, counts[i], 2);
        all = counted_poll(ALL, INT64_MAX, counts[i], 2);
        struct outcome no_counted = counted_poll(NO_COUNTED, INT64_MAX, counts[i], 2);
        same(&all, &ref, "time-out below 0", INT64_MAX);
        same(&no_counted, &ref, "time-out below 0, ff-counted off", INT64_MAX);
        ck_assert_uint_eq(all.r2, counts[i] % 4 - 4);
        if (counts[i] > 100) {
            ck_assert_uint_gt(all.skipped, counts[i] / 4 - 10);
            ck_assert_uint_eq(no_counted.skipped, 0);
        }
    }
}
END_TEST

/* A counter the body also reads (add r3, r3, r2) is no counted poll: the
 * loop runs as it is, and r3 shows every turn. */
START_TEST(counter_read_elsewhere_runs) {
    uint32_t r3[2];
    for (int ff = 0; ff < 2; ff++) {
        struct edge_in in = {INT64_MAX};
        struct pru_core *c = ff_core(ff ? ALL : NONE, &in);
        uint32_t prog[8];
        unsigned n = 0;
        prog[n++] = ldi(R(2), 1000);
        prog[n++] = qbi(PRU_OP_QBBC, 4, R(31), 0);
        prog[n++] = alu(PRU_OP_ADD, R(3), R(3), R(2));
        prog[n++] = alui(PRU_OP_SUB, R(2), R(2), 1);
        prog[n++] = qbi(PRU_OP_QBNE, -3, R(2), 0);
        prog[n++] = halt();
        pru_load_image(c, prog, n * 4);
        pru_start(c);
        ck_assert_int_eq(pru_run(c, 1000000), PRU_STOP_HALT);
        r3[ff] = pru_reg(c, 3);
        if (ff)
            ck_assert_uint_eq(pru_ff_skipped(c), 0);
        pru_core_free(c);
    }
    ck_assert_uint_eq(r3[0], 1000u * 1001u / 2u);
    ck_assert_uint_eq(r3[1], r3[0]);
}
END_TEST

/* A counted poll on a field of r2 (the firmware's FE_POLL counts r1.w2):
 * the rest of r2 holds 0x5a5a (w0) or 0x5a (b0) and must keep it. */
struct field_counter {
    const char *name;
    unsigned field;    /* W2(2), B1(2), ... */
    int op;            /* PRU_OP_SUB or PRU_OP_ADD */
    unsigned step;     /* its immediate */
    unsigned start;    /* the field's first value */
    unsigned end;      /* QBNE's value */
    unsigned other;    /* the other field: W0(2) or B0(2) (0: none) */
    int other_written; /* the body also writes the other field: no counted poll */
};

struct field_outcome {
    struct outcome o;
    uint32_t carry; /* the carry the loop left (adc r3, r4, 0 after it) */
};

/* Shift mode at 80 MHz as counted_poll(); the poll waits for the newest 4
 * samples low through and r1.b3, r31.b0, 15 and steps f's field. */
static struct field_outcome field_poll(enum path p, int64_t t_fall, const struct field_counter *f) {
    struct edge_in in = {t_fall};
    struct pru_core *c = ff_core(p, &in);
    uint32_t prog[16];
    unsigned n = shift_mode_80mhz(prog);
    if (f->other)
        prog[n++] = ldi(f->other, f->other == W0(2) ? 0x5a5a : 0x5a);
    prog[n++] = ldi(f->field, f->start);
    prog[n++] = qbi(PRU_OP_QBBC, 0, R(31), 0); /* until the high level is sampled */
    unsigned top = n;
    prog[n++] = alui(PRU_OP_AND, f->other_written ? f->other : B3(1), B0(31), 15);
    prog[n++] = qbi(PRU_OP_QBEQ, 0, f->other_written ? f->other : B3(1), 0); /* to DONE */
    unsigned exit_at = n - 1;
    prog[n++] = alui(f->op, f->field, f->field, f->step);
    int back = (int)top - (int)n;
    prog[n++] = qbi(PRU_OP_QBNE, back, f->field, f->end);
    prog[exit_at] =
        qbi(PRU_OP_QBEQ, (int)(n - exit_at), f->other_written ? f->other : B3(1), 0); /* DONE: */
    prog[n++] = alui(PRU_OP_ADC, R(3), R(4), 0);
    prog[n++] = halt();
    pru_load_image(c, prog, n * 4);
    pru_start(c);
    ck_assert_int_eq(pru_run(c, 10000000), PRU_STOP_HALT);
    struct field_outcome o = {
        {pru_cycles(c), pru_instructions(c), pru_ff_skipped(c), pru_reg(c, 2)}, pru_reg(c, 3)};
    pru_core_free(c);
    return o;
}

/* Counter fields at their corners: a half-word counted down to 0 as the
 * firmware's (ended by the fall, or timing out with the other half kept), a
 * byte counted up by 3 that wraps twice at the byte's width before it meets
 * its end (the carry of the wrapping step included), and a body that also
 * writes another field of the counter's register (no counted poll: it runs
 * as it is). Every fast path on, each off and all off: the same cycles,
 * instructions, r2 and carry. */
START_TEST(counted_field_poll_exact) {
    static const struct field_counter fc[] = {
        {"w2 down, fall", W2(2), PRU_OP_SUB, 1, 60000, 0, W0(2), 0},
        {"w2 down, time-out", W2(2), PRU_OP_SUB, 1, 5000, 0, W0(2), 0},
        {"w2 down by 255, time-out", W2(2), PRU_OP_SUB, 255, 255 * 200, 0, W0(2), 0},
        {"b1 up by 3, two wraps", B1(2), PRU_OP_ADD, 3, 10, 2, B0(2), 0},
        {"w1 down, b0 written too", W1(2), PRU_OP_SUB, 1, 5000, 0, B0(2), 1},
    };
    for (unsigned i = 0; i < sizeof fc / sizeof fc[0]; i++) {
        const struct field_counter *f = &fc[i];
        int64_t falls[] = {20000000, 20000000 + 7250, INT64_MAX};
        for (unsigned k = 0; k < 3; k++) {
            int64_t t = i == 0 ? falls[k] : INT64_MAX;
            struct field_outcome ref = field_poll(NONE, t, f);
            ck_assert_uint_eq(ref.o.skipped, 0);
            for (enum path p = ALL; p < NONE; p++) {
                struct field_outcome o = field_poll(p, t, f);
                same(&o.o, &ref.o, f->name, t);
                ck_assert_msg(o.carry == ref.carry, "%s: carry %u vs %u", f->name, o.carry,
                              ref.carry);
            }
            struct field_outcome all = field_poll(ALL, t, f);
            struct field_outcome no_counted = field_poll(NO_COUNTED, t, f);
            ck_assert_uint_eq(no_counted.o.skipped, 0);
            if (f->other_written) {
                ck_assert_uint_eq(all.o.skipped, 0);
            } else {
                ck_assert_msg(all.o.skipped * 10 > all.o.insns / 4 * 9,
                              "%s: %llu turns of %llu skipped", f->name,
                              (unsigned long long)all.o.skipped,
                              (unsigned long long)all.o.insns / 4);
            }
        }
    }
    /* the time-outs end with the counter at its end, the rest kept */
    ck_assert_uint_eq(field_poll(ALL, INT64_MAX, &fc[1]).o.r2, 0x5a5au);
    ck_assert_uint_eq(field_poll(ALL, INT64_MAX, &fc[3]).o.r2, 0x025au);
}
END_TEST

/* prog (n words) on c, run in pieces of `piece` cycles, never past a
 * piece's limit, until it halts (within max_cycles). */
static void run_to_halt(struct pru_core *c, const uint32_t *prog, unsigned n, int64_t piece,
                        int64_t max_cycles) {
    pru_load_image(c, prog, n * 4);
    pru_start(c);
    enum pru_stop st = PRU_STOP_LIMIT;
    for (int64_t limit = piece; st == PRU_STOP_LIMIT && limit < max_cycles; limit += piece) {
        st = pru_run_until_cycle(c, limit);
        ck_assert_int_le(pru_cycles(c), limit);
    }
    ck_assert_int_eq(st, PRU_STOP_HALT);
}

/* loop END, r0; <body>; END: halt -- run in pieces of `piece` cycles. */
static struct outcome loop_run(enum path p, uint32_t body, unsigned count, int64_t piece) {
    struct pru_core *c = ff_core(p, NULL);
    uint32_t prog[8];
    unsigned n = 0;
    prog[n++] = ldi(R(0), count);
    prog[n++] = loopr(2, R(0));
    prog[n++] = body;
    prog[n++] = alui(PRU_OP_ADD, R(2), R(2), 7);
    prog[n++] = halt();
    run_to_halt(c, prog, n, piece, 2000000);
    struct outcome o = {pru_cycles(c), pru_instructions(c), pru_ff_skipped(c), pru_reg(c, 2)};
    pru_core_free(c);
    return o;
}

/* A LOOP delay (mov r0, r0 = and r0, r0, r0) runs at once, never past a
 * run's limit, with the cycles and instructions of running it. */
START_TEST(loop_delay_exact) {
    uint32_t delay = alu(PRU_OP_AND, R(0), R(0), R(0));
    for (int64_t piece = 7; piece <= 70007; piece += 10000) {
        struct outcome ref = loop_run(NONE, delay, 9000, piece);
        struct outcome off = loop_run(NO_LOOP_DELAY, delay, 9000, piece);
        struct outcome all = loop_run(ALL, delay, 9000, piece);
        same(&off, &ref, "delay, no loop-delay path", piece);
        same(&all, &ref, "delay, all fast paths", piece);
        ck_assert_int_eq(ref.cycles, 9000 + 4);
        ck_assert_uint_eq(off.skipped, 0);
        /* (a LOOP is run at once when entered; cut by a limit, its rest runs) */
        ck_assert_uint_gt(all.skipped, piece > 9000 ? 8999 : (uint64_t)piece - 3);
    }
}
END_TEST

/* A LOOP over an instruction that changes something runs every turn. */
START_TEST(loop_with_work_runs) {
    struct outcome all = loop_run(ALL, alui(PRU_OP_ADD, R(2), R(2), 1), 500, 1000000);
    ck_assert_uint_eq(all.r2, 500 + 7);
    ck_assert_uint_eq(all.skipped, 0);
    /* the same register in another field is not "itself" */
    all = loop_run(ALL, alu(PRU_OP_OR, R(2), W0(2), W0(2)), 500, 1000000);
    ck_assert_uint_eq(all.skipped, 0);
}
END_TEST

/* The whole state a countdown loop leaves. */
struct count_end {
    int64_t cycles;
    uint64_t insns, skipped;
    uint32_t r[30];
};

/*
 * A delay as the firmware writes it (pru_fw/config.p DLY_TURN), with a
 * work instruction `work` among the pads: r10 = 0x00ab00cd with `count`
 * in r10.b1, r6/r7 inputs; the turns: sub r10.b1, r10.b1, step; work; mov
 * r0, r0; qbne TURN, r10.b1, 0; then adc r8, r8, 0 shows the carry. Run
 * in pieces of `piece` cycles.
 */
static struct count_end count_run(enum path p, uint32_t work, unsigned count, unsigned step,
                                  int64_t piece) {
    struct pru_core *c = ff_core(p, NULL);
    uint32_t prog[24];
    unsigned n = 0;
    mov32(prog, &n, 10, 0x00ab00cdu | count << 8);
    mov32(prog, &n, 6, 0x12345678u);
    prog[n++] = ldi(R(7), 0x5a5a);
    prog[n++] = alui(PRU_OP_SUB, B1(10), B1(10), step);
    prog[n++] = work;
    prog[n++] = alu(PRU_OP_AND, R(0), R(0), R(0));
    prog[n++] = qbi(PRU_OP_QBNE, -3, B1(10), 0);
    prog[n++] = alui(PRU_OP_ADC, R(8), R(8), 0);
    prog[n++] = halt();
    run_to_halt(c, prog, n, piece, 10000000);
    struct count_end e = {pru_cycles(c), pru_instructions(c), pru_ff_skipped(c), {0}};
    for (unsigned i = 0; i < 30; i++)
        e.r[i] = pru_reg(c, i);
    pru_core_free(c);
    return e;
}

static void same_end(const struct count_end *a, const struct count_end *b, const char *what,
                     int64_t piece) {
    ck_assert_msg(a->cycles == b->cycles && a->insns == b->insns,
                  "%s, pieces of %lld: %lld cycles %llu insns vs %lld %llu", what, (long long)piece,
                  (long long)a->cycles, (unsigned long long)a->insns, (long long)b->cycles,
                  (unsigned long long)b->insns);
    for (unsigned i = 0; i < 30; i++)
        ck_assert_msg(a->r[i] == b->r[i], "%s, pieces of %lld: r%u = 0x%x vs 0x%x", what,
                      (long long)piece, i, a->r[i], b->r[i]);
}

/* A countdown delay runs at once, never past a run's limit, with the
 * registers, carry, cycles and instructions of running it: with a pad or
 * an invariant write (xor r5, r6, r7; ldi r4) in the body, with steps that
 * end on 0 and ones that wrap the field first. */
START_TEST(count_loop_exact) {
    const uint32_t works[] = {alu(PRU_OP_AND, R(0), R(0), R(0)), alu(PRU_OP_XOR, R(5), R(6), R(7)),
                              ldi(R(4), 0x4321), alui(PRU_OP_LSR, W2(9), W0(6), 3)};
    const unsigned steps[] = {1, 3, 5};
    for (unsigned w = 0; w < sizeof works / sizeof works[0]; w++) {
        for (unsigned s = 0; s < 3; s++) {
            for (int64_t piece = 5; piece <= 100005; piece += 20000) {
                struct count_end ref = count_run(NONE, works[w], 200, steps[s], piece);
                struct count_end off = count_run(NO_COUNT_LOOP, works[w], 200, steps[s], piece);
                struct count_end all = count_run(ALL, works[w], 200, steps[s], piece);
                same_end(&off, &ref, "countdown, no count-loop path", piece);
                same_end(&all, &ref, "countdown, all fast paths", piece);
                ck_assert_uint_eq(off.skipped, 0);
                ck_assert_uint_eq(ref.r[10], 0x00ab00cdu);
                ck_assert_uint_eq(ref.r[8], 1); /* the last turn: no borrow */
                if (piece > 1000)
                    ck_assert_uint_ge(all.skipped, 200 / steps[s] - 2);
            }
        }
    }
    /* step 1 from 200: 200 turns of 4 cycles */
    struct count_end ref = count_run(NONE, works[0], 200, 1, 1000000);
    ck_assert_int_eq(ref.cycles, 4 + 1 + 200 * 4 + 2);
}
END_TEST

/* A body that carries other state from turn to turn (add r5, r5, 1: r5
 * counts the turns; adc: reads the carry; a write to the counter's
 * register elsewhere) runs as it is. */
START_TEST(count_loop_with_state_runs) {
    const uint32_t works[] = {alui(PRU_OP_ADD, R(5), R(5), 1), alui(PRU_OP_ADC, R(5), R(6), 0),
                              alui(PRU_OP_OR, B0(10), B0(10), 1)};
    for (unsigned w = 0; w < sizeof works / sizeof works[0]; w++) {
        struct count_end ref = count_run(NONE, works[w], 200, 1, 1000000);
        struct count_end all = count_run(ALL, works[w], 200, 1, 1000000);
        same_end(&all, &ref, "countdown with state", 1000000);
        ck_assert_uint_eq(all.skipped, 0);
    }
}
END_TEST

/* Countdown loops at tops[0..n), taken in turn 40 times by an outer loop
 * too long for the fast-forward: r1 counts down 3 in each, r2 counts the
 * loops done. */
static struct outcome loops_in_turn(enum path p, const unsigned *tops, unsigned n_loops,
                                    uint64_t *decoded) {
    struct pru_core *c = ff_core(p, NULL);
    uint32_t prog[200];
    unsigned n = 0;
    prog[n++] = ldi(R(5), 40);
    unsigned outer = n;
    for (unsigned i = 0; i < n_loops; i++) {
        prog[n++] = ldi(R(1), 3);
        while (n < tops[i])
            prog[n++] = alu(PRU_OP_AND, R(0), R(0), R(0)); /* a pad */
        prog[n++] = alui(PRU_OP_SUB, R(1), R(1), 1);
        prog[n++] = qbi(PRU_OP_QBNE, -1, R(1), 0);
        prog[n++] = alui(PRU_OP_ADD, R(2), R(2), 1);
    }
    prog[n++] = alui(PRU_OP_SUB, R(5), R(5), 1);
    prog[n] = qbi(PRU_OP_QBNE, (int)outer - (int)n, R(5), 0);
    n++;
    prog[n++] = halt();
    ck_assert_uint_le(n, 200);
    run_to_halt(c, prog, n, 1000000, 10000000);
    struct outcome o = {pru_cycles(c), pru_instructions(c), pru_ff_skipped(c), pru_reg(c, 2)};
    *decoded = c->ff_decoded;
    pru_core_free(c);
    return o;
}

/* Loops taken in turn keep their decoded bodies wherever their tops lie
 * (ff.c body(): any body in any entry). With one entry by the top modulo
 * 8, the firmware's period loop and SL poll at 10 MHz (tops 623 and 727)
 * and its delay turns and polls at 1 MHz (258, 366, 742) were decoded
 * again every frame. Two and three loops, their tops 8 to 64 words apart
 * (the same modulo 8): each body decoded once, with the cycles,
 * instructions and registers of running them without the fast-forward. */
START_TEST(loops_in_turn_decoded_once) {
    for (unsigned n_loops = 2; n_loops <= 3; n_loops++) {
        for (unsigned a = 20; a < 28; a++) { /* the outer loop: no body it looks at */
            for (unsigned d = 8; d <= 64; d += 8) {
                const unsigned tops[3] = {a, a + d, a + 2 * d};
                uint64_t decoded, none_decoded;
                struct outcome all = loops_in_turn(ALL, tops, n_loops, &decoded);
                struct outcome ref = loops_in_turn(NONE, tops, n_loops, &none_decoded);
                same(&all, &ref, "loops in turn", (int64_t)(a * 1000 + d));
                ck_assert_uint_eq(ref.r2, 40 * n_loops);
                ck_assert_uint_eq(decoded, n_loops);
                ck_assert_uint_eq(none_decoded, 0);
            }
        }
    }
}
END_TEST

int main(void) {
    Suite *s = suite_create("core_ff");
    TCase *tc = tcase_create("ff");
    tcase_set_timeout(tc, 60);
    tcase_add_test(tc, counted_poll_exact);
    tcase_add_test(tc, counted_poll_times_out);
    tcase_add_test(tc, counter_read_elsewhere_runs);
    tcase_add_test(tc, counted_field_poll_exact);
    tcase_add_test(tc, loop_delay_exact);
    tcase_add_test(tc, loop_with_work_runs);
    tcase_add_test(tc, count_loop_exact);
    tcase_add_test(tc, count_loop_with_state_runs);
    tcase_add_test(tc, loops_in_turn_decoded_once);
    suite_add_tcase(s, tc);
    return check_run(s);
}
