/* frame_marks.c - each frame's first MA fall at the master pin, and what
 * is measured there (frame_marks.h, INSTRUMENTS.md). */
#include "frame_marks.h"

#include <string.h>

void frame_marks_init(struct frame_marks *m) {
    *m = (struct frame_marks){.record = -1};
}

void bench_span_add(struct bench_span *s, int64_t v) {
    if (s->n == 0 || v < s->min_ps) {
        s->min_ps = v;
    }
    if (s->n == 0 || v > s->max_ps) {
        s->max_ps = v;
    }
    s->sum_ps += v;
    s->n++;
}

/* The end of the slave's closed frame k (its timeout over), -1 if its
 * record is no longer kept (or not yet closed). */
static sim_ps record_end(const link_model *l, uint64_t k) {
    return link_frame_end(l, k);
}

/* The slave's newest frame whose timeout ended before t, among the
 * records it keeps: its number, and in *sl_rise when SL rose at the
 * slave's pin after it (the timeout's end plus the output delay); -1 if
 * none. The falls come in time order: the search goes on from the last
 * answer (m->record) where it still holds. */
static int64_t ended_before(struct frame_marks *m, const link_model *l, int64_t t,
                            sim_ps *sl_rise) {
    int64_t k = m->record;
    sim_ps end = k >= 0 ? record_end(l, (uint64_t)k) : -1;
    if (end < 0 || end >= t) {
        /* from the newest back */
        for (k = (int64_t)link_frames(l) - 1; k >= 0; k--) {
            end = record_end(l, (uint64_t)k);
            if (end < 0 || end < t) {
                break;
            }
        }
        if (k < 0 || end < 0) {
            return -1;
        }
    }
    for (sim_ps next; (next = record_end(l, (uint64_t)k + 1)) >= 0 && next < t;) {
        k++;
        end = next;
    }
    m->record = k;
    *sl_rise = end + l->model->out_delay(link_model_cfg(l));
    return k;
}

/* SL high at the master pin after the previous frame (the first rise there
 * no earlier than the slave's rise plus the SL line's least delay) to the
 * first fall at t. SL at the master keeps a millisecond of history (the
 * bench drops what is older): a restart from further back is not measured. */
static void restart(struct frame_marks *m, struct bench_stats *st, link_model *l, sim_ps sl_rise,
                    int64_t t) {
    sim_ps from = sl_rise + l->sl_reach_ps;
    if (l->external) {
        /* the encoder firmware's SL rises within a few ns of the model's,
         * either side (pru_slave/README.md, "Timeout"); SL is low through
         * a timeout, so a look from 100 ns earlier finds its rise */
        from -= 100 * SIM_PS_PER_NS;
    }
    if (from < t - SIM_PS_PER_MS) {
        return;
    }
    sim_ps x = waveform_find(link_pin_record(l, LINK_SL_MASTER), from, 1, &m->sl_at);
    if (x <= t) { /* else SL did not rise before the fall */
        bench_span_add(&st->restart, t - x);
    }
}

/* The IEP, when CMP0 resets its count (a periodic trigger): its periods
 * start where COUNT is 0, `period` cycles apart; v (a view of it now)
 * places them, so a first fall at pin time t lies in the period that
 * began at the last such start at or before its cycle. */
static void iep_phase(struct frame_marks *m, struct bench_stats *st, const struct pru_iep_view *v,
                      int64_t gpo_delay_ps, int64_t t, int64_t frame) {
    if (!v->cmp0_resets || v->inc == 0) {
        return;
    }
    int64_t period = (int64_t)((v->cmp0 + v->inc - 1) / v->inc) + 1; /* 0 .. CMP0, then 0 */
    int64_t ref = v->cycle - v->count / v->inc;                      /* a period's start */
    int64_t b = (t - gpo_delay_ps) / PRU_PS_PER_CYCLE; /* the boundary the pin change follows */
    int64_t phase = (b - ref) % period;
    int64_t start = b - (phase < 0 ? phase + period : phase);
    if (st->iep_phase.n == 0) {
        st->iep_periods = 1;
    } else {
        int64_t gap = (start - m->iep_start) / period;
        st->iep_periods += (uint64_t)gap;
        st->iep_crowded += gap == 0;
        st->iep_skipped += gap > 1 ? (uint64_t)(gap - 1) : 0;
    }
    m->iep_start = start;
    st->iep_period = (uint32_t)period;
    bench_span_add(&st->iep_phase, t - start * PRU_PS_PER_CYCLE);
    if (frame >= 0) {
        iep_track_start(&st->iep_track, (uint64_t)frame, start, period,
                        t - start * PRU_PS_PER_CYCLE);
    }
}

/* Edge k's time for k >= -2 (k is unsigned: -1 wraps): before edge 0 MA
 * was high from time 0 (edge -1, a rise) after no fall at all (edge -2). */
static int64_t edge_time(const struct frame_marks_edges *e, uint64_t k) {
    if (k + 2 < 2) {
        return k == UINT64_MAX ? 0 : INT64_MIN / 4;
    }
    return e->ring[k & (e->ring_len - 1)];
}

/* Edges looked at a block at a time (even: a block keeps the parity). */
#define CLOCK_BLOCK 16u

/* Two ring entries at a time (GNU C vector extensions): a block of clock
 * periods is an arithmetic progression, p[k] = p[0] + k * H. */
typedef int64_t pair_t __attribute__((vector_size(16)));

/* Whether the edges p[1..CLOCK_BLOCK] follow p[0] by H each. */
static inline bool clock_block(const int64_t *p, int64_t half) {
    pair_t base = {p[0], p[0]}, step = {2 * half, 2 * half}, want = {half, 2 * half},
           other = {0, 0};
    for (unsigned i = 1; i <= CLOCK_BLOCK; i += 2) {
        pair_t v;
        memcpy(&v, p + i, sizeof v);
        other |= (v - base) ^ want;
        want += step;
    }
    return (other[0] | other[1]) == 0;
}

/* From fall f on (f >= 2), whole blocks of edges every phase of which
 * lasts H (clock periods: no frame starts there) skipped: the first fall
 * of the first block that has another phase, or that lies too close to
 * `end` or across the ring's end to look at whole. Most of the edges pass
 * only here. */
static uint64_t skip_clock(const int64_t *ring, uint64_t mask, int64_t half, uint64_t f,
                           uint64_t end) {
    for (; f + CLOCK_BLOCK <= end; f += CLOCK_BLOCK) {
        uint64_t at = (f - 2) & mask; /* the phases ending at edges f-1 .. f+BLOCK-2 */
        if (at + CLOCK_BLOCK > mask || !clock_block(ring + at, half)) {
            break;
        }
    }
    return f;
}

/* The next fall at or after `f` (even, >= 2) before `end` that is a
 * frame's first, else the first even edge at or after end. */
static uint64_t next_first(const int64_t *ring, uint64_t mask, int64_t half, uint64_t f,
                           uint64_t end) {
    for (; f < end; f += 2) {
        int64_t t = ring[f & mask], up = ring[(f - 1) & mask], down = ring[(f - 2) & mask];
        if (((t - up) ^ half) | ((up - down) ^ half)) {
            break;
        }
    }
    return f;
}

void frame_marks_scan(struct frame_marks *m, struct bench_stats *st,
                      const struct frame_marks_edges *e, link_model *l, const struct pru_core *c,
                      int64_t gpo_delay_ps, uint64_t frame_limit) {
    if (e->edges > e->ring_len && m->next < e->edges - e->ring_len + 2) {
        /* dropped before they were looked at: go on from the oldest fall
         * whose two edges before it are still there */
        uint64_t from = e->edges - e->ring_len + 2;
        from += from & 1u;
        m->lost += from - m->next;
        m->next = from;
    }
    if (!m->half_ps) {
        m->next = e->edges + (e->edges & 1u); /* no marks without H */
        return;
    }
    struct pru_iep_view v = {0};
    bool viewed = false;
    uint64_t mask = e->ring_len - 1;
    /* the falls (even edges), each with the rise and fall before it: a
     * frame's first unless both phases are H */
    while (m->next < e->edges) {
        uint64_t f = m->next;
        if (f >= 2) {
            f = skip_clock(e->ring, mask, m->half_ps, f, e->edges);
            uint64_t end = f + CLOCK_BLOCK < e->edges ? f + CLOCK_BLOCK : e->edges;
            f = next_first(e->ring, mask, m->half_ps, f, end);
            if (f >= end) {
                m->next = f; /* none in this block */
                continue;
            }
        }
        m->next = f + 2;
        int64_t t = edge_time(e, f);
        int64_t rise = edge_time(e, f - 1), fall = edge_time(e, f - 2);
        int64_t high = t - rise;
        if (((high ^ m->half_ps) | ((rise - fall) ^ m->half_ps)) == 0) {
            continue;
        }
        sim_ps sl_rise = 0;
        int64_t before = ended_before(m, l, t, &sl_rise);
        if ((uint64_t)(before + 1) >= frame_limit) {
            continue; /* the frame it starts is not measured */
        }
        bench_span_add(&st->ma_high, high);
        st->ma_high_short += high < m->half_ps;
        if (before >= 0 && (uint64_t)before + 1 != m->used_record) {
            m->used_record = (uint64_t)before + 1;
            restart(m, st, l, sl_rise, t);
        }
        if (!viewed) {
            pru_iep_view(c, pru_cycles(c), &v);
            viewed = true;
        }
        iep_phase(m, st, &v, gpo_delay_ps, t, before >= 0 ? before + 1 : -1);
    }
}
