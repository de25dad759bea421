/*
 * frame_marks.h - where each frame begins at the master's MA pin, and what
 * the bench measures there (emulator/bench/INSTRUMENTS.md): the MA high
 * phase before the frame's first falling edge, the restart after the
 * previous frame's timeout, the IEP period's start to the first fall.
 *
 * Inside a frame every MA phase is exactly H (the firmware's clocked
 * periods), so a falling edge whose high phase and the low phase before it
 * are both H closes a clock period; any other fall is a frame's first. This
 * needs nothing from the slave: a pulse the cable swallows still counts
 * where the master drove it.
 *
 * The edges are looked at afterwards, from the bench's ring of master MA
 * edge times (edge 0 a fall: MA idles high and the pins change level on
 * every edge, so even edges fall and odd ones rise), never on the way of
 * an edge: the bench scans after each run step.
 */
#ifndef FRAME_MARKS_H
#define FRAME_MARKS_H

#include "bench.h"

#include <stdbool.h>
#include <stdint.h>

struct frame_marks {
    int64_t half_ps;      /* H in ps, 0: unknown (no marks) */
    uint64_t next;        /* the next fall (an even edge) to look at */
    uint64_t used_record; /* the slave record a restart was last measured from, + 1 */
    int64_t record;       /* the slave record the last fall came after, -1 none */
    size_t sl_at;         /* where the last SL rise was found in SL's record */
    int64_t iep_start;    /* the IEP period start (cycle) of the last first fall */
    uint64_t lost;        /* edges the ring had dropped before they were looked at */
};

void frame_marks_init(struct frame_marks *m);

/* Where the edges are: ring[k % ring_len] is master edge k's pin time
 * (ps), `edges` of them so far; ring_len a power of two. */
struct frame_marks_edges {
    const int64_t *ring;
    uint64_t ring_len, edges;
};

/* Looks at the master edges not yet seen: each frame's first fall is
 * measured into st unless the frame it starts is numbered frame_limit or
 * later (the slave's numbering: the frames that ended before it). c is the
 * core that drove them (its IEP, now), gpo_delay_ps its pin delay. */
void frame_marks_scan(struct frame_marks *m, struct bench_stats *st,
                      const struct frame_marks_edges *e, link_model *l, const struct pru_core *c,
                      int64_t gpo_delay_ps, uint64_t frame_limit);

/* Adds v to a span. */
void bench_span_add(struct bench_span *s, int64_t v);

#endif
