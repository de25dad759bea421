/*
 * exec_mem.c - instructions that move bytes between the register file and
 * other register-file bytes or the scratch pads: XFR (XIN/XOUT/XCHG, ZERO,
 * FILL) and MVIx, and what moving bytes into R30/R31 or out of R31 implies
 * (bursts: exec_burst() in exec_priv.h).
 *
 * The register file is 128 bytes, little-endian: byte 4*n + k is rn.bk.
 */
#include "exec_priv.h"

#include <string.h>

static uint8_t *rf(struct pru_core *c) {
    return (uint8_t *)c->r;
}

/* Before reading register-file bytes [start, start+n): refresh R31. */
void rf_before_read(struct pru_core *c, unsigned start, unsigned n) {
    if (start + n > 124u)
        c->r[31] = gpi_r31(c, c->cycle);
}

/* After writing register-file bytes [start, start+n). */
void rf_after_write(struct pru_core *c, unsigned start, unsigned n, int64_t end_cycle) {
    unsigned end = start + n;
    if (start < 124u && end > 120u)
        exec_r30_changed(c, end_cycle);
    if (end > 124u) {
        uint32_t mask = 0;
        for (unsigned b = start > 124u ? start : 124u; b < end; b++)
            mask |= 0xffu << (8u * (b - 124u));
        exec_r31_written(c, mask);
    }
}

#define CFG_SPP          0x34u     /* CFG scratch-pad priority and shift */
#define SPP_XFR_SHIFT_EN (1u << 1) /* R0[4:0] offsets XFR to/from the banks */

/* The register offset of the XFR shift: R0[4:0] with SPP.XFR_SHIFT_EN, else
 * 0; negative when pru_params.xfr_shift_sub says the shift goes down. */
static int xfr_shift(const struct pru_core *c) {
    if (!(c->cfg_regs[CFG_SPP / 4] & SPP_XFR_SHIFT_EN))
        return 0;
    int s = (int)(c->r[0] & 0x1fu);
    return c->p.xfr_shift_sub ? -s : s;
}

/* Bank byte for register-file byte b under shift s (modulo 32 registers);
 * -1 for bank registers 30 and 31, which do not exist. */
static int bank_byte(unsigned b, int s) {
    unsigned reg = (unsigned)((int)(b / 4u) + s) & 0x1fu;
    return 4u * reg >= SPAD_BYTES ? -1 : (int)(4u * reg + b % 4u);
}

/* XIN/XOUT/XCHG on a scratch-pad bank (device 10, 11, 12), register-file
 * bytes [start, start + n), bank bytes shifted by s registers. */
static int xfr_spad(struct pru_core *c, unsigned op, uint8_t *bank, unsigned start, unsigned n,
                    int s) {
    bool in = op == PRU_OP_XIN || op == PRU_OP_SXIN;
    bool out = op == PRU_OP_XOUT || op == PRU_OP_SXOUT;
    int map[RF_BYTES];
    for (unsigned i = 0; i < n; i++)
        if ((map[i] = bank_byte(start + i, s)) < 0)
            return -1;
    if (!in)
        rf_before_read(c, start, n);
    for (unsigned i = 0; i < n; i++) {
        uint8_t r = rf(c)[start + i], b = bank[map[i]];
        if (in || (!out && !c->p.xchg_swaps)) {
            rf(c)[start + i] = b;
        } else if (out) {
            bank[map[i]] = r;
        } else {
            rf(c)[start + i] = b;
            bank[map[i]] = r;
        }
    }
    if (!out)
        rf_after_write(c, start, n, c->cycle + 1);
    if (!in)
        ff_dirty(c);
    return 0;
}

/* PRU0 issues before PRU1 within a cycle (pruss.c), so when PRU1 issues
 * an XFR in cycle t, PRU0's mark for t on that bank is there already. */
static bool spad_collides_at(const struct pru_core *c, unsigned dev, int64_t cycle) {
    return c->pru_idx == 1 && dev >= 10u && dev <= 12u && c->pru0->spad_cycle[dev - 10u] == cycle;
}

bool spad_collides(const struct pru_core *c, unsigned dev) {
    return spad_collides_at(c, dev, c->cycle);
}

/* The documented collision: both PRUs on one bank in one cycle, PRU0 goes
 * first and PRU1 stalls (pru_params.spad_stall_cycles). The XFR issues in
 * `cycle`. */
static unsigned spad_arbitrate(struct pru_core *c, unsigned dev, int64_t cycle) {
    c->spad_cycle[dev - 10u] = cycle;
    if (!spad_collides_at(c, dev, cycle))
        return 0;
    c->spad_collisions++;
    return c->p.spad_stall_cycles;
}

unsigned exec_xfr(struct pru_core *c, const struct pd *d) {
    const struct pru_insn *in = &d->in;
    unsigned n = pru_len_bytes(in->len, c->r[0]);
    unsigned start = 4u * in->rx + in->rxbyte;
    unsigned dev = in->dev;
    bool is_in = in->op == PRU_OP_XIN || in->op == PRU_OP_SXIN;
    int s = xfr_shift(c);

    unsigned stall = 0;
    if (n == 0 || start + n > RF_BYTES) {
        core_fault(c, PRU_FAULT_BURST, dev);
        return 0;
    }
    if ((dev == 254u || dev == 255u) && is_in) { /* FILL / ZERO */
        if (c->p.xfr_shift_fill && s) {
            int at = (int)start + 4 * s;
            if (at < 0 || at + (int)n > (int)RF_BYTES) {
                core_fault(c, PRU_FAULT_BURST, dev);
                return 0;
            }
            start = (unsigned)at;
        }
        memset(rf(c) + start, dev == 255u ? 0x00 : 0xff, n);
        rf_after_write(c, start, n, c->cycle + 1);
    } else if (dev >= 10u && dev <= 12u) {
        if (start + n > SPAD_BYTES || xfr_spad(c, in->op, c->spad[dev - 10u], start, n, s)) {
            core_fault(c, PRU_FAULT_BURST, dev);
            return 0;
        }
        stall = spad_arbitrate(c, dev, c->cycle);
    } else {
        core_fault(c, PRU_FAULT_XFR_DEVICE, dev);
        return 0;
    }
    c->pc++;
    return stall;
}

/*
 * PD_XFR_FIXED, issued in `cycle` (c->pc and c->cycle may lag): what
 * exec_xfr() does for a fixed length within r0..r29 (no R30/R31 effect),
 * the bank side in one copy, which it is when the shifted bank registers
 * are all below 30 (they then follow each other: exec_xfr() maps each byte
 * modulo 32 registers and faults on bank registers 30 and 31). Returns the
 * stall cycles, or -1 with nothing done for the general path (a fault, a
 * shifted ZERO/FILL with xfr_shift_fill).
 */
int exec_xfr_fixed(struct pru_core *c, const struct pd *d, int64_t cycle) {
    unsigned op = d->in.op, dev = d->in.dev;
    unsigned n = d->imm, start = d->target;
    int s = xfr_shift(c);
    if (dev >= 254u) { /* ZERO / FILL (XIN only) */
        if (c->p.xfr_shift_fill && s)
            return -1;
        memset(rf(c) + start, dev == 255u ? 0x00 : 0xff, n);
        return 0;
    }
    unsigned first = (unsigned)((int)(start / 4u) + s) & 0x1fu;
    if (4u * first + start % 4u + n > SPAD_BYTES)
        return -1;
    uint8_t *bank = c->spad[dev - 10u] + 4u * first + start % 4u;
    if (op == PRU_OP_XIN || op == PRU_OP_SXIN) {
        burst_copy(rf(c) + start, bank, n);
    } else {
        burst_copy(bank, rf(c) + start, n);
        ff_dirty(c);
    }
    return (int)spad_arbitrate(c, dev, cycle);
}

/* MVIx: register-file pointers are byte fields of r1; addresses wrap at 128. */
static uint32_t mvi_read(struct pru_core *c, unsigned addr, unsigned size) {
    uint32_t v = 0;
    rf_before_read(c, addr, size); /* a read that wraps past byte 127 covers R31 */
    for (unsigned i = 0; i < size; i++)
        v |= (uint32_t)rf(c)[(addr + i) & 0x7fu] << (8u * i);
    return v;
}

static void mvi_write(struct pru_core *c, unsigned addr, unsigned size, uint32_t v) {
    for (unsigned i = 0; i < size; i++) {
        unsigned a = (addr + i) & 0x7fu;
        rf(c)[a] = (uint8_t)(v >> (8u * i));
        rf_after_write(c, a, 1, c->cycle + 1);
    }
}

/* Pointer field value; pre-decrement / post-increment update it. */
static unsigned mvi_ptr(struct pru_core *c, unsigned reg, unsigned sel, unsigned mode,
                        unsigned size, bool post) {
    unsigned sh = pru_sel_shift(sel);
    uint32_t m = pru_sel_mask(sel);
    uint32_t p = fld(c->r, reg, sh, m);
    if (!post && mode == PRU_MVI_PREDEC) {
        p = (p - size) & m;
        fld_set(c->r, reg, sh, m, p);
    }
    if (post && mode == PRU_MVI_POSTINC)
        fld_set(c->r, reg, sh, m, p + size);
    return p;
}

void exec_mvi(struct pru_core *c, const struct pd *d) {
    const struct pru_insn *in = &d->in;
    unsigned size = 1u << in->mvi_size;
    uint32_t smask = size == 4 ? 0xffffffffu : (1u << (8u * size)) - 1u;
    uint32_t v;

    if (in->mvi_smode == PRU_MVI_DIRECT) {
        if (in->rs1 == 31)
            c->r[31] = gpi_r31(c, c->cycle);
        v = fld(c->r, in->rs1, pru_sel_shift(in->rs1sel), pru_sel_mask(in->rs1sel)) & smask;
    } else {
        unsigned a = mvi_ptr(c, in->rs1, in->rs1sel, in->mvi_smode, size, false);
        v = mvi_read(c, a, size);
        mvi_ptr(c, in->rs1, in->rs1sel, in->mvi_smode, size, true);
    }
    if (in->mvi_dmode == PRU_MVI_DIRECT) {
        unsigned sh = pru_sel_shift(in->rdsel);
        fld_set(c->r, in->rd, sh, pru_sel_mask(in->rdsel), v);
        if (in->rd >= 30)
            rf_after_write(c, 4u * in->rd + sh / 8u, pru_sel_width(in->rdsel) / 8u, c->cycle + 1);
    } else {
        unsigned a = mvi_ptr(c, in->rd, in->rdsel, in->mvi_dmode, size, false);
        mvi_write(c, a, size, v);
        mvi_ptr(c, in->rd, in->rdsel, in->mvi_dmode, size, true);
    }
    c->pc++;
}
