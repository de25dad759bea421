/*
 * intc.c - the subset of the PRU-ICSS INTC (docs/pru-facts.md §5.5) that decides
 * R31[31:30]: system events from R31 writes (16..31), Cnt_16 (1) and the
 * IEP compare (7, a level while any CMP_STATUS bit is set); raw/enabled
 * status set and clear; channel and host maps; global and host enables.
 * Host interrupt 0 -> R31[30], host 1 -> R31[31]. Other registers are
 * plain storage. The events come from the blocks that raise them (their
 * raise and next_raise, icss_block.h), R31 writes (intc_event).
 */
#include "core_priv.h"

#include <string.h>

static void intc_reset(struct pru_core *c) {
    memset(&c->pru0->intc, 0, sizeof c->pru0->intc);
}

void intc_event(struct pru_core *c, unsigned ev) {
    if (ev < 64)
        c->pru0->intc.raw[ev / 32] |= 1u << (ev % 32);
}

/* Bring the events of every block that raises some up to `cycle`. */
static void intc_sync(struct pru_core *c, int64_t cycle) {
    for (size_t i = 0; i < icss_nblocks; i++)
        if (icss_blocks[i]->raise)
            icss_blocks[i]->raise(c, cycle);
}

static bool host_pending(const struct intc *n, unsigned host) {
    if (!(n->ger & 1u) || !((n->hier >> host) & 1u))
        return false;
    for (unsigned w = 0; w < 2; w++) {
        uint32_t p = n->raw[w] & n->enabled[w];
        while (p) {
            unsigned b = (unsigned)__builtin_ctz(p);
            p &= p - 1;
            unsigned ch = n->cmr[32 * w + b] & 0xfu;
            if ((n->hmr[ch] & 0xfu) == host)
                return true;
        }
    }
    return false;
}

uint32_t intc_host_bits(struct pru_core *c, int64_t cycle) {
    struct intc *n = &c->pru0->intc;
    if (!(n->ger & 1u) || !(n->hier & 3u))
        return 0;
    intc_sync(c, cycle);
    return (host_pending(n, 0) ? 1u << 30 : 0) | (host_pending(n, 1) ? 1u << 31 : 0);
}

/* First cycle after `cycle` at which the status or host lines may change:
 * the next event any block may raise. */
int64_t intc_next_change(struct pru_core *c, int64_t cycle) {
    int64_t h = CYCLE_NEVER;
    for (size_t i = 0; i < icss_nblocks; i++) {
        if (icss_blocks[i]->next_raise) {
            int64_t t = icss_blocks[i]->next_raise(c, cycle);
            h = t < h ? t : h;
        }
    }
    return h;
}

static uint32_t byte_regs_read(const uint8_t *a, uint32_t first) {
    return (uint32_t)a[first] | (uint32_t)a[first + 1] << 8 | (uint32_t)a[first + 2] << 16 |
           (uint32_t)a[first + 3] << 24;
}

static void byte_regs_write(uint8_t *a, uint32_t first, uint32_t v, uint32_t bm) {
    for (unsigned b = 0; b < 4; b++)
        if ((bm >> (8 * b)) & 0xffu)
            a[first + b] = (uint8_t)(v >> (8 * b));
}

static uint32_t intc_read(struct pru_core *c, uint32_t ofs, int64_t at) {
    struct intc *n = &c->pru0->intc;
    intc_sync(c, at);
    switch (ofs) {
    case 0x10:
        return n->ger;
    case 0x200:
        return n->raw[0];
    case 0x204:
        return n->raw[1];
    case 0x280:
        return n->raw[0] & n->enabled[0];
    case 0x284:
        return n->raw[1] & n->enabled[1];
    case 0x300:
        return n->enabled[0];
    case 0x304:
        return n->enabled[1];
    case 0x1500:
        return n->hier;
    default:
        if (ofs >= 0x400u && ofs < 0x440u)
            return byte_regs_read(n->cmr, ofs - 0x400u);
        if (ofs >= 0x800u && ofs < 0x80Cu)
            return byte_regs_read(n->hmr, ofs - 0x800u);
        uint32_t v;
        memcpy(&v, n->regs + ofs, 4);
        return v;
    }
}

/* Host interrupts 0/1 can be pending: R31[31:30] follow the INTC. */
static bool intc_live(const struct intc *n) {
    return (n->ger & 1u) && (n->hier & 3u);
}

static void intc_write(struct pru_core *c, uint32_t ofs, uint32_t val, uint32_t bm, int64_t at) {
    struct intc *n = &c->pru0->intc;
    uint32_t v = val & bm;
    unsigned idx = v & 63u;
    bool was_live = intc_live(n);
    intc_sync(c, at);
    ff_dirty(c);
    switch (ofs) {
    case 0x10:
        n->ger = v & 1u;
        break;
    case 0x20:
        n->raw[idx / 32] |= 1u << (idx % 32);
        break; /* SISR */
    case 0x24:
        n->raw[idx / 32] &= ~(1u << (idx % 32));
        break; /* SICR */
    case 0x28:
        n->enabled[idx / 32] |= 1u << (idx % 32);
        break; /* EISR */
    case 0x2C:
        n->enabled[idx / 32] &= ~(1u << (idx % 32));
        break;
    case 0x34:
        n->hier |= 1u << (v & 15u);
        break; /* HIEISR */
    case 0x38:
        n->hier &= ~(1u << (v & 15u));
        break; /* HIDISR */
    case 0x200:
        n->raw[0] |= v;
        break; /* SRSR: write 1 sets */
    case 0x204:
        n->raw[1] |= v;
        break;
    case 0x280:
        n->raw[0] &= ~v;
        break; /* SECR: write 1 clears */
    case 0x284:
        n->raw[1] &= ~v;
        break;
    case 0x300:
        n->enabled[0] |= v;
        break; /* ESR */
    case 0x304:
        n->enabled[1] |= v;
        break;
    case 0x380:
        n->enabled[0] &= ~v;
        break; /* ECR */
    case 0x384:
        n->enabled[1] &= ~v;
        break;
    case 0x1500:
        n->hier = (n->hier & ~bm) | (v & 0x3ffu);
        break;
    default:
        if (ofs >= 0x400u && ofs < 0x440u)
            byte_regs_write(n->cmr, ofs - 0x400u, val, bm);
        else if (ofs >= 0x800u && ofs < 0x80Cu)
            byte_regs_write(n->hmr, ofs - 0x800u, val, bm);
        else
            byte_regs_write(n->regs, ofs, val, bm);
        break;
    }
    intc_sync(c, at); /* a level event (the IEP's) sets again */
    if (!was_live && intc_live(n))
        xpru_exclusive(c, PRUSS_OFS_INTC + ofs); /* the other PRU's R31 reads change */
}

static int64_t next_change(struct pru_core *c, int64_t cycle, uint32_t ofs) {
    (void)ofs;
    return intc_next_change(c, cycle);
}

const struct icss_block icss_intc = {
    .name = "INTC",
    .base = PRUSS_OFS_INTC,
    .size = INTC_BYTES,
    .load_cycles = offsetof(struct pru_params, load_intc_cycles),
    .reset = intc_reset,
    .read = intc_read,
    .write = intc_write,
    .next_change = next_change,
};
