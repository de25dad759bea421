/* slave_fw.c - the encoder firmware as the bench's encoder (slave_fw.h). */
#include "slave_fw.h"

#include "biss_soc.h"

#include "biss/biss_slave_shm.h"

#include <inttypes.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

static int io_read(void *ctx, uint32_t off, void *buf, size_t n) {
    struct slave_fw_ram *r = ctx;
    return pru_host_read(r->core, r->base + off, buf, n) ? BISS_E_IO : BISS_OK;
}

static int io_write(void *ctx, uint32_t off, const void *buf, size_t n) {
    struct slave_fw_ram *r = ctx;
    return pru_host_write(r->core, r->base + off, buf, n) ? BISS_E_IO : BISS_OK;
}

void slave_fw_ram_init(struct slave_fw_ram *ram, struct pru_core *core, enum pru_soc soc,
                       unsigned pru) {
    ram->core = core;
    ram->base = pru_soc_base(soc) + ICSS_DRAM(pru);
}

struct biss_proto_io slave_fw_io(struct slave_fw_ram *ram) {
    return (struct biss_proto_io){.read = io_read, .write = io_write, .ctx = ram};
}

static int fail(char *err, size_t errlen, const char *fmt, ...) {
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(err, errlen, fmt, ap);
    va_end(ap);
    return -1;
}

/* ps to whole ns, or -1 when not whole */
static int64_t whole_ns(sim_ps ps) {
    return ps % SIM_PS_PER_NS ? -1 : ps / SIM_PS_PER_NS;
}

static int slave_config(const biss_slave_cfg *s, unsigned i, unsigned *bank0,
                        struct biss_encoder_slave *o, char *err, size_t errlen) {
    if (s->speed_cps != 0.0) {
        return fail(err, errlen,
                    "biss.slaves[%u].speed_cps: the encoder firmware moves its position by "
                    "counts per frame (counts_per_frame), not with time",
                    i);
    }
    if (s->lc_fault != BISS_LC_FAULT_NONE || s->pos_fault_offset != 0) {
        return fail(err, errlen,
                    "biss.slaves[%u]: the encoder firmware injects no life-counter or position "
                    "faults",
                    i);
    }
    if (s->reg_proc_frames > 255) {
        return fail(err, errlen,
                    "biss.slaves[%u].register_processing_frames: the encoder firmware waits "
                    "at most 255 frames",
                    i);
    }
    unsigned banks = s->regs.nbanks;
    if (*bank0 + banks > BISS_ENC_POOL_BANKS) {
        return fail(err, errlen,
                    "biss.slaves[%u].banks: the encoder firmware's pool holds %u banks for the "
                    "whole chain",
                    i, BISS_ENC_POOL_BANKS);
    }
    *o = (struct biss_encoder_slave){.pos_bits = s->pos_bits,
                                     .fill_bits = s->fill_bits,
                                     .has_err = s->has_err,
                                     .has_warn = s->has_warn,
                                     .lc_bits = s->lc_bits,
                                     .crc_poly = s->crc_poly,
                                     .crc_start = s->crc_start,
                                     .position = s->pos0,
                                     .step = s->counts_per_frame,
                                     .error = s->error,
                                     .warning = s->warning,
                                     .id = s->id,
                                     .no_control = s->no_control,
                                     .exec_bit = s->cmd_exec,
                                     .reg_wait = s->reg_proc_frames,
                                     .banks = banks,
                                     .bank0 = *bank0,
                                     .protect = s->regs.protect,
                                     .idl_at_cts = s->idl_at_cts};
    *bank0 += banks;
    return 0;
}

int slave_fw_config(const biss_chain_cfg *c, struct biss_encoder_config *e, char *err,
                    size_t errlen) {
    biss_encoder_config_default(e);
    e->nslaves = c->n;
    unsigned bank0 = 0;
    for (unsigned i = 0; i < c->n && i < BISS_ENC_MAX_SLAVES; i++) {
        if (slave_config(&c->s[i], i, &bank0, &e->slave[i], err, errlen)) {
            return -1;
        }
    }
    int64_t busy = whole_ns(c->busy_ps);
    if (busy < 0) {
        return fail(err, errlen, "biss.busy_ns: the encoder firmware takes whole ns");
    }
    e->busy_ns = (uint32_t)busy;
    e->busy_clocks = c->busy_clocks;
    e->adaptive = c->timeout_mode == BISS_TIMEOUT_ADAPTIVE;
    int64_t tmo = whole_ns(e->adaptive ? c->adaptive_max_ps : c->timeout_ps);
    int64_t tmo_min = whole_ns(c->adaptive_min_ps);
    if (tmo < 0 || (e->adaptive && tmo_min < 0)) {
        return fail(err, errlen, "biss.timeout: the encoder firmware takes whole ns");
    }
    e->timeout_ns = (uint32_t)tmo;
    if (e->adaptive) {
        double f16 = c->adaptive_factor * 16.0;
        if (f16 != floor(f16) || f16 < 1 || f16 > 255) {
            return fail(err, errlen,
                        "biss.timeout.factor: the encoder firmware takes 1/16 .. 255/16 in "
                        "sixteenths (1.5, 0.5625, ...)");
        }
        e->factor16 = (unsigned)f16;
        e->timeout_min_ns = (uint32_t)tmo_min;
    }
    int rc = biss_encoder_config_check(e);
    if (rc) {
        return fail(err, errlen,
                    "the encoder firmware cannot take this chain (libbiss error %d, "
                    "biss_encoder_config_check)",
                    rc);
    }
    return 0;
}

/* A model's register file as the firmware's: the direct registers and the
 * access bits of every address. */
static void regs_from_model(const regfile *m, struct biss_slv_regs *r) {
    memset(r, 0, sizeof *r);
    memcpy(r->direct, m->direct, sizeof r->direct);
    for (unsigned a = 0; a < 128; a++) {
        if (m->flags[a] & REG_RO) {
            r->ro[a / 8] |= (uint8_t)(1u << (a % 8));
        }
        if (m->flags[a] & REG_WP) {
            r->wp[a / 8] |= (uint8_t)(1u << (a % 8));
        }
    }
}

int slave_fw_load(const struct biss_proto_io *io, const biss_chain_cfg *c, char *err,
                  size_t errlen) {
    struct biss_encoder_config e;
    if (slave_fw_config(c, &e, err, errlen)) {
        return -1;
    }
    int rc = 0;
    for (unsigned i = 0; i < e.nslaves && !rc; i++) {
        struct biss_slv_regs r;
        regs_from_model(&c->s[i].regs, &r);
        rc = biss_proto_encoder_regs_put(io, i, &r);
        for (unsigned b = 0; b < e.slave[i].banks && !rc; b++) {
            rc = biss_proto_encoder_bank_put(io, e.slave[i].bank0 + b, c->s[i].regs.bank[b]);
        }
    }
    struct biss_slv_config blk;
    biss_encoder_encode(&e, &blk);
    uint32_t seq = 0;
    if (!rc) {
        rc = biss_proto_encoder_seq_get(io, &seq);
    }
    if (!rc) {
        rc = biss_proto_encoder_put(io, &blk, seq + 1);
    }
    if (rc) {
        return fail(err, errlen, "the encoder firmware's data RAM: a transfer failed (%d)", rc);
    }
    return 0;
}

void slave_fw_chain(biss_chain_cfg *c, double frame_ps, FILE *notes) {
    unsigned banks = 0;
    for (unsigned i = 0; i < c->n; i++) {
        biss_slave_cfg *s = &c->s[i];
        unsigned left = BISS_ENC_POOL_BANKS - banks;
        if (s->regs.nbanks > left) {
            if (notes) {
                fprintf(notes,
                        "encoder: slave %u keeps %u of its %u register banks (the "
                        "firmware's pool holds %u for the chain; the model's the same)\n",
                        i, left, s->regs.nbanks, BISS_ENC_POOL_BANKS);
            }
            s->regs.nbanks = left;
        }
        banks += s->regs.nbanks;
        if (s->speed_cps == 0.0) {
            continue;
        }
        double step = s->speed_cps * frame_ps / SIM_PS_PER_S;
        s->counts_per_frame += (int64_t)llround(step);
        if (notes) {
            fprintf(notes,
                    "encoder: slave %u moves %" PRId64 " counts a frame (%g counts/s "
                    "over a frame of %.3f us)\n",
                    i, s->counts_per_frame, s->speed_cps, frame_ps / SIM_PS_PER_US);
        }
        s->speed_cps = 0.0;
    }
}
