/*
 * pru_core.h - cycle-exact emulator of one PRU core of an AM335x or AM437x
 * PRU-ICSS, with the ICSS blocks the BiSS-C firmware touches. A core made
 * here is PRU0 with the PRU-ICSS to itself; both PRUs together, sharing the
 * blocks: pruss.h.
 *
 * Time: 1 PRU cycle = 5000 ps; cycle c starts at t = c * 5000 ps. The core
 * keeps one clock (pru_cycles()) that advances while the PRU runs, sleeps or
 * is halted and time is advanced with pru_run_until_*().
 *
 * The host side sees the PRU-ICSS through the same global addresses as the
 * ARM (pru_host_read32/write32 and friends), so a host library drives the
 * emulator exactly as it drives silicon: load IRAM while halted, write data
 * RAM, start and stop through CONTROL.
 *
 * Timing assumptions and their parameters: emulator/core/TIMING.md.
 */
#ifndef PRU_CORE_H
#define PRU_CORE_H

#include "pruss/pruss_map.h"

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#define PRU_PS_PER_CYCLE 5000
/* Simulated time is bounded so that times in ps never overflow (~52 days). */
#define PRU_MAX_CYCLE (INT64_MAX / PRU_PS_PER_CYCLE / 4)

enum pru_soc {
    PRU_SOC_AM335X,
    PRU_SOC_AM437X_ICSS0, /* 4 KB IRAM / data RAM, no shared RAM */
    PRU_SOC_AM437X_ICSS1,
};

/* How a divide ratio with a .5 (or .25) part places shift-clock edges. */
enum pru_frac_mode {
    PRU_FRAC_EXACT, /* edges at the exact average rate (both 200 MHz clock edges usable) */
    PRU_FRAC_CYCLE, /* edges rounded down to a PRU clock edge (periods alternate) */
};

/* Emulation parameters for behaviour the documentation leaves open.
 * pru_params_default() fills the documented defaults (TIMING.md). */
struct pru_params {
    /* Local loads (own/other data RAM, shared RAM): base + ceil(N/4) cycles. */
    unsigned load_local_base;
    /* Stores anywhere: ceil(N/4) * store_beat_cycles, at least 1. */
    unsigned store_beat_cycles;
    /* Loads of 4 bytes from ICSS registers; + ceil(N/4) - 1 for longer bursts. */
    unsigned load_cfg_cycles, load_intc_cycles, load_ctrl_cycles, load_iep_cycles;
    /* Loads from the system bus (L3/L4, external windows); + ceil(N/4) - 1. */
    unsigned load_ext_cycles;
    /* XCHG to a scratch pad: 1 swaps register and bank, 0 behaves like XIN. */
    int xchg_swaps;
    /* The scratch-pad register shift (CFG SPP bit 1, XFR_SHIFT_EN: R0[4:0] is
     * an offset in 32-bit registers for XIN/XOUT/XCHG on banks 10-12; TIMING.md
     * "Scratch pad"). TI states the offset, not its direction: 0 (default)
     * bank register = register + R0[4:0], 1 = register - R0[4:0]; either way
     * modulo 32 (a 5-bit field), and a byte landing on bank register 30 or 31
     * (no such register) faults. xfr_shift_fill 1: ZERO/FILL move by the
     * same offset in the register file (default 0: unaffected). */
    int xfr_shift_sub;
    int xfr_shift_fill;
    /* Both PRUs of a PRU-ICSS on one scratch-pad bank in one cycle: PRU0
     * goes first and PRU1 stalls until PRU0's transfer is done (AM335x
     * PRU-ICSS guide SPRUHF8A Table 20, AM64x TRM SPRUIM2 XFR collisions,
     * AM62x TRM SPRUIV7: "PRU0 is given priority"; docs/pru-facts.md §3).
     * PRU1's XFR then costs 1 + spad_stall_cycles (default 1: PRU0's
     * transfer takes one cycle; TIMING.md "Scratch pad"). */
    unsigned spad_stall_cycles;
    /* GPI synchronizer: R31 read at cycle c sees the pins at c*5000 - gpi_delay_ps;
     * the shift register samples DATAIN at edge - gpi_delay_ps. */
    int64_t gpi_delay_ps;
    /* GPO: an R30 write by an instruction ending at cycle e reaches the pins at
     * e*5000 + gpo_delay_ps. */
    int64_t gpo_delay_ps;
    /* Shift clock: edges at t_cfg + shift_phase_ps + k * period, k >= 1, where
     * t_cfg is when GPCFG's mode/divider fields were last written. */
    int64_t shift_phase_ps;
    enum pru_frac_mode shift_frac;
    /* Skip idle polling loops in whole iterations (results are identical). */
    int fast_forward;
    /* With fast_forward, also skip counted polls: a loop whose only changing
     * register is a counter (a register or a field of one) stepped by a
     * constant and closed by QBNE on it (a poll with a time-out), up to
     * the iteration before it would end. */
    int ff_counted;
    /* With fast_forward, a loop that looks at R31 only through QBBS/QBBC is
     * skipped until one of the bits it tests may change (not every R31 bit:
     * e.g. Cnt_16 pulses). */
    int ff_r31_bits;
    /* With fast_forward, a LOOP whose body is one instruction that changes
     * nothing (AND/OR of a register with itself: a delay) runs its
     * iterations at once. */
    int ff_loop_delay;
    /* With fast_forward, a register-only countdown loop (a backward QBNE
     * on a counter field against 0, the counter stepped down by one SUB of
     * a constant, every other instruction of the body giving the same
     * result each turn: a delay) runs its turns at once. */
    int ff_count_loop;
    /* Run register-only instructions, fixed-length bursts and R30 writes of
     * ALU instructions in the threaded fast loop (exec.c run_fast); 0: every
     * instruction through the general path, one at a time (results are
     * identical). */
    int fast_loop;
    /* With fast_loop, a call from far below of a short routine of
     * single-cycle register-only instructions (the firmware's delay tails)
     * is replayed from a memo of what it read and wrote (leaf.h
     * leaf_call(); results are identical). */
    int leaf_call;
    /* With fast_loop, a run of single-cycle register-only instructions
     * without a branch (predecode.c set_run()) goes without the checks
     * between its instructions (the cycle limit, a LOOP end) when neither
     * falls within it or at its end, and the firmware's frequent pairs of
     * instructions (and its add/adc/adc carry chain) in it run as one, as
     * does a call from far below of a routine that is one returning JMP
     * (results are identical). */
    int straight_run;
    /* Two PRUs of one PRU-ICSS (pruss.h): each core runs ahead of the other
     * up to its next cross-PRU event (TIMING.md "Two PRUs") instead of
     * both taking turns cycle by cycle; 0: cycle by cycle (results are
     * identical, or a PRU_FAULT_RUN_AHEAD where they could not be). */
    int run_ahead;

    /* Strict mode (TIMING.md "Strict mode"): the PRU_STRICT_* rules checked,
     * 0 = off. A rule broken stops the core with PRU_FAULT_STRICT, or with
     * strict_log only records it (pru_strict_hits()). */
    unsigned strict;
    /* Where the rules apply: 0 (default) only in clocked code, i.e. between
     * two R30 changes at most strict_window cycles apart; 1 everywhere. */
    int strict_everywhere;
    unsigned strict_window;
    int strict_log;
    /* Data-RAM contention (TIMING.md "Contention mode"): a host access to the
     * local RAMs every contend_period cycles (0 = off); a PRU load/store to
     * data RAM 0/1 or shared RAM whose cycles meet one stalls contend_stall
     * cycles. Periodic at cycles = contend_phase mod period, or, with
     * contend_random, each cycle with probability 1/period (seeded, a pure
     * function of seed and cycle). */
    unsigned contend_period, contend_stall, contend_phase;
    int contend_random;
    uint32_t contend_seed;
};

struct pru_core;

/* Strict-mode rules (docs/silicon-assumptions.md A2-A5: the UNCERTAIN rows). */
enum pru_strict_rule {
    PRU_STRICT_LOOP1 = 1u << 0,     /* LOOP whose body is one instruction (A2c) */
    PRU_STRICT_LOOP0 = 1u << 1,     /* LOOP with a register count of 0 (A2d) */
    PRU_STRICT_LOOPFIELD = 1u << 2, /* LOOP counted by a field not rN or rN.w0 (A2e) */
    PRU_STRICT_MVI = 1u << 3,       /* MVIB/MVIW/MVID (A3) */
    PRU_STRICT_DRAM = 1u << 4,      /* load/store to data RAM 0/1 or shared RAM (A4, A5) */
    PRU_STRICT_SPAD = 1u << 5,      /* PRU1's XFR on the bank PRU0 uses in that cycle (A6) */
};
#define PRU_STRICT_ALL            0x3fu
#define PRU_STRICT_DEFAULT_WINDOW 1024u /* the largest half period, H = 1024 */

/* "loop1", "loop0", "loopfield", "mvi", "dram", "spad" (one rule bit), NULL else. */
const char *pru_strict_rule_name(unsigned rule);
/* A comma-separated list of rule names, or "all" (or NULL/"") for every
 * rule, into a mask. Returns 0, or -1 (*bad points at the unknown name). */
int pru_strict_parse(const char *list, unsigned *rules, const char **bad);

/* One strict-mode violation: the instruction, the rule, when it first broke
 * it and how often (counted once per execution). */
struct pru_strict_hit {
    uint32_t pc, word;
    unsigned rule;
    int64_t first_cycle;
    uint64_t count;
};
#define PRU_STRICT_MAX_HITS 256u
/* The violations recorded so far, in the order first seen (different
 * (pc, rule) pairs; at most PRU_STRICT_MAX_HITS, more are only counted in
 * *lost if lost is not NULL). */
size_t pru_strict_hits(const struct pru_core *c, const struct pru_strict_hit **hits,
                       uint64_t *lost);
void pru_strict_clear(struct pru_core *c);
/* Input edges as clocked-scope edges: a change of the R31 bits in mask, as
 * an instruction reads them, counts as an R30 change does (TIMING.md,
 * "Strict mode"): for a program clocked by its inputs, such as the encoder
 * firmware (pru_slave/), whose outputs may stand still for many of its
 * input's periods. 0 (the default): R30 changes only. Per core. */
void pru_strict_inputs(struct pru_core *c, uint32_t mask);
/* Contention so far: PRU accesses that met a host access, stall cycles added. */
void pru_contend_stats(const struct pru_core *c, uint64_t *collisions, uint64_t *stall_cycles);
/* Scratch-pad collisions this core stalled for (only PRU1 of a PRU-ICSS
 * ever does: pru_params.spad_stall_cycles). */
uint64_t pru_spad_collisions(const struct pru_core *c);
/* Parses "K,S[,periodic[:PHASE]|random[:SEED]]" into p's contend_* fields.
 * Returns 0, or -1 with a message in err. */
int pru_contend_parse(const char *spec, struct pru_params *p, char *err, size_t errlen);

void pru_params_default(struct pru_params *p);

/* Turns the core's fast path `name` off (--no-fast-path of pru-run and
 * biss-sim): ff (all of the fast-forward), ff-counted, ff-r31-bits,
 * ff-loop-delay, ff-count-loop, fast-loop, leaf-call, straight-run,
 * run-ahead. Returns 0, or -1 if there is none of that name. */
int pru_params_fast_path_off(struct pru_params *p, const char *name);

/*
 * Connection to the outside world (cable + encoder models).
 *
 * Ordering the core guarantees: inputs_at() times never decrease; an
 * outputs_changed() time is always later than every inputs_at() time asked
 * so far. With the bench's link model (emulator/slave/link_model.h) the
 * adapter is direct:
 *   inputs_at(t)          -> link_sl(l, t) << SL_BIT (bit 0 for shift mode)
 *   next_input_change(t)  -> link_next_change(l)  (a time <= t is tolerated)
 *   outputs_changed(t, v) -> link_ma(l, t, (v >> MA_BIT) & 1) when that bit moved
 *   inputs_run(t, &next)  -> link_sl_run(l, t, &next)
 */
struct pru_pins {
    void *ctx;
    /* Input levels of R31[29:0] (bit 0 is also the shift-mode DATAIN) at t_ps.
     * Called with non-decreasing t. */
    uint32_t (*inputs_at)(void *ctx, int64_t t_ps);
    /* Earliest time > t_ps at which the inputs may change if R30 does not
     * change; INT64_MAX if never. May be NULL (then no fast-forward on pins). */
    int64_t (*next_input_change)(void *ctx, int64_t t_ps);
    /* R30 changed; the pins take the new value at t_ps. t_ps may lie up to
     * 5000 + gpo_delay_ps + gpi_delay_ps after the latest inputs_at() time. */
    void (*outputs_changed)(void *ctx, int64_t t_ps, uint32_t r30);
    /* Optional (NULL: the shift register asks inputs_at and then
     * next_input_change): inputs_at(t_ps), and in *next
     * next_input_change(t_ps), in one call, as the shift register asks for
     * every run of equal samples. Used only with inputs_at. */
    uint32_t (*inputs_run)(void *ctx, int64_t t_ps, int64_t *next);
};

enum pru_fault_cause {
    PRU_FAULT_NONE,
    PRU_FAULT_BAD_OPCODE,   /* word does not decode, or SCAN/MAC not modelled */
    PRU_FAULT_UNMAPPED,     /* data access outside any modelled block */
    PRU_FAULT_PC_RANGE,     /* PC past the end of IRAM */
    PRU_FAULT_IRAM_RUNNING, /* host wrote IRAM while the PRU was running */
    PRU_FAULT_BURST,        /* zero-length burst or register file overrun */
    PRU_FAULT_XFR_DEVICE,   /* XIN/XOUT to a device that is not modelled */
    PRU_FAULT_GPO_SHIFT,    /* GPO shift-out mode enabled (not modelled) */
    PRU_FAULT_UNSUPPORTED,  /* other mode not modelled (GPI parallel/MII) */
    PRU_FAULT_STRICT,       /* strict mode: a construct of uncertain silicon behaviour */
    /* run_ahead: an access that changes what the other PRU already ran
     * ahead through (its CONTROL or GPCFG, the INTC turned on): rerun with
     * run_ahead 0 */
    PRU_FAULT_RUN_AHEAD,
};

struct pru_fault {
    enum pru_fault_cause cause;
    uint32_t pc;   /* word address of the faulting instruction */
    int64_t cycle; /* cycle in which it was issued */
    uint32_t addr; /* data address involved (if any) */
    uint32_t word; /* instruction word (if any) */
    /* PRU_FAULT_STRICT: the rule (one PRU_STRICT_* bit) and, in clocked
     * scope, the cycles of the R30 changes around it (else both -1) */
    unsigned rule;
    int64_t edge_from, edge_to;
};

enum pru_stop {
    PRU_STOP_LIMIT,    /* reached the requested cycle/time */
    PRU_STOP_HALT,     /* executed HALT */
    PRU_STOP_FAULT,    /* see pru_get_fault() */
    PRU_STOP_DISABLED, /* CONTROL.ENABLE is 0 (not started, or stopped by a write) */
    PRU_STOP_STEP,     /* single step done */
};

struct pru_core;

/* Create a core; params may be NULL for the defaults. Out of reset the PRU
 * is disabled (CONTROL = 1) with PC 0, like the SoC. */
struct pru_core *pru_core_new(enum pru_soc soc, const struct pru_params *params);
void pru_core_free(struct pru_core *c);

int pru_soc_from_name(const char *name, enum pru_soc *soc); /* 0 or -1 */
const char *pru_soc_name(enum pru_soc soc);
uint32_t pru_soc_base(enum pru_soc soc); /* global PRU-ICSS base address */
uint32_t pru_iram_bytes(const struct pru_core *c);
uint32_t pru_dram_bytes(const struct pru_core *c);
uint32_t pru_shared_bytes(const struct pru_core *c);

/* Global (ARM view) offsets inside the PRU-ICSS: include/pruss/pruss_map.h. */
#define PRU_OFS_DRAM0  PRUSS_OFS_DRAM0
#define PRU_OFS_DRAM1  PRUSS_OFS_DRAM1
#define PRU_OFS_SHARED PRUSS_OFS_SHARED
#define PRU_OFS_INTC   PRUSS_OFS_INTC
#define PRU_OFS_CTRL0  PRUSS_OFS_CTRL0
#define PRU_OFS_DEBUG0 PRUSS_OFS_DEBUG0
#define PRU_OFS_CTRL1  PRUSS_OFS_CTRL1
#define PRU_OFS_CFG    PRUSS_OFS_CFG
#define PRU_OFS_IEP    PRUSS_OFS_IEP
#define PRU_OFS_IRAM0  PRUSS_OFS_IRAM0
#define PRU_OFS_IRAM1  PRUSS_OFS_IRAM1

/* CONTROL bits */
#define PRU_CTRL_SOFT_RST_N  (1u << 0)
#define PRU_CTRL_ENABLE      (1u << 1)
#define PRU_CTRL_SLEEPING    (1u << 2)
#define PRU_CTRL_CTR_EN      (1u << 3)
#define PRU_CTRL_SINGLE_STEP (1u << 8)
#define PRU_CTRL_RUNSTATE    (1u << 15)

/* Host access through global addresses (pru_soc_base() + offset). Word
 * accesses must be 4-byte aligned. Return 0, -1 for an unmapped address,
 * -2 for an IRAM access while the PRU runs (a write is also recorded as a
 * fault). */
int pru_host_read32(struct pru_core *c, uint32_t addr, uint32_t *val);
int pru_host_write32(struct pru_core *c, uint32_t addr, uint32_t val);
int pru_host_read(struct pru_core *c, uint32_t addr, void *buf, size_t n);
int pru_host_write(struct pru_core *c, uint32_t addr, const void *buf, size_t n);

/* Map a RAM window of the system bus (e.g. DDR at 0x80000000 or OCMC at
 * 0x40300000) that PRU loads/stores above 0x80000 reach, with the cost
 * load_ext_cycles; the host reaches it at the same address. Zero-filled.
 * Up to 4 windows. Returns 0, or -1 (overlap, below 0x80000, no memory). */
int pru_map_ext(struct pru_core *c, uint32_t base, uint32_t size);

/* Convenience: load a raw little-endian IRAM image at word 0 (PRU must be
 * halted); bytes beyond the image are zero. Returns 0 or -1 (too big). */
int pru_load_image(struct pru_core *c, const void *image, size_t bytes);
/* Start (CONTROL.ENABLE = 1) and stop, as a host write to CONTROL would. */
void pru_start(struct pru_core *c);
void pru_stop(struct pru_core *c);

/* Pins: without a pins object the inputs are the constant pru_set_inputs(). */
void pru_set_pins(struct pru_core *c, const struct pru_pins *pins);
void pru_set_inputs(struct pru_core *c, uint32_t levels);

/* Calls fn(ctx, addr) right after every PRU store that writes the byte at
 * local data RAM address addr (the core's own data RAM), e.g. a firmware's
 * publication counter. Inside the callback pru_cycles() is the cycle the
 * store was issued in and pru_pc() its address, exactly, on every path of
 * the execute loop (as --trace shows the store). The callback may read
 * memory (pru_host_read) but must not run or stop the core. fn NULL
 * removes the watch. */
void pru_set_store_watch(struct pru_core *c, uint32_t addr, void (*fn)(void *ctx, uint32_t addr),
                         void *ctx);

/* Trace each executed instruction to f (NULL: off). */
void pru_set_trace(struct pru_core *c, FILE *f);

/* Run. Time advances to the limit even while the PRU is disabled or asleep,
 * except that a run stops right after HALT, a fault, or a step. Limits are
 * capped at PRU_MAX_CYCLE; a limit at or above it means "no limit": then a
 * disabled PRU returns at once and time stays where it is. */
enum pru_stop pru_run_until_cycle(struct pru_core *c, int64_t cycle);
enum pru_stop pru_run_until_time(struct pru_core *c, int64_t t_ps);
/* Run until HALT/fault/disable, at most max_cycles from now. */
enum pru_stop pru_run(struct pru_core *c, int64_t max_cycles);
/* Execute exactly one instruction (or one cycle of sleep). */
enum pru_stop pru_step(struct pru_core *c);

/* State */
int64_t pru_cycles(const struct pru_core *c); /* current time in cycles */
int64_t pru_time_ps(const struct pru_core *c);
/* In the GPI's 28-bit shift mode: the instants around t_ps at which the
 * shift register samples the pins (a shift-clock edge less gpi_delay_ps),
 * the last at or before t_ps and the next after it: 0; -1 in any other
 * mode. A pin change between the two reaches the samples only if the
 * level still differs at the second. */
int pru_gpi_sample_bracket(const struct pru_core *c, int64_t t_ps, int64_t *before_ps,
                           int64_t *after_ps);
uint64_t pru_instructions(const struct pru_core *c); /* executed instructions */
uint32_t pru_pc(const struct pru_core *c);
void pru_set_pc(struct pru_core *c, uint32_t pc);
uint32_t pru_reg(struct pru_core *c, unsigned n); /* r31 reads the inputs now */
void pru_set_reg(struct pru_core *c, unsigned n, uint32_t v);
int pru_carry(const struct pru_core *c);
int pru_halted(const struct pru_core *c); /* stopped by HALT */
int pru_sleeping(const struct pru_core *c);
const struct pru_fault *pru_get_fault(const struct pru_core *c);
const char *pru_fault_name(enum pru_fault_cause cause);
/* One line "fault: <cause> at pc=0x.. cycle=N (addr=0x.., word=0x..)"; for a
 * strict fault "fault: strict rule <rule> (<what>) at pc=0x.. cycle=N: <insn>"
 * and, in clocked scope, the R30 changes around it. */
void pru_print_fault(const struct pru_core *c, FILE *f);

/* The PRU-ICSS's IEP timer as an instruction issued in `cycle` would read
 * it (or, if the IEP has been brought past that cycle already, as of that
 * later cycle, in v->cycle), without moving the emulated IEP on: for
 * instruments that watch a run and must not change it (the bench's IEP
 * phase of each frame). Exact when nothing writes the IEP before `cycle`
 * that has not been issued yet, as in a callback of an instruction issued
 * in `cycle` or earlier. */
struct pru_iep_view {
    int64_t cycle;    /* the cycle boundary the values are for */
    uint32_t count;   /* COUNT */
    uint32_t inc;     /* the increment of this tick (DEFAULT_INC, or CMP_INC in compensation) */
    uint32_t cmp0;    /* CMP0 */
    bool cmp0_resets; /* CMP0 enabled and resetting COUNT (CMP_CFG bits 1 and 0) */
};
void pru_iep_view(const struct pru_core *c, int64_t cycle, struct pru_iep_view *v);

/* Fast-forward statistics: iterations skipped so far. */
uint64_t pru_ff_skipped(const struct pru_core *c);

#endif
