/* A frame-by-frame stand-in for the firmware's CDM program (biss_shm.h,
 * pru_fw/cd.p CD_PREPARE / CD_COMMIT), driving slave control
 * models directly: per frame, the CDM goes to every slave; the OR of their
 * answers is the CDS of the next frame (one shared SL line). The program
 * is taken from a packed data RAM image, as the firmware reads it. */
#ifndef CD_SIM_H
#define CD_SIM_H

#include "biss_cd.h"
#include "biss_ctrl.h"

#define CD_SIM_MAX_SLAVES 8

typedef struct {
    biss_ctrl *slave[CD_SIM_MAX_SLAVES];
    unsigned nslaves;
    int cds;                   /* the CDS the next frame carries */
    unsigned zeros;            /* frames in a row that sent CDM 0 */
    unsigned long frames;      /* frames run so far */
    unsigned long prog_frames; /* frames of the last program (its start to its end frame) */
    long flip_step;            /* answer of this step is recorded inverted (-1: none) */
    long fail_frame;           /* this frame of the program fails (-1: none) */
} cd_sim;

void cd_sim_init(cd_sim *s);
void cd_sim_add(cd_sim *s, biss_ctrl *slave);

/* Runs frames of CDM 0. */
void cd_sim_idle(cd_sim *s, unsigned frames);

/* Runs the program in dram (written by biss_cd_shm_put) as the firmware
 * would: CDM 0 frames until 14 in a row went out (those of an earlier
 * program count, as in the firmware), then one step per frame. Leaves the
 * status words and answers in dram. */
void cd_sim_run(cd_sim *s, uint8_t *dram);

#endif
