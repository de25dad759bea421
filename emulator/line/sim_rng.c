#include "sim_rng.h"

#include <math.h>

static uint64_t splitmix64(uint64_t *x) {
    uint64_t z = (*x += UINT64_C(0x9e3779b97f4a7c15));
    z = (z ^ (z >> 30)) * UINT64_C(0xbf58476d1ce4e5b9);
    z = (z ^ (z >> 27)) * UINT64_C(0x94d049bb133111eb);
    return z ^ (z >> 31);
}

static uint64_t rotl(uint64_t x, int k) {
    return (x << k) | (x >> (64 - k));
}

void sim_rng_seed(sim_rng *r, uint64_t seed) {
    uint64_t x = seed;
    for (int i = 0; i < 4; i++) {
        r->s[i] = splitmix64(&x);
    }
    r->has_spare = 0;
    r->spare = 0.0;
}

uint64_t sim_rng_derive(uint64_t seed, uint64_t stream) {
    uint64_t x = seed ^ (stream * UINT64_C(0xd1b54a32d192ed03));
    return splitmix64(&x);
}

uint64_t sim_rng_u64(sim_rng *r) {
    uint64_t *s = r->s;
    uint64_t result = rotl(s[1] * 5, 7) * 9;
    uint64_t t = s[1] << 17;
    s[2] ^= s[0];
    s[3] ^= s[1];
    s[1] ^= s[2];
    s[0] ^= s[3];
    s[2] ^= t;
    s[3] = rotl(s[3], 45);
    return result;
}

double sim_rng_uniform(sim_rng *r) {
    return (double)(sim_rng_u64(r) >> 11) * 0x1.0p-53;
}

double sim_rng_gauss(sim_rng *r) {
    if (r->has_spare) {
        r->has_spare = 0;
        return r->spare;
    }
    /* 1 - u is in (0, 1], so the logarithm is finite. */
    double u1 = 1.0 - sim_rng_uniform(r);
    double u2 = sim_rng_uniform(r);
    double mag = sqrt(-2.0 * log(u1));
    double ang = 2.0 * 3.14159265358979323846 * u2;
    r->spare = mag * sin(ang);
    r->has_spare = 1;
    return mag * cos(ang);
}

double sim_rng_exponential(sim_rng *r, double mean) {
    return -mean * log(1.0 - sim_rng_uniform(r));
}
