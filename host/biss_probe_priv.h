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

/* The frames whose every slave's CRC fits layout l (good[i] = 1): the ones
 * its fields are judged on. Returns how many. */
unsigned biss_probe_good_frames(const struct biss_probe_frames *f,
                                const struct biss_probe_layout *l, uint8_t *good);
/* A slave's life counter and nE/nW, judged on the good frames. */
void biss_probe_fields(const struct biss_probe_frames *f, const uint8_t *good,
                       struct biss_probe_slave *s);

#endif
