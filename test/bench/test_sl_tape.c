/* Check suite for SL on tape (emulator/bench/sl_tape.h): a tape written in
 * pieces from a record that drops its old edges between them, as the bench
 * writes it, answers every look as the whole record does (the level and
 * the next change, waveform_level_next), whatever order the looks come
 * in; and its end tells a core's RAMs apart. */
#include "pru_core.h"
#include "sl_tape.h"
#include "waveform.h"

#include "check_run.h"

#include <check.h>
#include <stdio.h>
#include <stdlib.h>
#include <unistd.h>

#define EDGES 3000

/* a small LCG: the test's own numbers, the same every run */
static uint64_t lcg(uint64_t *s) {
    *s = *s * UINT64_C(6364136223846793005) + UINT64_C(1442695040888963407);
    return *s >> 33;
}

struct fixture {
    char path[64];
    waveform whole; /* every edge, never dropped */
    struct pru_core *core;
    uint32_t base;
};

/* Edges 1..300 ns apart (some the same level: no edge), written to a tape
 * every 50 edges from a record that keeps only the last 2 us. */
static void record(struct fixture *f, uint64_t seed) {
    snprintf(f->path, sizeof f->path, "/tmp/test_sl_tape_XXXXXX");
    int fd = mkstemp(f->path);
    ck_assert_int_ge(fd, 0);
    close(fd);
    uint64_t s = seed;
    int initial = (int)(lcg(&s) & 1);
    waveform_init(&f->whole, initial);
    waveform part;
    waveform_init(&part, initial);
    struct sl_tape_writer w;
    char err[256];
    ck_assert_int_eq(sl_tape_create(&w, f->path, initial, err, sizeof err), 0);
    sim_ps t = 0;
    for (unsigned i = 0; i < EDGES; i++) {
        t += 1 + (sim_ps)(lcg(&s) % 300000);
        int level = (int)(lcg(&s) & 1);
        waveform_append(&f->whole, t, level);
        waveform_append(&part, t, level);
        if (i % 50 == 49) {
            sl_tape_append(&w, &part);
            waveform_forget_before(&part, t - 2 * SIM_PS_PER_US);
        }
    }
    sl_tape_append(&w, &part);
    waveform_free(&part);
    struct pru_params p;
    pru_params_default(&p);
    f->core = pru_core_new(PRU_SOC_AM335X, &p);
    f->base = pru_soc_base(PRU_SOC_AM335X);
    ck_assert_ptr_nonnull(f->core);
    ck_assert_int_eq(sl_tape_finish(&w, f->core, f->base, err, sizeof err), 0);
}

static void done(struct fixture *f) {
    waveform_free(&f->whole);
    pru_core_free(f->core);
    unlink(f->path);
}

/* The tape's pins against the whole record at time q: 0 if they agree
 * (counted, not asserted one by one: Check marks every assertion). */
static int differs(struct pru_pins *pins, waveform *whole, sim_ps q) {
    sim_ps next_w, next_t;
    int level = waveform_level_next(whole, q, &next_w);
    int bad = (int)pins->inputs_run(pins->ctx, q, &next_t) != level ||
              next_t != (next_w == SIM_NEVER ? INT64_MAX : next_w) ||
              (int)pins->inputs_at(pins->ctx, q) != level ||
              pins->next_input_change(pins->ctx, q) != next_t;
    if (bad) {
        fprintf(stderr, "at %lld ps: the record says %d until %lld\n", (long long)q, level,
                (long long)next_w);
    }
    return bad;
}

START_TEST(answers_as_the_record) {
    struct fixture f;
    record(&f, (uint64_t)_i + 1);
    struct sl_tape t;
    char err[256];
    ck_assert_msg(sl_tape_load(&t, f.path, err, sizeof err) == 0, "%s", err);
    ck_assert_uint_eq(t.n, f.whole.len); /* none lost, none twice */
    struct pru_pins pins = sl_tape_pins(&t);
    sim_ps end = f.whole.edges[f.whole.len - 1].t + SIM_PS_PER_US;
    /* forward in small steps (the core's reads), on and around each edge */
    int bad = 0;
    for (sim_ps q = 0; q < end; q += 997) {
        bad += differs(&pins, &f.whole, q);
    }
    for (size_t i = 0; i < f.whole.len; i += 7) {
        for (sim_ps d = -1; d <= 1; d++) {
            bad += differs(&pins, &f.whole, f.whole.edges[i].t + d);
        }
    }
    /* anywhere, back and forth */
    uint64_t s = 99;
    for (int k = 0; k < 2000; k++) {
        bad += differs(&pins, &f.whole, (sim_ps)(lcg(&s) % (uint64_t)end));
    }
    ck_assert_int_eq(bad, 0);
    sl_tape_free(&t);
    done(&f);
}
END_TEST

START_TEST(the_end_tells_the_run) {
    struct fixture f;
    record(&f, 7);
    struct sl_tape t;
    char err[256];
    ck_assert_int_eq(sl_tape_load(&t, f.path, err, sizeof err), 0);
    ck_assert(sl_tape_same(&t, f.core, f.base));
    /* one byte of data RAM 1 changed: the same instructions and cycles,
     * not the same run */
    uint8_t b = 0x5a;
    ck_assert_int_eq(pru_host_write(f.core, f.base + PRU_OFS_DRAM1 + 100, &b, 1), 0);
    ck_assert(!sl_tape_same(&t, f.core, f.base));
    sl_tape_free(&t);
    done(&f);
}
END_TEST

int main(void) {
    Suite *s = suite_create("sl_tape");
    TCase *tc = tcase_create("tape");
    tcase_add_loop_test(tc, answers_as_the_record, 0, 3);
    tcase_add_test(tc, the_end_tells_the_run);
    suite_add_tcase(s, tc);
    return check_run(s);
}
