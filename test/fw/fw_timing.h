/*
 * fw_timing.h - the firmware's clocked blocks stepped in the emulator, with
 * every write of R30 timed: the static timing proof of test_fw_timing.c.
 *
 * The firmware is assembled from source with pruasm (the library), its
 * labels read from the listing, so code is found by name. A run puts the
 * core at a label with the registers the firmware itself set up (its own
 * configuration code, then FRAME_REGS), feeds R31 period by period as a
 * slave would (ACK, busy, start bit, data), and steps instruction by
 * instruction until the clocked part ends, checking that
 *   - R30 is written every H cycles exactly (MA falls at t = 0 and rises at
 *     t = H of every period: docs of pru_fw/biss_periods.hp), the one
 *     exception the firmware documents being the last slave's switch
 *     period cut short (SWITCH_SHORT: 10-cycle halves, no MA edge in it or
 *     after it);
 *   - the clocked part ends where and when it must: full periods, the
 *     slave chain N - f periods long (f bits read after the switch).
 * A failure names the block: the label, macro label and source line of
 * both ends of the half period that was miscounted, and the labels passed.
 */
#ifndef FW_TIMING_H
#define FW_TIMING_H

#include "fw_listing.h"
#include "pru_core.h"
#include "pru_isa.h"
#include "pruasm.h"

#include <stddef.h>
#include <stdint.h>

#define FW_MA_BIT  1 /* the default build's MA bit (pru_fw/CMakeLists.txt) */
#define FW_MA_MASK (1u << FW_MA_BIT)

struct fw {
    struct pruasm_image img;
    struct fw_listing lst;
    struct pru_insn *dec; /* decoded words */
    uint8_t *ok;          /* dec[i] is valid */
    char **at;            /* per word: the labels there, "A/B", or NULL */
    uint8_t *entry;       /* per word: an ENTRY_* label is there */
    /* the clocked part: from period 0's MA edge to the first FINAL_* / FRAME_END */
    uint32_t lo, hi;
};

/* Assembles pru_fw/biss_master.p under src_dir (text: its source, or NULL
 * to read the file) for PRU pru (-DPRU_NUM). Returns 0 or -1 with a
 * message in err. */
int fw_load(struct fw *f, const char *src_dir, const char *text, unsigned pru, char *err,
            size_t errlen);
void fw_free(struct fw *f);

struct fw_slave {
    unsigned n, w; /* data bits, CRC bits */
};
struct fw_config {
    unsigned half;
    unsigned nslaves;
    struct fw_slave s[8];
    int ssi;             /* slave 0 an SSI encoder */
    unsigned proc_limit; /* busy periods accepted */
};

/* A core with the firmware started and configured by its own code (stopped
 * back in MAIN), R31 in direct mode so that a run controls each period's
 * samples. Returns NULL with a message in err (refused: the BISS_CFGERR_*
 * code is put in *cfg_error when not NULL). */
struct pru_core *fw_configure(const struct fw *f, const struct fw_config *cf, uint32_t *cfg_error,
                              char *err, size_t errlen);

#define FW_NEVER 0xffffffffu

/* One run through the clocked part, and what SL shows in it. */
struct fw_run {
    const char *start;   /* label to start at */
    uint32_t start_r12;  /* r12 (FRAME_REGS's return address when starting there) */
    const char *hook;    /* label at which hsum/cdm below are set (NULL: none) */
    int64_t hsum;        /* r4.w2 at hook: the ACK history sum (-1: as set up) */
    int64_t cdm;         /* r4.w0 at hook: CDM edges for CDS 0 / CDS 1 (-1: as set up) */
    unsigned ack_at;     /* WA_TOP period (1, 2, ...) whose samples hold the ACK; FW_NEVER */
    uint8_t ack_pattern; /* R31.b0 then */
    unsigned busy;       /* START_WAIT periods before the start bit; FW_NEVER */
    uint32_t seed;       /* data and CRC bits */
    const char *end;     /* the label the clocked part must end at */
    int chain_periods;   /* periods from the first ENTRY_* to the end (-1: no chain) */
};

/* What the runs of one H covered (conditional branches both ways, every
 * instruction, shortened switches). Sized by fw_cover_init(). */
struct fw_cover {
    uint8_t *seen; /* per word: 1 executed, 2 branch taken, 4 branch fell through */
    unsigned short_switches, full_switches;
    unsigned runs;
};
void fw_cover_init(struct fw_cover *cv, const struct fw *f);
void fw_cover_free(struct fw_cover *cv);
/* Every instruction of the clocked part executed (a delay LOOP's body
 * only when H > 10: its count is H - 10) and every conditional branch in
 * it taken and not taken: 0, or -1 naming what was missed. */
int fw_cover_check(const struct fw_cover *cv, const struct fw *f, unsigned half, char *err,
                   size_t errlen);

/* Runs `r` on core c from the registers in regs[0..29]. Returns 0, or -1
 * with the failure (the block and path) in err. */
int fw_run(const struct fw *f, struct pru_core *c, const uint32_t regs[30], unsigned half,
           const struct fw_run *r, struct fw_cover *cv, char *err, size_t errlen);

#endif
