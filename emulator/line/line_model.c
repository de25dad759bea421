#include "line_model.h"

#include <math.h>

#define LN2 0.69314718055994530942

void line_params_default(line_params *p) {
    p->length_m = 0.0;
    p->ps_per_m = 5000.0;
    p->driver_delay_ps = 9000;
    p->receiver_delay_ps = 15000;
    p->rise_extra_ps = 0;
    p->fall_extra_ps = 1000;
    p->tau0_ps = 0.0;
    p->tau_per_m2_ps = 20.0;
    p->jitter_rms_ps = 0.0;
    p->glitch_rate_hz = 0.0;
    p->glitch_width_ps = 20000;
    p->fault = LINE_OK;
    p->fault_at_ps = 0;
    p->fault_until_ps = 0;
}

double line_tau_ps(const line_params *p) {
    double t = p->tau0_ps + p->tau_per_m2_ps * p->length_m * p->length_m;
    return t > 0.0 ? t : 0.0;
}

sim_ps line_fixed_delay_ps(const line_params *p) {
    return p->driver_delay_ps + p->receiver_delay_ps + (sim_ps)llround(p->length_m * p->ps_per_m);
}

double line_nominal_delay_ps(const line_params *p) {
    return (double)line_fixed_delay_ps(p) + line_tau_ps(p) * LN2 +
           0.5 * (double)(p->rise_extra_ps + p->fall_extra_ps);
}

/* ---- output stage: glitches and faults sit on the receiver output ---- */

static int forced_level(line_fault f, int fallback) {
    switch (f) {
    case LINE_STUCK_LOW:
        return 0;
    case LINE_STUCK_HIGH:
    case LINE_OPEN:
        return 1;
    default:
        return fallback;
    }
}

static void send_current(line_dir *l, sim_ps t) {
    int want = l->fault != LINE_OK ? forced_level(l->fault, 0)
                                   : (l->glitching ? !l->true_level : l->true_level);
    if (want != l->cur_level) {
        l->cur_level = want;
        sim_edge_send(&l->out, t, want);
    }
}

static void on_output_edge(void *ctx, sim_ps t, int64_t level) {
    line_dir *l = ctx;
    l->true_level = (int)level;
    l->edges_out++;
    send_current(l, t);
}

static void on_glitch_end(void *ctx, sim_ps t, int64_t arg) {
    (void)arg;
    line_dir *l = ctx;
    l->glitching = 0;
    send_current(l, t);
}

static void schedule_next_glitch(line_dir *l, sim_ps from);

static void on_glitch_start(void *ctx, sim_ps t, int64_t arg) {
    (void)arg;
    line_dir *l = ctx;
    l->glitching = 1;
    l->glitches++;
    send_current(l, t);
    sim_ps w = l->p.glitch_width_ps > 0 ? l->p.glitch_width_ps : 1;
    eq_schedule(l->q, t + w, on_glitch_end, l, 0);
    schedule_next_glitch(l, t + w);
}

static void schedule_next_glitch(line_dir *l, sim_ps from) {
    if (l->p.glitch_rate_hz <= 0.0) {
        return;
    }
    double mean_ps = (double)SIM_PS_PER_S / l->p.glitch_rate_hz;
    double gap = sim_rng_exponential(&l->rng, mean_ps);
    /* a rate so low (a denormal: the mean overflows) that the next glitch
     * lies beyond any time a run reaches: none; llround would overflow */
    if (!(gap < (double)(SIM_NEVER - from))) {
        return;
    }
    sim_ps g = (sim_ps)llround(gap);
    eq_schedule(l->q, from + (g > 0 ? g : 1), on_glitch_start, l, 0);
}

static void on_fault(void *ctx, sim_ps t, int64_t f) {
    line_dir *l = ctx;
    l->fault = (line_fault)f;
    send_current(l, t);
}

/* ---- driver, low-pass, cable, receiver ---- */

void line_dir_init(line_dir *l, const line_params *p, event_queue *q, uint64_t seed, int idle_level,
                   sim_edge_sink out) {
    l->p = *p;
    l->q = q;
    sim_rng_seed(&l->rng, seed);
    l->out = out;
    l->tau = line_tau_ps(p);
    l->fixed = line_fixed_delay_ps(p);
    idle_level = idle_level ? 1 : 0;
    l->v0 = idle_level;
    l->t0 = eq_now(q);
    l->target = idle_level;
    l->in_level = idle_level;
    l->last_in = eq_now(q);
    l->filt_level = idle_level;
    for (int i = 0; i < 2; i++) {
        l->memo_dt[i] = -1;
        l->memo_exp[i] = 0.0;
        l->memo_ratio[i] = 0.0;
        l->memo_cross[i] = 0;
    }
    l->settled_steps = 0;
    line_dir_set_settled_fast(l, 1);
    l->hold = l->held = 0;
    l->pending = 0;
    l->pending_cross = 0;
    l->pending_ev = 0;
    l->pending_out = 0;
    l->last_out = eq_now(q);
    l->true_level = idle_level;
    l->cur_level = idle_level;
    l->glitching = 0;
    l->fault = LINE_OK;
    l->edges_in = l->edges_out = l->glitches = l->vanished = 0;
    schedule_next_glitch(l, eq_now(q));
    if (p->fault != LINE_OK) {
        line_dir_set_fault(l, p->fault_at_ps, p->fault);
        if (p->fault_until_ps > p->fault_at_ps) {
            line_dir_set_fault(l, p->fault_until_ps, LINE_OK);
        }
    }
}

void line_dir_set_fault(line_dir *l, sim_ps t, line_fault f) {
    eq_schedule(l->q, t, on_fault, l, (int64_t)f);
}

void line_dir_set_settled_fast(line_dir *l, int on) {
    l->settle_gap = SIM_NEVER;
    l->settled_cross = 0;
    /* 41 tau: gap / tau >= 40 even after the division's rounding, and
     * exp(-40) = 4.2e-18 < 2^-54 = 5.6e-17; |v0 - target| <= 1, so the
     * product is below half an ulp of 1 and target + it rounds to target */
    if (on && l->tau > 0.0 && 41.0 * l->tau < 1e15) {
        l->settle_gap = (sim_ps)ceil(41.0 * l->tau);
        l->settled_cross = (sim_ps)llround(l->tau * log(2.0));
    }
}

void line_dir_set_hold(line_dir *l, int on) {
    l->hold = on != 0;
}

void line_dir_schedule_held(line_dir *l) {
    l->held = 0;
    eq_schedule_as(l->q, l->held_out, l->held_id, on_output_edge, l, l->held_level);
}

void line_dir_take_held(line_dir *l) {
    l->held = 0;
    l->true_level = l->held_level;
    l->edges_out++;
    l->cur_level = l->held_level; /* send_current()'s, the sink told already */
}

/* With hold on: the output event of an edge at out held for the owner,
 * under the id it would have had. */
static inline eq_id hold_edge(line_dir *l, sim_ps out, int level) {
    l->held = 1;
    l->held_out = out;
    l->held_level = level;
    l->held_id = eq_take_id(l->q);
    return l->held_id;
}

/* The output event of an edge at out (after its crossing), or held. */
static eq_id schedule_or_hold(line_dir *l, sim_ps out, int level) {
    return l->hold ? hold_edge(l, out, level) : eq_schedule(l->q, out, on_output_edge, l, level);
}

/* Filter value at time t (>= t0), taken when the input goes to `level`. */
static double filter_value(line_dir *l, sim_ps t, int level) {
    if (l->tau <= 0.0) {
        return l->target;
    }
    sim_ps gap = t - l->t0;
    if (gap != l->memo_dt[level]) {
        l->memo_dt[level] = gap;
        l->memo_exp[level] = exp(-(double)gap / l->tau);
    }
    return l->target + (l->v0 - l->target) * l->memo_exp[level];
}

/* Time after t at which a filter at value v heading for target crosses 1/2. */
static sim_ps crossing_after(line_dir *l, double v, int target) {
    if (l->tau <= 0.0) {
        return 0;
    }
    /* (v - target) / (0.5 - target), > 1 when a crossing lies ahead; the
     * divisor is +-1/2, so multiplying by +-2 gives the same bits, faster */
    double ratio = (v - target) * (target ? -2.0 : 2.0);
    if (ratio <= 1.0) {
        return 0;
    }
    if (ratio != l->memo_ratio[target]) {
        l->memo_ratio[target] = ratio;
        l->memo_cross[target] = (sim_ps)llround(l->tau * log(ratio));
    }
    return l->memo_cross[target];
}

/* An input edge at te after the filter settled at the old target (see
 * settle_gap): the new target is the other level, so a crossing's ratio
 * is (v - target) * -+2 = 2, the one of settled_cross. 0 if the
 * receiver already shows the level (no crossing). */
static inline int settled_step(line_dir *l, sim_ps te, int level) {
    l->settled_steps++;
    l->v0 = l->target;
    l->t0 = te;
    l->target = level;
    return level != l->filt_level;
}

/* line_dir_input() in general: any edge, level already 0 or 1 and new. */
static __attribute__((noinline)) void input_general(line_dir *l, sim_ps t, int level) {
    l->in_level = level;
    l->edges_in++;

    /* Driver skew moves the edge; it can never move before the previous one. */
    sim_ps te = t + (level ? l->p.rise_extra_ps : l->p.fall_extra_ps);
    if (te < l->last_in) {
        te = l->last_in;
    }
    l->last_in = te;

    /* A crossing still ahead of this edge never happens: the pulse vanished.
     * One already passed is final, whether or not its output event has run. */
    if (l->pending) {
        if (l->pending_cross > te) {
            eq_cancel(l->q, l->pending_ev);
            l->vanished++;
        } else {
            l->filt_level = l->target;
            l->last_out = l->pending_out;
        }
        l->pending = 0;
    }

    sim_ps cross;
    if (te - l->t0 >= l->settle_gap) {
        if (!settled_step(l, te, level)) {
            return;
        }
        cross = te + l->settled_cross;
    } else {
        double v = filter_value(l, te, level);
        l->v0 = v;
        l->t0 = te;
        l->target = level;
        if (level == l->filt_level) {
            return; /* heading back to the level the receiver still shows */
        }
        cross = te + crossing_after(l, v, level);
    }
    sim_ps out = cross + l->fixed;
    if (l->p.jitter_rms_ps > 0.0) {
        out += (sim_ps)llround(sim_rng_gauss(&l->rng) * l->p.jitter_rms_ps);
    }
    if (out <= t) {
        out = t + 1; /* every effect strictly after its cause */
    }
    if (out <= l->last_out) {
        out = l->last_out + 1; /* jitter never reorders edges */
    }
    l->pending = 1;
    l->pending_cross = cross;
    l->pending_out = out;
    l->pending_ev = schedule_or_hold(l, out, level);
}

/* The output event of the edge just placed, when the queue has to grow
 * or sort it in out of line. */
static __attribute__((noinline)) void schedule_output(line_dir *l, sim_ps out, int level) {
    l->pending_ev = eq_schedule_any(l->q, out, on_output_edge, l, level);
}

/* A clocked line's edge: the filter settled (line-settled), the last
 * crossing passed, no jitter. That is input_general()'s arithmetic for the
 * case, step for step, with no call but in tail position, so it saves no
 * registers (every MA edge comes here); anything else goes there. */
void line_dir_input(line_dir *l, sim_ps t, int level) {
    level = level ? 1 : 0;
    if (level == l->in_level) {
        return;
    }
    sim_ps te = t + (level ? l->p.rise_extra_ps : l->p.fall_extra_ps);
    if (te < l->last_in) {
        te = l->last_in;
    }
    if (te - l->t0 < l->settle_gap || (l->pending && l->pending_cross > te) ||
        l->p.jitter_rms_ps > 0.0) {
        input_general(l, t, level);
        return;
    }
    l->in_level = level;
    l->edges_in++;
    l->last_in = te;
    if (l->pending) { /* the crossing has passed: final */
        l->filt_level = l->target;
        l->last_out = l->pending_out;
        l->pending = 0;
    }
    if (!settled_step(l, te, level)) {
        return;
    }
    sim_ps cross = te + l->settled_cross;
    sim_ps out = cross + l->fixed;
    if (out <= t) {
        out = t + 1;
    }
    if (out <= l->last_out) {
        out = l->last_out + 1;
    }
    l->pending = 1;
    l->pending_cross = cross;
    l->pending_out = out;
    if (l->hold) {
        l->pending_ev = hold_edge(l, out, level);
        return;
    }
    if (eq_fits(l->q, out)) {
        l->pending_ev = eq_put(l->q, out, on_output_edge, l, level);
        return;
    }
    schedule_output(l, out, level);
}

static void sink_fn(void *ctx, sim_ps t, int level) {
    line_dir_input(ctx, t, level);
}

sim_edge_sink line_dir_sink(line_dir *l) {
    sim_edge_sink s = {sink_fn, l};
    return s;
}
