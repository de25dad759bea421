/* Check suite for the BiSS-C slave from its pins: ACK, busy, start, CDS,
 * data, CRC, timeouts, CDM sampling, register access over real frames and
 * a daisy chain. Expected bit strings were computed by hand / separately. */
#include "biss_slave.h"
#include "slave_motion.h"
#include "slave_rig.h"

#include "check_run.h"

#include <check.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#define NS SIM_PS_PER_NS
#define US SIM_PS_PER_US

typedef struct {
    rig r;
    biss_slave b;
} bench;

static bench *bench_new(const biss_chain_cfg *cfg, sim_ps h) {
    bench *x = malloc(sizeof *x);
    ck_assert_ptr_nonnull(x);
    char err[200];
    ck_assert_msg(biss_chain_cfg_check(cfg, err, sizeof err) == 0, "%s", err);
    rig_init(&x->r, h);
    biss_slave_init(&x->b, cfg, &x->r.q, waveform_sink(&x->r.sl));
    x->r.slave = biss_slave_sink(&x->b);
    return x;
}

static void bench_free(bench *x) {
    rig_free(&x->r);
    free(x);
}

static biss_chain_cfg *cfg_12bit(uint64_t pos) {
    static biss_chain_cfg c;
    biss_chain_cfg_default(&c);
    c.s[0].pos0 = pos;
    return &c;
}

START_TEST(frame_bits_12bit_crc6) {
    bench *x = bench_new(cfg_12bit(0x3a7), 500 * NS);
    int bits[30];
    char s[64];
    rig_frame(&x->r, 26, 0, 0, 30 * US, bits);
    /* idle-high sample, ACK, start, CDS 0, position 0x3A7, nE nW = 1 1,
     * CRC6 0x43 sent inverted 001001, then the timeout's low */
    bits_str(bits, 0, 26, s);
    ck_assert_str_eq(s, "1"
                        "0"
                        "1"
                        "0"
                        "001110100111"
                        "11"
                        "001001"
                        "00");
    const biss_frame_record *rec = biss_slave_record(&x->b, 0);
    ck_assert_ptr_nonnull(rec);
    ck_assert_uint_eq(rec->s[0].position, 0x3a7);
    ck_assert_int_eq(rec->s[0].nE, 1);
    ck_assert_uint_eq(rec->s[0].crc, 0x09);
    ck_assert(rec->complete);
    ck_assert_int_eq(rec->cdm, 0);
    bench_free(x);
}
END_TEST

START_TEST(error_bit_active_low) {
    bench *x = bench_new(cfg_12bit(0x3a7), 500 * NS);
    biss_slave_set_status(&x->b, 0, true, false);
    int bits[30];
    char s[64];
    rig_frame(&x->r, 24, 0, 0, 30 * US, bits);
    bits_str(bits, 4, 20, s);
    ck_assert_str_eq(s, "001110100111"
                        "01"
                        "001111");
    ck_assert_int_eq(biss_slave_record(&x->b, 0)->s[0].nE, 0);
    bench_free(x);
}
END_TEST

START_TEST(output_delay_after_ma_edge) {
    bench *x = bench_new(cfg_12bit(0), 500 * NS);
    sim_ps t0 = x->r.t;
    rig_frame(&x->r, 24, 0, 0, 30 * US, NULL);
    /* ACK: second rising edge at t0 + 3h, SL falls 20 ns later */
    ck_assert_int_eq(waveform_next_after(&x->r.sl, t0), t0 + 1500 * NS + 20 * NS);
    bench_free(x);
}
END_TEST

START_TEST(busy_time_delays_start_bit) {
    biss_chain_cfg *c = cfg_12bit(0x800);
    c->busy_ps = 2400 * NS;
    bench *x = bench_new(c, 500 * NS);
    int bits[32];
    char s[64];
    rig_frame(&x->r, 28, 0, 0, 30 * US, bits);
    /* ACK on rise 2; rises 3, 4 are within 2.4 us of it; rise 5 (3 us) starts */
    bits_str(bits, 0, 27, s);
    ck_assert_str_eq(s, "1"
                        "0"
                        "00"
                        "1"
                        "0"
                        "100000000000"
                        "11"
                        "100100"
                        "0");
    bench_free(x);
}
END_TEST

/* The start bit's rise is the first at or past busy_ps after the ACK:
 * rise 5 lies 3 us after it. */
START_TEST(busy_time_boundary) {
    const sim_ps busy[2] = {3000 * NS, 3000 * NS + 1};
    const char *want[2] = {"10001", "100001"};
    for (int i = 0; i < 2; i++) {
        biss_chain_cfg *c = cfg_12bit(0x800);
        c->busy_ps = busy[i];
        bench *x = bench_new(c, 500 * NS);
        int bits[32];
        char s[64];
        rig_frame(&x->r, 28, 0, 0, 30 * US, bits);
        bits_str(bits, 0, (int)strlen(want[i]), s);
        ck_assert_str_eq(s, want[i]);
        bench_free(x);
    }
}
END_TEST

START_TEST(busy_clocks_delay_start_bit) {
    biss_chain_cfg *c = cfg_12bit(0x800);
    c->busy_clocks = 1;
    bench *x = bench_new(c, 50 * NS); /* 10 MHz */
    int bits[32];
    char s[64];
    rig_frame(&x->r, 26, 0, 0, 30 * US, bits);
    bits_str(bits, 0, 6, s);
    ck_assert_str_eq(s, "1"
                        "00"
                        "1"
                        "0"
                        "1");
    bench_free(x);
}
END_TEST

START_TEST(fixed_timeout_then_sl_high) {
    bench *x = bench_new(cfg_12bit(0), 500 * NS);
    sim_ps last = rig_frame(&x->r, 24, 0, 0, 30 * US, NULL);
    /* SL low from the end of data until 20 us after the last MA edge */
    ck_assert_int_eq(waveform_level_at(&x->r.sl, last + 19 * US), 0);
    sim_ps up = last + 20 * US + 20 * NS;
    ck_assert_int_eq(waveform_level_at(&x->r.sl, up - 1), 0);
    ck_assert_int_eq(waveform_level_at(&x->r.sl, up), 1);
    bench_free(x);
}
END_TEST

/* A slave that lost its frame keeps SL low, also through the end of a
 * frame it was in; two clocks of a new frame ([MB4] INIT) and its timeout
 * bring SL high again. */
START_TEST(lost_slave_holds_sl_low_until_a_new_frame_ends) {
    bench *x = bench_new(cfg_12bit(0), 500 * NS);
    x->r.t = 1 * US;
    rig_ma(&x->r, 1 * US, 0); /* a frame begins ... */
    rig_ma(&x->r, 1500 * NS, 1);
    biss_slave_lose_sync(&x->b, 1700 * NS); /* ... and breaks */
    eq_run_until(&x->r.q, 100 * US);
    ck_assert_int_eq(waveform_level_at(&x->r.sl, 100 * US), 0);
    x->r.t = 100 * US;
    sim_ps last = rig_frame(&x->r, 2, 0, 0, 30 * US, NULL); /* INIT: two clocks */
    eq_run_until(&x->r.q, last + 30 * US);
    ck_assert_int_eq(waveform_level_at(&x->r.sl, last + 19 * US), 0);
    ck_assert_int_eq(waveform_level_at(&x->r.sl, last + 20 * US + 20 * NS), 1);
    ck_assert(!x->b.lost);
    bench_free(x);
}
END_TEST

START_TEST(adaptive_timeout_one_and_a_half_periods) {
    biss_chain_cfg *c = cfg_12bit(0);
    c->timeout_mode = BISS_TIMEOUT_ADAPTIVE;
    bench *x = bench_new(c, 500 * NS);
    sim_ps last = rig_frame(&x->r, 24, 0, 0, 10 * US, NULL);
    /* MA period 1 us -> timeout 1.5 us after the last rising edge */
    sim_ps up = last + 1500 * NS + 20 * NS;
    ck_assert_int_eq(waveform_next_after(&x->r.sl, last + 100 * NS), up);
    /* with CDM = 1 the timeout runs from MA's fall, half a period later */
    last = rig_frame(&x->r, 24, 1, 3 * US, 10 * US, NULL);
    up = last + 500 * NS + 1500 * NS + 20 * NS;
    ck_assert_int_eq(waveform_next_after(&x->r.sl, last + 100 * NS), up);
    ck_assert_int_eq(biss_slave_record(&x->b, 1)->cdm, 1);
    bench_free(x);
}
END_TEST

START_TEST(adaptive_timeout_floor) {
    biss_chain_cfg *c = cfg_12bit(0);
    c->timeout_mode = BISS_TIMEOUT_ADAPTIVE;
    c->adaptive_min_ps = 650 * NS;
    bench *x = bench_new(c, 50 * NS); /* 10 MHz: 1.5 periods = 150 ns < 650 */
    sim_ps last = rig_frame(&x->r, 24, 0, 0, 10 * US, NULL);
    ck_assert_int_eq(waveform_next_after(&x->r.sl, last + 30 * NS), last + 650 * NS + 20 * NS);
    bench_free(x);
}
END_TEST

START_TEST(incomplete_frame_times_out) {
    bench *x = bench_new(cfg_12bit(0xfff), 500 * NS);
    sim_ps last = rig_frame(&x->r, 10, 0, 0, 30 * US, NULL);
    const biss_frame_record *rec = biss_slave_record(&x->b, 0);
    ck_assert(!rec->complete);
    ck_assert(rec->started);
    ck_assert_int_eq(rec->cdm, 0);
    ck_assert_int_eq(waveform_level_at(&x->r.sl, last + 21 * US), 1);
    bench_free(x);
}
END_TEST

START_TEST(position_moves_between_frames) {
    biss_chain_cfg *c = cfg_12bit(100);
    c->s[0].speed_cps = 1e5; /* 0.1 count per us */
    bench *x = bench_new(c, 500 * NS);
    for (int i = 0; i < 5; i++) {
        rig_frame(&x->r, 24, 0, 0, 30 * US, NULL);
    }
    for (uint64_t i = 0; i < 5; i++) {
        const biss_frame_record *rec = biss_slave_record(&x->b, i);
        uint64_t expect = biss_slave_position_at(&x->b, 0, rec->latch_ps);
        ck_assert_uint_eq(rec->latch_ps, rec->start_ps + 500 * NS);
        ck_assert_uint_eq(rec->s[0].position, expect);
        ck_assert_uint_eq(rec->s[0].position, 100 + (uint64_t)(rec->latch_ps / (10 * US)));
        if (i > 0) {
            ck_assert_uint_gt(rec->s[0].position, biss_slave_record(&x->b, i - 1)->s[0].position);
        }
    }
    bench_free(x);
}
END_TEST

/* [MB4] "BiSS C Frame": the position is taken at the first rising edge of
 * MA, not at the falling edge that starts the frame. 1 count per us; the
 * frame starts at 1.75 us (count 1) and its first rise comes at 2.25 us
 * (count 2). */
START_TEST(position_latched_at_first_rising_edge) {
    biss_chain_cfg *c = cfg_12bit(0);
    c->s[0].speed_cps = 1e6;
    bench *x = bench_new(c, 500 * NS);
    x->r.t += 750 * NS;
    rig_frame(&x->r, 24, 0, 0, 30 * US, NULL);
    const biss_frame_record *rec = biss_slave_record(&x->b, 0);
    ck_assert_int_eq(rec->start_ps, 1750 * NS);
    ck_assert_int_eq(rec->latch_ps, 2250 * NS);
    ck_assert_uint_eq(rec->s[0].position, 2);
    bench_free(x);
}
END_TEST

START_TEST(position_wraps_and_runs_backwards) {
    biss_chain_cfg *c = cfg_12bit(2);
    c->s[0].speed_cps = -1e6; /* 1 count per us, backwards */
    bench *x = bench_new(c, 500 * NS);
    ck_assert_uint_eq(biss_slave_position_at(&x->b, 0, 5 * US), (2 - 5 + 4096) % 4096);
    bench_free(x);
}
END_TEST

/* Register read of 0x67 over real frames: CDM as MA level in the timeout,
 * CDS read from SL in the following frames. */
START_TEST(register_read_over_frames) {
    biss_chain_cfg *c = cfg_12bit(0);
    regfile_poke(&c->s[0].regs, 0, 0x67, 0x5f);
    bench *x = bench_new(c, 250 * NS);
    const char *cdm = "00000000000000"
                      "1"
                      "10001100111"
                      "0010"
                      "101"
                      "00000000"
                      "0000"
                      "0"
                      "0"
                      "0";
    char cds[64];
    size_t n = strlen(cdm);
    int bits[30];
    for (size_t i = 0; i < n; i++) {
        rig_frame(&x->r, 24, cdm[i] == '1', 22 * US, 25 * US, bits);
        cds[i] = (char)('0' + bits[3]);
    }
    cds[n] = '\0';
    /* CDS in frame i answers CDM of frame i-1 */
    ck_assert_str_eq(cds + 14 + 1 + 16, "101"
                                        "01011111"
                                        "1111"
                                        "0"
                                        "0");
    ck_assert_uint_eq(x->b.ctrl[0].reads, 1);
    bench_free(x);
}
END_TEST

/* The AD38 chain layout (3 slaves): 16-bit A/D + E/W + CRC5 0x25; 36-bit
 * MT+ST + E/W + CRC6 0x43; 9-bit ST + E/W + 6-bit life counter + CRC16
 * 0x190D9. Data follow each other in chain order after one CDS. */
START_TEST(daisy_chain_three_slaves) {
    biss_chain_cfg c;
    biss_chain_cfg_default(&c);
    c.n = 3;
    c.s[0].pos_bits = 16;
    c.s[0].crc_poly = 0x25;
    c.s[0].pos0 = 0x1234;
    c.s[1].pos_bits = 36;
    c.s[1].pos0 = UINT64_C(0x123456789);
    c.s[2].pos_bits = 9;
    c.s[2].lc_bits = 6;
    c.s[2].crc_poly = 0x190d9;
    c.s[2].pos0 = 0x1ab;
    bench *x = bench_new(&c, 500 * NS);
    x->b.lc[2] = 5;
    int bits[120];
    char s[128];
    rig_frame(&x->r, 4 + 23 + 44 + 33 + 1, 0, 0, 30 * US, bits);
    bits_str(bits, 4, 23, s);
    ck_assert_str_eq(s, "00010010001101001111110");
    bits_str(bits, 27, 44, s);
    ck_assert_str_eq(s, "00010010001101000101011001111000100111110100");
    bits_str(bits, 71, 33, s);
    ck_assert_str_eq(s, "110101011110001011011101111001111");
    ck_assert_int_eq(bits[104], 0); /* after the last slave: its input, low */
    const biss_frame_record *rec = biss_slave_record(&x->b, 0);
    ck_assert_uint_eq(rec->s[2].lc, 5);
    ck_assert_uint_eq(rec->s[1].position, UINT64_C(0x123456789));
    bench_free(x);
}
END_TEST

START_TEST(chain_cds_from_addressed_slave) {
    biss_chain_cfg c;
    biss_chain_cfg_default(&c);
    c.n = 2;
    c.s[0].id = 0;
    c.s[1].id = 1;
    regfile_poke(&c.s[1].regs, 0, 0x11, 0xa5);
    bench *x = bench_new(&c, 500 * NS);
    /* read 0x11 of ID 1: header 10010010001, CRC 1110 */
    const char *cdm = "00000000000000"
                      "1"
                      "10010010001"
                      "1110"
                      "101"
                      "00000000"
                      "0000"
                      "0"
                      "0"
                      "0";
    size_t n = strlen(cdm);
    char cds[64];
    int bits[60];
    for (size_t i = 0; i < n; i++) {
        rig_frame(&x->r, 50, cdm[i] == '1', 22 * US, 25 * US, bits);
        cds[i] = (char)('0' + bits[3]);
    }
    cds[n] = '\0';
    ck_assert_str_eq(cds + 31, "101"
                               "10100101"
                               "0100"
                               "0"
                               "0");
    ck_assert_uint_eq(x->b.ctrl[1].reads, 1);
    ck_assert_uint_eq(x->b.ctrl[0].reads, 0);
    bench_free(x);
}
END_TEST

/* Runs one CDM per frame and collects the CDS seen in each frame. */
static void run_cdm(bench *x, const char *cdm, int nclk, char *cds) {
    int bits[128];
    size_t n = strlen(cdm);
    for (size_t i = 0; i < n; i++) {
        rig_frame(&x->r, nclk, cdm[i] == '1', 22 * US, 25 * US, bits);
        cds[i] = (char)('0' + bits[3]);
    }
    cds[n] = '\0';
}

START_TEST(register_write_over_frames_then_read_back) {
    biss_chain_cfg *c = cfg_12bit(0);
    bench *x = bench_new(c, 500 * NS);
    char cds[80];
    /* write 0x3A to 0x10: header 10000010000 CRC 0011, RWS 011, data,
     * CRC4 sent 1101, P, end; then read it back */
    run_cdm(x,
            "00000000000000"
            "1"
            "10000010000"
            "0011"
            "011"
            "00111010"
            "1101"
            "00",
            24, cds);
    ck_assert_str_eq(cds + 31, "011"
                               "00111010"
                               "1101"
                               "0");
    ck_assert_uint_eq(regfile_read(&x->b.cfg.s[0].regs, 0x10), 0x3a);
    run_cdm(x,
            "00000000000000"
            "1"
            "10000010000"
            "0011"
            "101"
            "00000000"
            "0000"
            "000",
            24, cds);
    ck_assert_str_eq(cds + 31, "101"
                               "00111010"
                               "1101"
                               "0"
                               "0");
    bench_free(x);
}
END_TEST

/* A command addressed to ID 2 in a 3-slave chain: only slave 2 answers in
 * IDA slot 2 and executes it. */
START_TEST(command_in_chain_over_frames) {
    biss_chain_cfg c;
    biss_chain_cfg_default(&c);
    c.n = 3;
    bench *x = bench_new(&c, 500 * NS);
    char cds[80];
    run_cdm(x,
            "00000000000000"
            "1"
            "0"
            "00100000"
            "10"
            "0111"
            "00000000"
            "1"
            "0",
            3 * 20 + 6, cds);
    ck_assert_str_eq(cds + 14 + 16, "001"
                                    "00000"
                                    "0"
                                    "0");
    ck_assert_uint_eq(x->b.ctrl[2].commands, 1);
    ck_assert_int_eq(x->b.ctrl[2].last_cmd, 2);
    ck_assert_uint_eq(x->b.ctrl[0].commands + x->b.ctrl[1].commands, 0);
    bench_free(x);
}
END_TEST

START_TEST(config_check_messages) {
    biss_chain_cfg c;
    biss_chain_cfg_default(&c);
    char err[200];
    ck_assert_int_eq(biss_chain_cfg_check(&c, err, sizeof err), 0);
    c.n = 9;
    ck_assert_int_eq(biss_chain_cfg_check(&c, err, sizeof err), -1);
    ck_assert_str_eq(err, "slaves: 9 out of range 1..8");
    c.n = 1;
    c.s[0].crc_poly = 0x42;
    ck_assert_int_eq(biss_chain_cfg_check(&c, err, sizeof err), -1);
    ck_assert_str_eq(err, "slaves[0].crc_poly: must be an odd polynomial of degree 1..16 (with its "
                          "top term)");
    c.s[0].crc_poly = 0x43;
    c.s[0].pos_bits = 65;
    ck_assert_int_eq(biss_chain_cfg_check(&c, err, sizeof err), -1);
    ck_assert_str_eq(err, "slaves[0].position_bits: 65 out of range 1..64");
    /* the range once, in the table; the relation once, in the slave's check */
    c.s[0].pos_bits = 60;
    c.s[0].lc_bits = 3;
    ck_assert_int_eq(biss_chain_cfg_check(&c, err, sizeof err), -1);
    ck_assert_str_eq(err, "slaves[0].position_bits: with fill_bits, nE, nW and life_counter_bits "
                          "more than 64 data bits before the CRC");
    c.s[0].lc_bits = 2;
    ck_assert_int_eq(biss_chain_cfg_check(&c, err, sizeof err), 0);
}
END_TEST

/* Position over time: wraps modulo 2^bits both ways, and stays defined
 * for speeds and times far beyond the scenario's ranges. */
START_TEST(position_wraps_and_never_overflows) {
    const sim_ps s1 = SIM_PS_PER_S;
    ck_assert_uint_eq(slave_position_at(0, -1.0, 12, s1), 4095);
    ck_assert_uint_eq(slave_position_at(0, -1.0, 64, s1), UINT64_MAX);
    ck_assert_uint_eq(slave_position_at(10, 2.5, 12, 2 * s1), 15);
    ck_assert_uint_eq(slave_position_at(4090, 10.0, 12, s1), 4);
    ck_assert_uint_eq(slave_position_at(UINT64_MAX, 1.0, 64, s1), 0);
    /* doubles this large are multiples of 2^64: no step modulo 2^64 */
    ck_assert_uint_eq(slave_position_at(0, 18446744073709551616.0, 64, s1), 0);
    ck_assert_uint_eq(slave_position_at(0, 1e300, 8, s1), 0);
    ck_assert_uint_eq(slave_position_at(7, INFINITY, 8, s1), 7);
}
END_TEST

/* The quick step (biss_slave_ma_edge_quick) against the general path on
 * random MA: clock runs of random period, pauses around and past the
 * timeout, lost frames; fixed and adaptive timeouts (held at their floor
 * by fast clocks, and 1.5 periods of every period drawn: the quick step's
 * memo of the period changes with each run), busy clocks, a chain; and
 * the quick step switched off (biss_slave_set_quick). Both slaves must
 * send the same SL edges, schedule the same events (ids) and close the
 * same frame records. */
static unsigned long quick_hits;
/* rises the quick step took before the start bit: the ACK, busy clocks,
 * the start bit's */
static unsigned long quick_acks, quick_busy, quick_starts;

static void edge_quick_or_general(void *ctx, sim_ps t, int level) {
    biss_slave *b = ctx;
    unsigned rises = b->rises;
    bool started = b->started;
    if (!biss_slave_ma_edge_quick(b, t, level)) {
        biss_slave_ma_edge_general(b, t, level);
        return;
    }
    quick_hits++;
    if (level && rises == 1) {
        quick_acks++;
    } else if (level && !started) {
        *(b->started ? &quick_starts : &quick_busy) += 1;
    }
}

static void edge_general(void *ctx, sim_ps t, int level) {
    biss_slave_ma_edge_general(ctx, t, level);
}

static uint64_t next_rand(uint64_t *s) {
    *s ^= *s << 13;
    *s ^= *s >> 7;
    *s ^= *s << 17;
    return *s;
}

START_TEST(quick_step_matches_general) {
    biss_chain_cfg c;
    biss_chain_cfg_default(&c);
    c.s[0].pos0 = 0x5a5;
    c.s[0].speed_cps = 1e6;
    if (_i == 1) {
        c.n = 2;
        c.busy_clocks = 2;
        c.busy_ps = 300 * NS;
        c.s[1].pos_bits = 20;
        c.s[1].lc_bits = 6;
    } else if (_i == 2) {
        c.timeout_mode = BISS_TIMEOUT_ADAPTIVE;
        c.adaptive_min_ps = 2 * US;
        c.adaptive_max_ps = 20 * US;
    } else if (_i == 3) {
        c.timeout_mode = BISS_TIMEOUT_ADAPTIVE;
        c.adaptive_min_ps = 10 * NS;
        c.adaptive_max_ps = 20 * US;
    }
    bench *x[2] = {bench_new(&c, 100 * NS), bench_new(&c, 100 * NS)};
    if (_i == 4) {
        biss_slave_set_quick(&x[0]->b, false);
    }
    x[0]->r.slave = (sim_edge_sink){edge_quick_or_general, &x[0]->b};
    x[1]->r.slave = (sim_edge_sink){edge_general, &x[1]->b};
    quick_hits = quick_acks = quick_busy = quick_starts = 0;
    uint64_t seed = 0x9e3779b97f4a7c15u + (uint64_t)_i;
    sim_ps t = 2 * US, h = 100 * NS;
    int level = 1;
    unsigned long edges = 0;
    for (int k = 0; k < 20000; k++) {
        uint64_t r = next_rand(&seed);
        sim_ps gap = h;
        switch (r % 64) {
        case 0:
            gap = 25 * US + (sim_ps)(r >> 8) % (20 * US); /* past the timeout */
            h = 40 * NS + (sim_ps)(r >> 32) % (2 * US);   /* then another rate */
            break;
        case 1:
            gap = 1 * US + (sim_ps)(r >> 8) % (22 * US); /* around it */
            break;
        case 2:
            if ((r >> 8) % 16 == 0) {
                biss_slave_lose_sync(&x[0]->b, t + 1);
                biss_slave_lose_sync(&x[1]->b, t + 1);
            }
            break;
        default:
            break;
        }
        t += gap;
        level = !level;
        for (int i = 0; i < 2; i++) {
            rig_ma(&x[i]->r, t, level);
        }
        edges++;
    }
    for (int i = 0; i < 2; i++) {
        eq_run_until(&x[i]->r.q, t + 100 * US);
    }
    /* most edges take the quick step, the rest the general path; none
     * with the quick step off */
    if (_i == 4) {
        ck_assert_uint_eq(quick_hits, 0);
    } else {
        ck_assert_uint_gt(quick_hits, edges / 2);
        ck_assert_uint_lt(quick_hits, edges);
        ck_assert_uint_gt(quick_acks, 100);
        ck_assert_uint_gt(quick_starts, 100);
    }
    if (_i == 1) { /* busy clocks only here */
        ck_assert_uint_gt(quick_busy, 100);
    }
    ck_assert_uint_eq(x[0]->r.q.next_id, x[1]->r.q.next_id);
    ck_assert_uint_gt(x[0]->b.st.frames, 100);
    ck_assert_uint_eq(x[0]->b.st.frames, x[1]->b.st.frames);
    for (uint64_t n = x[0]->b.st.frames - BISS_RECORD_RING; n < x[0]->b.st.frames; n++) {
        ck_assert_int_eq(memcmp(biss_slave_record(&x[0]->b, n), biss_slave_record(&x[1]->b, n),
                                sizeof(biss_frame_record)),
                         0);
    }
    waveform *a = &x[0]->r.sl, *b = &x[1]->r.sl;
    ck_assert_uint_gt(a->len, 1000);
    ck_assert_uint_eq(a->len, b->len);
    for (size_t i = 0; i < a->len; i++) {
        ck_assert_int_eq(a->edges[i].t, b->edges[i].t);
        ck_assert_int_eq(a->edges[i].level, b->edges[i].level);
    }
    bench_free(x[0]);
    bench_free(x[1]);
}
END_TEST

int main(void) {
    Suite *s = suite_create("biss_slave");
    TCase *tc = tcase_create("frames");
    tcase_add_test(tc, frame_bits_12bit_crc6);
    tcase_add_test(tc, error_bit_active_low);
    tcase_add_test(tc, output_delay_after_ma_edge);
    tcase_add_test(tc, busy_time_delays_start_bit);
    tcase_add_test(tc, busy_time_boundary);
    tcase_add_test(tc, busy_clocks_delay_start_bit);
    tcase_add_test(tc, fixed_timeout_then_sl_high);
    tcase_add_test(tc, lost_slave_holds_sl_low_until_a_new_frame_ends);
    tcase_add_test(tc, adaptive_timeout_one_and_a_half_periods);
    tcase_add_test(tc, adaptive_timeout_floor);
    tcase_add_test(tc, incomplete_frame_times_out);
    tcase_add_test(tc, position_moves_between_frames);
    tcase_add_test(tc, position_latched_at_first_rising_edge);
    tcase_add_test(tc, position_wraps_and_runs_backwards);
    tcase_add_test(tc, register_read_over_frames);
    tcase_add_test(tc, daisy_chain_three_slaves);
    tcase_add_test(tc, chain_cds_from_addressed_slave);
    tcase_add_test(tc, register_write_over_frames_then_read_back);
    tcase_add_test(tc, command_in_chain_over_frames);
    tcase_add_test(tc, config_check_messages);
    tcase_add_test(tc, position_wraps_and_never_overflows);
    tcase_add_loop_test(tc, quick_step_matches_general, 0, 5);
    suite_add_tcase(s, tc);
    return check_run(s);
}
