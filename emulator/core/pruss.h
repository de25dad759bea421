/*
 * pruss.h - both PRUs of one PRU-ICSS, run cycle by cycle together.
 *
 * Two cores (pru_core.h) that share what the subsystem has once: the IEP
 * timer, the INTC, the CFG block (GPCFG0 drives PRU0's GPI, GPCFG1
 * PRU1's), the three scratch-pad banks (XIN/XOUT 10..12: what one PRU
 * puts there the other reads), the shared RAM and the two data RAMs, each
 * PRU seeing its own at local 0x0 and the other's at 0x2000
 * (docs/pru-facts.md §5.1). Each
 * core keeps its own registers, CONTROL block, IRAM, pins and constant
 * table. The host reaches the whole subsystem through either core at the
 * global addresses (PRU1's data RAM at +0x2000, its CONTROL at +0x24000,
 * its IRAM at +0x38000).
 *
 * Running: the cores take turns so that every instruction that one PRU
 * can observe of the other (a cross-PRU event: memory, scratch pad,
 * INTC, ... TIMING.md "Two PRUs") is executed in the order of the cycles
 * it is issued in (PRU0 first within a cycle): so both see the IEP count,
 * the other's stores and shared RAM as they are in that cycle. Between
 * its events a core runs ahead (pru_params.run_ahead; with 0 both run
 * cycle by cycle, with the same results).
 *
 * Both on one scratch-pad bank in one cycle: PRU0 goes first and PRU1
 * stalls (pru_params.spad_stall_cycles, docs/pru-facts.md §3). Not shared:
 * the system-bus windows (pru_map_ext() maps for one core). A PRU's
 * Cnt_16 event reaches the INTC when that PRU's GPI is next evaluated.
 */
#ifndef PRUSS_H
#define PRUSS_H

#include "pru_core.h"

struct pru_icss;

/* A PRU-ICSS of soc with both PRUs disabled at PC 0; params (NULL: the
 * defaults) apply to both. NULL when out of memory or soc is unknown. */
struct pru_icss *pru_icss_new(enum pru_soc soc, const struct pru_params *params);
void pru_icss_free(struct pru_icss *s);

/* PRU 0 or 1 (NULL for any other index). Use it with the pru_core.h calls:
 * load an image (pru_load_image() loads that PRU's IRAM), start, set pins,
 * watch stores, read registers. Do not run a core alone: a core must not
 * get ahead of the other, run the subsystem. */
struct pru_core *pru_icss_core(struct pru_icss *s, unsigned pru);
/* Which PRU a core is: 0 or 1 (0 for a core alone). */
unsigned pru_core_index(const struct pru_core *c);

/* Runs both PRUs until both have reached the cycle (or time). A PRU that
 * is disabled or halted lets its time pass; the run stops early only at a
 * fault (PRU_STOP_FAULT; pru_get_fault() of the core says which).
 * Returns PRU_STOP_HALT if a PRU halted on the way or before, else
 * PRU_STOP_LIMIT. The limit must be below PRU_MAX_CYCLE. */
enum pru_stop pru_icss_run_until_cycle(struct pru_icss *s, int64_t cycle);
enum pru_stop pru_icss_run_until_time(struct pru_icss *s, int64_t t_ps);
/* The PRUs see each other through their pins (one's R30 drives the
 * other's R31, e.g. a master and an encoder firmware on one cable): pins
 * are then cross-PRU too, and the two run cycle by cycle whatever
 * pru_params.run_ahead says. */
void pru_icss_lockstep(struct pru_icss *s);
/* The time both PRUs have reached (the earlier of their clocks). */
int64_t pru_icss_cycles(const struct pru_icss *s);

#endif
