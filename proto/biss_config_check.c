/* biss_config_check.c - validation of a configuration before the firmware
 * sees it: every field, each with its own error code. */
#include "biss_proto.h"

#include "biss/biss_rules.h"

void biss_config_default(struct biss_config *c) {
    if (!c) {
        return;
    }
    *c = (struct biss_config){
        .freq_hz = 1000000,
        .nslaves = 0,
        .trigger = BISS_TRIGGER_FREERUN,
        .iep_period_ns = 0,
        .proc_limit = 1000,
    };
}

/* Degree of a polynomial written with its top term: index of the top bit. */
static int poly_degree(uint32_t poly) {
    int d = -1;
    while (poly) {
        poly >>= 1;
        d++;
    }
    return d;
}

static int check_crc(const struct biss_slave_config *s) {
    if (s->crc_bits > BISS_MAX_CRC_BITS) {
        return BISS_E_CRC_BITS;
    }
    if (s->crc_bits == 0) {
        return s->crc_poly == 0 && s->crc_start == 0 ? BISS_OK
               : s->crc_poly != 0                    ? BISS_E_CRC_POLY
                                                     : BISS_E_CRC_START;
    }
    if (!biss_crc_poly_valid(s->crc_poly) || poly_degree(s->crc_poly) != (int)s->crc_bits) {
        return BISS_E_CRC_POLY;
    }
    if (s->crc_start >> s->crc_bits) {
        return BISS_E_CRC_START;
    }
    return BISS_OK;
}

static int check_slave(const struct biss_slave_config *s) {
    if (s->data_bits < 1 || s->data_bits > BISS_MAX_DATA_BITS) {
        return BISS_E_DATA_BITS;
    }
    int rc = check_crc(s);
    if (rc) {
        return rc;
    }
    unsigned low = 0; /* bits below the position field */
    if (s->has_ew) {
        /* nW at ew_shift and nE at ew_shift + 1 must both be data bits */
        if (s->ew_shift + 2 > s->data_bits) {
            return BISS_E_EW;
        }
        low = s->ew_shift + 2;
    }
    if (s->pos_bits > s->data_bits - low) {
        return BISS_E_POS_BITS;
    }
    return BISS_OK;
}

/* SSI is slave[0] alone: no ACK, start bit, CDS or CRC on its wire, and
 * nE/nW are not the firmware's business there. */
static int check_ssi(const struct biss_config *c) {
    for (unsigned i = 1; i < c->nslaves; i++) {
        if (c->slave[i].ssi || c->slave[i].gray) {
            return BISS_E_SSI;
        }
    }
    const struct biss_slave_config *s = &c->slave[0];
    if (!s->ssi) {
        return s->gray ? BISS_E_SSI : BISS_OK;
    }
    if (c->nslaves != 1 || s->crc_bits || s->crc_poly || s->has_ew || c->ssi_delay_ns > 0xffff) {
        return BISS_E_SSI;
    }
    return BISS_OK;
}

/* The firmware's own rule: an IEP period (counts of 5 ns = PRU cycles) of
 * at least 2H (N + 8), N = all data and CRC bits of the chain. */
static int check_iep(const struct biss_config *c, unsigned half) {
    if (c->iep_period_ns % 5 != 0) {
        return BISS_E_IEP_PERIOD;
    }
    uint64_t bits = 0;
    for (unsigned i = 0; i < c->nslaves; i++) {
        bits += c->slave[i].data_bits + c->slave[i].crc_bits;
    }
    uint64_t min_counts = 2ull * half * (bits + 8);
    if (c->iep_period_ns / 5 < min_counts) {
        return BISS_E_IEP_PERIOD;
    }
    return BISS_OK;
}

int biss_config_check(const struct biss_config *c) {
    if (!c) {
        return BISS_E_INVAL;
    }
    unsigned half;
    int rc = biss_rate_half(c->freq_hz, &half);
    if (rc) {
        return rc;
    }
    if (c->nslaves < 1 || c->nslaves > BISS_MAX_SLAVES) {
        return BISS_E_NSLAVES;
    }
    if (c->trigger != BISS_TRIGGER_HOST && c->trigger != BISS_TRIGGER_IEP &&
        c->trigger != BISS_TRIGGER_FREERUN && c->trigger != BISS_TRIGGER_IEP_FOLLOW) {
        return BISS_E_TRIGGER;
    }
    if (c->proc_limit > BISS_MAX_PROC_LIMIT) {
        return BISS_E_PROC_LIMIT;
    }
    rc = check_ssi(c);
    if (rc) {
        return rc;
    }
    for (unsigned i = 0; i < c->nslaves; i++) {
        rc = check_slave(&c->slave[i]);
        if (rc) {
            return rc;
        }
    }
    if (c->trigger == BISS_TRIGGER_IEP) {
        rc = check_iep(c, half);
        if (rc) {
            return rc;
        }
    }
    return biss_safety_config_check(c);
}
