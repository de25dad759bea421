/*
 * exec_priv.h - handlers of the execute loop that live outside exec.c.
 */
#ifndef PRU_EXEC_PRIV_H
#define PRU_EXEC_PRIV_H

#include "core_priv.h"

/* exec_mem.c: LBBO/SBBO/LBCO/SBCO (returns cycles), XIN/XOUT/XCHG/ZERO/FILL, MVIx */
unsigned exec_burst(struct pru_core *c, const struct pd *d, bool load, bool cbase);
void exec_xfr(struct pru_core *c, const struct pd *d);
void exec_mvi(struct pru_core *c, const struct pd *d);

/* exec.c */
void exec_r30_changed(struct pru_core *c, int64_t end_cycle);
void exec_r31_written(struct pru_core *c, uint32_t written_mask);
void exec_recheck(struct pru_core *c);

#endif
