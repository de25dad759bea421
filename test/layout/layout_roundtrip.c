/*
 * layout_roundtrip.c - proto against the layout of whatever biss_shm.h it
 * is compiled with (layout_check.py builds it twice: with the project's
 * header, and with one whose status block has moved). The firmware's side
 * is played here from the header's macros alone, byte by byte; proto's
 * transfers and decoders must meet it wherever the header puts things.
 * Prints BISS_ST_MAGIC (so the caller sees the move took) and "ok", or the
 * first disagreement; exit status 0 only for "ok".
 */
#include "biss_proto.h"

#include <stdio.h>
#include <string.h>

static uint8_t dram[BISS_DRAM_BYTES];

static int img_read(void *ctx, uint32_t off, void *buf, size_t n) {
    (void)ctx;
    if (off > sizeof dram || n > sizeof dram - off) {
        return BISS_E_INVAL;
    }
    memcpy(buf, dram + off, n);
    return BISS_OK;
}

static int img_write(void *ctx, uint32_t off, const void *buf, size_t n) {
    (void)ctx;
    if (off > sizeof dram || n > sizeof dram - off) {
        return BISS_E_INVAL;
    }
    memcpy(dram + off, buf, n);
    return BISS_OK;
}

/* The firmware's side: little-endian words at the header's offsets. */
static void put(uint32_t off, uint64_t v, unsigned bytes) {
    for (unsigned i = 0; i < bytes; i++) {
        dram[off + i] = (uint8_t)(v >> 8 * i);
    }
}

static uint64_t get(uint32_t off, unsigned bytes) {
    uint64_t v = 0;
    for (unsigned i = 0; i < bytes; i++) {
        v |= (uint64_t)dram[off + i] << 8 * i;
    }
    return v;
}

static int failures;
#define SAME(got, want)                                                                            \
    do {                                                                                           \
        unsigned long long g_ = (got), w_ = (want);                                                \
        if (g_ != w_) {                                                                            \
            printf("%s:%d: %s is %llu, the header's place holds %llu\n", __FILE__, __LINE__, #got, \
                   g_, w_);                                                                        \
            failures++;                                                                            \
        }                                                                                          \
    } while (0)

static void status_words(const struct biss_proto_io *io) {
    put(BISS_ST_MAGIC, BISS_MAGIC, 4);
    put(BISS_ST_CFG_ACK, 41, 4);
    put(BISS_ST_CFG_ERROR, BISS_CFGERR_EW, 4);
    put(BISS_ST_STATE, BISS_STATE_CFG_ERROR, 4);
    put(BISS_ST_FRAMES, 1234, 4);
    put(BISS_ST_TRAINING, 3, 4);
    put(BISS_ST_PRU, 1, 4);
    struct biss_shm_status st;
    SAME(biss_proto_status_get(io, &st), 0);
    SAME(st.magic, BISS_MAGIC);
    SAME(st.cfg_ack, 41);
    SAME(st.cfg_error, BISS_CFGERR_EW);
    SAME(st.state, BISS_STATE_CFG_ERROR);
    SAME(st.frames, 1234);
    SAME(st.training, 3);
    uint32_t pru = 0;
    SAME(biss_proto_fw_pru_get(io, &pru), 0);
    SAME(pru, 1);
}

static void configuration(const struct biss_proto_io *io) {
    struct biss_config c;
    biss_config_default(&c);
    c.freq_hz = 5000000; /* H = 20 */
    c.nslaves = 2;
    c.trigger = BISS_TRIGGER_IEP;
    c.iep_period_ns = 100000;
    c.proc_limit = 300;
    struct biss_proto_word w = {.pos_bits = 18, .lc_bits = 6, .has_err = true, .has_warn = true};
    biss_proto_slave_layout(&w, 0x43, 0, &c.slave[0]);
    c.slave[1] = (struct biss_slave_config){.data_bits = 40, .crc_bits = 16, .crc_poly = 0x190D9};
    SAME(biss_config_check(&c), BISS_OK);
    struct biss_shm_config blk;
    biss_config_encode(&c, &blk);
    SAME(biss_proto_config_put(io, &blk, 7), 0);
    SAME(get(BISS_CFG_SEQ, 4), 7);
    SAME(get(BISS_CFG_HALF, 2), 20);
    SAME(get(BISS_CFG_NSLAVES, 1), 2);
    SAME(get(BISS_CFG_TRIGGER, 1), BISS_TRIG_IEP);
    SAME(get(BISS_CFG_IEP_PERIOD, 4), 20000);
    SAME(get(BISS_CFG_PROC_LIMIT, 2), 301); /* the busy count that ends the frame */
    uint32_t s0 = BISS_CFG_SLAVE0, s1 = BISS_CFG_SLAVE0 + BISS_CFG_SLAVE_SIZE;
    SAME(get(s0 + BISS_CFG_S_DATA_BITS, 1), 26);
    SAME(get(s0 + BISS_CFG_S_CRC_BITS, 1), 6);
    SAME(get(s0 + BISS_CFG_S_EW_SHIFT, 1), 6);
    SAME(get(s0 + BISS_CFG_S_FLAGS, 1), BISS_SF_EW);
    SAME(get(s0 + BISS_CFG_S_CRC_POLY, 2), 0x03);
    SAME(get(s1 + BISS_CFG_S_DATA_BITS, 1), 40);
    SAME(get(s1 + BISS_CFG_S_CRC_POLY, 2), 0x90D9);
    struct biss_shm_config back;
    SAME(biss_proto_config_get(io, &back), 0);
    struct biss_config dec;
    const char *field = NULL;
    SAME(biss_config_decode(&back, &dec, &field), BISS_OK);
    SAME(dec.freq_hz, 5000000);
    SAME(dec.slave[0].ew_shift, 6);
}

static void result(const struct biss_proto_io *io) {
    uint32_t res = BISS_RING0 + BISS_RING_STRIDE(1); /* the ring's second slot */
    put(BISS_ST_BUF, res, 4);
    put(BISS_ST_SEQ, 99, 4);
    put(res + BISS_R_FRAME, 77, 4);
    put(res + BISS_R_FLAGS, BISS_RF_VALID | BISS_RF_SMA, 4);
    put(res + BISS_R_PROC_CLOCKS, 5, 2);
    put(res + BISS_R_NSLAVES, 1, 1);
    put(res + BISS_R_DELAY_RAW, 27, 2);
    put(res + BISS_R_DELAY_AVG, 28, 2);
    put(res + BISS_R_SAMPLE_POINT, 3, 1);
    put(res + BISS_R_HALF, 20, 2);
    uint32_t sl = res + BISS_R_SLAVE0;
    /* position 0x2abcd, nE 1, nW 0, life counter 0x15 */
    put(sl + BISS_R_S_DATA_LO, (uint64_t)0x2abcd << 8 | 2u << 6 | 0x15, 4);
    put(sl + BISS_R_S_STATUS, BISS_RS_CRC_OK | BISS_RS_NE, 4);
    struct biss_config c;
    biss_config_default(&c);
    c.nslaves = 1;
    struct biss_proto_word w = {.pos_bits = 18, .lc_bits = 6, .has_err = true, .has_warn = true};
    biss_proto_slave_layout(&w, 0x43, 0, &c.slave[0]);
    uint32_t seq = 0;
    struct biss_shm_result r;
    struct biss_sample s;
    SAME(biss_proto_pub_seq(io, &seq), 0);
    SAME(seq, 99);
    SAME(biss_proto_result_get(io, 1, &r), 0);
    SAME(biss_sample_decode(&c, true, seq, &r, &s), 0);
    SAME(s.frame, 77);
    SAME(s.valid && s.sma, 1);
    SAME(s.proc_clocks, 5);
    SAME(s.delay.raw, 27);
    SAME(s.delay.avg, 28);
    SAME(s.delay.half, 20);
    SAME(s.sample_point, 3);
    SAME(s.slave[0].position, 0x2abcd);
    SAME(s.slave[0].error, 0);
    SAME(s.slave[0].warning, 1);
    /* the ring: the newest slot holds ST_SEQ's publication */
    put(res + BISS_R_FRAME, 99, 4);
    uint32_t cursor = 98, lost = 9;
    unsigned n = 9;
    SAME(biss_proto_ring_read(io, &cursor, &r, 1, &n, &lost), 0);
    SAME(n, 1);
    SAME(lost, 0);
    SAME(r.frame, 99);
    SAME(cursor, 99);
    put(BISS_ST_BUF, res + 4, 4); /* no slot the firmware fills */
    SAME(biss_proto_result_get(io, 1, &r), BISS_E_SHM_RESULT);
    SAME(biss_proto_ring_read(io, &cursor, &r, 1, &n, &lost), BISS_E_SHM_RESULT);
}

static void control(const struct biss_proto_io *io) {
    biss_cd_prog p;
    SAME(biss_cd_build_command(&p, 0x03, 1, true), BISS_CD_OK);
    put(BISS_CD_CMD, 4, 4);
    put(BISS_ST_CD_SEQ, 4, 4);
    uint32_t cmd = 0;
    SAME(biss_proto_cd_put(io, &p, 9, &cmd), 0);
    SAME(cmd, 5);
    SAME(get(BISS_CD_CMD, 4), 5);
    SAME(get(BISS_CD_STEPS, 2), p.len);
    SAME(get(BISS_CD_WAIT_LIMIT, 2), 9);
    SAME(get(BISS_CD_IDA_STEP, 2), p.end);
    SAME(get(BISS_CD_IDA_EXPECT, 1), p.ids);
    SAME(get(BISS_CD_PROG, 1), (p.op[0] & 15u) | (p.op[1] & 15u) << 4);
    SAME(biss_proto_cd_put(io, &p, 9, &cmd), BISS_E_CD_BUSY); /* 5 not ended yet */
    biss_cd_answer a;
    SAME(biss_proto_cd_ended(io, 5, &a), 0);
    put(BISS_ST_CD_STATUS, BISS_CDST_DONE, 1);
    put(BISS_ST_CD_STATUS + 1, 0, 1);
    put(BISS_ST_CD_STATUS + 2, p.len, 2);
    put(BISS_CD_RESP, 0xa5, 1);
    put(BISS_ST_CD_SEQ, 5, 4);
    SAME(biss_proto_cd_ended(io, 5, &a), 1);
    SAME(a.status, BISS_CDST_DONE);
    SAME(a.steps, p.len);
    SAME(a.resp[0], 0xa5);
}

static void identification(const struct biss_proto_io *io) {
    struct biss_shm_id id = {BISS_ID_MAGIC, BISS_SHM_VERSION, 0x12345678, 4096};
    uint8_t rsc[16];
    memset(rsc, 0x5a, sizeof rsc);
    SAME(biss_proto_id_put(io, &id, rsc), 0);
    SAME(get(BISS_ID, 4), BISS_ID_MAGIC);
    SAME(get(BISS_ID + 8, 4), 0x12345678);
    SAME(get(BISS_RSC_TABLE, 1), 0x5a);
    uint32_t pending = 1;
    put(BISS_CMD_TRIGGER, 0, 4);
    SAME(biss_proto_trigger_get(io, &pending), 0);
    SAME(pending, 0);
    SAME(biss_proto_trigger(io), 0);
    SAME(get(BISS_CMD_TRIGGER, 4), 1);
}

int main(void) {
    struct biss_proto_io io = {.read = img_read, .write = img_write, .ctx = NULL};
    status_words(&io);
    configuration(&io);
    result(&io);
    control(&io);
    identification(&io);
    printf("BISS_ST_MAGIC 0x%03x\n", BISS_ST_MAGIC);
    if (failures) {
        printf("%d disagreements\n", failures);
        return 1;
    }
    printf("ok\n");
    return 0;
}
