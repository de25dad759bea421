/*
 * sim_image.h - the PRU image biss-sim runs: a raw IRAM image (.bin) or
 * pasm-dialect source assembled in process, and the -D parameters of the
 * bench's clocking image (test/bench/clock_frames.p).
 */
#ifndef SIM_IMAGE_H
#define SIM_IMAGE_H

#include "bench.h"
#include "pruasm.h"

#include <stddef.h>

#define SIM_MAX_DEFINES 8

struct sim_defines {
    char text[SIM_MAX_DEFINES][40];
    size_t n;
};

/* Loads path into img (free with pruasm_image_free): a .bin as is, other
 * files assembled with the defines. Returns 0, or -1 with a message. */
int sim_load_image(const char *path, const struct sim_defines *d, struct pruasm_image *img,
                   char *err, size_t errlen);

/* The clocking image's parameters for the bench's chain at half period
 * `half`: clocks per frame (to the last bit, with the round trip), the idle
 * gap (the slave's timeout), the frame count and the MA bit. */
void sim_clock_defines(struct bench *b, unsigned half, uint64_t frames, struct sim_defines *d);

/* Rough duration of one clocking-image frame, ps (for time limits). */
double sim_clock_frame_ps(struct bench *b, unsigned half);

#endif
