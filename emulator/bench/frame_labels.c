/* frame_labels.c - bit names of a frame at the slave (see frame_labels.h). */
#include "frame_labels.h"

#include "biss_crc.h"

#include <stdio.h>

struct label_list {
    struct svg_label *out;
    size_t n, max;
    const sim_ps *t; /* start time of each bit on SL */
    size_t nt;
    size_t j; /* next bit */
};

static void add(struct label_list *L, sim_ps t0, sim_ps t1, const char *text) {
    if (L->n < L->max) {
        struct svg_label *l = &L->out[L->n++];
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

/* Rising MA edges at the slave from `from` on, shifted by the output delay:
 * the times at which SL takes each next bit. */
static size_t bit_starts(waveform *ma, sim_ps from, sim_ps to, sim_ps delay, sim_ps *t,
                         size_t max) {
    size_t n = 0;
    for (sim_ps e = from; e <= to && n < max; e = waveform_next_after(ma, e)) {
        if (waveform_level_at(ma, e) == 1) {
            t[n++] = e + delay;
        }
    }
    return n;
}

/* One BiSS slave's fields in wire order. */
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

size_t frame_labels(const link_model *l, const biss_frame_record *br, const ssi_frame_record *sr,
                    waveform *ma_slave, struct svg_label *out, size_t max) {
    sim_ps t[FRAME_LABELS_MAX];
    struct label_list L = {out, 0, max, t, 0, 0};
    if (l->sc.protocol == SCENARIO_SSI) {
        const ssi_frame_record *r = sr;
        if (r) {
            L.nt = bit_starts(ma_slave, r->start_ps, r->end_ps, l->sc.ssi.out_delay_ps, t,
                              FRAME_LABELS_MAX);
            numbered_bits(&L, "D", l->sc.ssi.bits);
        }
        return L.n;
    }
    const biss_frame_record *r = br;
    if (!r || !r->started) {
        return 0;
    }
    sim_ps d = l->sc.biss.out_delay_ps;
    add(&L, r->ack_ps + d, r->start_bit_ps + d, "ACK");
    L.nt = bit_starts(ma_slave, r->start_bit_ps, r->end_ps, d, t, FRAME_LABELS_MAX);
    bit(&L, "S");
    bit(&L, "CDS");
    for (unsigned i = 0; i < l->sc.biss.n; i++) {
        slave_bits(&L, &l->sc.biss.s[i]);
    }
    if (L.j < L.nt) {
        add(&L, t[L.j], r->end_ps + d, "timeout");
    }
    return L.n;
}
