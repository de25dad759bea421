/* biss_probe_ssi.c - what SSI words say about the encoder (no I/O).
 *
 * An SSI encoder sends no ACK, start bit, CDS or CRC: its word starts on
 * the first rising edge of the clock, MSB first, and after the last bit
 * the line reads 0 (the model, emulator/slave/ssi_slave.h; many real ones
 * do, some repeat the word or add a parity bit, which this cannot tell
 * from data). So the words are captured 64 bits long and the word ends
 * after the last bit that is ever 1. Bits on top that never change may be
 * unused position bits or fixed flags: only motion shows them. Gray or
 * binary: a shaft turning at a steady speed steps the position by about
 * the same amount per frame; read in the wrong code the steps jump
 * (Gray 0 1 3 2 read as binary steps +1 +2 -1). */
#include "biss_probe_priv.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static uint64_t from_gray(uint64_t g) {
    for (unsigned s = 1; s < 64; s <<= 1) {
        g ^= g >> s;
    }
    return g;
}

static int cmp_i64(const void *a, const void *b) {
    int64_t x = *(const int64_t *)a, y = *(const int64_t *)b;
    return x < y ? -1 : x > y;
}

/* Steps between successive frames (one frame apart, moved) of the n-bit values,
 * and how many stray from the median step by more than max(2, |median| /
 * 8): irregular steps. *pairs: the steps looked at; *median returned. */
static unsigned irregular(const uint64_t *w, const uint32_t *fno, unsigned n, unsigned bits,
                          bool gray, unsigned *pairs, int64_t *median) {
    int64_t *d = malloc(n * sizeof *d);
    *pairs = 0;
    *median = 0;
    if (!d) {
        return 0;
    }
    uint64_t mask = bits >= 64 ? ~0ull : (1ull << bits) - 1u;
    for (unsigned i = 1; i < n; i++) {
        /* frames one apart, with motion between them: a still shaft says
         * nothing, and a slow one would hide the jumps among zero steps */
        if ((fno && fno[i] - fno[i - 1] != 1) || w[i] == w[i - 1]) {
            continue;
        }
        uint64_t a = w[i - 1] >> (64 - bits), b = w[i] >> (64 - bits);
        if (gray) {
            a = from_gray(a);
            b = from_gray(b);
        }
        uint64_t step = (b - a) & mask; /* wraps around the word */
        d[(*pairs)++] = bits < 64 && step >> (bits - 1) ? (int64_t)(step | ~mask) : (int64_t)step;
    }
    if (*pairs == 0) {
        free(d);
        return 0;
    }
    int64_t *s = malloc(*pairs * sizeof *s);
    if (!s) {
        free(d);
        *pairs = 0;
        return 0;
    }
    memcpy(s, d, *pairs * sizeof *s);
    qsort(s, *pairs, sizeof *s, cmp_i64);
    *median = s[*pairs / 2];
    free(s);
    int64_t m = *median, tol = (m < 0 ? -m : m) / 8;
    tol = tol > 2 ? tol : 2;
    unsigned bad = 0;
    for (unsigned i = 0; i < *pairs; i++) {
        int64_t off = d[i] - m;
        bad += off > tol || off < -tol;
    }
    free(d);
    return bad;
}

/* A CRC split the BiSS analysis finds in the word (a CDS of 0 before it). */
static void crc_search(const uint64_t *w, unsigned n, struct biss_probe_ssi *out) {
    unsigned nbits = 1 + 64;
    uint8_t *bits = calloc((size_t)n, nbits);
    struct biss_probe_result *r = malloc(sizeof *r);
    if (!bits || !r) {
        free(bits);
        free(r);
        return;
    }
    for (unsigned i = 0; i < n; i++) {
        for (unsigned k = 0; k < 64; k++) {
            bits[(size_t)i * nbits + 1 + k] = (uint8_t)(w[i] >> (63 - k) & 1u);
        }
    }
    struct biss_probe_frames f = {n, nbits, bits, NULL};
    if (biss_probe_analyse(&f, r) == BISS_OK && r->nlayouts && r->verdict != BISS_PROBE_NONE) {
        const struct biss_probe_slave *s = &r->layout[0].slave[0];
        out->crc_fits = true;
        out->crc_data_bits = s->data_bits;
        out->crc_bits = s->crc_bits;
        out->crc_poly = s->crc_poly;
    }
    free(bits);
    free(r);
}

int biss_probe_ssi_analyse(const uint64_t *w, const uint32_t *fno, unsigned n,
                           struct biss_probe_ssi *out) {
    if (!w || !out || n < 1) {
        return BISS_E_INVAL;
    }
    uint32_t delay = out->delay_ns; /* the caller's, kept */
    memset(out, 0, sizeof *out);
    out->delay_ns = delay;
    out->tried = true;
    out->frames = n;
    uint64_t ones = 0, changed = 0;
    for (unsigned i = 0; i < n; i++) {
        ones |= w[i];
        changed |= w[i] ^ w[0];
    }
    if (!ones) {
        snprintf(out->verdict, sizeof out->verdict,
                 "cannot decide: no bit of %u SSI words was ever 1 (no encoder, or the line "
                 "idles low)",
                 n);
        return BISS_OK;
    }
    out->bits = 64 - (unsigned)__builtin_ctzll(ones);
    if (!changed) {
        snprintf(out->verdict, sizeof out->verdict,
                 "cannot decide: %u-bit words, all %u alike (move the encoder)", out->bits, n);
        return BISS_OK;
    }
    out->fixed_top = (unsigned)__builtin_clzll(changed);
    if (out->bits == 64) {
        snprintf(out->verdict, sizeof out->verdict,
                 "cannot decide: bits up to the 64th read 1: the word is longer than the "
                 "capture, or the encoder repeats it");
        return BISS_OK;
    }
    crc_search(w, n, out);
    unsigned pairs = 0;
    int64_t med_bin = 0, med_gray = 0;
    out->irregular_bin = irregular(w, fno, n, out->bits, false, &pairs, &med_bin);
    out->irregular_gray = irregular(w, fno, n, out->bits, true, &pairs, &med_gray);
    out->pairs = pairs;
    unsigned ib = out->irregular_bin, ig = out->irregular_gray;
    const char *code = NULL;
    if (pairs >= 16) {
        if (ib * 10 <= pairs && ig > 2 * ib + pairs / 20) {
            code = "binary";
        } else if (ig * 10 <= pairs && ib > 2 * ig + pairs / 20) {
            code = "Gray";
            out->gray = true;
        }
    }
    out->decided = code != NULL && !out->crc_fits;
    char crc[96];
    if (out->crc_fits) {
        snprintf(crc, sizeof crc, "yet %u data + %u CRC bits (poly 0x%X) fit: BiSS without an ACK?",
                 out->crc_data_bits, out->crc_bits, out->crc_poly);
    } else {
        snprintf(crc, sizeof crc, "no CRC of 3..16 bits fits");
    }
    snprintf(out->verdict, sizeof out->verdict,
             "SSI-like: %u-bit words (the top %u never changed); %s; %s "
             "(irregular steps: binary %u, Gray %u of %u moves)",
             out->bits, out->fixed_top, crc,
             code ? code : "Gray or binary: cannot tell (too little or uneven motion)", ib, ig,
             pairs);
    return BISS_OK;
}
