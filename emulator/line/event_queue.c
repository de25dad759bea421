/* Binary min-heap ordered by (time, id). Pending events are few (a handful
 * per component), so cancellation by a linear search is cheaper than
 * keeping an index map up to date. */
#include "event_queue.h"

#include <stdlib.h>

static int before(const eq_event *a, const eq_event *b) {
    return a->t < b->t || (a->t == b->t && a->id < b->id);
}

/* Sifts move a hole instead of swapping: one copy per level, not three. */
static void sift_up(event_queue *q, size_t i) {
    eq_event e = q->heap[i];
    while (i > 0) {
        size_t parent = (i - 1) / 2;
        if (!before(&e, &q->heap[parent])) {
            break;
        }
        q->heap[i] = q->heap[parent];
        i = parent;
    }
    q->heap[i] = e;
}

static void sift_down(event_queue *q, size_t i) {
    eq_event e = q->heap[i];
    for (;;) {
        size_t l = 2 * i + 1, r = l + 1, m = l;
        if (l >= q->len) {
            break;
        }
        if (r < q->len && before(&q->heap[r], &q->heap[l])) {
            m = r;
        }
        if (!before(&q->heap[m], &e)) {
            break;
        }
        q->heap[i] = q->heap[m];
        i = m;
    }
    q->heap[i] = e;
}

/* The last event fills slot i and moves down or up to its place. */
static void remove_at(event_queue *q, size_t i) {
    q->len--;
    if (i == q->len) {
        return;
    }
    q->heap[i] = q->heap[q->len];
    if (i > 0 && before(&q->heap[i], &q->heap[(i - 1) / 2])) {
        sift_up(q, i);
    } else {
        sift_down(q, i);
    }
}

void eq_init(event_queue *q) {
    q->heap = NULL;
    q->len = q->cap = 0;
    q->next_id = 1;
    q->now = 0;
}

void eq_free(event_queue *q) {
    free(q->heap);
    q->heap = NULL;
    q->len = q->cap = 0;
}

eq_id eq_take_id(event_queue *q) {
    return q->next_id++;
}

eq_id eq_schedule_as(event_queue *q, sim_ps t, eq_id id, eq_fn fn, void *ctx, int64_t arg) {
    if (q->len == q->cap) {
        size_t cap = q->cap ? q->cap * 2 : 16;
        eq_event *heap = realloc(q->heap, cap * sizeof *heap);
        if (!heap) {
            return 0;
        }
        q->heap = heap;
        q->cap = cap;
    }
    q->heap[q->len] = (eq_event){
        .t = t < q->now ? q->now : t, /* never schedule into the past */
        .id = id,
        .fn = fn,
        .ctx = ctx,
        .arg = arg,
    };
    sift_up(q, q->len++);
    return id;
}

eq_id eq_schedule(event_queue *q, sim_ps t, eq_fn fn, void *ctx, int64_t arg) {
    /* The id is taken before sifting: the new event may move up the heap,
     * and the slot it was written to then holds another event. */
    return eq_schedule_as(q, t, eq_take_id(q), fn, ctx, arg);
}

int eq_cancel(event_queue *q, eq_id id) {
    if (id == 0) {
        return 0;
    }
    for (size_t i = 0; i < q->len; i++) {
        if (q->heap[i].id == id) {
            remove_at(q, i);
            return 1;
        }
    }
    return 0;
}

size_t eq_run_until(event_queue *q, sim_ps t) {
    size_t n = 0;
    while (q->len > 0 && q->heap[0].t <= t) {
        eq_event e = q->heap[0];
        remove_at(q, 0);
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
    return q->len ? q->heap[0].t : SIM_NEVER;
}
