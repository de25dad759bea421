/* biss_model.c - the BiSS-C chain (biss_slave.h) as an encoder model
 * (slave_model.h): its configuration's tables and relations, and its
 * operations. */
#include "biss/biss_rules.h"
#include "biss_crc.h"
#include "scenario.h"

#include <math.h>
#include <stdio.h>

/* ---- configuration: biss_slave_cfg, one slave ---- */

#define S(name, kind, member, lo, hi) SF_FIELD(name, kind, biss_slave_cfg, member, 0, lo, hi)

static const char *const lc_fault_names[] = {"none", "frozen", "skip", NULL};
/* which CDS slot carries the ID lock IDL0 (host/CD.md, "IDL"): false S, true CTS */
static const char *const idl_slot_names[] = {"s", "cts", NULL};

/* What a slave needs beyond the ranges. */
static int check_slave(const void *obj, char *err, size_t errlen) {
    const biss_slave_cfg *s = obj;
    const char *e = NULL;
    if (s->lc_fault != BISS_LC_FAULT_NONE && s->lc_bits == 0) {
        e = "life_counter_fault: the slave has no life counter (life_counter_bits 0)";
    } else if (biss_slave_cfg_data_bits(s) > 64) {
        e = "position_bits: with fill_bits, nE, nW and life_counter_bits more than 64 data "
            "bits before the CRC";
    } else if (s->crc_poly != 0 && !biss_crc_poly_valid(s->crc_poly)) {
        e = "crc_poly: must be an odd polynomial of degree 1..16 (with its top term)";
    } else if (s->crc_poly != 0 && (s->crc_start >> biss_crc_width(s->crc_poly)) != 0) {
        e = "crc_start: wider than the CRC";
    }
    if (e) {
        snprintf(err, errlen, "%s", e);
        return -1;
    }
    return 0;
}

static const sf_field slave_fields[] = {
    S("id", SF_U8, id, 0, 7),
    S("position_bits", SF_UNSIGNED, pos_bits, 1, 64),
    S("fill_bits", SF_UNSIGNED, fill_bits, 0, 63),
    S("life_counter_bits", SF_UNSIGNED, lc_bits, 0, 32),
    S("crc_poly", SF_U32, crc_poly, 0, 0x1ffff),
    S("crc_start", SF_U32, crc_start, 0, 0xffff),
    S("position", SF_U64, pos0, 0, SF_U64_MAX),
    SF_FIELD("speed_cps", SF_DOUBLE, biss_slave_cfg, speed_cps, 1, -SF_MAX_SPEED, SF_MAX_SPEED),
    SF_FIELD("counts_per_frame", SF_I64, biss_slave_cfg, counts_per_frame, 0, -SF_MAX_STEP,
             SF_MAX_STEP),
    S("register_processing_frames", SF_UNSIGNED, reg_proc_frames, 0, 1000),
    S("command_execute_bit", SF_U8, cmd_exec, 0, 1),
    S("life_counter_fault_frame", SF_UNSIGNED, lc_fault_frame, 1, SF_MAX_FRAME_NO),
    S("position_fault_offset", SF_U64, pos_fault_offset, 0, SF_U64_MAX),
    S("position_fault_frame", SF_UNSIGNED, pos_fault_frame, 1, SF_MAX_FRAME_NO),
    SF_FLAG("error_bit", SF_BOOL, biss_slave_cfg, has_err),
    SF_FLAG("warning_bit", SF_BOOL, biss_slave_cfg, has_warn),
    SF_FLAG("error", SF_BOOL, biss_slave_cfg, error),
    SF_FLAG("warning", SF_BOOL, biss_slave_cfg, warning),
    SF_FLAG("control", SF_NOT, biss_slave_cfg, no_control),
    {.name = "banks",
     .kind = SF_REGBANKS,
     .offset = offsetof(biss_slave_cfg, regs),
     .hi = REGFILE_MAX_BANKS},
    SF_FLAG("registers", SF_REGS, biss_slave_cfg, regs),
    {.name = "read_only",
     .kind = SF_REGFLAGS,
     .offset = offsetof(biss_slave_cfg, regs),
     .hi = REG_RO},
    {.name = "write_protected",
     .kind = SF_REGFLAGS,
     .offset = offsetof(biss_slave_cfg, regs),
     .hi = REG_WP},
    SF_FLAG("protect", SF_BOOL, biss_slave_cfg, regs.protect),
    SF_CHOOSE("life_counter_fault", biss_slave_cfg, lc_fault, lc_fault_names),
    {.name = "id_lock_slot",
     .kind = SF_CHOICE,
     .offset = offsetof(biss_slave_cfg, idl_at_cts),
     .size = sizeof(bool),
     .names = idl_slot_names,
     .expect = "expected \"s\" (IDL0 answers S) or \"cts\" (it answers CTS)"},
    SF_END,
};

static const sf_table slave_table = {.fields = slave_fields, .check = check_slave};

/* ---- configuration: biss_chain_cfg, the chain ---- */

#define C(name, kind, member, scale, lo, hi)                                                       \
    SF_FIELD(name, kind, biss_chain_cfg, member, scale, lo, hi)

static const char *const timeout_modes[] = {"fixed", "adaptive", NULL};

static const sf_field timeout_fields[] = {
    SF_CHOOSE("mode", biss_chain_cfg, timeout_mode, timeout_modes),
    C("ns", SF_PS, timeout_ps, 0, 0, SF_MAX_FRAME_NS),
    C("factor", SF_DOUBLE, adaptive_factor, 1, 0, 100),
    C("min_ns", SF_PS, adaptive_min_ps, 0, 0, SF_MAX_FRAME_NS),
    C("max_ns", SF_PS, adaptive_max_ps, 0, 0, SF_MAX_FRAME_NS),
    SF_END,
};

static const sf_table timeout_table = {.fields = timeout_fields};

/* What the chain needs beyond the ranges and each slave's own. */
static int check_chain(const void *obj, char *err, size_t errlen) {
    const biss_chain_cfg *c = obj;
    unsigned first, second;
    if (biss_chain_shared_id(c, &first, &second)) {
        snprintf(err, errlen, "slaves[%u].id: %u is slaves[%u]'s id too", second, c->s[second].id,
                 first);
        return -1;
    }
    const char *e = NULL;
    if (c->out_delay_ps <= 0) {
        e = "output_delay_ns: must be > 0 (every effect follows its cause)";
    } else if (c->timeout_mode == BISS_TIMEOUT_FIXED && c->timeout_ps <= 0) {
        e = "timeout.ns: must be > 0";
    } else if (c->timeout_mode == BISS_TIMEOUT_ADAPTIVE &&
               (c->adaptive_factor <= 0.0 || c->adaptive_max_ps <= 0 ||
                c->adaptive_min_ps > c->adaptive_max_ps)) {
        e = "timeout: adaptive needs factor > 0 and 0 <= min_ns <= max_ns, max_ns > 0";
    }
    if (e) {
        snprintf(err, errlen, "%s", e);
        return -1;
    }
    return 0;
}

static const sf_field chain_fields[] = {
    {.name = "slaves",
     .kind = SF_ARRAY,
     .offset = offsetof(biss_chain_cfg, s),
     .lo = 1,
     .hi = BISS_MAX_SLAVES,
     .sub = &slave_table,
     .elem_size = sizeof(biss_slave_cfg),
     .count_offset = offsetof(biss_chain_cfg, n),
     .expect = "expected an array of 1 to 8 slave objects"},
    C("output_delay_ns", SF_PS, out_delay_ps, 0, 0, SF_MAX_EDGE_NS),
    C("busy_ns", SF_PS, busy_ps, 0, 0, SF_MAX_FRAME_NS),
    C("busy_clocks", SF_UNSIGNED, busy_clocks, 0, 0, 1000000),
    {.name = "timeout", .kind = SF_OBJECT, .offset = 0, .sub = &timeout_table},
    SF_END,
};

static const sf_table chain_table = {.fields = chain_fields, .check = check_chain};

int biss_chain_cfg_check(const biss_chain_cfg *c, char *err, size_t errlen) {
    return sf_check_object(&chain_table, c, "", err, errlen);
}

/* ---- operations ---- */

static void cfg_default(void *cfg) {
    biss_chain_cfg_default(cfg);
}

static const biss_chain_cfg *chain(const void *cfg) {
    return cfg;
}

static void init(void *m, const void *cfg, event_queue *q, sim_edge_sink out) {
    biss_slave_init(m, cfg, q, out);
}

static void ma_edge(void *m, sim_ps t, int level) {
    biss_slave_ma_edge(m, t, level);
}

static const void *record(const void *m, uint64_t n) {
    const biss_slave *b = m;
    return n == b->st.frames ? &b->cur : (const void *)biss_slave_record(b, n);
}

static sim_ps end(const void *rec) {
    return ((const biss_frame_record *)rec)->end_ps;
}

static void frame(const void *cfg, const void *rec, slave_frame *f) {
    const biss_chain_cfg *c = cfg;
    const biss_frame_record *r = rec;
    /* field by field: the words past the chain's are left as they are */
    f->frame = r->frame;
    f->start_ps = r->start_ps;
    f->end_ps = r->end_ps;
    f->latch_ps = r->latch_ps;
    f->last_bit_ps = r->last_bit_ps;
    f->data_ps = r->start_bit_ps;
    f->nwords = c->n;
    for (unsigned i = 0; i < c->n && i < SLAVE_MAX_WORDS; i++) {
        f->word[i].position = f->word[i].code = r->s[i].position;
        f->word[i].nE = r->s[i].nE;
        f->word[i].nW = r->s[i].nW;
        f->word[i].lc = r->s[i].lc;
        f->word[i].crc = r->s[i].crc;
    }
}

static sim_ps out_delay(const void *cfg) {
    return ((const biss_chain_cfg *)cfg)->out_delay_ps;
}

static sim_ps timeout(const void *cfg, sim_ps period_ps) {
    return biss_chain_timeout_ps(cfg, period_ps);
}

/* To the ACK, the busy clocks and time, start, CDS, every slave's bits. */
static unsigned clocks(const void *cfg, sim_ps period_ps) {
    const biss_chain_cfg *c = cfg;
    unsigned n = 2 + 2 + c->busy_clocks + (unsigned)ceil((double)c->busy_ps / (double)period_ps);
    for (unsigned i = 0; i < c->n; i++) {
        n += biss_slave_cfg_bits(&c->s[i]);
    }
    return n;
}

static unsigned words(const void *cfg, slave_word *w) {
    const biss_chain_cfg *c = cfg;
    for (unsigned i = 0; i < c->n && i < SLAVE_MAX_WORDS; i++) {
        const biss_slave_cfg *s = &c->s[i];
        w[i] = (slave_word){.pos_bits = s->pos_bits,
                            .fill_bits = s->fill_bits,
                            .lc_bits = s->lc_bits,
                            .has_err = s->has_err,
                            .has_warn = s->has_warn,
                            .crc_poly = s->crc_poly,
                            .crc_start = s->crc_start,
                            .ew_active = s->error || s->warning};
    }
    return c->n;
}

/* ---- the scope picture's bit names ---- */

struct label_list {
    slave_label *out;
    size_t n, max;
    const sim_ps *t; /* start time of each bit on SL */
    size_t nt;
    size_t j; /* next bit */
};

static void add(struct label_list *L, sim_ps t0, sim_ps t1, const char *text) {
    if (L->n < L->max) {
        slave_label *l = &L->out[L->n++];
        l->t0 = t0;
        l->t1 = t1;
        snprintf(l->text, sizeof(l->text), "%s", text);
    }
}

/* Names the next bit on the wire (if the frame got that far). */
static void bit(struct label_list *L, const char *text) {
    if (L->j + 1 < L->nt) {
        add(L, L->t[L->j], L->t[L->j + 1], text);
    }
    L->j++;
}

static void numbered_bits(struct label_list *L, const char *prefix, unsigned count) {
    char text[16];
    for (unsigned b = count; b-- > 0;) {
        snprintf(text, sizeof(text), "%s%u", prefix, b);
        bit(L, text);
    }
}

/* One slave's fields in wire order. */
static void slave_bits(struct label_list *L, const biss_slave_cfg *s) {
    numbered_bits(L, "", s->pos_bits);
    for (unsigned b = 0; b < s->fill_bits; b++) {
        bit(L, "0");
    }
    if (s->has_err) {
        bit(L, "nE");
    }
    if (s->has_warn) {
        bit(L, "nW");
    }
    numbered_bits(L, "L", s->lc_bits);
    numbered_bits(L, "C", biss_crc_width(s->crc_poly));
}

static size_t labels(const void *cfg, const void *rec, waveform *ma_slave, slave_label *out,
                     size_t max) {
    const biss_chain_cfg *c = cfg;
    const biss_frame_record *r = rec;
    if (!r->started) {
        return 0;
    }
    sim_ps t[SLAVE_LABELS_MAX];
    struct label_list L = {out, 0, max, t, 0, 0};
    sim_ps d = c->out_delay_ps;
    add(&L, r->ack_ps + d, r->start_bit_ps + d, "ACK");
    L.nt = slave_bit_starts(ma_slave, r->start_bit_ps, r->end_ps, d, t, SLAVE_LABELS_MAX);
    bit(&L, "S");
    bit(&L, "CDS");
    for (unsigned i = 0; i < c->n; i++) {
        slave_bits(&L, &c->s[i]);
    }
    if (L.j < L.nt) {
        add(&L, t[L.j], r->end_ps + d, "timeout");
    }
    return L.n;
}

const slave_model slave_model_biss = {
    .name = "biss",
    .title = "BiSS-C",
    .cfg_offset = offsetof(scenario, biss),
    .cfg_size = sizeof(biss_chain_cfg),
    .cfg = &chain_table,
    .cfg_default = cfg_default,
    .chain = chain,
    .state_size = sizeof(biss_slave),
    .init = init,
    .ma_edge = ma_edge,
    .record_size = sizeof(biss_frame_record),
    .record = record,
    .frame = frame,
    .end = end,
    .out_delay = out_delay,
    .timeout = timeout,
    .clocks = clocks,
    .words = words,
    .labels = labels,
};
