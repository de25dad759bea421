/* The far end of a BiSS/SSI link, ready for the bench: MA line, slave
 * model(s), SL line, and waveform records of the four pins, all on one
 * event queue, built from a scenario.
 *
 *   master MA pin --ma_line--> slave MA pin -> slave model -> slave SL pin
 *   master SL pin <--sl_line--------------------------------'
 *
 * Protocol with the PRU core (discrete-event, exact because every effect
 * comes strictly after its cause):
 *   - each MA pin change at the master: link_ma(l, t, level), in time order;
 *   - before the core reads SL at time T: link_sl(l, T) (advances every model
 *     to T, then returns the SL level at the master at T; T may lie a little
 *     before the latest MA change, whose effects are all later);
 *   - to fast-forward idle polling: nothing at the master can change before
 *     link_next_change(l) unless MA moves first. */
#ifndef LINK_MODEL_H
#define LINK_MODEL_H

#include "biss_slave.h"
#include "event_queue.h"
#include "line_model.h"
#include "scenario.h"
#include "slave_model.h"
#include "ssi_slave.h"
#include "waveform.h"

/* The four pins, in the order the bench writes them to VCD. */
typedef enum { LINK_MA_MASTER, LINK_SL_MASTER, LINK_MA_SLAVE, LINK_SL_SLAVE } link_pin;

/* Told of every level change on a pin, after the models have taken it. */
typedef void (*link_pin_fn)(void *ctx, link_pin pin, sim_ps t, int level);

/* The models' state that every MA edge touches first, the scenario (40 KB)
 * last, so the edge's fields share cache lines and pages. */
typedef struct {
    link_pin_fn observer;
    void *observer_ctx;
    unsigned observer_pins; /* bit (1 << link_pin): the pins it is told of */
    unsigned history_pins;  /* bit (1 << link_pin): the pins whose records keep their edges */
    event_queue q;
    waveform ma_master, ma_slave, sl_slave, sl_master;
    /* link_next_sl_change(): the least time from an input edge of the SL
     * line to its output (sl_reach_ps), and whether to use it (the fast
     * path "sl-reach"; off: every pending event counts as a change) */
    sim_ps sl_reach_ps;
    int sl_reach_on;
    /* The fast path "ma-ahead" (link_set_ma_ahead): a BiSS-C frame's clock
     * edge taken by the slave when the master drives it. ahead_on: on and
     * applicable to the scenario; ahead_until: no edge reaching the slave
     * later is taken ahead (the caller's run end); ahead_gap: the least
     * time between two MA edges at the master; ma_delay_max: the MA line's
     * longest delay; ahead_last: the latest arrival taken ahead (0 none);
     * ma_queued: the latest arrival of an MA edge left to the queue. */
    bool ahead_on;
    sim_ps ahead_until, ahead_gap, ma_delay_max, ahead_last, ma_queued;
    /* The edges taken ahead told to the observer in a batch
     * (link_batch_ahead()): at most batch_max at a time; batch_n of them
     * since it last took them, all of the open frame batch_frame, the
     * first at level batch_level, the next ones alternating. */
    uint64_t batch_max, batch_n, batch_frame;
    int batch_level;
    const slave_model *model; /* sc.model, here with the rest */
    slave_status *slave;      /* the model's state (its first member): &own.status */
    /* the BiSS-C chain's clock edges take its quick step, called directly
     * (link_model.c at_ma_slave): the model the table names is this */
    bool biss_quick;
    line_dir ma_line, sl_line;
    /* An external slave (link_set_external_slave): another core's pins at
     * the slave end; the model then runs beside it on the same MA, its SL
     * kept apart (sl_model) and compared with the external one's at every
     * rising MA edge at the slave pin (the bit both have settled on). */
    int external;
    waveform sl_model;
    uint64_t ext_compared, ext_differ; /* rising edges compared, SL levels that differed */
    sim_ps ext_first_differ;           /* the first of them, SIM_NEVER none */
    /* the model's state in place, beside the lines, as the edges use them
     * together (every model's fits: slave_model_register) */
    slave_state_room own;
    scenario sc;
} link_model;

/* Builds the link at time 0, idle (MA and SL high). The random streams of
 * the two lines derive from the scenario seed. Returns 0, or -1 with a
 * message naming the bad field. Heap-allocate: the struct is large. */
int link_init(link_model *l, const scenario *sc, char *err, size_t errlen);
void link_free(link_model *l);

/* The fast path "line-settled" of both lines (line_dir_set_settled_fast),
 * on by default. */
void link_set_line_settled(link_model *l, int on);

/* Sets (or with NULL clears) the pin observer, told of every pin. */
void link_set_observer(link_model *l, link_pin_fn fn, void *ctx);

/* Tells the observer only of the pins in mask (bit 1 << link_pin): an
 * observer that has nothing to do for a pin for a while spares the call
 * on each of its edges. */
void link_observe_pins(link_model *l, unsigned mask);

/* Keeps the edges of the pins in mask (bit 1 << link_pin) in their records
 * (all four by default); the others' records hold their last level only,
 * as their initial level with no edges. For a user that asks those records
 * for nothing but their level at the queue's time (eq_now) or later: every
 * pin edge is recorded at or before that time (link_ma's t is the queue's
 * time after it has run to t, the others are recorded by the events at
 * theirs), so that level is the last one. Each edge then costs a store
 * instead of an append. */
void link_keep_history(link_model *l, unsigned mask);

/* The record of a pin (level changes up to the queue's time, link_keep_history). */
waveform *link_pin_record(link_model *l, link_pin pin);

void link_ma(link_model *l, sim_ps t, int level);
int link_sl(link_model *l, sim_ps t);

/* link_sl(l, t), and in *next the earliest time after t at which SL at the
 * master may change unless MA changes first: a change already recorded, or
 * link_next_sl_change(l). */
int link_sl_run(link_model *l, sim_ps t, sim_ps *next);

/* Earliest time at which anything pending (an edge in flight, a timeout, a
 * glitch) happens, or SIM_NEVER: SL at the master is constant until then
 * unless MA changes. */
sim_ps link_next_change(const link_model *l);

/* Earliest time at which SL at the master may change, or SIM_NEVER, unless
 * MA changes first: an event of the SL line itself (an output edge, a
 * glitch, a fault) at its time; any other event (an edge on its way to the
 * slave, the slave's output, its timeout) only sl_reach_ps after it, since
 * whatever it sends down the SL line comes out that much later at least.
 * Never earlier than link_next_change(). With sl-reach off (link_set_sl_reach)
 * it is link_next_change(). */
sim_ps link_next_sl_change(const link_model *l);

/* A BiSS-C chain's quick step for clocked edges (biss_slave_set_quick) on
 * (default) or off: the fast path "slave-quick"; other models have none. */
void link_set_slave_quick(link_model *l, int on);

/* The fast path "ma-ahead" on or off (the default): an MA edge the BiSS-C
 * slave takes with its quick step is taken when link_ma() drives it, not
 * when it reaches the slave, where nothing before its arrival depends on
 * it or it on them (link_model.c, ahead_ok()). gap_ps: the least time
 * between two link_ma() edges (a PRU cycle). Call before any edge. The
 * caller bounds the edges taken ahead with link_set_ahead_until() and,
 * should it stop short of an arrival taken ahead (link_ahead_beyond()),
 * must discard the run: the slave took an edge it would not have. */
void link_set_ma_ahead(link_model *l, int on, sim_ps gap_ps);
/* Edges reaching the slave after t are not taken ahead (the run's end: the
 * caller looks at the link between runs). */
static inline void link_set_ahead_until(link_model *l, sim_ps t) {
    l->ahead_until = t;
}
/* Up to max MA edges taken ahead (0: none) are not shown to the observer
 * one by one but counted for it to take (link_take_ahead()), which it
 * must do before it is told of any pin and before it looks at what it
 * made of the edges. They are MA at the slave pin, each after the one
 * before in time and the other level, all inside one open frame; the
 * observer sees no other pin while they are taken (ahead_ok()). */
static inline void link_batch_ahead(link_model *l, uint64_t max) {
    l->batch_max = max;
}
/* The edges counted since the last call: their number, and in *frame the
 * open frame's number (link_frames() when they were taken) and in *level
 * the first one's level. */
static inline uint64_t link_take_ahead(link_model *l, uint64_t *frame, int *level) {
    uint64_t n = l->batch_n;
    l->batch_n = 0;
    *frame = l->batch_frame;
    *level = l->batch_level;
    return n;
}
/* Whether an edge taken ahead reaches the slave after t. */
static inline bool link_ahead_beyond(const link_model *l, sim_ps t) {
    return l->ahead_last > t;
}

/* Switches the fast path "sl-reach" of link_next_sl_change (on by default). */
void link_set_sl_reach(link_model *l, int on);

/* The slave end is another core (the BiSS-C encoder firmware on a PRU):
 * MA at the slave pin is its input (link_ma_at_slave), its SL pin drives
 * the SL line (link_sl_at_slave). The scenario's slave model still takes
 * every MA edge, so the bench numbers and checks frames as usual, but its
 * SL goes only to its own record (sl_model), compared with the external
 * slave's at each rising MA edge at the slave pin: ext_compared,
 * ext_differ. Call before any edge; BiSS-C only. MA at the slave pin then
 * keeps its history (link_keep_history). */
void link_set_external_slave(link_model *l, int on);
/* MA at the slave pin at t (the queue run to t), and in *next the earliest
 * time after t it may change unless MA at the master moves first. */
int link_ma_at_slave(link_model *l, sim_ps t, sim_ps *next);
/* The external slave's SL pin takes level at t (no earlier than anything
 * the queue has run: a core's output after its inputs). */
void link_sl_at_slave(link_model *l, sim_ps t, int level);

/* Drops pin history before t (a long run keeps its memory bounded). */
void link_forget_before(link_model *l, sim_ps t);
/* The same for the pins in mask (bit 1 << link_pin) only. */
void link_forget_pins_before(link_model *l, unsigned mask, sim_ps t);

/* Closed frame records of the slave model. In line: the bench asks on
 * every MA edge. */
static inline uint64_t link_frames(const link_model *l) {
    return l->slave->frames;
}

/* Whether the slave model is inside a frame (from its first MA edge to
 * its timeout). */
static inline bool link_in_frame(const link_model *l) {
    return l->slave->in_frame;
}

/* The model's record of frame n (slave_model record): closed and still
 * kept, or the open one (n == link_frames); NULL otherwise. */
static inline const void *link_record(const link_model *l, uint64_t n) {
    return l->model->record(l->slave, n);
}

/* The end of the model's closed frame n, -1 if not closed or no longer
 * kept. */
sim_ps link_frame_end(const link_model *l, uint64_t n);

/* The configuration of the link's model. */
static inline const void *link_model_cfg(const link_model *l) {
    return scenario_model_cfg(&l->sc);
}

/* The state of the BiSS-C chain model (its control communication, register
 * files, records), NULL if the link has another model. */
biss_slave *link_biss(link_model *l);
/* The same for the SSI model. */
ssi_slave *link_ssi(link_model *l);

#endif
