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

/* The 28-bit shift register samples SL at 8x MA through two cascaded
 * dividers of the 200 MHz clock, ratios a/2 and b/2 with 2 <= a, b <= 32
 * (docs/pru-facts.md §4.4, §4.5): 8 samples per 2H cycles need H = a * b. */
static int has_shift_factors(unsigned half) {
    for (unsigned a = 2; a <= 32; a++) {
        if (half % a == 0 && half / a >= 2 && half / a <= 32) {
            return 1;
        }
    }
    return 0;
}

const char *fw_config_half_problem(unsigned half) {
    if (half < BISS_MIN_HALF) {
        return "faster than the firmware's 10 MHz (BISS_MIN_HALF = 10 PRU cycles)";
    }
    if (half > BISS_MAX_HALF) {
        return "slower than the firmware's 97.7 kHz (BISS_MAX_HALF = 1024 PRU cycles)";
    }
    if (!has_shift_factors(half)) {
        return "no exact 8x shift clock for it (the half period in PRU cycles must be a * b, "
               "2 <= a, b <= 32)";
    }
    return NULL;
}

const char *fw_config_error_text(uint32_t code) {
    /* the meanings of include/biss/biss_shm.h */
    static const char *const text[] = {
        [BISS_CFGERR_NONE] = "BISS_CFGERR_NONE: accepted",
        [BISS_CFGERR_NSLAVES] = "BISS_CFGERR_NSLAVES: 0 or more than 8 slaves",
        [BISS_CFGERR_HALF] = "BISS_CFGERR_HALF: MA half period out of range or no exact 8x "
                             "shift clock for it",
        [BISS_CFGERR_DATA_BITS] = "BISS_CFGERR_DATA_BITS: a slave with 0 or more than 64 data "
                                  "bits",
        [BISS_CFGERR_CRC_BITS] = "BISS_CFGERR_CRC_BITS: a slave with more than 16 CRC bits",
        [BISS_CFGERR_TRIGGER] = "BISS_CFGERR_TRIGGER: unknown trigger mode",
        [BISS_CFGERR_EW] = "BISS_CFGERR_EW: nE/nW position outside the data word",
        [BISS_CFGERR_IEP_PERIOD] = "BISS_CFGERR_IEP_PERIOD: IEP period shorter than a frame can be",
        [BISS_CFGERR_SSI] = "BISS_CFGERR_SSI: SSI needs one slave and no CRC",
    };
    if (code < sizeof text / sizeof text[0] && text[code]) {
        return text[code];
    }
    return "an error code the header does not define";
}
