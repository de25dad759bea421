/*
 * icss_block.h - the PRU-ICSS register blocks behind one small interface,
 * as a small MCU emulator registers its peripherals with the core: each
 * block (INTC, the two CONTROL blocks, CFG, IEP; docs/pru-facts.md §5.1)
 * is a struct icss_block in its own file, and the core reaches it only
 * through that: reset, read, write, and when it next changes. The memory
 * map (memmap.c) finds a block by address in the table icss_blocks and
 * costs an access by it; the core's reset resets every block; the INTC
 * takes its system events from every block that raises some.
 *
 * The hot paths stay direct, outside the table: R31 reads (gpi_r31: GPI
 * and the INTC's host bits, on every read of R31 by the execute loop) and
 * their horizons, R31 writes' system events (intc_event), the CYCLE
 * counter's updates at sleep and halt (ctrl_counting_update), the execute
 * loop's look at its own CONTROL bits (c->ctrl: enable, sleeping, single
 * step) and the API's start and halt (ctrl_read, ctrl_write). A block's
 * read and write run for a load or store the memory map sends it, and
 * for the host's accesses. Each block's state is in struct pru_core
 * (core_priv.h), the blocks of one PRU-ICSS in PRU0's.
 */
#ifndef ICSS_BLOCK_H
#define ICSS_BLOCK_H

#include <stddef.h>
#include <stdint.h>

struct pru_core;

struct icss_block {
    const char *name;
    /* in the PRU-local data space, at the offsets the host sees them at
     * from the PRU-ICSS's base (pruss/pruss_map.h; docs/pru-facts.md §5.1) */
    uint32_t base, size;
    /* The first beat of a load from it: the pru_params field at this
     * offset (an unsigned: load_intc_cycles, ...); each further 32-bit
     * beat one cycle more. */
    size_t load_cycles;
    /* Its state as a new core has it (NULL: none of its own). */
    void (*reset)(struct pru_core *c);
    /* The 32-bit word at ofs (4-aligned) as core c reads it at cycle
     * `at`, and a write of the bytes in bmask to it landing at `at`. */
    uint32_t (*read)(struct pru_core *c, uint32_t ofs, int64_t at);
    void (*write)(struct pru_core *c, uint32_t ofs, uint32_t val, uint32_t bmask, int64_t at);
    /* The first cycle after `cycle` at which a read of word ofs may see
     * another value unless something writes the block (the fast-forward's
     * horizon). NULL: not before a write. */
    int64_t (*next_change)(struct pru_core *c, int64_t cycle, uint32_t ofs);
    /* As a source of the INTC's system events: brings the events it raises
     * for core c up to `cycle` (intc_event), and the first cycle after
     * `cycle` at which it may raise one. NULL: it raises none. */
    void (*raise)(struct pru_core *c, int64_t cycle);
    int64_t (*next_raise)(struct pru_core *c, int64_t cycle);
};

/* The blocks, in address order (memmap.c). */
extern const struct icss_block *const icss_blocks[];
extern const size_t icss_nblocks;

/* Each block (in its file). */
extern const struct icss_block icss_intc;  /* intc.c, 0x20000 */
extern const struct icss_block icss_ctrl0; /* ctrl.c, 0x22000: PRU0's CONTROL */
extern const struct icss_block icss_ctrl1; /* ctrl.c, 0x24000: PRU1's CONTROL */
extern const struct icss_block icss_cfg;   /* cfg_gpi.c, 0x26000 */
extern const struct icss_block icss_iep;   /* iep.c, 0x2E000 */

/* ---- kept direct (the hot paths above) ---- */

/* cfg_gpi.c: R31 as core c reads it at `cycle` (GPI, and the INTC's host
 * bits 31:30), and until when it stays. */
uint32_t gpi_r31(struct pru_core *c, int64_t cycle);
int64_t gpi_stable_until(struct pru_core *c, int64_t cycle);

/* intc.c: system event ev raised (an R31 write's, a block's); the host
 * bits R31[31:30] at `cycle`; the first cycle after `cycle` at which they
 * may change. */
void intc_event(struct pru_core *c, unsigned ev);
uint32_t intc_host_bits(struct pru_core *c, int64_t cycle);
int64_t intc_next_change(struct pru_core *c, int64_t cycle);

/* ctrl.c: CYCLE and STALL count from `at` on as ENABLE, COUNTER_ENABLE and
 * sleep now say; CONTROL as the API's start and halt read and write it. */
void ctrl_counting_update(struct pru_core *c, int64_t at);
uint32_t ctrl_read(struct pru_core *c, uint32_t ofs, int64_t at);
void ctrl_write(struct pru_core *c, uint32_t ofs, uint32_t val, uint32_t bmask, int64_t at);

#endif
