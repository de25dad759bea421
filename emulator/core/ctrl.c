/*
 * ctrl.c - PRU0 control registers (docs/pru-facts.md §5.3): CONTROL with soft reset,
 * enable, sleeping, counter enable, single step and the reset PC; STATUS;
 * WAKEUP_EN; CYCLE/STALL (section 3) kept lazily; CTBIR/CTPPR; and the
 * debug registers behind them (GPREG, CT_REG). Two blocks (icss_block.h):
 * PRU0's at 0x22000 and PRU1's at 0x24000, the same for both PRUs.
 */
#include "core_priv.h"
#include "exec_priv.h"

#define CYCLE_MAX 0xffffffffu

static void ctrl_reset(struct pru_core *c) {
    struct ctrl *k = &c->ctrl;
    *k = (struct ctrl){0};
    k->control = PRU_CTRL_SOFT_RST_N;
}

static uint32_t cycle_at(const struct ctrl *k, int64_t at) {
    if (!k->counting)
        return k->cycle_saved;
    int64_t v = (int64_t)k->cycle_saved + (at - k->cycle_since);
    return v >= (int64_t)CYCLE_MAX ? CYCLE_MAX : (uint32_t)v;
}

static uint32_t stall_at(const struct pru_core *c, int64_t at) {
    const struct ctrl *k = &c->ctrl;
    if (!k->counting)
        return k->stall_saved;
    int64_t v = (int64_t)k->stall_saved + (c->stall_total - k->stall_since);
    uint32_t cyc = cycle_at(k, at);
    return v >= (int64_t)cyc ? cyc : (uint32_t)v; /* STALL <= CYCLE; frozen when CYCLE is */
}

/* Fold the running count into the saved values and restart from `at`. */
static void fold(struct pru_core *c, int64_t at) {
    struct ctrl *k = &c->ctrl;
    k->stall_saved = stall_at(c, at);
    k->cycle_saved = cycle_at(k, at);
    k->cycle_since = at;
    k->stall_since = c->stall_total;
}

/* CYCLE counts while ENABLE and COUNTER_ENABLE are set and the PRU is awake. */
void ctrl_counting_update(struct pru_core *c, int64_t at) {
    struct ctrl *k = &c->ctrl;
    fold(c, at);
    k->counting = (k->control & PRU_CTRL_ENABLE) && (k->control & PRU_CTRL_CTR_EN) && !c->sleeping;
}

/* At 0xFFFFFFFF the counter stops and clears COUNTER_ENABLE. */
static void saturate(struct pru_core *c, int64_t at) {
    struct ctrl *k = &c->ctrl;
    if (k->counting && cycle_at(k, at) == CYCLE_MAX) {
        fold(c, at);
        k->control &= ~PRU_CTRL_CTR_EN;
        k->counting = false;
    }
}

uint32_t ctrl_read(struct pru_core *c, uint32_t ofs, int64_t at) {
    struct ctrl *k = &c->ctrl;
    saturate(c, at);
    switch (ofs) {
    case 0x00: {
        uint32_t v = k->control | PRU_CTRL_SOFT_RST_N;
        if (v & PRU_CTRL_ENABLE)
            v |= PRU_CTRL_RUNSTATE;
        return v;
    }
    case 0x04:
        return c->pc & 0xffffu;
    case 0x08:
        return k->wakeup_en;
    case 0x0C:
        return cycle_at(k, at);
    case 0x10:
        return stall_at(c, at);
    case 0x20:
        return k->ctbir0;
    case 0x24:
        return k->ctbir1;
    case 0x28:
        return k->ctppr0;
    case 0x2C:
        return k->ctppr1;
    default:
        return 0;
    }
}

static void soft_reset(struct pru_core *c, uint32_t control) {
    c->pc = control >> 16;
    c->halted = false;
    c->sleeping = false;
    c->loop_end = NO_LOOP;
    c->ctrl.control &= ~PRU_CTRL_SLEEPING;
}

static void control_write(struct pru_core *c, uint32_t v, uint32_t bm, int64_t at) {
    struct ctrl *k = &c->ctrl;
    uint32_t old = k->control;
    uint32_t nv = (old & ~bm) | (v & bm);
    /* SLEEPING: only a write of 0 changes it (wakes); RUNSTATE is read-only */
    nv = (nv & ~(PRU_CTRL_SLEEPING | PRU_CTRL_RUNSTATE)) | (old & PRU_CTRL_SLEEPING);
    if ((bm & PRU_CTRL_SLEEPING) && !(v & PRU_CTRL_SLEEPING))
        nv &= ~PRU_CTRL_SLEEPING;
    if ((bm & PRU_CTRL_SOFT_RST_N) && !(v & PRU_CTRL_SOFT_RST_N))
        soft_reset(c, nv);
    nv |= PRU_CTRL_SOFT_RST_N; /* returns to 1 by itself */
    if ((nv & PRU_CTRL_ENABLE) && !(old & PRU_CTRL_ENABLE))
        c->halted = false;
    k->control = nv;
    if (!(nv & PRU_CTRL_SLEEPING))
        c->sleeping = false;
    ctrl_counting_update(c, at);
    if (nv != old)
        exec_recheck(c); /* the run loop re-evaluates enable/sleep/step */
}

void ctrl_write(struct pru_core *c, uint32_t ofs, uint32_t v, uint32_t bm, int64_t at) {
    struct ctrl *k = &c->ctrl;
    saturate(c, at);
    switch (ofs) {
    case 0x00:
        control_write(c, v, bm, at);
        break;
    case 0x08:
        k->wakeup_en = (k->wakeup_en & ~bm) | (v & bm);
        break;
    case 0x0C:
        /* writable only while the counter or the PRU is disabled; clears STALL too */
        if (!k->counting) {
            k->cycle_saved = (k->cycle_saved & ~bm) | (v & bm);
            k->stall_saved = 0;
        }
        break;
    case 0x10:
        if (!k->counting)
            k->stall_saved = (k->stall_saved & ~bm) | (v & bm);
        break;
    case 0x20:
        k->ctbir0 = (k->ctbir0 & ~bm) | (v & bm & 0x00ff00ffu);
        break;
    case 0x24:
        k->ctbir1 = (k->ctbir1 & ~bm) | (v & bm & 0x00ff00ffu);
        break;
    case 0x28:
        k->ctppr0 = (k->ctppr0 & ~bm) | (v & bm);
        break;
    case 0x2C:
        k->ctppr1 = (k->ctppr1 & ~bm) | (v & bm);
        break;
    default:
        break;
    }
    ff_dirty(c);
}

/* ---- the two blocks ---- */

/* Debug block (CTRL + 0x400): GPREG0-31 then CT_REG0-31. */
static uint32_t debug_read(struct pru_core *c, uint32_t ofs) {
    unsigned i = (ofs - 0x400u) / 4u;
    if (i < 32)
        return i == 31 ? gpi_r31(c, c->cycle) : c->r[i];
    if (i < 64)
        return const_table(c, i - 32);
    return 0;
}

/* The core whose block this is, read or written by core k. */
static uint32_t block_read(struct pru_core *c, uint32_t ofs, int64_t at) {
    return ofs >= 0x400u ? debug_read(c, ofs) : ctrl_read(c, ofs, at);
}

static void block_write(struct pru_core *c, uint32_t ofs, uint32_t v, uint32_t bm, int64_t at) {
    if (ofs < 0x400u) {
        ctrl_write(c, ofs, v, bm, at);
    } else if (ofs < 0x47cu) { /* GPREG0..30 (host debug access) */
        unsigned i = (ofs - 0x400u) / 4u;
        c->r[i] = (c->r[i] & ~bm) | (v & bm);
    }
}

/* The other PRU's block shows its registers, PC and counters as of `at`
 * and its writes stop, start or move it: nothing it may have run ahead
 * through (xpru_exclusive). */
static struct pru_core *other_block(struct pru_core *c, struct pru_core *owner, uint32_t base,
                                    uint32_t ofs) {
    if (owner != c)
        xpru_exclusive(c, base + ofs);
    return owner;
}

static uint32_t ctrl0_read(struct pru_core *c, uint32_t ofs, int64_t at) {
    return block_read(other_block(c, c->pru0, PRUSS_OFS_CTRL0, ofs), ofs, at);
}

static void ctrl0_write(struct pru_core *c, uint32_t ofs, uint32_t v, uint32_t bm, int64_t at) {
    block_write(other_block(c, c->pru0, PRUSS_OFS_CTRL0, ofs), ofs, v, bm, at);
}

/* CYCLE, STALL and STATUS move every cycle. */
static int64_t ctrl0_next_change(struct pru_core *c, int64_t cycle, uint32_t ofs) {
    (void)c;
    (void)ofs;
    return cycle + 1;
}

/* PRU1's block: PRU1's registers in a PRU-ICSS; plain storage for a core
 * alone (docs/pru-facts.md §5.1). */
static uint32_t ctrl1_read(struct pru_core *c, uint32_t ofs, int64_t at) {
    if (c->pru0->pru1)
        return block_read(other_block(c, c->pru0->pru1, PRUSS_OFS_CTRL1, ofs), ofs, at);
    uint32_t v;
    memcpy(&v, c->ctrl1 + ofs, 4);
    return v;
}

static void ctrl1_write(struct pru_core *c, uint32_t ofs, uint32_t v, uint32_t bm, int64_t at) {
    if (c->pru0->pru1) {
        block_write(other_block(c, c->pru0->pru1, PRUSS_OFS_CTRL1, ofs), ofs, v, bm, at);
        return;
    }
    uint32_t old;
    memcpy(&old, c->ctrl1 + ofs, 4);
    old = (old & ~bm) | (v & bm);
    memcpy(c->ctrl1 + ofs, &old, 4);
}

const struct icss_block icss_ctrl0 = {
    .name = "CTRL0",
    .base = PRUSS_OFS_CTRL0,
    .size = CTRL_BYTES,
    .load_cycles = offsetof(struct pru_params, load_ctrl_cycles),
    .reset = ctrl_reset, /* each core's own CONTROL */
    .read = ctrl0_read,
    .write = ctrl0_write,
    .next_change = ctrl0_next_change,
};

/* Its reads give the fast-forward no horizon: a core alone has plain
 * storage here, which only the host writes; in a PRU-ICSS a load is a
 * cross-PRU event, and no skip passes the other PRU (pruss.c, xpru_wait;
 * test_core_pruss, poll_other_pru_ff). */
const struct icss_block icss_ctrl1 = {
    .name = "CTRL1",
    .base = PRUSS_OFS_CTRL1,
    .size = CTRL_BYTES,
    .load_cycles = offsetof(struct pru_params, load_ctrl_cycles),
    .read = ctrl1_read,
    .write = ctrl1_write,
};
