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

/* Starts the firmware image on the bench's PRU as a host does: loads it
 * and starts it (the image must be the one built for that PRU,
 * pru_fw/README.md). 0 or -1 (too big). */
int bench_fw_start(struct bench *b, const void *image, size_t bytes);

/* The bench's PRU's data RAM, through host accesses at the SoC's address. */
struct biss_proto_io bench_fw_io(struct bench *b);

/* A BiSS-C model slave's data-word fields, for proto's layout rule. */
struct biss_proto_word bench_fw_word(const biss_slave_cfg *s);
/* Any model's word (slave_model words), the same way. */
struct biss_proto_word bench_fw_slave_word(const slave_word *w);

/* The model's layout as libbiss describes it (slave_model words):
 * nslaves, each slave's data word (proto's layout rule), or an SSI
 * encoder with the line's round trip from the model (an SSI slave gives
 * no ACK to measure it by); and the scenario's safety checks. */
void bench_fw_layout(const struct bench *b, struct biss_config *c);

/* The configuration a host gives the chain: biss_config_default with the
 * chain's layout (bench_fw_layout). The caller sets the rate, trigger,
 * IEP period and processing-time limit, as for biss_configure. */
void bench_fw_config(const struct bench *b, struct biss_config *c);

/* The configuration block for c, encoded by proto as libbiss encodes it:
 * the MA half period from c->freq_hz by proto's rate rule, or, when half
 * is not 0, H = half as given (biss_config_encode_half): a rate the
 * firmware clocks that no whole number of Hz names, or one it refuses
 * (the bench tests that refusal). */
void bench_fw_block(const struct biss_config *c, unsigned half, struct biss_shm_config *blk);

/* Writes a block and increments CFG_SEQ. Returns 0 or a negative code. */
int bench_fw_put_block(struct bench *b, const struct biss_shm_config *blk);

/* bench_fw_block, then bench_fw_put_block; tells the bench H for its
 * frame marks (bench_set_ma_half). */
int bench_fw_configure(struct bench *b, const struct biss_config *c, unsigned half);

/* The firmware's status words (zeroed if unreadable). */
struct biss_shm_status bench_fw_status(struct bench *b);

#endif
