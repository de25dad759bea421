/* biss_probe_gf2.h - polynomials over GF(2) of degree < 128 (bit k is the
 * coefficient of x^k), for the probe's CRC search: a window of frame bits
 * is such a polynomial, and a CRC polynomial fits it when it divides it.
 * Two 64-bit words, as the 32-bit ARM the host also runs on has no 128-bit
 * integer. */
#ifndef BISS_PROBE_GF2_H
#define BISS_PROBE_GF2_H

#include <stdbool.h>
#include <stdint.h>

typedef struct {
    uint64_t hi, lo;
} gf2x;

static inline bool gf2x_zero(gf2x a) {
    return (a.hi | a.lo) == 0;
}

static inline int gf2x_deg(gf2x a) { /* -1 for 0 */
    return a.hi ? 127 - __builtin_clzll(a.hi) : a.lo ? 63 - __builtin_clzll(a.lo) : -1;
}

static inline gf2x gf2x_xor(gf2x a, gf2x b) {
    return (gf2x){a.hi ^ b.hi, a.lo ^ b.lo};
}

static inline gf2x gf2x_shl(gf2x a, unsigned n) { /* n < 128 */
    if (n >= 64) {
        return (gf2x){a.lo << (n - 64), 0};
    }
    return n ? (gf2x){a.hi << n | a.lo >> (64 - n), a.lo << n} : a;
}

static inline gf2x gf2x_shr1(gf2x a) {
    return (gf2x){a.hi >> 1, a.lo >> 1 | a.hi << 63};
}

/* a x + bit */
static inline gf2x gf2x_push(gf2x a, unsigned bit) {
    return (gf2x){a.hi << 1 | a.lo >> 63, a.lo << 1 | (bit & 1u)};
}

/* The remainder of a by b (b != 0); *steps counts the subtractions. */
static inline gf2x gf2x_mod(gf2x a, gf2x b, uint64_t *steps) {
    int db = gf2x_deg(b);
    for (int da = gf2x_deg(a); da >= db; da = gf2x_deg(a)) {
        a = gf2x_xor(a, gf2x_shl(b, (unsigned)(da - db)));
        ++*steps;
    }
    return a;
}

/* The quotient of a by b, when b divides a. */
static inline gf2x gf2x_div(gf2x a, gf2x b, uint64_t *steps) {
    gf2x q = {0, 0};
    int db = gf2x_deg(b);
    for (int da = gf2x_deg(a); da >= db; da = gf2x_deg(a)) {
        unsigned s = (unsigned)(da - db);
        a = gf2x_xor(a, gf2x_shl(b, s));
        q = gf2x_xor(q, gf2x_shl((gf2x){0, 1}, s));
        ++*steps;
    }
    return q;
}

static inline gf2x gf2x_gcd(gf2x a, gf2x b, uint64_t *steps) {
    while (!gf2x_zero(b)) {
        gf2x t = gf2x_mod(a, b, steps);
        a = b;
        b = t;
    }
    return a;
}

#endif
