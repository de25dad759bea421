/* line_usable.c - whether a clock rate survives a line (see line_model.h). */
#include "line_model.h"

#include <stdlib.h>

#define USABLE_PULSES 16

struct edge_log {
    sim_ps t[USABLE_PULSES + 2];
    int n;
};

static void log_edge(void *ctx, sim_ps t, int level) {
    struct edge_log *log = ctx;
    (void)level;
    if (log->n < USABLE_PULSES + 2) {
        log->t[log->n] = t;
    }
    log->n++;
}

int line_usable(const line_params *p, sim_ps half_ps) {
    line_params q = *p;
    q.jitter_rms_ps = 0; /* the question is the steady distortion, not noise */
    q.glitch_rate_hz = 0;
    q.fault = LINE_OK;
    event_queue eq;
    eq_init(&eq);
    struct edge_log log = {{0}, 0};
    line_dir l;
    line_dir_init(&l, &q, &eq, 1, 1, (sim_edge_sink){log_edge, &log});
    /* a long idle, then a burst of whole clock periods, as a frame starts */
    sim_ps t = 10 * SIM_PS_PER_US;
    for (int i = 0; i < USABLE_PULSES; i++) {
        eq_run_until(&eq, t);
        line_dir_input(&l, t, i & 1);
        t += half_ps;
    }
    eq_run_until(&eq, t + 100 * SIM_PS_PER_US);
    eq_free(&eq);
    if (log.n != USABLE_PULSES) {
        return 0; /* pulses vanished */
    }
    for (int i = 1; i < USABLE_PULSES; i++) {
        sim_ps w = log.t[i] - log.t[i - 1];
        if (4 * w < 3 * half_ps || 4 * w > 5 * half_ps) {
            return 0; /* a half period off by more than a quarter */
        }
    }
    return 1;
}
