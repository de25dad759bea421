/* slave_motion.h - an encoder's position over time, shared by the BiSS and
 * SSI slave models. */
#ifndef SLAVE_MOTION_H
#define SLAVE_MOTION_H

#include "sim_time.h"

#include <stdint.h>

/* pos0 + floor(speed_cps * t) modulo 2^bits (bits 1..64; negative speeds
 * wrap). Defined for any speed and time; exact while the counts moved stay
 * below 2^53 (the scenario's speed range keeps them there). */
uint64_t slave_position_at(uint64_t pos0, double speed_cps, unsigned bits, sim_ps t);

#endif
