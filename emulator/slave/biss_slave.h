/* A BiSS-C slave, or a daisy chain of up to 8, as seen from the MA/SL pins.
 *
 * Feed it MA edges as they arrive at the slave (biss_slave_ma_edge, or wire
 * biss_slave_sink() behind the MA line); it schedules SL edges on the event
 * queue, each out_delay after the MA edge that caused it, and sends them to
 * its output sink (normally the SL line).
 *
 * One frame, from the slave's side:
 *   idle       SL high
 *   MA falls   (while idle) the frame starts
 *   1st rise   every slave latches its position at this instant and builds
 *              its single-cycle data ([MB4] "BiSS C Frame": the sensors
 *              start calculating with the first rising edge)
 *   2nd rise   SL low: ACK
 *   busy       SL stays low on further rising edges until both busy_clocks
 *              extra clocks have passed and busy_ps has elapsed since the ACK
 *   next rise  start bit (1), then CDS (OR of the chain's CDS bits), then
 *              each slave's data, nearest the master first: position MSB
 *              first, fill zeros, nE, nW (active low), life counter, CRC
 *              (inverted, MSB first; over everything from the position on)
 *   then       0 on every further rising edge (the last slave's input is low)
 *   timeout    once MA has not moved for the timeout, the slave samples MA:
 *              CDM = NOT MA at that instant; SL goes high (out_delay later)
 *              and the frame record is closed. Fixed: timeout_ps. Adaptive:
 *              adaptive_factor x the MA period (last two rising edges; twice
 *              the last edge gap before that), clamped to [min, max].
 * A frame whose timeout comes before the ACK passes no CDM. */
#ifndef BISS_SLAVE_H
#define BISS_SLAVE_H

#include "biss_ctrl.h"
#include "event_queue.h"
#include "regfile.h"
#include "sim_time.h"
#include "slave_status.h"

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#define BISS_MAX_SLAVES     8
#define BISS_MAX_FRAME_BITS 2048
#define BISS_RECORD_RING    256

/* An injected life-counter fault (for the master's safety checks). */
typedef enum {
    BISS_LC_FAULT_NONE,
    BISS_LC_FAULT_FROZEN, /* the counter stops: frame N sends frame N-1's value, and on */
    BISS_LC_FAULT_SKIP,   /* the counter advances by 2 per frame from frame N on */
} biss_lc_fault;

typedef struct {
    uint8_t id;             /* control-frame ID, 0..7 */
    unsigned pos_bits;      /* 1..64: position / data word (MT+ST, A/D, ...) */
    unsigned fill_bits;     /* zeros after the position */
    bool has_err, has_warn; /* nE, nW bits present */
    unsigned lc_bits;       /* life counter after nE/nW, 0..32 */
    uint32_t crc_poly;      /* with its top term; 0 = no CRC */
    uint32_t crc_start;
    uint64_t pos0;            /* position at time 0 */
    double speed_cps;         /* counts per second, may be negative */
    int64_t counts_per_frame; /* added at every latch (first rising edge) after the
                                 first, may be negative: the motion of an encoder
                                 simulator (pru_slave/), whose positions step with the
                                 frames, not with time */
    bool error, warning;      /* drive nE / nW low (active) */
    unsigned reg_proc_frames; /* late S in register access */
    uint8_t cmd_exec;         /* the bit after IDA that executes a command (biss_ctrl cmd_stop) */
    bool idl_at_cts;          /* ID lock IDL0 answers CTS, not S (biss_ctrl idl_at_cts) */
    bool no_control;          /* a data channel only: its device's control
                                 communication is another chain slave's
                                 (same ID); it never answers a CDM */
    regfile regs;
    /* Faults injected from a frame on (frames count from 1, as biss-sim
     * and bissctl count them: 1 is the first frame the slave sees). */
    biss_lc_fault lc_fault;
    unsigned lc_fault_frame;
    uint64_t pos_fault_offset; /* added to the position sent (mod 2^pos_bits) ... */
    unsigned pos_fault_frame;  /* ... from this frame on */
} biss_slave_cfg;

typedef enum { BISS_TIMEOUT_FIXED, BISS_TIMEOUT_ADAPTIVE } biss_timeout_mode;

typedef struct {
    unsigned n;          /* slaves in the chain, 1..8 */
    sim_ps out_delay_ps; /* MA edge at the slave to SL edge, default 20 ns */
    sim_ps busy_ps;      /* processing time after the ACK edge */
    unsigned busy_clocks;
    biss_timeout_mode timeout_mode;
    sim_ps timeout_ps;      /* fixed timeout, default 20 us */
    double adaptive_factor; /* default 1.5 */
    sim_ps adaptive_min_ps, adaptive_max_ps;
    /* last: 5 KB each, while the models read the fields above on every
     * MA edge (they then share a few cache lines) */
    biss_slave_cfg s[BISS_MAX_SLAVES];
} biss_chain_cfg;

/* One slave with defaults: 12-bit position, nE nW, CRC6 0x43. */
void biss_slave_cfg_default(biss_slave_cfg *s, uint8_t id);
/* A chain of one default slave and default timing. */
void biss_chain_cfg_default(biss_chain_cfg *c);
/* Bits a slave puts on the wire per frame (position .. CRC). */
unsigned biss_slave_cfg_bits(const biss_slave_cfg *s);
/* Its data word before the CRC: position, fill, nE, nW, life counter. At
 * most 64 (the firmware's BISS_MAX_DATA_BITS; the bench checks the word
 * as one uint64_t). */
unsigned biss_slave_cfg_data_bits(const biss_slave_cfg *s);
/* Whether two slaves of the chain that answer control communication (not
 * no_control) share an id (then *first < *second). */
int biss_chain_shared_id(const biss_chain_cfg *c, unsigned *first, unsigned *second);
/* The timeout the chain's slaves apply while MA runs with period_ps: the
 * fixed one, or the adaptive factor x the period, clamped to [min, max]. */
sim_ps biss_chain_timeout_ps(const biss_chain_cfg *c, sim_ps period_ps);
/* The least timeout biss_chain_timeout_ps() gives for any period: an MA
 * edge at the slave changes SL no sooner than this (the timeout it
 * restarts) plus out_delay_ps later, unless it is a rising edge that sends
 * a bit. */
sim_ps biss_chain_least_timeout_ps(const biss_chain_cfg *c);
/* Checks a configuration against its tables (biss_model.c): every range
 * and relation. Returns 0, or -1 with a message naming the field
 * ("slaves[0].crc_poly: ...") in err. */
int biss_chain_cfg_check(const biss_chain_cfg *c, char *err, size_t errlen);

/* What one slave sent in one frame. */
typedef struct {
    uint64_t position;
    int nE, nW;    /* as sent: 1 = no error / no warning; -1 if absent */
    uint32_t lc;   /* life counter */
    uint32_t crc;  /* as sent (inverted) */
    uint64_t fill; /* always 0 */
} biss_slave_sent;

typedef struct {
    uint64_t frame; /* 0, 1, ... */
    sim_ps start_ps, ack_ps, start_bit_ps, end_ps;
    sim_ps latch_ps;    /* first rising edge: the position's instant (0: none) */
    sim_ps last_bit_ps; /* the rise that put the frame's last bit on SL: the last
                           slave's last CRC bit (0: not clocked out) */
    int cds;            /* CDS sent in this frame */
    int cdm;            /* CDM sampled at its timeout, -1 if none */
    bool acked;         /* at least two rising edges */
    bool started;       /* start bit sent */
    bool complete;      /* every data bit was clocked out */
    unsigned clocks;    /* rising edges seen */
    biss_slave_sent s[BISS_MAX_SLAVES];
} biss_frame_record;

typedef void (*biss_frame_fn)(void *ctx, const biss_frame_record *rec);

/* What every MA edge touches comes first, the large arrays and the
 * per-slave configuration last, so the edge's fields share cache lines
 * and pages. */
typedef struct {
    slave_status st; /* closed frames; in a frame (from its first MA edge to its timeout) */
    event_queue *q;
    sim_edge_sink out;

    int ma;
    sim_ps last_edge, prev_edge, last_rise, prev_rise;
    unsigned rises;
    bool started;
    unsigned bit, nbits;
    int sl_sched;            /* SL level after the last scheduled change */
    eq_id timeout_ev;        /* the pending timeout event, 0 none */
    sim_ps timeout_ev_at;    /* ... its time */
    sim_ps timeout_due;      /* when the timeout is due: at or after timeout_ev_at */
    eq_id timeout_due_order; /* ... the event's place among events at that time */
    bool quick;              /* the quick step on (biss_slave_set_quick), default on */
    sim_ps memo_period;      /* the quick step's adaptive timeout: the last period */
    sim_ps memo_timeout;     /* ... and its timeout (biss_chain_timeout_ps), -1 none */
    int cds;                 /* CDS for the next frame */
    bool lost;               /* SL held low since lost_at (biss_slave_lose_sync) */
    sim_ps lost_at;

    uint64_t latches; /* frames whose data were latched (a first rising edge) */
    biss_frame_fn on_frame;
    void *on_frame_ctx;
    biss_frame_record cur;
    uint8_t bits[BISS_MAX_FRAME_BITS];

    biss_chain_cfg cfg;
    biss_ctrl ctrl[BISS_MAX_SLAVES];
    uint32_t lc[BISS_MAX_SLAVES];
    biss_frame_record ring[BISS_RECORD_RING];
} biss_slave;

/* cfg must pass biss_chain_cfg_check. The chain starts idle (SL high, MA
 * assumed high) at eq_now(q). The slave keeps its own copy of cfg. */
void biss_slave_init(biss_slave *b, const biss_chain_cfg *cfg, event_queue *q, sim_edge_sink out);

void biss_slave_ma_edge(biss_slave *b, sim_ps t, int level);
/* biss_slave_ma_edge() for an edge of a frame but its first rise (the
 * timeout's event pending no later than the new deadline, room in the
 * queue): the same steps with no call, so a caller that has its own calls
 * in tail position only saves no registers. Returns false, having changed
 * nothing, for any other edge. */
bool biss_slave_ma_edge_quick(biss_slave *b, sim_ps t, int level);
/* The quick step on (default) or off: off, every edge takes the general
 * step (the same results, slower: the fast path "slave-quick"). */
void biss_slave_set_quick(biss_slave *b, bool on);
/* biss_slave_ma_edge() without trying the quick step first: any edge. */
void biss_slave_ma_edge_general(biss_slave *b, sim_ps t, int level);
sim_edge_sink biss_slave_sink(biss_slave *b);

/* Called with each closed frame record. */
void biss_slave_on_frame(biss_slave *b, biss_frame_fn fn, void *ctx);

/* Record of closed frame n, if still in the ring; NULL otherwise. */
const biss_frame_record *biss_slave_record(const biss_slave *b, uint64_t n);

/* Position slave i would latch at time t (its counts_per_frame motion as of
 * the next latch included). */
uint64_t biss_slave_position_at(const biss_slave *b, unsigned i, sim_ps t);

/* The last slave loses its frame (a disconnect, a broken frame): SL goes
 * low at t and stays low, whatever MA does, until a frame that starts after
 * t has timed out ([MB4] "BiSS C Initialization Sequence": "After power-on
 * or after a failure the last slave may not be defined and the SLx line is
 * digital low"; an INIT, two MA pulses, brings it back). */
void biss_slave_lose_sync(biss_slave *b, sim_ps t);

/* Runtime switches. */
void biss_slave_set_status(biss_slave *b, unsigned i, bool error, bool warning);

#endif
