/* biss_probe_fields.c - the fields inside each slave's data word once the
 * data + CRC split is found (no I/O): the life counter at the word's LSB and
 * nE/nW above it ([MB4] "BiSS C Frame"; the order position, nE, nW, life
 * counter as in [AD38]'s SCD tables), judged on the good frames only (those
 * whose CRCs all fit the layout: the others are set aside as noise).
 *
 * What the frames cannot settle is said, not guessed: a counter whose top
 * bit never carried over into the bit above (no wrap seen) and whose next
 * bit never changed may be wider than the bits that moved (a 16-bit counter
 * shows 10 bits in 1024 frames), and then the bits above it may be its top,
 * nE/nW or fill alike (lc_open). */
#include "biss_probe_priv.h"

#include <stdlib.h>

static uint32_t crc_from(uint32_t reg, uint64_t data, unsigned d, uint32_t poly, unsigned c) {
    uint32_t low = poly & ((1u << c) - 1u), top = 1u << (c - 1);
    for (unsigned k = d; k > 0; k--) {
        uint32_t fb = ((reg & top) != 0) ^ (uint32_t)(data >> (k - 1) & 1u);
        reg = (reg << 1) & ((1u << c) - 1u);
        reg ^= fb ? low : 0;
    }
    return reg;
}

static bool slave_fits(const struct biss_probe_frames *f, unsigned i,
                       const struct biss_probe_slave *s) {
    uint32_t mask = (1u << s->crc_bits) - 1u;
    uint64_t data = probe_word(f, i, s->offset, s->data_bits);
    uint32_t sent = (uint32_t)probe_word(f, i, s->offset + s->data_bits, s->crc_bits);
    return crc_from(s->crc_start, data, s->data_bits, s->crc_poly, s->crc_bits) == (~sent & mask);
}

unsigned biss_probe_good_frames(const struct biss_probe_frames *f,
                                const struct biss_probe_layout *l, uint8_t *good) {
    unsigned n = 0;
    for (unsigned i = 0; i < f->nframes; i++) {
        bool ok = true;
        for (unsigned s = 0; s < l->nslaves && ok; s++) {
            ok = slave_fits(f, i, &l->slave[s]);
        }
        good[i] = ok;
        n += ok;
    }
    return n;
}

/* Pairs of successive good frames a counter is tested on: their words and
 * how many frames apart they are (the firmware's frame numbers). */
struct pairs {
    unsigned n; /* words; n - 1 pairs */
    uint64_t *w;
    uint64_t *step; /* step[j]: frames from word j - 1 to word j */
};

/* The widest k (below the word's top bit) whose low k bits step by the
 * frame-number difference in all but a few pairs (2 + 0.2 %: a CRC lets a
 * rare wrong frame through), and whose top bit moved: a counter's top bit
 * must move, or constant bits above it (nE, nW) would pass as counter bits
 * until it wraps. *open: no wrap seen and the bit above never changed. */
static unsigned counter_width(const struct pairs *p, unsigned d, bool *open) {
    *open = false;
    if (p->n < 4 || d < 2) {
        return 0;
    }
    unsigned tol = 2 + (p->n - 1) / 500;
    for (unsigned k = d - 1 < 32 ? d - 1 : 32; k >= 1; k--) {
        uint64_t m = (1ull << k) - 1u;
        unsigned bad = 0;
        bool top_moves = false, wrapped = false, above_moves = false;
        for (unsigned j = 1; j < p->n; j++) {
            uint64_t a = p->w[j - 1], b = p->w[j], st = p->step[j];
            bool steps = st != 0 && ((b - a) & m) == (st & m);
            bad += !steps;
            top_moves |= ((a ^ b) >> (k - 1) & 1u) != 0;
            wrapped |= steps && (a & m) + st > m;
            above_moves |= ((b ^ p->w[0]) >> k & 1u) != 0;
        }
        if (bad <= tol && top_moves) {
            *open = !wrapped && !above_moves;
            return k;
        }
    }
    return 0;
}

void biss_probe_fields(const struct biss_probe_frames *f, const uint8_t *good,
                       struct biss_probe_slave *s) {
    struct pairs p = {0, malloc(f->nframes * sizeof *p.w), malloc(f->nframes * sizeof *p.step)};
    s->lc_bits = 0;
    s->lc_open = false;
    s->has_ew = false;
    s->ew_shift = s->ew_ones_pct = 0;
    uint32_t last = 0;
    for (unsigned i = 0; p.w && p.step && i < f->nframes; i++) {
        if (!good[i]) {
            continue;
        }
        uint32_t fno = f->frame_no ? f->frame_no[i] : i;
        p.w[p.n] = probe_word(f, i, s->offset, s->data_bits);
        p.step[p.n++] = fno - last;
        last = fno;
    }
    if (p.n) {
        s->lc_bits = counter_width(&p, s->data_bits, &s->lc_open);
        /* nE/nW are active low: two bits that are (nearly) always 1 right
         * above the counter, with a position bit above them */
        unsigned sh = s->lc_bits, ones_e = 0, ones_w = 0;
        for (unsigned j = 0; j < p.n && s->data_bits >= sh + 3; j++) {
            ones_w += (unsigned)(p.w[j] >> sh & 1u);
            ones_e += (unsigned)(p.w[j] >> (sh + 1) & 1u);
        }
        unsigned lo = ones_e < ones_w ? ones_e : ones_w;
        s->ew_ones_pct = (unsigned)((uint64_t)lo * 100 / p.n);
        s->has_ew = s->ew_ones_pct >= 90;
        s->ew_shift = s->has_ew ? sh : 0;
    }
    free(p.w);
    free(p.step);
}
