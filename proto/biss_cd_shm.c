/* biss_cd_shm.c - the control-communication words of a data RAM image
 * (biss_cd.h): proto's transfers (biss_proto_io.c) on a byte array. */
#include "biss_proto.h"

#include <string.h>

struct image {
    uint8_t *dram;
    const uint8_t *cdram;
    size_t len;
};

static int img_read(void *ctx, uint32_t off, void *buf, size_t n) {
    struct image *m = ctx;
    if (off > m->len || n > m->len - off) {
        return BISS_E_INVAL;
    }
    memcpy(buf, m->cdram + off, n);
    return BISS_OK;
}

static int img_write(void *ctx, uint32_t off, const void *buf, size_t n) {
    struct image *m = ctx;
    if (!m->dram || off > m->len || n > m->len - off) {
        return BISS_E_INVAL;
    }
    memcpy(m->dram + off, buf, n);
    return BISS_OK;
}

biss_cd_err biss_cd_shm_put(const biss_cd_prog *p, uint16_t wait_limit, uint8_t *dram,
                            size_t dram_len) {
    if (!dram || dram_len < BISS_CD_RESP) {
        return BISS_CD_E_ARG;
    }
    if (p->len < 1 || p->len > BISS_CD_MAX_STEPS) {
        return BISS_CD_E_TOO_LONG;
    }
    struct image m = {dram, dram, dram_len};
    struct biss_proto_io io = {.read = img_read, .write = img_write, .ctx = &m};
    uint8_t none[BISS_CD_PROG_BYTES] = {0}; /* an image holds no stale steps */
    img_write(&m, BISS_CD_PROG, none, sizeof none);
    return biss_proto_cd_load(&io, p, wait_limit) ? BISS_CD_E_ARG : BISS_CD_OK;
}

biss_cd_err biss_cd_shm_get(const uint8_t *dram, size_t dram_len, biss_cd_answer *a) {
    if (!dram || dram_len < BISS_CD_RESP + BISS_CD_RESP_BYTES) {
        return BISS_CD_E_ARG;
    }
    struct image m = {NULL, dram, dram_len};
    struct biss_proto_io io = {.read = img_read, .write = img_write, .ctx = &m};
    return biss_proto_cd_answer(&io, a) ? BISS_CD_E_ARG : BISS_CD_OK;
}
