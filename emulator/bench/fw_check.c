/* fw_check.c - firmware publications against the slave models (fw_check.h). */
#include "fw_check.h"

#include "biss/biss_shm.h"

#include <string.h>

uint64_t fw_check_sent_word(const biss_slave_cfg *s, const biss_slave_sent *sent) {
    uint64_t v = sent->position << s->fill_bits;
    if (s->has_err) {
        v = (v << 1) | (uint64_t)(sent->nE > 0);
    }
    if (s->has_warn) {
        v = (v << 1) | (uint64_t)(sent->nW > 0);
    }
    if (s->lc_bits) {
        v = (v << s->lc_bits) | sent->lc;
    }
    return v;
}

void fw_check_split(const biss_slave_cfg *s, uint64_t word, uint64_t *position, int *nE, int *nW) {
    word >>= s->lc_bits;
    *nW = s->has_warn ? (int)(word & 1) : 1;
    word >>= s->has_warn;
    *nE = s->has_err ? (int)(word & 1) : 1;
    word >>= s->has_err;
    *position = word >> s->fill_bits;
}

static void read_dram(struct fw_check *fc, uint32_t off, void *buf, size_t n) {
    struct pru_core *c = bench_core(fc->b);
    pru_host_read(c, pru_soc_base(bench_config(fc->b)->soc) + off, buf, n);
}

/* The record of the frame just published: closed, or still in its timeout. */
static const biss_frame_record *frame_record(struct fw_check *fc) {
    link_model *l = bench_link(fc->b);
    uint64_t n = bench_current_frame(fc->b);
    if (n == UINT64_MAX) {
        return NULL;
    }
    if (n < l->biss.frames) {
        return biss_slave_record(&l->biss, n);
    }
    return n == l->biss.frames ? &l->biss.cur : NULL;
}

/* An SSI frame: the code word as the encoder sent it (Gray or binary). */
static void compare_ssi(struct fw_check *fc, const uint8_t *res) {
    link_model *l = bench_link(fc->b);
    uint64_t n = bench_current_frame(fc->b);
    const ssi_frame_record *r = n < l->ssi.frames    ? ssi_slave_record(&l->ssi, n)
                                : n == l->ssi.frames ? &l->ssi.cur
                                                     : NULL;
    if (!r) {
        fc->unmatched++;
        return;
    }
    uint32_t lo, hi;
    memcpy(&lo, res + BISS_R_SLAVE0 + BISS_R_S_DATA_LO, 4);
    memcpy(&hi, res + BISS_R_SLAVE0 + BISS_R_S_DATA_HI, 4);
    memcpy(&fc->status[0], res + BISS_R_SLAVE0 + BISS_R_S_STATUS, 4);
    fc->data[0] = (uint64_t)hi << 32 | lo;
    fc->sent[0] = r->position;
    if (fc->data[0] != r->code) {
        fc->mismatches++;
        if (!fc->first_mismatch_frame) {
            fc->first_mismatch_frame = fc->publications;
        }
    }
}

/* Slave i's data word and status in the result buffer res. */
static uint64_t result_word(const uint8_t *res, unsigned i, uint32_t *status) {
    const uint8_t *s = res + BISS_R_SLAVE0 + i * BISS_R_SLAVE_SIZE;
    uint32_t lo, hi;
    memcpy(&lo, s + BISS_R_S_DATA_LO, 4);
    memcpy(&hi, s + BISS_R_S_DATA_HI, 4);
    memcpy(status, s + BISS_R_S_STATUS, 4);
    return (uint64_t)hi << 32 | lo;
}

static void compare(struct fw_check *fc, const uint8_t *res) {
    link_model *l = bench_link(fc->b);
    if (l->sc.protocol == SCENARIO_SSI) {
        compare_ssi(fc, res);
        return;
    }
    const biss_frame_record *r = frame_record(fc);
    if (!r) {
        fc->unmatched++;
        return;
    }
    bool same = true;
    for (unsigned i = 0; i < l->sc.biss.n && i < BISS_MAX_SLAVES; i++) {
        fc->data[i] = result_word(res, i, &fc->status[i]);
        uint64_t want = fw_check_sent_word(&l->sc.biss.s[i], &r->s[i]);
        fc->sent[i] = r->s[i].position;
        /* a word whose CRC failed is reported as such; only a word passed
         * as right must be what was sent */
        same = same && (fc->data[i] == want || !(fc->status[i] & BISS_RS_CRC_OK));
    }
    if (!same) {
        fc->mismatches++;
        if (!fc->first_mismatch_frame) {
            fc->first_mismatch_frame = fc->publications;
        }
    }
}

/* A frame the firmware refused for its ACK (BISS_RF_ACK_JUMP): was every
 * word right all the same (CRC good, and what was sent)? Then the rule
 * cost a good frame. */
static void judge_refused(struct fw_check *fc, const uint8_t *res) {
    link_model *l = bench_link(fc->b);
    const biss_frame_record *r = l->sc.protocol == SCENARIO_BISS ? frame_record(fc) : NULL;
    if (!r) {
        return;
    }
    for (unsigned i = 0; i < l->sc.biss.n && i < BISS_MAX_SLAVES; i++) {
        uint32_t st;
        if (result_word(res, i, &st) != fw_check_sent_word(&l->sc.biss.s[i], &r->s[i]) ||
            !(st & BISS_RS_CRC_OK)) {
            return;
        }
    }
    fc->ack_jump_good++;
}

/* A result buffer as struct fw_frame. */
static void keep(struct fw_frame *f, const uint8_t *res) {
    uint16_t u16;
    f->seen = 1;
    memcpy(&f->frame, res + BISS_R_FRAME, 4);
    memcpy(&f->flags, res + BISS_R_FLAGS, 4);
    memcpy(&f->timestamp, res + BISS_R_TIMESTAMP, 4);
    memcpy(&u16, res + BISS_R_DELAY_RAW, 2);
    f->delay_raw = u16;
    memcpy(&u16, res + BISS_R_DELAY_AVG, 2);
    f->delay_avg = u16;
    memcpy(&u16, res + BISS_R_HALF, 2);
    f->half = u16;
    f->sample_point = res[BISS_R_SAMPLE_POINT];
    f->lag = res[BISS_R_LAG_PERIODS];
    f->nslaves = res[BISS_R_NSLAVES];
    for (unsigned i = 0; i < f->nslaves && i < BISS_MAX_SLAVES; i++) {
        f->data[i] = result_word(res, i, &f->status[i]);
    }
}

static void on_publish(void *ctx, uint32_t addr) {
    struct fw_check *fc = ctx;
    (void)addr;
    bool watched = fc->watch != UINT64_MAX && bench_current_frame(fc->b) == fc->watch;
    if (fc->frames >= fc->limit && !watched) {
        return;
    }
    uint32_t buf;
    uint8_t res[BISS_RES_SIZE];
    read_dram(fc, BISS_ST_BUF, &buf, 4);
    read_dram(fc, BISS_RES0 + (buf & 1) * BISS_RES_SIZE, res, sizeof res);
    if (watched) {
        keep(&fc->watched, res);
    }
    if (fc->frames >= fc->limit) {
        return;
    }
    uint32_t flags;
    uint16_t u16;
    memcpy(&flags, res + BISS_R_FLAGS, 4);
    fc->publications++;
    fc->last_flags = flags;
    fc->no_slave += !!(flags & BISS_RF_NO_SLAVE);
    fc->proc_errors += !!(flags & BISS_RF_PROC_ERROR);
    fc->training += !!(flags & BISS_RF_TRAINING);
    if (flags & BISS_RF_ACK_JUMP) {
        fc->ack_jumps++;
        judge_refused(fc, res);
    }
    fc->delay_frames += (flags & (BISS_RF_VALID | BISS_RF_TRAINING)) != 0;
    memcpy(&u16, res + BISS_R_DELAY_RAW, 2);
    fc->delay_raw = u16;
    memcpy(&u16, res + BISS_R_DELAY_AVG, 2);
    fc->delay_avg = u16;
    memcpy(&u16, res + BISS_R_PROC_CLOCKS, 2);
    if (u16 > fc->proc_clocks_max && (flags & BISS_RF_VALID)) {
        fc->proc_clocks_max = u16;
    }
    memcpy(&u16, res + BISS_R_HALF, 2);
    fc->half = u16;
    fc->sample_point = res[BISS_R_SAMPLE_POINT];
    fc->lag = res[BISS_R_LAG_PERIODS];
    fc->nslaves = res[BISS_R_NSLAVES];
    if (!(flags & BISS_RF_VALID)) {
        return;
    }
    if (fc->frames == 0 || fc->delay_raw < fc->delay_raw_min) {
        fc->delay_raw_min = fc->delay_raw;
    }
    if (fc->delay_raw > fc->delay_raw_max) {
        fc->delay_raw_max = fc->delay_raw;
    }
    fc->frames++;
    fc->crc_errors += !!(flags & BISS_RF_CRC_ERROR);
    compare(fc, res);
}

void fw_check_attach(struct fw_check *fc, struct bench *b) {
    memset(fc, 0, sizeof(*fc));
    fc->b = b;
    fc->limit = UINT64_MAX;
    fc->watch = UINT64_MAX;
    pru_set_store_watch(bench_core(b), BISS_ST_SEQ, on_publish, fc);
}

void fw_check_watch(struct fw_check *fc, uint64_t k) {
    fc->watch = k;
    fc->watched.seen = 0;
}

void fw_check_restart(struct fw_check *fc, uint64_t limit) {
    struct bench *b = fc->b;
    uint64_t watch = fc->watch;
    struct fw_frame watched = fc->watched;
    memset(fc, 0, sizeof(*fc));
    fc->b = b;
    fc->limit = limit;
    fc->watch = watch;
    fc->watched = watched;
}
