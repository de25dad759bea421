/* Named encoder profiles. Values come from the reference documents (named
 * per profile); where a document leaves a value open the choice is marked
 * "model choice" and listed in MODELS.md. */
#include "scenario.h"

#include <stdio.h>
#include <string.h>

#define NS SIM_PS_PER_NS
#define US SIM_PS_PER_US

static void base(scenario *s, const char *name) {
    memset(s, 0, sizeof *s);
    snprintf(s->profile, sizeof s->profile, "%s", name);
    /* every model in the table from its defaults, BiSS-C chosen */
    const slave_model *m;
    for (size_t i = 0; (m = slave_model_at(i)); i++) {
        if (m->cfg_offset != offsetof(scenario, ext)) {
            m->cfg_default((char *)s + m->cfg_offset);
        }
    }
    s->model = &slave_model_biss;
    line_params_default(&s->ma_line);
    line_params_default(&s->sl_line);
    scenario_set_cable(s, 2.0); /* TIDEP0022 Table 10's shortest setup */
    s->seed = 1;
}

static void poke_ro(biss_slave_cfg *c, uint8_t addr, uint8_t value) {
    regfile_poke(&c->regs, 0, addr, value);
    c->regs.flags[addr] |= REG_RO;
}

/* TIDEP0022: 12-bit single-turn test encoder, nE nW, CRC6 0x43; register
 * values read back in the design guide's Table 11 (0x60 is written to send
 * commands, Table 7, so it stays writable). */
static void tidep0022(scenario *s) {
    base(s, "tidep0022-test-encoder");
    biss_slave_cfg *c = &s->biss.s[0];
    c->pos_bits = 12;
    c->speed_cps = 50000.0; /* model choice: a new value every 20 us */
    static const struct {
        uint8_t addr, value;
    } t11[] = {{0x44, 0x00}, {0x45, 0xD9}, {0x46, 0x01}, {0x47, 0x32}, {0x67, 0x5F},
               {0x68, 0x00}, {0x78, 0x46}, {0x79, 0x3A}, {0x7A, 0xC0}, {0x7B, 0x0C},
               {0x7C, 0x00}, {0x7D, 0x01}, {0x7E, 0x57}, {0x7F, 0x41}};
    for (size_t i = 0; i < sizeof t11 / sizeof t11[0]; i++) {
        poke_ro(c, t11[i].addr, t11[i].value);
    }
    regfile_poke(&c->regs, 0, 0x60, 0x0B);
}

/* The POSITAL IXARC kit's SCD layout (MT24 + ST17 + 7 fill + E + W + CRC6
 * 0x43, start 0, inverted) and registers (direct registers of the manual's
 * appendix 8.1.1, 68 banks) on a BiSS-C line. The kit itself is a BiSS
 * Line encoder ([POS] §3.1: half-duplex, 8b10b, 12.5 Mbit/s, no MA clock),
 * which this master cannot talk to: hence the name. */
static void posital(scenario *s) {
    base(s, "posital-kit-layout-biss-c");
    biss_slave_cfg *c = &s->biss.s[0];
    c->pos_bits = 41;
    c->fill_bits = 7;
    c->speed_cps = 1e6; /* model choice */
    regfile_init(&c->regs, 68);
    static const struct {
        uint8_t addr, value;
    } direct[] = {{0x41, 0x02},
                  {0x42, 0x61},
                  {0x43, 0x29},
                  /* serial number and live values: "-" in the manual, model choice */
                  {0x44, 0x12},
                  {0x45, 0x34},
                  {0x46, 0x56},
                  {0x47, 0x78},
                  {0x66, 0x2A},
                  {0x68, 0x00},
                  {0x69, 0x00},
                  {0x6E, 0x03},
                  {0x74, 0x01},
                  {0x75, 0x00},
                  {0x76, 0x00},
                  /* device ID and manufacturer: manual defaults */
                  {0x78, 0x01},
                  {0x79, 0x01},
                  {0x7A, 0x68},
                  {0x7B, 0x11},
                  {0x7C, 0x00},
                  {0x7D, 0x01},
                  {0x7E, 0x46},
                  {0x7F, 0x72}};
    for (size_t i = 0; i < sizeof direct / sizeof direct[0]; i++) {
        poke_ro(c, direct[i].addr, direct[i].value);
    }
    /* R/W direct registers: bank select, device mode, protection */
    regfile_poke(&c->regs, 0, 0x6A, 0x00);
    regfile_poke(&c->regs, 0, 0x6B, 0x00);
    /* banks: 0 special functions, 1 reserved, 2-3 EDS, 4-67 user data; their
     * contents are not in the manual and start as zeros */
}

/* The AD38's direct registers ([AD38] register tables, "Address /
 * Content"). ID 1 (the A/D and position channels) describes its format at
 * 0x78..0x7D: "Data length ADC", "Length CRC ADC", "Resolution MT",
 * "Resolution ST", "Length Life counter", "Length CRC Position"; 0x7E..0x7F
 * "Manufacturer ID (HE = Hengstler)". The notes print no values: model
 * choice, each a bit count (what the names say) with the widths the
 * notes' SCD tables give: A/D 16, CRC 5, MT 12, ST 24, life counter 6
 * (SCD-Slave 3), CRC 6. ID 0 (the life-counter channel): 0x41..0x5F and
 * 0x78..0x7F "0xFF (not used)". All read-only (identification). */
static void ad38_registers(regfile *id1, regfile *id0) {
    static const uint8_t id1_78[8] = {16, 5, 12, 24, 6, 6, 'H', 'E'};
    for (unsigned i = 0; i < 8; i++) {
        regfile_poke(id1, 0, (uint8_t)(0x78 + i), id1_78[i]);
        id1->flags[0x78 + i] |= REG_RO;
    }
    for (unsigned a = 0x41; a <= 0x7F; a++) {
        if (a <= 0x5F || a >= 0x78) {
            regfile_poke(id0, 0, (uint8_t)a, 0xFF);
            id0->flags[a] |= REG_RO;
        }
    }
}

/* Hengstler AD38 3-slave chain (application notes): A/D converter,
 * MT+ST position, ST + life counter; busy about 2.3-2.5 us, adaptive
 * timeout 650 ns. */
static void ad38(scenario *s) {
    base(s, "hengstler-ad38");
    biss_chain_cfg *b = &s->biss;
    b->n = 3;
    b->busy_ps = 2400 * NS;
    b->timeout_mode = BISS_TIMEOUT_ADAPTIVE;
    b->adaptive_factor = 1.5;
    b->adaptive_min_ps = 650 * NS;
    b->adaptive_max_ps = 20 * US;
    b->s[0].pos_bits = 16; /* PT1000 A/D value */
    b->s[0].crc_poly = 0x25;
    b->s[0].pos0 = 0x4000;
    b->s[0].speed_cps = 1000.0; /* model choice: slowly drifting reading */
    b->s[1].pos_bits = 36;      /* MT 12 + ST 24 ([AD38] SCD-Slave 2 table) */
    b->s[1].crc_poly = 0x43;
    b->s[1].speed_cps = 1e6;
    b->s[2].pos_bits = 9;
    b->s[2].lc_bits = 6;
    b->s[2].crc_poly = 0x190D9;
    b->s[2].speed_cps = 20000.0;
    /* Two register devices, not three ([AD38] register tables, "Slave ID"
     * column; error table "SCD Slave2 -> Slave-ID 1 0x69", "SCD Slave3 ->
     * Slave-ID 0 0x70..0x72"; temperature 0x67 at Slave ID 0 only): the
     * channel with the life counter is ID 0, the A/D and position channels
     * belong to the ID 1 device, whose registers chain slave 1 holds. */
    b->s[0].id = 1;
    b->s[0].no_control = true;
    b->s[1].id = 1;
    b->s[2].id = 0;
    ad38_registers(&b->s[1].regs, &b->s[2].regs);
}

/* A BiSS Safety style encoder: two position words from two daisy-chained
 * sensors, the control position word (CPW, slave 0) and the safety
 * position word (SPW, slave 1), each with nE/nW, a sign-of-life counter
 * and its own CRC (biss-interface.com, "BiSS Safety", System and Data
 * Channels; iC-Haus "BiSS Safety Concept" A3: one or two BiSS slaves).
 * Both CRCs are the 16-bit 0x190D9, told apart by their start values as
 * the iC-MB4 datasheet describes ("CRC start value", Table 16: start
 * values "to safely differentiate between single-cycle data words e.g.
 * two position words provided by two different sensors"). Resolutions,
 * counter width, start value 0x5A5A and speed: model choices (MODELS.md). */
static void biss_safety(scenario *s) {
    base(s, "biss-safety-two-channel");
    biss_chain_cfg *b = &s->biss;
    b->n = 2;
    b->s[0].pos_bits = 24; /* CPW: the fine sensor */
    b->s[0].lc_bits = 6;
    b->s[0].crc_poly = 0x190D9;
    b->s[0].crc_start = 0x0000;    /* [MB4]: "a typical default slave CRC start value" */
    b->s[0].speed_cps = 1048576.0; /* 2^20 counts/s: 1/16 turn per second */
    b->s[1].pos_bits = 20;         /* SPW: a coarser second sensor on the same shaft */
    b->s[1].lc_bits = 6;
    b->s[1].crc_poly = 0x190D9;
    b->s[1].crc_start = 0x5A5A;
    b->s[1].speed_cps = 65536.0; /* the same motion at 1/16 the resolution */
}

static void generic(scenario *s) {
    base(s, "generic");
    s->biss.s[0].speed_cps = 50000.0;
}

static void ssi(scenario *s) {
    base(s, "ssi");
    s->model = &slave_model_ssi;
    s->ssi.bits = 13;
    s->ssi.speed_cps = 50000.0;
}

static const struct {
    const char *name;
    void (*fill)(scenario *);
} table[] = {
    {"tidep0022-test-encoder", tidep0022},
    {"posital-kit-layout-biss-c", posital},
    {"hengstler-ad38", ad38},
    {"biss-safety-two-channel", biss_safety},
    {"generic", generic},
    {"ssi", ssi},
};

#define NPROFILES (sizeof table / sizeof table[0])

int profile_by_name(const char *name, scenario *s) {
    for (size_t i = 0; i < NPROFILES; i++) {
        if (strcmp(name, table[i].name) == 0) {
            table[i].fill(s);
            return 0;
        }
    }
    return -1;
}

const char *profile_name_at(size_t i) {
    return i < NPROFILES ? table[i].name : NULL;
}

void scenario_set_cable(scenario *s, double length_m) {
    s->ma_line.length_m = length_m;
    s->sl_line.length_m = length_m;
}
