/* The safety checks of proto/biss_safety.c on samples made here: the life
 * counter judged by frame numbers (frames the host did not read, the
 * counter's and the frame number's wrap, a frame read twice, a bad CRC, a
 * lost slave), position pairs (shifts, tolerance, the circular distance),
 * the nE/nW check of slaves that never set them (through the decoding of a
 * published result), the configuration errors and the command-line
 * spellings. */
#include "biss_proto.h"
#include "libbiss.h" /* biss_strerror: each code has its text */

#include "check_run.h"

#include <check.h>
#include <math.h>
#include <string.h>

/* Two BiSS Safety channels at 10 MHz: slave 0 a 24-bit position, slave 1 a
 * 20-bit one, each with nE/nW, a 6-bit life counter and CRC16 0x190D9,
 * start values 0 and 0x5A5A. */
static struct biss_config two_channels(void) {
    struct biss_config c;
    biss_config_default(&c);
    c.freq_hz = 10000000;
    c.nslaves = 2;
    for (unsigned i = 0; i < 2; i++) {
        c.slave[i] = (struct biss_slave_config){.data_bits = (i ? 20 : 24) + 2 + 6,
                                                .crc_bits = 16,
                                                .crc_poly = 0x190D9,
                                                .crc_start = i ? 0x5A5A : 0,
                                                .has_ew = true,
                                                .ew_shift = 6,
                                                .life_check = true};
    }
    c.npairs = 1;
    c.pair[0] = (struct biss_pair_check){
        .a = 0, .b = 1, .shift_b = 4, .tolerance = 16, .distinct_crc = true};
    return c;
}

/* 22.7 us in IEP counts: a free-running frame at 10 MHz. */
#define PERIOD 4541u

/* A valid frame: positions, life counters, both CRCs good; free-running
 * (one every PERIOD). */
static struct biss_sample frame(uint32_t n, uint64_t pos0, uint64_t pos1, uint32_t lc0,
                                uint32_t lc1) {
    struct biss_sample s;
    memset(&s, 0, sizeof s);
    s.frame = n;
    s.timestamp = n * PERIOD;
    s.valid = true;
    s.nslaves = 2;
    s.slave[0].position = pos0;
    s.slave[0].data = pos0 << 8 | 3u << 6 | (lc0 & 63);
    s.slave[1].position = pos1;
    s.slave[1].data = pos1 << 8 | 3u << 6 | (lc1 & 63);
    s.slave[0].crc_ok = s.slave[1].crc_ok = true;
    return s;
}

/* Judges frame n with both counters at lc; returns slave 0's flags. */
static uint32_t judge(const struct biss_config *c, struct biss_safety_state *st, uint32_t n,
                      uint32_t lc) {
    struct biss_sample s = frame(n, 1000, 1000 >> 4, lc, lc);
    biss_safety_check(c, st, &s);
    ck_assert_uint_eq(s.slave[0].safety, s.slave[1].safety);
    return s.slave[0].safety;
}

START_TEST(test_counter_every_frame) {
    struct biss_config c = two_channels();
    ck_assert_int_eq(biss_config_check(&c), BISS_OK);
    struct biss_safety_state st;
    biss_safety_init(&st);
    /* the first frame has nothing to compare with */
    ck_assert_uint_eq(judge(&c, &st, 10, 7) & BISS_SAFE_LC_CHECKED, 0);
    for (uint32_t n = 11; n < 200; n++) { /* the 6-bit counter wraps three times */
        uint32_t f = judge(&c, &st, n, 7 + (n - 10));
        ck_assert_uint_eq(f & (BISS_SAFE_LC_CHECKED | BISS_SAFE_FAULTS), BISS_SAFE_LC_CHECKED);
    }
    ck_assert_uint_eq(st.stats.lc_checked[0], 189);
    ck_assert_uint_eq(st.stats.lc_frozen[0] + st.stats.lc_skipped[0], 0);
}
END_TEST

/* The host polls: it reads frames 5, 9, 73 (a 64-frame gap looks like no
 * gap to a 6-bit counter), 74; each counter moved by the frames run. */
START_TEST(test_frames_the_host_did_not_read) {
    struct biss_config c = two_channels();
    struct biss_safety_state st;
    biss_safety_init(&st);
    static const uint32_t n[] = {5, 9, 73, 74, 200, 1000};
    for (size_t i = 0; i < sizeof n / sizeof n[0]; i++) {
        uint32_t f = judge(&c, &st, n[i], 40 + n[i]);
        ck_assert_uint_eq(f & BISS_SAFE_FAULTS, 0);
    }
    ck_assert_uint_eq(st.stats.lc_checked[1], 5);
    /* a counter that stood still over a gap of 3 frames is frozen */
    ck_assert_uint_eq(judge(&c, &st, 1003, 40 + 1000),
                      BISS_SAFE_LC_CHECKED | BISS_SAFE_LC_FROZEN | BISS_SAFE_PAIR_CHECKED);
    /* one that moved by 1 over a gap of 4 skipped */
    ck_assert_uint_eq(judge(&c, &st, 1007, 40 + 1001) & BISS_SAFE_FAULTS, BISS_SAFE_LC_SKIP);
    ck_assert_uint_eq(st.stats.lc_frozen[0], 1);
    ck_assert_uint_eq(st.stats.lc_skipped[0], 1);
}
END_TEST

/* Frame n (both counters at lc) judged as `reader` read it; its flags. */
static uint32_t read_by(const struct biss_config *c, struct biss_safety_readers *r, unsigned reader,
                        uint32_t n, uint32_t lc) {
    struct biss_sample s = frame(n, 1000, 1000 >> 4, lc, lc);
    biss_safety_readers_check(c, r, reader, &s, BISS_SAFETY_NO_CLOCK);
    return s.safety;
}

/* Two readers of one handle: the ring frames 1..30 in order, the newest
 * read frame 20 between its 10th and 11th; then a counter fault at 31..
 * seen by the newest read first. Each reader judges its frames in its own
 * order (ring frame 11 against 10, not against 20), the counts take each
 * frame once, in frame order; a restart forgets both readers' references. */
START_TEST(test_two_readers) {
    struct biss_config c = two_channels();
    struct biss_safety_readers r;
    memset(&r, 0, sizeof r);
    for (uint32_t n = 1; n <= 30; n++) {
        if (n == 11) { /* its first: no counter yet, the pair only */
            ck_assert_uint_eq(read_by(&c, &r, BISS_READER_NEWEST, 20, 20), BISS_SAFE_PAIR_CHECKED);
        }
        uint32_t f = read_by(&c, &r, BISS_READER_RING, n, n);
        ck_assert_uint_eq(f & BISS_SAFE_FAULTS, 0);
        ck_assert_uint_eq(f & BISS_SAFE_LC_CHECKED, n > 1 ? BISS_SAFE_LC_CHECKED : 0);
    }
    /* counted: ring 2..10, newest 20 (no counter: pair only), ring 21..30 */
    ck_assert_uint_eq(r.stats.lc_checked[0], 9 + 10);
    ck_assert_uint_eq(r.stats.pair_checked[0], 10 + 1 + 10);
    ck_assert_uint_eq(r.reader[BISS_READER_RING].stats.lc_checked[0], 29);
    /* the counter stands still from 31: the newest read (frame 40 against
     * 20) and the ring (31 against 30) each see it */
    ck_assert_uint_ne(read_by(&c, &r, BISS_READER_NEWEST, 40, 30) & BISS_SAFE_LC_SKIP, 0);
    ck_assert_uint_ne(read_by(&c, &r, BISS_READER_RING, 31, 30) & BISS_SAFE_LC_FROZEN, 0);
    ck_assert_uint_eq(r.stats.lc_skipped[0], 1);
    ck_assert_uint_eq(r.stats.lc_frozen[0], 0); /* frame 31 older than 40: not counted */
    /* a new configuration: no reference left in either reader, counts kept */
    biss_safety_readers_restart(&r);
    ck_assert_uint_eq(read_by(&c, &r, BISS_READER_RING, 50, 3) & BISS_SAFE_LC_CHECKED, 0);
    ck_assert_uint_eq(read_by(&c, &r, BISS_READER_NEWEST, 51, 9) & BISS_SAFE_LC_CHECKED, 0);
    ck_assert_uint_eq(r.stats.lc_checked[0], 9 + 10 + 1);
}
END_TEST

/* The firmware's frame number wraps at 2^32, the counter with it. */
START_TEST(test_frame_number_wraps) {
    struct biss_config c = two_channels();
    struct biss_safety_state st;
    biss_safety_init(&st);
    judge(&c, &st, 0xfffffffeu, 62);
    ck_assert_uint_eq(judge(&c, &st, 0xffffffffu, 63) & BISS_SAFE_FAULTS, 0);
    ck_assert_uint_eq(judge(&c, &st, 2, 2) & BISS_SAFE_FAULTS, 0); /* 3 frames later */
    ck_assert_uint_eq(judge(&c, &st, 3, 2) & BISS_SAFE_FAULTS, BISS_SAFE_LC_FROZEN);
}
END_TEST

START_TEST(test_frozen_and_skipping) {
    struct biss_config c = two_channels();
    struct biss_safety_state st;
    biss_safety_init(&st);
    judge(&c, &st, 1, 1);
    judge(&c, &st, 2, 2);
    for (uint32_t n = 3; n < 13; n++) { /* frozen at 2 */
        ck_assert_uint_eq(judge(&c, &st, n, 2) & BISS_SAFE_FAULTS, BISS_SAFE_LC_FROZEN);
    }
    for (uint32_t n = 13; n < 23; n++) { /* then by two a frame */
        ck_assert_uint_eq(judge(&c, &st, n, 2 + 2 * (n - 12)) & BISS_SAFE_FAULTS,
                          BISS_SAFE_LC_SKIP);
    }
    ck_assert_uint_eq(st.stats.lc_frozen[0], 10);
    ck_assert_uint_eq(st.stats.lc_skipped[1], 10);
    ck_assert_uint_eq(st.stats.lc_checked[0], 21);
}
END_TEST

/* A frame read twice keeps its verdict and is counted once. */
START_TEST(test_same_frame_read_again) {
    struct biss_config c = two_channels();
    struct biss_safety_state st;
    biss_safety_init(&st);
    judge(&c, &st, 1, 1);
    ck_assert_uint_eq(judge(&c, &st, 2, 1) & BISS_SAFE_FAULTS, BISS_SAFE_LC_FROZEN);
    ck_assert_uint_eq(judge(&c, &st, 2, 1) & BISS_SAFE_FAULTS, BISS_SAFE_LC_FROZEN);
    ck_assert_uint_eq(st.stats.lc_frozen[0], 1);
    ck_assert_uint_eq(st.stats.lc_checked[0], 1);
    ck_assert_uint_eq(st.stats.pair_checked[0], 2);
}
END_TEST

/* A word with a bad CRC is not judged and keeps the reference; a frame
 * without the slave (it may not have counted it) forgets it. */
START_TEST(test_bad_crc_and_lost_slave) {
    struct biss_config c = two_channels();
    struct biss_safety_state st;
    biss_safety_init(&st);
    judge(&c, &st, 1, 1);
    struct biss_sample s = frame(2, 1000, 1000 >> 4, 55, 2);
    s.slave[0].crc_ok = false;
    s.crc_error = true;
    biss_safety_check(&c, &st, &s);
    ck_assert_uint_eq(s.slave[0].safety, 0); /* no life check, no pair check */
    ck_assert_uint_eq(s.slave[1].safety, BISS_SAFE_LC_CHECKED);
    ck_assert_uint_eq(judge(&c, &st, 3, 3) & BISS_SAFE_FAULTS, 0); /* against frame 1 */
    struct biss_sample lost;
    memset(&lost, 0, sizeof lost);
    lost.frame = 4;
    lost.no_slave = true;
    biss_safety_check(&c, &st, &lost);
    ck_assert_uint_eq(lost.safety, 0);
    /* the slave missed frame 4: its counter says 4 at frame 5, no fault */
    ck_assert_uint_eq(judge(&c, &st, 5, 4) & BISS_SAFE_LC_CHECKED, 0);
    ck_assert_uint_eq(judge(&c, &st, 6, 5) & BISS_SAFE_FAULTS, 0);
    ck_assert_uint_eq(st.stats.lc_frozen[0] + st.stats.lc_skipped[0], 0);
}
END_TEST

/* 24 bits against 20 bits shifted by 4: within 16 counts, and the
 * distance is circular (one word wrapped before the other). */
START_TEST(test_pairs) {
    struct biss_config c = two_channels();
    c.slave[0].life_check = c.slave[1].life_check = false;
    struct biss_safety_state st;
    biss_safety_init(&st);
    static const struct {
        uint64_t a, b;
        int64_t diff;
        bool bad;
    } t[] = {
        {0x123456, 0x12345, 6, false},        {0x123440, 0x12345, -16, false},
        {0x12343f, 0x12345, -17, true},       {0x123461, 0x12345, 17, true},
        {0x000003, 0xfffff, 19, true}, /* across the wrap: 19 counts, not 2^24 - 19 */
        {0x000003, 0x00000, 3, false},        {0xfffff8, 0x00000, -8, false}, /* b wrapped first */
        {0x800000, 0x00000, -0x800000, true},
    };
    for (unsigned i = 0; i < sizeof t / sizeof t[0]; i++) {
        struct biss_sample s = frame(i + 1, t[i].a, t[i].b, 0, 0);
        biss_safety_check(&c, &st, &s);
        ck_assert_int_eq(st.stats.pair_last_diff[0], t[i].diff);
        ck_assert_uint_eq(s.slave[0].safety,
                          BISS_SAFE_PAIR_CHECKED | (t[i].bad ? BISS_SAFE_DISAGREE : 0));
        ck_assert_uint_eq(s.safety, s.slave[0].safety);
    }
    ck_assert_uint_eq(st.stats.pair_checked[0], 8);
    ck_assert_uint_eq(st.stats.pair_disagree[0], 4);
    /* one bad CRC: not compared */
    struct biss_sample s = frame(100, 0, 0x80000, 0, 0);
    s.slave[1].crc_ok = false;
    biss_safety_check(&c, &st, &s);
    ck_assert_uint_eq(s.safety, 0);
    ck_assert_uint_eq(st.stats.pair_checked[0], 8);
}
END_TEST

/* Each wrong check has its own code. */
START_TEST(test_config_errors) {
    struct biss_config c = two_channels();
    c.slave[0].life_bits = 7; /* the counter is the 6 bits below nW */
    ck_assert_int_eq(biss_config_check(&c), BISS_E_SAFETY_LIFE);
    c.slave[0].life_bits = 33;
    ck_assert_int_eq(biss_config_check(&c), BISS_E_SAFETY_LIFE);
    c.slave[0].life_bits = 3; /* part of it: fine */
    ck_assert_int_eq(biss_config_check(&c), BISS_OK);
    c = two_channels();
    c.slave[2].life_check = true; /* no slave 2 */
    ck_assert_int_eq(biss_config_check(&c), BISS_E_SAFETY_LIFE);
    c = two_channels();
    c.slave[1].ew_shift = 0; /* no counter bits left */
    c.slave[1].data_bits = 22;
    ck_assert_int_eq(biss_config_check(&c), BISS_E_SAFETY_LIFE);
    c = two_channels();
    c.slave[1].has_ew = false; /* without nE/nW: life_bits says where */
    c.slave[1].pos_bits = 20;
    ck_assert_int_eq(biss_config_check(&c), BISS_E_SAFETY_LIFE);
    c.slave[1].life_bits = 8;
    ck_assert_int_eq(biss_config_check(&c), BISS_OK);
    c.slave[1].life_bits = 9; /* into the position */
    ck_assert_int_eq(biss_config_check(&c), BISS_E_SAFETY_LIFE);

    c = two_channels();
    c.pair[0].b = 0;
    ck_assert_int_eq(biss_config_check(&c), BISS_E_SAFETY_PAIR);
    c.pair[0].b = 2;
    ck_assert_int_eq(biss_config_check(&c), BISS_E_SAFETY_PAIR);
    c = two_channels();
    c.pair[0].shift_b = 45; /* 20 + 45 > 64 */
    ck_assert_int_eq(biss_config_check(&c), BISS_E_SAFETY_PAIR);
    c = two_channels();
    c.npairs = BISS_API_MAX_PAIRS + 1;
    ck_assert_int_eq(biss_config_check(&c), BISS_E_SAFETY_PAIR);

    /* the two channels' CRCs must differ, in start value or polynomial */
    c = two_channels();
    c.slave[1].crc_start = 0;
    ck_assert_int_eq(biss_config_check(&c), BISS_E_SAFETY_CRC);
    c.pair[0].distinct_crc = false; /* two separate encoders: allowed */
    ck_assert_int_eq(biss_config_check(&c), BISS_OK);
    c = two_channels();
    c.slave[1].crc_start = 0;
    c.slave[1].crc_bits = 6;
    c.slave[1].crc_poly = 0x43;
    ck_assert_int_eq(biss_config_check(&c), BISS_OK);
    ck_assert_str_ne(biss_strerror(BISS_E_SAFETY_CRC), "unknown error");
    ck_assert_str_ne(biss_strerror(BISS_E_SAFETY_LIFE), biss_strerror(BISS_E_SAFETY_PAIR));
}
END_TEST

START_TEST(test_command_line_spellings) {
    struct biss_config k;
    memset(&k, 0, sizeof k);
    ck_assert_int_eq(biss_safety_parse_life("2", &k), BISS_OK);
    ck_assert(k.slave[2].life_check);
    ck_assert_uint_eq(k.slave[2].life_bits, 0);
    ck_assert_int_eq(biss_safety_parse_life("1,6", &k), BISS_OK);
    ck_assert_uint_eq(k.slave[1].life_bits, 6);
    static const char *const bad_life[] = {"", "8", "1,0", "1,33", "-1", "1,", "1,2,3", "x"};
    for (size_t i = 0; i < sizeof bad_life / sizeof bad_life[0]; i++) {
        ck_assert_msg(biss_safety_parse_life(bad_life[i], &k) == BISS_E_INVAL, "%s", bad_life[i]);
    }
    ck_assert_int_eq(biss_safety_parse_pair("0,1,16,0,4", &k), BISS_OK);
    ck_assert_uint_eq(k.npairs, 1);
    ck_assert_uint_eq(k.pair[0].shift_b, 4);
    ck_assert_uint_eq(k.pair[0].tolerance, 16);
    ck_assert(k.pair[0].distinct_crc);
    static const char *const bad_pair[] = {"0,1", "0,1,2,3", "0,8,1", "0,1,1,64,0", "0,1,,2"};
    for (size_t i = 0; i < sizeof bad_pair / sizeof bad_pair[0]; i++) {
        ck_assert_msg(biss_safety_parse_pair(bad_pair[i], &k) == BISS_E_INVAL, "%s", bad_pair[i]);
    }
    for (int i = 0; i < 3; i++) {
        ck_assert_int_eq(biss_safety_parse_pair("2,3,0x10", &k), BISS_OK);
    }
    ck_assert_int_eq(biss_safety_parse_pair("2,3,1", &k), BISS_E_SAFETY_PAIR);
    /* merged onto a layout from elsewhere */
    struct biss_config c = two_channels();
    c.slave[0].life_check = c.slave[1].life_check = false;
    c.npairs = 0;
    ck_assert_int_eq(biss_safety_merge(&c, &k), BISS_OK);
    ck_assert(c.slave[1].life_check && c.slave[2].life_check && !c.slave[0].life_check);
    ck_assert_uint_eq(c.npairs, 4);
    ck_assert_int_eq(biss_safety_merge(&c, &k), BISS_E_SAFETY_PAIR);
}
END_TEST

/* ---- nE/nW of a slave that never sets them (ew_static) ---- */

/* A published result of the two channels, as the firmware writes it: both
 * CRCs good, slave 0's nE and nW as given (1: inactive), slave 1's 1, 1. */
static struct biss_sample published(const struct biss_config *c, uint32_t n, int nE, int nW,
                                    bool crc_ok) {
    struct biss_shm_result r;
    memset(&r, 0, sizeof r);
    r.frame = n;
    r.timestamp = n * PERIOD;
    r.flags = BISS_RF_VALID | (crc_ok ? 0 : BISS_RF_CRC_ERROR);
    r.nslaves = 2;
    r.half = 10;
    for (unsigned i = 0; i < 2; i++) {
        unsigned e = i ? 1 : (unsigned)nE, w = i ? 1 : (unsigned)nW;
        r.slave[i].data_lo = 1000u << 8 | e << 7 | w << 6 | (n & 63);
        r.slave[i].status =
            (i || crc_ok ? BISS_RS_CRC_OK : 0) | (e ? BISS_RS_NE : 0) | (w ? BISS_RS_NW : 0);
    }
    struct biss_sample s;
    ck_assert_int_eq(biss_sample_decode(c, true, n, &r, &s), BISS_OK);
    return s;
}

START_TEST(test_ew_static) {
    struct biss_config c = two_channels();
    c.npairs = 0;
    c.slave[0].life_check = c.slave[1].life_check = false;
    struct biss_safety_state st;
    biss_safety_init(&st);
    /* without the option an active nE/nW is the encoder's report: valid */
    struct biss_sample s = published(&c, 1, 0, 1, true);
    biss_safety_check(&c, &st, &s);
    ck_assert(s.valid && !s.misframed && s.slave[0].error);
    ck_assert_uint_eq(s.safety, 0);

    c.slave[0].ew_static = true;
    ck_assert_int_eq(biss_config_check(&c), BISS_OK);
    biss_safety_restart(&st);
    s = published(&c, 2, 1, 1, true); /* inactive: checked, valid */
    biss_safety_check(&c, &st, &s);
    ck_assert(s.valid && !s.misframed);
    ck_assert_uint_eq(s.slave[0].safety, BISS_SAFE_EW_CHECKED);
    ck_assert_uint_eq(s.slave[1].safety, 0); /* no option on slave 1 */
    static const int bits[][2] = {{0, 1}, {1, 0}, {0, 0}};
    for (unsigned k = 0; k < 3; k++) {
        s = published(&c, 3 + k, bits[k][0], bits[k][1], true);
        biss_safety_check(&c, &st, &s);
        ck_assert_msg(!s.valid && s.misframed, "nE %d nW %d", bits[k][0], bits[k][1]);
        ck_assert_uint_eq(s.slave[0].safety, BISS_SAFE_EW_CHECKED | BISS_SAFE_EW_SET);
        ck_assert(s.safety & BISS_SAFE_FAULTS);
        ck_assert_uint_eq(s.flags & BISS_RF_VALID, BISS_RF_VALID); /* as published */
    }
    /* read again: the same verdict, counted once */
    s = published(&c, 5, 0, 0, true);
    biss_safety_check(&c, &st, &s);
    ck_assert(!s.valid && s.misframed);
    /* a word with a bad CRC is refused already: not judged */
    s = published(&c, 6, 0, 0, false);
    biss_safety_check(&c, &st, &s);
    ck_assert(s.valid && s.crc_error && !s.misframed);
    ck_assert_uint_eq(s.slave[0].safety, 0);
    ck_assert_uint_eq(st.stats.ew_checked[0], 4);
    ck_assert_uint_eq(st.stats.ew_set[0], 3);
    ck_assert_uint_eq(st.stats.ew_checked[1], 0);
}
END_TEST

/* A misframed frame is not judged by the life counter, and the counter's
 * reference stays: the next good frame is checked against the last good
 * one. */
START_TEST(test_ew_static_and_life) {
    struct biss_config c = two_channels();
    c.npairs = 0;
    c.slave[0].ew_static = true;
    struct biss_safety_state st;
    biss_safety_init(&st);
    struct biss_sample s = published(&c, 10, 1, 1, true);
    biss_safety_check(&c, &st, &s);
    s = published(&c, 11, 1, 0, true);
    biss_safety_check(&c, &st, &s);
    ck_assert(s.misframed);
    ck_assert_uint_eq(s.slave[0].safety & BISS_SAFE_LC_CHECKED, 0);
    ck_assert_uint_eq(s.slave[1].safety & BISS_SAFE_LC_CHECKED, 0);
    s = published(&c, 12, 1, 1, true);
    biss_safety_check(&c, &st, &s);
    ck_assert(s.valid && !s.misframed);
    ck_assert_uint_eq(s.slave[0].safety, BISS_SAFE_EW_CHECKED | BISS_SAFE_LC_CHECKED);
    ck_assert_uint_eq(st.stats.lc_frozen[0] + st.stats.lc_skipped[0], 0);
}
END_TEST

/* A slave that sends no nE/nW, or none at all, cannot take the option. */
START_TEST(test_ew_static_config) {
    struct biss_config c = two_channels();
    c.slave[1].ew_static = true;
    ck_assert_int_eq(biss_config_check(&c), BISS_OK);
    c.slave[1].has_ew = false;
    c.slave[1].life_bits = 6;
    c.slave[1].pos_bits = 20;
    ck_assert_int_eq(biss_config_check(&c), BISS_E_SAFETY_EW);
    c = two_channels();
    c.slave[2].ew_static = true; /* no slave 2 */
    ck_assert_int_eq(biss_config_check(&c), BISS_E_SAFETY_EW);
    ck_assert_str_ne(biss_strerror(BISS_E_SAFETY_EW), "unknown error");
    struct biss_config k;
    memset(&k, 0, sizeof k);
    ck_assert_int_eq(biss_safety_parse_ew("1", &k), BISS_OK);
    ck_assert(k.slave[1].ew_static && !k.slave[0].ew_static);
    static const char *const bad[] = {"", "8", "-1", "1,2", "x", "1,"};
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        ck_assert_msg(biss_safety_parse_ew(bad[i], &k) == BISS_E_INVAL, "%s", bad[i]);
    }
    c = two_channels();
    ck_assert_int_eq(biss_safety_merge(&c, &k), BISS_OK);
    ck_assert(c.slave[1].ew_static && !c.slave[0].ew_static);
}
END_TEST

/* ---- the position within reach of the last one accepted (max_speed) ---- */

/* Two channels with only slave 0's speed check (50000 counts/s). */
static struct biss_config speed_checked(void) {
    struct biss_config c = two_channels();
    c.npairs = 0;
    c.slave[0].life_check = c.slave[1].life_check = false;
    c.slave[0].max_speed = 50000.0;
    return c;
}

/* Judges a frame with slave 0 at pos, IEP timestamp ts; returns slave 0's
 * flags (the frame's validity in *valid). */
static uint32_t at(const struct biss_config *c, struct biss_safety_state *st, uint32_t n,
                   uint32_t ts, uint64_t pos, bool *valid) {
    struct biss_sample s = frame(n, pos, 1000, 0, 0);
    s.timestamp = ts;
    biss_safety_check(c, st, &s);
    ck_assert_uint_eq(s.slave[1].safety, 0);
    ck_assert(s.misframed == !s.valid);
    *valid = s.valid;
    return s.slave[0].safety;
}

START_TEST(test_speed_free_run) {
    struct biss_config c = speed_checked();
    struct biss_safety_state st;
    biss_safety_init(&st);
    bool v;
    const uint32_t us20 = 4000; /* 20 us in IEP counts: 1 count of motion, reach 2 */
    ck_assert_uint_eq(at(&c, &st, 1, 0, 1000, &v), 0); /* the first: nothing to compare */
    ck_assert(v);
    ck_assert_uint_eq(at(&c, &st, 2, us20, 1002, &v), BISS_SAFE_POS_CHECKED);
    ck_assert(v);
    ck_assert_uint_eq(at(&c, &st, 3, 2 * us20, 1005, &v),
                      BISS_SAFE_POS_CHECKED | BISS_SAFE_POS_JUMP);
    ck_assert(!v);
    /* the refused position is no reference: 40 us from 1002 reach 3 */
    ck_assert_uint_eq(at(&c, &st, 4, 3 * us20, 999, &v), BISS_SAFE_POS_CHECKED);
    ck_assert(v);
    ck_assert_uint_eq(st.stats.pos_checked[0], 3);
    ck_assert_uint_eq(st.stats.pos_jumped[0], 1);
    /* a word with a bad CRC is not judged and changes nothing */
    struct biss_sample s = frame(5, 3000, 1000, 0, 0);
    s.timestamp = 4 * us20;
    s.slave[0].crc_ok = false;
    biss_safety_check(&c, &st, &s);
    ck_assert_uint_eq(s.slave[0].safety, 0);
    ck_assert_uint_eq(at(&c, &st, 6, 5 * us20, 997, &v), BISS_SAFE_POS_CHECKED);
    /* the position's and the timestamp's wraps are no jumps */
    uint64_t top = (1u << 24) - 1;
    biss_safety_init(&st);
    at(&c, &st, 1, 0xfffff000u, top, &v);
    ck_assert_uint_eq(at(&c, &st, 2, 0x00000f00u, 1, &v), BISS_SAFE_POS_CHECKED);
    ck_assert(v); /* 39.7 us: reach 2.98, moved 2 */
    ck_assert_uint_eq(at(&c, &st, 3, 0x00000f00u + us20, top - 1, &v),
                      BISS_SAFE_POS_CHECKED | BISS_SAFE_POS_JUMP);
    /* a reach of half the circle or more judges nothing (8 bits: 128) */
    c.slave[0].pos_bits = 8;
    biss_safety_init(&st);
    at(&c, &st, 1, 0, 10, &v);
    ck_assert_uint_eq(at(&c, &st, 2, 500000, 130, &v), BISS_SAFE_POS_CHECKED); /* 2.5 ms */
    ck_assert_uint_eq(at(&c, &st, 4, 500000 + 520000, 10, &v), 0);             /* 2.6 ms: 131 */
    ck_assert(v);
}
END_TEST

START_TEST(test_speed_resync) {
    /* two frames in a row that agree with each other, not with the
     * reference: the second is taken (the encoder was set to a new
     * position, or the reference was wrong); one alone is refused */
    struct biss_config c = speed_checked();
    struct biss_safety_state st;
    biss_safety_init(&st);
    bool v;
    const uint32_t us20 = 4000;
    at(&c, &st, 1, 0, 1000, &v);
    ck_assert_uint_eq(at(&c, &st, 2, us20, 5000, &v), BISS_SAFE_POS_CHECKED | BISS_SAFE_POS_JUMP);
    ck_assert(!v);
    ck_assert_uint_eq(at(&c, &st, 3, 2 * us20, 1003, &v), BISS_SAFE_POS_CHECKED);
    ck_assert(v); /* back in reach of 1000: 5000 was one wrong frame */
    ck_assert_uint_eq(at(&c, &st, 4, 3 * us20, 9000, &v),
                      BISS_SAFE_POS_CHECKED | BISS_SAFE_POS_JUMP);
    ck_assert_uint_eq(at(&c, &st, 5, 4 * us20, 9001, &v), BISS_SAFE_POS_CHECKED);
    ck_assert(v);
    ck_assert_uint_eq(at(&c, &st, 6, 5 * us20, 9002, &v), BISS_SAFE_POS_CHECKED);
    ck_assert_uint_eq(st.stats.pos_jumped[0], 2);
    ck_assert_uint_eq(st.stats.pos_resync[0], 1);
    ck_assert_uint_eq(st.stats.pos_checked[0], 5);
    /* two wrong frames far from each other take nothing over */
    at(&c, &st, 7, 6 * us20, 100, &v);
    ck_assert(!v);
    ck_assert_uint_eq(at(&c, &st, 8, 7 * us20, 200, &v),
                      BISS_SAFE_POS_CHECKED | BISS_SAFE_POS_JUMP);
    ck_assert_uint_eq(at(&c, &st, 9, 8 * us20, 9005, &v), BISS_SAFE_POS_CHECKED);
    ck_assert(v);
}
END_TEST

START_TEST(test_speed_iep) {
    /* IEP trigger: the count restarts each period, the frame numbers tell
     * the time (100 us a frame: reach 5 per frame, plus 1) */
    struct biss_config c = speed_checked();
    c.trigger = BISS_TRIGGER_IEP;
    c.iep_period_ns = 100000;
    struct biss_safety_state st;
    biss_safety_init(&st);
    bool v;
    at(&c, &st, 10, 7, 1000, &v);
    ck_assert_uint_eq(at(&c, &st, 12, 7, 1011, &v), BISS_SAFE_POS_CHECKED);
    ck_assert_uint_eq(at(&c, &st, 13, 7, 1018, &v), BISS_SAFE_POS_CHECKED | BISS_SAFE_POS_JUMP);
    ck_assert(!v);
    /* following another channel's IEP: timed by that channel's period */
    c.trigger = BISS_TRIGGER_IEP_FOLLOW;
    ck_assert_int_eq(biss_config_check(&c), BISS_OK);
    biss_safety_init(&st);
    at(&c, &st, 1, 7, 1000, &v);
    ck_assert_uint_eq(at(&c, &st, 2, 7, 1006, &v), BISS_SAFE_POS_CHECKED);
    ck_assert_uint_eq(at(&c, &st, 3, 7, 3000, &v), BISS_SAFE_POS_CHECKED | BISS_SAFE_POS_JUMP);
    ck_assert(!v);
    /* and without a period the check refuses to be configured (it has no
     * time to judge by), on either IEP trigger */
    c.iep_period_ns = 0;
    ck_assert_int_eq(biss_config_check(&c), BISS_E_SAFETY_SPEED);
    c.trigger = BISS_TRIGGER_IEP;
    ck_assert_int_eq(biss_safety_config_check(&c), BISS_E_SAFETY_SPEED);
    c.slave[0].max_speed = 0;
    ck_assert_int_eq(biss_safety_config_check(&c), BISS_OK);
}
END_TEST

/* Free-running: the timestamps tell the time from one frame start to the
 * other, however long the master waited for the slave; a count that went
 * backwards (another channel's IEP trigger restarts it every period) tells
 * none: the position is not judged, neither passed as within reach nor
 * refused (BISS_SAFE_POS_UNTIMED), and becomes the reference, by which
 * the next frame is judged. */
START_TEST(test_speed_free_run_count_restarted) {
    struct biss_config c = speed_checked(); /* 50 000 counts/s: 1.1 a frame, reach 2.1 */
    struct biss_safety_state st;
    biss_safety_init(&st);
    bool v;
    at(&c, &st, 1, 0, 1000, &v);
    /* one frame on, four frame times later (the master waited): reach 5.5 */
    ck_assert_uint_eq(at(&c, &st, 2, 4 * PERIOD, 1004, &v), BISS_SAFE_POS_CHECKED);
    ck_assert(v);
    ck_assert_uint_eq(at(&c, &st, 3, 100, 1005, &v), BISS_SAFE_POS_UNTIMED);
    ck_assert(v);
    ck_assert_uint_eq(at(&c, &st, 4, 100 + PERIOD, 1006, &v), BISS_SAFE_POS_CHECKED);
    ck_assert(v);
    ck_assert_uint_eq(at(&c, &st, 5, 100 + 2 * PERIOD, 1010, &v),
                      BISS_SAFE_POS_CHECKED | BISS_SAFE_POS_JUMP);
    ck_assert(!v);
    /* the same frame time again (no time passed, or a whole wrap) tells none either */
    ck_assert_uint_eq(at(&c, &st, 6, 100 + PERIOD, 1006, &v), BISS_SAFE_POS_UNTIMED);
    ck_assert(v);
    ck_assert_uint_eq(st.stats.pos_untimed[0], 2);
    ck_assert_uint_eq(st.stats.pos_checked[0], 3);
    ck_assert_uint_eq(st.stats.pos_jumped[0], 1);
    ck_assert_uint_eq(st.stats.pos_resync[0], 0);
}
END_TEST

/* Host trigger: the timestamps alone (the host chooses when frames run);
 * a count that went backwards tells no time: the position is not judged
 * and becomes the reference; the next frame is judged by it. */
START_TEST(test_speed_host_trigger) {
    struct biss_config c = speed_checked();
    c.trigger = BISS_TRIGGER_HOST;
    struct biss_safety_state st;
    biss_safety_init(&st);
    bool v;
    at(&c, &st, 1, 1000, 1000, &v);
    at(&c, &st, 2, 1000 + PERIOD, 1001, &v);
    /* 1 ms later, 40 counts on: within 51 */
    ck_assert_uint_eq(at(&c, &st, 3, 1000 + PERIOD + 200000, 1041, &v), BISS_SAFE_POS_CHECKED);
    ck_assert(v);
    ck_assert_uint_eq(at(&c, &st, 4, 500, 1041, &v), BISS_SAFE_POS_UNTIMED);
    ck_assert(v);
    ck_assert_uint_eq(at(&c, &st, 5, 500 + PERIOD, 1042, &v), BISS_SAFE_POS_CHECKED);
    ck_assert(v);
}
END_TEST

/* A host polling slower than every 10.7 s (host trigger): from 2^31 IEP
 * counts on (half the counter), a count that ran on reads as one that went
 * back, so the time since the reference is not known. Such a frame is not
 * judged by the speed check, neither passed nor refused: it is valid and
 * its position becomes the reference; from there the check judges again.
 * The gaps at the edge, 2^31 - 1 (judged: 10.74 s, reach 536 871), 2^31,
 * 2^31 + 1 and 2^32 - 1, each with the encoder far from where it was;
 * then a host polling every 11 s while the encoder turns at 40 000
 * counts/s: every frame valid. (Before, every frame from the first such
 * gap on was refused: the reference never renewed.) */
START_TEST(test_speed_slow_poller) {
    struct biss_config c = speed_checked();
    c.trigger = BISS_TRIGGER_HOST;
    struct biss_safety_state st;
    biss_safety_init(&st);
    bool v;
    uint32_t ts = 1000;
    uint64_t pos = 1000;
    at(&c, &st, 1, ts, pos, &v);
    ts += 0x7fffffffu;
    pos += 536000;
    ck_assert_uint_eq(at(&c, &st, 2, ts, pos, &v), BISS_SAFE_POS_CHECKED);
    ck_assert(v);
    static const uint32_t gap[] = {0x80000000u, 0x80000001u, 0xffffffffu};
    for (unsigned k = 0; k < 3; k++) {
        ts += gap[k];
        pos += 3000000;
        uint32_t f = at(&c, &st, 3 + k, ts, pos, &v);
        ck_assert_msg(v, "a frame 0x%x counts on refused (0x%x)", gap[k], f);
        ck_assert_uint_eq(f, BISS_SAFE_POS_UNTIMED);
    }
    /* judged again from the last one: 1 ms on, reach 51 */
    ck_assert_uint_eq(at(&c, &st, 6, ts + 200000, pos + 50, &v), BISS_SAFE_POS_CHECKED);
    ck_assert(v);
    ck_assert_uint_eq(at(&c, &st, 7, ts + 400000, pos + 150, &v),
                      BISS_SAFE_POS_CHECKED | BISS_SAFE_POS_JUMP);
    ck_assert(!v);
    ck_assert_uint_eq(st.stats.pos_untimed[0], 3);
    ck_assert_uint_eq(st.stats.pos_checked[0], 3);
    ck_assert_uint_eq(st.stats.pos_jumped[0], 1);
    /* every 11 s (2.2 * 10^9 counts), 440 000 counts on each time */
    biss_safety_init(&st);
    ts = 7;
    pos = 0;
    for (uint32_t n = 1; n <= 20; n++, ts += 2200000000u, pos += 440000) {
        uint32_t f = at(&c, &st, n, ts, pos & 0xffffff, &v);
        ck_assert_msg(v, "frame %u refused (0x%x)", n, f);
        ck_assert_uint_eq(f, n == 1 ? 0 : BISS_SAFE_POS_UNTIMED);
    }
    ck_assert_uint_eq(st.stats.pos_untimed[0], 19);
    ck_assert_uint_eq(st.stats.pos_jumped[0] + st.stats.pos_checked[0], 0);
}
END_TEST

/* Frame n with slave 0 at pos, IEP timestamp ts, read at the host's clock
 * read_us; slave 0's flags, the frame's validity in *valid. */
static uint32_t read_at(const struct biss_config *c, struct biss_safety_state *st, uint32_t n,
                        uint32_t ts, uint64_t pos, uint64_t read_us, bool *valid) {
    struct biss_sample s = frame(n, pos, 1000, 0, 0);
    s.timestamp = ts;
    biss_safety_check_read(c, st, &s, read_us);
    ck_assert(s.misframed == !s.valid);
    *valid = s.valid;
    return s.slave[0].safety;
}

/* A count that came round once more between two frames reads as a short
 * time: only the host's clock tells. Frames read 22 s apart by it, 22 s of
 * IEP counts on (2^32 + 0.53 s: the count says 0.53 s, reach 26 844), the
 * encoder 880 000 counts on: not judged, not refused (with no clock, as
 * the bench judges, refused). Read 2^31 counts' time apart (10 737 418.24
 * us) or more, a frame is not judged; under it, judged by its count. Under
 * the IEP trigger the same by the frame numbers: 2^31 periods. */
START_TEST(test_speed_clock_came_round) {
    struct biss_config c = speed_checked();
    c.trigger = BISS_TRIGGER_HOST;
    struct biss_safety_state st;
    biss_safety_init(&st);
    bool v;
    const uint32_t s22 = (uint32_t)(22ull * 200000000u); /* modulo 2^32 */
    const uint64_t t0 = 5000000;
    ck_assert_uint_eq(read_at(&c, &st, 1, 100, 1000, t0, &v), 0);
    for (uint32_t k = 1; k <= 3; k++) {
        uint32_t f =
            read_at(&c, &st, 1 + k, 100 + k * s22, 1000 + k * 880000, t0 + k * 22000000u, &v);
        ck_assert_msg(v && f == BISS_SAFE_POS_UNTIMED, "frame %u 22 s on: 0x%x", 1 + k, f);
    }
    ck_assert_uint_eq(st.stats.pos_untimed[0], 3);
    /* the same frames with no clock: judged by the count alone, refused */
    biss_safety_init(&st);
    read_at(&c, &st, 1, 100, 1000, BISS_SAFETY_NO_CLOCK, &v);
    ck_assert_uint_eq(read_at(&c, &st, 2, 100 + s22, 881000, BISS_SAFETY_NO_CLOCK, &v),
                      BISS_SAFE_POS_CHECKED | BISS_SAFE_POS_JUMP);
    /* the clock's edge: 1 ms of counts (reach 51), read 10 737 418 us
     * apart (judged) or 10 737 419 us (not) */
    biss_safety_init(&st);
    read_at(&c, &st, 1, 100, 1000, t0, &v);
    ck_assert_uint_eq(read_at(&c, &st, 2, 200100, 1040, t0 + 10737418u, &v), BISS_SAFE_POS_CHECKED);
    ck_assert_uint_eq(read_at(&c, &st, 3, 400100, 1080, t0 + 2 * 10737418u, &v),
                      BISS_SAFE_POS_CHECKED);
    ck_assert_uint_eq(read_at(&c, &st, 4, 600100, 5000, t0 + 3 * 10737418u + 1, &v),
                      BISS_SAFE_POS_UNTIMED);
    ck_assert(v);
    ck_assert_uint_eq(read_at(&c, &st, 5, 800100, 5100, t0 + 3 * 10737418u + 2, &v),
                      BISS_SAFE_POS_CHECKED | BISS_SAFE_POS_JUMP);
    ck_assert(!v);
    /* a clock not known on either side: the count alone */
    ck_assert_uint_eq(read_at(&c, &st, 6, 1000100, 5040, BISS_SAFETY_NO_CLOCK, &v),
                      BISS_SAFE_POS_CHECKED);
    /* IEP trigger, 100 us a frame: 2^31 periods are 214 748.3648 s */
    c.trigger = BISS_TRIGGER_IEP;
    c.iep_period_ns = 100000;
    biss_safety_init(&st);
    read_at(&c, &st, 10, 7, 1000, t0, &v);
    ck_assert_uint_eq(read_at(&c, &st, 12, 7, 1011, t0 + 214748364799u, &v), BISS_SAFE_POS_CHECKED);
    ck_assert_uint_eq(read_at(&c, &st, 14, 7, 1022, t0 + 2 * 214748364799u + 1, &v),
                      BISS_SAFE_POS_UNTIMED);
    /* and the frame numbers past half their range */
    ck_assert_uint_eq(read_at(&c, &st, 14 + 0x80000000u, 7, 1022, BISS_SAFETY_NO_CLOCK, &v),
                      BISS_SAFE_POS_UNTIMED);
    ck_assert_uint_eq(read_at(&c, &st, 15 + 0x80000000u, 7, 1027, BISS_SAFETY_NO_CLOCK, &v),
                      BISS_SAFE_POS_CHECKED);
}
END_TEST

START_TEST(test_speed_and_ew) {
    /* a frame the nE/nW check refused does not become the reference */
    struct biss_config c = speed_checked();
    c.slave[0].ew_static = true;
    struct biss_safety_state st;
    biss_safety_init(&st);
    struct biss_sample s = published(&c, 1, 1, 1, true);
    biss_safety_check(&c, &st, &s);
    ck_assert(s.valid);
    s = published(&c, 2, 1, 0, true);
    s.slave[0].position = 5000;
    biss_safety_check(&c, &st, &s);
    ck_assert(s.misframed && (s.slave[0].safety & BISS_SAFE_POS_JUMP));
    /* nor is it a witness against the reference: the next frame with the
     * same position is refused as well */
    s = published(&c, 3, 1, 1, true);
    s.slave[0].position = 5000;
    biss_safety_check(&c, &st, &s);
    ck_assert(s.misframed && (s.slave[0].safety & BISS_SAFE_POS_JUMP));
    ck_assert_uint_eq(st.stats.pos_resync[0], 0);
    s = published(&c, 4, 1, 1, true);
    biss_safety_check(&c, &st, &s);
    ck_assert(s.valid && s.slave[0].safety == (BISS_SAFE_EW_CHECKED | BISS_SAFE_POS_CHECKED));
}
END_TEST

START_TEST(test_speed_config) {
    struct biss_config c = speed_checked();
    ck_assert_int_eq(biss_config_check(&c), BISS_OK);
    /* the range the scenario files take, 1e-9..1e18 (biss/biss_rules.h) */
    static const double bad[] = {-1.0, NAN, INFINITY, 1e308, 1.01e18, 0.99e-9, 5e-324};
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        c.slave[0].max_speed = bad[i];
        ck_assert_int_eq(biss_config_check(&c), BISS_E_SAFETY_SPEED);
    }
    c = speed_checked();
    c.slave[2].max_speed = 1.0; /* no slave 2 */
    ck_assert_int_eq(biss_config_check(&c), BISS_E_SAFETY_SPEED);
    ck_assert_str_ne(biss_strerror(BISS_E_SAFETY_SPEED), "unknown error");
    struct biss_config k;
    memset(&k, 0, sizeof k);
    ck_assert_int_eq(biss_safety_parse_speed("1,6e4", &k), BISS_OK);
    ck_assert(k.slave[1].max_speed == 60000.0 && k.slave[0].max_speed == 0);
    ck_assert_int_eq(biss_safety_parse_speed("2,1e18", &k), BISS_OK);
    ck_assert_int_eq(biss_safety_parse_speed("2,1e-9", &k), BISS_OK);
    k.slave[2].max_speed = 0;
    static const char *const spell[] = {"",      "0",       "0,",      "0,0",    "0,-5",   "8,1",
                                        "0,nan", "0,inf",   "x,1",     "0,1x",   ",1",     "-1,5",
                                        "0,1,2", "0,1e999", "0,1e308", "0,2e18", "0,1e-10"};
    for (size_t i = 0; i < sizeof spell / sizeof spell[0]; i++) {
        ck_assert_msg(biss_safety_parse_speed(spell[i], &k) == BISS_E_INVAL, "%s", spell[i]);
    }
    c = two_channels();
    ck_assert_int_eq(biss_safety_merge(&c, &k), BISS_OK);
    ck_assert(c.slave[1].max_speed == 60000.0 && c.slave[0].max_speed == 0);
}
END_TEST

int main(void) {
    Suite *s = suite_create("safety");
    TCase *tc = tcase_create("checks");
    tcase_add_test(tc, test_counter_every_frame);
    tcase_add_test(tc, test_frames_the_host_did_not_read);
    tcase_add_test(tc, test_two_readers);
    tcase_add_test(tc, test_frame_number_wraps);
    tcase_add_test(tc, test_frozen_and_skipping);
    tcase_add_test(tc, test_same_frame_read_again);
    tcase_add_test(tc, test_bad_crc_and_lost_slave);
    tcase_add_test(tc, test_pairs);
    tcase_add_test(tc, test_config_errors);
    tcase_add_test(tc, test_command_line_spellings);
    tcase_add_test(tc, test_ew_static);
    tcase_add_test(tc, test_ew_static_and_life);
    tcase_add_test(tc, test_ew_static_config);
    tcase_add_test(tc, test_speed_free_run);
    tcase_add_test(tc, test_speed_resync);
    tcase_add_test(tc, test_speed_iep);
    tcase_add_test(tc, test_speed_free_run_count_restarted);
    tcase_add_test(tc, test_speed_host_trigger);
    tcase_add_test(tc, test_speed_slow_poller);
    tcase_add_test(tc, test_speed_clock_came_round);
    tcase_add_test(tc, test_speed_and_ew);
    tcase_add_test(tc, test_speed_config);
    suite_add_tcase(s, tc);
    return check_run(s);
}
