/* biss_probe_priv.h - what the probe's analysis files share (not API). */
#ifndef BISS_PROBE_PRIV_H
#define BISS_PROBE_PRIV_H

#include "biss_probe.h"

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

#endif
