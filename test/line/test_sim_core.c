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

/* An id taken early places an event scheduled later where it would have
 * run had it been scheduled then: before events at its time scheduled in
 * between, after those scheduled before the id was taken. */
START_TEST(queue_schedule_under_an_earlier_id) {
    event_queue q;
    log_t g = {.n = 0};
    eq_init(&q);
    eq_schedule(&q, 100, note, &g, 1);
    eq_id early = eq_take_id(&q);
    eq_schedule(&q, 100, note, &g, 3);
    eq_schedule(&q, 50, note, &g, 0);
    eq_run_until(&q, 60);
    ck_assert_uint_eq(eq_schedule_as(&q, 100, early, note, &g, 2), early);
    eq_schedule(&q, 100, note, &g, 4);
    eq_run_until(&q, 1000);
    ck_assert_int_eq(g.n, 5);
    for (int i = 0; i < 5; i++) {
        ck_assert_int_eq(g.order[i], i);
    }
    ck_assert_int_eq(eq_cancel(&q, early), 0); /* it ran */
    eq_free(&q);
}
END_TEST

START_TEST(queue_cancel_of_an_event_that_sifted_up) {
    /* B is earlier than A, so it is put before A when scheduled:
     * its id must still be its own. */
    event_queue q;
    log_t g = {.n = 0};
    eq_init(&q);
    eq_id a = eq_schedule(&q, 100, note, &g, 1);
    eq_id b = eq_schedule(&q, 50, note, &g, 2);
    ck_assert_uint_ne(a, b);
    ck_assert_int_eq(eq_cancel(&q, b), 1);
    eq_run_until(&q, 1000);
    ck_assert_int_eq(g.n, 1);
    ck_assert_int_eq(g.order[0], 1);
    eq_free(&q);
}
END_TEST

/* The reference: pending events in a plain array, the next one found by a
 * linear scan for the least (time, scheduling order). */
typedef struct {
    sim_ps t;
    eq_id id;
    int64_t arg;
} ref_event;

typedef struct {
    ref_event ev[512];
    int n;
} ref_queue;

static int ref_earliest(const ref_queue *r) {
    int best = -1;
    for (int i = 0; i < r->n; i++) {
        if (best < 0 || r->ev[i].t < r->ev[best].t ||
            (r->ev[i].t == r->ev[best].t && r->ev[i].id < r->ev[best].id)) {
            best = i;
        }
    }
    return best;
}

static void ref_remove(ref_queue *r, int i) {
    r->ev[i] = r->ev[--r->n];
}

typedef struct {
    int64_t args[4096];
    sim_ps when[4096];
    int n;
} run_log;

static void log_run(void *ctx, sim_ps t, int64_t arg) {
    run_log *l = ctx;
    ck_assert_int_lt(l->n, 4096);
    l->args[l->n] = arg;
    l->when[l->n] = t;
    l->n++;
}

START_TEST(queue_agrees_with_reference_model) {
    /* Random schedules (earlier and later than what is pending, equal times
     * too), cancellations of pending, run and unknown ids, and runs up to a
     * time: every event runs exactly when and in the order the reference
     * says, and eq_cancel's verdict matches. */
    sim_rng rng;
    sim_rng_seed(&rng, 0x5eed + (uint64_t)_i);
    event_queue q;
    eq_init(&q);
    static ref_queue ref;
    static run_log got;
    ref.n = 0;
    got.n = 0;
    eq_id ids[4096];
    int nids = 0;
    int64_t next_arg = 0;
    for (int step = 0; step < 3000; step++) {
        unsigned op = (unsigned)(sim_rng_u64(&rng) % 10);
        if (op < 5 && ref.n < 512) {
            sim_ps t = eq_now(&q) + (sim_ps)(sim_rng_u64(&rng) % 64);
            eq_id id = eq_schedule(&q, t, log_run, &got, next_arg);
            ck_assert_uint_ne(id, 0);
            ref.ev[ref.n++] = (ref_event){t, id, next_arg};
            ids[nids++ % 4096] = id;
            next_arg++;
        } else if (op < 8) {
            /* any id seen so far (pending or not), or one never issued */
            eq_id id = nids && op < 7
                           ? ids[sim_rng_u64(&rng) % (uint64_t)(nids < 4096 ? nids : 4096)]
                           : (eq_id)(sim_rng_u64(&rng) % 100000 + 1000000);
            int pending = -1;
            for (int i = 0; i < ref.n; i++) {
                if (ref.ev[i].id == id) {
                    pending = i;
                }
            }
            ck_assert_int_eq(eq_cancel(&q, id), pending >= 0);
            if (pending >= 0) {
                ref_remove(&ref, pending);
            }
        } else {
            sim_ps until = eq_now(&q) + (sim_ps)(sim_rng_u64(&rng) % 40);
            int first = got.n;
            eq_run_until(&q, until);
            int k = first;
            for (int i; (i = ref_earliest(&ref)) >= 0 && ref.ev[i].t <= until;) {
                ck_assert_int_lt(k, got.n);
                ck_assert_int_eq(got.args[k], ref.ev[i].arg);
                ck_assert_int_eq(got.when[k], ref.ev[i].t);
                ref_remove(&ref, i);
                k++;
            }
            ck_assert_int_eq(k, got.n);
        }
        ck_assert_uint_eq(eq_pending(&q), (size_t)ref.n);
        int e = ref_earliest(&ref);
        ck_assert_int_eq(eq_next_time(&q), e < 0 ? SIM_NEVER : ref.ev[e].t);
    }
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

/* waveform_level_next() against a direct count, on queries that stay
 * between the same two edges, step one edge on (its in-line case), several
 * on, land on an edge exactly, go back, or jump far: level and next change
 * must be the record's whatever the hint was. */
START_TEST(waveform_level_next_agrees_with_a_count) {
    waveform w;
    waveform_init(&w, 1);
    sim_ps et[200];
    int n = 0;
    sim_ps t = 0;
    unsigned seed = 7;
    for (int i = 0; i < 200; i++) {
        seed = seed * 1103515245u + 12345u;
        t += 1 + (seed >> 16) % 50;
        et[n++] = t;
        waveform_append(&w, t, !(i & 1) ? 0 : 1); /* toggles from 1 */
    }
    sim_ps q = -10;
    for (int step = 0; step < 20000; step++) {
        seed = seed * 1103515245u + 12345u;
        unsigned r = (seed >> 16) % 100;
        if (r < 30) {
            q += (seed >> 8) % 3; /* within the same edges mostly */
        } else if (r < 70) {
            int k = 0; /* to the next edge, exactly or past it */
            while (k < n && et[k] <= q) {
                k++;
            }
            q = k < n ? et[k] + (r & 1) : q + 5;
        } else if (r < 85) {
            q += (seed >> 8) % 200;
        } else if (r < 95) {
            q -= (seed >> 8) % 200;
        } else {
            q = (sim_ps)((seed >> 4) % (unsigned)(t + 100)) - 20;
        }
        int k = 0;
        while (k < n && et[k] <= q) {
            k++;
        }
        sim_ps next;
        int level = waveform_level_next(&w, q, &next);
        ck_assert_int_eq(level, k == 0 ? 1 : (k - 1) & 1 ? 1 : 0);
        ck_assert_int_eq(next, k < n ? et[k] : SIM_NEVER);
    }
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
    tcase_add_test(tc, queue_cancel_of_an_event_that_sifted_up);
    tcase_add_test(tc, queue_schedule_under_an_earlier_id);
    tcase_add_loop_test(tc, queue_agrees_with_reference_model, 0, 20);
    tcase_add_test(tc, waveform_lookups);
    tcase_add_test(tc, waveform_many_edges_binary_search);
    tcase_add_test(tc, waveform_level_next_agrees_with_a_count);
    tcase_add_test(tc, rng_reproducible_and_sane);
    suite_add_tcase(s, tc);
    return check_run(s);
}
