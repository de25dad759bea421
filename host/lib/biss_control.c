/* biss_control.c - control communication transport: the codec's program
 * (biss_cd.h) into data RAM, CD_CMD last, the wait for the firmware's end
 * of it, and its answer back. */
#include "biss_priv.h"

#include "biss/biss_shm_struct.h"

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
    biss_cd_answer *a; /* filled when it ended */
};

/* Done when the firmware echoes the command; in host-trigger mode each
 * step needs a frame, so ask for the next one whenever the last started. */
static int cd_ended(biss_t *h, void *arg) {
    struct cd_wait *w = arg;
    struct biss_proto_io io = biss_io(h);
    int rc = biss_proto_cd_ended(&io, w->cmd, w->a);
    if (rc) {
        return rc;
    }
    if (w->host_trigger) {
        uint32_t pending;
        rc = biss_proto_trigger_get(&io, &pending);
        if (!rc && pending == 0) {
            rc = biss_proto_trigger(&io);
        }
    }
    return rc;
}

/* A built frame (register access, command) after a program that stopped
 * inside its control frame, by this handle or any other: CDM 0 steps first,
 * so the slave is armed again at its S (biss_cd.h, BISS_CD_REARM_ZEROS). A
 * raw program runs as given (host/CD.md). */
static int rearm_locked(biss_t *h, biss_cd_prog *p) {
    if (p->kind == BISS_CD_RAW) {
        return BISS_OK;
    }
    struct biss_proto_io io = biss_io(h);
    biss_cd_answer last;
    int rc = biss_proto_cd_answer(&io, &last);
    if (rc || (last.status != BISS_CDST_ERR_FRAME && last.status != BISS_CDST_ERR_WAIT)) {
        return rc;
    }
    return biss_cd_error(biss_cd_lead_in(p, BISS_CD_REARM_ZEROS));
}

/* Checks and puts a program (handle locked); *cmd is the CD_CMD it runs as. */
static int begin_locked(biss_t *h, biss_cd_prog *p, unsigned wait_limit, uint32_t *cmd) {
    if (wait_limit > 0xffff) {
        return BISS_E_INVAL;
    }
    if (!h->configured) {
        return BISS_E_NOT_CONFIGURED;
    }
    if (h->cfg.slave[0].ssi) {
        return BISS_E_SSI_NO_CONTROL; /* its frames carry no CDM or CDS to answer it */
    }
    int rc = biss_exclusive(h);
    if (!rc) {
        rc = rearm_locked(h, p);
    }
    if (rc) {
        return rc;
    }
    struct biss_proto_io io = biss_io(h);
    return biss_proto_cd_put(&io, p, wait_limit, cmd);
}

static int exchange_locked(biss_t *h, biss_cd_prog *p, unsigned wait_limit, unsigned timeout_ms,
                           biss_cd_answer *a) {
    struct cd_wait w = {.host_trigger = h->cfg.trigger == BISS_TRIGGER_HOST, .a = a};
    int rc = begin_locked(h, p, wait_limit, &w.cmd);
    return rc ? rc : biss_wait_for(h, timeout_ms, cd_ended, &w);
}

int biss_cd_exchange(biss_t *h, biss_cd_prog *p, unsigned wait_limit, unsigned timeout_ms,
                     biss_cd_answer *a) {
    memset(a, 0, sizeof *a);
    biss_op_begin(h);
    int rc = exchange_locked(h, p, wait_limit, timeout_ms, a);
    biss_op_end(h);
    return rc;
}

int biss_cd_begin(biss_t *h, biss_cd_prog *p, unsigned wait_limit, uint32_t *cmd) {
    biss_op_begin(h);
    int rc = begin_locked(h, p, wait_limit, cmd);
    biss_op_end(h);
    return rc;
}

int biss_cd_check(biss_t *h, uint32_t cmd, biss_cd_answer *a) {
    struct cd_wait w = {.cmd = cmd, .a = a};
    biss_op_begin(h);
    if (h->cd_cut_set && h->cd_cut == cmd) {
        biss_op_end(h);
        return BISS_E_SSI_NO_CONTROL; /* an SSI configuration cut it */
    }
    w.host_trigger = h->cfg.trigger == BISS_TRIGGER_HOST;
    int rc = cd_ended(h, &w); /* 1: the answer is in *a */
    if (rc == 0) {
        rc = BISS_E_CD_BUSY;
    } else if (rc == 1) {
        rc = BISS_OK;
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
