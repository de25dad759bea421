/*
 * exec_priv.h - handlers of the execute loop that live outside exec.c.
 */
#ifndef PRU_EXEC_PRIV_H
#define PRU_EXEC_PRIV_H

#include "core_priv.h"

#include <string.h>

#define RF_BYTES 128u /* the register file, byte 4n + k is rn.bk */

/* exec_mem.c: XIN/XOUT/XCHG/ZERO/FILL, MVIx; register-file side effects */
/* Returns the cycles PRU1 stalls for a scratch-pad collision (else 0). */
unsigned exec_xfr(struct pru_core *c, const struct pd *d);
void exec_mvi(struct pru_core *c, const struct pd *d);
int exec_xfr_fixed(struct pru_core *c, const struct pd *d, int64_t cycle);
void rf_before_read(struct pru_core *c, unsigned start, unsigned n);
void rf_after_write(struct pru_core *c, unsigned start, unsigned n, int64_t end_cycle);

/* exec.c */
void exec_r30_changed(struct pru_core *c, int64_t end_cycle);
void exec_r31_written(struct pru_core *c, uint32_t written_mask);
void exec_recheck(struct pru_core *c);
bool exec_simple_step(uint32_t *r, const struct pd *d, unsigned kind, uint32_t *pc, int *carry);

/*
 * LBBO/SBBO/LBCO/SBCO at pc, issued in cycle `cycle` (c->pc and c->cycle
 * may lag: they are brought up to date before anything reads them, a
 * store watch included): the one
 * implementation of loads and stores. Every target goes through
 * mem_load()/mem_store() (which also cost it); a load that faults part way
 * leaves the registers as they were; bytes into R30/R31 or out of R31 have
 * their effects. Returns the cycles (the caller advances pc unless it
 * faulted). Inline: the execute loop's fast path runs it in place.
 */
static inline __attribute__((always_inline)) unsigned
exec_burst(struct pru_core *c, const struct pd *d, uint32_t pc, int64_t cycle) {
    const struct pru_insn *in = &d->in;
    bool fixed = d->burst_bytes != 0; /* fixed length, registers below r30 */
    unsigned n = fixed ? d->burst_bytes : pru_len_bytes(in->len, c->r[0]);
    unsigned start = fixed ? d->burst_rf : 4u * in->rx + in->rxbyte;
    uint32_t base = d->flags & PD_BURST_CBASE ? const_table(c, in->base) : c->r[in->base];
    uint32_t addr = base + (fld(c->r, d->rs2, d->rs2sh, d->rs2mask) | d->imm);
    uint8_t *rf = (uint8_t *)c->r + start;
    unsigned cycles = 1;

    if (!fixed && (n == 0 || start + n > RF_BYTES)) {
        c->pc = pc;
        c->cycle = cycle;
        core_fault(c, PRU_FAULT_BURST, addr);
        return 1;
    }
    if (d->flags & PD_BURST_LOAD) {
        if (mem_load(c, addr, rf, n, &cycles, pc, cycle) != 0)
            return 1;
        if (!fixed)
            rf_after_write(c, start, n, cycle + cycles);
    } else {
        if (!fixed)
            rf_before_read(c, start, n);
        if (mem_store(c, addr, rf, n, &cycles, pc, cycle) != 0)
            return 1;
        ff_dirty(c);
    }
    return cycles;
}

#endif
