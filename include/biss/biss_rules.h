/*
 * biss_rules.h - the rules for values a user gives both the host (libbiss,
 * bissctl) and the bench's scenario files, written once so that both take
 * and refuse the same values. C only (the firmware's contract is
 * biss_shm.h).
 */
#ifndef BISS_RULES_H
#define BISS_RULES_H

#include <math.h>
#include <stdbool.h>
#include <stdint.h>

/* A CRC polynomial written with its top term, as datasheets write it
 * (0x43 = x^6 + x + 1): degree 1..16 (BISS_MAX_CRC_BITS) and odd. Every
 * BiSS CRC has the x^0 term (0x43, 0x25, 0x190D9: iC-MB4 datasheet, "CRC
 * polynomial"); without it the register's lowest bit never takes the
 * feedback and the check degenerates. */
#define BISS_CRC_POLY_MAX 0x1ffffu
static inline bool biss_crc_poly_valid(uint32_t poly) {
    return poly >= 3u && poly <= BISS_CRC_POLY_MAX && (poly & 1u);
}

/* The speed check's top speed (counts per second): from 1e-9 (a count in
 * 30 years) to 1e18, beyond any encoder at both ends; its reach over any
 * time it measures is then a finite number. */
#define BISS_MAX_SPEED_MIN_CPS 1e-9
#define BISS_MAX_SPEED_MAX_CPS 1e18
static inline bool biss_max_speed_valid(double cps) {
    return isfinite(cps) && cps >= BISS_MAX_SPEED_MIN_CPS && cps <= BISS_MAX_SPEED_MAX_CPS;
}

#endif
