/* One direction of the cable: driver, twisted pair, receiver.
 *
 * Input edges (the logic level at the driver input) arrive in time order at
 * their own time; output edges (the receiver output) are delivered to a sink
 * through the event queue at the time they happen. The chain of effects:
 *
 *   driver skew      rising edges are delayed by rise_extra, falling by
 *                    fall_extra (driver tPLH vs tPHL), so pulse widths change
 *   bandwidth        a first-order low-pass with time constant
 *                    tau = tau0 + tau_per_m2 * length^2; the receiver switches
 *                    where the filtered signal crosses half swing. The crossing
 *                    time is solved in closed form from the filter state left
 *                    by earlier edges, so a pulse shorter than about
 *                    tau * ln 2 after a long run vanishes, longer ones shrink
 *   propagation      length * ps_per_m
 *   transceivers     driver_delay + receiver_delay
 *   jitter           Gaussian, per output edge (edges never reorder)
 *   glitches         Poisson-timed inversions of the receiver output
 *   faults           stuck low, stuck high, or open (an RS-485 receiver with
 *                    open-bus fail-safe then reads high), from a given time
 *
 * Every output happens strictly after the input that caused it. */
#ifndef LINE_MODEL_H
#define LINE_MODEL_H

#include "event_queue.h"
#include "sim_rng.h"
#include "sim_time.h"

typedef enum {
    LINE_OK = 0,
    LINE_STUCK_LOW,
    LINE_STUCK_HIGH,
    LINE_OPEN, /* receiver fail-safe: reads high */
} line_fault;

typedef struct {
    double length_m;
    double ps_per_m;          /* propagation, default 5000 (5 ns/m) */
    sim_ps driver_delay_ps;   /* default 9 ns */
    sim_ps receiver_delay_ps; /* default 15 ns */
    sim_ps rise_extra_ps;     /* added to rising edges, default 0 */
    sim_ps fall_extra_ps;     /* added to falling edges, default 1 ns */
    double tau0_ps;           /* low-pass time constant at 0 m, default 0 */
    double tau_per_m2_ps;     /* growth with length squared, default 20 ps/m^2 */
    double jitter_rms_ps;     /* default 0 */
    double glitch_rate_hz;    /* mean glitches per second, default 0 */
    sim_ps glitch_width_ps;   /* default 20 ns */
    line_fault fault;         /* applied from fault_at_ps; default LINE_OK */
    sim_ps fault_at_ps;
    sim_ps fault_until_ps; /* the fault ends then (reconnected); 0: it never ends */
} line_params;

void line_params_default(line_params *p);

/* Propagation plus transceiver delays, in ps: what every edge takes at
 * least beyond the low-pass crossing and the driver skew. */
sim_ps line_fixed_delay_ps(const line_params *p);

/* Low-pass time constant for these parameters, in ps. */
double line_tau_ps(const line_params *p);

/* Delay of an isolated edge after a long steady level: transceivers,
 * cable, the low-pass threshold delay tau*ln2 and the mean of the rise and
 * fall skews. What a master measures as the one-way line delay. */
double line_nominal_delay_ps(const line_params *p);

typedef struct {
    line_params p;
    event_queue *q;
    sim_rng rng;
    sim_edge_sink out;
    double tau;   /* ps */
    sim_ps fixed; /* propagation + transceivers, ps */

    /* low-pass state: value v0 at time t0, heading for target */
    double v0;
    sim_ps t0;
    int target;
    int in_level;   /* last input level */
    sim_ps last_in; /* time of the last effective input edge */

    /* The last exp() and crossing, per edge direction (index: the new
     * level): a clocked line sees the same gap and the same filter value
     * edge after edge, and the same argument gives the same result, so a
     * hit is exact. memo_dt < 0 / memo_ratio 0: empty. */
    sim_ps memo_dt[2];
    double memo_exp[2];
    double memo_ratio[2];
    sim_ps memo_cross[2];

    /* The fast path "line-settled": from settle_gap after the last input
     * edge on, exp(-gap/tau) < 2^-54, so the filter value is its target's
     * level to the last bit (1.0; 0.0 where the arithmetic leaves a value
     * below 2^-54 that no later step can tell from 0: it only ever enters
     * as v - 1 = -1) and a crossing is settled_cross, the one for ratio 2.
     * SIM_NEVER: off (or no low-pass). settled_steps counts its uses. */
    sim_ps settle_gap;
    sim_ps settled_cross;
    unsigned long settled_steps;

    /* Held outputs (line_dir_set_hold, for the fast path "ma-ahead"): an
     * edge's output is not scheduled but held for the line's owner, under
     * the id the queue would have given it, to be scheduled
     * (line_dir_schedule_held) or taken by the sink at once
     * (line_dir_take_held) before the next input. */
    int hold;
    int held;
    int held_level;
    sim_ps held_out;
    eq_id held_id;

    int filt_level; /* receiver decision after the last committed crossing */
    int pending;    /* a crossing is computed but may still be cancelled */
    sim_ps pending_cross;
    sim_ps pending_out;
    eq_id pending_ev;
    sim_ps last_out; /* output time of the last committed edge: later ones must follow */

    int true_level; /* receiver output without glitches and faults */
    int cur_level;  /* what the sink was last told */
    int glitching;
    line_fault fault;

    unsigned long edges_in, edges_out, glitches, vanished;
} line_dir;

/* Starts the line at the idle level at time eq_now(q). Schedules the first
 * glitch and the configured fault, if any. The sink receives the output. */
void line_dir_init(line_dir *l, const line_params *p, event_queue *q, uint64_t seed, int idle_level,
                   sim_edge_sink out);

/* An input edge at time t (>= the previous one, and the queue must not be
 * past t). Repeated levels are ignored. */
void line_dir_input(line_dir *l, sim_ps t, int level);

/* Switches the fast path "line-settled" on (the default) or off: the
 * results are the same either way, only the filter arithmetic is spared. */
void line_dir_set_settled_fast(line_dir *l, int on);

/* Holds every output edge for the owner (on) instead of scheduling it
 * (off, the default). After each line_dir_input() that leaves one held
 * (l->held), the owner schedules it or lets its sink take it. */
void line_dir_set_hold(line_dir *l, int on);
/* Schedules the held output as line_dir_input() would have (the same id,
 * so the same order among events of its time). */
void line_dir_schedule_held(line_dir *l);
/* The sink took the held output at its time (held_out, held_level): the
 * line's output state moves on as its output event would move it. For a
 * line without glitches and faults only (what the sink is told is then
 * the output edge itself). */
void line_dir_take_held(line_dir *l);

/* Switches the fault state at time t (LINE_OK reconnects). */
void line_dir_set_fault(line_dir *l, sim_ps t, line_fault f);

/* Whether MA clocks with half period half_ps get through this line in
 * shape: a burst after a long idle keeps every pulse, each within a quarter
 * of its width (what an 8x-oversampling master tolerates with margin).
 * Noise (jitter, glitches) and faults are left out. */
int line_usable(const line_params *p, sim_ps half_ps);

/* A sink that feeds this line's input, for wiring it behind a model. */
sim_edge_sink line_dir_sink(line_dir *l);

#endif
