/* biss_control.c - control communication transport: the codec's program
 * (biss_cd.h) into data RAM, CD_CMD last, the wait for the firmware's end
 * of it, and its answer back. */
#include "biss_priv.h"

#include "biss/biss_shm_struct.h"

#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>

_Static_assert(BISS_CD_OP_0 == BISS_CDOP_0 && BISS_CD_OP_1 == BISS_CDOP_1 &&
                   BISS_CD_OP_WAIT == BISS_CDOP_WAIT && BISS_CD_OP_CRC == BISS_CDOP_CRC,
               "program ops match the shm codes");
_Static_assert(BISS_CD_CL_DATA == BISS_CDCL_DATA << 2 && BISS_CD_CL_CHECK == BISS_CDCL_CHECK << 2 &&
                   BISS_CD_CL_ECHO == BISS_CDCL_ECHO << 2,
               "program classes match the shm codes");

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

/* PROG (the words the steps use), STEPS and WAIT_LIMIT, then CD_CMD. */
static int put_program(biss_t *h, const biss_cd_prog *p, unsigned wait_limit, uint32_t *cmd) {
    struct biss_shm_cd cd;
    int rc = biss_dram_read(h, BISS_CD_CMD, &cd, sizeof cd);
    if (rc) {
        return rc;
    }
    if (cd.cmd != cd.seq) {
        return BISS_E_CD_BUSY;
    }
    uint8_t prog[BISS_CD_PROG_BYTES];
    biss_cd_pack(p, prog);
    rc = biss_dram_write(h, BISS_CD_PROG, prog, (p->len + 7u) / 8u * 4u);
    if (!rc) {
        rc = biss_dram_write32(h, BISS_CD_STEPS, p->len | (uint32_t)wait_limit << 16);
    }
    if (!rc) {
        rc = biss_dram_write32(h, BISS_CD_IDA_STEP, biss_cd_ida_word(p));
    }
    atomic_thread_fence(memory_order_seq_cst);
    *cmd = cd.cmd + 1;
    if (!rc) {
        rc = biss_dram_write32(h, BISS_CD_CMD, *cmd);
    }
    atomic_thread_fence(memory_order_seq_cst);
    return rc;
}

static int get_answer(biss_t *h, biss_cd_answer *a) {
    struct biss_shm_cd cd;
    int rc = biss_dram_read(h, BISS_CD_CMD, &cd, sizeof cd);
    if (!rc) {
        rc = biss_dram_read(h, BISS_CD_RESP, a->resp, sizeof a->resp);
    }
    a->seq = cd.seq;
    a->status = cd.status;
    a->bytes = cd.bytes;
    a->steps = cd.steps_done;
    return rc;
}

/* Checks and puts a program (handle locked); *cmd is the CD_CMD it runs as. */
static int begin_locked(biss_t *h, const biss_cd_prog *p, unsigned wait_limit, uint32_t *cmd) {
    if (wait_limit > 0xffff) {
        return BISS_E_INVAL;
    }
    if (!h->configured) {
        return BISS_E_NOT_CONFIGURED;
    }
    int rc = biss_exclusive(h);
    return rc ? rc : put_program(h, p, wait_limit, cmd);
}

static int exchange_locked(biss_t *h, const biss_cd_prog *p, unsigned wait_limit,
                           unsigned timeout_ms, biss_cd_answer *a) {
    struct cd_wait w = {.host_trigger = h->cfg.trigger == BISS_TRIGGER_HOST};
    int rc = begin_locked(h, p, wait_limit, &w.cmd);
    if (!rc) {
        rc = biss_wait_for(h, timeout_ms, cd_ended, &w);
    }
    return rc ? rc : get_answer(h, a);
}

int biss_cd_exchange(biss_t *h, const biss_cd_prog *p, unsigned wait_limit, unsigned timeout_ms,
                     biss_cd_answer *a) {
    memset(a, 0, sizeof *a);
    biss_op_begin(h);
    int rc = exchange_locked(h, p, wait_limit, timeout_ms, a);
    biss_op_end(h);
    return rc;
}

int biss_cd_begin(biss_t *h, const biss_cd_prog *p, unsigned wait_limit, uint32_t *cmd) {
    biss_op_begin(h);
    int rc = begin_locked(h, p, wait_limit, cmd);
    biss_op_end(h);
    return rc;
}

int biss_cd_check(biss_t *h, uint32_t cmd, biss_cd_answer *a) {
    struct cd_wait w = {.cmd = cmd};
    biss_op_begin(h);
    w.host_trigger = h->cfg.trigger == BISS_TRIGGER_HOST;
    int rc = cd_ended(h, &w);
    if (rc == 0) {
        rc = BISS_E_CD_BUSY;
    } else if (rc == 1) {
        memset(a, 0, sizeof *a);
        rc = get_answer(h, a);
    }
    biss_op_end(h);
    return rc;
}

int biss_cd_error(biss_cd_err e) {
    switch (e) {
    case BISS_CD_OK:
        return BISS_OK;
    case BISS_CD_E_ARG:
        return BISS_E_INVAL;
    case BISS_CD_E_TOO_LONG:
    case BISS_CD_E_REFUSED:
        return BISS_E_CD_STEPS;
    case BISS_CD_E_NOT_DONE:
        return BISS_E_TIMEOUT;
    case BISS_CD_E_FRAME:
        return BISS_E_CD_FRAME;
    case BISS_CD_E_NO_ECHO:
        return BISS_E_CD_NO_ECHO;
    case BISS_CD_E_NO_START:
        return BISS_E_CD_WAIT;
    case BISS_CD_E_CRC:
        return BISS_E_CD_CRC;
    case BISS_CD_E_ECHO:
        return BISS_E_CD_ECHO;
    case BISS_CD_E_IDA:
        return BISS_E_CD_IDA;
    case BISS_CD_E_WITHHELD:
        return BISS_E_CD_WITHHELD;
    }
    return BISS_E_CD_CRC;
}

int biss_cd_run(biss_t *h, const uint8_t *ops, unsigned n, unsigned wait_limit, unsigned timeout_ms,
                uint8_t *resp) {
    if (!h || !ops || !resp) {
        return BISS_E_INVAL;
    }
    if (n < 1 || n > BISS_CD_MAX_STEPS) {
        return BISS_E_CD_STEPS;
    }
    for (unsigned i = 0; i < n; i++) {
        /* biss_shm.h: a WAIT (class NONE) is never followed by a WAIT or a CRC bit */
        bool wait = (ops[i] & 3u) == BISS_CD_OP_WAIT;
        bool after_wait = i > 0 && ops[i - 1] == BISS_CD_OP_WAIT;
        if (ops[i] > 15 || (wait && ops[i] != BISS_CD_OP_WAIT) ||
            (after_wait && (wait || (ops[i] & 3u) == BISS_CD_OP_CRC))) {
            return BISS_E_INVAL;
        }
    }
    biss_cd_prog *p = malloc(sizeof *p); /* ~2 KB */
    biss_cd_answer *a = malloc(sizeof *a);
    int rc = p && a ? BISS_OK : BISS_E_NOMEM;
    if (!rc) {
        rc = biss_cd_error(biss_cd_build_raw(p, ops, n));
    }
    if (!rc) {
        rc = biss_cd_exchange(h, p, wait_limit, timeout_ms, a);
    }
    if (!rc) {
        biss_cd_result r; /* a raw program's: only the firmware's verdict */
        rc = biss_cd_error(biss_cd_parse(p, a, &r));
    }
    if (!rc) {
        memcpy(resp, a->resp, (n + 7) / 8);
    }
    free(p);
    free(a);
    return rc;
}
