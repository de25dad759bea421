/* Test helpers: a master that clocks MA frames into a slave model through
 * the event queue, exactly as the bench will, and reads SL back. */
#ifndef SLAVE_RIG_H
#define SLAVE_RIG_H

#include "event_queue.h"
#include "waveform.h"

typedef struct {
    event_queue q;
    waveform ma, sl;
    sim_edge_sink slave; /* MA input of the model under test */
    sim_ps t;            /* master's time cursor */
    sim_ps h;            /* MA half period */
    int ma_level;
} rig;

static inline void rig_init(rig *r, sim_ps half_period) {
    eq_init(&r->q);
    waveform_init(&r->ma, 1);
    waveform_init(&r->sl, 1);
    r->t = 1 * SIM_PS_PER_US;
    r->h = half_period;
    r->ma_level = 1;
    r->slave.fn = NULL;
}

static inline void rig_free(rig *r) {
    waveform_free(&r->ma);
    waveform_free(&r->sl);
    eq_free(&r->q);
}

static inline void rig_ma(rig *r, sim_ps t, int level) {
    eq_run_until(&r->q, t);
    r->ma_level = level;
    waveform_append(&r->ma, t, level);
    sim_edge_send(&r->slave, t, level);
}

/* One frame of nclk clocks from r->t: MA falls, then rises/falls every half
 * period. bits[k] = SL just before MA falls after rising edge k + 1. With
 * cdm = 1, MA goes low a half period after the last rise and stays low
 * until `hold` after it, then returns high. The cursor moves to `gap` after
 * the last MA edge. Returns the time of the last rising edge. */
static inline sim_ps rig_frame(rig *r, int nclk, int cdm, sim_ps hold, sim_ps gap, int *bits) {
    sim_ps t = r->t, last_rise = t;
    rig_ma(r, t, 0);
    for (int k = 1; k <= nclk; k++) {
        last_rise = t + (2 * k - 1) * r->h;
        rig_ma(r, last_rise, 1);
        if (k < nclk) {
            rig_ma(r, last_rise + r->h, 0);
        }
    }
    sim_ps end = last_rise;
    if (cdm) {
        rig_ma(r, last_rise + r->h, 0);
        rig_ma(r, last_rise + r->h + hold, 1);
        end = last_rise + r->h + hold;
    }
    eq_run_until(&r->q, end + gap);
    if (bits) {
        for (int k = 1; k <= nclk; k++) {
            bits[k - 1] = waveform_level_at(&r->sl, t + 2 * k * r->h - 1);
        }
    }
    r->t = end + gap;
    return last_rise;
}

static inline void bits_str(const int *bits, int from, int n, char *out) {
    for (int i = 0; i < n; i++) {
        out[i] = (char)('0' + bits[from + i]);
    }
    out[n] = '\0';
}

#endif
