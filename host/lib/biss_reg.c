/* biss_reg.c - register access and BiSS commands: programs built and
 * answers parsed by the codec (biss_cd.h), run by the firmware through
 * biss_cd_exchange() (blocking) or biss_cd_begin()/biss_cd_check()
 * (non-blocking). */
#include "biss_priv.h"

#include <stdlib.h>
#include <string.h>

/* Frames a register may take to answer (late S) before the firmware gives up. */
#define REG_WAIT_LIMIT 64

/* The codec's structs are a few KB: on the heap, not on a caller's stack. */
struct biss_cd_job {
    biss_cd_prog prog;
    biss_cd_answer answer;
    biss_cd_result result;
    unsigned n;   /* bytes of a register access */
    uint32_t cmd; /* CD_CMD of a started job */
    bool done;
    int rc; /* the verdict, once done */
};

static int valid_access(const biss_t *h, unsigned id, uint8_t addr, unsigned n) {
    return h && id <= 7 && addr <= 0x7f && n >= 1 && n <= BISS_REG_MAX_SEQ;
}

static int build_read(biss_cd_job *j, unsigned id, uint8_t addr, unsigned n) {
    j->n = n;
    return biss_cd_error(biss_cd_build_read(&j->prog, id, addr, n));
}

static int build_write(biss_cd_job *j, unsigned id, uint8_t addr, const uint8_t *buf, unsigned n) {
    j->n = n;
    return biss_cd_error(biss_cd_build_write(&j->prog, id, addr, buf, n));
}

static int build_command(biss_cd_job *j, uint8_t ids, unsigned cmd, bool check_ida) {
    return biss_cd_error(biss_cd_build_command(&j->prog, ids, cmd, check_ida));
}

static int parse(biss_cd_job *j) {
    return biss_cd_error(biss_cd_parse(&j->prog, &j->answer, &j->result));
}

/* Blocking: build (rc from the builder), run to the end, parse. */
static int run_job(biss_t *h, biss_cd_job *j, int rc) {
    if (!rc) {
        rc = biss_cd_exchange(h, &j->prog, REG_WAIT_LIMIT, h->timeout_ms, &j->answer);
    }
    return rc ? rc : parse(j);
}

static void copy_bytes(const biss_cd_job *j, uint8_t *buf) {
    for (unsigned i = 0; i < j->n; i++) {
        buf[i] = j->result.byte[i].data;
    }
}

int biss_reg_read(biss_t *h, unsigned id, uint8_t addr, uint8_t *buf, unsigned n) {
    if (!buf || !valid_access(h, id, addr, n)) {
        return BISS_E_INVAL;
    }
    biss_cd_job *j = calloc(1, sizeof *j);
    if (!j) {
        return BISS_E_NOMEM;
    }
    int rc = run_job(h, j, build_read(j, id, addr, n));
    if (!rc) {
        copy_bytes(j, buf);
    }
    free(j);
    return rc;
}

int biss_reg_write(biss_t *h, unsigned id, uint8_t addr, const uint8_t *buf, unsigned n) {
    if (!buf || !valid_access(h, id, addr, n)) {
        return BISS_E_INVAL;
    }
    biss_cd_job *j = calloc(1, sizeof *j);
    if (!j) {
        return BISS_E_NOMEM;
    }
    int rc = run_job(h, j, build_write(j, id, addr, buf, n));
    free(j);
    return rc;
}

int biss_command(biss_t *h, uint8_t ids, unsigned cmd, bool check_ida, uint8_t *ida) {
    if (!h || cmd > 3) {
        return BISS_E_INVAL;
    }
    biss_cd_job *j = calloc(1, sizeof *j);
    if (!j) {
        return BISS_E_NOMEM;
    }
    int rc = run_job(h, j, build_command(j, ids, cmd, check_ida));
    if (ida) {
        *ida = j->result.ida;
    }
    free(j);
    return rc;
}

/* ---- non-blocking forms ------------------------------------------------- */

/* Starts a built job; on any error nothing is left running and *out is NULL. */
static int start_job(biss_t *h, biss_cd_job *j, int rc, biss_cd_job **out) {
    if (!rc) {
        rc = biss_cd_begin(h, &j->prog, REG_WAIT_LIMIT, &j->cmd);
    }
    if (rc) {
        free(j);
        j = NULL;
    }
    *out = j;
    return rc;
}

int biss_reg_read_start(biss_t *h, unsigned id, uint8_t addr, unsigned n, biss_cd_job **job) {
    if (!job || !valid_access(h, id, addr, n)) {
        return BISS_E_INVAL;
    }
    biss_cd_job *j = calloc(1, sizeof *j);
    if (!j) {
        *job = NULL;
        return BISS_E_NOMEM;
    }
    return start_job(h, j, build_read(j, id, addr, n), job);
}

int biss_reg_write_start(biss_t *h, unsigned id, uint8_t addr, const uint8_t *buf, unsigned n,
                         biss_cd_job **job) {
    if (!job || !buf || !valid_access(h, id, addr, n)) {
        return BISS_E_INVAL;
    }
    biss_cd_job *j = calloc(1, sizeof *j);
    if (!j) {
        *job = NULL;
        return BISS_E_NOMEM;
    }
    return start_job(h, j, build_write(j, id, addr, buf, n), job);
}

int biss_command_start(biss_t *h, uint8_t ids, unsigned cmd, bool check_ida, biss_cd_job **job) {
    if (!h || !job || cmd > 3) {
        return BISS_E_INVAL;
    }
    biss_cd_job *j = calloc(1, sizeof *j);
    if (!j) {
        *job = NULL;
        return BISS_E_NOMEM;
    }
    return start_job(h, j, build_command(j, ids, cmd, check_ida), job);
}

int biss_cd_poll(biss_t *h, biss_cd_job *j) {
    if (!h || !j) {
        return BISS_E_INVAL;
    }
    if (j->done) {
        return j->rc;
    }
    int rc = biss_cd_check(h, j->cmd, &j->answer);
    if (rc == BISS_E_CD_BUSY) {
        return rc;
    }
    j->rc = rc ? rc : parse(j);
    j->done = true;
    return j->rc;
}

int biss_cd_job_bytes(const biss_cd_job *j, uint8_t *buf) {
    if (!j || !buf) {
        return BISS_E_INVAL;
    }
    if (!j->done) {
        return BISS_E_CD_BUSY;
    }
    if (j->rc) {
        return j->rc;
    }
    copy_bytes(j, buf);
    return BISS_OK;
}

int biss_cd_job_ida(const biss_cd_job *j, uint8_t *ida) {
    if (!j || !ida) {
        return BISS_E_INVAL;
    }
    if (!j->done) {
        return BISS_E_CD_BUSY;
    }
    *ida = j->result.ida;
    return j->rc;
}

int biss_cd_job_slots(const biss_cd_job *j, struct biss_cd_slots *out) {
    if (!j || !out) {
        return BISS_E_INVAL;
    }
    if (!j->done) {
        return BISS_E_CD_BUSY;
    }
    *out = (struct biss_cd_slots){
        .idl = j->result.idl,
        .ida = j->result.ida,
        .header_cds = j->result.header_cds,
        .ida_cds = j->result.ida_cds,
    };
    return BISS_OK;
}

void biss_cd_job_free(biss_cd_job *j) {
    free(j);
}
