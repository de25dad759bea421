#include "waveform.h"

#include <stdlib.h>
#include <string.h>

void waveform_init(waveform *w, int initial_level) {
    w->initial = initial_level ? 1 : 0;
    w->edges = NULL;
    w->len = w->cap = 0;
    w->hint = 0;
}

void waveform_free(waveform *w) {
    free(w->edges);
    w->edges = NULL;
    w->len = w->cap = 0;
}

int waveform_append_any(waveform *w, sim_ps t, int level) {
    level = level ? 1 : 0;
    if (w->len && t < w->edges[w->len - 1].t) {
        return -1;
    }
    if (level == waveform_last_level(w)) {
        return 0;
    }
    if (w->len == w->cap) {
        size_t cap = w->cap ? w->cap * 2 : 64;
        wave_edge *e = realloc(w->edges, cap * sizeof *e);
        if (!e) {
            return -1;
        }
        w->edges = e;
        w->cap = cap;
    }
    w->edges[w->len].t = t;
    w->edges[w->len].level = level;
    w->len++;
    return 0;
}

/* Binary search: the first index in [lo, hi) whose edge comes after t (hi
 * if none); the edges before lo are known to be at or before t. */
static size_t first_after(const waveform *w, size_t lo, size_t hi, sim_ps t) {
    while (lo < hi) {
        size_t mid = lo + (hi - lo) / 2;
        if (w->edges[mid].t <= t) {
            lo = mid + 1;
        } else {
            hi = mid;
        }
    }
    return lo;
}

size_t waveform_index_after(const waveform *w, sim_ps t) {
    return first_after(w, 0, w->len, t);
}

/* Number of transitions with time <= t. Starts from the last answer and
 * walks, falling back to a binary search for long jumps. */
static size_t count_upto(waveform *w, sim_ps t) {
    size_t i = w->hint > w->len ? w->len : w->hint;
    if (i > 0 && w->edges[i - 1].t > t) {
        i = first_after(w, 0, i, t);
    } else {
        size_t steps = 0;
        while (i < w->len && w->edges[i].t <= t && steps < 16) {
            i++;
            steps++;
        }
        if (i < w->len && w->edges[i].t <= t) {
            i = first_after(w, i, w->len, t);
        }
    }
    w->hint = i;
    return i;
}

int waveform_level_at(waveform *w, sim_ps t) {
    size_t n = count_upto(w, t);
    return n ? w->edges[n - 1].level : w->initial;
}

sim_ps waveform_next_after(waveform *w, sim_ps t) {
    size_t n = count_upto(w, t);
    return n < w->len ? w->edges[n].t : SIM_NEVER;
}

int waveform_level_next(waveform *w, sim_ps t, sim_ps *next) {
    /* mostly asked again between the same two edges as last time: that
     * answer is tested first, without count_upto()'s loop (whose varying
     * length the host mispredicts) */
    size_t n = w->hint;
    if (n > w->len || (n > 0 && w->edges[n - 1].t > t)) {
        n = count_upto(w, t);
    } else if (n < w->len && w->edges[n].t <= t) {
        /* mostly one edge on: the run after a change */
        if (n + 1 == w->len || w->edges[n + 1].t > t) {
            w->hint = ++n;
        } else {
            n = count_upto(w, t);
        }
    }
    *next = n < w->len ? w->edges[n].t : SIM_NEVER;
    return n ? w->edges[n - 1].level : w->initial;
}

sim_ps waveform_find(const waveform *w, sim_ps t, int level, size_t *at) {
    size_t i = *at;
    if (i >= w->len || w->edges[i].t >= t) {
        /* not a place before t (the record was cut, or t went back): back
         * from the end by doubling steps to an edge before t, then a
         * binary search from there */
        size_t back = 1;
        while (back < w->len && w->edges[w->len - back].t >= t) {
            back *= 2;
        }
        i = first_after(w, back < w->len ? w->len - back : 0, w->len, t - 1);
    }
    if (i < w->len && w->edges[i].t < t) {
        /* on from a place before t by doubling steps, then a binary search */
        size_t step = 1;
        while (i + step < w->len && w->edges[i + step].t < t) {
            i += step;
            step *= 2;
        }
        size_t hi = i + step < w->len ? i + step : w->len;
        i = first_after(w, i + 1, hi, t - 1);
    }
    for (; i < w->len; i++) {
        if (w->edges[i].level == level) {
            *at = i;
            return w->edges[i].t;
        }
    }
    return SIM_NEVER;
}

void waveform_forget_before(waveform *w, sim_ps t) {
    size_t n = count_upto(w, t);
    /* Keep the transition at exactly t if there is one, so edge times stay. */
    while (n > 0 && w->edges[n - 1].t == t) {
        n--;
    }
    if (n == 0) {
        return;
    }
    w->initial = w->edges[n - 1].level;
    memmove(w->edges, w->edges + n, (w->len - n) * sizeof *w->edges);
    w->len -= n;
    w->hint = 0;
}

static void sink_fn(void *ctx, sim_ps t, int level) {
    waveform_append(ctx, t, level);
}

sim_edge_sink waveform_sink(waveform *w) {
    sim_edge_sink s = {sink_fn, w};
    return s;
}
