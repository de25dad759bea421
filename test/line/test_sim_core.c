/* Check suite for the scheduler, the waveform record and the PRNG. */
#include "event_queue.h"
#include "sim_rng.h"
#include "waveform.h"

#include "check_run.h"

#include <check.h>
#include <math.h>
#include <stdlib.h>

typedef struct {
    int order[16];
    sim_ps when[16];
    int n;
} log_t;

static void note(void *ctx, sim_ps t, int64_t arg) {
    log_t *g = ctx;
    g->order[g->n] = (int)arg;
    g->when[g->n] = t;
    g->n++;
}

START_TEST(queue_runs_in_time_then_fifo_order) {
    event_queue q;
    log_t g = {.n = 0};
    eq_init(&q);
    eq_schedule(&q, 300, note, &g, 3);
    eq_schedule(&q, 100, note, &g, 1);
    eq_schedule(&q, 200, note, &g, 2);
    eq_schedule(&q, 100, note, &g, 10); /* same time: after 1 */
    ck_assert_uint_eq(eq_run_until(&q, 200), 3);
    ck_assert_int_eq(g.order[0], 1);
    ck_assert_int_eq(g.order[1], 10);
    ck_assert_int_eq(g.order[2], 2);
    ck_assert_int_eq(eq_now(&q), 200);
    ck_assert_int_eq(eq_next_time(&q), 300);
    eq_run_until(&q, 1000);
    ck_assert_int_eq(g.n, 4);
    ck_assert_int_eq(eq_next_time(&q), SIM_NEVER);
    eq_free(&q);
}
END_TEST

START_TEST(queue_cancel_removes_only_that_event) {
    event_queue q;
    log_t g = {.n = 0};
    eq_init(&q);
    eq_id a = eq_schedule(&q, 50, note, &g, 1);
    eq_id b = eq_schedule(&q, 60, note, &g, 2);
    eq_schedule(&q, 70, note, &g, 3);
    ck_assert_int_eq(eq_cancel(&q, b), 1);
    ck_assert_int_eq(eq_cancel(&q, b), 0);
    ck_assert_int_eq(eq_cancel(&q, 0), 0);
    eq_run_until(&q, 100);
    ck_assert_int_eq(g.n, 2);
    ck_assert_int_eq(g.order[0], 1);
    ck_assert_int_eq(g.order[1], 3);
    ck_assert_int_eq(eq_cancel(&q, a), 0); /* already ran */
    eq_free(&q);
}
END_TEST

typedef struct {
    event_queue *q;
    log_t g;
} resched_t;

static void resched(void *ctx, sim_ps t, int64_t arg) {
    resched_t *r = ctx;
    note(&r->g, t, arg);
    if (arg < 3) {
        eq_schedule(r->q, t + 5, resched, r, arg + 1);
    }
}

START_TEST(queue_runs_events_scheduled_while_running) {
    event_queue q;
    eq_init(&q);
    resched_t r = {&q, {.n = 0}};
    eq_schedule(&q, 10, resched, &r, 0);
    eq_run_until(&q, 20); /* 10, 15, 20 run; 25 stays */
    ck_assert_int_eq(r.g.n, 3);
    ck_assert_int_eq(r.g.when[2], 20);
    ck_assert_int_eq(eq_next_time(&q), 25);
    eq_free(&q);
}
END_TEST

START_TEST(waveform_lookups) {
    waveform w;
    waveform_init(&w, 1);
    ck_assert_int_eq(waveform_append(&w, 100, 0), 0);
    ck_assert_int_eq(waveform_append(&w, 150, 0), 0); /* no change: dropped */
    ck_assert_int_eq(waveform_append(&w, 200, 1), 0);
    ck_assert_int_eq(waveform_append(&w, 300, 0), 0);
    ck_assert_int_eq(waveform_append(&w, 250, 1), -1); /* out of order */
    ck_assert_uint_eq(w.len, 3);
    ck_assert_int_eq(waveform_level_at(&w, 0), 1);
    ck_assert_int_eq(waveform_level_at(&w, 99), 1);
    ck_assert_int_eq(waveform_level_at(&w, 100), 0);
    ck_assert_int_eq(waveform_level_at(&w, 250), 1);
    ck_assert_int_eq(waveform_level_at(&w, 120), 0); /* backwards */
    ck_assert_int_eq(waveform_level_at(&w, 1000), 0);
    ck_assert_int_eq(waveform_next_after(&w, 0), 100);
    ck_assert_int_eq(waveform_next_after(&w, 100), 200);
    ck_assert_int_eq(waveform_next_after(&w, 300), SIM_NEVER);
    waveform_forget_before(&w, 250);
    ck_assert_int_eq(w.initial, 1);
    ck_assert_uint_eq(w.len, 1);
    ck_assert_int_eq(waveform_level_at(&w, 260), 1);
    ck_assert_int_eq(waveform_level_at(&w, 300), 0);
    waveform_free(&w);
}
END_TEST

START_TEST(waveform_many_edges_binary_search) {
    waveform w;
    waveform_init(&w, 0);
    for (int i = 1; i <= 10000; i++) {
        waveform_append(&w, (sim_ps)i * 10, i & 1);
    }
    ck_assert_int_eq(waveform_level_at(&w, 99995), 1); /* edge 9999 at 99990 */
    ck_assert_int_eq(waveform_level_at(&w, 15), 1);
    ck_assert_int_eq(waveform_level_at(&w, 25), 0);
    ck_assert_int_eq(waveform_next_after(&w, 55555), 55560);
    waveform_free(&w);
}
END_TEST

START_TEST(rng_reproducible_and_sane) {
    sim_rng a, b;
    sim_rng_seed(&a, 42);
    sim_rng_seed(&b, 42);
    for (int i = 0; i < 100; i++) {
        ck_assert_uint_eq(sim_rng_u64(&a), sim_rng_u64(&b));
    }
    sim_rng_seed(&b, 43);
    ck_assert_uint_ne(sim_rng_u64(&a), sim_rng_u64(&b));

    double sum = 0, sum2 = 0;
    const int n = 200000;
    sim_rng_seed(&a, 7);
    for (int i = 0; i < n; i++) {
        double g = sim_rng_gauss(&a);
        sum += g;
        sum2 += g * g;
    }
    double mean = sum / n, sd = sqrt(sum2 / n - mean * mean);
    ck_assert_double_lt(fabs(mean), 0.01);
    ck_assert_double_lt(fabs(sd - 1.0), 0.01);
    for (int i = 0; i < 1000; i++) {
        double u = sim_rng_uniform(&a);
        ck_assert(u >= 0.0 && u < 1.0);
    }
}
END_TEST

int main(void) {
    Suite *s = suite_create("sim_core");
    TCase *tc = tcase_create("core");
    tcase_add_test(tc, queue_runs_in_time_then_fifo_order);
    tcase_add_test(tc, queue_cancel_removes_only_that_event);
    tcase_add_test(tc, queue_runs_events_scheduled_while_running);
    tcase_add_test(tc, waveform_lookups);
    tcase_add_test(tc, waveform_many_edges_binary_search);
    tcase_add_test(tc, rng_reproducible_and_sane);
    suite_add_tcase(s, tc);
    return check_run(s);
}
