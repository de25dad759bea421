/* biss_probe_priv.h - what the probe's files share, and the steps of
 * biss_probe that its tests reach one by one: no part of libbiss's API
 * (the public part is host/include/biss_probe.h), nor of libbiss.so's
 * exports. */
#ifndef BISS_PROBE_PRIV_H
#define BISS_PROBE_PRIV_H

#include "biss_probe.h"

#pragma GCC visibility push(hidden)

/* Bit p after the CDS of frame i (0/1). */
static inline int probe_bit(const struct biss_probe_frames *f, unsigned i, unsigned p) {
    return f->bits[(size_t)i * f->nbits + 1 + p] & 1;
}

/* n bits from p on, MSB first (n <= 64). */
static inline uint64_t probe_word(const struct biss_probe_frames *f, unsigned i, unsigned p,
                                  unsigned n) {
    uint64_t w = 0;
    for (unsigned k = 0; k < n; k++) {
        w = w << 1 | (uint64_t)probe_bit(f, i, p + k);
    }
    return w;
}

/* The limits of one analysis, over all its searches. */
struct probe_budget {
    uint64_t work, limit;
    uint64_t next_look; /* work at which the clock is read next */
    double start_s, deadline_s, next_report_s;
    enum biss_probe_stop ran_out;
    const struct biss_probe_limits *lim;
    unsigned offsets_searched, end_bit; /* for the progress report */
};

/* Starts a budget at start_s (probe_now_s()) with lim's limits or the
 * defaults (lim NULL). */
void probe_budget_init(struct probe_budget *b, const struct biss_probe_limits *lim, double start_s);
double probe_now_s(void);
/* Spends w steps; true once a limit is reached (and from then on). */
bool probe_budget_spend(struct probe_budget *b, uint64_t w);
unsigned probe_budget_elapsed_ms(const struct probe_budget *b);

/* The frames whose every slave's CRC fits layout l (good[i] = 1): the ones
 * its fields are judged on. Returns how many. */
unsigned biss_probe_good_frames(const struct biss_probe_frames *f,
                                const struct biss_probe_layout *l, uint8_t *good);
/* A slave's life counter and nE/nW, judged on the good frames. */
void biss_probe_fields(const struct biss_probe_frames *f, const uint8_t *good,
                       struct biss_probe_slave *s);

/* ---- the registers' layout (biss_probe_regs.c, no I/O) ---- */

/* The layout regs (of one ID) describe; false when they are of no format
 * known. Values that make no frame (a data word over 64 bits, a CRC
 * outside 3..16 bits, 0xFF "not used") are described too: *why then says
 * which and the return is still true, with out->nchannels 0. */
bool biss_probe_reg_layout_decode(const struct biss_probe_regs *regs,
                                  struct biss_probe_reg_layout *out, char *why, size_t why_size);

/* The described layout against the wire's candidates: the verdict, which
 * candidate agrees (1-based; 0: none) and, for a disagreement, the first
 * field that differs from candidate 1, in words. */
enum biss_probe_reg_verdict biss_probe_reg_compare(const struct biss_probe_reg_layout *rl,
                                                   const struct biss_probe_result *wire,
                                                   unsigned *agree_with, char *why,
                                                   size_t why_size);

/* ---- SSI words (biss_probe_ssi.c, no I/O) ---- */

/* The words w[0..n-1] (fno: their frame numbers, or NULL); out->delay_ns
 * is kept. 0, or BISS_E_INVAL. "Cannot decide" is in out->verdict. */
int biss_probe_ssi_analyse(const uint64_t *w, const uint32_t *fno, unsigned n,
                           struct biss_probe_ssi *out);

#pragma GCC visibility pop

#endif
