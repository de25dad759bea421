/* The record of one wire: its initial level and every transition after it.
 *
 * The bench keeps one per pin of interest ("SL at the master", "MA at the
 * slave", ...) to answer level queries when the PRU reads SL, to find the
 * next change for fast-forwarding, and to write VCD. Transitions are stored
 * in time order; appending an edge that does not change the level is a
 * no-op, so producers may send redundant edges. */
#ifndef WAVEFORM_H
#define WAVEFORM_H

#include "sim_time.h"

#include <stddef.h>

typedef struct {
    sim_ps t;
    int level;
} wave_edge;

typedef struct {
    int initial;
    wave_edge *edges;
    size_t len, cap;
    size_t hint; /* index of the last lookup: queries are mostly monotonic */
} waveform;

void waveform_init(waveform *w, int initial_level);
void waveform_free(waveform *w);

/* waveform_append() in full (it takes the common case in line). */
int waveform_append_any(waveform *w, sim_ps t, int level);

/* Appends a transition at t (not earlier than the last one). Returns 0, or -1
 * on out-of-order time or no memory (the record is left unchanged). Every
 * pin edge of the bench comes here, mostly with room and in order. */
static inline int waveform_append(waveform *w, sim_ps t, int level) {
    if (w->len && w->len < w->cap && t >= w->edges[w->len - 1].t) {
        level = level ? 1 : 0;
        if (level != w->edges[w->len - 1].level) {
            w->edges[w->len].t = t;
            w->edges[w->len].level = level;
            w->len++;
        }
        return 0;
    }
    return waveform_append_any(w, t, level);
}

/* Level at time t; a transition at exactly t is already in effect. */
int waveform_level_at(waveform *w, sim_ps t);

/* Time of the first transition strictly after t, or SIM_NEVER. */
sim_ps waveform_next_after(waveform *w, sim_ps t);

/* The index of the first transition strictly after t (len if none), by
 * binary search, leaving the record's place for the calls above alone. */
size_t waveform_index_after(const waveform *w, sim_ps t);

/* Level at time t, and in *next the time of the first transition after t
 * (SIM_NEVER if none): waveform_level_at and waveform_next_after at once. */
int waveform_level_next(waveform *w, sim_ps t, sim_ps *next);

/* The first transition to `level` at or after t, SIM_NEVER if none; a
 * look elsewhere that leaves the record's place for the calls above (the
 * core's reads of SL) where it was. *at is the caller's own place: where
 * the answer was (an index), and where the next search starts when t has
 * moved on (asked in time order, each search walks a few edges). */
sim_ps waveform_find(const waveform *w, sim_ps t, int level, size_t *at);

/* Level after the last transition. */
static inline int waveform_last_level(const waveform *w) {
    return w->len ? w->edges[w->len - 1].level : w->initial;
}

/* Drops transitions before t, keeping the level at t as the initial level,
 * so a long run can bound its memory. */
void waveform_forget_before(waveform *w, sim_ps t);

/* A sink that appends to the waveform, for wiring it behind a model. */
sim_edge_sink waveform_sink(waveform *w);

#endif
