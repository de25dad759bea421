/* probe_frames.h - raw capture frames from the slave model, for the probe
 * tests: the bits a master clocking nbits after the start bit reads. */
#ifndef PROBE_FRAMES_H
#define PROBE_FRAMES_H

#include "biss_slave.h"

#include <stdint.h>

/* Frames every `period` ps (or as soon as the slave is idle again) at MA
 * half period `half`; bits[f * nbits + k] = bit k after the start bit (CDS
 * first); frame_no[f] = f (may be NULL). 0, or -1 if a start bit never came. */
int probe_frames_from_model(const biss_chain_cfg *cfg, unsigned nframes, unsigned nbits,
                            sim_ps half, sim_ps period, uint8_t *bits, uint32_t *frame_no);

#endif
