/* ssi_model.c - the SSI encoder (ssi_slave.h) as an encoder model
 * (slave_model.h): its configuration's table and relations, and its
 * operations. */
#include "scenario.h"

#include <stdio.h>

#define I(name, kind, member, scale, lo, hi) SF_FIELD(name, kind, ssi_cfg, member, scale, lo, hi)

/* What the encoder needs beyond the ranges. */
static int check(const void *obj, char *err, size_t errlen) {
    const ssi_cfg *c = obj;
    const char *e = NULL;
    if (c->out_delay_ps <= 0) {
        e = "output_delay_ns: must be > 0";
    } else if (c->monoflop_ps <= 0) {
        e = "monoflop_ns: must be > 0";
    }
    if (e) {
        snprintf(err, errlen, "%s", e);
        return -1;
    }
    return 0;
}

static const sf_field fields[] = {
    I("bits", SF_UNSIGNED, bits, 0, 1, 64),
    I("position", SF_U64, pos0, 0, 0, SF_U64_MAX),
    I("speed_cps", SF_DOUBLE, speed_cps, 1, -SF_MAX_SPEED, SF_MAX_SPEED),
    I("output_delay_ns", SF_PS, out_delay_ps, 0, 0, SF_MAX_EDGE_NS),
    I("monoflop_ns", SF_PS, monoflop_ps, 0, 0, SF_MAX_FRAME_NS),
    SF_FLAG("gray", SF_BOOL, ssi_cfg, gray),
    SF_END,
};

static const sf_table table = {.fields = fields, .check = check};

int ssi_cfg_check(const ssi_cfg *c, char *err, size_t errlen) {
    return sf_check_object(&table, c, "", err, errlen);
}

static void cfg_default(void *cfg) {
    ssi_cfg_default(cfg);
}

static void init(void *m, const void *cfg, event_queue *q, sim_edge_sink out) {
    ssi_slave_init(m, cfg, q, out);
}

static void ma_edge(void *m, sim_ps t, int level) {
    ssi_slave_ma_edge(m, t, level);
}

static const void *record(const void *m, uint64_t n) {
    const ssi_slave *s = m;
    return n == s->st.frames ? &s->cur : (const void *)ssi_slave_record(s, n);
}

/* The position is latched at the first fall, which starts the word. */
static sim_ps end(const void *rec) {
    return ((const ssi_frame_record *)rec)->end_ps;
}

static void frame(const void *cfg, const void *rec, slave_frame *f) {
    (void)cfg;
    const ssi_frame_record *r = rec;
    f->frame = r->frame;
    f->start_ps = r->start_ps;
    f->end_ps = r->end_ps;
    f->latch_ps = r->start_ps;
    f->last_bit_ps = r->last_bit_ps;
    f->data_ps = r->start_ps;
    f->nwords = 1;
    f->word[0].position = r->position;
    f->word[0].code = r->code;
    f->word[0].nE = f->word[0].nW = -1;
    f->word[0].lc = f->word[0].crc = 0;
}

static sim_ps out_delay(const void *cfg) {
    return ((const ssi_cfg *)cfg)->out_delay_ps;
}

static sim_ps monoflop(const void *cfg, sim_ps period_ps) {
    (void)period_ps;
    return ((const ssi_cfg *)cfg)->monoflop_ps;
}

/* The word's bits and the rise after the last. */
static unsigned clocks(const void *cfg, sim_ps period_ps) {
    (void)period_ps;
    return ((const ssi_cfg *)cfg)->bits + 1;
}

static unsigned words(const void *cfg, slave_word *w) {
    const ssi_cfg *c = cfg;
    w[0] = (slave_word){.pos_bits = c->bits, .ssi = true, .gray = c->gray};
    return 1;
}

static size_t labels(const void *cfg, const void *rec, waveform *ma_slave, slave_label *out,
                     size_t max) {
    const ssi_cfg *c = cfg;
    const ssi_frame_record *r = rec;
    sim_ps t[SLAVE_LABELS_MAX];
    size_t nt =
        slave_bit_starts(ma_slave, r->start_ps, r->end_ps, c->out_delay_ps, t, SLAVE_LABELS_MAX);
    size_t n = 0;
    for (unsigned b = c->bits, j = 0; b-- > 0; j++) {
        if (j + 1 < nt && n < max) {
            out[n] = (slave_label){.t0 = t[j], .t1 = t[j + 1]};
            snprintf(out[n].text, sizeof out[n].text, "D%u", b);
            n++;
        }
    }
    return n;
}

const slave_model slave_model_ssi = {
    .name = "ssi",
    .title = "SSI",
    .cfg_offset = offsetof(scenario, ssi),
    .cfg_size = sizeof(ssi_cfg),
    .cfg = &table,
    .cfg_default = cfg_default,
    .state_size = sizeof(ssi_slave),
    .init = init,
    .ma_edge = ma_edge,
    .record_size = sizeof(ssi_frame_record),
    .record = record,
    .frame = frame,
    .end = end,
    .out_delay = out_delay,
    .timeout = monoflop,
    .clocks = clocks,
    .words = words,
    .labels = labels,
    .word_note = "as sent (binary or Gray)",
};
