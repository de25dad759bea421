/* biss_probe.c - encoder discovery on a handle: raw frames through the
 * normal firmware in a capture layout, the wire analysis, and the
 * identification registers.
 *
 * Capture layout: 8 slaves x (64 data bits + 16 CRC bits), no nE/nW: the
 * longest frame the firmware can clock (include/biss/biss_shm.h: 1..64
 * data bits and 0..16 CRC bits per slave, 8 slaves), 640 bits after the
 * CDS. No firmware change is needed. The data bits are published as data
 * words. The CRC bits are not published, but the CRC register after them
 * is (BISS_R_S_CRC_REG, left-aligned): the register over the data word
 * (known) and the 16 received bits. A CRC is linear, so that register is
 * crc(data) advanced over 16 zero bits, XOR crc(0, received); with an odd
 * polynomial of degree 16 the second is a bijection of the received bits
 * (their polynomial times x^16 mod P), so a table inverts it. Each frame
 * then reads "CRC error", which is harmless here (counted, nothing else).
 * Bits after the chain's last CRC read 0 (the last slave's SLI is tied low
 * and passed on, [MB4] "BiSS C Frame"; emulator/slave/biss_slave.h does the
 * same), and the slaves' own timeout only starts once MA stops, so
 * clocking on past the frame is harmless. */
#include "biss_probe_priv.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define DEFAULT_FRAMES 1024
#define SAMPLE_TIMEOUT 100 /* ms per frame (emulator: simulated) */
#define CAPTURE_BITS   BISS_PROBE_CAPTURE_DATA
#define CAPTURE_CRC    BISS_PROBE_CAPTURE_CRC
#define CAPTURE_POLY   0x190D9u /* any odd polynomial of degree 16 */
#define CAPTURE_SLAVE  (CAPTURE_BITS + CAPTURE_CRC)

static void capture_config(uint32_t freq_hz, struct biss_config *c) {
    biss_config_default(c);
    c->freq_hz = freq_hz;
    c->nslaves = BISS_API_MAX_SLAVES;
    for (unsigned i = 0; i < BISS_API_MAX_SLAVES; i++) {
        c->slave[i] = (struct biss_slave_config){
            .data_bits = CAPTURE_BITS, .crc_bits = CAPTURE_CRC, .crc_poly = CAPTURE_POLY};
    }
    c->trigger = BISS_TRIGGER_FREERUN;
}

static uint32_t step16(uint32_t reg, unsigned bit) {
    uint32_t fb = (reg >> 15 & 1u) ^ bit;
    reg = reg << 1 & 0xFFFFu;
    return fb ? reg ^ (CAPTURE_POLY & 0xFFFFu) : reg;
}

/* The capture layout's CRC register (left-aligned, as the firmware
 * publishes it) after a data word and 16 received bits. */
static uint32_t capture_crc(uint64_t data, uint32_t received) {
    uint32_t reg = 0; /* the capture layout's start value */
    for (unsigned k = CAPTURE_BITS; k > 0; k--) {
        reg = step16(reg, (unsigned)(data >> (k - 1) & 1u));
    }
    for (unsigned k = CAPTURE_CRC; k > 0; k--) {
        reg = step16(reg, received >> (k - 1) & 1u);
    }
    return reg << 16; /* left-aligned, as BISS_R_S_CRC_REG */
}

/* inv[crc(0, r)] = r for the 16 received bits r (a bijection, see top). */
static uint16_t *crc_inverse(void) {
    uint16_t *inv = malloc(65536 * sizeof *inv);
    for (uint32_t r = 0; inv && r < 65536; r++) {
        uint32_t reg = 0;
        for (unsigned k = CAPTURE_CRC; k > 0; k--) {
            reg = step16(reg, r >> (k - 1) & 1u);
        }
        inv[reg] = (uint16_t)r;
    }
    return inv;
}

/* The 16 bits received after a data word, from the firmware's register. */
static uint32_t received_crc(const uint16_t *inv, uint64_t data, uint32_t crc_reg) {
    uint32_t from_data = capture_crc(data, 0) >> 16;
    return inv[((crc_reg >> 16) ^ from_data) & 0xFFFFu];
}

/* A sample's bits in wire order: CDS, then per slave its 64-bit word and
 * the 16 bits after it, MSB first. */
static void sample_bits(const uint16_t *inv, const struct biss_sample *s, uint8_t *bits) {
    bits[0] = (uint8_t)(s->cds & 1u);
    for (unsigned i = 0; i < BISS_API_MAX_SLAVES; i++) {
        uint8_t *b = bits + 1 + i * CAPTURE_SLAVE;
        uint64_t d = s->slave[i].data;
        uint32_t r = received_crc(inv, d, s->slave[i].crc_reg);
        for (unsigned k = 0; k < CAPTURE_BITS; k++) {
            b[k] = (uint8_t)(d >> (CAPTURE_BITS - 1 - k) & 1u);
        }
        for (unsigned k = 0; k < CAPTURE_CRC; k++) {
            b[CAPTURE_BITS + k] = (uint8_t)(r >> (CAPTURE_CRC - 1 - k) & 1u);
        }
    }
}

static int capture(biss_t *h, const uint16_t *inv, unsigned n, double deadline_s, uint8_t *bits,
                   uint32_t *fno, struct biss_probe_report *out, unsigned *got) {
    struct biss_sample s;
    uint32_t after = biss_read_sample(h, &s) == BISS_OK ? s.frame : 0;
    unsigned tries = 0;
    *got = 0;
    while (*got < n) {
        if (++tries > 2 * n + 16) {
            break; /* too few valid frames: analyse what came */
        }
        if (probe_now_s() >= deadline_s) {
            out->capture_cut = true;
            break; /* the time limit: analyse what came */
        }
        int rc = biss_wait_sample(h, after, SAMPLE_TIMEOUT, &s);
        if (rc) {
            return rc;
        }
        after = s.frame;
        if (s.training) {
            continue;
        }
        if (!s.valid) {
            out->no_slave += s.no_slave;
            out->invalid += !s.no_slave;
            continue;
        }
        out->busy_max = s.proc_clocks > out->busy_max ? s.proc_clocks : out->busy_max;
        out->delay_ns = s.delay.ns;
        sample_bits(inv, &s, bits + (size_t)*got * BISS_PROBE_MAX_BITS);
        fno[*got] = s.frame;
        (*got)++;
    }
    return BISS_OK;
}

static void note(struct biss_probe_report *out, const char *fmt, unsigned a, unsigned b) {
    if (out->nnotes < sizeof out->notes / sizeof out->notes[0]) {
        snprintf(out->notes[out->nnotes++], sizeof out->notes[0], fmt, a, b);
    }
}

static void read_regs(biss_t *h, unsigned id, struct biss_probe_regs *r) {
    memset(r, 0, sizeof *r);
    r->id = id;
    r->rc_device = biss_reg_read(h, id, 0x78, r->device, sizeof r->device);
    if (r->rc_device == BISS_E_CD_NO_ECHO) { /* nobody with this ID: the rest the same */
        r->rc_manufacturer = r->rc_profile = r->rc_serial = r->rc_device;
        return;
    }
    r->rc_manufacturer = biss_reg_read(h, id, 0x7E, r->manufacturer, sizeof r->manufacturer);
    r->rc_profile = biss_reg_read(h, id, 0x41, r->profile, sizeof r->profile);
    r->rc_serial = biss_reg_read(h, id, 0x44, r->serial, sizeof r->serial);
}

/* The first ID whose registers describe a layout, compared with the wire. */
static void reg_layout(struct biss_probe_report *out) {
    out->reg_verdict = BISS_PROBE_REG_NONE;
    for (unsigned i = 0; i < out->nregs; i++) {
        if (biss_probe_reg_layout_decode(&out->regs[i], &out->reg_layout, out->reg_why,
                                         sizeof out->reg_why)) {
            if (out->reg_layout.nchannels) {
                out->reg_verdict =
                    biss_probe_reg_compare(&out->reg_layout, &out->wire, &out->reg_agree_with,
                                           out->reg_why, sizeof out->reg_why);
            } else {
                out->reg_verdict = BISS_PROBE_REG_INVALID;
            }
            return;
        }
    }
}

/* IDs 0..n-1 for the n slaves the wire shows, and ID n: an answer there
 * means more slaves than the wire layout has. */
static void probe_regs(biss_t *h, const struct biss_probe_params *p,
                       struct biss_probe_report *out) {
    const struct biss_probe_result *w = &out->wire;
    unsigned wire_n = w->nkept && w->verdict != BISS_PROBE_NONE ? w->layout[0].nslaves : 0;
    unsigned n = p->reg_ids ? p->reg_ids : wire_n + 1;
    if (n > BISS_API_MAX_SLAVES) {
        n = BISS_API_MAX_SLAVES;
    }
    unsigned answering = 0;
    for (unsigned id = 0; id < n; id++) {
        read_regs(h, id, &out->regs[out->nregs++]);
        bool answers = out->regs[id].rc_device == BISS_OK;
        answering += answers;
        if (wire_n && id < wire_n && !answers) {
            note(out, "wire slave %u: no register answer for ID %u", id, id);
        }
        if (wire_n && id >= wire_n && answers) {
            note(out, "ID %u answers register reads but the wire shows %u slaves", id, wire_n);
        }
    }
    if (wire_n && answering == wire_n) {
        note(out, "registers: IDs 0..%u answer, as the wire's %u slaves", wire_n - 1, wire_n);
    }
    reg_layout(out);
}

/* Nothing BiSS-like on the line: clock it as an SSI encoder's (slave 0 alone,
 * 64 bits, no CRC) and look at the words. The SSI configuration is left in
 * force. */
static int probe_ssi(biss_t *h, const struct biss_probe_params *p, unsigned n,
                     struct biss_probe_report *out) {
    struct biss_config c;
    biss_config_default(&c);
    c.freq_hz = p->freq_hz;
    c.nslaves = 1;
    c.slave[0] = (struct biss_slave_config){.data_bits = 64, .ssi = true};
    c.ssi_delay_ns = p->ssi_delay_ns ? p->ssi_delay_ns : BISS_PROBE_SSI_DELAY_NS;
    c.trigger = BISS_TRIGGER_FREERUN;
    int rc = biss_configure(h, &c);
    if (rc) {
        return rc;
    }
    uint64_t *w = calloc(n, sizeof *w);
    uint32_t *fno = calloc(n, sizeof *fno);
    unsigned got = 0;
    rc = w && fno ? BISS_OK : BISS_E_NOMEM;
    struct biss_sample s;
    uint32_t after = biss_read_sample(h, &s) == BISS_OK ? s.frame : 0;
    for (unsigned tries = 0; rc == BISS_OK && got < n && tries < 2 * n + 16; tries++) {
        rc = biss_wait_sample(h, after, SAMPLE_TIMEOUT, &s);
        if (rc == BISS_OK) {
            after = s.frame;
            if (s.valid && !s.training) {
                w[got] = s.slave[0].data;
                fno[got++] = s.frame;
            }
        }
    }
    out->ssi.delay_ns = c.ssi_delay_ns;
    if (rc == BISS_OK && got) {
        rc = biss_probe_ssi_analyse(w, fno, got, &out->ssi);
    } else if (rc == BISS_OK) {
        out->ssi.tried = true;
        snprintf(out->ssi.verdict, sizeof out->ssi.verdict,
                 "cannot decide: no valid SSI word in %u tries", 2 * n + 16);
    }
    free(w);
    free(fno);
    return rc;
}

int biss_probe(biss_t *h, const struct biss_probe_params *p, struct biss_probe_report *out) {
    if (!h || !p || !out || p->frames > BISS_PROBE_MAX_FRAMES || p->frames == 1) {
        return BISS_E_INVAL;
    }
    memset(out, 0, sizeof *out);
    /* the time limit holds from here: the analysis gets what the capture left */
    double start = probe_now_s();
    unsigned limit_ms =
        p->limits.time_limit_ms ? p->limits.time_limit_ms : BISS_PROBE_TIME_LIMIT_MS;
    double deadline = start + limit_ms / 1000.0;
    struct biss_config c;
    capture_config(p->freq_hz, &c);
    int rc = biss_configure(h, &c);
    if (rc) {
        return rc;
    }
    unsigned n = p->frames ? p->frames : DEFAULT_FRAMES;
    uint8_t *bits = calloc(n, BISS_PROBE_MAX_BITS);
    uint32_t *fno = calloc(n, sizeof *fno);
    uint16_t *inv = crc_inverse();
    unsigned got = 0;
    rc = bits && fno && inv ? capture(h, inv, n, deadline, bits, fno, out, &got) : BISS_E_NOMEM;
    free(inv);
    if (rc == BISS_OK && got == 0) {
        out->wire.verdict = BISS_PROBE_NONE;
        snprintf(out->wire.reason, sizeof out->wire.reason,
                 "no valid frame in %u tries%s (%u without ACK: no BiSS slave answered; an SSI "
                 "encoder sends none)",
                 out->capture_cut ? out->no_slave + out->invalid : 2 * n + 16,
                 out->capture_cut ? " before the time limit" : "", out->no_slave);
    } else if (rc == BISS_OK) {
        struct biss_probe_frames f = {got, BISS_PROBE_MAX_BITS, bits, fno};
        struct biss_probe_limits lim = p->limits;
        double left_ms = (deadline - probe_now_s()) * 1000.0;
        lim.time_limit_ms = left_ms >= 1.0 ? (unsigned)left_ms : 1u;
        rc = biss_probe_analyse_limited(&f, &lim, &out->wire);
    }
    free(bits);
    free(fno);
    if (rc == BISS_OK && p->read_regs) {
        probe_regs(h, p, out);
    }
    /* nothing BiSS-like: no layout, and no register device answered (an
     * SSI encoder's word can pass for an ACK and a start bit) */
    bool answered = false;
    for (unsigned i = 0; i < out->nregs; i++) {
        answered |= out->regs[i].rc_device == BISS_OK;
    }
    if (rc == BISS_OK && out->wire.verdict == BISS_PROBE_NONE && !answered && !p->no_ssi) {
        rc = probe_ssi(h, p, n, out);
    }
    return rc;
}

/* A scenario biss-sim and bissctl --scenario accept: the generic profile
 * with the slaves the wire showed, every field the analysis found (a life
 * counter at the LSB, nE/nW above it or not; the speed is a choice, so that
 * positions move). */
int biss_probe_to_json(const struct biss_probe_layout *l, char *buf, size_t size) {
    size_t used = 0;
    int n = snprintf(buf, size, "{\n  \"profile\": \"generic\",\n  \"biss\": {\n    \"slaves\": [");
    for (unsigned i = 0; n >= 0 && i < l->nslaves; i++) {
        used += (size_t)n;
        const struct biss_probe_slave *s = &l->slave[i];
        unsigned lc = s->lc_bits;
        unsigned pos = s->data_bits - lc - (s->has_ew ? 2 : 0);
        n = snprintf(buf + used, used < size ? size - used : 0,
                     "%s\n      { \"position_bits\": %u, \"error_bit\": %s, \"warning_bit\": %s, "
                     "\"life_counter_bits\": %u, \"crc_poly\": \"0x%X\", \"crc_start\": \"0x%X\", "
                     "\"speed_cps\": 50000 }",
                     i ? "," : "", pos, s->has_ew ? "true" : "false", s->has_ew ? "true" : "false",
                     lc, s->crc_poly, s->crc_start);
    }
    if (n >= 0) {
        used += (size_t)n;
        n = snprintf(buf + used, used < size ? size - used : 0, "\n    ]\n  }\n}\n");
    }
    if (n < 0 || used + (size_t)n >= size) {
        return BISS_E_INVAL;
    }
    return BISS_OK;
}
