/*
 * core.c - creation, parameters, SoC geometry, faults and the run API of
 * the PRU core emulator.
 */
#include "core_priv.h"

#include <stdlib.h>
#include <string.h>

void pru_params_default(struct pru_params *p) {
    /* Sources and reasoning for each value: TIMING.md. */
    p->load_local_base = 2;
    p->store_beat_cycles = 1;
    p->load_cfg_cycles = 3;
    p->load_intc_cycles = 3;
    p->load_ctrl_cycles = 4;
    p->load_iep_cycles = 3;
    p->load_ext_cycles = 36;
    p->xchg_swaps = 1;
    p->xfr_shift_sub = 0;
    p->xfr_shift_fill = 0;
    p->spad_stall_cycles = 1;
    p->gpi_delay_ps = 2 * PRU_PS_PER_CYCLE;
    p->gpo_delay_ps = 0;
    p->shift_phase_ps = 0;
    p->shift_frac = PRU_FRAC_EXACT;
    p->fast_forward = 1;
    p->ff_counted = 1;
    p->ff_r31_bits = 1;
    p->ff_loop_delay = 1;
    p->ff_count_loop = 1;
    p->fast_loop = 1;
    p->leaf_call = 1;
    p->straight_run = 1;
    p->run_ahead = 1;
    p->strict = 0;
    p->strict_everywhere = 0;
    p->strict_window = PRU_STRICT_DEFAULT_WINDOW;
    p->strict_log = 0;
    p->contend_period = 0;
    p->contend_stall = 1;
    p->contend_phase = 0;
    p->contend_random = 0;
    p->contend_seed = 0;
}

int pru_params_fast_path_off(struct pru_params *p, const char *name) {
    if (!name)
        return -1;
    if (strcmp(name, "ff") == 0)
        p->fast_forward = 0;
    else if (strcmp(name, "ff-counted") == 0)
        p->ff_counted = 0;
    else if (strcmp(name, "ff-r31-bits") == 0)
        p->ff_r31_bits = 0;
    else if (strcmp(name, "ff-loop-delay") == 0)
        p->ff_loop_delay = 0;
    else if (strcmp(name, "ff-count-loop") == 0)
        p->ff_count_loop = 0;
    else if (strcmp(name, "fast-loop") == 0)
        p->fast_loop = 0;
    else if (strcmp(name, "leaf-call") == 0)
        p->leaf_call = 0;
    else if (strcmp(name, "straight-run") == 0)
        p->straight_run = 0;
    else if (strcmp(name, "run-ahead") == 0)
        p->run_ahead = 0;
    else
        return -1;
    return 0;
}

static const struct {
    const char *name;
    uint32_t base, iram, dram, shared;
} socs[] = {
    [PRU_SOC_AM335X] = {"am335x", PRUSS_AM335X_BASE, PRUSS_AM335X_IRAM0_BYTES,
                        PRUSS_AM335X_DRAM0_BYTES, PRUSS_AM335X_SHARED_BYTES},
    [PRU_SOC_AM437X_ICSS0] = {"am437x-icss0", PRUSS_AM437X_ICSS0_BASE,
                              PRUSS_AM437X_ICSS0_IRAM0_BYTES, PRUSS_AM437X_ICSS0_DRAM0_BYTES,
                              PRUSS_AM437X_ICSS0_SHARED_BYTES},
    [PRU_SOC_AM437X_ICSS1] = {"am437x-icss1", PRUSS_AM437X_ICSS1_BASE,
                              PRUSS_AM437X_ICSS1_IRAM0_BYTES, PRUSS_AM437X_ICSS1_DRAM0_BYTES,
                              PRUSS_AM437X_ICSS1_SHARED_BYTES},
};

int pru_soc_from_name(const char *name, enum pru_soc *soc) {
    for (unsigned i = 0; i < sizeof socs / sizeof socs[0]; i++) {
        if (strcmp(name, socs[i].name) == 0) {
            *soc = (enum pru_soc)i;
            return 0;
        }
    }
    return -1;
}

const char *pru_soc_name(enum pru_soc soc) {
    return socs[soc].name;
}

uint32_t pru_soc_base(enum pru_soc soc) {
    return socs[soc].base;
}

uint32_t pru_iram_bytes(const struct pru_core *c) {
    return c->iram_bytes;
}

uint32_t pru_dram_bytes(const struct pru_core *c) {
    return c->dram_bytes;
}

uint32_t pru_shared_bytes(const struct pru_core *c) {
    return c->shared_bytes;
}

struct pru_core *pru_core_new(enum pru_soc soc, const struct pru_params *params) {
    if ((unsigned)soc > PRU_SOC_AM437X_ICSS1)
        return NULL;
    struct pru_core *c = calloc(1, sizeof *c);
    if (!c)
        return NULL;
    if (params)
        c->p = *params;
    else
        pru_params_default(&c->p);
    c->soc = soc;
    c->pru0 = c; /* alone until pruss.c pairs it */
    c->xlimit = CYCLE_NEVER;
    c->cfg_regs = c->own_cfg;
    c->spad = c->own_spad;
    for (unsigned i = 0; i < 3; i++)
        c->spad_cycle[i] = -1;
    c->watch_addr = UINT32_MAX;
    c->iram_bytes = socs[soc].iram;
    c->dram_bytes = socs[soc].dram;
    c->shared_bytes = socs[soc].shared;
    c->iram_words = c->iram_bytes / 4;
    c->dram0 = calloc(1, c->dram_bytes);
    c->dram1 = calloc(1, c->dram_bytes);
    c->shared = calloc(1, c->shared_bytes ? c->shared_bytes : 1);
    c->iram0 = calloc(c->iram_words, 4);
    c->iram1 = calloc(c->iram_words, 4);
    /* + the end of IRAM (predecode.c); one cache line each */
    c->pd = aligned_alloc(_Alignof(struct pd), (c->iram_words + 1u) * sizeof *c->pd);
    if (c->pd)
        memset(c->pd, 0, (c->iram_words + 1u) * sizeof *c->pd);
    if (!c->dram0 || !c->dram1 || !c->shared || !c->iram0 || !c->iram1 || !c->pd) {
        pru_core_free(c);
        return NULL;
    }
    c->loop_end = NO_LOOP;
    c->ff.top = NO_LOOP;
    for (unsigned i = 0; i < FF_BODIES; i++)
        c->ff.body[i].top = 1; /* no body decoded yet */
    /* strict and contention see every instruction: no fast path skips one */
    c->checked = c->p.strict != 0 || c->p.contend_period != 0;
    c->ff_on = c->p.fast_forward != 0 && !c->checked;
    strict_reset(c);
    for (size_t i = 0; i < icss_nblocks; i++)
        if (icss_blocks[i]->reset)
            icss_blocks[i]->reset(c);
    predecode_all(c);
    return c;
}

void pru_core_free(struct pru_core *c) {
    if (!c)
        return;
    if (!c->borrowed) {
        free(c->dram0);
        free(c->dram1);
        free(c->shared);
    }
    free(c->iram0);
    free(c->iram1);
    free(c->pd);
    for (unsigned i = 0; i < c->n_ext; i++)
        free(c->ext[i].mem);
    free(c);
}

void core_fault(struct pru_core *c, enum pru_fault_cause cause, uint32_t addr) {
    if (c->fault.cause != PRU_FAULT_NONE)
        return; /* keep the first one */
    c->fault.cause = cause;
    c->fault.pc = c->pc;
    c->fault.cycle = c->cycle;
    c->fault.addr = addr;
    c->fault.word = c->pc < c->iram_words ? c->iram0[c->pc] : 0;
    c->stop = true;
    c->stop_reason = PRU_STOP_FAULT;
}

const struct pru_fault *pru_get_fault(const struct pru_core *c) {
    return &c->fault;
}

const char *pru_fault_name(enum pru_fault_cause cause) {
    static const char *const names[] = {
        [PRU_FAULT_NONE] = "none",
        [PRU_FAULT_BAD_OPCODE] = "invalid or unsupported opcode",
        [PRU_FAULT_UNMAPPED] = "access to unmapped memory",
        [PRU_FAULT_PC_RANGE] = "PC past the end of IRAM",
        [PRU_FAULT_IRAM_RUNNING] = "IRAM write while the PRU is running",
        [PRU_FAULT_BURST] = "bad burst length or register file overrun",
        [PRU_FAULT_XFR_DEVICE] = "XFR device not modelled",
        [PRU_FAULT_GPO_SHIFT] = "GPO shift-out mode enabled (not modelled)",
        [PRU_FAULT_UNSUPPORTED] = "unsupported peripheral mode",
        [PRU_FAULT_STRICT] = "strict-mode rule broken",
        [PRU_FAULT_RUN_AHEAD] = "cross-PRU access the run-ahead cannot order (rerun with "
                                "--no-fast-path run-ahead)",
    };
    return (unsigned)cause < sizeof names / sizeof names[0] ? names[cause] : "unknown";
}

void pru_print_fault(const struct pru_core *c, FILE *f) {
    const struct pru_fault *ft = &c->fault;
    if (ft->cause == PRU_FAULT_STRICT) {
        strict_print_fault(c, f);
        return;
    }
    fprintf(f, "fault: %s at pc=0x%04x cycle=%lld (addr=0x%08x, word=0x%08x)\n",
            pru_fault_name(ft->cause), ft->pc, (long long)ft->cycle, ft->addr, ft->word);
}

int pru_load_image(struct pru_core *c, const void *image, size_t bytes) {
    if (bytes > c->iram_bytes)
        return -1;
    uint8_t *buf = calloc(1, c->iram_bytes);
    if (!buf)
        return -1;
    memcpy(buf, image, bytes);
    uint32_t iram = c->pru_idx ? PRU_OFS_IRAM1 : PRU_OFS_IRAM0;
    int rc = pru_host_write(c, pru_soc_base(c->soc) + iram, buf, c->iram_bytes);
    free(buf);
    return rc;
}

void pru_start(struct pru_core *c) {
    uint32_t v = ctrl_read(c, 0, c->cycle);
    ctrl_write(c, 0, v | PRU_CTRL_ENABLE, 0xffffffffu, c->cycle);
}

void pru_stop(struct pru_core *c) {
    uint32_t v = ctrl_read(c, 0, c->cycle);
    ctrl_write(c, 0, v & ~PRU_CTRL_ENABLE, 0xffffffffu, c->cycle);
}

void pru_set_store_watch(struct pru_core *c, uint32_t addr, void (*fn)(void *ctx, uint32_t addr),
                         void *ctx) {
    c->watch_fn = fn;
    c->watch_ctx = ctx;
    c->watch_addr = fn ? addr : UINT32_MAX;
}

void pru_set_pins(struct pru_core *c, const struct pru_pins *pins) {
    if (pins) {
        c->pins = *pins;
        c->have_pins = pins->inputs_at != NULL;
        if (!c->have_pins)
            c->pins.inputs_run = NULL; /* used only with inputs_at */
    } else {
        memset(&c->pins, 0, sizeof c->pins);
        c->have_pins = false;
    }
}

void pru_set_inputs(struct pru_core *c, uint32_t levels) {
    c->const_inputs = levels;
}

void pru_set_trace(struct pru_core *c, FILE *f) {
    c->trace = f;
    c->trace_on = f != NULL;
}

enum pru_stop pru_run_until_cycle(struct pru_core *c, int64_t cycle) {
    return exec_run(c, cycle, false);
}

enum pru_stop pru_run_until_time(struct pru_core *c, int64_t t_ps) {
    /* run every cycle that starts before t_ps */
    int64_t cyc = t_ps <= 0 ? 0 : t_ps / PRU_PS_PER_CYCLE + (t_ps % PRU_PS_PER_CYCLE != 0);
    return exec_run(c, cyc, false);
}

enum pru_stop pru_run(struct pru_core *c, int64_t max_cycles) {
    int64_t limit = max_cycles > INT64_MAX - c->cycle ? INT64_MAX : c->cycle + max_cycles;
    return exec_run(c, limit, false);
}

enum pru_stop pru_step(struct pru_core *c) {
    return exec_run(c, INT64_MAX, true);
}

int64_t pru_cycles(const struct pru_core *c) {
    return c->cycle;
}

int64_t pru_time_ps(const struct pru_core *c) {
    return c->cycle * PRU_PS_PER_CYCLE;
}

uint64_t pru_instructions(const struct pru_core *c) {
    return c->insns;
}

uint32_t pru_pc(const struct pru_core *c) {
    return c->pc;
}

void pru_set_pc(struct pru_core *c, uint32_t pc) {
    c->pc = pc & 0xffffu;
}

uint32_t pru_reg(struct pru_core *c, unsigned n) {
    if (n > 31)
        return 0;
    if (n == 31)
        return gpi_r31(c, c->cycle);
    return c->r[n];
}

void pru_set_reg(struct pru_core *c, unsigned n, uint32_t v) {
    if (n < 31)
        c->r[n] = v;
}

int pru_carry(const struct pru_core *c) {
    return c->carry;
}

int pru_halted(const struct pru_core *c) {
    return c->halted;
}

int pru_sleeping(const struct pru_core *c) {
    return c->sleeping;
}

uint64_t pru_ff_skipped(const struct pru_core *c) {
    return c->ff.skipped;
}
