/* biss_sample_decode.c - a published result buffer to biss_sample: flags,
 * line delay, and per slave the data word split by the configuration. */
#include "biss_proto.h"

#include <string.h>

/* biss_shm.h: the round trip is (DELAY - BISS_DELAY_ZERO) * H / 4 -
 * BISS_DELAY_ADJ_CYCLES PRU cycles of 5 ns; one bit/8 is H / 4 cycles. A
 * round trip shorter than the firmware can resolve there (the ACK in the
 * first eighth it can see: DELAY = BISS_DELAY_ZERO) would come out as
 * less than nothing (-BISS_DELAY_ADJ_CYCLES): it is 0, no line delay. */
static void delay_of(uint16_t counts, unsigned half, double *bit8, double *cycles, double *ns) {
    const double ns_per_cycle = 1e9 / BISS_PRU_HZ;
    double unit = half / 4.0;
    *cycles = ((double)counts - BISS_DELAY_ZERO) * unit - BISS_DELAY_ADJ_CYCLES;
    if (*cycles < 0) {
        *cycles = 0;
    }
    *bit8 = half ? *cycles / unit : 0.0;
    *ns = *cycles * ns_per_cycle;
}

void biss_delay_decode(uint16_t raw, uint16_t avg, unsigned half, struct biss_line_delay *d) {
    d->raw = raw;
    d->avg = avg;
    d->half = half;
    delay_of(avg, half, &d->bit8, &d->cycles, &d->ns);
    delay_of(raw, half, &d->raw_bit8, &d->raw_cycles, &d->raw_ns);
}

/* The position is the top of the data word (biss_proto_pos_bits). */
static uint64_t position_of(const struct biss_slave_config *c, uint64_t data) {
    unsigned low = c->has_ew ? c->ew_shift + 2 : 0;
    if (low >= c->data_bits) {
        return 0;
    }
    unsigned pos = biss_proto_pos_bits(c);
    unsigned shift = c->data_bits - pos;
    return (data >> shift) & biss_low_mask(pos);
}

static void decode_slave(const struct biss_slave_config *c, const struct biss_shm_slave_result *r,
                         struct biss_slave_result *o) {
    o->data = (uint64_t)r->data_hi << 32 | r->data_lo;
    if (c) {
        o->data &= biss_low_mask(c->data_bits); /* no bit the layout does not have */
    }
    o->crc_reg = r->crc_reg;
    o->status = r->status;
    o->crc_ok = (r->status & BISS_RS_CRC_OK) != 0;
    if (!c) {
        /* no layout known: the whole word, and no claim about nE/nW */
        o->position = o->data;
        return;
    }
    o->position = position_of(c, c->gray ? biss_proto_from_gray(o->data) : o->data);
    /* nE and nW are active low on the wire; the firmware reports them as
     * received, and 0 for a slave that sends none */
    o->error = c->has_ew && !(r->status & BISS_RS_NE);
    o->warning = c->has_ew && !(r->status & BISS_RS_NW);
}

int biss_sample_decode(const struct biss_config *c, bool configured, uint32_t seq,
                       const struct biss_shm_result *r, struct biss_sample *s) {
    memset(s, 0, sizeof *s);
    s->seq = seq;
    s->frame = r->frame;
    s->flags = r->flags;
    s->valid = (r->flags & BISS_RF_VALID) != 0;
    s->crc_error = (r->flags & BISS_RF_CRC_ERROR) != 0;
    s->no_slave = (r->flags & BISS_RF_NO_SLAVE) != 0;
    s->proc_error = (r->flags & BISS_RF_PROC_ERROR) != 0;
    s->training = (r->flags & BISS_RF_TRAINING) != 0;
    s->sma = (r->flags & BISS_RF_SMA) != 0;
    s->ack_jump = (r->flags & BISS_RF_ACK_JUMP) != 0;
    s->off_grid = (r->flags & BISS_RF_OFF_GRID) != 0;
    s->timestamp = r->timestamp;
    s->proc_clocks = r->proc_clocks;
    s->cds = r->cds;
    s->sample_point = r->sample_point;
    s->lag_periods = r->lag_periods;
    biss_delay_decode(r->delay_raw, r->delay_avg, r->half, &s->delay);
    /* data RAM is untrusted: what the firmware never writes is junk, not
     * data */
    if (biss_result_problem(c, configured, r)) {
        return BISS_E_SHM_RESULT;
    }
    s->nslaves = r->nslaves;
    /* an aborted frame leaves older data in its buffer: report none */
    if (!s->valid) {
        return BISS_OK;
    }
    for (unsigned i = 0; i < s->nslaves; i++) {
        const struct biss_slave_config *sc = configured && i < c->nslaves ? &c->slave[i] : NULL;
        decode_slave(sc, &r->slave[i], &s->slave[i]);
    }
    return BISS_OK;
}
