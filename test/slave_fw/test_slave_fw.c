/*
 * The encoder firmware (pru_slave/) on PRU1 of an emulated PRU-ICSS,
 * driven by MA waveforms as masters make them, against the C slave model
 * (emulator/slave/biss_slave.h) on the same waveform: SL bit by bit
 * (the ACK, the busy bits, start, CDS, data, CRC, the tail), the frame's
 * words, the timeout, control communication (the CDS of every frame, the
 * register files, the command counters); and, from the documents directly,
 * the register reads of TIDEP0022's Table 7 and 11, the response time, the
 * highest rate and the configuration's refusals.
 */
#include "check_run.h"
#include "slave_fw_rig.h"

#include "fw_check.h"

#include "scenario.h"

#include <check.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define US SIM_PS_PER_US
#define NS SIM_PS_PER_NS

/* The firmware's private data fits its areas: pru_slave/layout.hp's
 * structures, whose sizes its .assign lines hold at assembly (SlvPriv 40
 * bytes, SlvRun 48 and SlvCtl 8 per slave; P_SHADOW: CtrlState 16 and a
 * word). */
_Static_assert(40 + BISS_SLV_MAX_SLAVES * (48 + 8) <= BISS_SLV_PRIV_END - BISS_SLV_PRIV,
               "pru_slave/layout.hp: P_END past BISS_SLV_PRIV_END");
_Static_assert(16 + 4 <= BISS_SLV_PRIV2_END - BISS_SLV_PRIV2,
               "pru_slave/layout.hp: P_END2 past BISS_SLV_PRIV2_END");

/* A profile with its motion per frame (the firmware's kind of motion). */
/* A profile with its motion per frame (the firmware's kind of motion) and
 * at most 16 register banks over the chain (its pool). */
static biss_chain_cfg chain_of(const char *profile) {
    scenario sc;
    ck_assert_int_eq(profile_by_name(profile, &sc), 0);
    for (unsigned i = 0; i < sc.biss.n; i++) {
        sc.biss.s[i].speed_cps = 0;
        sc.biss.s[i].counts_per_frame = 3 + 1000 * (int64_t)i;
        if (sc.biss.s[i].regs.nbanks > 4) {
            sc.biss.s[i].regs.nbanks = 4;
        }
    }
    return sc.biss;
}

/* The same SL as the model's; and, unless the script has partial frames,
 * the work after every timeout's end within its allowance (else a timeout
 * would end late). */
static void expect_same(struct rig *r) {
    char what[200];
    unsigned d = rig_compare(r, what, sizeof what);
    ck_assert_msg(d == 0, "%u differences; first: %s", d, what);
    struct biss_slv_status st = rig_status(r);
    ck_assert_msg(r->partial_frames || st.work <= st.work_pad,
                  "the work after a timeout took %u cycles, over %u", st.work, st.work_pad);
}

/* The frame's words: what the firmware said it would send (FRAME_REC,
 * left-aligned) against what the model sent (its record), slave by slave. */
static void expect_words(struct rig *r) {
    for (unsigned k = 0; k < r->nframes; k++) {
        const biss_frame_record *m = rig_model_record(r, k);
        ck_assert_ptr_nonnull(m);
        ck_assert_uint_eq(r->frames[k].rec.frame, k + 1);
        if (!m->latch_ps) {
            continue;
        }
        for (unsigned i = 0; i < r->chain.n; i++) {
            unsigned n = biss_slave_cfg_data_bits(&r->chain.s[i]);
            struct biss_proto_word w = bench_fw_word(&r->chain.s[i]);
            uint64_t want = biss_proto_word_compose(&w, m->s[i].position, m->s[i].nE > 0,
                                                    m->s[i].nW > 0, m->s[i].lc);
            uint64_t got = r->frames[k].rec.word[i] >> (64 - n);
            ck_assert_msg(got == want, "frame %u slave %u: word %llx, the model sent %llx", k, i,
                          (unsigned long long)got, (unsigned long long)want);
        }
    }
}

/* Pseudo-random bits, the same every run. */
static uint32_t rnd_state = 12345;
static unsigned rnd(unsigned n) {
    rnd_state = rnd_state * 1103515245u + 12345u;
    return (rnd_state >> 8) % n;
}

/* ---- frames, SL bit by bit ---------------------------------------------- */

/* Every profile, every rate the master has (10, 5, 2, 1 MHz), whole frames
 * with a random CDM after each. */
static void profile_at(const char *profile, unsigned half, unsigned frames) {
    biss_chain_cfg c = chain_of(profile);
    struct rig r;
    rig_open(&r, &c, NULL);
    unsigned bits = 2 + (unsigned)(c.busy_ps / ((sim_ps)half * 10 * NS)) + 3;
    for (unsigned i = 0; i < c.n; i++) {
        bits += biss_slave_cfg_bits(&c.s[i]);
    }
    for (unsigned k = 0; k < frames; k++) {
        rig_add(&r, half, bits + 2, (int)rnd(2), 40 * US);
    }
    rig_run(&r);
    expect_same(&r);
    expect_words(&r);
    rig_close(&r);
}

START_TEST(profiles_at_master_rates) {
    static const char *const profiles[] = {"tidep0022-test-encoder", "posital-kit-layout-biss-c",
                                           "hengstler-ad38", "biss-safety-two-channel", "generic"};
    static const unsigned halves[] = {10, 20, 50, 100};
    profile_at(profiles[_i / 4], halves[_i % 4], 12);
}
END_TEST

/* The longest chain: 8 slaves, CRCs of every width class, start values,
 * fill, life counters, data words up to 64 bits, one without a CRC. */
static biss_chain_cfg chain8(void) {
    biss_chain_cfg c;
    biss_chain_cfg_default(&c);
    c.n = 8;
    static const struct {
        unsigned pos, fill, lc;
        uint32_t poly, start;
        bool e, w;
    } s[8] = {{12, 0, 0, 0x43, 0, true, true},           {64, 0, 0, 0x190d9, 0x5a5a, false, false},
              {1, 0, 0, 0x3, 1, false, false},           {24, 7, 6, 0x25, 0x11, true, true},
              {17, 1, 32, 0x190d9, 0xffff, true, false}, {30, 0, 0, 0, 0, true, true},
              {33, 2, 3, 0x12f, 0x80, false, true},      {9, 0, 5, 0x89, 0x7f, true, true}};
    for (unsigned i = 0; i < 8; i++) {
        biss_slave_cfg_default(&c.s[i], (uint8_t)i);
        c.s[i].pos_bits = s[i].pos;
        c.s[i].fill_bits = s[i].fill;
        c.s[i].lc_bits = s[i].lc;
        c.s[i].crc_poly = s[i].poly;
        c.s[i].crc_start = s[i].start;
        c.s[i].has_err = s[i].e;
        c.s[i].has_warn = s[i].w;
        c.s[i].pos0 = 0x0123456789abcdefull * (i + 1);
        c.s[i].speed_cps = 0;
        c.s[i].counts_per_frame = (int64_t)(0x0001111111111111ull * (i + 1)) - 5;
    }
    {
        char err[160];
        ck_assert_msg(biss_chain_cfg_check(&c, err, sizeof err) == 0, "%s", err);
    }
    return c;
}

START_TEST(eight_slave_chain) {
    biss_chain_cfg c = chain8();
    struct rig r;
    rig_open(&r, &c, NULL);
    rig_add_n(&r, 16, 10, 400, NULL, 40 * US);
    rig_run(&r);
    expect_same(&r);
    expect_words(&r);
    rig_close(&r);
}
END_TEST

/* Frames a master cuts short or clocks on: none, one, two (the master's
 * training frame, iC-MB4's INIT), a few clocks, into the data, past it;
 * with CDM 0 and 1. The model decides what latches, advances and answers. */
START_TEST(partial_and_long_frames) {
    biss_chain_cfg c = chain_of("hengstler-ad38");
    c.busy_ps = 0;
    struct rig r;
    rig_open(&r, &c, NULL);
    r.partial_frames = true;
    static const unsigned clocks[] = {0, 1, 2, 3, 4, 5, 9, 30, 80, 129, 130, 131, 200};
    for (unsigned k = 0; k < 2 * sizeof clocks / sizeof clocks[0]; k++) {
        rig_add(&r, 10, clocks[k / 2], (int)(k % 2), 40 * US);
    }
    rig_add_n(&r, 40, 10, 1 + rnd(160), NULL, 40 * US);
    rig_run(&r);
    expect_same(&r);
    rig_close(&r);
}
END_TEST

/* Processing time: busy clocks, busy time off the clock grid, both. */
START_TEST(processing_time) {
    static const struct {
        unsigned clocks;
        sim_ps ns;
        unsigned half;
    } t[] = {{3, 0, 10}, {0, 2430, 10}, {0, 2430, 50}, {5, 1270, 10}, {40, 0, 20}, {1, 330, 100}};
    for (unsigned i = 0; i < sizeof t / sizeof t[0]; i++) {
        biss_chain_cfg c = chain_of("tidep0022-test-encoder");
        c.busy_clocks = t[i].clocks;
        c.busy_ps = t[i].ns * NS;
        struct rig r;
        rig_open(&r, &c, NULL);
        rig_add_n(&r, 6, t[i].half, 90, NULL, 40 * US);
        rig_run(&r);
        expect_same(&r);
        rig_close(&r);
    }
}
END_TEST

/* ---- the highest rate and the response time -------------------------------- */

/* The highest MA rate the firmware answers right: H = 9, 11.1 MHz (its
 * longest block, SWITCH, and the polls fit 18 cycles); at H = 8 it falls
 * behind. A master of this project runs H >= 10. */
START_TEST(highest_rate) {
    biss_chain_cfg c = chain_of("hengstler-ad38");
    c.busy_ps = 0;
    for (unsigned half = 9; half >= 8; half--) {
        struct rig r;
        rig_open(&r, &c, NULL);
        rig_add_n(&r, 6, half, 140, NULL, 40 * US);
        rig_run(&r);
        char what[200];
        unsigned d = rig_compare(&r, what, sizeof what);
        if (half == 9) {
            ck_assert_msg(d == 0, "H = 9: %u differences; first: %s", d, what);
        } else {
            ck_assert_msg(d > 0, "H = 8 answers right: the stated highest rate is too low");
        }
        rig_close(&r);
    }
}
END_TEST

/* The response time, MA edge at the slave's pin to SL change at it:
 * the input synchronizer (gpi_delay_ps), up to 2 cycles of the poll, and
 * the one instruction that writes R30. With the emulator's default (2
 * cycles) 20..25 ns, i.e. 4..5 cycles; each cycle of synchronizer adds one.
 * Across the plausible synchronizer (2..4 cycles) and CYCLE read (4..6
 * cycles) the frames stay right at 10 MHz. */
START_TEST(response_time_and_margins) {
    biss_chain_cfg c = chain_of("hengstler-ad38");
    c.busy_ps = 2430 * NS;
    for (unsigned sync = 2; sync <= 4; sync++) {
        for (unsigned ctrl = 4; ctrl <= 6; ctrl++) {
            struct pru_params pp;
            pru_params_default(&pp);
            pp.gpi_delay_ps = sync * SIM_PS_PER_PRU_CYCLE;
            pp.load_ctrl_cycles = ctrl;
            struct rig r;
            rig_open(&r, &c, &pp);
            rig_add_n(&r, 6, 10, 160, NULL, 40 * US);
            rig_run(&r);
            expect_same(&r);
            sim_ps lo, hi;
            unsigned n;
            rig_latency(&r, &lo, &hi, &n);
            ck_assert_uint_gt(n, 100);
            ck_assert_int_eq(lo, (sim_ps)(sync + 2) * SIM_PS_PER_PRU_CYCLE);
            ck_assert_int_eq(hi, (sim_ps)(sync + 3) * SIM_PS_PER_PRU_CYCLE);
            rig_close(&r);
        }
    }
}
END_TEST

/* Off the cycle grid (a cable's delay puts MA's edges anywhere): an edge
 * p ps past a cycle boundary is first seen by the sample at the next
 * boundary but one (the synchronizer's), 5000 - p ps more than an edge on
 * it; so the response time is 20..30 ns, 4..6 cycles, with the default
 * synchronizer. */
START_TEST(response_time_off_grid) {
    static const sim_ps phase[] = {1, 1000, 2500, 4055, 4999};
    biss_chain_cfg c = chain_of("tidep0022-test-encoder");
    struct rig r;
    rig_open(&r, &c, NULL);
    r.phase = phase[_i];
    rig_add_n(&r, 6, 10, 60, NULL, 40 * US);
    rig_run(&r);
    expect_same(&r);
    sim_ps lo, hi; /* (one slave: a few SL changes a frame) */
    unsigned n;
    rig_latency(&r, &lo, &hi, &n);
    ck_assert_uint_gt(n, 40);
    ck_assert_int_eq(lo, 4 * SIM_PS_PER_PRU_CYCLE + (SIM_PS_PER_PRU_CYCLE - phase[_i]));
    ck_assert_int_eq(hi, 5 * SIM_PS_PER_PRU_CYCLE + (SIM_PS_PER_PRU_CYCLE - phase[_i]));
    rig_close(&r);
}
END_TEST

/* ---- the timeout ---------------------------------------------------------- */

/* When SL goes high for good after `edge`, before `end`: ps after edge, or -1. */
static sim_ps sl_high_after(waveform *w, sim_ps edge, sim_ps end) {
    sim_ps t = edge, last = -1;
    for (;;) {
        sim_ps n = waveform_next_after(w, t);
        if (n == SIM_NEVER || n > end) {
            break;
        }
        t = n;
        last = waveform_level_at(w, n) ? n : -1;
    }
    return last < 0 ? -1 : last - edge;
}

/* The firmware's timeout: from the frame's last MA edge (the last rise, or
 * the CDM = 1 fall after it) to SL high, in ps, for frame k. */
static sim_ps fw_timeout(struct rig *r, unsigned k) {
    const struct rig_frame *f = &r->frames[k];
    sim_ps last = f->rise[f->clocks - 1];
    sim_ps edge = f->cdm ? last + (sim_ps)f->half * SIM_PS_PER_PRU_CYCLE : last;
    return sl_high_after(&r->sl, edge, last + f->gap);
}

/* A fixed timeout ends within 5..35 ns of the time set (the model's 20 ns
 * output delay is in the middle): SL rises T after the last MA edge, the
 * slave's own work after the timeout's end counted into it, on either
 * CDM and at any rate, the first frame after the configuration included. */
START_TEST(timeout_fixed) {
    static const sim_ps tmo[] = {20 * US, 7 * US, 100 * US, 1000 * US};
    for (unsigned i = 0; i < sizeof tmo / sizeof tmo[0]; i++) {
        biss_chain_cfg c = chain_of("tidep0022-test-encoder");
        c.timeout_ps = tmo[i];
        struct rig r;
        rig_open(&r, &c, NULL);
        rig_add_n(&r, 2, 10, 30, (const int[]){0, 1}, tmo[i] + 20 * US);
        rig_add_n(&r, 2, 100, 30, (const int[]){0, 1}, tmo[i] + 20 * US);
        rig_run(&r);
        expect_same(&r);
        for (unsigned k = 0; k < 4; k++) {
            sim_ps t = fw_timeout(&r, k);
            ck_assert_msg(t >= tmo[i] + 5 * NS && t <= tmo[i] + 35 * NS,
                          "timeout %lld ns: SL high %lld ps after the last edge (frame %u)",
                          (long long)(tmo[i] / NS), (long long)t, k);
        }
        rig_close(&r);
    }
}
END_TEST

/* An adaptive timeout (the Hengstler AD38's kind): the MA period times
 * the factor, clamped; from the first frame's period on it ends within
 * -5..50 ns of that: the fixed one's 5..35 ns (its turns of 4 cycles, the
 * nearest), and the period's own measure (a PRU cycle either way) times
 * the factor more, as far as the slave's own work allows (below, the
 * floor: 3/4 of a period, PREWORK, ST_WORK_PAD). */
START_TEST(timeout_adaptive) {
    biss_chain_cfg c = chain_of("tidep0022-test-encoder");
    c.timeout_mode = BISS_TIMEOUT_ADAPTIVE;
    c.adaptive_factor = 2.5;
    c.adaptive_min_ps = 650 * NS;
    c.adaptive_max_ps = 20 * US;
    struct rig r;
    rig_open(&r, &c, NULL);
    /* the first frame knows no period: the longest; then 2.5 periods of the
     * frame before; a faster frame keeps the last one's; a slower one (over
     * 1.5 times what the timeout serves) the longest */
    rig_add_n(&r, 3, 500, 30, (const int[]){0, 1, 0}, 40 * US); /* 200 kHz: 12.5 us */
    rig_add_n(&r, 3, 250, 30, (const int[]){1, 0, 1}, 40 * US); /* 400 kHz: 6.25 us */
    rig_add_n(&r, 2, 100, 30, (const int[]){0, 1}, 40 * US);    /* 1 MHz: 2.5 us */
    rig_add_n(&r, 2, 1000, 30, (const int[]){0, 1}, 60 * US);   /* 100 kHz: 25 us, 20 us */
    rig_run(&r);
    static const sim_ps want[] = {20 * US,   12500 * NS, 12500 * NS, 12500 * NS, 6250 * NS,
                                  6250 * NS, 6250 * NS,  2500 * NS,  20 * US,    20 * US};
    for (unsigned k = 0; k < 10; k++) {
        sim_ps t = fw_timeout(&r, k);
        ck_assert_msg(t >= want[k] - 5 * NS && t <= want[k] + 50 * NS,
                      "frame %u: SL high %lld ps after the last edge, want %lld", k, (long long)t,
                      (long long)want[k]);
    }
    rig_close(&r);
}
END_TEST

/* ---- the motion, the table, nE/nW live ------------------------------------ */

/* Table mode: frame k sends entry start + k mod len, and its life counter
 * counts on; another slave steps on as before. */
START_TEST(position_table) {
    biss_chain_cfg c = chain_of("biss-safety-two-channel");
    struct rig r;
    rig_open(&r, &c, NULL);
    uint64_t table[5];
    for (unsigned i = 0; i < 5; i++) {
        table[i] = 0xfff000ull * (i + 1) + 0x123 * i;
    }
    ck_assert_int_eq(biss_proto_encoder_table_put(&r.io, 100, table, 5), 0);
    struct biss_encoder_config e;
    char err[200];
    ck_assert_msg(slave_fw_config(&c, &e, err, sizeof err) == 0, "%s", err);
    e.slave[0].table_start = 100;
    e.slave[0].table_len = 5;
    struct biss_slv_config blk;
    biss_encoder_encode(&e, &blk);
    ck_assert_int_eq(biss_proto_encoder_put(&r.io, &blk, 2), 0);
    r.cursor += 1400 * US; /* idle, the firmware looks every 1.3 ms */
    rig_run_fw_until(&r, r.cursor);
    ck_assert_uint_eq(rig_status(&r).cfg_ack, 2);
    rig_add_n(&r, 12, 10, 100, NULL, 40 * US);
    rig_run(&r);
    for (unsigned k = 0; k < 12; k++) {
        uint64_t w0 = r.frames[k].rec.word[0] >> (64 - 32); /* 24 + 2 + 6 bits */
        ck_assert_uint_eq(w0 >> 8, table[k % 5] & 0xffffff);
        ck_assert_uint_eq(w0 & 0x3f, k & 0x3f); /* life counter */
        ck_assert_uint_eq((w0 >> 6) & 3, 3);    /* nE, nW: none */
        uint64_t w1 = r.frames[k].rec.word[1] >> (64 - 28);
        ck_assert_uint_eq(w1 >> 8, (c.s[1].pos0 + k * (uint64_t)c.s[1].counts_per_frame) & 0xfffff);
    }
    rig_close(&r);
}
END_TEST

/* LIVE_EW: nE and nW from the next frame on, nothing restarted. */
START_TEST(error_and_warning_live) {
    biss_chain_cfg c = chain_of("tidep0022-test-encoder");
    struct rig r;
    rig_open(&r, &c, NULL);
    rig_add_n(&r, 6, 10, 30, NULL, 40 * US);
    rig_run_fw_until(&r, r.frames[0].t0 - 1);
    for (unsigned k = 0; k < 6; k++) {
        rig_run_fw_until(&r, r.frames[k].t0 - 1);
        ck_assert_int_eq(biss_proto_encoder_rec(&r.io, &r.frames[k].rec), 0);
        uint8_t live[8] = {(uint8_t)(k % 4)};
        ck_assert_int_eq(biss_proto_encoder_ew_put(&r.io, live), 0);
    }
    for (unsigned k = 0; k < 6; k++) {
        uint64_t w = r.frames[k].rec.word[0] >> 50; /* 12 + 2 bits */
        unsigned set = k ? (k - 1) % 4 : 0;         /* written before the frame before */
        ck_assert_uint_eq(w >> 2, (3 * k) & 0xfff);
        ck_assert_uint_eq((w >> 1) & 1, !(set & BISS_SLV_EW_ERROR));
        ck_assert_uint_eq(w & 1, !(set & BISS_SLV_EW_WARNING));
    }
    rig_close(&r);
}
END_TEST

/* ---- control communication --------------------------------------------------- */

/* CRC4, polynomial 0x13, start 0, MSB first (TIDEP0022 Table 3; §3.2.4's
 * worked example: 10001100111 gives 1101). */
static unsigned crc4(uint32_t v, unsigned n) {
    unsigned c = 0;
    for (unsigned i = n; i-- > 0;) {
        unsigned fb = ((c >> 3) ^ (v >> i)) & 1u;
        c = (c << 1) & 0xf;
        if (fb) {
            c ^= 0x3;
        }
    }
    return c;
}

/* CDM bits of a control frame, appended to a script. */
struct cdm_seq {
    int bit[4096];
    unsigned n;
};

static void put(struct cdm_seq *s, uint32_t v, unsigned n) {
    for (unsigned i = n; i-- > 0;) {
        ck_assert_uint_lt(s->n, 4096);
        s->bit[s->n++] = (int)((v >> i) & 1u);
    }
}

/* 14 zeros, S, and a register access header: CTS 1, ID, ADR, inverted CRC4. */
static void put_reg_header(struct cdm_seq *s, unsigned id, unsigned addr) {
    put(s, 0, 14);
    put(s, 1, 1);
    uint32_t h = 0x400u | (id << 7) | addr;
    put(s, h, 11);
    put(s, ~crc4(h, 11) & 0xf, 4);
}

/* A read of n consecutive registers with the slave's S at once: R W S,
 * then per byte 8 + 4 zeros, P, and S (1: the next, 0: the end). With
 * wait frames of late S, CDM 1 while the slave's S is 0. */
static void put_read(struct cdm_seq *s, unsigned id, unsigned addr, unsigned n, unsigned wait) {
    put_reg_header(s, id, addr);
    put(s, 5, 3);
    for (unsigned b = 0; b < n; b++) {
        put(s, (1u << wait) - 1, wait);
        put(s, 0, 12);
        put(s, 0, 1);
        put(s, b + 1 < n, 1);
    }
}

static void put_write(struct cdm_seq *s, unsigned id, unsigned addr, const uint8_t *v, unsigned n,
                      unsigned wait, bool bad_crc) {
    put_reg_header(s, id, addr);
    put(s, 3, 3);
    for (unsigned b = 0; b < n; b++) {
        put(s, (1u << wait) - 1, wait);
        put(s, v[b], 8);
        put(s, (~crc4(v[b], 8) & 0xf) ^ (bad_crc ? 1u : 0u), 4);
        put(s, 0, 1);
        put(s, b + 1 < n, 1);
    }
}

/* A command: 14 zeros, S, CTS 0, IDS (bit 7: ID 0), CMD, CRC4, 8 IDA slots
 * (0), the execute bit. */
static void put_command(struct cdm_seq *s, unsigned ids, unsigned cmd, int exec) {
    put(s, 0, 14);
    put(s, 1, 1);
    uint32_t h = (ids << 2) | cmd;
    put(s, h, 11);
    put(s, ~crc4(h, 11) & 0xf, 4);
    put(s, 0, 8);
    put(s, (unsigned)exec, 1);
}

/* Runs the CDM sequence, one bit a frame (whole frames at H), then 16
 * frames of 0, and compares every frame's SL with the model's. */
static void run_cdm(struct rig *r, const struct cdm_seq *s, unsigned half, unsigned clocks) {
    for (unsigned i = 0; i < s->n; i++) {
        rig_add(r, half, clocks, s->bit[i], 30 * US);
    }
    rig_add_n(r, 16, half, clocks, NULL, 30 * US);
    rig_run(r);
    expect_same(r);
}

/* The CDS the firmware sent in frame k: the bit after the start bit. */
static int cds_of(struct rig *r, unsigned k) {
    const struct rig_frame *f = &r->frames[k];
    for (unsigned j = 2; j + 1 < f->clocks; j++) {
        /* the bit rise j put out, read before rise j + 1 */
        if (rig_sl_fw(r, f->rise[j] - 1)) {
            return rig_sl_fw(r, f->rise[j + 1] - 1);
        }
    }
    ck_abort_msg("frame %u: no start bit", k);
    return -1;
}

/* The byte a read answered: 8 CDS bits from the frame after the one that
 * carried data bit 0's CDM (first), MSB first. */
static unsigned cds_byte(struct rig *r, unsigned first) {
    unsigned v = 0;
    for (unsigned j = 0; j < 8; j++) {
        v = (v << 1) | (unsigned)cds_of(r, first + 1 + j);
    }
    return v;
}

/* TIDEP0022's Table 7 frames (the CDM after S as 32 bits) read the test
 * encoder's registers to Table 11's values, followed by their CRC4. */
START_TEST(tidep0022_table7_reads) {
    static const struct {
        uint32_t hex;
        unsigned value;
    } t[] = {{0x889B4000, 0x00}, {0x88BD4000, 0xD9}, {0x88D74000, 0x01}, {0x88F14000, 0x32},
             {0x8C174000, 0x0B}, {0x8F474000, 0xC0}, {0x8F614000, 0x0C}, {0x8FB54000, 0x01}};
    biss_chain_cfg c = chain_of("tidep0022-test-encoder");
    struct rig r;
    rig_open(&r, &c, NULL);
    struct cdm_seq s = {.n = 0};
    unsigned at[8];
    for (unsigned i = 0; i < 8; i++) {
        put(&s, 0, 14);
        put(&s, 1, 1);
        at[i] = s.n + 18; /* the first data bit's CDM: after CTS..CRC (15) and R W S */
        put(&s, t[i].hex, 32);
    }
    run_cdm(&r, &s, 10, 30);
    for (unsigned i = 0; i < 8; i++) {
        ck_assert_uint_eq(cds_byte(&r, at[i]), t[i].value);
        unsigned crc = 0;
        for (unsigned j = 0; j < 4; j++) {
            crc = (crc << 1) | (unsigned)cds_of(&r, at[i] + 9 + j);
        }
        ck_assert_uint_eq(crc, ~crc4(t[i].value, 8) & 0xf);
    }
    rig_close(&r);
}
END_TEST

/* The register files after writes, as the model's. */
static void expect_regs(struct rig *r) {
    unsigned bank0 = 0;
    for (unsigned i = 0; i < r->chain.n; i++) {
        struct biss_slv_regs fw;
        ck_assert_int_eq(biss_proto_encoder_regs_get(&r->io, i, &fw), 0);
        const regfile *m = &r->model->cfg.s[i].regs;
        ck_assert_mem_eq(fw.direct, m->direct, 64);
        for (unsigned b = 0; b < m->nbanks; b++) {
            uint8_t bank[64];
            ck_assert_int_eq(biss_proto_encoder_bank_get(&r->io, bank0 + b, bank), 0);
            ck_assert_mem_eq(bank, m->bank[b], 64);
        }
        bank0 += m->nbanks;
    }
}

/* Register access as the documents lay it out: single and sequential reads
 * and writes, late S, the bank select, read-only and protected registers,
 * a write with a wrong CRC, a header with a wrong CRC, another ID. SL of
 * every frame (so every CDS), the register files and the counters equal
 * the model's. */
START_TEST(register_access) {
    biss_chain_cfg c = chain_of("posital-kit-layout-biss-c");
    c.s[0].reg_proc_frames = (unsigned)_i; /* late S: 0 .. 3 frames */
    c.s[0].regs.flags[0x50] = REG_RO;
    c.s[0].regs.flags[0x51] = REG_WP;
    c.s[0].regs.protect = true;
    regfile_poke(&c.s[0].regs, 1, 0x10, 0xa5);
    struct rig r;
    rig_open(&r, &c, NULL);
    struct cdm_seq s = {.n = 0};
    unsigned w = (unsigned)_i;
    put_read(&s, 0, 0x78, 6, w);                                        /* device ID */
    put_write(&s, 0, 0x6a, (const uint8_t[]){0x12, 0x34}, 2, w, false); /* sequential write */
    put_read(&s, 0, 0x6a, 2, w);
    put_write(&s, 0, 0x40, (const uint8_t[]){1}, 1, w, false); /* bank 1 */
    put_read(&s, 0, 0x10, 1, w);
    put_write(&s, 0, 0x10, (const uint8_t[]){0x5c}, 1, w, false);
    put_write(&s, 0, 0x50, (const uint8_t[]){0x77, 0x66}, 2, w, false); /* RO, then WP */
    put_write(&s, 0, 0x6b, (const uint8_t[]){0x99}, 1, w, true);        /* wrong CRC */
    put_write(&s, 5, 0x6b, (const uint8_t[]){0x98}, 1, w, false);       /* another ID */
    put_write(&s, 0, 0x7f, (const uint8_t[]){0xe1, 0xe2}, 2, w, false); /* wraps to 0x00 */
    put(&s, 0, 14);
    put(&s, 1, 1);
    put(&s, 0x7ff, 11);
    put(&s, 0, 4); /* a header with a wrong CRC */
    run_cdm(&r, &s, 10, 70);
    expect_regs(&r);
    struct biss_slv_status st = rig_status(&r);
    const biss_ctrl *m = &r.model->ctrl[0];
    ck_assert_uint_eq(st.slave[0].reads, m->reads);
    ck_assert_uint_eq(st.slave[0].writes, m->writes);
    ck_assert_uint_eq(st.slave[0].refused, m->write_refused);
    ck_assert_uint_eq(st.slave[0].crc_errors + st.hdr_crc_errors, m->crc_errors);
    ck_assert_uint_eq(st.slave[0].last_addr, (unsigned)m->last_addr);
    ck_assert_uint_eq(st.slave[0].last_value, (unsigned)m->last_value);
    /* 0x6a, 0x6b, 0x40, bank 1's 0x10 and 0x00; refused: 0x50 (read-only),
     * 0x51 (protected), 0x7f (read-only in the profile) */
    ck_assert_uint_eq(m->writes, 5);
    ck_assert_uint_eq(m->write_refused, 3);
    rig_close(&r);
}
END_TEST

/* Commands in a chain: addressed with the IDA answers, broadcast, the
 * execute bit of either convention, an inverted execute bit (a master's
 * IDA test withholding it), and a data-only channel that answers nothing. */
START_TEST(commands) {
    biss_chain_cfg c = chain_of("hengstler-ad38"); /* channel 1 is data only */
    c.busy_ps = 0;
    c.n = 4;
    biss_slave_cfg_default(&c.s[3], 5);
    c.s[3].cmd_exec = 0;
    c.s[3].counts_per_frame = 1;
    {
        char err[160];
        ck_assert_msg(biss_chain_cfg_check(&c, err, sizeof err) == 0, "%s", err);
    }
    struct rig r;
    rig_open(&r, &c, NULL);
    struct cdm_seq s = {.n = 0};
    put_command(&s, 0x40, 2, 1); /* ID 1 */
    put_command(&s, 0x84, 3, 1); /* IDs 0 and 5: ID 5 takes 0 */
    put_command(&s, 0x84, 1, 0); /* the same, other value */
    put_command(&s, 0x00, 0, 1); /* broadcast */
    put_command(&s, 0x20, 1, 1); /* ID 2: nobody */
    put_read(&s, 1, 0x78, 2, 0); /* and a read of ID 1 among them */
    run_cdm(&r, &s, 10, 150);
    struct biss_slv_status st = rig_status(&r);
    for (unsigned i = 0; i < c.n; i++) {
        const biss_ctrl *m = &r.model->ctrl[i];
        ck_assert_uint_eq(st.slave[i].commands, m->commands);
        ck_assert_uint_eq(st.slave[i].dropped, m->commands_dropped);
        ck_assert_uint_eq(st.slave[i].last_cmd, m->last_cmd < 0 ? 0xff : (unsigned)m->last_cmd);
    }
    ck_assert_uint_eq(st.slave[3].commands, 1); /* 0x84 with 0 */
    ck_assert_uint_eq(st.slave[3].dropped, 2);  /* 0x84 with 1, the broadcast */
    ck_assert_uint_eq(st.slave[0].commands, 0); /* data only */
    rig_close(&r);
}
END_TEST

/* 14 zeros cancel a control frame in any state; 13 do not. */
START_TEST(fourteen_zeros_cancel) {
    biss_chain_cfg c = chain_of("tidep0022-test-encoder");
    c.s[0].reg_proc_frames = 20;
    struct rig r;
    rig_open(&r, &c, NULL);
    struct cdm_seq s = {.n = 0};
    put_reg_header(&s, 0, 0x44); /* cut in the header */
    s.n -= 6;
    put(&s, 0, 14);
    put_reg_header(&s, 0, 0x44); /* in the late S */
    put(&s, 5, 3);
    put(&s, 1, 5);
    put(&s, 0, 14);
    put_read(&s, 0, 0x45, 1, 20);                                  /* whole */
    put_write(&s, 0, 0x60, (const uint8_t[]){0x3c}, 1, 20, false); /* cut in the data */
    s.n -= 10;
    put(&s, 0, 13);
    put(&s, 1, 3);
    put(&s, 0, 14);
    run_cdm(&r, &s, 10, 30);
    ck_assert_uint_eq(rig_status(&r).cancels, r.model->ctrl[0].cancels);
    ck_assert_uint_eq(r.model->ctrl[0].cancels, 2); /* the data cut short ends as a frame */
    expect_regs(&r);
    rig_close(&r);
}
END_TEST

/* Random CDM streams with control frames in them: every CDS, register and
 * counter as the model's. */
START_TEST(random_cdm) {
    biss_chain_cfg c = chain_of("hengstler-ad38");
    c.busy_ps = 0;
    c.s[1].reg_proc_frames = 2;
    struct rig r;
    rig_open(&r, &c, NULL);
    struct cdm_seq s = {.n = 0};
    for (unsigned k = 0; k < 30; k++) {
        switch (rnd(5)) {
        case 0:
            put_read(&s, rnd(2), rnd(128), 1 + rnd(3), c.s[1].reg_proc_frames);
            break;
        case 1: {
            uint8_t v[3] = {(uint8_t)rnd(256), (uint8_t)rnd(256), (uint8_t)rnd(256)};
            put_write(&s, rnd(2), rnd(128), v, 1 + rnd(3), c.s[1].reg_proc_frames, rnd(4) == 0);
            break;
        }
        case 2:
            put_command(&s, rnd(256), rnd(4), (int)rnd(2));
            break;
        default:
            for (unsigned i = rnd(30); i > 0; i--) {
                put(&s, rnd(3) == 0, 1);
            }
        }
    }
    run_cdm(&r, &s, 10, 150);
    expect_regs(&r);
    struct biss_slv_status st = rig_status(&r);
    for (unsigned i = 0; i < c.n; i++) {
        ck_assert_uint_eq(st.slave[i].commands, r.model->ctrl[i].commands);
        ck_assert_uint_eq(st.slave[i].reads, r.model->ctrl[i].reads);
        ck_assert_uint_eq(st.slave[i].writes, r.model->ctrl[i].writes);
    }
    rig_close(&r);
}
END_TEST

/* Random CDM on a chain of eight, each slave's control communication its
 * own: scattered IDs, a data-only channel, both ID-lock slots, both
 * execute bits, late S; register accesses and commands to any ID among
 * stray bits. A slave a header does not address ignores the frame until
 * 14 zeros, while the addressed one ends it and wants 14 fresh ones: the
 * firmware keeps them apart as the model's eight state machines do. */
START_TEST(random_cdm_chain) {
    static const uint8_t ids[8] = {3, 0, 7, 5, 1, 6, 2, 4};
    biss_chain_cfg c = chain_of("tidep0022-test-encoder");
    c.busy_ps = 0;
    c.n = 8;
    unsigned bits = 0;
    for (unsigned i = 0; i < 8; i++) {
        biss_slave_cfg_default(&c.s[i], ids[i]);
        c.s[i].counts_per_frame = 1 + (int64_t)i;
        c.s[i].regs.nbanks = 2;
        bits += biss_slave_cfg_bits(&c.s[i]);
    }
    c.s[2].no_control = true; /* ID 7 answers for nobody */
    c.s[1].idl_at_cts = true;
    c.s[4].idl_at_cts = true;
    c.s[5].cmd_exec = 0;
    c.s[6].reg_proc_frames = 1;
    {
        char err[160];
        ck_assert_msg(biss_chain_cfg_check(&c, err, sizeof err) == 0, "%s", err);
    }
    struct rig r;
    rig_open(&r, &c, NULL);
    rnd_state = 1; /* (the same script however the tests run) */
    struct cdm_seq s = {.n = 0};
    for (unsigned k = 0; k < 60; k++) {
        unsigned id = rnd(8);
        unsigned wait = id == 2 ? 1 : 0;
        switch (rnd(7)) {
        case 0:
            put_read(&s, id, rnd(128), 1 + rnd(2), wait);
            break;
        case 1: {
            uint8_t v[2] = {(uint8_t)rnd(256), (uint8_t)rnd(256)};
            put_write(&s, id, 0x41 + rnd(60), v, 1 + rnd(2), wait, rnd(4) == 0);
            break;
        }
        case 2:
        case 3:
            put_command(&s, rnd(4) ? 1u << rnd(8) : rnd(256), rnd(4), (int)rnd(2));
            break;
        default:
            for (unsigned i = rnd(20); i > 0; i--) {
                put(&s, rnd(5) == 0, 1);
            }
        }
    }
    run_cdm(&r, &s, 10, 8 + bits);
    expect_regs(&r);
    struct biss_slv_status st = rig_status(&r);
    unsigned long seen[5] = {0};
    for (unsigned i = 0; i < c.n; i++) {
        const biss_ctrl *m = &r.model->ctrl[i];
        ck_assert_uint_eq(st.slave[i].commands, m->commands);
        ck_assert_uint_eq(st.slave[i].dropped, m->commands_dropped);
        ck_assert_uint_eq(st.slave[i].reads, m->reads);
        ck_assert_uint_eq(st.slave[i].writes, m->writes);
        ck_assert_uint_eq(st.slave[i].refused, m->write_refused);
        ck_assert_uint_eq(st.slave[i].last_cmd, m->last_cmd < 0 ? 0xff : (unsigned)m->last_cmd);
        seen[0] += m->reads;
        seen[1] += m->writes;
        seen[2] += m->commands;
        seen[3] += m->commands_dropped;
        seen[4] += m->cancels;
    }
    for (unsigned k = 0; k < 5; k++) {
        ck_assert_uint_gt(seen[k], 4); /* (the script has every kind) */
    }
    rig_close(&r);
}
END_TEST

/* A master that moves MA after the slave took the frame's control step
 * ahead in its tail (the CDM = 1 fall 3 us after the last rise, long after
 * 3/4 of a period of MA standing high): the step is taken again for the
 * CDM MA then stands for, from the state before it; the same CDS as the
 * model's, and the same register file. Those frames' timeouts end late by
 * the step (the work after them over WORK_PAD), as partial frames' do. */
START_TEST(cdm_moved_late) {
    biss_chain_cfg c = chain_of("hengstler-ad38");
    c.busy_ps = 0;
    c.timeout_mode = BISS_TIMEOUT_FIXED; /* 20 us: the fall inside it */
    c.timeout_ps = 20 * US;
    struct rig r;
    rig_open(&r, &c, NULL);
    r.partial_frames = true;
    r.cdm_fall = 3 * US;
    struct cdm_seq s = {.n = 0};
    put_read(&s, 1, 0x78, 3, 0);
    put_write(&s, 0, 0x6a, (const uint8_t[]){0x5a, 0xa5}, 2, 0, false);
    put_command(&s, 0x40, 2, 1);
    put_read(&s, 0, 0x6a, 2, 0);
    run_cdm(&r, &s, 10, 150);
    expect_regs(&r);
    struct biss_slv_status st = rig_status(&r);
    ck_assert_uint_gt(st.work, st.work_pad); /* the steps taken again */
    for (unsigned i = 0; i < c.n; i++) {
        const biss_ctrl *m = &r.model->ctrl[i];
        ck_assert_uint_eq(st.slave[i].reads, m->reads);
        ck_assert_uint_eq(st.slave[i].writes, m->writes);
        ck_assert_uint_eq(st.slave[i].commands, m->commands);
    }
    ck_assert_uint_eq(r.model->ctrl[1].reads, 3);  /* ID 1 */
    ck_assert_uint_eq(r.model->ctrl[2].writes, 2); /* ID 0 */
    ck_assert_uint_eq(r.model->ctrl[2].reads, 2);
    ck_assert_uint_eq(r.model->ctrl[1].commands, 1);
    rig_close(&r);
}
END_TEST

/* ---- strict mode ------------------------------------------------------------------ */

/* Strict mode on the slave's core with its clocked scope taken from MA (the
 * input it is clocked by, pru_strict_inputs) and every rule: no LOOP, MVI,
 * data-RAM access or scratch-pad collision between two MA edges a half
 * period apart, over busy time, partial frames, a chain, control frames
 * and the table. With a window that takes in the work between frames too,
 * the same run is stopped at its first data-RAM access: the check bites. */
static void strict_run(unsigned half, unsigned window, bool expect_clean) {
    biss_chain_cfg c = chain_of("hengstler-ad38");
    c.busy_ps = 2430 * NS;
    c.s[1].reg_proc_frames = 2;
    struct pru_params pp;
    pru_params_default(&pp);
    pp.strict = PRU_STRICT_ALL;
    pp.strict_window = window;
    struct rig r;
    rig_open(&r, &c, &pp);
    r.partial_frames = true;
    pru_strict_inputs(r.core, 1u << RIG_MA_BIT);
    struct cdm_seq s = {.n = 0};
    put_read(&s, 1, 0x78, 3, 2);
    put_write(&s, 0, 0x40, (const uint8_t[]){0}, 1, 0, false);
    put_command(&s, 0x40, 1, 1);
    for (unsigned i = 0; i < s.n; i++) {
        rig_add(&r, half, 1 + (i % 7 ? 150 : rnd(150)), s.bit[i], 30 * US);
    }
    if (!expect_clean) {
        for (unsigned k = 0; k < r.nframes; k++) {
            enum pru_stop why = pru_icss_run_until_time(r.icss, r.frames[k].t0 + 40 * US);
            if (why == PRU_STOP_FAULT) {
                const struct pru_fault *f = pru_get_fault(r.core);
                ck_assert_int_eq(f->cause, PRU_FAULT_STRICT);
                ck_assert_uint_eq(f->rule, PRU_STRICT_DRAM);
                rig_close(&r);
                return;
            }
        }
        ck_abort_msg("a window over the whole frame found no data-RAM access");
    }
    rig_run(&r);
    expect_same(&r);
    rig_close(&r);
}

START_TEST(strict_timing_critical_code) {
    strict_run(10, 10, true);
    strict_run(100, 100, true);
    strict_run(10, 100000, false);
}
END_TEST

/* ---- configuration ------------------------------------------------------------- */

/* Every refusal: ST_CFG_ERROR names it, SL stays low (no slave answers),
 * and a good configuration after it runs. */
START_TEST(configuration_refused) {
    biss_chain_cfg c = chain_of("tidep0022-test-encoder");
    struct rig r;
    rig_open(&r, &c, NULL);
    struct biss_encoder_config e;
    char err[200];
    ck_assert_msg(slave_fw_config(&c, &e, err, sizeof err) == 0, "%s", err);
    struct biss_slv_config good;
    biss_encoder_encode(&e, &good);
    struct biss_slv_config b;
    uint32_t seq = 1;
#define REFUSED(code, stmt)                                                                        \
    do {                                                                                           \
        b = good;                                                                                  \
        stmt;                                                                                      \
        ck_assert_int_eq(biss_proto_encoder_put(&r.io, &b, ++seq), 0);                             \
        r.cursor += 2000 * US;                                                                     \
        rig_run_fw_until(&r, r.cursor);                                                            \
        struct biss_slv_status st = rig_status(&r);                                                \
        ck_assert_uint_eq(st.cfg_ack, seq);                                                        \
        ck_assert_msg(st.cfg_error == (code), "%s: error %u, want %u", #stmt, st.cfg_error,        \
                      (unsigned)(code));                                                           \
        ck_assert_int_eq(rig_sl_fw(&r, r.cursor), (code) == 0);                                    \
    } while (0)
    REFUSED(BISS_SLV_CFGERR_NSLAVES, b.nslaves = 0);
    REFUSED(BISS_SLV_CFGERR_NSLAVES, b.nslaves = 9);
    REFUSED(BISS_SLV_CFGERR_DATA_BITS, b.slave[0].pos_bits = 0);
    REFUSED(BISS_SLV_CFGERR_DATA_BITS, b.slave[0].pos_bits = 65);
    REFUSED(BISS_SLV_CFGERR_DATA_BITS, b.slave[0].fill_bits = 51);
    REFUSED(BISS_SLV_CFGERR_CRC_BITS, b.slave[0].crc_bits = 17);
    REFUSED(BISS_SLV_CFGERR_CRC_BITS, b.slave[0].crc_start = 0x40);
    REFUSED(BISS_SLV_CFGERR_LC_BITS, b.slave[0].lc_bits = 33);
    REFUSED(BISS_SLV_CFGERR_ID, b.slave[0].id = 8);
    REFUSED(BISS_SLV_CFGERR_ID, (b.nslaves = 2, b.slave[1] = b.slave[0]));
    REFUSED(BISS_SLV_CFGERR_TABLE, (b.slave[0].table_start = 120, b.slave[0].table_len = 9));
    REFUSED(BISS_SLV_CFGERR_BANKS, (b.slave[0].bank0 = 10, b.slave[0].banks = 7));
    REFUSED(BISS_SLV_CFGERR_TIMEOUT, b.timeout = 0);
    REFUSED(BISS_SLV_CFGERR_TIMEOUT, b.timeout = BISS_SLV_MAX_TIMEOUT + 1);
    REFUSED(BISS_SLV_CFGERR_TIMEOUT, b.tmo_mode = 2);
    REFUSED(BISS_SLV_CFGERR_TIMEOUT, (b.tmo_mode = BISS_SLV_TMO_ADAPTIVE, b.tmo_factor = 0));
    REFUSED(BISS_SLV_CFGERR_TIMEOUT,
            (b.tmo_mode = BISS_SLV_TMO_ADAPTIVE, b.tmo_factor = 24, b.tmo_min = b.timeout + 1));
    REFUSED(BISS_SLV_CFGERR_BUSY, b.busy_cycles = 1u << 24);
    REFUSED(0, (void)0);
#undef REFUSED
    rig_close(&r);
}
END_TEST

/* libbiss's check of an encoder configuration (proto/biss_encoder.c). */
START_TEST(host_config_check) {
    struct biss_encoder_config c;
    biss_encoder_config_default(&c);
    ck_assert_int_eq(biss_encoder_config_check(&c), 0);
    c.nslaves = 9;
    ck_assert_int_eq(biss_encoder_config_check(&c), BISS_E_NSLAVES);
    biss_encoder_config_default(&c);
    c.slave[0].crc_poly = 0x42;
    ck_assert_int_eq(biss_encoder_config_check(&c), BISS_E_CRC_POLY);
    biss_encoder_config_default(&c);
    c.slave[0].crc_start = 0x40;
    ck_assert_int_eq(biss_encoder_config_check(&c), BISS_E_CRC_START);
    biss_encoder_config_default(&c);
    c.slave[0].pos_bits = 63;
    ck_assert_int_eq(biss_encoder_config_check(&c), BISS_E_DATA_BITS);
    biss_encoder_config_default(&c);
    c.nslaves = 2;
    c.slave[1].id = 0;
    ck_assert_int_eq(biss_encoder_config_check(&c), BISS_E_ENC_ID);
    c.slave[1].no_control = true;
    ck_assert_int_eq(biss_encoder_config_check(&c), 0);
    biss_encoder_config_default(&c);
    c.adaptive = true;
    c.factor16 = 0;
    ck_assert_int_eq(biss_encoder_config_check(&c), BISS_E_ENC_TIMEOUT);
    biss_encoder_config_default(&c);
    c.slave[0].reg_wait = 256;
    ck_assert_int_eq(biss_encoder_config_check(&c), BISS_E_ENC_REG_WAIT);
}
END_TEST

int main(void) {
    Suite *s = suite_create("slave_fw");
    TCase *tc = tcase_create("frames");
    tcase_set_timeout(tc, 600);
    tcase_add_loop_test(tc, profiles_at_master_rates, 0, 20);
    tcase_add_test(tc, eight_slave_chain);
    tcase_add_test(tc, partial_and_long_frames);
    tcase_add_test(tc, processing_time);
    tcase_add_test(tc, highest_rate);
    tcase_add_test(tc, response_time_and_margins);
    tcase_add_loop_test(tc, response_time_off_grid, 0, 5);
    suite_add_tcase(s, tc);
    tc = tcase_create("timeout");
    tcase_set_timeout(tc, 600);
    tcase_add_test(tc, timeout_fixed);
    tcase_add_test(tc, timeout_adaptive);
    suite_add_tcase(s, tc);
    tc = tcase_create("motion");
    tcase_add_test(tc, position_table);
    tcase_add_test(tc, error_and_warning_live);
    suite_add_tcase(s, tc);
    tc = tcase_create("control");
    tcase_set_timeout(tc, 600);
    tcase_add_test(tc, tidep0022_table7_reads);
    tcase_add_loop_test(tc, register_access, 0, 4);
    tcase_add_test(tc, commands);
    tcase_add_test(tc, fourteen_zeros_cancel);
    tcase_add_test(tc, random_cdm);
    tcase_add_test(tc, random_cdm_chain);
    tcase_add_test(tc, cdm_moved_late);
    suite_add_tcase(s, tc);
    tc = tcase_create("strict");
    tcase_set_timeout(tc, 600);
    tcase_add_test(tc, strict_timing_critical_code);
    suite_add_tcase(s, tc);
    tc = tcase_create("configuration");
    tcase_add_test(tc, configuration_refused);
    tcase_add_test(tc, host_config_check);
    suite_add_tcase(s, tc);
    return check_run(s);
}
