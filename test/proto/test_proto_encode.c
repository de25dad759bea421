/* libbiss shm encoding: the configuration block as bytes at the offsets of
 * biss_shm.h, and result buffers (built as bytes the same way) decoded into
 * samples. */
#include "biss_proto.h"

#include "biss/biss_shm.h"
#include "biss/biss_shm_struct.h"

#include "check_run.h"

#include <check.h>
#include <stdlib.h>
#include <string.h>

static unsigned u8(const uint8_t *b, unsigned off) {
    return b[off];
}
static unsigned u16(const uint8_t *b, unsigned off) {
    return b[off] | b[off + 1] << 8;
}
static uint32_t u32(const uint8_t *b, unsigned off) {
    return (uint32_t)b[off] | (uint32_t)b[off + 1] << 8 | (uint32_t)b[off + 2] << 16 |
           (uint32_t)b[off + 3] << 24;
}
static void put16(uint8_t *b, unsigned off, unsigned v) {
    b[off] = (uint8_t)v;
    b[off + 1] = (uint8_t)(v >> 8);
}
static void put32(uint8_t *b, unsigned off, uint32_t v) {
    for (int i = 0; i < 4; i++) {
        b[off + i] = (uint8_t)(v >> (8 * i));
    }
}

START_TEST(test_config_bytes) {
    struct biss_config c;
    biss_config_default(&c);
    c.freq_hz = 2000000;
    c.nslaves = 2;
    c.trigger = BISS_TRIGGER_IEP;
    c.iep_period_ns = 100000;
    c.proc_limit = 300;
    /* CRC6 0x43 with nE/nW under a 4-bit life counter */
    c.slave[0] = (struct biss_slave_config){.data_bits = 30,
                                            .crc_bits = 6,
                                            .crc_poly = 0x43,
                                            .crc_start = 0x2a,
                                            .has_ew = true,
                                            .ew_shift = 4};
    /* CRC16 0x190D9, no nE/nW */
    c.slave[1] = (struct biss_slave_config){
        .data_bits = 64, .crc_bits = 16, .crc_poly = 0x190D9, .crc_start = 0xbeef};
    ck_assert_int_eq(biss_config_check(&c), BISS_OK);
    struct biss_shm_config blk;
    memset(&blk, 0xa5, sizeof blk);
    biss_config_encode(&c, &blk);
    uint8_t b[BISS_CFG_END];
    memcpy(b, &blk, sizeof b);
    ck_assert_uint_eq(u32(b, BISS_CFG_SEQ), 0); /* the caller writes it last */
    ck_assert_uint_eq(u16(b, BISS_CFG_HALF), 50);
    ck_assert_uint_eq(u8(b, BISS_CFG_NSLAVES), 2);
    ck_assert_uint_eq(u8(b, BISS_CFG_TRIGGER), BISS_TRIG_IEP);
    ck_assert_uint_eq(u32(b, BISS_CFG_IEP_PERIOD), 20000); /* 5 ns counts */
    ck_assert_uint_eq(u16(b, BISS_CFG_PROC_LIMIT), 301);   /* the busy count that ends it */
    ck_assert_uint_eq(u8(b, BISS_CFG_SSI_DELAY_NS), 0);
    unsigned s0 = BISS_CFG_SLAVE0, s1 = BISS_CFG_SLAVE0 + BISS_CFG_SLAVE_SIZE;
    ck_assert_uint_eq(u8(b, s0 + BISS_CFG_S_DATA_BITS), 30);
    ck_assert_uint_eq(u8(b, s0 + BISS_CFG_S_CRC_BITS), 6);
    ck_assert_uint_eq(u8(b, s0 + BISS_CFG_S_EW_SHIFT), 4);
    ck_assert_uint_eq(u8(b, s0 + BISS_CFG_S_FLAGS), BISS_SF_EW);
    ck_assert_uint_eq(u16(b, s0 + BISS_CFG_S_CRC_POLY), 0x03); /* top term dropped */
    ck_assert_uint_eq(u16(b, s0 + BISS_CFG_S_CRC_START), 0x2a);
    ck_assert_uint_eq(u8(b, s1 + BISS_CFG_S_DATA_BITS), 64);
    ck_assert_uint_eq(u8(b, s1 + BISS_CFG_S_CRC_BITS), 16);
    ck_assert_uint_eq(u8(b, s1 + BISS_CFG_S_FLAGS), 0);
    ck_assert_uint_eq(u16(b, s1 + BISS_CFG_S_CRC_POLY), 0x90D9);
    ck_assert_uint_eq(u16(b, s1 + BISS_CFG_S_CRC_START), 0xbeef);
    /* unused slave blocks are zero */
    for (unsigned off = s1 + BISS_CFG_SLAVE_SIZE; off < BISS_CFG_END; off++) {
        ck_assert_uint_eq(b[off], 0);
    }
    /* and back (what an attached handle reads) */
    struct biss_config d;
    const char *field;
    ck_assert_int_eq(biss_config_decode(&blk, &d, &field), BISS_OK);
    ck_assert_ptr_null(field);
    ck_assert_uint_eq(d.freq_hz, 2000000);
    ck_assert_uint_eq(d.slave[0].crc_poly, 0x43);
    ck_assert_uint_eq(d.slave[1].crc_poly, 0x190D9);
    ck_assert(d.slave[0].has_ew && !d.slave[1].has_ew);
    ck_assert_uint_eq(d.iep_period_ns, 100000);
}
END_TEST

START_TEST(test_free_run_writes_no_iep_period) {
    struct biss_config c;
    biss_config_default(&c);
    c.nslaves = 1;
    c.slave[0] = (struct biss_slave_config){.data_bits = 12};
    c.iep_period_ns = 5000;
    struct biss_shm_config blk;
    biss_config_encode(&c, &blk);
    ck_assert_uint_eq(blk.iep_period, 0);
    ck_assert_uint_eq(blk.half, 100);
    ck_assert_uint_eq(blk.slave[0].crc_bits, 0);
    ck_assert_uint_eq(blk.slave[0].crc_poly, 0);
}
END_TEST

START_TEST(test_firmware_errors_map) {
    ck_assert_int_eq(biss_fw_cfg_error(BISS_CFGERR_NONE), BISS_OK);
    ck_assert_int_eq(biss_fw_cfg_error(BISS_CFGERR_NSLAVES), BISS_E_FW_NSLAVES);
    ck_assert_int_eq(biss_fw_cfg_error(BISS_CFGERR_HALF), BISS_E_FW_HALF);
    ck_assert_int_eq(biss_fw_cfg_error(BISS_CFGERR_DATA_BITS), BISS_E_FW_DATA_BITS);
    ck_assert_int_eq(biss_fw_cfg_error(BISS_CFGERR_CRC_BITS), BISS_E_FW_CRC_BITS);
    ck_assert_int_eq(biss_fw_cfg_error(BISS_CFGERR_TRIGGER), BISS_E_FW_TRIGGER);
    ck_assert_int_eq(biss_fw_cfg_error(BISS_CFGERR_EW), BISS_E_FW_EW);
    ck_assert_int_eq(biss_fw_cfg_error(BISS_CFGERR_IEP_PERIOD), BISS_E_FW_IEP_PERIOD);
    ck_assert_int_eq(biss_fw_cfg_error(99), BISS_E_FW_UNKNOWN);
}
END_TEST

/* A result buffer as the firmware writes it, byte by byte. */
static void result_bytes(uint8_t *b) {
    memset(b, 0, BISS_RING_STRIDE(BISS_MAX_SLAVES));
    put32(b, BISS_R_FRAME, 77);
    put32(b, BISS_R_FLAGS, BISS_RF_VALID | BISS_RF_CRC_ERROR | BISS_RF_SMA);
    put32(b, BISS_R_TIMESTAMP, 123456);
    put16(b, BISS_R_PROC_CLOCKS, 3);
    b[BISS_R_CDS] = 1;
    b[BISS_R_NSLAVES] = 2;
    put16(b, BISS_R_DELAY_RAW, 27);
    put16(b, BISS_R_DELAY_AVG, 28);
    b[BISS_R_SAMPLE_POINT] = 7;
    b[BISS_R_LAG_PERIODS] = 5;
    put16(b, BISS_R_HALF, 10);
    unsigned s0 = BISS_R_SLAVE0, s1 = BISS_R_SLAVE0 + BISS_R_SLAVE_SIZE;
    /* slave 0: 12-bit position 0xabc, nE = 0 (error), nW = 1, 4-bit counter 0x5 */
    put32(b, s0 + BISS_R_S_DATA_LO, 0xabc << 6 | 0 << 5 | 1 << 4 | 0x5);
    put32(b, s0 + BISS_R_S_CRC_REG, 0x08000000);
    put32(b, s0 + BISS_R_S_STATUS, BISS_RS_CRC_OK | BISS_RS_NW);
    /* slave 1: 40 bits, no nE/nW, CRC6 wrong */
    put32(b, s1 + BISS_R_S_DATA_LO, 0x89abcdef);
    put32(b, s1 + BISS_R_S_DATA_HI, 0x12);
    put32(b, s1 + BISS_R_S_STATUS, 0);
}

static struct biss_config two_slaves(void) {
    struct biss_config c;
    biss_config_default(&c);
    c.freq_hz = 10000000;
    c.nslaves = 2;
    c.slave[0] = (struct biss_slave_config){
        .data_bits = 18, .crc_bits = 6, .crc_poly = 0x43, .has_ew = true, .ew_shift = 4};
    c.slave[1] = (struct biss_slave_config){.data_bits = 40, .crc_bits = 6, .crc_poly = 0x43};
    return c;
}

START_TEST(test_result_decode) {
    uint8_t b[BISS_RING_STRIDE(BISS_MAX_SLAVES)];
    result_bytes(b);
    struct biss_shm_result r;
    memcpy(&r, b, sizeof r);
    struct biss_config c = two_slaves();
    struct biss_sample s;
    ck_assert_int_eq(biss_sample_decode(&c, true, 9, &r, &s), BISS_OK);
    ck_assert_uint_eq(s.seq, 9);
    ck_assert_uint_eq(s.frame, 77);
    ck_assert(s.valid && s.crc_error && s.sma && !s.training && !s.no_slave && !s.proc_error);
    ck_assert_uint_eq(s.timestamp, 123456);
    ck_assert_uint_eq(s.proc_clocks, 3);
    ck_assert_uint_eq(s.cds, 1);
    ck_assert_uint_eq(s.nslaves, 2);
    ck_assert_uint_eq(s.sample_point, 7);
    ck_assert_uint_eq(s.lag_periods, 5);
    ck_assert_uint_eq(s.slave[0].data, 0xabc << 6 | 1 << 4 | 0x5);
    ck_assert_uint_eq(s.slave[0].position, 0xabc);
    ck_assert(s.slave[0].crc_ok);
    ck_assert(s.slave[0].error);    /* nE low */
    ck_assert(!s.slave[0].warning); /* nW high */
    ck_assert_uint_eq(s.slave[0].crc_reg, 0x08000000);
    ck_assert_uint_eq(s.slave[1].data, 0x1289abcdefull);
    ck_assert_uint_eq(s.slave[1].position, 0x1289abcdefull);
    ck_assert(!s.slave[1].crc_ok);
    ck_assert(!s.slave[1].error && !s.slave[1].warning); /* it has none */
    /* explicit position bits: the top 8 of slave 0's 12 */
    c.slave[0].pos_bits = 8;
    ck_assert_int_eq(biss_sample_decode(&c, true, 9, &r, &s), BISS_OK);
    ck_assert_uint_eq(s.slave[0].position, 0xab);
}
END_TEST

/* biss_shm.h: round trip = (DELAY - BISS_DELAY_ZERO) * H / 4 -
 * BISS_DELAY_ADJ_CYCLES PRU cycles; a bit/8 is H/4 cycles. */
START_TEST(test_delay_decode) {
    struct biss_line_delay d;
    biss_delay_decode(27, 28, 10, &d);
    double cycles = (28 - BISS_DELAY_ZERO) * 2.5 - BISS_DELAY_ADJ_CYCLES;
    ck_assert_double_eq_tol(d.cycles, cycles, 1e-9);
    ck_assert_double_eq_tol(d.bit8, cycles / 2.5, 1e-9);
    ck_assert_double_eq_tol(d.ns, cycles * 5, 1e-9);
    double raw_cycles = (27 - BISS_DELAY_ZERO) * 2.5 - BISS_DELAY_ADJ_CYCLES;
    ck_assert_double_eq_tol(d.raw_cycles, raw_cycles, 1e-9);
    ck_assert_double_eq_tol(d.raw_ns, raw_cycles * 5, 1e-9);
    biss_delay_decode(100, 100, 100, &d);
    ck_assert_double_eq_tol(d.ns, ((100 - BISS_DELAY_ZERO) * 25.0 - BISS_DELAY_ADJ_CYCLES) * 5,
                            1e-9);
    ck_assert_uint_eq(d.half, 100);
    /* the ACK in the first eighth the firmware resolves (a short line at a
     * slow rate: 2 m at 125 kHz), or before it: no delay, not less */
    biss_delay_decode(BISS_DELAY_ZERO - 1, BISS_DELAY_ZERO, 800, &d);
    ck_assert(d.cycles == 0 && d.bit8 == 0 && d.ns == 0);
    ck_assert(d.raw_cycles == 0 && d.raw_bit8 == 0 && d.raw_ns == 0);
    biss_delay_decode(BISS_DELAY_ZERO + 1, BISS_DELAY_ZERO + 1, 800, &d);
    ck_assert_double_eq_tol(d.cycles, 200.0 - BISS_DELAY_ADJ_CYCLES, 1e-9);
}
END_TEST

/* The two-slave result buffer published with only `flags`, decoded. */
static void decode_with_flags(uint32_t flags, struct biss_sample *s) {
    uint8_t b[BISS_RING_STRIDE(BISS_MAX_SLAVES)];
    result_bytes(b);
    put32(b, BISS_R_FLAGS, flags);
    struct biss_shm_result r;
    memcpy(&r, b, sizeof r);
    struct biss_config c = two_slaves();
    ck_assert_int_eq(biss_sample_decode(&c, true, 1, &r, s), BISS_OK);
}

START_TEST(test_aborted_frame_has_no_slave_data) {
    struct biss_sample s;
    decode_with_flags(BISS_RF_NO_SLAVE, &s);
    ck_assert(!s.valid && s.no_slave);
    ck_assert_uint_eq(s.slave[0].data, 0);
    ck_assert_uint_eq(s.slave[0].position, 0);
}
END_TEST

static void spoil_half(struct biss_shm_config *b) {
    b->half = 1;
}
static void spoil_nslaves(struct biss_shm_config *b) {
    b->nslaves = 9;
}
static void spoil_trigger(struct biss_shm_config *b) {
    b->trigger = 7;
}
static void spoil_data_bits(struct biss_shm_config *b) {
    b->slave[1].data_bits = 200;
}
static void spoil_crc_bits(struct biss_shm_config *b) {
    b->slave[0].crc_bits = 17;
}
static void spoil_flags(struct biss_shm_config *b) {
    b->slave[0].flags |= 0x80;
}
static void spoil_ew(struct biss_shm_config *b) {
    b->slave[0].ew_shift = 17;
}
static void spoil_poly(struct biss_shm_config *b) {
    b->slave[0].crc_poly = 0x1ff;
}
static void spoil_ssi_chain(struct biss_shm_config *b) {
    b->slave[1].flags = BISS_SF_SSI;
}
static void spoil_shift_clock(struct biss_shm_config *b) {
    b->half = 1000; /* 100 kHz: 1000 = 8 * 125 has no exact 8x shift clock */
}
static void spoil_inexact(struct biss_shm_config *b) {
    b->half = 12; /* 8.33 MHz: the firmware clocks it, no biss_config names it */
}
static void spoil_iep_period(struct biss_shm_config *b) {
    b->trigger = BISS_TRIG_IEP;
    b->iep_period = 1; /* 5 ns: shorter than any frame */
}

/* A block read back from data RAM is untrusted: each junk field is refused
 * by name before it can become a shift count or a loop bound (a half
 * period of 1 once gave freq_hz=100000000, a data_bits of 200 a shift by
 * 200). */
START_TEST(test_junk_config_block_refused) {
    struct biss_config c = two_slaves();
    c.freq_hz = 2000000;
    c.proc_limit = 300;
    struct biss_shm_config good;
    biss_config_encode(&c, &good);
    struct {
        const char *field;
        void (*spoil)(struct biss_shm_config *b);
    } cases[] = {
        {"MA half period", spoil_half},
        {"slave count", spoil_nslaves},
        {"trigger mode", spoil_trigger},
        {"slave data bits", spoil_data_bits},
        {"slave CRC bits", spoil_crc_bits},
        {"slave flags", spoil_flags},
        {"slave nE/nW position", spoil_ew},
        {"slave CRC polynomial or start value", spoil_poly},
        {"slave SSI flag", spoil_ssi_chain},
        {"MA half period", spoil_shift_clock}, /* the firmware's rule: refused */
        {"MA half period", spoil_inexact},
        {"configuration (fails the library's checks)", spoil_iep_period},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        struct biss_shm_config b = good;
        cases[i].spoil(&b);
        struct biss_config d;
        const char *field = NULL;
        ck_assert_int_eq(biss_config_decode(&b, &d, &field), BISS_E_SHM_CONFIG);
        ck_assert_str_eq(field, cases[i].field);
    }
    /* all 0xff: refused, and so is all zero (never configured) */
    struct biss_shm_config b;
    memset(&b, 0xff, sizeof b);
    struct biss_config d;
    const char *field;
    ck_assert_int_eq(biss_config_decode(&b, &d, &field), BISS_E_SHM_CONFIG);
    memset(&b, 0, sizeof b);
    ck_assert_int_eq(biss_config_decode(&b, &d, &field), BISS_E_NOT_CONFIGURED);
}
END_TEST

/* A result the firmware cannot have written is junk, refused by name
 * (biss_result_problem): a slave count not the configuration's or past the
 * limit, flags it never combines, a half period it never runs, a sample
 * point, lag or line delay out of range, status bits or data bits it never
 * sets, a CRC verdict the flags contradict. */
static void expect_junk(struct biss_shm_result r, bool configured, const char *field) {
    struct biss_config c = two_slaves();
    struct biss_sample s;
    ck_assert_int_eq(biss_sample_decode(&c, configured, 1, &r, &s), BISS_E_SHM_RESULT);
    const char *why = biss_result_problem(&c, configured, &r);
    ck_assert_msg(why && strstr(why, field), "%s: got %s", field, why ? why : "(none)");
}

START_TEST(test_junk_result_refused) {
    uint8_t b[BISS_RING_STRIDE(BISS_MAX_SLAVES)];
    result_bytes(b);
    struct biss_shm_result good, r;
    memcpy(&good, b, sizeof good);
    struct biss_config c = two_slaves();
    struct biss_sample s;
    ck_assert_ptr_null(biss_result_problem(&c, true, &good));
    r = good, r.nslaves = 200;
    expect_junk(r, true, "slave count");
    expect_junk(r, false, "slave count");
    r = good, r.nslaves = 3;
    expect_junk(r, true, "slave count");
    r = good, r.nslaves = 0;
    expect_junk(r, false, "slave count");
    /* flags: VALID with ACK_JUMP, all ones, SMA on a refused frame, two
     * early ends at once, a flag the contract does not have */
    static const uint32_t flags[] = {
        BISS_RF_VALID | BISS_RF_ACK_JUMP, 0xffffffffu,       0,
        BISS_RF_ACK_JUMP | BISS_RF_SMA,   BISS_RF_CRC_ERROR, BISS_RF_NO_SLAVE | BISS_RF_TRAINING,
        BISS_RF_VALID | BISS_RF_TRAINING, BISS_RF_SL_INIT,   BISS_RF_VALID | 0x80,
        BISS_RF_PROC_ERROR | BISS_RF_SMA};
    for (size_t i = 0; i < sizeof flags / sizeof flags[0]; i++) {
        r = good, r.flags = flags[i];
        expect_junk(r, true, "result flags");
    }
    /* half periods the firmware refuses to run */
    static const uint16_t halves[] = {0, 9, 11, 1025, 0xffff};
    for (size_t i = 0; i < sizeof halves / sizeof halves[0]; i++) {
        r = good, r.half = halves[i];
        expect_junk(r, false, "MA half period");
    }
    r = good, r.sample_point = 8;
    expect_junk(r, true, "sample point");
    r = good, r.sample_point = 255;
    expect_junk(r, false, "sample point");
    /* at 1 MHz the firmware waits 44 periods for the ACK at most: lag 255
     * and a delay of 0xffff eighths cannot be */
    r = good, r.half = 100, r.lag_periods = 255;
    expect_junk(r, false, "lag");
    r = good, r.half = 100, r.lag_periods = 47; /* 44 periods to the ACK, LAG 2 */
    ck_assert_ptr_null(biss_result_problem(&c, true, &r));
    r.lag_periods = 60;
    expect_junk(r, true, "lag");
    r = good, r.delay_avg = 0xffff;
    expect_junk(r, false, "line delay");
    r = good, r.cds = 2;
    expect_junk(r, false, "CDS");
    r = good, r.proc_clocks = 1001; /* over the configuration's limit */
    expect_junk(r, true, "processing time");
    ck_assert_ptr_null(biss_result_problem(&c, false, &r));
    /* slaves: status bits, nE/nW of a slave that has none, a CRC error the
     * flags lack, CRC_ERROR no slave has, data above the data bits */
    r = good, r.slave[0].status |= 0x100;
    expect_junk(r, false, "slave status");
    r = good, r.slave[1].status |= BISS_RS_NE;
    expect_junk(r, true, "slave status");
    r = good, r.flags = BISS_RF_VALID;
    expect_junk(r, true, "slave status");
    r = good, r.slave[1].status = BISS_RS_CRC_OK;
    expect_junk(r, true, "result flags");
    r = good, r.slave[0].data_hi = 0xffffffffu; /* above slave 0's 18 bits */
    expect_junk(r, true, "slave data");
    /* a frame that ended early keeps older words in its buffer: only its
     * header is judged */
    r = good, r.flags = BISS_RF_NO_SLAVE, r.sample_point = 200, r.slave[0].status = 0xff;
    ck_assert_int_eq(biss_sample_decode(&c, true, 1, &r, &s), BISS_OK);
}
END_TEST

/* Status words a running firmware never writes, named. */
START_TEST(test_junk_status_refused) {
    struct biss_shm_status st = {.magic = BISS_MAGIC, .state = BISS_STATE_RUNNING};
    ck_assert_ptr_null(biss_status_problem(&st, 1));
    ck_assert_ptr_nonnull(strstr(biss_status_problem(&st, 2), "ST_PRU"));
    st.state = 4;
    ck_assert_ptr_nonnull(strstr(biss_status_problem(&st, 0), "ST_STATE"));
    st.state = 0, st.buf = 2; /* before the first publication: 0 */
    ck_assert_ptr_nonnull(strstr(biss_status_problem(&st, 0), "ST_BUF"));
    st.seq = 5, st.buf = BISS_RING0 + 3 * BISS_R_SLAVE_SIZE; /* a slot's start, some layout */
    ck_assert_ptr_null(biss_status_problem(&st, 0));
    st.buf = BISS_RING0 + 4; /* off the slots' grid */
    ck_assert_ptr_nonnull(strstr(biss_status_problem(&st, 0), "ST_BUF"));
    st.buf = BISS_RING_END - BISS_R_SLAVE_SIZE; /* no room for a header */
    ck_assert_ptr_nonnull(strstr(biss_status_problem(&st, 0), "ST_BUF"));
    st.buf = BISS_RING0, st.cfg_error = 9;
    ck_assert_ptr_nonnull(strstr(biss_status_problem(&st, 0), "ST_CFG_ERROR"));
    st.magic = 0; /* not running: nothing judged */
    ck_assert_ptr_null(biss_status_problem(&st, 7));
}
END_TEST

START_TEST(test_ack_jump_frame_is_not_valid) {
    struct biss_sample s;
    decode_with_flags(BISS_RF_ACK_JUMP | BISS_RF_CRC_ERROR, &s);
    ck_assert(!s.valid && s.ack_jump && !s.no_slave);
    ck_assert_uint_eq(s.slave[0].data, 0); /* words read at the wrong place: none */
}
END_TEST

int main(void) {
    Suite *s = suite_create("proto_encode");
    TCase *tc = tcase_create("encode");
    tcase_add_test(tc, test_config_bytes);
    tcase_add_test(tc, test_junk_status_refused);
    tcase_add_test(tc, test_free_run_writes_no_iep_period);
    tcase_add_test(tc, test_firmware_errors_map);
    tcase_add_test(tc, test_result_decode);
    tcase_add_test(tc, test_delay_decode);
    tcase_add_test(tc, test_aborted_frame_has_no_slave_data);
    tcase_add_test(tc, test_junk_config_block_refused);
    tcase_add_test(tc, test_junk_result_refused);
    tcase_add_test(tc, test_ack_jump_frame_is_not_valid);
    suite_add_tcase(s, tc);
    return check_run(s);
}
