/* biss_enc.c - the encoder firmware (pru_slave/) on a board: loading it on
 * a PRU, configuring it, its live inputs and its status (libbiss.h, "the
 * encoder firmware"). The same backends as the master's handle (the Linux
 * one hands its opener in: biss_encoder_open, backend_linux.c); the data
 * RAM is biss_slave_shm.h's. */
#include "biss_priv.h"

#include "biss/biss_slave_shm_struct.h"
#include "biss_oserr.h"
#include "default_image.h"

#include <limits.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Where the images are when nothing names them (host/CMakeLists.txt). */
#ifndef BISS_BUILD_ENCODER
#define BISS_BUILD_ENCODER          "biss_encoder.bin"
#define BISS_BUILD_ENCODER_PRU1     "biss_encoder_pru1.bin"
#define BISS_BIN_TO_ENCODER         "../../lib/firmware/biss_encoder.bin"
#define BISS_BIN_TO_ENCODER_PRU1    "../../lib/firmware/biss_encoder_pru1.bin"
#define BISS_INSTALLED_ENCODER      "/lib/firmware/biss_encoder.bin"
#define BISS_INSTALLED_ENCODER_PRU1 "/lib/firmware/biss_encoder_pru1.bin"
#endif
#ifndef BISS_BUILD_DIR
#define BISS_BUILD_DIR "/nonexistent"
#endif

struct biss_encoder {
    biss_t *h;
};

static const char *encoder_path(const struct biss_open_params *p, char *buf, size_t len) {
    if (p->firmware && *p->firmware) {
        return p->firmware;
    }
    const char *env = getenv("BISS_ENCODER_FIRMWARE");
    if (env && *env) {
        return env;
    }
    const struct default_image d[2] = {
        {BISS_BUILD_DIR, BISS_BUILD_ENCODER, BISS_BIN_TO_ENCODER, BISS_INSTALLED_ENCODER},
        {BISS_BUILD_DIR, BISS_BUILD_ENCODER_PRU1, BISS_BIN_TO_ENCODER_PRU1,
         BISS_INSTALLED_ENCODER_PRU1},
    };
    return default_image(&d[p->pru ? 1 : 0], buf, len);
}

static int magic_seen(biss_t *h, void *arg) {
    (void)arg;
    uint32_t magic = 0;
    int rc = biss_dram_read32(h, BISS_SLV_ST_MAGIC, &magic);
    return rc ? rc : magic == BISS_SLV_MAGIC;
}

/* The encoder runs, assembled for this PRU. */
static int check_running(biss_t *h, struct biss_errbuf *e) {
    pthread_mutex_lock(&h->lock); /* the wait drops it while it sleeps */
    int rc = biss_wait_for(h, h->timeout_ms, magic_seen, NULL);
    pthread_mutex_unlock(&h->lock);
    if (rc == BISS_E_TIMEOUT) {
        return biss_err(e, BISS_E_NOT_RUNNING,
                        "no encoder magic (0x%08x) in PRU%u's data RAM within %u ms: is the "
                        "image biss_encoder%s.bin (.elf through remoteproc)?",
                        BISS_SLV_MAGIC, h->be.pru, h->timeout_ms, h->be.pru ? "_pru1" : "");
    }
    uint32_t pru = 0;
    if (!rc) {
        rc = biss_dram_read32(h, BISS_SLV_ST_PRU, &pru);
    }
    if (!rc && pru != h->be.pru) {
        rc = biss_err(e, BISS_E_FW_PRU,
                      "PRU%u runs an encoder assembled for PRU%u: load biss_encoder%s.bin",
                      h->be.pru, pru, h->be.pru ? "_pru1" : "");
    }
    return rc;
}

int biss_encoder_open_with(const struct biss_open_params *p, biss_backend_open_fn linux_open,
                           biss_encoder_t **out) {
    if (!out) {
        return BISS_E_INVAL;
    }
    *out = NULL;
    struct biss_errbuf e;
    int rc = biss_open_params_check(p, &e);
    if (rc) {
        return rc;
    }
    if (p->target == BISS_TARGET_EMU || !linux_open) {
        return biss_err(&e, BISS_E_TARGET,
                        "the emulator runs the encoder firmware beside the master on one "
                        "PRU-ICSS: biss-sim --encoder");
    }
    struct biss_open_params q = *p;
    if (!q.rproc_firmware || !*q.rproc_firmware) {
        q.rproc_firmware = p->pru ? "biss_encoder_pru1.elf" : "biss_encoder.elf";
    }
    struct biss_backend be;
    rc = linux_open(&q, &be);
    if (rc) {
        return rc;
    }
    biss_t *h;
    rc = biss_handle_new(p->target, &be, p->timeout_ms, &h);
    if (rc) {
        return rc;
    }
    h->attached = p->attach;
    if (!p->attach) {
        char buf[PATH_MAX + 64];
        bool rproc = p->loader == BISS_LOADER_REMOTEPROC;
        rc = rproc ? BISS_OK : biss_read_image(h, encoder_path(p, buf, sizeof buf), false, &e);
        if (!rc) {
            rc = biss_exclusive(h);
        }
        if (!rc) {
            rc = biss_pru_load_and_start(h);
        }
    }
    if (!rc) {
        rc = check_running(h, &e);
    }
    if (rc) {
        biss_close(h);
        return rc;
    }
    biss_encoder_t *enc = calloc(1, sizeof *enc);
    if (!enc) {
        biss_close(h);
        return BISS_E_NOMEM;
    }
    enc->h = h;
    *out = enc;
    return BISS_OK;
}

void biss_encoder_close(biss_encoder_t *e) {
    if (!e) {
        return;
    }
    biss_close(e->h);
    free(e);
}

int biss_encoder_leave_running(biss_encoder_t *e) {
    return e ? biss_leave_running(e->h) : BISS_E_INVAL;
}

int biss_encoder_stop(biss_encoder_t *e) {
    if (!e) {
        return BISS_E_INVAL;
    }
    biss_op_begin(e->h);
    int rc = biss_exclusive(e->h);
    if (!rc) {
        rc = biss_pru_halt(e->h);
    }
    biss_op_end(e->h);
    return rc;
}

static int acked(biss_t *h, void *arg) {
    uint32_t ack = 0, seq = *(const uint32_t *)arg;
    int rc = biss_dram_read32(h, BISS_SLV_ST_CFG_ACK, &ack);
    return rc ? rc : ack == seq;
}

int biss_encoder_configure(biss_encoder_t *e, const struct biss_encoder_config *c) {
    if (!e || !c) {
        return BISS_E_INVAL;
    }
    int rc = biss_encoder_config_check(c);
    if (rc) {
        return rc;
    }
    struct biss_slv_config blk;
    biss_encoder_encode(c, &blk);
    biss_t *h = e->h;
    biss_op_begin(h);
    rc = biss_exclusive(h);
    struct biss_proto_io io = biss_io(h);
    uint32_t seq = 0;
    if (!rc) {
        rc = biss_proto_encoder_seq_get(&io, &seq);
    }
    seq = seq + 1 ? seq + 1 : 1; /* never 0: the firmware's "none written yet" */
    if (!rc) {
        rc = biss_proto_encoder_put(&io, &blk, seq);
    }
    if (!rc) {
        rc = biss_wait_for(h, h->timeout_ms, acked, &seq);
    }
    uint32_t err = 0;
    if (!rc) {
        rc = biss_dram_read32(h, BISS_SLV_ST_CFG_ERROR, &err);
    }
    biss_op_end(h);
    return rc ? rc : biss_encoder_fw_error(err);
}

int biss_encoder_set_ew(biss_encoder_t *e, unsigned slave, bool error, bool warning) {
    if (!e || slave >= BISS_ENC_MAX_SLAVES) {
        return BISS_E_INVAL;
    }
    uint8_t v = (uint8_t)((error ? BISS_SLV_EW_ERROR : 0) | (warning ? BISS_SLV_EW_WARNING : 0));
    pthread_mutex_lock(&e->h->lock);
    int rc = biss_dram_write(e->h, BISS_SLV_LIVE_EW + slave, &v, 1);
    pthread_mutex_unlock(&e->h->lock);
    return rc;
}

int biss_encoder_table(biss_encoder_t *e, unsigned start, const uint64_t *pos, unsigned n) {
    if (!e || (!pos && n) || start > BISS_ENC_TABLE_ENTRIES || n > BISS_ENC_TABLE_ENTRIES - start) {
        return BISS_E_INVAL;
    }
    pthread_mutex_lock(&e->h->lock);
    struct biss_proto_io io = biss_io(e->h);
    int rc = biss_proto_encoder_table_put(&io, start, pos, n);
    pthread_mutex_unlock(&e->h->lock);
    return rc;
}

/* Where a register byte is: its data RAM offset, and for its access bits
 * the slave's file (addresses 0x00..0x3F in a bank of the pool). */
static int reg_at(biss_t *h, unsigned slave, unsigned bank, uint8_t addr, uint32_t *off) {
    if (slave >= BISS_ENC_MAX_SLAVES || addr > 0x7f) {
        return BISS_E_INVAL;
    }
    uint32_t base = BISS_SLV_REGS + slave * BISS_SLV_REGS_SIZE;
    if (addr >= 0x40) {
        *off = base + BISS_SLV_R_DIRECT + (addr - 0x40u);
        return BISS_OK;
    }
    uint8_t sb[2]; /* the configuration in force: the slave's banks, its first */
    uint32_t cfg = BISS_SLV_CFG_SLAVE0 + slave * BISS_SLV_CFG_SLAVE_SIZE;
    int rc = biss_dram_read(h, cfg + offsetof(struct biss_slv_slave_cfg, banks), &sb[0], 1);
    if (!rc) {
        rc = biss_dram_read(h, cfg + offsetof(struct biss_slv_slave_cfg, bank0), &sb[1], 1);
    }
    if (rc) {
        return rc;
    }
    if (bank >= sb[0] || sb[1] + bank >= BISS_SLV_POOL_BANKS) {
        return BISS_E_INVAL;
    }
    *off = BISS_SLV_POOL + (sb[1] + bank) * BISS_SLV_BANK_SIZE + addr;
    return BISS_OK;
}

int biss_encoder_reg_set(biss_encoder_t *e, unsigned slave, unsigned bank, uint8_t addr,
                         uint8_t value, bool read_only, bool write_protected) {
    if (!e) {
        return BISS_E_INVAL;
    }
    biss_t *h = e->h;
    pthread_mutex_lock(&h->lock);
    uint32_t off;
    int rc = reg_at(h, slave, bank, addr, &off);
    if (!rc) {
        rc = biss_dram_write(h, off, &value, 1);
    }
    uint32_t base = BISS_SLV_REGS + slave * BISS_SLV_REGS_SIZE;
    const uint32_t rights[2] = {BISS_SLV_R_RO, BISS_SLV_R_WP};
    const bool set[2] = {read_only, write_protected};
    for (unsigned k = 0; k < 2 && !rc; k++) {
        uint8_t bits;
        uint32_t at = base + rights[k] + addr / 8u;
        rc = biss_dram_read(h, at, &bits, 1);
        if (!rc) {
            bits = (uint8_t)(set[k] ? bits | 1u << (addr % 8u) : bits & ~(1u << (addr % 8u)));
            rc = biss_dram_write(h, at, &bits, 1);
        }
    }
    pthread_mutex_unlock(&h->lock);
    return rc;
}

int biss_encoder_reg_get(biss_encoder_t *e, unsigned slave, unsigned bank, uint8_t addr,
                         uint8_t *value) {
    if (!e || !value) {
        return BISS_E_INVAL;
    }
    pthread_mutex_lock(&e->h->lock);
    uint32_t off;
    int rc = reg_at(e->h, slave, bank, addr, &off);
    if (!rc) {
        rc = biss_dram_read(e->h, off, value, 1);
    }
    pthread_mutex_unlock(&e->h->lock);
    return rc;
}

int biss_encoder_get_status(biss_encoder_t *e, struct biss_encoder_status *out) {
    if (!e || !out) {
        return BISS_E_INVAL;
    }
    struct biss_slv_status st;
    pthread_mutex_lock(&e->h->lock);
    struct biss_proto_io io = biss_io(e->h);
    int rc = biss_proto_encoder_status(&io, &st);
    pthread_mutex_unlock(&e->h->lock);
    if (rc) {
        return rc;
    }
    memset(out, 0, sizeof *out);
    out->pru = st.pru;
    out->ma_bit = st.ma_bit;
    out->cfg_seq = st.cfg_ack;
    out->cfg_error = st.cfg_error;
    out->frames = st.frames;
    out->latches = st.latches;
    out->cd_frames = st.cd_frames;
    out->cdm = st.cdm == 0xff ? -1 : st.cdm;
    out->cds = st.cds;
    out->ctrl_state = st.ctrl_state;
    out->cancels = st.cancels;
    out->header_crc_errors = st.hdr_crc_errors;
    out->period_ns = st.period * 5u;
    out->timeout_ns = st.timeout * 5u;
    out->work_cycles = st.work;
    out->work_pad_cycles = st.work_pad;
    for (unsigned i = 0; i < BISS_ENC_MAX_SLAVES; i++) {
        const struct biss_slv_slave_status *s = &st.slave[i];
        out->slave[i].reads = s->reads;
        out->slave[i].writes = s->writes;
        out->slave[i].refused = s->refused;
        out->slave[i].write_crc_errors = s->crc_errors;
        out->slave[i].commands = s->commands;
        out->slave[i].dropped = s->dropped;
        out->slave[i].last_cmd = s->last_cmd == 0xff ? -1 : s->last_cmd;
        out->slave[i].last_addr = s->last_addr == 0xff ? -1 : s->last_addr;
        out->slave[i].last_value = s->last_addr == 0xff ? -1 : s->last_value;
    }
    return BISS_OK;
}
