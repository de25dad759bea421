/*
 * sim_pair.h - biss-sim with a second encoder: the firmware on both PRUs of
 * one PRU-ICSS (bench_new_pair), each with its own line and encoder(s);
 * PRU0's channel owns the IEP (BISS_TRIG_IEP), PRU1's follows it
 * (BISS_TRIG_IEP_FOLLOW), so the frames of both start together. The host's
 * safety checks of each channel (its scenario's, and for PRU0 the command
 * line's) time its frames as its trigger does: both by the IEP period.
 */
#ifndef SIM_PAIR_H
#define SIM_PAIR_H

#include "bench.h"
#include "biss_proto.h"

#include <stddef.h>
#include <stdint.h>

struct sim_pair_run {
    struct bench_config cfg[2]; /* PRU0's line and PRU1's (soc and core parameters: cfg[0]) */
    unsigned half;              /* MA half period of both, PRU cycles */
    uint32_t iep_period;        /* IEP counts (5 ns); 0: twice the longer frame, whole us */
    uint64_t frames;            /* valid frames each, checked and measured */
    uint64_t settle;            /* ... after this many more, run first */
    int64_t max_ps;             /* simulated time limit; 0: twice the periods the frames take */
    int64_t cap_ps;             /* ... but never more than this */
    const void *image[2];       /* the firmware image of PRU0 and of PRU1 */
    size_t bytes[2];
    const struct biss_config *checks; /* the command line's safety checks, for PRU0; or NULL */
    bool json;                        /* one JSON object ({"pru0", "pru1", ...}) for the text */
};

/* Runs the firmware images on both, checks every frame of each against its
 * own encoder, and prints each PRU's summary (sim_report; or, with json,
 * each PRU's object of biss-sim --json in one object), how far apart
 * the frame starts of the two were and how often PRU1 stalled on PRU0's
 * scratch-pad bank. Returns biss-sim's exit code: 0, 1 (a message
 * printed), 124 (frames not done in time), 3 (a PRU fault), 5 (a frame check
 * failed, frame starts more than one PRU cycle apart, for a BiSS-C and an
 * SSI line their offset varying by more than one, or a bank collision;
 * with json none of these changes it, as in a single run: the object
 * holds them). */
int sim_pair(const struct sim_pair_run *r);

#endif
