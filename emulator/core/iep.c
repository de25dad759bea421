/*
 * iep.c - the IEP timer (docs/pru-facts.md §6): COUNT with DEFAULT_INC / CMP_INC /
 * COMPEN, compares CMP0..7 (hit when COUNT >= CMPn, status write-1-to-clear),
 * reset on CMP0, overflow flag. Evaluated lazily: the state is brought up to
 * a cycle boundary when read or written, in bulk between events.
 *
 * Timing (EST, TIMING.md): one IEP tick per PRU cycle boundary. A read by an
 * instruction issued at cycle c sees the state after the tick at boundary c;
 * a write lands at boundary c+1, after that boundary's tick. The tick after
 * COUNT >= CMP0 (with CMP0_RST_CNT_EN and CMP0 enabled) sets COUNT to 0.
 */
#include "core_priv.h"

#include <stddef.h>
#include <string.h>

#define G_CFG    0x00u
#define G_STATUS 0x04u
#define COMPEN   0x08u
#define COUNT    0x0Cu
#define CMP_CFG  0x40u
#define CMP_STAT 0x44u
#define CMP0     0x48u
#define U32_MAX  0xffffffffu

static void iep_reset(struct pru_core *c) {
    struct iep *e = &c->pru0->iep; /* one IEP per PRU-ICSS */
    memset(e, 0, sizeof *e);
    e->global_cfg = 0x550u;
}

static bool counting(const struct iep *e) {
    return e->global_cfg & 1u;
}

static uint32_t inc_now(const struct iep *e) {
    return e->compen ? (e->global_cfg >> 8) & 0xfu : (e->global_cfg >> 4) & 0xfu;
}

static bool cmp_enabled(const struct iep *e, unsigned n) {
    return (e->cmp_cfg >> (n + 1)) & 1u;
}

static bool reset_pending(const struct iep *e) {
    return (e->cmp_cfg & 1u) && cmp_enabled(e, 0) && e->count >= e->cmp[0];
}

static void check_hits(struct iep *e) {
    for (unsigned n = 0; n < 8; n++)
        if (cmp_enabled(e, n) && e->count >= e->cmp[n])
            e->cmp_status |= 1u << n;
}

/* One tick with every event applied. */
static void tick(struct iep *e) {
    if (reset_pending(e)) {
        e->count = 0;
    } else {
        uint64_t n = (uint64_t)e->count + inc_now(e);
        if (e->compen)
            e->compen--;
        if (n > U32_MAX)
            e->global_status |= 1u;
        e->count = (uint32_t)n;
    }
    check_hits(e);
}

/* How many ticks can be applied as plain additions (no event among them). */
static int64_t quiet_ticks(const struct iep *e) {
    if (reset_pending(e))
        return 0;
    uint32_t inc = inc_now(e);
    int64_t k = e->compen ? (int64_t)e->compen : INT64_MAX;
    for (unsigned n = 0; n < 8; n++) {
        if (!cmp_enabled(e, n))
            continue;
        bool hit = (e->cmp_status >> n) & 1u;
        bool resets = n == 0 && (e->cmp_cfg & 1u);
        if (hit && !resets)
            continue;
        if (e->count >= e->cmp[n])
            return 0;
        if (inc) {
            int64_t kn = (int64_t)((e->cmp[n] - e->count - 1u) / inc);
            if (kn < k)
                k = kn;
        }
    }
    if (inc) {
        int64_t kw = (int64_t)((U32_MAX - e->count) / inc);
        if (kw < k)
            k = kw;
    }
    return k;
}

/* Brings e up to the cycle boundary `cycle` (never back). In line in both
 * callers: iep_sync() stays what it was before pru_iep_view() shared it. */
static inline __attribute__((always_inline)) void iep_advance(struct iep *e, int64_t cycle) {
    while (e->synced < cycle) {
        if (!counting(e)) {
            e->synced = cycle;
            break;
        }
        int64_t k = quiet_ticks(e);
        if (k > cycle - e->synced)
            k = cycle - e->synced;
        if (k > 0) {
            e->count += (uint32_t)k * inc_now(e);
            if (e->compen)
                e->compen -= (uint32_t)k;
            e->synced += k;
        } else {
            tick(e);
            e->synced++;
        }
    }
}

static void iep_sync(struct pru_core *c, int64_t cycle) {
    iep_advance(&c->pru0->iep, cycle);
}

void pru_iep_view(const struct pru_core *c, int64_t cycle, struct pru_iep_view *v) {
    const struct iep *now = &c->pru0->iep;
    if (!((now->cmp_cfg & 1u) && cmp_enabled(now, 0))) {
        /* no periods: nothing to bring up to `cycle` for */
        *v = (struct pru_iep_view){
            .cycle = now->synced, .count = now->count, .inc = inc_now(now), .cmp0 = now->cmp[0]};
        return;
    }
    /* a copy of the counting state (not the backing store): the emulated
     * IEP stays where it is */
    struct iep e;
    memcpy(&e, &c->pru0->iep, offsetof(struct iep, regs));
    iep_advance(&e, cycle);
    v->cycle = e.synced;
    v->count = e.count;
    v->inc = inc_now(&e);
    v->cmp0 = e.cmp[0];
    v->cmp0_resets = (e.cmp_cfg & 1u) && cmp_enabled(&e, 0);
}

static uint32_t iep_read(struct pru_core *c, uint32_t ofs, int64_t at) {
    struct iep *e = &c->pru0->iep;
    iep_sync(c, at);
    switch (ofs) {
    case G_CFG:
        return e->global_cfg;
    case G_STATUS:
        return e->global_status;
    case COMPEN:
        return e->compen;
    case COUNT:
        return e->count;
    case CMP_CFG:
        return e->cmp_cfg;
    case CMP_STAT:
        return e->cmp_status;
    default:
        if (ofs >= CMP0 && ofs < CMP0 + 32u)
            return e->cmp[(ofs - CMP0) / 4u];
        uint32_t v;
        memcpy(&v, e->regs + ofs, 4);
        return v;
    }
}

static void iep_write(struct pru_core *c, uint32_t ofs, uint32_t val, uint32_t bm, int64_t at) {
    struct iep *e = &c->pru0->iep;
    uint32_t v = val & bm;
    iep_sync(c, at);
    if (e->synced < at)
        e->synced = at;
    ff_dirty(c);
    switch (ofs) {
    case G_CFG:
        e->global_cfg = ((e->global_cfg & ~bm) | v) & 0xff1u;
        break;
    case G_STATUS:
        e->global_status &= ~v;
        break; /* write 1 to clear */
    case COMPEN:
        e->compen = ((e->compen & ~bm) | v) & 0xffffffu;
        break;
    case COUNT:
        e->count = (e->count & ~bm) | v;
        break; /* plain write (docs/pru-facts.md §8) */
    case CMP_CFG:
        e->cmp_cfg = ((e->cmp_cfg & ~bm) | v) & 0x1ffu;
        break;
    case CMP_STAT:
        e->cmp_status &= ~(v & 0xffu);
        break;
    default:
        if (ofs >= CMP0 && ofs < CMP0 + 32u) {
            uint32_t *r = &e->cmp[(ofs - CMP0) / 4u];
            *r = (*r & ~bm) | v;
        } else {
            uint32_t old;
            memcpy(&old, e->regs + ofs, 4);
            old = (old & ~bm) | v;
            memcpy(e->regs + ofs, &old, 4);
        }
        break;
    }
}

/* First cycle after `cycle` at which register `ofs` may read differently. */
static int64_t iep_next_change(struct pru_core *c, int64_t cycle, uint32_t ofs) {
    struct iep *e = &c->pru0->iep;
    iep_sync(c, cycle);
    if (!counting(e))
        return CYCLE_NEVER;
    switch (ofs) {
    case COUNT:
    case COMPEN:
        return cycle + 1;
    case G_STATUS:
    case CMP_STAT: {
        int64_t k = quiet_ticks(e);
        if (k == INT64_MAX)
            return CYCLE_NEVER;
        return e->synced + k + 1;
    }
    default:
        return CYCLE_NEVER;
    }
}

/* The compare event (system event 7) is a level: set while any
 * CMP_STATUS bit is. */
static void raise_cmp(struct pru_core *c, int64_t cycle) {
    iep_sync(c, cycle);
    if (c->pru0->iep.cmp_status)
        intc_event(c, 7);
}

static int64_t next_cmp(struct pru_core *c, int64_t cycle) {
    return iep_next_change(c, cycle, CMP_STAT);
}

const struct icss_block icss_iep = {
    .name = "IEP",
    .base = PRUSS_OFS_IEP,
    .size = IEP_BYTES,
    .load_cycles = offsetof(struct pru_params, load_iep_cycles),
    .reset = iep_reset,
    .read = iep_read,
    .write = iep_write,
    .next_change = iep_next_change,
    .raise = raise_cmp,
    .next_raise = next_cmp,
};
