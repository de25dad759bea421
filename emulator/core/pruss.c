/*
 * pruss.c - a PRU-ICSS of two cores (pruss.h): PRU1 borrows PRU0's RAMs
 * and shared blocks, and the two run in turns ordered by cycle.
 */
#include "pruss.h"

#include "core_priv.h"

#include <stdlib.h>

struct pru_icss {
    struct pru_core *core[2];
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
 * The core behind runs: PRU0 up to and including the cycle PRU1 is at,
 * PRU1 up to but not including the cycle PRU0 is at (an instruction may
 * end a few cycles after its limit). So whenever a core issues an
 * instruction in cycle t, the other has issued everything before t and
 * nothing after it, and within t PRU0's comes first: reads of the IEP and
 * of the other's RAM see that cycle's state. Each turn moves one core on
 * by at least one cycle (PRU1 runs only when it is behind).
 */
enum pru_stop pru_icss_run_until_cycle(struct pru_icss *s, int64_t cycle) {
    if (cycle >= PRU_MAX_CYCLE)
        cycle = PRU_MAX_CYCLE - 1;
    for (;;) {
        unsigned a = s->core[1]->cycle < s->core[0]->cycle;
        struct pru_core *c = s->core[a], *o = s->core[1 - a];
        if (c->cycle >= cycle)
            break; /* the one behind is there: both are */
        int64_t other = a == 0 ? o->cycle + 1 : o->cycle;
        int64_t to = other < cycle ? other : cycle;
        if (exec_run(c, to, false) == PRU_STOP_FAULT)
            return PRU_STOP_FAULT;
    }
    return s->core[0]->halted || s->core[1]->halted ? PRU_STOP_HALT : PRU_STOP_LIMIT;
}

enum pru_stop pru_icss_run_until_time(struct pru_icss *s, int64_t t_ps) {
    int64_t cyc = t_ps <= 0 ? 0 : t_ps / PRU_PS_PER_CYCLE + (t_ps % PRU_PS_PER_CYCLE != 0);
    return pru_icss_run_until_cycle(s, cyc);
}
