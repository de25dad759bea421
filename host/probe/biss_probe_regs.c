/* biss_probe_regs.c - the layout an encoder describes in its own registers,
 * and how it compares with the wire's (no I/O).
 *
 * In the BiSS register map 0x78..0x7D is the device ID, a name, not a
 * layout ([POS] §8.1.1; [TI] Table 11 reads "F:" 46 3A C0 0C 00 01 there).
 * The Hengstler AD38 notes give the same addresses a meaning ([AD38]
 * register table of the Slave ID 1 device, "Address / Content": 0x78 "Data
 * length ADC", 0x79 "Length CRC ADC", 0x7A "Resolution MT", 0x7B
 * "Resolution ST", 0x7C "Length Life counter", 0x7D "Length CRC Position",
 * 0x7E..0x7F "Manufacturer ID (HE = Hengstler)"). So the manufacturer ID
 * picks the format; for any other the bytes stay a name. The notes name the
 * registers without printing values; read as bit counts (the only reading
 * their names allow), the notes' SCD tables give 16, 5, 12, 24, 6, 6. */
#include "biss_probe_priv.h"

#include <stdio.h>
#include <string.h>

#define AD38_FORMAT "Hengstler AD38 notes (0x78..0x7D: A/D, CRC, MT, ST, LC, CRC lengths)"
#define EW_BITS     2 /* [AD38] SCD tables: "Err + Warning 2 bit" per channel */

static bool is_hengstler(const struct biss_probe_regs *r) {
    return r->rc_device == BISS_OK && r->rc_manufacturer == BISS_OK && r->manufacturer[0] == 'H' &&
           r->manufacturer[1] == 'E';
}

static bool crc_ok(unsigned c) {
    return c >= BISS_PROBE_MIN_CRC && c <= BISS_PROBE_MAX_CRC;
}

bool biss_probe_reg_layout_decode(const struct biss_probe_regs *regs,
                                  struct biss_probe_reg_layout *out, char *why, size_t why_size) {
    memset(out, 0, sizeof *out);
    if (why_size) {
        why[0] = '\0';
    }
    if (!is_hengstler(regs)) {
        return false;
    }
    const uint8_t *d = regs->device;
    out->id = regs->id;
    out->format = AD38_FORMAT;
    memcpy(out->raw, d, sizeof out->raw);
    unsigned adc = d[0], adc_crc = d[1], pos_crc = d[5];
    out->mt_bits = d[2];
    out->st_bits = d[3];
    out->lc_bits = d[4];
    unsigned pos = out->mt_bits + out->st_bits;
    /* 0xFF is "not used" in the notes' other device; 0 A/D bits: the
     * single-channel AD38 ([AD38] "1 Slave" drawing: MT + ST only) */
    const char *bad = adc > 64 - EW_BITS               ? "0x78 A/D data length"
                      : adc && !crc_ok(adc_crc)        ? "0x79 A/D CRC length"
                      : pos == 0 || pos > 64 - EW_BITS ? "0x7A + 0x7B MT + ST resolution"
                      : !crc_ok(pos_crc)               ? "0x7D position CRC length"
                      : out->lc_bits > 32              ? "0x7C life-counter length"
                                                       : NULL;
    if (bad) {
        snprintf(why, why_size,
                 "ID %u (\"HE\"): %s out of range (0x78..0x7D = %02X %02X %02X %02X %02X %02X): "
                 "no frame has it",
                 regs->id, bad, d[0], d[1], d[2], d[3], d[4], d[5]);
        return true;
    }
    if (adc) {
        out->ch[out->nchannels++] =
            (struct biss_probe_reg_channel){"A/D", adc, adc + EW_BITS, adc_crc};
    }
    out->ch[out->nchannels++] =
        (struct biss_probe_reg_channel){"MT+ST position", pos, pos + EW_BITS, pos_crc};
    return true;
}

/* Whether layout l has the described widths; if not, the first
 * difference in words. */
static bool matches(const struct biss_probe_reg_layout *rl, const struct biss_probe_layout *l,
                    char *why, size_t why_size) {
    if (l->nslaves < rl->nchannels) {
        snprintf(why, why_size, "registers describe %u channels, the wire shows %u slaves",
                 rl->nchannels, l->nslaves);
        return false;
    }
    for (unsigned i = 0; i < rl->nchannels; i++) {
        const struct biss_probe_reg_channel *c = &rl->ch[i];
        const struct biss_probe_slave *s = &l->slave[i];
        if (c->data_bits != s->data_bits || c->crc_bits != s->crc_bits) {
            snprintf(why, why_size,
                     "slave %u: registers %s %u + nE/nW = %u data bits, CRC %u; wire %u data "
                     "bits, CRC %u",
                     i, c->what, c->value_bits, c->data_bits, c->crc_bits, s->data_bits,
                     s->crc_bits);
            return false;
        }
        if (!s->has_ew || s->ew_shift != 0) {
            snprintf(why, why_size,
                     "slave %u: registers put nE/nW right after the %s value; the wire %s", i,
                     c->what, s->has_ew ? "has them above a life counter" : "shows none");
            return false;
        }
    }
    if (rl->lc_bits) {
        /* the counter's channel is not among the described ones ([AD38]:
         * the 9-bit ST + LC channel, another device): any slave may hold it */
        unsigned seen = 0;
        for (unsigned i = 0; i < l->nslaves; i++) {
            seen = l->slave[i].lc_bits > seen ? l->slave[i].lc_bits : seen;
            if (l->slave[i].lc_bits == rl->lc_bits) {
                return true;
            }
        }
        snprintf(why, why_size,
                 "registers: a %u-bit life counter (0x7C); the wire's widest counter: %u bits",
                 rl->lc_bits, seen);
        return false;
    }
    return true;
}

enum biss_probe_reg_verdict biss_probe_reg_compare(const struct biss_probe_reg_layout *rl,
                                                   const struct biss_probe_result *wire,
                                                   unsigned *agree_with, char *why,
                                                   size_t why_size) {
    *agree_with = 0;
    if (why_size) {
        why[0] = '\0';
    }
    if (rl->nchannels == 0) {
        return BISS_PROBE_REG_INVALID;
    }
    if (wire->verdict == BISS_PROBE_NONE || wire->nkept == 0) {
        snprintf(why, why_size, "the wire gave no layout to compare with (%s)", wire->reason);
        return BISS_PROBE_REG_NO_WIRE;
    }
    char first[160] = "";
    for (unsigned k = 0; k < wire->nkept; k++) {
        char w[160];
        if (matches(rl, &wire->layout[k], w, sizeof w)) {
            *agree_with = k + 1;
            if (k == 0) {
                snprintf(why, why_size, "the wire's first candidate has the described widths");
                return BISS_PROBE_REG_AGREE;
            }
            snprintf(why, why_size, "candidate %u has the described widths; candidate 1: %s", k + 1,
                     first);
            return BISS_PROBE_REG_AGREE_K;
        }
        if (k == 0) {
            snprintf(first, sizeof first, "%s", w);
        }
    }
    snprintf(why, why_size, "%s", first);
    return BISS_PROBE_REG_DISAGREE;
}

const char *biss_probe_reg_verdict_name(enum biss_probe_reg_verdict v) {
    switch (v) {
    case BISS_PROBE_REG_NONE:
        return "no layout in the registers";
    case BISS_PROBE_REG_INVALID:
        return "registers invalid";
    case BISS_PROBE_REG_NO_WIRE:
        return "registers only";
    case BISS_PROBE_REG_AGREE:
        return "registers agree with the wire";
    case BISS_PROBE_REG_AGREE_K:
        return "registers agree with a later wire candidate";
    case BISS_PROBE_REG_DISAGREE:
        return "registers disagree with the wire";
    }
    return "?";
}
