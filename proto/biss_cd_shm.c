/* The control-communication words of the firmware's data RAM, as
 * include/biss/biss_shm.h lays them out (little-endian). */
#include "biss_cd.h"

#include <string.h>

static void put16(uint8_t *at, uint16_t v) {
    at[0] = (uint8_t)v;
    at[1] = (uint8_t)(v >> 8);
}

static uint16_t get16(const uint8_t *at) {
    return (uint16_t)(at[0] | at[1] << 8);
}

static uint32_t get32(const uint8_t *at) {
    return (uint32_t)get16(at) | (uint32_t)get16(at + 2) << 16;
}

void biss_cd_pack(const biss_cd_prog *p, uint8_t prog[BISS_CD_PROG_BYTES]) {
    memset(prog, 0, BISS_CD_PROG_BYTES);
    for (unsigned i = 0; i < p->len && i < BISS_CD_MAX_STEPS; i++) {
        prog[i / 2] |= (uint8_t)((p->op[i] & 15u) << 4 * (i % 2));
    }
}

uint32_t biss_cd_ida_word(const biss_cd_prog *p) {
    if (p->kind != BISS_CD_COMMAND || !p->ida_test) {
        return 0;
    }
    return p->end | (uint32_t)p->ids << 16;
}

biss_cd_err biss_cd_shm_put(const biss_cd_prog *p, uint16_t wait_limit, uint8_t *dram,
                            size_t dram_len) {
    if (!dram || dram_len < BISS_CD_RESP) {
        return BISS_CD_E_ARG;
    }
    if (p->len < 1 || p->len > BISS_CD_MAX_STEPS) {
        return BISS_CD_E_TOO_LONG;
    }
    biss_cd_pack(p, dram + BISS_CD_PROG);
    put16(dram + BISS_CD_STEPS, p->len);
    put16(dram + BISS_CD_WAIT_LIMIT, wait_limit);
    uint32_t ida = biss_cd_ida_word(p);
    put16(dram + BISS_CD_IDA_STEP, (uint16_t)ida);
    put16(dram + BISS_CD_IDA_EXPECT, (uint16_t)(ida >> 16));
    return BISS_CD_OK;
}

biss_cd_err biss_cd_shm_get(const uint8_t *dram, size_t dram_len, biss_cd_answer *a) {
    if (!dram || dram_len < BISS_CD_RESP + BISS_CD_RESP_BYTES) {
        return BISS_CD_E_ARG;
    }
    a->seq = get32(dram + BISS_ST_CD_SEQ);
    a->status = dram[BISS_ST_CD_STATUS];
    a->bytes = dram[BISS_ST_CD_STATUS + 1];
    a->steps = get16(dram + BISS_ST_CD_STATUS + 2);
    memcpy(a->resp, dram + BISS_CD_RESP, BISS_CD_RESP_BYTES);
    return BISS_CD_OK;
}
