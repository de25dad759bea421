/* biss_layout.c - a slave's single-cycle data word (biss_proto.h): the
 * one place that knows the order position, fill, nE, nW, life counter
 * (BiSS C protocol description: single-cycle data, MSB first). */
#include "biss_proto.h"

unsigned biss_proto_crc_bits(uint32_t poly) {
    unsigned d = 0;
    while (poly >> (d + 1)) {
        d++;
    }
    return poly ? d : 0;
}

void biss_proto_slave_layout(const struct biss_proto_word *w, uint32_t crc_poly, uint32_t crc_start,
                             struct biss_slave_config *o) {
    bool ew = w->has_err && w->has_warn; /* the firmware knows nE and nW only as a pair */
    *o = (struct biss_slave_config){
        .data_bits = w->pos_bits + w->fill_bits + w->has_err + w->has_warn + w->lc_bits,
        .crc_bits = biss_proto_crc_bits(crc_poly),
        .crc_poly = crc_poly,
        .crc_start = crc_start,
        .has_ew = ew,
        .ew_shift = ew ? w->lc_bits : 0,
        .pos_bits = w->pos_bits,
    };
}

uint64_t biss_proto_word_compose(const struct biss_proto_word *w, uint64_t position, int nE, int nW,
                                 uint32_t lc) {
    uint64_t v = position << w->fill_bits;
    if (w->has_err) {
        v = (v << 1) | (uint64_t)(nE != 0);
    }
    if (w->has_warn) {
        v = (v << 1) | (uint64_t)(nW != 0);
    }
    if (w->lc_bits) {
        v = (v << w->lc_bits) | lc;
    }
    return v;
}

void biss_proto_word_split(const struct biss_proto_word *w, uint64_t word, uint64_t *position,
                           int *nE, int *nW) {
    word >>= w->lc_bits;
    *nW = w->has_warn ? (int)(word & 1) : 1;
    word >>= w->has_warn;
    *nE = w->has_err ? (int)(word & 1) : 1;
    word >>= w->has_err;
    *position = word >> w->fill_bits;
}

/* pos_bits of it, or (pos_bits 0) everything above nE/nW, or the whole
 * word for a slave without them. */
unsigned biss_proto_pos_bits(const struct biss_slave_config *c) {
    unsigned low = c->has_ew ? c->ew_shift + 2 : 0;
    if (low >= c->data_bits) {
        return 0;
    }
    return c->pos_bits ? c->pos_bits : c->data_bits - low;
}

uint64_t biss_proto_from_gray(uint64_t g) {
    for (unsigned s = 1; s < 64; s <<= 1) {
        g ^= g >> s;
    }
    return g;
}
