/* toy_model.c - an encoder model that lives in this file alone: an
 * SSI-like encoder that answers every read with one constant word (a
 * "fixed answer" test encoder). It shows what a protocol model is: its
 * configuration's table and relations, its answer to MA edges, its frame
 * records and what a master needs to know (slave_model.h); the suite
 * (test_e2e_model.c) registers it (slave_model_register: the table's row
 * for a model outside the table) and runs it with the firmware.
 *
 * Its frame, from the slave's side (the SSI frame of ssi_slave.h, the
 * position replaced by the word): the first falling MA edge while idle
 * starts it; each rising edge shifts out one bit of the word, MSB first,
 * then zeros; once MA has not moved for the monoflop time, SL returns
 * high and the frame is closed. Every SL change comes out_delay after the
 * MA edge that caused it. */
#include "scenario.h"

#include <stdio.h>
#include <string.h>

typedef struct {
    uint64_t word;       /* sent in every frame, MSB first */
    unsigned bits;       /* 1..64 */
    sim_ps out_delay_ps; /* MA edge to SL edge */
    sim_ps monoflop_ps;  /* MA at rest this long ends the frame */
    bool misreport;      /* its records say one bit off what it sent */
} toy_cfg;

#define RING 64

typedef struct {
    uint64_t frame;
    sim_ps start_ps, end_ps, last_bit_ps;
} toy_record;

typedef struct {
    slave_status st; /* first: the link reads it */
    toy_cfg cfg;
    event_queue *q;
    sim_edge_sink out;
    int ma, sl;
    unsigned rises;
    eq_id monoflop;
    toy_record cur, ring[RING];
} toy_state;

/* ---- configuration ---- */

static int check(const void *obj, char *err, size_t errlen) {
    const toy_cfg *c = obj;
    if (c->bits < 64 && c->word >> c->bits) {
        snprintf(err, errlen, "word: wider than its %u bits", c->bits);
        return -1;
    }
    if (c->out_delay_ps <= 0 || c->monoflop_ps <= 0) {
        snprintf(err, errlen, "%s: must be > 0",
                 c->out_delay_ps <= 0 ? "output_delay_ns" : "monoflop_ns");
        return -1;
    }
    return 0;
}

static const sf_field fields[] = {
    SF_FIELD("word", SF_U64, toy_cfg, word, 0, 0, SF_U64_MAX),
    SF_FIELD("bits", SF_UNSIGNED, toy_cfg, bits, 0, 1, 64),
    SF_FIELD("output_delay_ns", SF_PS, toy_cfg, out_delay_ps, 0, 0, SF_MAX_EDGE_NS),
    SF_FIELD("monoflop_ns", SF_PS, toy_cfg, monoflop_ps, 0, 0, SF_MAX_FRAME_NS),
    SF_FLAG("misreport", SF_BOOL, toy_cfg, misreport),
    SF_END,
};

static const sf_table table = {.fields = fields, .check = check};

static void cfg_default(void *cfg) {
    *(toy_cfg *)cfg = (toy_cfg){.word = 0x2b5,
                                .bits = 10,
                                .out_delay_ps = 20 * SIM_PS_PER_NS,
                                .monoflop_ps = 20 * SIM_PS_PER_US};
}

/* ---- at work ---- */

static void init(void *m, const void *cfg, event_queue *q, sim_edge_sink out) {
    toy_state *s = m;
    memset(s, 0, sizeof *s);
    s->cfg = *(const toy_cfg *)cfg;
    s->q = q;
    s->out = out;
    s->ma = s->sl = 1;
}

static void emit(void *ctx, sim_ps t, int64_t level) {
    toy_state *s = ctx;
    sim_edge_send(&s->out, t, (int)level);
}

static void drive(toy_state *s, sim_ps t, int level) {
    if (level != s->sl) {
        s->sl = level;
        eq_schedule(s->q, t + s->cfg.out_delay_ps, emit, s, level);
    }
}

static void monoflop_over(void *ctx, sim_ps t, int64_t arg) {
    (void)arg;
    toy_state *s = ctx;
    s->monoflop = 0;
    s->st.in_frame = false;
    drive(s, t, 1);
    s->cur.end_ps = t;
    s->ring[s->st.frames % RING] = s->cur;
    s->st.frames++;
}

static void ma_edge(void *m, sim_ps t, int level) {
    toy_state *s = m;
    level = level ? 1 : 0;
    if (level == s->ma) {
        return;
    }
    s->ma = level;
    if (!s->st.in_frame) {
        if (level) {
            return;
        }
        s->st.in_frame = true;
        s->rises = 0;
        s->cur = (toy_record){.frame = s->st.frames, .start_ps = t};
    } else if (level) {
        s->rises++;
        unsigned n = s->cfg.bits;
        drive(s, t, s->rises <= n ? (int)(s->cfg.word >> (n - s->rises) & 1u) : 0);
        if (s->rises == n) {
            s->cur.last_bit_ps = t;
        }
    }
    eq_cancel(s->q, s->monoflop);
    s->monoflop = eq_schedule(s->q, t + s->cfg.monoflop_ps, monoflop_over, s, 0);
}

static const void *record(const void *m, uint64_t n) {
    const toy_state *s = m;
    if (n == s->st.frames) {
        return &s->cur;
    }
    return n < s->st.frames && s->st.frames - n <= RING ? &s->ring[n % RING] : NULL;
}

/* The word it sent; misreport: one bit off, which the bench must catch. */
static sim_ps end(const void *rec) {
    return ((const toy_record *)rec)->end_ps;
}

static void frame(const void *cfg, const void *rec, slave_frame *f) {
    const toy_cfg *c = cfg;
    const toy_record *r = rec;
    f->frame = r->frame;
    f->start_ps = f->latch_ps = f->data_ps = r->start_ps;
    f->end_ps = r->end_ps;
    f->last_bit_ps = r->last_bit_ps;
    f->nwords = 1;
    f->word[0].position = f->word[0].code = c->misreport ? c->word ^ 1u : c->word;
    f->word[0].nE = f->word[0].nW = -1;
    f->word[0].lc = f->word[0].crc = 0;
}

/* ---- what a master needs ---- */

static sim_ps out_delay(const void *cfg) {
    return ((const toy_cfg *)cfg)->out_delay_ps;
}

static sim_ps timeout(const void *cfg, sim_ps period_ps) {
    (void)period_ps;
    return ((const toy_cfg *)cfg)->monoflop_ps;
}

static unsigned clocks(const void *cfg, sim_ps period_ps) {
    (void)period_ps;
    return ((const toy_cfg *)cfg)->bits + 1;
}

/* Read as an SSI word: no ACK, start bit, CDS or CRC. */
static unsigned words(const void *cfg, slave_word *w) {
    w[0] = (slave_word){.pos_bits = ((const toy_cfg *)cfg)->bits, .ssi = true};
    return 1;
}

static size_t labels(const void *cfg, const void *rec, waveform *ma_slave, slave_label *out,
                     size_t max) {
    const toy_cfg *c = cfg;
    const toy_record *r = rec;
    sim_ps t[SLAVE_LABELS_MAX];
    size_t nt =
        slave_bit_starts(ma_slave, r->start_ps, r->end_ps, c->out_delay_ps, t, SLAVE_LABELS_MAX);
    size_t n = 0;
    for (unsigned b = c->bits, j = 0; b-- > 0 && j + 1 < nt && n < max; j++, n++) {
        out[n] = (slave_label){.t0 = t[j], .t1 = t[j + 1]};
        snprintf(out[n].text, sizeof out[n].text, "W%u", b);
    }
    return n;
}

extern const slave_model toy_model;
const slave_model toy_model = {
    .name = "toy",
    .title = "toy",
    .cfg_offset = offsetof(scenario, ext),
    .cfg_size = sizeof(toy_cfg),
    .cfg = &table,
    .cfg_default = cfg_default,
    .state_size = sizeof(toy_state),
    .init = init,
    .ma_edge = ma_edge,
    .record_size = sizeof(toy_record),
    .record = record,
    .frame = frame,
    .end = end,
    .out_delay = out_delay,
    .timeout = timeout,
    .clocks = clocks,
    .words = words,
    .labels = labels,
    .word_note = "the constant word",
};
