/*
 * bench_fw.h - the bench as the firmware's host: its PRU0 data RAM as a
 * reader/writer for the protocol layer (proto/biss_proto.h), and the
 * bench's own slave chain as the configuration a host would write. Every
 * word goes through proto: the bench keeps no layout of its own.
 */
#ifndef BENCH_FW_H
#define BENCH_FW_H

#include "bench.h"
#include "biss_proto.h"
#include "biss_soc.h"

/* What a bench run chooses beyond the chain (which the models fix). */
struct bench_fw_settings {
    unsigned half;       /* MA half period in PRU cycles (f = 100 MHz / half) */
    unsigned trigger;    /* BISS_TRIG_* */
    uint32_t iep_period; /* IEP counts, for BISS_TRIG_IEP (fw_check_configure: the owner's
                            for BISS_TRIG_IEP_FOLLOW) */
    unsigned proc_limit; /* longest processing time accepted, MA clocks */
};

/* Starts the firmware image on the bench's PRU as a host does: loads it
 * and starts it (the image must be the one built for that PRU,
 * pru_fw/README.md). 0 or -1 (too big). */
int bench_fw_start(struct bench *b, const void *image, size_t bytes);

/* The bench's PRU's data RAM, through host accesses at the SoC's address. */
struct biss_proto_io bench_fw_io(struct bench *b);

/* A model slave's data-word fields, for proto's layout rule. */
struct biss_proto_word bench_fw_word(const biss_slave_cfg *s);

/* The chain's layout as libbiss describes it: nslaves, each slave's data
 * word (proto's layout rule), or the SSI encoder with the line's round
 * trip from the model (an SSI slave gives no ACK to measure it by). */
void bench_fw_layout(const struct bench *b, struct biss_config *c);

/* The configuration block for the chain and s, encoded by proto. The half
 * period goes in as given, even one the firmware will refuse (the bench
 * tests that refusal). */
void bench_fw_block(const struct bench *b, const struct bench_fw_settings *s,
                    struct biss_shm_config *blk);

/* Writes a block and increments CFG_SEQ. Returns 0 or a negative code. */
int bench_fw_put_block(struct bench *b, const struct biss_shm_config *blk);

/* bench_fw_block, then bench_fw_put_block; tells the bench H for its
 * frame marks (bench_set_ma_half). */
int bench_fw_configure(struct bench *b, const struct bench_fw_settings *s);

/* The firmware's status words (zeroed if unreadable). */
struct biss_shm_status bench_fw_status(struct bench *b);

#endif
