/*
 * pruss.c - a PRU-ICSS of two cores (pruss.h): PRU1 borrows PRU0's RAMs
 * and shared blocks, and the two run in turns ordered by cycle.
 */
#include "pruss.h"

#include "core_priv.h"

#include <stdlib.h>

struct pru_icss {
    struct pru_core *core[2];
    bool lockstep; /* pru_icss_lockstep(): cycle by cycle, whatever run_ahead says */
};

struct pru_icss *pru_icss_new(enum pru_soc soc, const struct pru_params *params) {
    struct pru_icss *s = calloc(1, sizeof *s);
    if (!s)
        return NULL;
    s->core[0] = pru_core_new(soc, params);
    s->core[1] = pru_core_new(soc, params);
    if (!s->core[0] || !s->core[1]) {
        pru_icss_free(s);
        return NULL;
    }
    struct pru_core *p0 = s->core[0], *p1 = s->core[1];
    /* PRU1 sees data RAM1 at 0x0 and data RAM0 at 0x2000, the one shared
     * RAM, the scratch-pad banks, and the INTC, CFG and IEP of PRU0's core
     * (docs/pru-facts.md §5.1, §3) */
    free(p1->dram0);
    free(p1->dram1);
    free(p1->shared);
    p1->dram0 = p0->dram1;
    p1->dram1 = p0->dram0;
    p1->shared = p0->shared;
    p1->cfg_regs = p0->cfg_regs; /* one CFG block, one set of scratch-pad banks */
    p1->spad = p0->spad;
    p1->borrowed = true;
    p1->pru0 = p0;
    p1->pru1 = p1;
    p1->pru_idx = 1;
    p0->pru1 = p1;
    predecode_all(p0); /* the cross-PRU events (PD_XPRU) */
    predecode_all(p1);
    return s;
}

void pru_icss_free(struct pru_icss *s) {
    if (!s)
        return;
    pru_core_free(s->core[1]); /* first: it borrows from PRU0 */
    pru_core_free(s->core[0]);
    free(s);
}

struct pru_core *pru_icss_core(struct pru_icss *s, unsigned pru) {
    return pru < 2 ? s->core[pru] : NULL;
}

unsigned pru_core_index(const struct pru_core *c) {
    return c->pru_idx;
}

int64_t pru_icss_cycles(const struct pru_icss *s) {
    int64_t a = s->core[0]->cycle, b = s->core[1]->cycle;
    return a < b ? a : b;
}

/*
 * Cycle by cycle (run_ahead 0, or pins that join the two): the core behind
 * runs, PRU0 up to and including the cycle PRU1 is at, PRU1 up to but not
 * including the cycle PRU0 is at (an instruction may end a few cycles
 * after its limit). So whenever a core issues an instruction in cycle t,
 * the other has issued everything before t and nothing after it, and
 * within t PRU0's comes first: reads of the IEP and of the other's RAM
 * see that cycle's state. Each turn moves one core on by at least one
 * cycle (PRU1 runs only when it is behind).
 *
 * Run-ahead: the same order for every cross-PRU event, and none for the
 * rest. The core behind runs with that bound as its xlimit: it runs
 * everything that touches only itself (its registers, its pins, its GPI)
 * as far as the run's limit, and stops in front of the first cross-PRU
 * event (xpru_wait) at or past its xlimit; then the other, now behind,
 * runs the same way. A cross-PRU event is therefore issued only when the
 * other has issued everything before its cycle and (PRU1's) everything in
 * it, as cycle by cycle, and what a core runs between its events neither
 * sees nor changes anything the other does. TIMING.md "Two PRUs" lists
 * the events and why the list is complete.
 */
static enum pru_stop run_turns(struct pru_icss *s, int64_t cycle, bool ahead) {
    for (;;) {
        unsigned a = s->core[1]->cycle < s->core[0]->cycle;
        struct pru_core *c = s->core[a], *o = s->core[1 - a];
        if (c->cycle >= cycle)
            break; /* the one behind is there: both are */
        int64_t other = a == 0 ? o->cycle + 1 : o->cycle;
        int64_t to = other < cycle ? other : cycle;
        c->xlimit = ahead ? other : CYCLE_NEVER;
        if (exec_run(c, ahead ? cycle : to, false) == PRU_STOP_FAULT)
            return PRU_STOP_FAULT;
    }
    return PRU_STOP_LIMIT;
}

enum pru_stop pru_icss_run_until_cycle(struct pru_icss *s, int64_t cycle) {
    if (cycle >= PRU_MAX_CYCLE)
        cycle = PRU_MAX_CYCLE - 1;
    bool ahead = s->core[0]->p.run_ahead && !s->lockstep;
    enum pru_stop why = run_turns(s, cycle, ahead);
    s->core[0]->xlimit = s->core[1]->xlimit = CYCLE_NEVER; /* the host's turn */
    if (why == PRU_STOP_FAULT)
        return why;
    return s->core[0]->halted || s->core[1]->halted ? PRU_STOP_HALT : PRU_STOP_LIMIT;
}

void pru_icss_lockstep(struct pru_icss *s) {
    s->lockstep = true;
}

void xpru_exclusive(struct pru_core *c, uint32_t addr) {
    if (c->xlimit == CYCLE_NEVER)
        return; /* alone, or cycle by cycle */
    const struct pru_core *o = c->pru_idx ? c->pru0 : c->pru1;
    /* PRU1 must have issued nothing in this cycle or later, PRU0 nothing
     * after it; o->cycle bounds its last issue from above (an instruction
     * issued before may still be running: then this faults needlessly) */
    if (o && o->cycle > c->cycle + (int64_t)c->pru_idx)
        core_fault(c, PRU_FAULT_RUN_AHEAD, addr);
}

enum pru_stop pru_icss_run_until_time(struct pru_icss *s, int64_t t_ps) {
    int64_t cyc = t_ps <= 0 ? 0 : t_ps / PRU_PS_PER_CYCLE + (t_ps % PRU_PS_PER_CYCLE != 0);
    return pru_icss_run_until_cycle(s, cyc);
}
