/* biss_rate.c - which MA rates the firmware can clock exactly: the one
 * copy of its rule on the host side (the firmware's own is config.p's
 * factor loop; test_e2e_rate_rule holds the two together at every H), and
 * the conversions between a rate and H that rest on it. */
#include "biss_proto.h"

/* The 28-bit shift register samples SL at 8x MA from two cascaded
 * dividers of the 200 MHz clock with ratios a/2 and b/2 (2 <= a, b <= 32;
 * docs/pru-facts.md §4.4, §4.5): 8 samples per 2H cycles need H = a * b. */
static int has_shift_factors(unsigned half) {
    for (unsigned a = 2; a <= 32; a++) {
        if (half % a == 0 && half / a >= 2 && half / a <= 32) {
            return 1;
        }
    }
    return 0;
}

int biss_proto_half_check(unsigned half) {
    if (half < BISS_MIN_HALF || half > BISS_MAX_HALF) {
        return BISS_E_RATE_RANGE;
    }
    return has_shift_factors(half) ? BISS_OK : BISS_E_RATE_SHIFT;
}

const char *biss_proto_half_problem(unsigned half) {
    if (half < BISS_MIN_HALF) {
        return "faster than the firmware's 10 MHz (BISS_MIN_HALF = 10 PRU cycles)";
    }
    if (half > BISS_MAX_HALF) {
        return "slower than the firmware's 97.7 kHz (BISS_MAX_HALF = 1024 PRU cycles)";
    }
    if (biss_proto_half_check(half) != BISS_OK) {
        return "no exact 8x shift clock for it (the half period in PRU cycles must be a * b, "
               "2 <= a, b <= 32)";
    }
    return NULL;
}

int biss_proto_half_rate(unsigned half, uint32_t *freq_hz) {
    int rc = biss_proto_half_check(half);
    if (rc != BISS_OK) {
        return rc;
    }
    if (BISS_HALF_CLOCK_HZ % half != 0) {
        return BISS_E_RATE_INEXACT;
    }
    if (freq_hz) {
        *freq_hz = BISS_HALF_CLOCK_HZ / half;
    }
    return BISS_OK;
}

int biss_proto_freq_half(double freq_hz, unsigned *half) {
    if (!half || !(freq_hz > 0)) {
        return BISS_E_INVAL;
    }
    double h = BISS_HALF_CLOCK_HZ / freq_hz;
    if (!(h <= UINT16_MAX)) {
        return BISS_E_RATE_RANGE; /* no half period the block holds (and no double to round) */
    }
    unsigned n = (unsigned)(h + 0.5); /* h > 0: the nearest whole number */
    if (h - n > 1e-9 || n - h > 1e-9) {
        return BISS_E_RATE_INEXACT;
    }
    *half = n;
    return BISS_OK;
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
    int rc = biss_proto_half_check(h);
    if (rc == BISS_OK) {
        *half = h;
    }
    return rc;
}

const char *biss_proto_cfg_error_text(uint32_t code) {
    /* the meanings of include/biss/biss_shm.h */
    static const char *const text[] = {
        [BISS_CFGERR_NONE] = "BISS_CFGERR_NONE: accepted",
        [BISS_CFGERR_NSLAVES] = "BISS_CFGERR_NSLAVES: 0 or more than 8 slaves",
        [BISS_CFGERR_HALF] = "BISS_CFGERR_HALF: MA half period out of range or no exact 8x "
                             "shift clock for it",
        [BISS_CFGERR_DATA_BITS] = "BISS_CFGERR_DATA_BITS: a slave with 0 or more than 64 data "
                                  "bits",
        [BISS_CFGERR_CRC_BITS] = "BISS_CFGERR_CRC_BITS: a slave with more than 16 CRC bits",
        [BISS_CFGERR_TRIGGER] = "BISS_CFGERR_TRIGGER: unknown trigger mode",
        [BISS_CFGERR_EW] = "BISS_CFGERR_EW: nE/nW position outside the data word",
        [BISS_CFGERR_IEP_PERIOD] = "BISS_CFGERR_IEP_PERIOD: IEP period shorter than a frame can be",
        [BISS_CFGERR_SSI] = "BISS_CFGERR_SSI: SSI needs one slave and no CRC",
    };
    if (code < sizeof text / sizeof text[0] && text[code]) {
        return text[code];
    }
    return "an error code the header does not define";
}
