/*
 * biss_slave_shm_struct.h - the C struct view of the BiSS-C slave
 * firmware's shared-memory layout in biss_slave_shm.h (the slave PRU's data
 * RAM, little-endian).
 *
 * biss_slave_shm.h is the source of truth: every field below is checked
 * against its offset there at compile time, so the two views cannot drift
 * apart. Fields are ordered so that natural alignment gives the packed
 * layout; no compiler-specific packing is needed.
 */
#ifndef BISS_SLAVE_SHM_STRUCT_H
#define BISS_SLAVE_SHM_STRUCT_H

#include "biss_shm.h"
#include "biss_slave_shm.h"

#include <stddef.h>
#include <stdint.h>

#if defined(__BYTE_ORDER__) && __BYTE_ORDER__ != __ORDER_LITTLE_ENDIAN__
#error "the shared-memory struct view assumes a little-endian host, as the PRU is"
#endif

/* One slave's block of the configuration (BISS_SLV_S_*). */
struct biss_slv_slave_cfg {
    uint8_t pos_bits;  /* 1..64 */
    uint8_t fill_bits; /* zeros after the position */
    uint8_t lc_bits;   /* life counter, 0..32 */
    uint8_t flags;     /* BISS_SLV_SF_* */
    uint8_t crc_bits;  /* 0..16 */
    uint8_t id;        /* 0..7 */
    uint8_t reg_wait;  /* late S: frames of register processing */
    uint8_t banks;     /* register banks in the pool */
    uint16_t crc_poly; /* without its top term */
    uint16_t crc_start;
    uint8_t bank0;       /* first bank in the pool */
    uint8_t table_start; /* table mode: first entry */
    uint16_t table_len;  /* 0: position + step a frame; else table mode */
    uint64_t position;   /* the first frame's position */
    uint64_t step;       /* counts a frame, two's complement */
};

/* The configuration block the host writes (BISS_SLV_CFG_*), with the live
 * nE/nW bits between the chain's and the slaves' blocks. */
struct biss_slv_config {
    uint32_t seq;
    uint8_t nslaves;
    uint8_t tmo_mode;   /* BISS_SLV_TMO_* */
    uint8_t tmo_factor; /* adaptive: period x factor / 16 */
    uint8_t rsvd0;
    uint32_t timeout; /* PRU cycles: fixed, or the adaptive one's longest */
    uint32_t tmo_min; /* adaptive: its shortest */
    uint32_t busy_cycles;
    uint16_t busy_clocks;
    uint16_t rsvd1;
    uint8_t live_ew[BISS_SLV_MAX_SLAVES]; /* BISS_SLV_EW_* */
    struct biss_slv_slave_cfg slave[BISS_SLV_MAX_SLAVES];
};

/* What control communication did to one slave (BISS_SLV_SS_*). */
struct biss_slv_slave_status {
    uint16_t commands;
    uint16_t dropped;
    uint8_t last_cmd;
    uint8_t last_addr;
    uint8_t last_value;
    uint8_t rsvd;
    uint16_t reads;
    uint16_t writes;
    uint16_t refused;
    uint16_t crc_errors;
};

/* Status words the firmware writes (BISS_SLV_ST_*). */
struct biss_slv_status {
    uint32_t magic;
    uint32_t pru;
    uint32_t cfg_ack;
    uint32_t cfg_error;
    uint32_t frames;
    uint32_t latches;
    uint32_t cd_frames;
    uint8_t cdm;
    uint8_t cds;
    uint8_t ctrl_state;
    uint8_t ma_bit;
    uint16_t cancels;
    uint16_t hdr_crc_errors;
    uint32_t period;
    uint32_t timeout;
    uint16_t work;
    uint16_t work_pad;
    struct biss_slv_slave_status slave[BISS_SLV_MAX_SLAVES];
};

/* What the next frame sends (BISS_SLV_REC_*). */
struct biss_slv_frame_rec {
    uint32_t frame;
    uint8_t cds;
    uint8_t nslaves;
    uint16_t rsvd;
    uint64_t word[BISS_SLV_MAX_SLAVES]; /* data words, left-aligned (first bit at bit 63) */
};

/* One slave's register file (BISS_SLV_R_*). */
struct biss_slv_regs {
    uint8_t direct[64]; /* 0x40..0x7F */
    uint8_t ro[16];     /* bit a % 8 of byte a / 8: read-only */
    uint8_t wp[16];     /* write-protected */
};

/* The slave PRU's data RAM up to the identification block. */
struct biss_slv_shm {
    struct biss_slv_config cfg;
    struct biss_slv_status st;
    struct biss_slv_frame_rec rec;
    uint8_t gap_rec[BISS_SLV_PRIV - BISS_SLV_REC_END];
    uint8_t priv[BISS_SLV_PRIV_END - BISS_SLV_PRIV];
    struct biss_slv_regs regs[BISS_SLV_MAX_SLAVES];
    uint8_t gap_regs[BISS_SLV_POOL - BISS_SLV_REGS - BISS_SLV_MAX_SLAVES * BISS_SLV_REGS_SIZE];
    uint8_t pool[BISS_SLV_POOL_BANKS][BISS_SLV_BANK_SIZE];
    uint64_t table[BISS_SLV_TABLE_ENTRIES];
    uint8_t priv2[BISS_SLV_PRIV2_END - BISS_SLV_PRIV2];
};

/* ---- compile-time agreement with biss_slave_shm.h ----------------------- */
#define BISS_SLV_AT(member, off)                                                                   \
    _Static_assert(offsetof(struct biss_slv_shm, member) == (off), #member " is not at " #off)
#define BISS_SLV_SLAVE_CFG_AT(member, off)                                                         \
    _Static_assert(offsetof(struct biss_slv_slave_cfg, member) == (off),                           \
                   "slave cfg " #member " is not at " #off)
#define BISS_SLV_SLAVE_ST_AT(member, off)                                                          \
    _Static_assert(offsetof(struct biss_slv_slave_status, member) == (off),                        \
                   "slave status " #member " is not at " #off)
#define BISS_SLV_REGS_AT(member, off)                                                              \
    _Static_assert(offsetof(struct biss_slv_regs, member) == (off),                                \
                   "register file " #member " is not at " #off)

BISS_SLV_AT(cfg.seq, BISS_SLV_CFG_SEQ);
BISS_SLV_AT(cfg.nslaves, BISS_SLV_CFG_NSLAVES);
BISS_SLV_AT(cfg.tmo_mode, BISS_SLV_CFG_TMO_MODE);
BISS_SLV_AT(cfg.tmo_factor, BISS_SLV_CFG_TMO_FACTOR);
BISS_SLV_AT(cfg.rsvd0, BISS_SLV_CFG_RSVD0);
BISS_SLV_AT(cfg.timeout, BISS_SLV_CFG_TIMEOUT);
BISS_SLV_AT(cfg.tmo_min, BISS_SLV_CFG_TMO_MIN);
BISS_SLV_AT(cfg.busy_cycles, BISS_SLV_CFG_BUSY_CYCLES);
BISS_SLV_AT(cfg.busy_clocks, BISS_SLV_CFG_BUSY_CLOCKS);
BISS_SLV_AT(cfg.rsvd1, BISS_SLV_CFG_RSVD1);
BISS_SLV_AT(cfg.live_ew, BISS_SLV_LIVE_EW);
BISS_SLV_AT(cfg.slave, BISS_SLV_CFG_SLAVE0);
BISS_SLV_AT(cfg.slave[1], BISS_SLV_CFG_SLAVE0 + BISS_SLV_CFG_SLAVE_SIZE);
_Static_assert(sizeof(struct biss_slv_config) == BISS_SLV_CFG_END, "config block size");
_Static_assert(sizeof(struct biss_slv_slave_cfg) == BISS_SLV_CFG_SLAVE_SIZE, "slave block size");
_Static_assert(BISS_SLV_CFG_SLAVE0 + BISS_SLV_MAX_SLAVES * BISS_SLV_CFG_SLAVE_SIZE ==
                   BISS_SLV_CFG_END,
               "the slave blocks end the configuration");
BISS_SLV_SLAVE_CFG_AT(pos_bits, BISS_SLV_S_POS_BITS);
BISS_SLV_SLAVE_CFG_AT(fill_bits, BISS_SLV_S_FILL_BITS);
BISS_SLV_SLAVE_CFG_AT(lc_bits, BISS_SLV_S_LC_BITS);
BISS_SLV_SLAVE_CFG_AT(flags, BISS_SLV_S_FLAGS);
BISS_SLV_SLAVE_CFG_AT(crc_bits, BISS_SLV_S_CRC_BITS);
BISS_SLV_SLAVE_CFG_AT(id, BISS_SLV_S_ID);
BISS_SLV_SLAVE_CFG_AT(reg_wait, BISS_SLV_S_REG_WAIT);
BISS_SLV_SLAVE_CFG_AT(banks, BISS_SLV_S_BANKS);
BISS_SLV_SLAVE_CFG_AT(crc_poly, BISS_SLV_S_CRC_POLY);
BISS_SLV_SLAVE_CFG_AT(crc_start, BISS_SLV_S_CRC_START);
BISS_SLV_SLAVE_CFG_AT(bank0, BISS_SLV_S_BANK0);
BISS_SLV_SLAVE_CFG_AT(table_start, BISS_SLV_S_TABLE_START);
BISS_SLV_SLAVE_CFG_AT(table_len, BISS_SLV_S_TABLE_LEN);
BISS_SLV_SLAVE_CFG_AT(position, BISS_SLV_S_POSITION);
BISS_SLV_SLAVE_CFG_AT(step, BISS_SLV_S_STEP);

BISS_SLV_AT(st, BISS_SLV_ST_MAGIC);
BISS_SLV_AT(st.pru, BISS_SLV_ST_PRU);
BISS_SLV_AT(st.cfg_ack, BISS_SLV_ST_CFG_ACK);
BISS_SLV_AT(st.cfg_error, BISS_SLV_ST_CFG_ERROR);
BISS_SLV_AT(st.frames, BISS_SLV_ST_FRAMES);
BISS_SLV_AT(st.latches, BISS_SLV_ST_LATCHES);
BISS_SLV_AT(st.cd_frames, BISS_SLV_ST_CD_FRAMES);
BISS_SLV_AT(st.cdm, BISS_SLV_ST_CDM);
BISS_SLV_AT(st.cds, BISS_SLV_ST_CDS);
BISS_SLV_AT(st.ctrl_state, BISS_SLV_ST_CTRL_STATE);
BISS_SLV_AT(st.ma_bit, BISS_SLV_ST_MA_BIT);
BISS_SLV_AT(st.cancels, BISS_SLV_ST_CANCELS);
BISS_SLV_AT(st.hdr_crc_errors, BISS_SLV_ST_HDR_CRC_ERRORS);
BISS_SLV_AT(st.period, BISS_SLV_ST_PERIOD);
BISS_SLV_AT(st.timeout, BISS_SLV_ST_TIMEOUT);
BISS_SLV_AT(st.work, BISS_SLV_ST_WORK);
BISS_SLV_AT(st.work_pad, BISS_SLV_ST_WORK_PAD);
BISS_SLV_AT(st.slave, BISS_SLV_ST_SLAVE0);
BISS_SLV_AT(st.slave[1], BISS_SLV_ST_SLAVE0 + BISS_SLV_ST_SLAVE_SIZE);
_Static_assert(BISS_SLV_ST_MAGIC + sizeof(struct biss_slv_status) == BISS_SLV_ST_END,
               "status size");
_Static_assert(sizeof(struct biss_slv_slave_status) == BISS_SLV_ST_SLAVE_SIZE, "slave status size");
BISS_SLV_SLAVE_ST_AT(commands, BISS_SLV_SS_COMMANDS);
BISS_SLV_SLAVE_ST_AT(dropped, BISS_SLV_SS_DROPPED);
BISS_SLV_SLAVE_ST_AT(last_cmd, BISS_SLV_SS_LAST_CMD);
BISS_SLV_SLAVE_ST_AT(last_addr, BISS_SLV_SS_LAST_ADDR);
BISS_SLV_SLAVE_ST_AT(last_value, BISS_SLV_SS_LAST_VALUE);
BISS_SLV_SLAVE_ST_AT(rsvd, BISS_SLV_SS_RSVD);
BISS_SLV_SLAVE_ST_AT(reads, BISS_SLV_SS_READS);
BISS_SLV_SLAVE_ST_AT(writes, BISS_SLV_SS_WRITES);
BISS_SLV_SLAVE_ST_AT(refused, BISS_SLV_SS_REFUSED);
BISS_SLV_SLAVE_ST_AT(crc_errors, BISS_SLV_SS_CRC_ERRORS);

BISS_SLV_AT(rec.frame, BISS_SLV_REC_FRAME);
BISS_SLV_AT(rec.cds, BISS_SLV_REC_CDS);
BISS_SLV_AT(rec.nslaves, BISS_SLV_REC_NSLAVES);
BISS_SLV_AT(rec.rsvd, BISS_SLV_REC_RSVD);
BISS_SLV_AT(rec.word, BISS_SLV_REC_WORD0);
_Static_assert(BISS_SLV_REC_FRAME + sizeof(struct biss_slv_frame_rec) == BISS_SLV_REC_END,
               "frame record size");

BISS_SLV_AT(priv, BISS_SLV_PRIV);
BISS_SLV_AT(regs, BISS_SLV_REGS);
BISS_SLV_AT(regs[1], BISS_SLV_REGS + BISS_SLV_REGS_SIZE);
_Static_assert(sizeof(struct biss_slv_regs) == BISS_SLV_REGS_SIZE, "register file size");
BISS_SLV_REGS_AT(direct, BISS_SLV_R_DIRECT);
BISS_SLV_REGS_AT(ro, BISS_SLV_R_RO);
BISS_SLV_REGS_AT(wp, BISS_SLV_R_WP);
BISS_SLV_AT(pool, BISS_SLV_POOL);
BISS_SLV_AT(pool[1], BISS_SLV_POOL + BISS_SLV_BANK_SIZE);
BISS_SLV_AT(table, BISS_SLV_TABLE);
BISS_SLV_AT(priv2, BISS_SLV_PRIV2);
_Static_assert(sizeof(struct biss_slv_shm) == BISS_SLV_PRIV2_END, "shared area size");
/* The master's identification block and resource table (biss_shm.h) sit at
 * the top of the 4 KB data RAM in this image too: the same loaders and
 * ELF writer serve both firmwares. */
_Static_assert(BISS_SLV_PRIV2_END <= BISS_ID, "the shared area stays below the identification");

#undef BISS_SLV_AT
#undef BISS_SLV_SLAVE_CFG_AT
#undef BISS_SLV_SLAVE_ST_AT
#undef BISS_SLV_REGS_AT

#endif
