/* fw_check.c - firmware publications against the slave models (fw_check.h). */
#include "fw_check.h"

#include "frame_marks.h"

#include <string.h>

/* The record of the frame just published: closed, or still in its
 * timeout; what each slave sent, in every model's terms. */
static const void *frame_record(struct fw_check *fc, slave_frame *f) {
    link_model *l = bench_link(fc->b);
    uint64_t n = bench_current_frame(fc->b);
    const void *r = n == UINT64_MAX ? NULL : link_record(l, n);
    if (r) {
        l->model->frame(link_model_cfg(l), r, f);
    }
    return r;
}

/* The data word slave i sent in frame f (its word fc->words[i]). */
static uint64_t sent_word(const struct fw_check *fc, const slave_frame *f, unsigned i) {
    return biss_proto_word_compose(&fc->layout[i], f->word[i].code, f->word[i].nE > 0,
                                   f->word[i].nW > 0, f->word[i].lc);
}

/* A valid frame's publication (now: the watch sees the store's own cycle)
 * against the slave's record of it: after its last bit at the master's SL
 * pin, and after the position's latch (an SSI encoder latches on the
 * first fall). A record without its last bit (the slave never clocked it
 * out) is not timed. */
static void time_publication(struct fw_check *fc, sim_ps latch, sim_ps last, sim_ps out) {
    if (!last) {
        return;
    }
    sim_ps pub = pru_time_ps(bench_core(fc->b));
    bench_span_add(&fc->latency, pub - (last + out + fc->sl_delay_ps));
    bench_span_add(&fc->age, pub - latch);
}

/* Each word against what its slave sent: a word passed as right must be
 * what was sent (a word whose CRC failed is reported as such). */
static void compare(struct fw_check *fc, const struct biss_sample *smp) {
    link_model *l = bench_link(fc->b);
    slave_frame f;
    const slave_word *w = fc->words;
    unsigned n = fc->nwords;
    const void *r = frame_record(fc, &f);
    if (!r) {
        fc->unmatched++;
        return;
    }
    bool same = true;
    for (unsigned i = 0; i < n && i < BISS_MAX_SLAVES; i++) {
        fc->data[i] = smp->slave[i].data;
        fc->status[i] = smp->slave[i].status;
        fc->sent[i] = f.word[i].position;
        bool crc_failed = w[i].crc_poly && !(fc->status[i] & BISS_RS_CRC_OK);
        same = same && (fc->data[i] == sent_word(fc, &f, i) || crc_failed);
    }
    time_publication(fc, f.latch_ps, f.last_bit_ps, l->model->out_delay(link_model_cfg(l)));
    if (!same) {
        fc->mismatches++;
        if (!fc->first_mismatch_frame) {
            fc->first_mismatch_frame = fc->publications;
        }
        if (!link_biss(l)) {
            return; /* the classes are BiSS-C's, from its records */
        }
        struct wrong_frame wf;
        wrong_frame_classify(
            &l->sc.biss, r, fc->data, smp->frame, &l->sl_master, pru_time_ps(bench_core(fc->b)),
            2 * (int64_t)smp->delay.half * PRU_PS_PER_CYCLE, bench_core(fc->b), &wf);
        fc->wrong_by_class[wf.cls]++;
        if (fc->nwrong < FW_CHECK_WRONG_KEPT) {
            fc->wrong[fc->nwrong++] = wf;
        }
    }
}

/* Whether every word of a decoded frame is right (CRC good, and what was
 * sent): a frame refused all the same is a good frame lost. */
static bool words_right(struct fw_check *fc, const struct biss_sample *smp) {
    slave_frame f;
    if (!frame_record(fc, &f)) {
        return false;
    }
    for (unsigned i = 0; i < fc->nwords && i < BISS_MAX_SLAVES; i++) {
        if (smp->slave[i].data != sent_word(fc, &f, i) || !smp->slave[i].crc_ok) {
            return false;
        }
    }
    return true;
}

/* A frame the firmware refused for its ACK (BISS_RF_ACK_JUMP) or an edge
 * off the bit grid (BISS_RF_OFF_GRID): was every word right all the same?
 * Then the rule cost a good frame. */
static bool refused_good(struct fw_check *fc, const struct biss_shm_result *res) {
    /* a refused frame is not VALID, so decode its words as if it were */
    struct biss_shm_result as_valid = *res;
    as_valid.flags =
        (as_valid.flags & ~(uint32_t)(BISS_RF_ACK_JUMP | BISS_RF_OFF_GRID)) | BISS_RF_VALID;
    struct biss_sample smp;
    return biss_sample_decode(&fc->cfg, true, 0, &as_valid, &smp) == BISS_OK &&
           words_right(fc, &smp);
}

/* A decoded publication as struct fw_frame. */
static void keep(struct fw_frame *f, const struct biss_sample *smp) {
    f->seen = 1;
    f->sample = *smp;
    f->frame = smp->frame;
    f->flags = smp->flags;
    f->timestamp = smp->timestamp;
    f->delay_raw = smp->delay.raw;
    f->delay_avg = smp->delay.avg;
    f->half = smp->delay.half;
    f->sample_point = smp->sample_point;
    f->lag = smp->lag_periods;
    f->nslaves = smp->nslaves;
    for (unsigned i = 0; i < f->nslaves && i < BISS_MAX_SLAVES; i++) {
        f->data[i] = smp->slave[i].data;
        f->status[i] = smp->slave[i].status;
    }
}

/* Counts one publication (below the limit). */
static void count(struct fw_check *fc, const struct biss_shm_result *res, struct biss_sample *smp) {
    uint32_t flags = smp->flags;
    fc->publications++;
    fc->last_flags = flags;
    fc->no_slave += smp->no_slave;
    fc->proc_errors += smp->proc_error;
    fc->training += smp->training;
    if (smp->ack_jump) {
        fc->ack_jumps++;
        fc->ack_jump_good += refused_good(fc, res);
    }
    if (smp->off_grid) {
        fc->off_grid++;
        fc->off_grid_good += refused_good(fc, res);
    }
    fc->delay_frames += smp->valid || smp->training;
    fc->delay_raw = smp->delay.raw;
    fc->delay_avg = smp->delay.avg;
    fc->delay_frame = smp->frame;
    if (smp->proc_clocks > fc->proc_clocks_max && smp->valid) {
        fc->proc_clocks_max = smp->proc_clocks;
    }
    fc->half = smp->delay.half;
    fc->sample_point = smp->sample_point;
    fc->lag = smp->lag_periods;
    fc->nslaves = smp->nslaves;
    biss_safety_check(&fc->cfg, &fc->safety, smp);
    biss_link_check(&fc->link, smp);
    if (smp->safety & BISS_SAFE_FAULTS) {
        fc->safety_faults++;
        fc->safety_first_fault = fc->safety_first_fault ? fc->safety_first_fault : smp->frame;
    }
    if (smp->misframed) {
        /* refused by the host's nE/nW check (its words stay decoded) */
        fc->misframed++;
        fc->misframed_good += words_right(fc, smp);
    }
    if (!smp->valid) {
        return;
    }
    if (fc->frames == 0 || fc->delay_raw < fc->delay_raw_min) {
        fc->delay_raw_min = fc->delay_raw;
    }
    if (fc->delay_raw > fc->delay_raw_max) {
        fc->delay_raw_max = fc->delay_raw;
    }
    fc->frames++;
    fc->crc_errors += smp->crc_error;
    compare(fc, smp);
}

static void on_publish(void *ctx, uint32_t addr) {
    struct fw_check *fc = ctx;
    (void)addr;
    bool watched = fc->watch != UINT64_MAX && bench_current_frame(fc->b) == fc->watch;
    if (fc->frames >= fc->limit && !watched) {
        return;
    }
    /* the buffer just published (ST_BUF is written before ST_SEQ), decoded
     * as libbiss decodes it */
    struct biss_proto_io io = bench_fw_io(fc->b);
    struct biss_shm_result res;
    struct biss_sample smp;
    uint32_t seq;
    bool any;
    if (biss_proto_pub_seq_any(&io, &seq, &any) == BISS_OK && !any) {
        return; /* the start-up clearing the status words: nothing published */
    }
    if (biss_proto_result_get(&io, BISS_MAX_SLAVES, &res) != BISS_OK ||
        biss_sample_decode(&fc->cfg, true, 0, &res, &smp) != BISS_OK) {
        /* a result no firmware with this layout publishes is wrong too */
        fc->bad_results++;
        fc->mismatches += fc->frames < fc->limit;
        return;
    }
    bench_iep_published(fc->b, bench_current_frame(fc->b), res.flags);
    if (watched) {
        keep(&fc->watched, &smp);
    }
    if (fc->frames < fc->limit) {
        count(fc, &res, &smp);
    }
}

/* Each slave's word, as the configuration (fixed for the run) gives it. */
static void words_of(struct fw_check *fc) {
    link_model *l = bench_link(fc->b);
    fc->nwords = l->model->words(link_model_cfg(l), fc->words);
    for (unsigned i = 0; i < fc->nwords && i < SLAVE_MAX_WORDS; i++) {
        fc->layout[i] = bench_fw_slave_word(&fc->words[i]);
    }
}

void fw_check_attach(struct fw_check *fc, struct bench *b) {
    memset(fc, 0, sizeof(*fc));
    fc->b = b;
    bench_fw_config(b, &fc->cfg);
    fc->limit = UINT64_MAX;
    fc->watch = UINT64_MAX;
    biss_link_init(&fc->link, 0, 0);
    fc->sl_delay_ps = (sim_ps)(line_nominal_delay_ps(&bench_link(b)->sc.sl_line) + 0.5);
    words_of(fc);
    pru_set_store_watch(bench_core(b), BISS_ST_SEQ, on_publish, fc);
}

int fw_check_configure(struct fw_check *fc, unsigned half) {
    biss_safety_restart(&fc->safety);
    return bench_fw_configure(fc->b, &fc->cfg, half);
}

void fw_check_watch(struct fw_check *fc, uint64_t k) {
    fc->watch = k;
    fc->watched.seen = 0;
}

void fw_check_restart(struct fw_check *fc, uint64_t limit) {
    struct bench *b = fc->b;
    struct biss_config cfg = fc->cfg;
    uint64_t watch = fc->watch;
    struct fw_frame watched = fc->watched;
    sim_ps sl_delay = fc->sl_delay_ps;
    uint32_t link_window = fc->link.window, link_warn = fc->link.warn;
    memset(fc, 0, sizeof(*fc));
    biss_link_init(&fc->link, link_window, link_warn);
    fc->sl_delay_ps = sl_delay;
    fc->b = b;
    fc->cfg = cfg;
    fc->limit = limit;
    fc->watch = watch;
    fc->watched = watched;
    words_of(fc);
}
