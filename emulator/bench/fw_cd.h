/*
 * fw_cd.h - control communication with the encoder models through the
 * BiSS-C master firmware on the bench: a CDM program (proto/biss_cd.h) is
 * handed to the firmware as a host would and its answers parsed when it
 * has run, while position frames go on.
 */
#ifndef FW_CD_H
#define FW_CD_H

#include "bench.h"
#include "bench_fw.h"

struct fw_cd {
    struct bench *b;
    const biss_cd_prog *prog;
    uint32_t cmd;    /* CD_CMD written for it */
    int put_error;   /* proto's refusal to hand it over (BISS_E_CD_BUSY: one still runs) */
    uint64_t frame0; /* slave frames when it was issued */
    uint64_t frames; /* frames it took, once done */
    int done;
    biss_cd_err err;
    biss_cd_result result;
    unsigned status; /* the firmware's BISS_CDST_* */
};

/* Hands the program to the firmware (it starts after 14 frames of CDM 0). */
void fw_cd_issue(struct fw_cd *cd, struct bench *b, const biss_cd_prog *p, uint16_t wait_limit);

/* Checks whether the firmware has ended it; fills err/result/frames then.
 * Returns cd->done. */
int fw_cd_poll(struct fw_cd *cd);

#endif
