/* biss_encoder.c - the host side of the encoder firmware's shared memory
 * (include/biss/biss_slave_shm.h): a struct biss_encoder_config checked
 * and encoded, and the transfers of the block, the live nE/nW bits, the
 * status, the next frame's record, the register files, the bank pool and
 * the position table (biss_proto.h). */
#include "biss_proto.h"

#include <stdatomic.h>
#include <string.h>

#define NS_PER_CYCLE 5u
/* the longest times the firmware counts, in ns */
#define MAX_TIMEOUT_NS ((uint32_t)BISS_SLV_MAX_TIMEOUT * NS_PER_CYCLE)
#define MAX_BUSY_NS    ((uint32_t)((1u << 24) - 1u) * NS_PER_CYCLE)

void biss_encoder_config_default(struct biss_encoder_config *c) {
    if (!c) {
        return;
    }
    memset(c, 0, sizeof *c);
    c->nslaves = 1;
    for (unsigned i = 0; i < BISS_ENC_MAX_SLAVES; i++) {
        struct biss_encoder_slave *s = &c->slave[i];
        s->pos_bits = 12;
        s->has_err = s->has_warn = true;
        s->crc_poly = 0x43;
        s->id = i;
        s->exec_bit = 1;
    }
    c->timeout_ns = 20000;
    c->factor16 = 24;
}

static unsigned data_bits(const struct biss_encoder_slave *s) {
    return s->pos_bits + s->fill_bits + s->has_err + s->has_warn + s->lc_bits;
}

static int slave_check(const struct biss_encoder_slave *s) {
    if (s->pos_bits < 1 || s->pos_bits > BISS_SLV_MAX_DATA_BITS) {
        return BISS_E_POS_BITS;
    }
    if (s->lc_bits > BISS_SLV_MAX_LC_BITS) {
        return BISS_E_ENC_LC_BITS;
    }
    if (s->fill_bits > BISS_SLV_MAX_DATA_BITS || data_bits(s) > BISS_SLV_MAX_DATA_BITS) {
        return BISS_E_DATA_BITS;
    }
    /* a generator polynomial has its constant term (iC-MB4 datasheet,
     * "CRC polynomial": "the least significant bit of the CRC polynomial
     * is always 1") */
    unsigned w = biss_proto_crc_bits(s->crc_poly);
    if (s->crc_poly && (w < 1 || w > BISS_SLV_MAX_CRC_BITS || !(s->crc_poly & 1u))) {
        return BISS_E_CRC_POLY;
    }
    if (s->crc_start >> w) {
        return BISS_E_CRC_START;
    }
    if (s->id > 7) {
        return BISS_E_ENC_ID;
    }
    if (s->table_len > BISS_SLV_TABLE_ENTRIES ||
        (s->table_len && s->table_start + s->table_len > BISS_SLV_TABLE_ENTRIES)) {
        return BISS_E_ENC_TABLE;
    }
    if (s->banks > BISS_SLV_POOL_BANKS || s->bank0 + s->banks > BISS_SLV_POOL_BANKS) {
        return BISS_E_ENC_BANKS;
    }
    if (s->reg_wait > 255 || s->exec_bit > 1) {
        return BISS_E_ENC_REG_WAIT;
    }
    return BISS_OK;
}

int biss_encoder_config_check(const struct biss_encoder_config *c) {
    if (!c) {
        return BISS_E_INVAL;
    }
    if (c->nslaves < 1 || c->nslaves > BISS_SLV_MAX_SLAVES) {
        return BISS_E_NSLAVES;
    }
    if (c->timeout_ns < NS_PER_CYCLE || c->timeout_ns > MAX_TIMEOUT_NS ||
        (c->adaptive &&
         (c->factor16 < 1 || c->factor16 > 255 || c->timeout_min_ns > c->timeout_ns))) {
        return BISS_E_ENC_TIMEOUT;
    }
    if (c->busy_ns > MAX_BUSY_NS || c->busy_clocks > 0xffff) {
        return BISS_E_ENC_BUSY;
    }
    unsigned ids = 0;
    for (unsigned i = 0; i < c->nslaves; i++) {
        const struct biss_encoder_slave *s = &c->slave[i];
        int rc = slave_check(s);
        if (rc) {
            return rc;
        }
        if (!s->no_control) {
            if (ids & (1u << s->id)) {
                return BISS_E_ENC_ID;
            }
            ids |= 1u << s->id;
        }
    }
    return BISS_OK;
}

/* ns to PRU cycles, to the nearest */
static uint32_t cycles(uint32_t ns) {
    return (uint32_t)(((uint64_t)ns + NS_PER_CYCLE / 2) / NS_PER_CYCLE);
}

uint8_t biss_encoder_ew_bits(const struct biss_encoder_slave *s) {
    return (uint8_t)((s->error ? BISS_SLV_EW_ERROR : 0) | (s->warning ? BISS_SLV_EW_WARNING : 0));
}

void biss_encoder_encode(const struct biss_encoder_config *c, struct biss_slv_config *out) {
    memset(out, 0, sizeof *out);
    out->nslaves = (uint8_t)c->nslaves;
    out->tmo_mode = c->adaptive ? BISS_SLV_TMO_ADAPTIVE : BISS_SLV_TMO_FIXED;
    out->tmo_factor = c->adaptive ? (uint8_t)c->factor16 : 0;
    out->timeout = cycles(c->timeout_ns);
    out->tmo_min = c->adaptive ? cycles(c->timeout_min_ns) : 0;
    out->busy_cycles = cycles(c->busy_ns);
    out->busy_clocks = (uint16_t)c->busy_clocks;
    for (unsigned i = 0; i < c->nslaves; i++) {
        const struct biss_encoder_slave *s = &c->slave[i];
        struct biss_slv_slave_cfg *o = &out->slave[i];
        unsigned w = biss_proto_crc_bits(s->crc_poly);
        out->live_ew[i] = biss_encoder_ew_bits(s);
        o->pos_bits = (uint8_t)s->pos_bits;
        o->fill_bits = (uint8_t)s->fill_bits;
        o->lc_bits = (uint8_t)s->lc_bits;
        o->flags =
            (uint8_t)((s->has_err ? BISS_SLV_SF_NE : 0) | (s->has_warn ? BISS_SLV_SF_NW : 0) |
                      (s->no_control ? BISS_SLV_SF_NO_CONTROL : 0) |
                      (s->exec_bit == 0 ? BISS_SLV_SF_EXEC_0 : 0) |
                      (s->protect ? BISS_SLV_SF_PROTECT : 0) |
                      (s->idl_at_cts ? BISS_SLV_SF_IDL_AT_CTS : 0));
        o->crc_bits = (uint8_t)w;
        o->id = (uint8_t)s->id;
        o->reg_wait = (uint8_t)s->reg_wait;
        o->banks = (uint8_t)s->banks;
        o->crc_poly = (uint16_t)(s->crc_poly & biss_low_mask(w));
        o->crc_start = (uint16_t)s->crc_start;
        o->bank0 = (uint8_t)s->bank0;
        o->table_start = (uint8_t)s->table_start;
        o->table_len = (uint16_t)s->table_len;
        o->position = s->position;
        o->step = (uint64_t)s->step;
    }
}

/* ---- transfers -------------------------------------------------------- */

static int rd(const struct biss_proto_io *io, uint32_t off, void *buf, size_t n) {
    return io->read(io->ctx, off, buf, n);
}

static int wr(const struct biss_proto_io *io, uint32_t off, const void *buf, size_t n) {
    return io->write(io->ctx, off, buf, n);
}

/* The firmware applies a block when CFG_SEQ changes: the block first. */
int biss_proto_encoder_put(const struct biss_proto_io *io, const struct biss_slv_config *blk,
                           uint32_t seq) {
    const size_t at = offsetof(struct biss_slv_config, nslaves);
    int rc = wr(io, BISS_SLV_CFG_SEQ + (uint32_t)at, (const uint8_t *)blk + at, sizeof *blk - at);
    atomic_thread_fence(memory_order_seq_cst);
    if (!rc) {
        rc = wr(io, BISS_SLV_CFG_SEQ, &seq, 4);
    }
    atomic_thread_fence(memory_order_seq_cst);
    return rc;
}

int biss_proto_encoder_seq_get(const struct biss_proto_io *io, uint32_t *seq) {
    return rd(io, BISS_SLV_CFG_SEQ, seq, 4);
}

int biss_proto_encoder_ew_put(const struct biss_proto_io *io,
                              const uint8_t live[BISS_SLV_MAX_SLAVES]) {
    return wr(io, BISS_SLV_LIVE_EW, live, BISS_SLV_MAX_SLAVES);
}

int biss_proto_encoder_status(const struct biss_proto_io *io, struct biss_slv_status *st) {
    return rd(io, BISS_SLV_ST_MAGIC, st, sizeof *st);
}

int biss_proto_encoder_rec(const struct biss_proto_io *io, struct biss_slv_frame_rec *rec) {
    return rd(io, BISS_SLV_REC_FRAME, rec, sizeof *rec);
}

int biss_proto_encoder_regs_put(const struct biss_proto_io *io, unsigned slave,
                                const struct biss_slv_regs *r) {
    if (slave >= BISS_SLV_MAX_SLAVES) {
        return BISS_E_INVAL;
    }
    return wr(io, BISS_SLV_REGS + slave * BISS_SLV_REGS_SIZE, r, sizeof *r);
}

int biss_proto_encoder_regs_get(const struct biss_proto_io *io, unsigned slave,
                                struct biss_slv_regs *r) {
    if (slave >= BISS_SLV_MAX_SLAVES) {
        return BISS_E_INVAL;
    }
    return rd(io, BISS_SLV_REGS + slave * BISS_SLV_REGS_SIZE, r, sizeof *r);
}

int biss_proto_encoder_bank_put(const struct biss_proto_io *io, unsigned bank,
                                const uint8_t bytes[BISS_SLV_BANK_SIZE]) {
    if (bank >= BISS_SLV_POOL_BANKS) {
        return BISS_E_INVAL;
    }
    return wr(io, BISS_SLV_POOL + bank * BISS_SLV_BANK_SIZE, bytes, BISS_SLV_BANK_SIZE);
}

int biss_proto_encoder_bank_get(const struct biss_proto_io *io, unsigned bank,
                                uint8_t bytes[BISS_SLV_BANK_SIZE]) {
    if (bank >= BISS_SLV_POOL_BANKS) {
        return BISS_E_INVAL;
    }
    return rd(io, BISS_SLV_POOL + bank * BISS_SLV_BANK_SIZE, bytes, BISS_SLV_BANK_SIZE);
}

int biss_proto_encoder_table_put(const struct biss_proto_io *io, unsigned start,
                                 const uint64_t *pos, unsigned n) {
    if (start > BISS_SLV_TABLE_ENTRIES || n > BISS_SLV_TABLE_ENTRIES - start || (n && !pos)) {
        return BISS_E_INVAL;
    }
    return n ? wr(io, BISS_SLV_TABLE + start * 8u, pos, n * 8u) : BISS_OK;
}

int biss_encoder_fw_error(uint32_t cfgerr) {
    return cfgerr == BISS_SLV_CFGERR_NONE ? BISS_OK : BISS_E_ENC_REFUSED;
}

const char *biss_encoder_cfg_error_text(uint32_t code) {
    static const char *const text[] = {
        [BISS_SLV_CFGERR_NONE] = "accepted",
        [BISS_SLV_CFGERR_NSLAVES] = "BISS_SLV_CFGERR_NSLAVES: 0 or more than 8 slaves",
        [BISS_SLV_CFGERR_DATA_BITS] =
            "BISS_SLV_CFGERR_DATA_BITS: a position of 0 or over 64 bits, or a data word over 64",
        [BISS_SLV_CFGERR_CRC_BITS] =
            "BISS_SLV_CFGERR_CRC_BITS: over 16 CRC bits, or a start value wider than them",
        [BISS_SLV_CFGERR_LC_BITS] = "BISS_SLV_CFGERR_LC_BITS: a life counter over 32 bits",
        [BISS_SLV_CFGERR_ID] = "BISS_SLV_CFGERR_ID: an ID over 7, or two answering slaves with one",
        [BISS_SLV_CFGERR_TABLE] = "BISS_SLV_CFGERR_TABLE: table entries past 128",
        [BISS_SLV_CFGERR_BANKS] = "BISS_SLV_CFGERR_BANKS: register banks past 16",
        [BISS_SLV_CFGERR_TIMEOUT] = "BISS_SLV_CFGERR_TIMEOUT: timeout 0 or too long, an unknown "
                                    "mode, or an adaptive factor 0 or minimum above the longest",
        [BISS_SLV_CFGERR_BUSY] = "BISS_SLV_CFGERR_BUSY: processing time over 2^24 cycles",
    };
    return code < sizeof text / sizeof text[0] && text[code] ? text[code]
                                                             : "unknown configuration error";
}
