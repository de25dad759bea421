/* biss_config_encode.c - a checked biss_config to the firmware's block and
 * back, and the firmware's verdict as an error code. */
#include "biss_proto.h"

#include <string.h>

_Static_assert(BISS_TRIGGER_HOST == BISS_TRIG_HOST && BISS_TRIGGER_IEP == BISS_TRIG_IEP &&
                   BISS_TRIGGER_FREERUN == BISS_TRIG_FREERUN &&
                   BISS_TRIGGER_IEP_FOLLOW == BISS_TRIG_IEP_FOLLOW,
               "trigger enum matches the shm codes");
_Static_assert(BISS_API_MAX_SLAVES == BISS_MAX_SLAVES, "slave limit matches the shm");

static void encode_slave(const struct biss_slave_config *s, struct biss_shm_slave_cfg *o) {
    o->data_bits = (uint8_t)s->data_bits;
    o->crc_bits = (uint8_t)s->crc_bits;
    o->ew_shift = s->has_ew ? (uint8_t)s->ew_shift : 0;
    o->flags = (uint8_t)((s->has_ew ? BISS_SF_EW : 0) | (s->ssi ? BISS_SF_SSI : 0));
    /* the firmware keeps the polynomial without its top term */
    o->crc_poly = s->crc_bits ? (uint16_t)(s->crc_poly & ((1u << s->crc_bits) - 1u)) : 0;
    o->crc_start = (uint16_t)s->crc_start;
}

/* out->seq is left 0: the caller writes CFG_SEQ last, on its own. */
void biss_config_encode(const struct biss_config *c, struct biss_shm_config *out) {
    unsigned half = 0;
    biss_rate_half(c->freq_hz, &half);
    biss_config_encode_half(c, half, out);
}

void biss_config_encode_half(const struct biss_config *c, unsigned half,
                             struct biss_shm_config *out) {
    memset(out, 0, sizeof *out);
    out->half = (uint16_t)half;
    out->nslaves = (uint8_t)c->nslaves;
    out->trigger = (uint8_t)c->trigger;
    out->iep_period = c->trigger == BISS_TRIGGER_IEP ? c->iep_period_ns / 5 : 0;
    /* the firmware gives up when the busy count reaches the word: the
     * longest accepted + 1 (biss_shm.h), so no u16 value waits forever */
    out->proc_limit = (uint16_t)(c->proc_limit + 1);
    out->ssi_delay_ns = c->slave[0].ssi ? (uint16_t)c->ssi_delay_ns : 0;
    for (unsigned i = 0; i < c->nslaves && i < BISS_MAX_SLAVES; i++) {
        encode_slave(&c->slave[i], &out->slave[i]);
    }
}

/* Reading back a block another process wrote (attach): untrusted, every
 * field is checked before it is used (a junk byte would otherwise become a
 * shift count or a loop bound). The position field is what lies above
 * nE/nW, as pos_bits 0 means. */
static const char *bad_slave(const struct biss_shm_slave_cfg *s, unsigned i) {
    if (s->data_bits < 1 || s->data_bits > BISS_MAX_DATA_BITS) {
        return "slave data bits";
    }
    if (s->crc_bits > BISS_MAX_CRC_BITS) {
        return "slave CRC bits";
    }
    if (s->flags & ~(BISS_SF_EW | BISS_SF_SSI)) {
        return "slave flags";
    }
    if ((s->flags & BISS_SF_EW) && (unsigned)s->ew_shift + 2u > s->data_bits) {
        return "slave nE/nW position";
    }
    if (s->crc_bits < 16 && (s->crc_poly >> s->crc_bits || s->crc_start >> s->crc_bits)) {
        return "slave CRC polynomial or start value";
    }
    if ((s->flags & BISS_SF_SSI) && (i != 0 || s->crc_bits || (s->flags & BISS_SF_EW))) {
        return "slave SSI flag";
    }
    return NULL;
}

static const char *bad_block(const struct biss_shm_config *in) {
    /* one the firmware clocks, at a rate a biss_config names */
    if (biss_proto_half_rate(in->half, NULL) != BISS_OK) {
        return "MA half period";
    }
    if (in->nslaves < 1 || in->nslaves > BISS_MAX_SLAVES) {
        return "slave count";
    }
    if (in->trigger > BISS_TRIG_IEP_FOLLOW) {
        return "trigger mode";
    }
    if ((in->slave[0].flags & BISS_SF_SSI) && in->nslaves != 1) {
        return "slave count (SSI)";
    }
    for (unsigned i = 0; i < in->nslaves; i++) {
        const char *why = bad_slave(&in->slave[i], i);
        if (why) {
            return why;
        }
    }
    return NULL;
}

int biss_config_decode(const struct biss_shm_config *in, struct biss_config *c,
                       const char **field) {
    biss_config_default(c);
    *field = NULL;
    if (in->half == 0) {
        return BISS_E_NOT_CONFIGURED;
    }
    *field = bad_block(in);
    if (*field) {
        return BISS_E_SHM_CONFIG;
    }
    biss_proto_half_rate(in->half, &c->freq_hz);
    c->nslaves = in->nslaves;
    c->trigger = (enum biss_trigger)in->trigger;
    c->iep_period_ns = in->iep_period * 5u;
    c->proc_limit = in->proc_limit ? in->proc_limit - 1u : 0; /* 0 gives up as 1 does */
    c->ssi_delay_ns = in->ssi_delay_ns;
    for (unsigned i = 0; i < c->nslaves; i++) {
        const struct biss_shm_slave_cfg *s = &in->slave[i];
        struct biss_slave_config *o = &c->slave[i];
        o->data_bits = s->data_bits;
        o->crc_bits = s->crc_bits;
        o->crc_poly = s->crc_bits ? (s->crc_poly | (1u << s->crc_bits)) : 0;
        o->crc_start = s->crc_start;
        o->has_ew = (s->flags & BISS_SF_EW) != 0;
        o->ew_shift = o->has_ew ? s->ew_shift : 0;
        o->pos_bits = 0;
        o->ssi = (s->flags & BISS_SF_SSI) != 0; /* Gray or not is not in the block */
    }
    /* the library's own rules too (shift clock, IEP period, SSI delay) */
    if (biss_config_check(c) != BISS_OK) {
        *field = "configuration (fails the library's checks)";
        return BISS_E_SHM_CONFIG;
    }
    return BISS_OK;
}

int biss_fw_cfg_error(uint32_t cfgerr) {
    switch (cfgerr) {
    case BISS_CFGERR_NONE:
        return BISS_OK;
    case BISS_CFGERR_NSLAVES:
        return BISS_E_FW_NSLAVES;
    case BISS_CFGERR_HALF:
        return BISS_E_FW_HALF;
    case BISS_CFGERR_DATA_BITS:
        return BISS_E_FW_DATA_BITS;
    case BISS_CFGERR_CRC_BITS:
        return BISS_E_FW_CRC_BITS;
    case BISS_CFGERR_TRIGGER:
        return BISS_E_FW_TRIGGER;
    case BISS_CFGERR_EW:
        return BISS_E_FW_EW;
    case BISS_CFGERR_IEP_PERIOD:
        return BISS_E_FW_IEP_PERIOD;
    case BISS_CFGERR_SSI:
        return BISS_E_FW_SSI;
    default:
        return BISS_E_FW_UNKNOWN;
    }
}
