/* biss_reg.c - register access and BiSS commands: programs built and
 * answers parsed by the codec (biss_cd.h), run by the firmware through
 * biss_cd_exchange(). */
#include "biss_priv.h"

#include <stdlib.h>
#include <string.h>

/* Frames a register may take to answer (late S) before the firmware gives up. */
#define REG_WAIT_LIMIT 64

/* The codec's structs are a few KB: on the heap, not on a caller's stack. */
struct cd_job {
    biss_cd_prog prog;
    biss_cd_answer answer;
    biss_cd_result result;
};

static int run_job(biss_t *h, struct cd_job *j, biss_cd_err built) {
    int rc = biss_cd_error(built);
    if (!rc) {
        rc = biss_cd_exchange(h, &j->prog, REG_WAIT_LIMIT, h->timeout_ms, &j->answer);
    }
    if (!rc) {
        rc = biss_cd_error(biss_cd_parse(&j->prog, &j->answer, &j->result));
    }
    return rc;
}

static int valid_access(biss_t *h, unsigned id, uint8_t addr, const uint8_t *buf, unsigned n) {
    return h && buf && id <= 7 && addr <= 0x7f && n >= 1 && n <= BISS_REG_MAX_SEQ;
}

int biss_reg_read(biss_t *h, unsigned id, uint8_t addr, uint8_t *buf, unsigned n) {
    if (!valid_access(h, id, addr, buf, n)) {
        return BISS_E_INVAL;
    }
    struct cd_job *j = malloc(sizeof *j);
    if (!j) {
        return BISS_E_NOMEM;
    }
    int rc = run_job(h, j, biss_cd_build_read(&j->prog, id, addr, n));
    for (unsigned i = 0; !rc && i < n; i++) {
        buf[i] = j->result.byte[i].data;
    }
    free(j);
    return rc;
}

int biss_reg_write(biss_t *h, unsigned id, uint8_t addr, const uint8_t *buf, unsigned n) {
    if (!valid_access(h, id, addr, buf, n)) {
        return BISS_E_INVAL;
    }
    struct cd_job *j = malloc(sizeof *j);
    if (!j) {
        return BISS_E_NOMEM;
    }
    int rc = run_job(h, j, biss_cd_build_write(&j->prog, id, addr, buf, n));
    free(j);
    return rc;
}

int biss_command(biss_t *h, uint8_t ids, unsigned cmd, uint8_t *ida) {
    if (!h || cmd > 3) {
        return BISS_E_INVAL;
    }
    struct cd_job *j = malloc(sizeof *j);
    if (!j) {
        return BISS_E_NOMEM;
    }
    int rc = run_job(h, j, biss_cd_build_command(&j->prog, ids, cmd));
    if (ida) {
        *ida = j->result.ida;
    }
    free(j);
    return rc;
}
