#include "link_model.h"

#include <math.h>
#include <string.h>

/* Fan-out points: a pin is recorded, passed on, and shown to the observer. */

static void observe(link_model *l, link_pin pin, sim_ps t, int level) {
    if (l->observer_pins & 1u << pin) {
        l->observer(l->observer_ctx, pin, t, level);
    }
}

/* A pin's record takes the edge, or its level only (link_keep_history). */
static inline void record(link_model *l, link_pin pin, waveform *w, sim_ps t, int level) {
    if (l->history_pins & 1u << pin) {
        waveform_append(w, t, level);
    } else {
        w->initial = level ? 1 : 0;
    }
}

/* Any model's MA edge through its table, but BiSS-C's, whose quick step
 * was tried already. */
static __attribute__((noinline)) void ma_slave_general(link_model *l, sim_ps t, int level) {
    if (l->biss_quick) {
        biss_slave_ma_edge_general((biss_slave *)l->slave, t, level);
    } else {
        l->model->ma_edge(l->slave, t, level);
    }
    observe(l, LINK_MA_SLAVE, t, level);
}

/* An external slave: at a rising MA edge at the slave pin, its SL and the
 * model's, each settled on the bit the last rise asked for. */
static __attribute__((noinline)) void compare_external(link_model *l, sim_ps t) {
    l->ext_compared++;
    if (waveform_last_level(&l->sl_slave) != waveform_last_level(&l->sl_model)) {
        if (l->ext_differ++ == 0) {
            l->ext_first_differ = t;
        }
    }
}

/* A BiSS frame's clock edges take the slave's quick step, called directly
 * rather than through the model's table, with calls in tail position only
 * (no saved registers); the rest goes out of line. */
static void at_ma_slave(void *ctx, sim_ps t, int level) {
    link_model *l = ctx;
    record(l, LINK_MA_SLAVE, &l->ma_slave, t, level);
    if (l->biss_quick && biss_slave_ma_edge_quick((biss_slave *)l->slave, t, level)) {
        observe(l, LINK_MA_SLAVE, t, level);
        return;
    }
    ma_slave_general(l, t, level);
}

/* MA at the slave pin with an external slave: the comparison at a rising
 * edge, then the model's step as ever (the MA line's sink only while an
 * external slave is set: the model's own edges pay no test for it). */
static void at_ma_slave_external(void *ctx, sim_ps t, int level) {
    if (level) {
        compare_external(ctx, t);
    }
    at_ma_slave(ctx, t, level);
}

static void at_sl_slave(void *ctx, sim_ps t, int level) {
    link_model *l = ctx;
    if (l->external) { /* the model beside an external slave: its own record */
        l->sl_model.initial = level ? 1 : 0;
        return;
    }
    record(l, LINK_SL_SLAVE, &l->sl_slave, t, level);
    line_dir_input(&l->sl_line, t, level);
    observe(l, LINK_SL_SLAVE, t, level);
}

static void at_sl_master(void *ctx, sim_ps t, int level) {
    link_model *l = ctx;
    record(l, LINK_SL_MASTER, &l->sl_master, t, level);
    observe(l, LINK_SL_MASTER, t, level);
}

/* The least delay from an SL line input at t to its output: the output is
 * at cross + fixed (+ jitter), cross >= t + the smaller driver skew, never
 * at or before t, never before the previous output (line_dir_input). With
 * jitter any delay down to 1 ps is possible. */
static sim_ps sl_reach(const line_params *p) {
    if (p->jitter_rms_ps > 0.0) {
        return 1;
    }
    sim_ps skew = p->rise_extra_ps < p->fall_extra_ps ? p->rise_extra_ps : p->fall_extra_ps;
    sim_ps d = line_fixed_delay_ps(p) + (skew < 0 ? skew : 0);
    return d > 1 ? d : 1;
}

void link_set_observer(link_model *l, link_pin_fn fn, void *ctx) {
    l->observer = fn;
    l->observer_ctx = ctx;
    l->observer_pins = fn ? 0xfu : 0;
}

void link_observe_pins(link_model *l, unsigned mask) {
    l->observer_pins = l->observer ? mask & 0xfu : 0;
}

waveform *link_pin_record(link_model *l, link_pin pin) {
    waveform *w[4] = {&l->ma_master, &l->sl_master, &l->ma_slave, &l->sl_slave};
    return w[pin];
}

void link_keep_history(link_model *l, unsigned mask) {
    l->history_pins = mask & 0xfu;
    for (int i = 0; i < 4; i++) {
        if (!(l->history_pins & 1u << i)) {
            /* its last level, no edges */
            waveform_forget_before(link_pin_record(l, (link_pin)i), SIM_NEVER);
        }
    }
}

int link_init(link_model *l, const scenario *sc, char *err, size_t errlen) {
    if (scenario_check(sc, err, errlen)) {
        return -1;
    }
    memset(l, 0, sizeof *l);
    l->slave = &l->own.status; /* zeroed with the rest */
    l->sc = *sc;
    l->model = sc->model;
    l->biss_quick = sc->model == &slave_model_biss;
    eq_init(&l->q);
    waveform_init(&l->ma_master, 1);
    waveform_init(&l->ma_slave, 1);
    waveform_init(&l->sl_slave, 1);
    waveform_init(&l->sl_master, 1);
    waveform_init(&l->sl_model, 1);
    l->ext_first_differ = SIM_NEVER;
    l->history_pins = 0xfu;
    l->sl_reach_ps = sl_reach(&l->sc.sl_line);
    l->sl_reach_on = 1;
    sim_edge_sink to_slave = {at_ma_slave, l};
    sim_edge_sink from_slave = {at_sl_slave, l};
    line_dir_init(&l->ma_line, &l->sc.ma_line, &l->q, sim_rng_derive(sc->seed, 1), 1, to_slave);
    line_dir_init(&l->sl_line, &l->sc.sl_line, &l->q, sim_rng_derive(sc->seed, 2), 1,
                  (sim_edge_sink){at_sl_master, l});
    l->model->init(l->slave, link_model_cfg(l), &l->q, from_slave);
    return 0;
}

void link_free(link_model *l) {
    l->slave = NULL;
    waveform_free(&l->ma_master);
    waveform_free(&l->ma_slave);
    waveform_free(&l->sl_slave);
    waveform_free(&l->sl_master);
    waveform_free(&l->sl_model);
    eq_free(&l->q);
}

/* Runs the queue up to t; never backwards, since the queue may already be
 * ahead of a read (the read then finds its answer in the record). */
static void advance(link_model *l, sim_ps t) {
    if (t > eq_now(&l->q)) {
        eq_run_until(&l->q, t);
    }
}

/* Taking the held MA edge ahead (ma-ahead: when it is driven at t, not when
 * it reaches the slave at held_out) changes nothing where the only events
 * before its arrival are the SL side's (the slave's outputs and the SL
 * line's, which touch neither the slave nor the MA line, and draw no
 * random numbers without noise: ahead_applies()) and the slave's timeout
 * moving on (on_timeout() before it is due), and nothing looks at the
 * slave before it arrives. The line's part: no MA edge before it is still
 * on its way in the queue; the line cannot swallow it (the next input
 * comes ahead_gap later at the soonest, with the smaller driver skew, past
 * its crossing); its output is the edge itself (no glitch, no fault). */
static bool ahead_line_ok(const link_model *l, sim_ps t) {
    const line_dir *m = &l->ma_line;
    sim_ps skew = m->p.rise_extra_ps < m->p.fall_extra_ps ? m->p.rise_extra_ps : m->p.fall_extra_ps;
    sim_ps next_in = t + l->ahead_gap + (skew < 0 ? skew : 0);
    return l->ma_queued <= t && m->pending_cross <= next_in && m->cur_level != m->held_level &&
           !m->glitching && m->fault == LINE_OK;
}

/* The rest: the caller does not look at the link before the arrival
 * (ahead_until), the pin observer has no other pin to see (no VCD, no
 * capture), the frame stays open until the arrival (its timeout due
 * later); the timeout the edge restarts, at least the least one, lies
 * beyond every edge driven before the arrival (ahead_applies()), so the
 * order the slave takes for it now is the one it would take then. The
 * slave's quick step decides the rest (taken, or refused having changed
 * nothing). */
static bool ahead_ok(const link_model *l, sim_ps t) {
    const biss_slave *b = (const biss_slave *)l->slave;
    sim_ps out = l->ma_line.held_out;
    return out <= l->ahead_until && l->observer_pins == 1u << LINK_MA_SLAVE && b->st.in_frame &&
           b->timeout_due > out && ahead_line_ok(l, t);
}

/* The MA line's held output: taken by the slave now, or scheduled. */
static __attribute__((noinline)) void ma_held(link_model *l, sim_ps t) {
    line_dir *m = &l->ma_line;
    if (l->ahead_on && ahead_ok(l, t) &&
        biss_slave_ma_edge_quick((biss_slave *)l->slave, m->held_out, m->held_level)) {
        line_dir_take_held(m);
        l->ahead_last = m->held_out;
        record(l, LINK_MA_SLAVE, &l->ma_slave, m->held_out, m->held_level);
        if (l->batch_n < l->batch_max) { /* counted for the observer (link_batch_ahead) */
            if (l->batch_n++ == 0) {
                l->batch_frame = link_frames(l);
                l->batch_level = m->held_level;
            }
            return;
        }
        observe(l, LINK_MA_SLAVE, m->held_out, m->held_level);
        return;
    }
    l->ma_queued = m->held_out;
    line_dir_schedule_held(m);
}

void link_ma(link_model *l, sim_ps t, int level) {
    advance(l, t);
    if (waveform_last_level(&l->ma_master) == level) {
        return;
    }
    record(l, LINK_MA_MASTER, &l->ma_master, t, level);
    observe(l, LINK_MA_MASTER, t, level);
    line_dir_input(&l->ma_line, t, level);
    if (l->ma_line.held) {
        ma_held(l, t);
    }
}

int link_sl(link_model *l, sim_ps t) {
    advance(l, t);
    return waveform_level_at(&l->sl_master, t);
}

/* min(bound, link_next_sl_change(l)): the scan stops at the first pending
 * event no sooner than bound (events are in time order, and an event's
 * own bound is no sooner than its time), so a change already recorded
 * before the next event spares it. */
static sim_ps sl_change_before(const link_model *l, sim_ps bound) {
    if (!l->sl_reach_on) {
        sim_ps t = eq_next_time(&l->q);
        return t < bound ? t : bound;
    }
    sim_ps first = bound;
    for (size_t i = l->q.head; i < l->q.len && l->q.ev[i].t < first; i++) {
        const eq_event *e = &l->q.ev[i];
        sim_ps t = e->ctx == &l->sl_line || e->t > SIM_NEVER - l->sl_reach_ps
                       ? e->t
                       : e->t + l->sl_reach_ps;
        if (t < first) {
            first = t;
        }
    }
    return first;
}

int link_sl_run(link_model *l, sim_ps t, sim_ps *next) {
    advance(l, t);
    sim_ps recorded;
    int level = waveform_level_next(&l->sl_master, t, &recorded);
    *next = sl_change_before(l, recorded);
    return level;
}

sim_ps link_next_change(const link_model *l) {
    return eq_next_time(&l->q);
}

void link_set_line_settled(link_model *l, int on) {
    line_dir_set_settled_fast(&l->ma_line, on);
    line_dir_set_settled_fast(&l->sl_line, on);
}

void link_set_slave_quick(link_model *l, int on) {
    biss_slave *b = link_biss(l);
    if (b) {
        biss_slave_set_quick(b, on != 0);
    }
}

/* The MA line's longest delay from input to output: the fixed delays, the
 * larger driver skew, the low-pass crossing (at most tau ln 2: the filter
 * starts no further than the old level), a picosecond of rounding and one
 * of the line's "strictly after" rule. */
static sim_ps ma_delay_max(const line_params *p) {
    sim_ps skew = p->rise_extra_ps > p->fall_extra_ps ? p->rise_extra_ps : p->fall_extra_ps;
    return line_fixed_delay_ps(p) + (skew > 0 ? skew : 0) +
           (sim_ps)ceil(line_tau_ps(p) * log(2.0)) + 2;
}

/* Whether the scenario lets MA edges be taken ahead: a BiSS-C slave of its
 * own (not an external one), both lines without noise and faults, and its
 * least timeout longer than the MA line's delay (ahead_ok()). */
static bool ahead_applies(const link_model *l) {
    const line_params *ma = &l->sc.ma_line, *sl = &l->sc.sl_line;
    if (l->model != &slave_model_biss || l->external) {
        return false;
    }
    bool quiet = ma->jitter_rms_ps <= 0.0 && ma->glitch_rate_hz <= 0.0 && ma->fault == LINE_OK &&
                 sl->jitter_rms_ps <= 0.0 && sl->glitch_rate_hz <= 0.0 && sl->fault == LINE_OK;
    return quiet && biss_chain_least_timeout_ps(link_model_cfg(l)) > ma_delay_max(ma);
}

void link_set_ma_ahead(link_model *l, int on, sim_ps gap_ps) {
    l->ahead_on = on && ahead_applies(l);
    l->ahead_gap = gap_ps;
    line_dir_set_hold(&l->ma_line, l->ahead_on);
}

void link_set_sl_reach(link_model *l, int on) {
    l->sl_reach_on = on;
}

sim_ps link_next_sl_change(const link_model *l) {
    /* pending events are a handful: a scan, not a second queue */
    return sl_change_before(l, SIM_NEVER);
}

void link_set_external_slave(link_model *l, int on) {
    l->external = on && l->model == &slave_model_biss;
    if (l->external) {
        link_set_ma_ahead(l, 0, 0);
    }
    l->ma_line.out = (sim_edge_sink){l->external ? at_ma_slave_external : at_ma_slave, l};
    if (l->external) {
        l->history_pins |= 1u << LINK_MA_SLAVE;
    }
}

int link_ma_at_slave(link_model *l, sim_ps t, sim_ps *next) {
    advance(l, t);
    sim_ps recorded;
    int level = waveform_level_next(&l->ma_slave, t, &recorded);
    sim_ps pending = eq_next_time(&l->q);
    *next = recorded < pending ? recorded : pending;
    return level;
}

void link_sl_at_slave(link_model *l, sim_ps t, int level) {
    if (waveform_last_level(&l->sl_slave) == level) {
        return;
    }
    record(l, LINK_SL_SLAVE, &l->sl_slave, t, level);
    line_dir_input(&l->sl_line, t, level);
    observe(l, LINK_SL_SLAVE, t, level);
}

void link_forget_pins_before(link_model *l, unsigned mask, sim_ps t) {
    for (int i = 0; i < 4; i++) {
        if (mask & 1u << i) {
            waveform_forget_before(link_pin_record(l, (link_pin)i), t);
        }
    }
}

void link_forget_before(link_model *l, sim_ps t) {
    link_forget_pins_before(l, 0xfu, t);
}

sim_ps link_frame_end(const link_model *l, uint64_t n) {
    const void *r = n < link_frames(l) ? link_record(l, n) : NULL;
    return r ? l->model->end(r) : -1;
}

biss_slave *link_biss(link_model *l) {
    return l->model == &slave_model_biss ? (biss_slave *)l->slave : NULL;
}

ssi_slave *link_ssi(link_model *l) {
    return l->model == &slave_model_ssi ? (ssi_slave *)l->slave : NULL;
}
