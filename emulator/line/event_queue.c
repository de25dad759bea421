/* Pending events are few (a handful per component) and mostly scheduled
 * after every other one, so they are kept in one array sorted by (time,
 * id) from `head` on: the next event is at ev[head], taking it moves head,
 * and a new event moves only the later ones it overtakes, usually none.
 * Cancellation is a linear search. */
#include "event_queue.h"

#include <stdlib.h>
#include <string.h>

static int before(const eq_event *a, const eq_event *b) {
    return a->t < b->t || (a->t == b->t && a->id < b->id);
}

void eq_init(event_queue *q) {
    q->ev = NULL;
    q->head = q->len = q->cap = 0;
    q->next_id = 1;
    q->now = 0;
}

void eq_free(event_queue *q) {
    free(q->ev);
    q->ev = NULL;
    q->head = q->len = q->cap = 0;
}

/* Room for one more at the end: the taken slots before head are reused
 * first, the array grows only when at least half of it is pending. It
 * starts at 256 (10 kB): a handful pending, so the pending ones move to the
 * front once every 250 events or so, not every ten (the in-line
 * eq_schedule() handles all but those). */
static int make_room(event_queue *q) {
    if (q->len < q->cap) {
        return 0;
    }
    size_t n = q->len - q->head;
    if (q->head > 0 && n < q->cap / 2) {
        memmove(q->ev, q->ev + q->head, n * sizeof *q->ev);
        q->head = 0;
        q->len = n;
        return 0;
    }
    size_t cap = q->cap ? q->cap * 2 : 256;
    eq_event *ev = realloc(q->ev, cap * sizeof *ev);
    if (!ev) {
        return -1;
    }
    q->ev = ev;
    q->cap = cap;
    return 0;
}

eq_id eq_schedule_as(event_queue *q, sim_ps t, eq_id id, eq_fn fn, void *ctx, int64_t arg) {
    if (make_room(q) != 0) {
        return 0;
    }
    eq_event e = {
        .t = t < q->now ? q->now : t, /* never schedule into the past */
        .id = id,
        .fn = fn,
        .ctx = ctx,
        .arg = arg,
    };
    size_t i = q->len++;
    while (i > q->head && before(&e, &q->ev[i - 1])) {
        q->ev[i] = q->ev[i - 1];
        i--;
    }
    q->ev[i] = e;
    return id;
}

eq_id eq_schedule_any(event_queue *q, sim_ps t, eq_fn fn, void *ctx, int64_t arg) {
    return eq_schedule_as(q, t, eq_take_id(q), fn, ctx, arg);
}

int eq_cancel(event_queue *q, eq_id id) {
    if (id == 0) {
        return 0;
    }
    for (size_t i = q->head; i < q->len; i++) {
        if (q->ev[i].id == id) {
            memmove(q->ev + i, q->ev + i + 1, (q->len - i - 1) * sizeof *q->ev);
            q->len--;
            return 1;
        }
    }
    return 0;
}

size_t eq_run_until(event_queue *q, sim_ps t) {
    size_t n = 0;
    while (q->head < q->len && q->ev[q->head].t <= t) {
        eq_event e = q->ev[q->head++];
        if (q->head == q->len) {
            q->head = q->len = 0;
        }
        q->now = e.t;
        e.fn(e.ctx, e.t, e.arg);
        n++;
    }
    if (t > q->now) {
        q->now = t;
    }
    return n;
}

sim_ps eq_next_time(const event_queue *q) {
    return q->head < q->len ? q->ev[q->head].t : SIM_NEVER;
}
