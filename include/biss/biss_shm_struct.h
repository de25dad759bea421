/*
 * biss_shm_struct.h - the C struct view of the shared-memory layout in
 * biss_shm.h (PRU0 data RAM, little-endian).
 *
 * biss_shm.h is the source of truth: every field below is checked against
 * its offset there at compile time, so the two views cannot drift apart.
 * Fields are ordered so that natural alignment gives the packed layout; no
 * compiler-specific packing is needed.
 */
#ifndef BISS_SHM_STRUCT_H
#define BISS_SHM_STRUCT_H

#include "biss_shm.h"

#include <stddef.h>
#include <stdint.h>

#if defined(__BYTE_ORDER__) && __BYTE_ORDER__ != __ORDER_LITTLE_ENDIAN__
#error "the shared-memory struct view assumes a little-endian host, as the PRU is"
#endif

/* One slave's block of the configuration (BISS_CFG_S_*). */
struct biss_shm_slave_cfg {
    uint8_t data_bits; /* 1..64: everything before the CRC */
    uint8_t crc_bits;  /* 0..16 */
    uint8_t ew_shift;  /* bit of nW from the data word's LSB */
    uint8_t flags;     /* BISS_SF_* */
    uint16_t crc_poly; /* without its top term */
    uint16_t crc_start;
};

/* The configuration block the host writes (BISS_CFG_*). */
struct biss_shm_config {
    uint32_t seq;
    uint16_t half;
    uint8_t nslaves;
    uint8_t trigger;
    uint32_t iep_period;
    uint16_t proc_limit;
    uint16_t ssi_delay_ns;
    struct biss_shm_slave_cfg slave[BISS_MAX_SLAVES];
};

/* Status words the firmware writes (BISS_ST_*). */
struct biss_shm_status {
    uint32_t magic;
    uint32_t seq;
    uint32_t buf;
    uint32_t cfg_ack;
    uint32_t cfg_error;
    uint32_t state;
    uint32_t frames;
    uint32_t crc_errors;
    uint32_t no_slave;
    uint32_t proc_errors;
    uint32_t training;
};

/* Control communication: the host's command words and the firmware's
 * answer (BISS_CD_*, BISS_ST_CD_*). */
struct biss_shm_cd {
    uint32_t cmd;        /* host */
    uint16_t steps;      /* host */
    uint16_t wait_limit; /* host */
    uint32_t seq;        /* firmware: CD_CMD of the program last ended */
    uint8_t status;      /* firmware: BISS_CDST_* */
    uint8_t bytes;       /* firmware: bytes transferred correctly */
    uint16_t steps_done; /* firmware */
    uint16_t ida_step;   /* host: the P of a command with IDA test (0: none) */
    uint8_t ida_expect;  /* host */
    uint8_t reserved;
};

/* One slave's result (BISS_R_S_*). */
struct biss_shm_slave_result {
    uint32_t data_lo;
    uint32_t data_hi;
    uint32_t crc_reg;
    uint32_t status; /* BISS_RS_* */
};

/* One result slot of the ring (BISS_R_*), with room for every slave: a
 * slot in data RAM holds only the configured slaves' (BISS_RING_STRIDE). */
struct biss_shm_result {
    uint32_t frame;
    uint32_t flags; /* BISS_RF_* */
    uint32_t timestamp;
    uint16_t proc_clocks;
    uint8_t cds;
    uint8_t nslaves;
    uint16_t delay_raw;
    uint16_t delay_avg;
    uint8_t sample_point;
    uint8_t lag_periods;
    uint16_t half;
    uint8_t cdm;
    uint8_t reserved[BISS_R_SLAVE0 - BISS_R_CDM - 1];
    struct biss_shm_slave_result slave[BISS_MAX_SLAVES];
};

#define BISS_SHM_CD_PROG_BYTES (BISS_CD_MAX_STEPS / 2) /* 4 bits a step */
#define BISS_SHM_CD_RESP_BYTES (BISS_CD_MAX_STEPS / 8) /* 1 bit a step */

/* The whole shared area, from data RAM address 0 to the end of the
 * control-communication answers. */
struct biss_shm {
    struct biss_shm_config cfg;
    uint32_t cmd_trigger;
    uint8_t gap_cmd[BISS_ST_PRU - BISS_CMD_TRIGGER - 4];
    uint32_t st_pru;
    struct biss_shm_status st;
    uint8_t gap_st[BISS_CD_CMD - BISS_ST_END];
    struct biss_shm_cd cd;
    uint32_t ring_next;
    uint16_t ring_stride;
    uint16_t ring_last;
    uint32_t st_off_grid;
    uint8_t gap_ring[BISS_PRIV - BISS_ST_LINK_END];
    uint8_t priv[BISS_PRIV_END - BISS_PRIV];
    uint8_t gap_priv[BISS_CD_PROG - BISS_PRIV_END];
    uint8_t cd_prog[BISS_SHM_CD_PROG_BYTES];
    uint8_t gap_prog[BISS_CD_RESP - BISS_CD_PROG - BISS_SHM_CD_PROG_BYTES];
    uint8_t cd_resp[BISS_SHM_CD_RESP_BYTES];
    uint8_t gap_resp[BISS_RING0 - BISS_CD_RESP - BISS_SHM_CD_RESP_BYTES];
    uint8_t ring[BISS_RING_END - BISS_RING0]; /* the result slots */
};

/* The ring's geometry for a slave count n (1..BISS_MAX_SLAVES): a slot is
 * the header and n slave results; as many slots as fit. The firmware works
 * out the same stride (pru_fw/config.p: n << 4, + BISS_R_SLAVE0) and last
 * slot start (BISS_RING_END - stride) and reports them in ST_RING_STRIDE
 * and ST_RING_LAST. */
#define BISS_RING_STRIDE(n) (BISS_R_SLAVE0 + (unsigned)(n)*BISS_R_SLAVE_SIZE)
#define BISS_RING_SLOTS(n)  ((BISS_RING_END - BISS_RING0) / BISS_RING_STRIDE(n))

/* ---- compile-time agreement with biss_shm.h ---------------------------- */
#define BISS_SHM_AT(member, off)                                                                   \
    _Static_assert(offsetof(struct biss_shm, member) == (off), #member " is not at " #off)
#define BISS_SHM_SLAVE_CFG_AT(member, off)                                                         \
    _Static_assert(offsetof(struct biss_shm_slave_cfg, member) == (off),                           \
                   "slave cfg " #member " is not at " #off)
#define BISS_SHM_RESULT_AT(member, off)                                                            \
    _Static_assert(offsetof(struct biss_shm_result, member) == (off),                              \
                   "result " #member " is not at " #off)
#define BISS_SHM_SLAVE_RESULT_AT(member, off)                                                      \
    _Static_assert(offsetof(struct biss_shm_slave_result, member) == (off),                        \
                   "slave result " #member " is not at " #off)

BISS_SHM_AT(cfg.seq, BISS_CFG_SEQ);
BISS_SHM_AT(cfg.half, BISS_CFG_HALF);
BISS_SHM_AT(cfg.nslaves, BISS_CFG_NSLAVES);
BISS_SHM_AT(cfg.trigger, BISS_CFG_TRIGGER);
BISS_SHM_AT(cfg.iep_period, BISS_CFG_IEP_PERIOD);
BISS_SHM_AT(cfg.proc_limit, BISS_CFG_PROC_LIMIT);
BISS_SHM_AT(cfg.ssi_delay_ns, BISS_CFG_SSI_DELAY_NS);
BISS_SHM_AT(cfg.slave, BISS_CFG_SLAVE0);
BISS_SHM_AT(cfg.slave[1], BISS_CFG_SLAVE0 + BISS_CFG_SLAVE_SIZE);
_Static_assert(sizeof(struct biss_shm_config) == BISS_CFG_END, "config block size");
_Static_assert(sizeof(struct biss_shm_slave_cfg) == BISS_CFG_SLAVE_SIZE, "slave cfg size");
BISS_SHM_SLAVE_CFG_AT(data_bits, BISS_CFG_S_DATA_BITS);
BISS_SHM_SLAVE_CFG_AT(crc_bits, BISS_CFG_S_CRC_BITS);
BISS_SHM_SLAVE_CFG_AT(ew_shift, BISS_CFG_S_EW_SHIFT);
BISS_SHM_SLAVE_CFG_AT(flags, BISS_CFG_S_FLAGS);
BISS_SHM_SLAVE_CFG_AT(crc_poly, BISS_CFG_S_CRC_POLY);
BISS_SHM_SLAVE_CFG_AT(crc_start, BISS_CFG_S_CRC_START);

BISS_SHM_AT(cmd_trigger, BISS_CMD_TRIGGER);
BISS_SHM_AT(ring_next, BISS_ST_RING_NEXT);
BISS_SHM_AT(ring_stride, BISS_ST_RING_STRIDE);
BISS_SHM_AT(ring_last, BISS_ST_RING_LAST);
BISS_SHM_AT(st_off_grid, BISS_ST_OFF_GRID);
BISS_SHM_AT(gap_ring, BISS_ST_LINK_END);
BISS_SHM_AT(st_pru, BISS_ST_PRU);

BISS_SHM_AT(st, BISS_ST_MAGIC);
BISS_SHM_AT(st.magic, BISS_ST_MAGIC);
BISS_SHM_AT(st.seq, BISS_ST_SEQ);
BISS_SHM_AT(st.buf, BISS_ST_BUF);
BISS_SHM_AT(st.cfg_ack, BISS_ST_CFG_ACK);
BISS_SHM_AT(st.cfg_error, BISS_ST_CFG_ERROR);
BISS_SHM_AT(st.state, BISS_ST_STATE);
BISS_SHM_AT(st.frames, BISS_ST_FRAMES);
BISS_SHM_AT(st.crc_errors, BISS_ST_CRC_ERRORS);
BISS_SHM_AT(st.no_slave, BISS_ST_NO_SLAVE);
BISS_SHM_AT(st.proc_errors, BISS_ST_PROC_ERRORS);
BISS_SHM_AT(st.training, BISS_ST_TRAINING);
_Static_assert(BISS_ST_MAGIC + sizeof(struct biss_shm_status) == BISS_ST_END, "status size");

BISS_SHM_AT(cd.cmd, BISS_CD_CMD);
BISS_SHM_AT(cd.steps, BISS_CD_STEPS);
BISS_SHM_AT(cd.wait_limit, BISS_CD_WAIT_LIMIT);
BISS_SHM_AT(cd.seq, BISS_ST_CD_SEQ);
BISS_SHM_AT(cd.status, BISS_ST_CD_STATUS);
BISS_SHM_AT(cd.bytes, BISS_ST_CD_STATUS + 1);
BISS_SHM_AT(cd.steps_done, BISS_ST_CD_STATUS + 2);
BISS_SHM_AT(cd.ida_step, BISS_CD_IDA_STEP);
BISS_SHM_AT(cd.ida_expect, BISS_CD_IDA_EXPECT);
_Static_assert(BISS_CD_CMD + sizeof(struct biss_shm_cd) == BISS_ST_CD_END, "cd area size");

BISS_SHM_AT(ring, BISS_RING0);
_Static_assert(sizeof(struct biss_shm_result) == BISS_RING_STRIDE(BISS_MAX_SLAVES),
               "a slot of every slave is the whole result struct");
_Static_assert(BISS_R_SLAVE_SIZE == 16, "pru_fw/config.p's stride: slaves << 4");
_Static_assert(BISS_R_SLAVE0 < 256 && BISS_RING0 < 0x10000 && BISS_RING_END < 0x10000,
               "config.p's immediates: the header an 8-bit, the ring's bounds 16-bit ones");
_Static_assert(BISS_RING0 % 4 == 0 && BISS_R_SLAVE0 % 4 == 0 && BISS_R_SLAVE_SIZE % 4 == 0,
               "slots of whole words");
_Static_assert(BISS_RING_SLOTS(BISS_MAX_SLAVES) >= 2, "a ring of at least two slots");
BISS_SHM_RESULT_AT(frame, BISS_R_FRAME);
BISS_SHM_RESULT_AT(flags, BISS_R_FLAGS);
BISS_SHM_RESULT_AT(timestamp, BISS_R_TIMESTAMP);
BISS_SHM_RESULT_AT(proc_clocks, BISS_R_PROC_CLOCKS);
BISS_SHM_RESULT_AT(cds, BISS_R_CDS);
BISS_SHM_RESULT_AT(nslaves, BISS_R_NSLAVES);
BISS_SHM_RESULT_AT(delay_raw, BISS_R_DELAY_RAW);
BISS_SHM_RESULT_AT(delay_avg, BISS_R_DELAY_AVG);
BISS_SHM_RESULT_AT(sample_point, BISS_R_SAMPLE_POINT);
BISS_SHM_RESULT_AT(lag_periods, BISS_R_LAG_PERIODS);
BISS_SHM_RESULT_AT(half, BISS_R_HALF);
BISS_SHM_RESULT_AT(cdm, BISS_R_CDM);
BISS_SHM_RESULT_AT(slave, BISS_R_SLAVE0);
BISS_SHM_RESULT_AT(slave[1], BISS_R_SLAVE0 + BISS_R_SLAVE_SIZE);
_Static_assert(sizeof(struct biss_shm_slave_result) == BISS_R_SLAVE_SIZE, "slave result size");
BISS_SHM_SLAVE_RESULT_AT(data_lo, BISS_R_S_DATA_LO);
BISS_SHM_SLAVE_RESULT_AT(data_hi, BISS_R_S_DATA_HI);
BISS_SHM_SLAVE_RESULT_AT(crc_reg, BISS_R_S_CRC_REG);
BISS_SHM_SLAVE_RESULT_AT(status, BISS_R_S_STATUS);

BISS_SHM_AT(priv, BISS_PRIV);
BISS_SHM_AT(cd_prog, BISS_CD_PROG);
BISS_SHM_AT(cd_resp, BISS_CD_RESP);
_Static_assert(BISS_CD_PROG + BISS_SHM_CD_PROG_BYTES <= BISS_CD_RESP, "CD program fits its area");
/* The firmware's CD_OP forms BISS_CD_PROG + step / 2 by setting bit 9
 * (CD_PROG_BIT) of step / 2 (at most 511). */
_Static_assert(BISS_CD_PROG == 0x200 && BISS_SHM_CD_PROG_BYTES <= 0x200,
               "CD_OP's program address is a bit set");
/* CD_COMMIT forms BISS_CD_RESP + step / 8 by setting bit 10 (CD_RESP_BIT) of
 * step / 8 (at most 127). */
_Static_assert(BISS_CD_RESP == 0x400 && BISS_SHM_CD_RESP_BYTES <= 0x400,
               "CD_COMMIT's answer address is a bit set");
/* C28 (the private area) is set in 256-byte pages. */
_Static_assert(BISS_PRIV % 256 == 0 && BISS_PRIV_END - BISS_PRIV == 256, "private area: one page");
_Static_assert(sizeof(struct biss_shm) == BISS_RING_END, "shared area size");
_Static_assert(sizeof(struct biss_shm) <= BISS_DRAM_BYTES, "shared area fits the data RAM");

/* The identification block and the resource table (biss_shm.h). */
struct biss_shm_id {
    uint32_t magic;       /* BISS_ID_MAGIC */
    uint32_t shm_version; /* BISS_SHM_VERSION of the image's build */
    uint32_t image_crc;   /* CRC-32 of the IRAM image */
    uint32_t image_bytes;
};
_Static_assert(sizeof(struct biss_shm) <= BISS_ID, "the identification block is above the shm");
_Static_assert(BISS_ID + sizeof(struct biss_shm_id) == BISS_RSC_TABLE, "id block size");
_Static_assert(BISS_RSC_TABLE + 16 == BISS_ID_END && BISS_ID_END == BISS_DRAM_BYTES,
               "the resource table ends the 4 KB data RAM");

#undef BISS_SHM_AT
#undef BISS_SHM_SLAVE_CFG_AT
#undef BISS_SHM_RESULT_AT
#undef BISS_SHM_SLAVE_RESULT_AT

#endif
