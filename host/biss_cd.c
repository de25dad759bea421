/* biss_cd.c - control communication: handing a CDM program to the
 * firmware (one step per frame) and collecting the CDS answers. */
#include "biss_priv.h"

#include "biss/biss_shm_struct.h"

#include <stdatomic.h>
#include <string.h>

_Static_assert(BISS_CD_OP_0 == BISS_CDOP_0 && BISS_CD_OP_1 == BISS_CDOP_1 &&
                   BISS_CD_OP_WAIT == BISS_CDOP_WAIT && BISS_CD_OP_END == BISS_CDOP_END,
               "program ops match the shm codes");

uint8_t biss_crc4_sent(uint32_t value, unsigned n) {
    unsigned crc = 0;
    for (unsigned i = n; i-- > 0;) {
        unsigned feedback = ((crc >> 3) ^ (value >> i)) & 1u;
        crc = (crc << 1) & 0xfu;
        if (feedback) {
            crc ^= 0x3u; /* x^4 + x + 1 without its top term */
        }
    }
    return (uint8_t)(~crc & 0xfu);
}

/* Two bits a step, step i in bits 2(i%4)+1..2(i%4) of byte i/4. */
static void pack(const uint8_t *ops, unsigned n, uint8_t *prog) {
    memset(prog, 0, BISS_CD_PROG_BYTES);
    for (unsigned i = 0; i < n; i++) {
        prog[i / 4] |= (uint8_t)((ops[i] & 3u) << (2 * (i % 4)));
    }
}

struct cd_wait {
    uint32_t cmd;
    bool host_trigger;
};

/* Done when the firmware echoes the command; in host-trigger mode each
 * step needs a frame, so ask for the next one whenever the last started. */
static int cd_ended(biss_t *h, void *arg) {
    struct cd_wait *w = arg;
    uint32_t seq;
    int rc = biss_dram_read32(h, BISS_ST_CD_SEQ, &seq);
    if (rc || seq == w->cmd) {
        return rc ? rc : 1;
    }
    if (w->host_trigger) {
        uint32_t pending;
        rc = biss_dram_read32(h, BISS_CMD_TRIGGER, &pending);
        if (!rc && pending == 0) {
            rc = biss_dram_write32(h, BISS_CMD_TRIGGER, 1);
        }
    }
    return rc;
}

static int cd_status_error(unsigned status) {
    switch (status) {
    case BISS_CDST_DONE:
        return BISS_OK;
    case BISS_CDST_ERR_WAIT:
        return BISS_E_CD_WAIT;
    case BISS_CDST_ERR_STEPS:
        return BISS_E_CD_STEPS;
    case BISS_CDST_ERR_FRAME:
        return BISS_E_CD_FRAME;
    default:
        return BISS_E_TIMEOUT; /* still busy or idle: no verdict */
    }
}

static int write_program(biss_t *h, const uint8_t *ops, unsigned n, unsigned wait_limit,
                         uint32_t *cmd) {
    struct biss_shm_cd cd;
    int rc = biss_dram_read(h, BISS_CD_CMD, &cd, sizeof cd);
    if (rc) {
        return rc;
    }
    if (cd.cmd != cd.seq) {
        return BISS_E_CD_BUSY;
    }
    uint8_t prog[BISS_CD_PROG_BYTES];
    pack(ops, n, prog);
    rc = biss_dram_write(h, BISS_CD_PROG, prog, (n + 15) / 16 * 4);
    if (!rc) {
        rc = biss_dram_write32(h, BISS_CD_STEPS, n | (uint32_t)wait_limit << 16);
    }
    atomic_thread_fence(memory_order_seq_cst);
    *cmd = cd.cmd + 1;
    if (!rc) {
        rc = biss_dram_write32(h, BISS_CD_CMD, *cmd);
    }
    atomic_thread_fence(memory_order_seq_cst);
    return rc;
}

static int cd_run_locked(biss_t *h, const uint8_t *ops, unsigned n, unsigned wait_limit,
                         unsigned timeout_ms, uint8_t *resp) {
    if (!h->configured) {
        return BISS_E_NOT_CONFIGURED;
    }
    struct cd_wait w = {.host_trigger = h->cfg.trigger == BISS_TRIGGER_HOST};
    int rc = write_program(h, ops, n, wait_limit, &w.cmd);
    if (!rc) {
        rc = biss_wait_for(h, timeout_ms, cd_ended, &w);
    }
    uint32_t status = 0;
    if (!rc) {
        rc = biss_dram_read32(h, BISS_ST_CD_STATUS, &status);
    }
    if (!rc) {
        rc = cd_status_error(status & 0xffffu);
    }
    if (!rc) {
        rc = biss_dram_read(h, BISS_CD_RESP, resp, (n + 7) / 8);
    }
    return rc;
}

int biss_cd_run(biss_t *h, const uint8_t *ops, unsigned n, unsigned wait_limit, unsigned timeout_ms,
                uint8_t *resp) {
    if (!h || !ops || !resp || wait_limit == 0 || wait_limit > 0xffff) {
        return BISS_E_INVAL;
    }
    if (n < 1 || n > BISS_CD_MAX_STEPS) {
        return BISS_E_CD_STEPS;
    }
    for (unsigned i = 0; i < n; i++) {
        if (ops[i] > BISS_CD_OP_END) {
            return BISS_E_INVAL;
        }
    }
    biss_op_begin(h);
    int rc = cd_run_locked(h, ops, n, wait_limit, timeout_ms, resp);
    biss_op_end(h);
    return rc;
}
