/* biss_pru.c - the handle's PRU (0 or 1) controlled through its CONTROL
 * register, and loading the image into its IRAM; the same register writes
 * on silicon and in the emulator. */
#include "biss_priv.h"

#include "biss/biss_shm_struct.h"
#include "biss_image_id.h"
#include "biss_oserr.h"

#include <stdlib.h>
#include <string.h>

static int write_control(biss_t *h, uint32_t v) {
    return h->be.ops->write(h->be.ctx, ICSS_CTRL(h->be.pru), &v, 4);
}

int biss_exclusive(biss_t *h) {
    return h->be.ops->exclusive ? h->be.ops->exclusive(h->be.ctx) : BISS_OK;
}

int biss_pru_halt(biss_t *h) {
    if (h->be.ops->pru_halt) {
        return h->be.ops->pru_halt(h->be.ctx);
    }
    /* ENABLE clear, SOFT_RST_N kept high: the PRU stops where it is */
    return write_control(h, ICSS_CTRL_RESET_N);
}

int biss_pru_enabled(biss_t *h, bool *on) {
    if (h->be.ops->pru_enabled) {
        return h->be.ops->pru_enabled(h->be.ctx, on);
    }
    uint32_t control = 0;
    int rc = h->be.ops->read(h->be.ctx, ICSS_CTRL(h->be.pru), &control, 4);
    *on = (control & ICSS_CTRL_ENABLE) != 0;
    return rc;
}

/* IRAM is written whole (zeros after the image) so nothing from an earlier
 * program survives behind a shorter one. */
static int load_iram(biss_t *h) {
    uint8_t *buf = calloc(1, h->be.iram_bytes);
    if (!buf) {
        return BISS_E_NOMEM;
    }
    memcpy(buf, h->image, h->image_bytes);
    int rc = h->be.ops->write(h->be.ctx, ICSS_IRAM(h->be.pru), buf, h->be.iram_bytes);
    free(buf);
    return rc;
}

/* What remoteproc's loader puts at BISS_ID from the ELF (pru-elf). */
int biss_pru_write_id(biss_t *h) {
    uint8_t rsc[16];
    struct biss_shm_id id;
    biss_image_id(h->image, h->image_bytes, &id);
    biss_rsc_table(rsc);
    struct biss_proto_io io = biss_io(h);
    return biss_proto_id_put(&io, &id, rsc);
}

/* Config, commands, status, results and the control-communication area
 * start from zero: data RAM keeps whatever an earlier run left (a stale
 * magic or ack would lie). */
static int clear_shared(biss_t *h) {
    static const uint8_t zeros[sizeof(struct biss_shm)] = {0};
    return biss_dram_write(h, 0, zeros, sizeof zeros);
}

/* Each PRU has its own image (its CONTROL block, GPCFG and scratch-pad
 * bank are in the instruction words, pru_fw/README.md): the other PRU's
 * would set up the other PRU's C28 and line, and use its bank. */
int biss_pru_image_check(biss_t *h, struct biss_errbuf *e) {
    struct biss_proto_io io = biss_io(h);
    struct biss_shm_status st;
    uint32_t pru;
    int rc = biss_proto_status_get(&io, &st);
    if (!rc) {
        rc = biss_proto_fw_pru_get(&io, &pru);
    }
    if (rc || st.magic != BISS_MAGIC || pru == h->be.pru) {
        return rc;
    }
    if (pru > 1) {
        h->problem = biss_status_problem(&st, pru);
        return biss_err(e, BISS_E_SHM_RESULT, "data RAM: %s (0x%08x)", h->problem, pru);
    }
    return biss_err(e, BISS_E_FW_PRU,
                    "PRU%u runs an image assembled for PRU%u (BISS_ST_PRU): load "
                    "%s on PRU%u",
                    h->be.pru, pru, h->be.pru ? "biss_master_pru1" : "biss_master", h->be.pru);
}

/* The longest slave timeout the ranges allow (pru_fw/README.md, "Start-up
 * and recovery"). A firmware halted inside a frame leaves its slave inside
 * it, waiting for more clocks with SL high; if the next firmware's first
 * frame came within the slave's timeout, the slave would take its clocks as
 * that frame's (an ACK a period early, the data misread). MA stands still
 * this long after the halt, so the slave has timed out first. */
#define SLAVE_TIMEOUT_MAX_US 1000

static int halt_and_settle(biss_t *h) {
    bool was_on = false;
    int rc = biss_pru_enabled(h, &was_on);
    if (!rc) {
        rc = biss_pru_halt(h);
    }
    if (!rc && was_on) {
        rc = h->be.ops->advance(h->be.ctx, SLAVE_TIMEOUT_MAX_US);
    }
    return rc;
}

/* What a restart leaves of the run before (the firmware halted): its
 * frames the ring reader did not take (lost), and the number of its last
 * configuration, which the next one's continues, so that every reader
 * sees a restart as a new configuration (ST_CFG_ACK; biss_ring_follow). */
static int end_run(biss_t *h) {
    struct biss_proto_io io = biss_io(h);
    struct biss_shm_config blk = {0};
    int rc = biss_ring_restart(h);
    if (!rc) {
        rc = biss_proto_config_get(&io, &blk);
    }
    h->cfg_seq = blk.seq;
    return rc;
}

int biss_pru_load_and_start(biss_t *h) {
    int rc = halt_and_settle(h);
    if (!rc) {
        rc = end_run(h);
    }
    if (h->be.ops->pru_start) {
        /* the kernel loads the ELF (code, identification block) and starts */
        if (!rc) {
            rc = clear_shared(h);
        }
        if (!rc) {
            rc = h->be.ops->pru_start(h->be.ctx);
        }
        return rc;
    }
    if (!rc) {
        rc = load_iram(h);
    }
    if (!rc) {
        rc = clear_shared(h);
    }
    if (!rc) {
        rc = biss_pru_write_id(h);
    }
    /* ENABLE with SOFT_RST_N low: reset (PC to 0) and run, as prussdrv does */
    if (!rc) {
        rc = write_control(h, ICSS_CTRL_ENABLE);
    }
    return rc;
}
