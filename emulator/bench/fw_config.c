/* fw_config.c - firmware configuration from the bench's chain (fw_config.h). */
#include "fw_config.h"

#include "biss/biss_shm.h"
#include "biss_crc.h"

static void put(struct bench *b, uint32_t off, uint32_t v, size_t n) {
    uint8_t bytes[4] = {(uint8_t)v, (uint8_t)(v >> 8), (uint8_t)(v >> 16), (uint8_t)(v >> 24)};
    pru_host_write(bench_core(b), pru_soc_base(bench_config(b)->soc) + off, bytes, n);
}

static uint32_t get32(struct bench *b, uint32_t off) {
    uint8_t x[4];
    pru_host_read(bench_core(b), pru_soc_base(bench_config(b)->soc) + off, x, 4);
    return (uint32_t)x[0] | (uint32_t)x[1] << 8 | (uint32_t)x[2] << 16 | (uint32_t)x[3] << 24;
}

/* One slave's block: everything before the CRC is its data word. */
static void put_slave(struct bench *b, unsigned i, const biss_slave_cfg *s) {
    uint32_t o = BISS_CFG_SLAVE0 + i * BISS_CFG_SLAVE_SIZE;
    unsigned w = biss_crc_width(s->crc_poly);
    unsigned n = s->pos_bits + s->fill_bits + s->has_err + s->has_warn + s->lc_bits;
    bool ew = s->has_err && s->has_warn;
    put(b, o + BISS_CFG_S_DATA_BITS, n, 1);
    put(b, o + BISS_CFG_S_CRC_BITS, w, 1);
    put(b, o + BISS_CFG_S_EW_SHIFT, ew ? s->lc_bits : 0, 1);
    put(b, o + BISS_CFG_S_FLAGS, ew ? BISS_SF_EW : 0, 1);
    put(b, o + BISS_CFG_S_CRC_POLY, w ? s->crc_poly & ((1u << w) - 1u) : 0, 2);
    put(b, o + BISS_CFG_S_CRC_START, s->crc_start, 2);
}

/* An SSI encoder: its code word, no CRC; the line delay from the model
 * (an SSI slave gives no ACK to measure it by). */
static void put_ssi(struct bench *b, const ssi_cfg *s) {
    uint32_t o = BISS_CFG_SLAVE0;
    put(b, o + BISS_CFG_S_DATA_BITS, s->bits, 1);
    put(b, o + BISS_CFG_S_CRC_BITS, 0, 1);
    put(b, o + BISS_CFG_S_EW_SHIFT, 0, 1);
    put(b, o + BISS_CFG_S_FLAGS, BISS_SF_SSI, 1);
    put(b, o + BISS_CFG_S_CRC_POLY, 0, 2);
    put(b, o + BISS_CFG_S_CRC_START, 0, 2);
    put(b, BISS_CFG_SSI_DELAY_NS, bench_ssi_delay_ns(b), 2);
}

int fw_config_write(struct bench *b, const struct fw_settings *s) {
    link_model *l = bench_link(b);
    int ssi = l->sc.protocol == SCENARIO_SSI;
    put(b, BISS_CFG_HALF, s->half, 2);
    put(b, BISS_CFG_NSLAVES, ssi ? 1 : l->sc.biss.n, 1);
    put(b, BISS_CFG_TRIGGER, s->trigger, 1);
    put(b, BISS_CFG_IEP_PERIOD, s->iep_period, 4);
    put(b, BISS_CFG_PROC_LIMIT, s->proc_limit, 2);
    if (ssi) {
        put_ssi(b, &l->sc.ssi);
    } else {
        put(b, BISS_CFG_SSI_DELAY_NS, 0, 2);
        for (unsigned i = 0; i < l->sc.biss.n; i++) {
            put_slave(b, i, &l->sc.biss.s[i]);
        }
    }
    put(b, BISS_CFG_SEQ, get32(b, BISS_CFG_SEQ) + 1, 4);
    return 0;
}
