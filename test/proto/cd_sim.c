#include "cd_sim.h"

#include "biss_crc.h"

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

#define PAST_END 0x10u /* step_at past the length, as the firmware's CD_OP */

static unsigned step_at(const uint8_t *dram, unsigned len, unsigned step) {
    if (step >= len) {
        return PAST_END;
    }
    return (dram[BISS_CD_PROG + step / 2] >> (4 * (step % 2))) & 15u;
}

static void record(uint8_t *dram, unsigned step, int cds) {
    uint8_t *at = &dram[BISS_CD_RESP + step / 8];
    *at = (uint8_t)((*at & ~(1u << (step % 8))) | (unsigned)cds << (step % 8));
}

static void finish(uint8_t *dram, unsigned status, unsigned bytes, unsigned steps) {
    uint8_t *st = dram + BISS_ST_CD_STATUS;
    st[0] = (uint8_t)status;
    st[1] = (uint8_t)bytes;
    st[2] = (uint8_t)steps;
    st[3] = (uint8_t)(steps >> 8);
    memcpy(dram + BISS_ST_CD_SEQ, dram + BISS_CD_CMD, 4);
}

/* The firmware's program state (P_CD). */
struct run {
    unsigned len, limit, ida_step, ida_expect;
    unsigned step, waited;
    long pending; /* step whose answer the next frame's CDS is */
    unsigned crc_m, crc_s, cdm_sent, err, bytes;
    bool open;
};

/* The CDM of the next frame for either CDS (CD_PREPARE). */
static void prepare(const struct run *r, const uint8_t *dram, int cdm[2]) {
    unsigned st = step_at(dram, r->len, r->step);
    cdm[0] = cdm[1] = 0;
    if (st == PAST_END || (r->err && st == BISS_CDOP_1)) {
        return;
    }
    unsigned op = st & 3u;
    if (op == BISS_CDOP_WAIT) { /* CDM 1 while the slave's S is late */
        cdm[0] = 1;
        cdm[1] = (step_at(dram, r->len, r->step + 1) & (PAST_END | 3u)) == BISS_CDOP_1;
        return;
    }
    unsigned bit = op == BISS_CDOP_CRC ? !(r->crc_m >> 3 & 1u) : op;
    if (r->step == r->ida_step && r->err) {
        bit ^= 1u;
    }
    cdm[0] = cdm[1] = (int)bit;
}

static void set_err(struct run *r, unsigned status) {
    if (!r->err) {
        r->err = status;
    }
}

/* The answer cds to step r->pending: recorded and checked (CD_COMMIT). */
static void answer(struct run *r, uint8_t *dram, int cds) {
    unsigned step = (unsigned)r->pending;
    record(dram, step, cds);
    unsigned k = step + 9u - r->ida_step;
    if (r->ida_step && k < 8 && (unsigned)cds != (r->ida_expect >> k & 1u)) {
        set_err(r, BISS_CDST_ERR_IDA);
    }
    unsigned cl = step_at(dram, r->len, step) >> 2;
    if (cl == BISS_CDCL_CHECK) {
        if ((unsigned)cds == (r->crc_s >> 3 & 1u)) {
            set_err(r, BISS_CDST_ERR_CRC);
        }
        r->crc_s = (r->crc_s << 1) & 15u;
    } else if (cl != BISS_CDCL_NONE) {
        r->crc_s = biss_crc_bit(r->crc_s, BISS_CRC4_POLY, cds);
        if (cl == BISS_CDCL_ECHO && (unsigned)cds != r->cdm_sent) {
            set_err(r, BISS_CDST_ERR_ECHO);
        }
    }
}

/* Step st went out with cdm: the CRC of the CDM, the byte count. */
static void sent(struct run *r, unsigned st, int cdm) {
    r->cdm_sent = (unsigned)cdm;
    if (st >= BISS_CDOP_CRC) {
        unsigned crc_bit = (st & 3u) == BISS_CDOP_CRC;
        r->crc_m = biss_crc_bit(r->crc_m, BISS_CRC4_POLY, (int)((unsigned)cdm ^ crc_bit));
    } else if (!r->err && r->open) {
        r->open = false;
        r->bytes++;
    }
}

void cd_sim_run(cd_sim *s, uint8_t *dram) {
    struct run r = {.len = get16(dram + BISS_CD_STEPS),
                    .limit = get16(dram + BISS_CD_WAIT_LIMIT),
                    .ida_step = get16(dram + BISS_CD_IDA_STEP),
                    .ida_expect = dram[BISS_CD_IDA_EXPECT],
                    .pending = -1};
    if (r.len < 1 || r.len > BISS_CD_MAX_STEPS) {
        finish(dram, BISS_CDST_ERR_STEPS, 0, 0);
        return;
    }
    while (s->zeros < BISS_CD_IDLE_ZEROS) {
        frame(s, 0);
    }
    unsigned long first = s->frames;
    for (;;) {
        int cdm[2];
        prepare(&r, dram, cdm);
        if ((long)(s->frames - first) == s->fail_frame) {
            /* no timeout, no CDM: the slave sees nothing */
            s->frames++;
            s->zeros = 0;
            finish(dram, BISS_CDST_ERR_FRAME, r.bytes, r.step);
            break;
        }
        int cds = s->cds;
        if (r.pending >= 0 && r.pending == s->flip_step) {
            cds = !cds;
        }
        int out = cdm[cds];
        frame(s, out);
        if (r.pending >= 0) {
            answer(&r, dram, cds);
            r.pending = -1;
        }
        unsigned st = step_at(dram, r.len, r.step);
        if (st == BISS_CDOP_WAIT) {
            if (!cds) {
                if (++r.waited > r.limit) {
                    finish(dram, BISS_CDST_ERR_WAIT, r.bytes, r.step);
                    s->zeros = out ? 0 : 1;
                    break;
                }
                continue;
            }
            r.waited = 0;
            r.crc_m = r.crc_s = 0;
            r.open = true;
            st = step_at(dram, r.len, ++r.step); /* goes out in this same frame */
        }
        if (st == PAST_END || (r.err && st == BISS_CDOP_1 && !out)) {
            finish(dram, r.err ? r.err : BISS_CDST_DONE, r.bytes, r.step);
            s->zeros = out ? 0 : 1; /* the slaves count 14 zeros afresh from a frame's end */
            break;
        }
        sent(&r, st, out);
        r.pending = r.step++;
    }
    s->prog_frames = s->frames - first;
}
