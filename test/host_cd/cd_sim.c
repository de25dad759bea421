#include "cd_sim.h"

#include <string.h>

void cd_sim_init(cd_sim *s) {
    memset(s, 0, sizeof *s);
    s->flip_step = -1;
    s->fail_frame = -1;
}

void cd_sim_add(cd_sim *s, biss_ctrl *slave) {
    if (s->nslaves < CD_SIM_MAX_SLAVES) {
        s->slave[s->nslaves++] = slave;
    }
}

/* One frame: returns its CDS, sends cdm in its timeout. */
static int frame(cd_sim *s, int cdm) {
    int cds = s->cds;
    int next = 0;
    for (unsigned i = 0; i < s->nslaves; i++) {
        next |= biss_ctrl_cdm(s->slave[i], cdm);
    }
    s->cds = next;
    s->frames++;
    s->zeros = cdm ? 0 : s->zeros + 1;
    return cds;
}

void cd_sim_idle(cd_sim *s, unsigned frames) {
    while (frames--) {
        frame(s, 0);
    }
}

static uint16_t get16(const uint8_t *at) {
    return (uint16_t)(at[0] | at[1] << 8);
}

static unsigned op_at(const uint8_t *dram, unsigned len, unsigned step) {
    if (step >= len) {
        return BISS_CDOP_END;
    }
    return (dram[BISS_CD_PROG + step / 4] >> (2 * (step % 4))) & 3u;
}

static void record(cd_sim *s, uint8_t *dram, unsigned step, int cds) {
    if ((long)step == s->flip_step) {
        cds = !cds;
    }
    uint8_t *at = &dram[BISS_CD_RESP + step / 8];
    *at = (uint8_t)((*at & ~(1u << (step % 8))) | (unsigned)cds << (step % 8));
}

static void finish(uint8_t *dram, unsigned status, unsigned steps) {
    uint8_t *st = dram + BISS_ST_CD_STATUS;
    st[0] = (uint8_t)status;
    st[1] = (uint8_t)(status >> 8);
    st[2] = (uint8_t)steps;
    st[3] = (uint8_t)(steps >> 8);
    memcpy(dram + BISS_ST_CD_SEQ, dram + BISS_CD_CMD, 4);
}

void cd_sim_run(cd_sim *s, uint8_t *dram) {
    unsigned len = get16(dram + BISS_CD_STEPS);
    unsigned limit = get16(dram + BISS_CD_WAIT_LIMIT);
    if (len < 1 || len > BISS_CD_MAX_STEPS) {
        finish(dram, BISS_CDST_ERR_STEPS, 0);
        return;
    }
    while (s->zeros < BISS_CD_IDLE_ZEROS) {
        frame(s, 0);
    }
    unsigned long first = s->frames;
    unsigned step = 0, waited = 0;
    long pending = -1; /* step whose answer this frame's CDS is */
    for (;;) {
        if ((long)(s->frames - first) == s->fail_frame) {
            /* no timeout, no CDM: the slave sees nothing */
            s->frames++;
            s->zeros = 0;
            finish(dram, BISS_CDST_ERR_FRAME, step);
            break;
        }
        int cds = s->cds;
        if (pending >= 0) {
            record(s, dram, (unsigned)pending, cds);
            pending = -1;
        }
        unsigned op = op_at(dram, len, step);
        if (op == BISS_CDOP_WAIT) {
            if (!cds) {
                frame(s, 0);
                if (++waited > limit) {
                    finish(dram, BISS_CDST_ERR_WAIT, step);
                    s->zeros = 1;
                    break;
                }
                continue;
            }
            waited = 0;
            op = op_at(dram, len, ++step); /* goes out in this same frame */
        }
        if (op == BISS_CDOP_END) {
            frame(s, 0);
            finish(dram, BISS_CDST_DONE, step);
            s->zeros = 1; /* the slaves count 14 zeros afresh from a frame's end */
            break;
        }
        frame(s, op == BISS_CDOP_1);
        pending = step++;
    }
    s->prog_frames = s->frames - first;
}
