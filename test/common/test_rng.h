/* test_rng.h - the tests' random numbers: xorshift64*, reproducible from
 * the seed each test sets (no clock, no libc state). */
#ifndef TEST_RNG_H
#define TEST_RNG_H

#include <stdint.h>

static inline uint32_t test_rng_next(uint64_t *state) {
    *state ^= *state >> 12;
    *state ^= *state << 25;
    *state ^= *state >> 27;
    return (uint32_t)((*state * 0x2545F4914F6CDD1Dull) >> 32);
}

#endif
