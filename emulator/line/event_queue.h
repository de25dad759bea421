/* A small discrete-event scheduler.
 *
 * Components schedule callbacks at future times; the bench advances the
 * queue to a time T, which runs every event with time <= T in order of time
 * and then of scheduling (so equal-time events run first-in first-out and a
 * run is reproducible). A scheduled event can be cancelled by its id, which
 * is how a slave drops its pending timeout when MA moves again. */
#ifndef EVENT_QUEUE_H
#define EVENT_QUEUE_H

#include "sim_time.h"

#include <stddef.h>
#include <stdint.h>

typedef void (*eq_fn)(void *ctx, sim_ps t, int64_t arg);

typedef uint64_t eq_id; /* 0 is never a valid id: use it for "none pending" */

typedef struct {
    sim_ps t;
    eq_id id; /* also the scheduling order */
    eq_fn fn;
    void *ctx;
    int64_t arg;
} eq_event;

typedef struct {
    eq_event *ev; /* ev[head .. len): pending, in order of (t, id) */
    size_t head, len, cap;
    eq_id next_id;
    sim_ps now; /* time of the event running or last run, or of the last advance */
} event_queue;

void eq_init(event_queue *q);
void eq_free(event_queue *q);

/* eq_schedule_as(q, t, eq_take_id(q), ...), out of line. */
eq_id eq_schedule_any(event_queue *q, sim_ps t, eq_fn fn, void *ctx, int64_t arg);

/* Whether eq_put() may schedule at t: room in the array, t not in the past. */
static inline int eq_fits(const event_queue *q, sim_ps t) {
    return q->len < q->cap && t >= q->now;
}

/* eq_schedule() when eq_fits(q, t): in line (a new id is greater than
 * every id taken, so only later times move). */
static inline eq_id eq_put(event_queue *q, sim_ps t, eq_fn fn, void *ctx, int64_t arg) {
    size_t i = q->len++;
    while (i > q->head && q->ev[i - 1].t > t) {
        q->ev[i] = q->ev[i - 1];
        i--;
    }
    eq_event *e = &q->ev[i];
    e->t = t;
    e->id = q->next_id++;
    e->fn = fn;
    e->ctx = ctx;
    e->arg = arg;
    return e->id;
}

/* Schedules fn(ctx, t, arg). t must not be earlier than eq_now(q).
 * Returns the event's id, or 0 if memory ran out. Almost every event goes
 * after all pending ones but a slave's timeout or two: with room in the
 * array that is done in line (eq_put). */
static inline eq_id eq_schedule(event_queue *q, sim_ps t, eq_fn fn, void *ctx, int64_t arg) {
    if (eq_fits(q, t)) {
        return eq_put(q, t, fn, ctx, arg);
    }
    return eq_schedule_any(q, t, fn, ctx, arg);
}

/* The id the next eq_schedule() would give, taken now without scheduling
 * anything: with eq_schedule_as() an event can be scheduled later where it
 * would have run had it been scheduled now (among events at its time). A
 * component that moves one deadline often (a timeout restarted by every
 * edge) keeps one event pending and, when it fires early, schedules it
 * again under the id it took when the deadline last moved. */
static inline eq_id eq_take_id(event_queue *q) {
    return q->next_id++;
}

/* eq_schedule() under an id from eq_take_id() (not otherwise used). */
eq_id eq_schedule_as(event_queue *q, sim_ps t, eq_id id, eq_fn fn, void *ctx, int64_t arg);

/* Removes a pending event. Returns 1 if it was pending, 0 otherwise (already
 * run, cancelled, or id 0), so callers may cancel unconditionally. */
int eq_cancel(event_queue *q, eq_id id);

/* Runs every event with time <= t (including ones scheduled while running),
 * then sets the current time to t. Returns the number of events run. */
size_t eq_run_until(event_queue *q, sim_ps t);

/* Time of the earliest pending event, or SIM_NEVER. */
sim_ps eq_next_time(const event_queue *q);

static inline sim_ps eq_now(const event_queue *q) {
    return q->now;
}

static inline size_t eq_pending(const event_queue *q) {
    return q->len - q->head;
}

#endif
