/* biss_proto_io.c - the firmware's shared-memory transfers (biss_proto.h)
 * through a caller's data-RAM reader/writer: which words, in which order. */
#include "biss_proto.h"

#include <stdatomic.h>
#include <string.h>

static int rd(const struct biss_proto_io *io, uint32_t off, void *buf, size_t n) {
    return io->read(io->ctx, off, buf, n);
}

static int wr(const struct biss_proto_io *io, uint32_t off, const void *buf, size_t n) {
    return io->write(io->ctx, off, buf, n);
}

/* The firmware applies a block when CFG_SEQ changes: the block first. */
int biss_proto_config_put(const struct biss_proto_io *io, const struct biss_shm_config *blk,
                          uint32_t seq) {
    const size_t at = offsetof(struct biss_shm_config, half);
    int rc = wr(io, BISS_CFG_SEQ + (uint32_t)at, (const uint8_t *)blk + at, sizeof *blk - at);
    atomic_thread_fence(memory_order_seq_cst);
    if (!rc) {
        rc = wr(io, BISS_CFG_SEQ, &seq, 4);
    }
    atomic_thread_fence(memory_order_seq_cst);
    return rc;
}

int biss_proto_config_get(const struct biss_proto_io *io, struct biss_shm_config *blk) {
    return rd(io, BISS_CFG_SEQ, blk, sizeof *blk);
}

int biss_proto_status_get(const struct biss_proto_io *io, struct biss_shm_status *st) {
    return rd(io, BISS_ST_MAGIC, st, sizeof *st);
}

int biss_proto_id_get(const struct biss_proto_io *io, struct biss_shm_id *id) {
    return rd(io, BISS_ID, id, sizeof *id);
}

int biss_proto_id_put(const struct biss_proto_io *io, const struct biss_shm_id *id,
                      const uint8_t rsc[16]) {
    uint8_t blk[BISS_ID_END - BISS_ID];
    _Static_assert(sizeof blk == sizeof *id + 16, "id block and resource table");
    memcpy(blk, id, sizeof *id);
    memcpy(blk + sizeof *id, rsc, 16);
    return wr(io, BISS_ID, blk, sizeof blk);
}

int biss_proto_fw_pru_get(const struct biss_proto_io *io, uint32_t *pru) {
    return rd(io, BISS_ST_PRU, pru, 4);
}

int biss_proto_off_grid_get(const struct biss_proto_io *io, uint32_t *frames) {
    return rd(io, BISS_ST_OFF_GRID, frames, 4);
}

int biss_proto_iep_period_get(const struct biss_proto_io *io, uint32_t *counts) {
    return rd(io, BISS_CFG_IEP_PERIOD, counts, 4);
}

int biss_proto_trigger_get(const struct biss_proto_io *io, uint32_t *pending) {
    return rd(io, BISS_CMD_TRIGGER, pending, 4);
}

int biss_proto_trigger(const struct biss_proto_io *io) {
    uint32_t one = 1;
    return wr(io, BISS_CMD_TRIGGER, &one, 4);
}

int biss_proto_pub_seq(const struct biss_proto_io *io, uint32_t *seq) {
    return rd(io, BISS_ST_SEQ, seq, 4);
}

int biss_proto_pub_seq_any(const struct biss_proto_io *io, uint32_t *seq, bool *any) {
    uint32_t buf = 0;
    int rc = biss_proto_pub_seq(io, seq);
    if (!rc && *seq == 0) {
        rc = rd(io, BISS_ST_BUF, &buf, 4);
    }
    *any = *seq != 0 || buf != 0;
    return rc;
}

int biss_proto_slot_check(uint32_t slot, unsigned nslaves) {
    /* any layout: on the grid every stride keeps (16 bytes), with a header's room */
    unsigned step = nslaves ? BISS_RING_STRIDE(nslaves) : BISS_R_SLAVE_SIZE;
    unsigned room = nslaves ? BISS_RING_STRIDE(nslaves) : BISS_RING_STRIDE(1);
    if (nslaves > BISS_MAX_SLAVES || slot < BISS_RING0 || slot > BISS_RING_END - room ||
        (slot - BISS_RING0) % step != 0) {
        return BISS_E_SHM_RESULT;
    }
    return BISS_OK;
}

int biss_proto_result_get(const struct biss_proto_io *io, unsigned nslaves,
                          struct biss_shm_result *r) {
    uint32_t buf;
    int rc = rd(io, BISS_ST_BUF, &buf, 4);
    if (rc) {
        return rc;
    }
    if (biss_proto_slot_check(buf, 0) != BISS_OK) {
        return BISS_E_SHM_RESULT;
    }
    if (nslaves > BISS_MAX_SLAVES) {
        nslaves = BISS_MAX_SLAVES;
    }
    memset(r, 0, sizeof *r);
    /* header and only the slaves that can be in it: fewer bus reads on
     * silicon, so fewer races with the next publication; never past the
     * ring (a caller that does not know the layout asks for 8) */
    size_t n = offsetof(struct biss_shm_result, slave) + nslaves * sizeof r->slave[0];
    if (n > BISS_RING_END - buf) {
        n = BISS_RING_END - buf;
    }
    return rd(io, buf, r, n);
}

int biss_proto_cd_load(const struct biss_proto_io *io, const biss_cd_prog *p, unsigned wait_limit) {
    if (p->len < 1 || p->len > BISS_CD_MAX_STEPS) {
        return BISS_E_CD_STEPS; /* the firmware would refuse it (BISS_CDST_ERR_STEPS) */
    }
    uint8_t prog[BISS_CD_PROG_BYTES];
    biss_cd_pack(p, prog);
    /* the words the steps use */
    int rc = wr(io, BISS_CD_PROG, prog, (p->len + 7u) / 8u * 4u);
    uint32_t steps = p->len | (uint32_t)wait_limit << 16;
    uint32_t ida = biss_cd_ida_word(p);
    if (!rc) {
        rc = wr(io, BISS_CD_STEPS, &steps, 4);
    }
    if (!rc) {
        rc = wr(io, BISS_CD_IDA_STEP, &ida, 4);
    }
    return rc;
}

int biss_proto_cd_put(const struct biss_proto_io *io, const biss_cd_prog *p, unsigned wait_limit,
                      uint32_t *cmd) {
    if (p->len < 1 || p->len > BISS_CD_MAX_STEPS) {
        return BISS_E_CD_STEPS;
    }
    struct biss_shm_cd cd;
    int rc = rd(io, BISS_CD_CMD, &cd, sizeof cd);
    if (rc) {
        return rc;
    }
    if (cd.cmd != cd.seq) {
        return BISS_E_CD_BUSY;
    }
    rc = biss_proto_cd_load(io, p, wait_limit);
    atomic_thread_fence(memory_order_seq_cst);
    /* the next number, past 0: the firmware's "no program" (pru_fw/cd.p,
     * CdState.cmd); a program numbered 0 restarted every frame, never ended */
    *cmd = cd.cmd + 1 == 0 ? 1 : cd.cmd + 1;
    if (!rc) {
        rc = wr(io, BISS_CD_CMD, cmd, 4);
    }
    atomic_thread_fence(memory_order_seq_cst);
    return rc;
}

int biss_proto_cd_answer(const struct biss_proto_io *io, biss_cd_answer *a) {
    struct biss_shm_cd cd;
    int rc = rd(io, BISS_CD_CMD, &cd, sizeof cd);
    if (!rc) {
        rc = rd(io, BISS_CD_RESP, a->resp, sizeof a->resp);
    }
    a->seq = cd.seq;
    a->status = cd.status;
    a->bytes = cd.bytes;
    a->steps = cd.steps_done;
    return rc;
}

int biss_proto_cd_running(const struct biss_proto_io *io, uint32_t *cmd) {
    struct biss_shm_cd cd;
    int rc = rd(io, BISS_CD_CMD, &cd, sizeof cd);
    if (rc) {
        return rc;
    }
    *cmd = cd.cmd;
    return cd.cmd != cd.seq;
}

int biss_proto_cd_ended(const struct biss_proto_io *io, uint32_t cmd, biss_cd_answer *a) {
    struct biss_shm_cd cd;
    int rc = rd(io, BISS_CD_CMD, &cd, sizeof cd);
    if (rc || cd.seq != cmd) {
        return rc;
    }
    rc = biss_proto_cd_answer(io, a);
    return rc ? rc : 1;
}
