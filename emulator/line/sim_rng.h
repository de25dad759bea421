/* Seeded random numbers for the models: xoshiro256** (Blackman and Vigna,
 * 2018) seeded through splitmix64, as the authors recommend, and a Gaussian
 * by the Box-Muller transform. Each model owns its generator, so adding a
 * model to a bench never changes the numbers another model draws. */
#ifndef SIM_RNG_H
#define SIM_RNG_H

#include <stdint.h>

typedef struct {
    uint64_t s[4];
    double spare; /* second Box-Muller value, used on the next call */
    int has_spare;
} sim_rng;

/* Same seed, same stream. Any seed (0 included) is fine. */
void sim_rng_seed(sim_rng *r, uint64_t seed);

/* Derives an independent seed for a sub-component (e.g. one line direction)
 * from a scenario seed and a small stream number. */
uint64_t sim_rng_derive(uint64_t seed, uint64_t stream);

uint64_t sim_rng_u64(sim_rng *r);
double sim_rng_uniform(sim_rng *r); /* [0, 1) with 53 random bits */
double sim_rng_gauss(sim_rng *r);   /* mean 0, standard deviation 1 */
double sim_rng_exponential(sim_rng *r, double mean);

#endif
