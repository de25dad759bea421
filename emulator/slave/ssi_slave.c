#include "ssi_slave.h"

#include "slave_motion.h"

#include <string.h>

void ssi_cfg_default(ssi_cfg *c) {
    memset(c, 0, sizeof *c);
    c->bits = 13;
    c->out_delay_ps = 20 * SIM_PS_PER_NS;
    c->monoflop_ps = 20 * SIM_PS_PER_US;
}

uint64_t ssi_to_gray(uint64_t v) {
    return v ^ (v >> 1);
}

uint64_t ssi_slave_position_at(const ssi_slave *s, sim_ps t) {
    return slave_position_at(s->cfg.pos0, s->cfg.speed_cps, s->cfg.bits, t);
}

void ssi_slave_init(ssi_slave *s, const ssi_cfg *cfg, event_queue *q, sim_edge_sink out) {
    memset(s, 0, sizeof *s);
    s->cfg = *cfg;
    s->q = q;
    s->out = out;
    s->ma = 1;
    s->sl_sched = 1;
}

const ssi_frame_record *ssi_slave_record(const ssi_slave *s, uint64_t n) {
    if (n >= s->st.frames || s->st.frames - n > SSI_RECORD_RING) {
        return NULL;
    }
    return &s->ring[n % SSI_RECORD_RING];
}

static void emit_sl(void *ctx, sim_ps t, int64_t level) {
    ssi_slave *s = ctx;
    sim_edge_send(&s->out, t, (int)level);
}

static void drive_sl(ssi_slave *s, sim_ps t, int level) {
    if (level == s->sl_sched) {
        return;
    }
    s->sl_sched = level;
    eq_schedule(s->q, t + s->cfg.out_delay_ps, emit_sl, s, level);
}

static void on_monoflop(void *ctx, sim_ps t, int64_t arg) {
    (void)arg;
    ssi_slave *s = ctx;
    s->monoflop_ev = 0;
    s->st.in_frame = false;
    drive_sl(s, t, 1);
    s->cur.end_ps = t;
    s->cur.clocks = s->rises;
    s->cur.complete = s->rises >= s->cfg.bits;
    s->ring[s->st.frames % SSI_RECORD_RING] = s->cur;
    s->st.frames++;
}

void ssi_slave_ma_edge(ssi_slave *s, sim_ps t, int level) {
    level = level ? 1 : 0;
    if (level == s->ma) {
        return;
    }
    s->ma = level;
    if (!s->st.in_frame) {
        if (level) {
            return;
        }
        s->st.in_frame = true;
        s->rises = 0;
        memset(&s->cur, 0, sizeof s->cur);
        s->cur.frame = s->st.frames;
        s->cur.start_ps = t;
        s->cur.position = ssi_slave_position_at(s, t);
        s->cur.code = s->cfg.gray ? ssi_to_gray(s->cur.position) : s->cur.position;
    } else if (level) {
        s->rises++;
        int bit = 0;
        if (s->rises <= s->cfg.bits) {
            bit = (int)((s->cur.code >> (s->cfg.bits - s->rises)) & 1u);
        }
        if (s->rises == s->cfg.bits) {
            s->cur.last_bit_ps = t;
        }
        drive_sl(s, t, bit);
    }
    eq_cancel(s->q, s->monoflop_ev);
    s->monoflop_ev = eq_schedule(s->q, t + s->cfg.monoflop_ps, on_monoflop, s, 0);
}

static void sink_fn(void *ctx, sim_ps t, int level) {
    ssi_slave_ma_edge(ctx, t, level);
}

sim_edge_sink ssi_slave_sink(ssi_slave *s) {
    sim_edge_sink k = {sink_fn, s};
    return k;
}
