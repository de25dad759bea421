/*
 * memmap.c - the PRU-local data space (docs/pru-facts.md §5.1), the constant
 * table (§5.2), the host's global view (§5.4) and the cost of each access (§3).
 * RAMs are bytes here; the register blocks are registered in icss_blocks and
 * reached through their interface (icss_block.h).
 */
#include "core_priv.h"

#include <stdlib.h>
#include <string.h>

const struct icss_block *const icss_blocks[] = {
    &icss_intc, &icss_ctrl0, &icss_ctrl1, &icss_cfg, &icss_iep,
};
const size_t icss_nblocks = sizeof icss_blocks / sizeof icss_blocks[0];

enum region {
    RG_NONE,
    RG_DRAM0,
    RG_DRAM1,
    RG_SHARED,
    RG_BLOCK, /* a register block: hit.blk */
    RG_EXT,
    RG_IRAM0,
    RG_IRAM1,
};

struct hit {
    enum region rg;
    uint32_t ofs;                 /* offset inside the block */
    uint32_t size;                /* size of the block */
    uint8_t *mem;                 /* RAM blocks: bytes at ofs */
    const struct icss_block *blk; /* RG_BLOCK */
};

static bool inside(uint32_t addr, uint32_t n, uint32_t base, uint32_t size) {
    return addr >= base && (uint64_t)addr + n <= (uint64_t)base + size;
}

/* Find the block holding [addr, addr+n) of the local space; host adds IRAM. */
static enum region find_local(struct pru_core *c, uint32_t addr, uint32_t n, bool host,
                              struct hit *h) {
    h->mem = NULL;
    if (inside(addr, n, 0, c->dram_bytes)) {
        h->ofs = addr;
        h->size = c->dram_bytes;
        h->mem = c->dram0 + addr;
        return h->rg = RG_DRAM0;
    }
    if (inside(addr, n, 0x2000u, c->dram_bytes)) {
        h->ofs = addr - 0x2000u;
        h->size = c->dram_bytes;
        h->mem = c->dram1 + h->ofs;
        return h->rg = RG_DRAM1;
    }
    if (c->shared_bytes && inside(addr, n, 0x10000u, c->shared_bytes)) {
        h->ofs = addr - 0x10000u;
        h->size = c->shared_bytes;
        h->mem = c->shared + h->ofs;
        return h->rg = RG_SHARED;
    }
    for (size_t i = 0; i < icss_nblocks; i++) {
        const struct icss_block *b = icss_blocks[i];
        if (inside(addr, n, b->base, b->size)) {
            h->ofs = addr - b->base;
            h->size = b->size;
            h->blk = b;
            return h->rg = RG_BLOCK;
        }
    }
    if (host && inside(addr, n, PRU_OFS_IRAM0, c->iram_bytes)) {
        h->ofs = addr - PRU_OFS_IRAM0;
        h->size = c->iram_bytes;
        h->mem = (uint8_t *)c->iram0 + h->ofs;
        return h->rg = RG_IRAM0;
    }
    if (host && inside(addr, n, PRU_OFS_IRAM1, c->iram_bytes)) {
        h->ofs = addr - PRU_OFS_IRAM1;
        h->size = c->iram_bytes;
        h->mem = (uint8_t *)c->iram1 + h->ofs;
        return h->rg = RG_IRAM1;
    }
    return h->rg = RG_NONE;
}

static enum region find_ext(struct pru_core *c, uint32_t addr, uint32_t n, struct hit *h) {
    for (unsigned i = 0; i < c->n_ext; i++) {
        if (inside(addr, n, c->ext[i].base, c->ext[i].size)) {
            h->ofs = addr - c->ext[i].base;
            h->size = c->ext[i].size;
            h->mem = c->ext[i].mem + h->ofs;
            return h->rg = RG_EXT;
        }
    }
    return h->rg = RG_NONE;
}

uint32_t const_table(const struct pru_core *c, unsigned n) {
    static const uint32_t fixed[24] = {
        0x00020000u, 0x48040000u, 0x4802A000u, 0x00030000u, 0x00026000u, 0x48060000u,
        0x48030000u, 0x00028000u, 0x46000000u, 0x4A100000u, 0x48318000u, 0x48022000u,
        0x48024000u, 0x48310000u, 0x481CC000u, 0x481D0000u, 0x481A0000u, 0x4819C000u,
        0x48300000u, 0x48302000u, 0x48304000u, 0x00032400u, 0x480C8000u, 0x480CA000u,
    };
    const struct ctrl *k = &c->ctrl;
    switch (n & 31u) {
    case 24:
        return (k->ctbir0 & 0xffu) << 8;
    case 25:
        return 0x2000u | ((k->ctbir0 >> 16) & 0xffu) << 8;
    case 26:
        return 0x2E000u | (k->ctbir1 & 0xffu) << 8;
    case 27:
        return 0x32000u | ((k->ctbir1 >> 16) & 0xffu) << 8;
    case 28:
        return (k->ctppr0 & 0xffffu) << 8;
    case 29:
        return 0x49000000u | ((k->ctppr0 >> 16) & 0xffffu) << 8;
    case 30:
        return 0x40000000u | (k->ctppr1 & 0xffffu) << 8;
    case 31:
        return 0x80000000u | ((k->ctppr1 >> 16) & 0xffffu) << 8;
    default:
        return fixed[n & 31u];
    }
}

/* Register blocks: byte accesses become aligned word reads. */
static void regs_load(struct pru_core *c, const struct hit *h, uint8_t *dst, unsigned n,
                      int64_t at) {
    uint32_t first = h->ofs & ~3u;
    for (uint32_t w = first; w < h->ofs + n; w += 4) {
        uint32_t v = h->blk->read(c, w, at);
        for (unsigned b = 0; b < 4; b++) {
            uint32_t o = w + b;
            if (o >= h->ofs && o < h->ofs + n)
                dst[o - h->ofs] = (uint8_t)(v >> (8u * b));
        }
    }
}

/* ... and writes become aligned word writes with a bit mask of the bytes. */
static void regs_store(struct pru_core *c, const struct hit *h, const uint8_t *src, unsigned n,
                       int64_t at) {
    uint32_t first = h->ofs & ~3u;
    for (uint32_t w = first; w < h->ofs + n; w += 4) {
        uint32_t v = 0, bm = 0;
        for (unsigned b = 0; b < 4; b++) {
            uint32_t o = w + b;
            if (o >= h->ofs && o < h->ofs + n) {
                v |= (uint32_t)src[o - h->ofs] << (8u * b);
                bm |= 0xffu << (8u * b);
            }
        }
        h->blk->write(c, w, v, bm, at);
    }
}

static unsigned load_cycles(const struct pru_core *c, const struct hit *h, unsigned n) {
    switch (h->rg) {
    case RG_DRAM0:
    case RG_DRAM1:
    case RG_SHARED:
        return mem_local_load_cycles(c, n);
    case RG_BLOCK: {
        unsigned first;
        memcpy(&first, (const char *)&c->p + h->blk->load_cycles, sizeof first);
        return first + mem_beats(n) - 1;
    }
    default:
        return c->p.load_ext_cycles + mem_beats(n) - 1;
    }
}

/* How far ahead a value read from a block can be known unchanged (ff.c). */
static void note_horizon(struct pru_core *c, const struct hit *h) {
    if (!ff_input_read(c) || !h->blk->next_change)
        return;
    ff_horizon(c, h->blk->next_change(c, c->cycle, h->ofs & ~3u));
}

/* Block holding the byte at addr and how many bytes of n fit in it. */
static bool lookup(struct pru_core *c, uint32_t addr, unsigned n, struct hit *h, unsigned *chunk) {
    enum region rg =
        addr < LOCAL_LIMIT ? find_local(c, addr, 1, false, h) : find_ext(c, addr, 1, h);
    if (rg == RG_NONE)
        return false;
    unsigned left = h->size - h->ofs;
    *chunk = n < left ? n : left;
    return true;
}

/* Accesses may run from one block into an adjacent one (PRU0 into PRU1
 * data RAM on an 8 KB part); the first block decides the cost. A load that
 * faults part way leaves dst as it was. */
int mem_load_any(struct pru_core *c, uint32_t addr, uint8_t *out, unsigned n, unsigned *cycles) {
    uint8_t dst[128];
    if (n > sizeof dst) {
        core_fault(c, PRU_FAULT_BURST, addr);
        return -1;
    }
    for (unsigned done = 0, chunk; done < n; done += chunk) {
        struct hit h;
        if (!lookup(c, addr + done, n - done, &h, &chunk)) {
            core_fault(c, PRU_FAULT_UNMAPPED, addr + done);
            return -1;
        }
        if (done == 0)
            *cycles = load_cycles(c, &h, n);
        if (h.mem) {
            memcpy(dst + done, h.mem, chunk);
        } else {
            regs_load(c, &h, dst + done, chunk, c->cycle);
            note_horizon(c, &h);
        }
    }
    memcpy(out, dst, n);
    return 0;
}

int mem_store_any(struct pru_core *c, uint32_t addr, const uint8_t *src, unsigned n,
                  unsigned *cycles) {
    *cycles = mem_store_cycles(c, n);
    /* check the whole range first: a faulting store writes nothing */
    for (unsigned done = 0, chunk = 0; done < n; done += chunk) {
        struct hit h = {0};
        if (!lookup(c, addr + done, n - done, &h, &chunk)) {
            core_fault(c, PRU_FAULT_UNMAPPED, addr + done);
            return -1;
        }
    }
    for (unsigned done = 0, chunk = 0; done < n; done += chunk) {
        struct hit h = {0};
        lookup(c, addr + done, n - done, &h, &chunk);
        if (h.mem)
            memcpy(h.mem, src + done, chunk);
        else
            regs_store(c, &h, src + done, chunk, c->cycle + 1); /* lands next boundary */
    }
    return 0;
}

/* ---- host (ARM) view ---- */

static bool host_find(struct pru_core *c, uint32_t addr, size_t n, struct hit *h) {
    uint32_t base = pru_soc_base(c->soc);
    if (n > LOCAL_LIMIT)
        return false;
    if (addr < base || addr - base >= LOCAL_LIMIT)
        return find_ext(c, addr, (uint32_t)n, h) != RG_NONE;
    return find_local(c, addr - base, (uint32_t)n, true, h) != RG_NONE;
}

int pru_map_ext(struct pru_core *c, uint32_t base, uint32_t size) {
    if (c->n_ext >= sizeof c->ext / sizeof c->ext[0] || base < LOCAL_LIMIT || size == 0 ||
        (uint64_t)base + size > 0x100000000ull)
        return -1;
    for (unsigned i = 0; i < c->n_ext; i++)
        if (base < c->ext[i].base + c->ext[i].size && c->ext[i].base < base + size)
            return -1;
    uint8_t *mem = calloc(1, size);
    if (!mem)
        return -1;
    c->ext[c->n_ext++] = (struct ext_window){base, size, mem};
    return 0;
}

static bool running(const struct pru_core *c) {
    return (c->ctrl.control & PRU_CTRL_ENABLE) != 0;
}

/* The host sees a PRU-ICSS at global addresses, which are PRU0's local
 * view (docs/pru-facts.md §5.4), whichever core it is asked through.
 * Returns the core whose IRAM h is in (NULL: h is no IRAM); a PRU1 that is
 * a core of its own gets its IRAM1 hit moved to that core's IRAM. */
static struct pru_core *host_iram(struct pru_core *c, struct hit *h) {
    if (h->rg == RG_IRAM0)
        return c;
    if (h->rg != RG_IRAM1)
        return NULL;
    if (!c->pru1)
        return NULL; /* a core alone: PRU1's IRAM is plain storage */
    h->rg = RG_IRAM0;
    h->mem = (uint8_t *)c->pru1->iram0 + h->ofs;
    return c->pru1;
}

int pru_host_read(struct pru_core *c, uint32_t addr, void *buf, size_t n) {
    struct hit h;
    c = c->pru0;
    if (!host_find(c, addr, n, &h))
        return -1;
    struct pru_core *ic = host_iram(c, &h);
    if (ic && running(ic))
        return -2; /* locked out while RUNSTATE is 1, as on the SoC */
    if (h.mem)
        memcpy(buf, h.mem, n);
    else
        regs_load(c, &h, buf, (unsigned)n, c->cycle);
    return 0;
}

int pru_host_write(struct pru_core *c, uint32_t addr, const void *buf, size_t n) {
    struct hit h;
    c = c->pru0;
    if (!host_find(c, addr, n, &h))
        return -1;
    struct pru_core *ic = host_iram(c, &h);
    if (ic && running(ic)) {
        core_fault(ic, PRU_FAULT_IRAM_RUNNING, addr);
        return -2;
    }
    if (h.mem)
        memcpy(h.mem, buf, n);
    else
        regs_store(c, &h, buf, (unsigned)n, c->cycle);
    if (ic) {
        for (uint32_t w = h.ofs / 4u; w < (h.ofs + (uint32_t)n + 3u) / 4u; w++)
            predecode_word(ic, w);
    }
    return 0;
}

int pru_host_read32(struct pru_core *c, uint32_t addr, uint32_t *val) {
    if (addr & 3u)
        return -1;
    uint8_t b[4];
    int rc = pru_host_read(c, addr, b, 4);
    if (rc == 0)
        *val = (uint32_t)b[0] | (uint32_t)b[1] << 8 | (uint32_t)b[2] << 16 | (uint32_t)b[3] << 24;
    return rc;
}

int pru_host_write32(struct pru_core *c, uint32_t addr, uint32_t val) {
    if (addr & 3u)
        return -1;
    uint8_t b[4] = {(uint8_t)val, (uint8_t)(val >> 8), (uint8_t)(val >> 16), (uint8_t)(val >> 24)};
    return pru_host_write(c, addr, b, 4);
}
