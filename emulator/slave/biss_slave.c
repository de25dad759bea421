#include "biss_slave.h"

#include "biss_crc.h"
#include "slave_motion.h"

#include <math.h>
#include <string.h>

void biss_slave_cfg_default(biss_slave_cfg *s, uint8_t id) {
    memset(s, 0, sizeof *s);
    s->id = id;
    s->pos_bits = 12;
    s->has_err = s->has_warn = true;
    s->crc_poly = 0x43;
    s->cmd_exec = BISS_CTRL_CMD_EXEC_DEFAULT;
    s->lc_fault_frame = 1;
    s->pos_fault_frame = 1;
    regfile_init(&s->regs, 1);
}

void biss_chain_cfg_default(biss_chain_cfg *c) {
    memset(c, 0, sizeof *c);
    c->n = 1;
    for (unsigned i = 0; i < BISS_MAX_SLAVES; i++) {
        biss_slave_cfg_default(&c->s[i], (uint8_t)i);
    }
    c->out_delay_ps = 20 * SIM_PS_PER_NS;
    c->timeout_mode = BISS_TIMEOUT_FIXED;
    c->timeout_ps = 20 * SIM_PS_PER_US;
    c->adaptive_factor = 1.5;
    c->adaptive_min_ps = 0;
    c->adaptive_max_ps = 20 * SIM_PS_PER_US;
}

unsigned biss_slave_cfg_data_bits(const biss_slave_cfg *s) {
    return s->pos_bits + s->fill_bits + (s->has_err ? 1 : 0) + (s->has_warn ? 1 : 0) + s->lc_bits;
}

unsigned biss_slave_cfg_bits(const biss_slave_cfg *s) {
    return biss_slave_cfg_data_bits(s) + biss_crc_width(s->crc_poly);
}

int biss_chain_shared_id(const biss_chain_cfg *c, unsigned *first, unsigned *second) {
    for (unsigned j = 1; j < c->n && j < BISS_MAX_SLAVES; j++) {
        for (unsigned i = 0; i < j; i++) {
            /* a data-only channel shares its device's id */
            if (c->s[i].id == c->s[j].id && !c->s[i].no_control && !c->s[j].no_control) {
                *first = i;
                *second = j;
                return 1;
            }
        }
    }
    return 0;
}

void biss_slave_init(biss_slave *b, const biss_chain_cfg *cfg, event_queue *q, sim_edge_sink out) {
    memset(b, 0, sizeof *b);
    b->cfg = *cfg;
    b->q = q;
    b->out = out;
    for (unsigned i = 0; i < cfg->n; i++) {
        biss_ctrl_init(&b->ctrl[i], b->cfg.s[i].id, &b->cfg.s[i].regs, b->cfg.s[i].reg_proc_frames);
        b->ctrl[i].cmd_stop = b->cfg.s[i].cmd_exec;
        b->ctrl[i].idl_at_cts = b->cfg.s[i].idl_at_cts;
    }
    b->st.in_frame = false;
    b->ma = 1;
    b->sl_sched = 1;
    b->last_edge = b->prev_edge = b->last_rise = b->prev_rise = eq_now(q);
    b->quick = true;
    b->memo_period = b->memo_timeout = -1;
}

void biss_slave_set_quick(biss_slave *b, bool on) {
    b->quick = on;
}

void biss_slave_on_frame(biss_slave *b, biss_frame_fn fn, void *ctx) {
    b->on_frame = fn;
    b->on_frame_ctx = ctx;
}

const biss_frame_record *biss_slave_record(const biss_slave *b, uint64_t n) {
    if (n >= b->st.frames || b->st.frames - n > BISS_RECORD_RING) {
        return NULL;
    }
    return &b->ring[n % BISS_RECORD_RING];
}

void biss_slave_set_status(biss_slave *b, unsigned i, bool error, bool warning) {
    if (i < b->cfg.n) {
        b->cfg.s[i].error = error;
        b->cfg.s[i].warning = warning;
    }
}

static uint64_t mask_bits(unsigned n) {
    return n >= 64 ? UINT64_MAX : ((UINT64_C(1) << n) - 1);
}

uint64_t biss_slave_position_at(const biss_slave *b, unsigned i, sim_ps t) {
    const biss_slave_cfg *s = &b->cfg.s[i];
    uint64_t stepped = (uint64_t)s->counts_per_frame * b->latches; /* modulo 2^64 */
    return (slave_position_at(s->pos0, s->speed_cps, s->pos_bits, t) + stepped) &
           mask_bits(s->pos_bits);
}

/* ---- SL output ---- */

static void emit_sl(void *ctx, sim_ps t, int64_t level) {
    biss_slave *b = ctx;
    sim_edge_send(&b->out, t, (int)level);
}

/* A slave that lost its frame keeps SL low until a new frame ends. */
static bool held_low(const biss_slave *b) {
    return b->lost && b->cur.start_ps <= b->lost_at;
}

/* Whether driving SL to level changes what is scheduled (a slave that lost
 * sync holds SL low). */
static inline bool sl_moves(const biss_slave *b, int level) {
    return !(level == b->sl_sched || (level && held_low(b)));
}

static void drive_sl(biss_slave *b, sim_ps t_cause, int level) {
    if (!sl_moves(b, level)) {
        return;
    }
    b->sl_sched = level;
    eq_schedule(b->q, t_cause + b->cfg.out_delay_ps, emit_sl, b, level);
}

void biss_slave_lose_sync(biss_slave *b, sim_ps t) {
    b->lost = true;
    b->lost_at = t;
    drive_sl(b, t, 0);
}

/* ---- frame data ---- */

static void push_bits(biss_slave *b, uint64_t v, unsigned n, uint32_t *crc, uint32_t poly) {
    for (unsigned k = n; k > 0; k--) {
        int bit = (int)((v >> (k - 1)) & 1u);
        if (b->nbits < BISS_MAX_FRAME_BITS) {
            b->bits[b->nbits++] = (uint8_t)bit;
        }
        if (crc) {
            *crc = biss_crc_bit(*crc, poly, bit);
        }
    }
}

/* How far the life counter moves from frame n - 1 to frame n (n from 1):
 * one, or what an injected fault makes of it. */
static uint32_t lc_step(const biss_slave_cfg *s, uint64_t n) {
    if (s->lc_fault == BISS_LC_FAULT_NONE || n < s->lc_fault_frame) {
        return 1;
    }
    return s->lc_fault == BISS_LC_FAULT_FROZEN ? 0 : 2;
}

/* The position as sent: the sensor's, or off by the injected fault (one
 * channel of a two-channel encoder disagreeing with the other). */
static uint64_t sent_position(const biss_slave *b, unsigned i, sim_ps t) {
    const biss_slave_cfg *s = &b->cfg.s[i];
    uint64_t p = biss_slave_position_at(b, i, t);
    if (s->pos_fault_offset && b->cur.frame + 1 >= s->pos_fault_frame) {
        p = (p + s->pos_fault_offset) & mask_bits(s->pos_bits);
    }
    return p;
}

static void build_slave_data(biss_slave *b, unsigned i, sim_ps t) {
    const biss_slave_cfg *s = &b->cfg.s[i];
    biss_slave_sent *rec = &b->cur.s[i];
    uint32_t crc = s->crc_start;
    rec->position = sent_position(b, i, t);
    push_bits(b, rec->position, s->pos_bits, &crc, s->crc_poly);
    push_bits(b, 0, s->fill_bits, &crc, s->crc_poly);
    rec->nE = s->has_err ? !s->error : -1;
    rec->nW = s->has_warn ? !s->warning : -1;
    if (s->has_err) {
        push_bits(b, (uint64_t)rec->nE, 1, &crc, s->crc_poly);
    }
    if (s->has_warn) {
        push_bits(b, (uint64_t)rec->nW, 1, &crc, s->crc_poly);
    }
    rec->lc = (uint32_t)(b->lc[i] & mask_bits(s->lc_bits));
    push_bits(b, rec->lc, s->lc_bits, &crc, s->crc_poly);
    b->lc[i] += lc_step(s, b->cur.frame + 2); /* the value of the next frame */
    unsigned w = biss_crc_width(s->crc_poly);
    rec->crc = (uint32_t)(~crc & mask_bits(w));
    push_bits(b, rec->crc, w, NULL, 0);
}

static void start_frame(biss_slave *b, sim_ps t) {
    memset(&b->cur, 0, sizeof b->cur);
    b->cur.frame = b->st.frames;
    b->cur.start_ps = t;
    b->cur.cdm = -1;
    b->cur.cds = b->cds;
    b->nbits = 0;
    b->bit = 0;
    push_bits(b, (uint64_t)b->cds, 1, NULL, 0);
    b->rises = 0;
    b->started = false;
    b->st.in_frame = true;
}

/* ---- timeout ---- */

sim_ps biss_chain_timeout_ps(const biss_chain_cfg *c, sim_ps period_ps) {
    if (c->timeout_mode == BISS_TIMEOUT_FIXED) {
        return c->timeout_ps;
    }
    sim_ps t = (sim_ps)llround(c->adaptive_factor * (double)period_ps);
    if (t < c->adaptive_min_ps) {
        t = c->adaptive_min_ps;
    }
    if (t > c->adaptive_max_ps) {
        t = c->adaptive_max_ps;
    }
    return t > 0 ? t : 1;
}

sim_ps biss_chain_least_timeout_ps(const biss_chain_cfg *c) {
    if (c->timeout_mode == BISS_TIMEOUT_FIXED) {
        return c->timeout_ps;
    }
    /* clamped to [min, max] in that order, then at least 1 */
    sim_ps lo = c->adaptive_min_ps < c->adaptive_max_ps ? c->adaptive_min_ps : c->adaptive_max_ps;
    return lo > 1 ? lo : 1;
}

static sim_ps timeout_len(const biss_slave *b) {
    const biss_chain_cfg *c = &b->cfg;
    sim_ps period = c->adaptive_max_ps;
    if (b->rises >= 2) {
        period = b->last_rise - b->prev_rise;
    } else if (b->last_edge != b->prev_edge) {
        period = 2 * (b->last_edge - b->prev_edge);
    }
    return biss_chain_timeout_ps(c, period);
}

static void close_frame(biss_slave *b, sim_ps t) {
    b->cur.end_ps = t;
    b->cur.clocks = b->rises;
    b->cur.complete = b->started && b->bit >= b->nbits;
    b->ring[b->st.frames % BISS_RECORD_RING] = b->cur;
    b->st.frames++;
    if (b->on_frame) {
        b->on_frame(b->on_frame_ctx, &b->ring[(b->st.frames - 1) % BISS_RECORD_RING]);
    }
}

static void on_timeout(void *ctx, sim_ps t, int64_t arg) {
    (void)arg;
    biss_slave *b = ctx;
    b->timeout_ev = 0;
    if (t < b->timeout_due) {
        /* MA moved since this was scheduled: on to the deadline it moved
         * to, in the order the event would have had if scheduled then */
        b->timeout_ev =
            eq_schedule_as(b->q, b->timeout_due, b->timeout_due_order, on_timeout, b, 0);
        b->timeout_ev_at = b->timeout_due;
        return;
    }
    if (!b->st.in_frame) {
        return;
    }
    if (b->rises >= 2) {
        int cdm = !b->ma;
        int cds = 0;
        for (unsigned i = 0; i < b->cfg.n; i++) {
            if (!b->cfg.s[i].no_control) {
                cds |= biss_ctrl_cdm(&b->ctrl[i], cdm);
            }
        }
        b->cds = cds;
        b->cur.cdm = cdm;
    }
    if (b->lost && !held_low(b)) {
        b->lost = false; /* a whole frame after the loss: defined again */
    }
    drive_sl(b, t, 1);
    b->st.in_frame = false;
    close_frame(b, t);
}

/* Every MA edge restarts the timeout. Rather than cancel and schedule an
 * event each time, a pending event due no later than the new deadline stays
 * and moves on when it fires (on_timeout); the deadline takes its order
 * among events of its time now (eq_take_id), so everything runs as if
 * the event had been scheduled here. */
static void restart_timeout(biss_slave *b, sim_ps t) {
    b->timeout_due = t + timeout_len(b);
    b->timeout_due_order = eq_take_id(b->q);
    if (b->timeout_ev && b->timeout_ev_at <= b->timeout_due) {
        return;
    }
    eq_cancel(b->q, b->timeout_ev);
    b->timeout_ev = eq_schedule_as(b->q, b->timeout_due, b->timeout_due_order, on_timeout, b, 0);
    b->timeout_ev_at = b->timeout_due;
}

/* ---- MA edges ---- */

/* What a rising MA edge at t is to the frame, before it is taken. */
enum rise_kind { RISE_FIRST, RISE_ACK, RISE_BUSY, RISE_START, RISE_BIT };

static inline enum rise_kind rise_kind(const biss_slave *b, sim_ps t) {
    if (__builtin_expect(b->started, 1)) { /* a clocked frame's bits: laid out first */
        return RISE_BIT;
    }
    unsigned rises = b->rises + 1; /* this rise's number in the frame */
    if (rises == 1) {
        return RISE_FIRST;
    }
    if (rises == 2) {
        return RISE_ACK;
    }
    bool clocks_ok = rises >= 3 + b->cfg.busy_clocks;
    bool time_ok = t - b->cur.ack_ps >= b->cfg.busy_ps;
    return clocks_ok && time_ok ? RISE_START : RISE_BUSY;
}

/* The SL level a rise drives: the ACK's low, the start bit, the next data
 * bit (low past the last); busy clocks and the first rise drive none. */
static inline int rise_sl(const biss_slave *b, enum rise_kind kind) {
    if (kind == RISE_BIT) {
        return b->bit < b->nbits ? b->bits[b->bit] : 0;
    }
    return kind == RISE_START;
}

/* A rise's steps but the first rise's and SL's. */
static inline void take_rise(biss_slave *b, sim_ps t, enum rise_kind kind) {
    b->rises++;
    if (kind == RISE_BIT) {
        if (b->bit < b->nbits && ++b->bit == b->nbits) {
            b->cur.last_bit_ps = t;
        }
    } else if (kind == RISE_ACK) {
        b->cur.acked = true;
        b->cur.ack_ps = t;
    } else if (kind == RISE_START) {
        b->started = true;
        b->cur.started = true;
        b->cur.start_bit_ps = t;
    }
}

static void on_rise(biss_slave *b, sim_ps t) {
    enum rise_kind kind = rise_kind(b, t);
    if (kind == RISE_FIRST) {
        b->rises++;
        /* [MB4] "BiSS C Frame": "With the first rising edge at MAx all
         * sensors start calculating their sensor data" - the position is
         * taken here, not at the falling edge that starts the frame. */
        b->cur.latch_ps = t;
        for (unsigned i = 0; i < b->cfg.n; i++) {
            build_slave_data(b, i, t);
        }
        b->latches++;
        return;
    }
    int level = rise_sl(b, kind);
    take_rise(b, t, kind);
    if (kind != RISE_BUSY) {
        drive_sl(b, t, level);
    }
}

/* MA's new level at t, and the times of the edges before it. */
static inline void note_ma(biss_slave *b, sim_ps t, int level) {
    b->ma = level;
    b->prev_edge = b->last_edge;
    b->last_edge = t;
    if (level) {
        b->prev_rise = b->last_rise;
        b->last_rise = t;
    }
}

/* timeout_len() as it will be once the quick step has taken the edge at t
 * (note_ma(), and at a rise on_rise()'s count: a rise here is the third or
 * later). The adaptive timeout through a memo of the last period: a
 * clocked frame's periods are alike, so one llround() a frame, not one an
 * edge (biss_chain_timeout_ps() is a function of the period alone). */
static inline sim_ps quick_timeout(biss_slave *b, sim_ps t, int level) {
    const biss_chain_cfg *c = &b->cfg;
    if (c->timeout_mode == BISS_TIMEOUT_FIXED) {
        return c->timeout_ps;
    }
    sim_ps period = c->adaptive_max_ps;
    if (b->rises + (unsigned)level >= 2) {
        period = level ? t - b->last_rise : b->last_rise - b->prev_rise;
    } else if (t != b->last_edge) {
        period = 2 * (t - b->last_edge);
    }
    if (period != b->memo_period) {
        b->memo_period = period;
        b->memo_timeout = biss_chain_timeout_ps(c, period);
    }
    return b->memo_timeout;
}

bool biss_slave_ma_edge_quick(biss_slave *b, sim_ps t, int level) {
    level = level ? 1 : 0;
    if (level == b->ma || !b->st.in_frame || !b->quick) {
        return false;
    }
    sim_ps due = t + quick_timeout(b, t, level); /* timeout_len() */
    if (!b->timeout_ev || b->timeout_ev_at > due) {
        return false; /* restart_timeout() would schedule */
    }
    int sl = -1; /* the SL level the rise drives, -1 none */
    if (level) {
        enum rise_kind kind = rise_kind(b, t);
        if (kind == RISE_FIRST) {
            return false; /* it builds the frame's data */
        }
        int level_sl = rise_sl(b, kind);
        if (kind != RISE_BUSY && sl_moves(b, level_sl)) {
            if (!eq_fits(b->q, t + b->cfg.out_delay_ps)) {
                return false;
            }
            sl = level_sl;
        }
        take_rise(b, t, kind); /* its fields and note_ma()'s are apart */
    }
    note_ma(b, t, level);
    if (sl >= 0) {
        b->sl_sched = sl;
        eq_put(b->q, t + b->cfg.out_delay_ps, emit_sl, b, sl);
    }
    /* restart_timeout(): the pending event stays */
    b->timeout_due = due;
    b->timeout_due_order = eq_take_id(b->q);
    return true;
}

void biss_slave_ma_edge(biss_slave *b, sim_ps t, int level) {
    if (!biss_slave_ma_edge_quick(b, t, level)) {
        biss_slave_ma_edge_general(b, t, level);
    }
}

void biss_slave_ma_edge_general(biss_slave *b, sim_ps t, int level) {
    level = level ? 1 : 0;
    if (level == b->ma) {
        return;
    }
    note_ma(b, t, level);
    if (!b->st.in_frame) {
        if (level) {
            return; /* MA returning high after a CDM = 1: not a frame */
        }
        start_frame(b, t);
    } else if (level) {
        on_rise(b, t);
    }
    restart_timeout(b, t);
}

static void sink_fn(void *ctx, sim_ps t, int level) {
    biss_slave_ma_edge(ctx, t, level);
}

sim_edge_sink biss_slave_sink(biss_slave *b) {
    sim_edge_sink s = {sink_fn, b};
    return s;
}
