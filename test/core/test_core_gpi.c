/*
 * Check suite: GPI 28-bit shift mode (docs/pru-facts.md §4.4, §4.5) against known
 * input waveforms, for every divisor code pair that gives the 8x shift
 * clocks of 1, 2, 5 and 10 MHz MA (8, 16, 40, 80 MHz), both fractional
 * divider patterns and several phases: R31 contents asserted at every
 * cycle against a direct evaluation of the documented behaviour. Also the
 * start bit, Cnt_16, clearing through GPCFG0 bit 13, reads by instructions,
 * direct mode, and fast-forward of a poll loop.
 */
#include "check_run.h"
#include "core_test_util.h"

#include <stdlib.h>

#define BASE   0x4A300000u
#define GPCFG0 (BASE + 0x26008u)
#define MAXT   4096

/* A piecewise-constant input: level toggles at t[i]; level before t[0] is 0. */
struct wave {
    int n;
    int64_t t[MAXT];
    int64_t last_query; /* inputs_at must see non-decreasing times */
};

static uint32_t wave_level(const struct wave *w, int64_t t) {
    int lo = 0, hi = w->n; /* count transitions <= t */
    while (lo < hi) {
        int mid = (lo + hi) / 2;
        if (w->t[mid] <= t)
            lo = mid + 1;
        else
            hi = mid;
    }
    return (uint32_t)(lo & 1);
}

static uint32_t wave_in(void *ctx, int64_t t) {
    struct wave *w = ctx;
    ck_assert_int_ge(t, w->last_query);
    w->last_query = t;
    return wave_level(w, t);
}

static int64_t wave_next(void *ctx, int64_t t) {
    const struct wave *w = ctx;
    for (int i = 0; i < w->n; i++) /* small waves: linear is fine */
        if (w->t[i] > t)
            return w->t[i];
    return INT64_MAX;
}

/* Both in one call, as the bench's pins give them (struct pru_pins
 * inputs_run). */
static uint32_t wave_run(void *ctx, int64_t t, int64_t *next) {
    uint32_t v = wave_in(ctx, t);
    *next = wave_next(ctx, t);
    return v;
}

/* Random toggles, spacing between 1 and 80 ns (so several per shift period
 * at 80 MHz and long runs at 8 MHz), starting at t_start. */
static void wave_random(struct wave *w, unsigned seed, int64_t t_start, int n) {
    srand(seed);
    w->n = n;
    w->last_query = INT64_MIN;
    int64_t t = t_start;
    for (int i = 0; i < n; i++) {
        t += 1000 + rand() % 80000;
        w->t[i] = t;
    }
}

/* Documented behaviour, evaluated directly for a read at `cycle`. */
struct geom {
    int64_t t_cfg, phase, period, delay;
    int frac_cycle;
};

static int64_t edge_t(const struct geom *g, int64_t k) {
    int64_t off = k * g->period;
    if (g->frac_cycle)
        off = off / 5000 * 5000;
    return g->t_cfg + g->phase + off;
}

static uint32_t expect_r31(const struct geom *g, const struct wave *w, int64_t cycle) {
    int64_t k_last = 0;
    while (edge_t(g, k_last + 1) <= cycle * 5000)
        k_last++;
    uint32_t reg = 0;
    int64_t k_sb = -1;
    for (int64_t k = 1; k <= k_last; k++) {
        int64_t ts = edge_t(g, k) - g->delay;
        uint32_t s = wave_level(w, ts < 0 ? 0 : ts);
        reg = ((reg << 1) | s) & 0x0FFFFFFFu;
        if (s && k_sb < 0)
            k_sb = k;
    }
    uint32_t v = reg;
    if (k_sb >= 0) {
        v |= 1u << 29;
        if (k_last > k_sb && (k_last - k_sb) % 16 == 0)
            v |= 1u << 28;
    }
    return v;
}

/* Host sets shift mode with codes (c0, c1) at cycle `cfg_cycle`, then R31 is
 * compared at every cycle up to `cycles` (gap_max 1), or at cycles 1 to
 * gap_max apart (a read that finds no new shift edge, one, or many, whose
 * samples it takes in runs of the input). The pins give the input only
 * (use_next 0: one run per edge), also its next change (1), or both in one
 * call (2). */
static void check_shift_gaps(unsigned c0, unsigned c1, int frac_cycle, int64_t phase, int use_next,
                             unsigned seed, unsigned gap_max) {
    static struct wave w;
    wave_random(&w, seed, 20000, 600);
    struct pru_params p;
    pru_params_default(&p);
    p.shift_frac = frac_cycle ? PRU_FRAC_CYCLE : PRU_FRAC_EXACT;
    p.shift_phase_ps = phase;
    struct pru_core *c = pru_core_new(PRU_SOC_AM335X, &p);
    struct pru_pins pins = {.ctx = &w,
                            .inputs_at = wave_in,
                            .next_input_change = use_next ? wave_next : NULL,
                            .inputs_run = use_next == 2 ? wave_run : NULL};
    pru_set_pins(c, &pins);
    int64_t cfg_cycle = 3;
    pru_run_until_cycle(c, cfg_cycle);
    ck_assert_int_eq(pru_host_write32(c, GPCFG0, 2u | c0 << 3 | c1 << 8), 0);
    struct geom g = {cfg_cycle * 5000, phase, 1250 * (int64_t)(2 + c0) * (2 + c1), p.gpi_delay_ps,
                     frac_cycle};
    int64_t end = 400 + 40 * g.period / 5000; /* at least ~40 shift periods */
    uint32_t gaps = seed * 2654435761u + 1u;
    for (int64_t cy = cfg_cycle; cy < end; cy += 1 + (gap_max > 1 ? gaps % gap_max : 0)) {
        gaps = gaps * 1103515245u + 12345u;
        pru_run_until_cycle(c, cy);
        uint32_t got = pru_reg(c, 31);
        uint32_t want = expect_r31(&g, &w, cy);
        if (got != want)
            ck_abort_msg("codes %u/%u frac %d phase %lld next %d: cycle %lld R31 0x%08x, "
                         "expected 0x%08x",
                         c0, c1, frac_cycle, (long long)phase, use_next, (long long)cy, got, want);
    }
    pru_core_free(c);
}

static void check_shift(unsigned c0, unsigned c1, int frac_cycle, int64_t phase, int use_next,
                        unsigned seed) {
    check_shift_gaps(c0, c1, frac_cycle, phase, use_next, seed, 1);
}

/* (2+c0)(2+c1)/4 = ratio0 * ratio1 for 80, 40, 16, 8 MHz: 2.5, 5, 12.5, 25 */
static const unsigned combos[][2] = {
    {0, 3},  {3, 0},                            /* 80 MHz */
    {0, 8},  {8, 0},  {2, 3}, {3, 2},           /* 40 MHz */
    {0, 23}, {23, 0}, {3, 8}, {8, 3},           /* 16 MHz */
    {2, 23}, {23, 2}, {8, 8}, {3, 18}, {18, 3}, /* 8 MHz */
};
#define NCOMBO ((int)(sizeof combos / sizeof combos[0]))

START_TEST(shift_all_divisor_combos) {
    int i = _i;
    unsigned c0 = combos[i][0], c1 = combos[i][1];
    int64_t prod4 = (2 + c0) * (2 + c1);
    ck_assert(prod4 == 10 || prod4 == 20 || prod4 == 50 || prod4 == 100);
    static const int64_t phases[] = {0, 1250, 3700};
    for (int frac = 0; frac < 2; frac++)
        for (int ph = 0; ph < 3; ph++)
            for (int nx = 0; nx < 3; nx++)
                check_shift(c0, c1, frac, phases[ph], nx, (unsigned)(i * 7 + ph));
}
END_TEST

/* Reads 1 to 80 cycles apart: up to 32 shift edges new at 80 MHz, a
 * fraction of one at 8 MHz, so a read finds none, one or many (the 28-bit
 * register shifted over runs of the input at once, cfg_gpi.c
 * shift_apply); every read against the direct evaluation. */
START_TEST(shift_sparse_reads) {
    int i = _i;
    unsigned c0 = combos[i][0], c1 = combos[i][1];
    for (int frac = 0; frac < 2; frac++)
        for (int nx = 0; nx < 3; nx++)
            check_shift_gaps(c0, c1, frac, 1250 * (int64_t)nx, nx, (unsigned)(i * 5 + nx + 11), 80);
}
END_TEST

/* A few literal values: 80 MHz (period 12.5 ns), constant input high from
 * t = 0: SB at the first edge, ones fill from bit 0, Cnt_16 16 edges later. */
START_TEST(shift_literal_values) {
    struct pru_core *c = pru_core_new(PRU_SOC_AM335X, NULL);
    pru_set_inputs(c, 1);
    ck_assert_int_eq(pru_host_write32(c, GPCFG0, 2u | 3u << 3), 0); /* 2.5 x 1 */
    /* edges at 12.5, 25, 37.5, 50 ns ... -> cycles 3, 5, 8, 10 */
    static const struct {
        int64_t cycle;
        uint32_t r31;
    } expect[] = {
        {0, 0},
        {2, 0},
        {3, (1u << 29) | 0x1},
        {4, (1u << 29) | 0x1},
        {5, (1u << 29) | 0x3},
        {8, (1u << 29) | 0x7},
        {10, (1u << 29) | 0xF},
        {42, (1u << 29) | 0xFFFF},
        {43, (1u << 29) | (1u << 28) | 0x1FFFF}, /* edge 17 = 16 after the SB edge */
        {45, (1u << 29) | 0x3FFFF},
        {200, (1u << 29) | 0x0FFFFFFF},
    };
    for (unsigned i = 0; i < sizeof expect / sizeof expect[0]; i++) {
        pru_run_until_cycle(c, expect[i].cycle);
        ck_assert_uint_eq(pru_reg(c, 31), expect[i].r31);
    }
    uint32_t v;
    pru_host_read32(c, GPCFG0, &v);
    ck_assert_uint_eq(v, 2u | 3u << 3 | 1u << 13); /* bit 13 reads SB */
    /* clear: write 1 to bit 13 -> SB and the register clear, shifting goes on */
    pru_host_write32(c, GPCFG0, 2u | 3u << 3 | 1u << 13);
    ck_assert_uint_eq(pru_reg(c, 31), 0);
    pru_set_inputs(c, 0);
    pru_run_until_cycle(c, 300);
    ck_assert_uint_eq(pru_reg(c, 31), 0);
    pru_set_inputs(c, 1);
    int64_t k = 0;
    while (k * 12500 <= 300 * 5000)
        k++; /* next edge index */
    pru_run_until_cycle(c, (k * 12500 + 4999) / 5000);
    ck_assert_uint_eq(pru_reg(c, 31), (1u << 29) | 1u);
    pru_core_free(c);
}
END_TEST

/* The sample instants around a time (pru_gpi_sample_bracket, the bench's
 * look at what the samples saw): shift-clock edges at 12.5 ns * k less the
 * synchronizer's 2 cycles; none outside shift mode. */
START_TEST(shift_sample_bracket) {
    struct pru_core *c = pru_core_new(PRU_SOC_AM335X, NULL);
    int64_t before = 0, after = 0;
    ck_assert_int_eq(pru_gpi_sample_bracket(c, 30000, &before, &after), -1); /* direct mode */
    ck_assert_int_eq(pru_host_write32(c, GPCFG0, 2u | 3u << 3), 0);          /* 80 MHz */
    ck_assert_int_eq(pru_gpi_sample_bracket(c, 30000, &before, &after), 0);
    ck_assert_int_eq(before, 37500 - 10000); /* edge 3 sampled the pins at 27.5 ns */
    ck_assert_int_eq(after, 50000 - 10000);
    ck_assert_int_eq(pru_gpi_sample_bracket(c, 27500, &before, &after), 0); /* at an instant */
    ck_assert_int_eq(before, 27500);
    ck_assert_int_eq(after, 40000);
    ck_assert_int_eq(pru_gpi_sample_bracket(c, 27499, &before, &after), 0);
    ck_assert_int_eq(before, 15000);
    ck_assert_int_eq(after, 27500);
    pru_core_free(c);
}
END_TEST

/* Instructions read R31 at their issue cycle: store R31 every 2 cycles. */
START_TEST(shift_read_by_instructions) {
    static struct wave w;
    wave_random(&w, 99, 30000, 400);
    struct pru_core *c = pru_core_new(PRU_SOC_AM335X, NULL);
    struct pru_pins pins = {.ctx = &w, .inputs_at = wave_in, .next_input_change = wave_next};
    pru_set_pins(c, &pins);
    uint32_t prog[16];
    unsigned n = 0;
    mov32(prog, &n, 1, 2u | 8u << 3 | 3u << 8);      /* 5 x 2.5: 16 MHz */
    prog[n++] = burst(PRU_OP_SBCO, 4 * 1, 4, 8, 4);  /* c=2: lands at 3 */
    prog[n++] = ldi(R(2), 0);                        /* c=3 */
    prog[n++] = loopi(3, 200);                       /* c=4 */
    prog[n++] = burst(PRU_OP_SBBO, 4 * 31, 2, 0, 4); /* c=5+2i */
    prog[n++] = alui(PRU_OP_ADD, R(2), R(2), 4);
    prog[n++] = halt();
    pru_load_image(c, prog, sizeof prog);
    pru_start(c);
    ck_assert_int_eq(pru_run(c, 10000), PRU_STOP_HALT);
    ck_assert_int_eq(pru_cycles(c), 5 + 400 + 1);
    struct geom g = {3 * 5000, 0, 1250 * 10 * 5, 10000, 0};
    for (int i = 0; i < 200; i++) {
        uint32_t v;
        pru_host_read32(c, BASE + 4u * (uint32_t)i, &v);
        ck_assert_uint_eq(v, expect_r31(&g, &w, 5 + 2 * i));
    }
    pru_core_free(c);
}
END_TEST

/* Direct mode: R31[29:0] are the pins, seen gpi_delay_ps late. */
START_TEST(direct_mode_delay) {
    static struct wave w;
    wave_random(&w, 5, 0, 200);
    struct pru_core *c = pru_core_new(PRU_SOC_AM335X, NULL);
    struct pru_pins pins = {.ctx = &w, .inputs_at = wave_in, .next_input_change = wave_next};
    pru_set_pins(c, &pins);
    for (int64_t cy = 0; cy < 2000; cy++) {
        pru_run_until_cycle(c, cy);
        int64_t t = cy * 5000 - 10000;
        ck_assert_uint_eq(pru_reg(c, 31), wave_level(&w, t < 0 ? 0 : t));
    }
    pru_core_free(c);
}
END_TEST

/* An MVI load through a pointer reads the pins only where the word it
 * loads reaches R31 (bytes 124..127), on the fast path as on the general
 * one (exec_mvi(), rf_before_read()): a load below R31 leaves the inputs
 * unasked; one that reaches it loads their value. */
static int pin_reads;
static uint32_t counted_in(void *ctx, int64_t t) {
    (void)ctx;
    (void)t;
    pin_reads++;
    return 0x5au;
}

START_TEST(mvi_reads_pins_only_at_r31) {
    static const struct {
        int op;
        uint32_t ptr;
        int reads;
    } cases[] = {{PRU_OP_MVID, 16, 0},
                 {PRU_OP_MVIW, 122, 0},
                 {PRU_OP_MVIB, 123, 0},
                 {PRU_OP_MVID, 121, 1},
                 {PRU_OP_MVIB, 124, 1}};
    for (int fast = 0; fast < 2; fast++) {
        for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
            struct pru_params p;
            pru_params_default(&p);
            uint32_t prog[] = {ldi(R(1), cases[i].ptr),
                               mvi(cases[i].op, PRU_MVI_DIRECT, R(2), PRU_MVI_IND, B0(1)), halt()};
            struct pru_core *c = core_loaded(&p, prog, sizeof prog / sizeof prog[0]);
            struct pru_pins pins = {.inputs_at = counted_in};
            pru_set_pins(c, &pins);
            pru_start(c);
            pin_reads = 0;
            if (fast) {
                ck_assert_int_eq(pru_run(c, 100), PRU_STOP_HALT);
            } else {
                for (int s = 0; s < 3; s++)
                    pru_step(c);
            }
            ck_assert_int_eq(pin_reads > 0, cases[i].reads);
            if (cases[i].ptr == 124)
                ck_assert_uint_eq(pru_reg(c, 2), 0x5a);
            if (cases[i].ptr == 121)
                ck_assert_uint_eq(pru_reg(c, 2) >> 24, 0x5a);
            pru_core_free(c);
        }
    }
}
END_TEST

/* Wait for the start bit (wbs r31.t29), then sample 5 bytes 8 shift clocks
 * apart; with and without fast-forward the results are identical. */
/* Without fast-forward, with it, and with it on pins that give inputs_run
 * (the R31 horizon then takes the input and its next change in one call):
 * the same run, and both skip the same. */
START_TEST(shift_poll_fast_forward_exact) {
    uint32_t res[3][8];
    int64_t cyc[3];
    uint64_t ins[3], skipped[3] = {0};
    for (int run = 0; run < 3; run++) {
        int ff = run > 0;
        static struct wave w;
        wave_random(&w, 7, 2000000000, 300); /* quiet for 2 ms */
        struct pru_params p;
        pru_params_default(&p);
        p.fast_forward = ff;
        struct pru_core *c = pru_core_new(PRU_SOC_AM335X, &p);
        struct pru_pins pins = {.ctx = &w,
                                .inputs_at = wave_in,
                                .next_input_change = wave_next,
                                .inputs_run = run == 2 ? wave_run : NULL};
        pru_set_pins(c, &pins);
        uint32_t prog[32];
        unsigned n = 0;
        mov32(prog, &n, 1, 2u | 8u << 3 | 8u << 8); /* 5 x 5: 8 MHz */
        prog[n++] = burst(PRU_OP_SBCO, 4 * 1, 4, 8, 4);
        prog[n++] = qbi(PRU_OP_QBBC, 0, R(31), 29); /* wbs r31.t29 */
        prog[n++] = ldi(R(2), 0);
        prog[n++] = loopi(5, 5);
        prog[n++] = ldi(R(3), 10); /* 25 cycles per byte */
        prog[n++] = alui(PRU_OP_SUB, R(3), R(3), 1);
        prog[n++] = qbi(PRU_OP_QBNE, -1, R(3), 0);
        prog[n++] = burst(PRU_OP_SBBO, 4 * 31, 2, 0, 4);
        prog[n++] = alui(PRU_OP_ADD, R(2), R(2), 4);
        prog[n++] = halt();
        pru_load_image(c, prog, sizeof prog);
        pru_start(c);
        ck_assert_int_eq(pru_run(c, 2000000), PRU_STOP_HALT);
        cyc[run] = pru_cycles(c);
        ins[run] = pru_instructions(c);
        pru_host_read(c, BASE, res[run], sizeof res[run]);
        skipped[run] = pru_ff_skipped(c);
        pru_core_free(c);
    }
    ck_assert_int_gt(cyc[0], 400000);
    for (int run = 1; run < 3; run++) {
        ck_assert_int_eq(cyc[0], cyc[run]);
        ck_assert_uint_eq(ins[0], ins[run]);
        ck_assert_mem_eq(res[0], res[run], sizeof res[0]);
    }
    ck_assert_uint_gt(skipped[1], 300000);
    ck_assert_uint_eq(skipped[1], skipped[2]);
}
END_TEST

/* Cnt_16 raises system event 1; mapped to host 0 it shows in R31[30]. */
START_TEST(cnt16_event_to_intc) {
    struct pru_core *c = pru_core_new(PRU_SOC_AM335X, NULL);
    pru_host_write32(c, BASE + 0x20010u, 1); /* GER */
    pru_host_write32(c, BASE + 0x20028u, 1); /* EISR event 1 (channel 0 -> host 0) */
    pru_host_write32(c, BASE + 0x20034u, 0); /* HIEISR host 0 */
    pru_set_inputs(c, 1);
    pru_host_write32(c, GPCFG0, 2u | 3u << 3); /* 80 MHz: edges at 12.5 ns * k */
    pru_run_until_cycle(c, 42);                /* edge 16: 15 after the SB edge */
    ck_assert_uint_eq(pru_reg(c, 31) >> 30, 0);
    pru_run_until_cycle(c, 43);                   /* edge 17 */
    ck_assert_uint_eq(pru_reg(c, 31) >> 28, 0x7); /* host 0, SB, Cnt_16 */
    pru_run_until_cycle(c, 45);
    ck_assert_uint_eq(pru_reg(c, 31) >> 28, 0x6); /* Cnt_16 gone, event latched */
    uint32_t v;
    pru_host_read32(c, BASE + 0x20200u, &v);
    ck_assert_uint_eq(v, 2);
    pru_core_free(c);
}
END_TEST

START_TEST(unsupported_modes_fault) {
    for (unsigned mode = 1; mode <= 3; mode += 2) {
        struct pru_core *c = pru_core_new(PRU_SOC_AM335X, NULL);
        const uint32_t w[] = {ldi(R(1), mode), burst(PRU_OP_SBCO, 4, 4, 8, 4), halt()};
        pru_load_image(c, w, sizeof w);
        pru_start(c);
        ck_assert_int_eq(pru_run(c, 100), PRU_STOP_FAULT);
        ck_assert_int_eq(pru_get_fault(c)->cause, PRU_FAULT_UNSUPPORTED);
        pru_core_free(c);
    }
}
END_TEST

Suite *gpi_suite(void) {
    Suite *s = suite_create("core_gpi");
    TCase *t = tcase_create("shift");
    tcase_set_timeout(t, 120);
    tcase_add_loop_test(t, shift_all_divisor_combos, 0, NCOMBO);
    tcase_add_loop_test(t, shift_sparse_reads, 0, NCOMBO);
    tcase_add_test(t, shift_literal_values);
    tcase_add_test(t, shift_sample_bracket);
    tcase_add_test(t, shift_read_by_instructions);
    tcase_add_test(t, direct_mode_delay);
    tcase_add_test(t, mvi_reads_pins_only_at_r31);
    tcase_add_test(t, shift_poll_fast_forward_exact);
    tcase_add_test(t, cnt16_event_to_intc);
    tcase_add_test(t, unsupported_modes_fault);
    suite_add_tcase(s, t);
    return s;
}

int main(void) {
    return check_run(gpi_suite());
}
