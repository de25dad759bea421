/* biss_rate.c - which MA rates the firmware can clock exactly. */
#include "libbiss.h"

#include "biss/biss_shm.h"

/* The 28-bit shift register samples SL at 8x MA from two cascaded
 * dividers of the 200 MHz clock with ratios a/2 and b/2 (2 <= a, b <= 32):
 * 8 samples per 2H cycles need H = a * b. */
static int has_shift_factors(unsigned half) {
    for (unsigned a = 2; a <= 32; a++) {
        if (half % a == 0 && half / a >= 2 && half / a <= 32) {
            return 1;
        }
    }
    return 0;
}

int biss_rate_half(uint32_t freq_hz, unsigned *half) {
    if (!half) {
        return BISS_E_INVAL;
    }
    /* range first, on f itself, so a far-off rate is not reported as inexact */
    if (freq_hz == 0 || (uint64_t)freq_hz * BISS_MIN_HALF > BISS_HALF_CLOCK_HZ ||
        (uint64_t)freq_hz * BISS_MAX_HALF < BISS_HALF_CLOCK_HZ) {
        return BISS_E_RATE_RANGE;
    }
    if (BISS_HALF_CLOCK_HZ % freq_hz != 0) {
        return BISS_E_RATE_INEXACT;
    }
    unsigned h = BISS_HALF_CLOCK_HZ / freq_hz;
    if (!has_shift_factors(h)) {
        return BISS_E_RATE_SHIFT;
    }
    *half = h;
    return BISS_OK;
}
