/* slave_fw_rig.h - the encoder firmware (pru_slave/) on PRU1 of an
 * emulated PRU-ICSS, driven by a scripted MA waveform at its pin, beside
 * the C slave model (emulator/slave/) driven by the same waveform: both
 * SL outputs are recorded, for the suites to compare bit by bit.
 *
 * A script is a list of frames, each an MA waveform a master would make:
 * MA falls, `clocks` rising edges a half period `half` PRU cycles apart,
 * then the CDM (MA low after the last rise for CDM = 1) held until `gap`
 * after the last rise, MA back high. The rig builds the whole waveform,
 * runs the firmware through it (reading the firmware's record of each
 * frame's words just before the frame starts), then the model. */
#ifndef SLAVE_FW_RIG_H
#define SLAVE_FW_RIG_H

#include "biss_slave.h"
#include "pruss.h"
#include "slave_fw.h"
#include "waveform.h"

#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>

#define RIG_MAX_FRAMES 4096
#define RIG_MA_BIT     1 /* the images' MA_IN_BIT (pru_slave/CMakeLists.txt) */

struct rig_frame {
    unsigned half;    /* MA half period, PRU cycles */
    unsigned clocks;  /* rising edges */
    int cdm;          /* MA level held after the last rise: 1 = low (CDM 1) */
    sim_ps gap;       /* from the last rise to MA back high / the next frame */
    sim_ps t0;        /* the first fall (filled by the rig) */
    sim_ps rise[160]; /* the rising edges (filled; at most 160 are kept) */
    /* the firmware's record of this frame, read just before it starts */
    struct biss_slv_frame_rec rec;
};

struct rig {
    struct pru_icss *icss;
    struct pru_core *core; /* PRU1 */
    struct slave_fw_ram ram;
    struct biss_proto_io io;
    waveform ma;   /* at the slave pin, the whole script */
    waveform sl;   /* SL the firmware drove */
    waveform sl_m; /* SL the model drove */
    sim_ps cursor; /* the end of the script so far */
    struct rig_frame *frames;
    unsigned nframes;
    biss_chain_cfg chain;
    event_queue q;
    biss_slave *model;
    /* Frames the master ends inside the slaves' data (or before the ACK):
     * the next frame is built after their timeout, whose end is then late
     * by the work over WORK_PAD (ST_WORK says how much). */
    bool partial_frames;
    FILE *trace; /* RIG_TRACE=file: the firmware's instructions appended, one a line */
    /* Non-zero: rig_add's CDM = 1 frames fall this long after their last
     * rise (a master that moves MA late), not half a period. */
    sim_ps cdm_fall;
    /* rig_add's edges this far past the PRU's cycle grid (0..4999 ps) */
    sim_ps phase;
};

/* A rig with the firmware image built for PRU1 loaded and started, and
 * params for both cores (NULL: the defaults). The chain is loaded into
 * the firmware (slave_fw_load) and into the model. */
void rig_open(struct rig *r, const biss_chain_cfg *chain, const struct pru_params *params);
void rig_close(struct rig *r);

/* Appends a frame to the script. */
struct rig_frame *rig_add(struct rig *r, unsigned half, unsigned clocks, int cdm, sim_ps gap);
/* Appends n frames with the CDM bits of cdm[] (NULL: all 0). */
void rig_add_n(struct rig *r, unsigned n, unsigned half, unsigned clocks, const int *cdm,
               sim_ps gap);

/* Runs the firmware over the script (frame records read on the way), then
 * the model. */
void rig_run(struct rig *r);
/* Runs the firmware alone until t (for waits with no MA). */
void rig_run_fw_until(struct rig *r, sim_ps t);

/* The firmware's and the model's SL at t. */
int rig_sl_fw(struct rig *r, sim_ps t);
int rig_sl_model(struct rig *r, sim_ps t);

/* Compares both SL outputs in every frame where a master samples: just
 * before each rising edge after the first (the bit the one before it put
 * out) and just before each frame's first fall (the timeout over).
 * Returns the number of differences; the first is described in what. */
unsigned rig_compare(struct rig *r, char *what, size_t len);

/* The model's record of frame k (from 0). */
const biss_frame_record *rig_model_record(struct rig *r, unsigned k);

/* The firmware's status words. */
struct biss_slv_status rig_status(struct rig *r);

/* Response time of the firmware: for every MA rising edge after which its
 * SL changed before the next MA edge, the delay from the edge to the
 * change, min and max in ps (0, 0 if none). */
void rig_latency(struct rig *r, sim_ps *min, sim_ps *max, unsigned *n);

#endif
