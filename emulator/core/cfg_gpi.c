/*
 * cfg_gpi.c - the CFG block (SYSCFG, GPCFG0/1; docs/pru-facts.md §4.5) and what R31
 * reads: GPI direct mode, and the 28-bit shift mode of §4.4 evaluated lazily
 * from the input waveform when R31 is read (never stepped per cycle).
 *
 * Shift mode: edge k (k >= 1) of the shift clock is at
 *   T(k) = t_cfg + shift_phase_ps + k * P,   P = 5000 ps * ratio0 * ratio1,
 * ratio = 1 + code/2 (so P = 1250 * (2+code0) * (2+code1) ps, an integer),
 * or rounded down to a PRU clock edge with PRU_FRAC_CYCLE. At each edge
 * DATAIN (input bit 0, seen at T(k) - gpi_delay_ps) enters bit 0, bit 27
 * drops. The first 1 sets SB (R31[29], sticky); R31[28] (Cnt_16) is high
 * for one shift period from every 16th edge after the start-bit edge and
 * raises system event 1. A read at cycle c sees every edge with T(k) <= c*5000.
 */
#include "core_priv.h"

#define GPCFG0      0x08u
#define GPCFG1      0x0Cu
#define SYSCFG      0x04u
#define GP_SB       (1u << 13)
#define GP_GPO_MODE (1u << 14)
#define GP_GPO_SEL  (1u << 25)
#define SHIFT_MASK  0x0fffffffu
#define MODE_SHIFT  2u
/* input changes this late count as never (keeps edge arithmetic in range) */
#define NEVER_PS (PRU_MAX_CYCLE * PRU_PS_PER_CYCLE)

/* Each PRU's GPI follows its own GPCFG (GPCFG0 PRU0, GPCFG1 PRU1) in the
 * one CFG block of its PRU-ICSS (docs/pru-facts.md §4.5). */
static uint32_t gpcfg_ofs(const struct pru_core *c) {
    return GPCFG0 + 4u * c->pru_idx;
}

static unsigned gpi_mode(const struct pru_core *c) {
    return c->pru0->cfg_regs[gpcfg_ofs(c) / 4] & 3u;
}

/* The PRU whose GPI a GPCFG offset drives, NULL for none. */
static struct pru_core *gpcfg_owner(struct pru_core *c, uint32_t ofs) {
    if (ofs == GPCFG0)
        return c->pru0;
    return ofs == GPCFG1 ? c->pru0->pru1 : NULL;
}

static void cfg_reset(struct pru_core *c) {
    for (unsigned i = 0; i < CFG_BYTES / 4; i++)
        c->cfg_regs[i] = 0;
    c->cfg_regs[0] = 0x47000000u;    /* REVID (value not used by anyone) */
    c->cfg_regs[SYSCFG / 4] = 0x1Au; /* idle/standby modes, STANDBY_INIT = 1 */
    c->sh = (struct gpi_shift){0};
    c->sh.period_ps = 5000;
    c->sh.cnt16_k = -1;
}

static uint32_t pins_inputs_at(struct pru_core *c, int64_t t_ps) {
    if (!c->have_pins)
        return c->const_inputs;
    return c->pins.inputs_at(c->pins.ctx, t_ps < 0 ? 0 : t_ps);
}

/* ---- shift clock geometry ---- */

static int64_t period_ps(const struct pru_core *c) {
    return c->sh.period_ps;
}

static int64_t t0(const struct pru_core *c) {
    return c->sh.t_cfg_ps + c->p.shift_phase_ps;
}

static int64_t edge_time(const struct pru_core *c, int64_t k) {
    int64_t off = k * period_ps(c);
    if (c->p.shift_frac == PRU_FRAC_CYCLE)
        off = off / PRU_PS_PER_CYCLE * PRU_PS_PER_CYCLE;
    return t0(c) + off;
}

/* Index of the last edge at or before t (0 if none). */
static int64_t last_edge(const struct pru_core *c, int64_t t) {
    int64_t rel = t - t0(c);
    if (rel < 0)
        return 0;
    int64_t p = period_ps(c);
    if (c->p.shift_frac == PRU_FRAC_CYCLE) {
        int64_t m = rel / PRU_PS_PER_CYCLE;
        return ((m + 1) * PRU_PS_PER_CYCLE - 1) / p;
    }
    return rel / p;
}

static int64_t cycle_of(int64_t t_ps) {
    return t_ps <= 0 ? 0 : (t_ps + PRU_PS_PER_CYCLE - 1) / PRU_PS_PER_CYCLE;
}

/* ---- lazy shift register ---- */

/* Apply m samples of value v starting at edge k. */
static void shift_samples(struct gpi_shift *s, uint32_t v, int64_t m, int64_t k) {
    if (v && !s->sb) {
        s->sb = true;
        s->cnt16_k = k; /* here: the start-bit edge; pulses at k + 16j */
    }
    if (m >= 28)
        s->reg = v ? SHIFT_MASK : 0;
    else
        s->reg = ((s->reg << m) | (v ? (1u << m) - 1u : 0)) & SHIFT_MASK;
}

/* Did a Cnt_16 edge (k_sb + 16j, j >= 1) fall into edges [a, b]? */
static bool cnt16_in(const struct gpi_shift *s, int64_t a, int64_t b) {
    if (!s->sb || b <= s->cnt16_k)
        return false;
    int64_t lo = a > s->cnt16_k + 1 ? a : s->cnt16_k + 1;
    int64_t first = s->cnt16_k + ((lo - s->cnt16_k + 15) / 16) * 16;
    return first <= b;
}

/* DATAIN at t >= 0, and in *next the earliest time after t at which it
 * may change (NEVER_PS or later: never): the pins' inputs_run, or
 * inputs_at and next_input_change (without the latter, any time). */
static uint32_t datain_run(struct pru_core *c, int64_t t, int64_t *next) {
    if (c->pins.inputs_run)
        return c->pins.inputs_run(c->pins.ctx, t, next) & 1u;
    if (!c->have_pins) {
        *next = NEVER_PS;
        return c->const_inputs & 1u;
    }
    uint32_t v = c->pins.inputs_at(c->pins.ctx, t) & 1u;
    *next = c->pins.next_input_change ? c->pins.next_input_change(c->pins.ctx, t) : t + 1;
    return v;
}

static void shift_apply(struct pru_core *c, int64_t k_from, int64_t k_to) {
    struct gpi_shift *s = &c->sh;
    int64_t delay = c->p.gpi_delay_ps;
    int64_t k = k_from;
    while (k <= k_to) {
        if (s->sb && k_to - k >= 28)
            k = k_to - 27; /* older samples are shifted out; only SB/Cnt_16 remain */
        int64_t t = edge_time(c, k) - delay;
        int64_t tn;
        uint32_t v = datain_run(c, t < 0 ? 0 : t, &tn);
        /* the samples up to the last edge before the change are v */
        int64_t j = tn >= NEVER_PS ? k_to : last_edge(c, tn + delay - 1);
        if (j > k_to)
            j = k_to;
        int64_t m = j >= k ? j - k + 1 : 1;
        shift_samples(s, v, m, k);
        k += m;
    }
    if (cnt16_in(s, k_from, k_to))
        intc_event(c, 1 + c->pru_idx); /* Cnt_16 of PRU0 / PRU1 */
}

static void gpi_sync(struct pru_core *c, int64_t cycle) {
    if (gpi_mode(c) != MODE_SHIFT || cycle < c->sh.next_edge_cycle)
        return; /* no new edge since the last evaluation */
    int64_t k = last_edge(c, cycle * PRU_PS_PER_CYCLE);
    c->sh.next_edge_cycle = cycle_of(edge_time(c, k + 1));
    if (k > c->sh.k_done) {
        shift_apply(c, c->sh.k_done + 1, k);
        c->sh.k_done = k;
    }
}

static int64_t gpi_bits_stable_until(struct pru_core *c, int64_t cycle, uint32_t mask);

static bool cnt16_high(const struct gpi_shift *s, int64_t k) {
    return s->sb && k > s->cnt16_k && (k - s->cnt16_k) % 16 == 0;
}

uint32_t gpi_r31(struct pru_core *c, int64_t cycle) {
    uint32_t v;
    if (gpi_mode(c) == MODE_SHIFT) {
        gpi_sync(c, cycle);
        const struct gpi_shift *s = &c->sh;
        v = s->reg | (s->sb ? 1u << 29 : 0) | (cnt16_high(s, s->k_done) ? 1u << 28 : 0);
    } else {
        v = pins_inputs_at(c, cycle * PRU_PS_PER_CYCLE - c->p.gpi_delay_ps) & 0x3fffffffu;
    }
    v |= intc_host_bits(c, cycle);
    if (ff_input_read(c))
        ff_horizon(c, gpi_bits_stable_until(c, cycle, c->ff.r31_mask));
    return v;
}

bool gpi_r31_shared(struct pru_core *c, int64_t cycle) {
    const struct intc *n = &c->pru0->intc;
    if ((n->ger & 1u) && (n->hier & 3u))
        return true; /* R31[31:30] follow the INTC (intc_host_bits) */
    if (gpi_mode(c) != MODE_SHIFT || cycle < c->sh.next_edge_cycle)
        return false; /* gpi_sync() does nothing */
    const struct gpi_shift *s = &c->sh;
    int64_t k = last_edge(c, cycle * PRU_PS_PER_CYCLE);
    /* shift_apply() raises Cnt_16 for a pulse edge in (k_done, k]: without a
     * start bit yet, one 16 edges after a start bit at k_done + 1 or later */
    if (!s->sb)
        return k >= s->k_done + 17;
    return k >= s->cnt16_k + ((s->k_done - s->cnt16_k) / 16 + 1) * 16;
}

/* First cycle after `cycle` at which the input level may differ from now. */
static int64_t input_change_cycle(struct pru_core *c, int64_t cycle) {
    if (!c->have_pins)
        return CYCLE_NEVER;
    if (!c->pins.next_input_change)
        return cycle + 1;
    int64_t t = cycle * PRU_PS_PER_CYCLE - c->p.gpi_delay_ps;
    int64_t tn = c->pins.next_input_change(c->pins.ctx, t < 0 ? 0 : t);
    if (tn >= NEVER_PS)
        return CYCLE_NEVER;
    int64_t cn = cycle_of(tn + c->p.gpi_delay_ps);
    return cn > cycle ? cn : cycle + 1;
}

/* Register bits 0..n where n is the highest shift-register bit in mask: a
 * shift moves bit j-1 into j, so these stay as they are exactly when all
 * of them equal the new sample. */
static uint32_t low_bits(uint32_t mask) {
    uint32_t m = mask & SHIFT_MASK;
    while (m & (m + 1)) /* fill below the highest set bit */
        m |= m >> 1 | m >> 2 | m >> 4 | m >> 8 | m >> 16;
    return m;
}

/* First cycle at which a read may see an input change at tn (datain_run's
 * next) through the shift register: from the first edge whose sample
 * (taken gpi_delay_ps before the edge) is at or after the change.
 * (Rounding the change to a cycle first would miss an edge between the
 * change and that cycle.) */
static int64_t shift_sees_change(struct pru_core *c, int64_t tn) {
    if (tn >= NEVER_PS)
        return CYCLE_NEVER;
    return cycle_of(edge_time(c, last_edge(c, tn + c->p.gpi_delay_ps - 1) + 1));
}

static int64_t shift_stable_until(struct pru_core *c, int64_t cycle, uint32_t mask) {
    struct gpi_shift *s = &c->sh;
    gpi_sync(c, cycle);
    int64_t k = s->k_done;
    int64_t next_edge = cycle_of(edge_time(c, k + 1));
    /* the input now and its next change */
    int64_t t = cycle * PRU_PS_PER_CYCLE - c->p.gpi_delay_ps;
    int64_t tn;
    uint32_t v = datain_run(c, t < 0 ? 0 : t, &tn);
    uint32_t low = low_bits(mask);
    bool fixed = (s->reg & low) == (v ? low : 0);
    if ((mask & 1u << 29) && !s->sb && v) /* SB is set by the next edge */
        fixed = false;
    if (!fixed)
        return next_edge;
    int64_t in = shift_sees_change(c, tn);
    if (in < next_edge)
        in = next_edge;
    if (s->sb && (mask & 1u << 28)) {
        int64_t e = k + 1;
        if (!cnt16_high(s, k)) /* next pulse edge */
            e = s->cnt16_k + ((k - s->cnt16_k) / 16 + 1) * 16;
        int64_t ce = cycle_of(edge_time(c, e));
        if (ce < in)
            in = ce;
    }
    return in;
}

static int64_t gpi_bits_stable_until(struct pru_core *c, int64_t cycle, uint32_t mask) {
    int64_t h = gpi_mode(c) == MODE_SHIFT ? shift_stable_until(c, cycle, mask)
                                          : input_change_cycle(c, cycle);
    if ((mask & 3u << 30) && (c->pru0->intc.ger & 1u) &&
        (c->pru0->intc.hier & 3u)) { /* R31[31:30] can move */
        int64_t hi = intc_next_change(c, cycle);
        if (hi < h)
            h = hi;
    }
    return h;
}

int64_t gpi_stable_until(struct pru_core *c, int64_t cycle) {
    return gpi_bits_stable_until(c, cycle, ~0u);
}

static int64_t gpi_next_cnt16(struct pru_core *c, int64_t cycle) {
    struct gpi_shift *s = &c->sh;
    if (gpi_mode(c) != MODE_SHIFT)
        return CYCLE_NEVER;
    gpi_sync(c, cycle);
    if (!s->sb) /* a start bit at the next edge is followed by 16 more */
        return cycle_of(edge_time(c, s->k_done + 17));
    int64_t e = s->cnt16_k + ((s->k_done - s->cnt16_k) / 16 + 1) * 16;
    return cycle_of(edge_time(c, e));
}

int pru_gpi_sample_bracket(const struct pru_core *c, int64_t t_ps, int64_t *before_ps,
                           int64_t *after_ps) {
    if (gpi_mode(c) != MODE_SHIFT || period_ps(c) <= 0)
        return -1;
    int64_t d = c->p.gpi_delay_ps, k = last_edge(c, t_ps + d);
    *before_ps = edge_time(c, k) - d;
    *after_ps = edge_time(c, k + 1) - d;
    return 0;
}

/* ---- CFG registers ---- */

static uint32_t cfg_read(struct pru_core *c, uint32_t ofs, int64_t at) {
    struct pru_core *g = gpcfg_owner(c, ofs);
    if (g) {
        if (g != c)
            xpru_exclusive(c, 0x26000u + ofs); /* the other PRU's GPI, as of `at` */
        gpi_sync(g, at);
        return (c->pru0->cfg_regs[ofs / 4] & ~(GP_SB | GP_GPO_SEL)) | (g->sh.sb ? GP_SB : 0);
    }
    return c->pru0->cfg_regs[ofs / 4];
}

/* A write to GPCFG0/1 (ofs) by core w: the GPI of core c follows it. */
static void gpcfg_write(struct pru_core *c, struct pru_core *w, uint32_t ofs, uint32_t v,
                        uint32_t bm, int64_t at) {
    uint32_t old = c->pru0->cfg_regs[ofs / 4];
    uint32_t nv = ((old & ~bm) | (v & bm)) & ~(GP_SB | GP_GPO_SEL);
    gpi_sync(c, at);
    c->pru0->cfg_regs[ofs / 4] = nv;
    if ((old ^ nv) & 0x1fffu & ~GP_SB) {
        /* mode or divider changed: the shift clock restarts from here */
        unsigned c0 = (nv >> 3) & 0x1fu, c1 = (nv >> 8) & 0x1fu;
        c->sh.t_cfg_ps = at * PRU_PS_PER_CYCLE;
        c->sh.period_ps = 1250 * (int64_t)(2 + c0) * (int64_t)(2 + c1);
        c->sh.k_done = 0;
        c->sh.next_edge_cycle = 0;
    }
    if ((bm & GP_SB) && (v & GP_SB)) { /* write 1: clear SB and the register */
        c->sh.sb = false;
        c->sh.reg = 0;
        c->sh.cnt16_k = -1;
    }
    if (nv & GP_GPO_MODE)
        core_fault(w, PRU_FAULT_GPO_SHIFT, 0x26000u + ofs);
    unsigned mode = nv & 3u;
    if (mode == 1u || mode == 3u)
        core_fault(w, PRU_FAULT_UNSUPPORTED, 0x26000u + ofs);
}

static void cfg_write(struct pru_core *c, uint32_t ofs, uint32_t val, uint32_t bmask, int64_t at) {
    ff_dirty(c);
    struct pru_core *g = gpcfg_owner(c, ofs);
    if (g) {
        if (g != c)
            xpru_exclusive(c, 0x26000u + ofs); /* the other PRU's GPI changes */
        gpcfg_write(g, c, ofs, val, bmask, at);
        return;
    }
    if (ofs == 0x00u)
        return; /* REVID is read-only */
    uint32_t *r = &c->pru0->cfg_regs[ofs / 4];
    *r = (*r & ~bmask) | (val & bmask);
}

/* A read of any CFG word, GPCFG's SB included, holds while R31 does. */
static int64_t cfg_next_change(struct pru_core *c, int64_t cycle, uint32_t ofs) {
    (void)ofs;
    return gpi_stable_until(c, cycle);
}

const struct icss_block icss_cfg = {
    .name = "CFG",
    .base = PRUSS_OFS_CFG,
    .size = CFG_BYTES,
    .load_cycles = offsetof(struct pru_params, load_cfg_cycles),
    .reset = cfg_reset,
    .read = cfg_read,
    .write = cfg_write,
    .next_change = cfg_next_change,
    /* Cnt_16 (system event 1 for PRU0, 2 for PRU1) from the shift register */
    .raise = gpi_sync,
    .next_raise = gpi_next_cnt16,
};
