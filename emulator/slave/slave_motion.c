/* slave_motion.c - see slave_motion.h. */
#include "slave_motion.h"

#include <math.h>

uint64_t slave_position_at(uint64_t pos0, double speed_cps, unsigned bits, sim_ps t) {
    const double two64 = 18446744073709551616.0;
    double moved = floor(speed_cps * ((double)t / (double)SIM_PS_PER_S));
    uint64_t step = 0;
    if (isfinite(moved)) {
        /* modulo 2^64 first (fmod is exact), so the conversion is defined;
         * a negative step becomes its two's complement */
        moved = fmod(moved, two64);
        step = moved >= 0 ? (uint64_t)moved : UINT64_C(0) - (uint64_t)-moved;
    }
    uint64_t mask = bits >= 64 ? UINT64_MAX : (UINT64_C(1) << bits) - 1;
    return (pos0 + step) & mask;
}
