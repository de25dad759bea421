/*
 * slave_fw.h - the encoder firmware (pru_slave/, a BiSS-C slave on a PRU)
 * as the bench's encoder: the slave model's chain (a scenario's "biss") as
 * the firmware's configuration, register files and bank pool, written
 * through proto into the data RAM of the PRU it runs on. One scenario
 * then drives either end: the C model (emulator/slave/) or the firmware.
 */
#ifndef SLAVE_FW_H
#define SLAVE_FW_H

#include "biss_proto.h"
#include "biss_slave.h"
#include "pru_core.h"

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

/* A PRU's data RAM through the host side of a core (pru_host_read/write at
 * the global address of PRU pru's data RAM). */
struct slave_fw_ram {
    struct pru_core *core;
    uint32_t base; /* global address of the data RAM */
};
void slave_fw_ram_init(struct slave_fw_ram *ram, struct pru_core *core, enum pru_soc soc,
                       unsigned pru);
struct biss_proto_io slave_fw_io(struct slave_fw_ram *ram);

/* The chain as the firmware's configuration: 0, or -1 with err naming the
 * field the firmware cannot take ("biss.slaves[0].speed_cps: ...": it
 * moves by counts per frame; life-counter and position faults; register
 * processing over 255 frames; banks past the pool's 16, allocated in the
 * slaves' order). Register banks go to the pool in the slaves' order. */
int slave_fw_config(const biss_chain_cfg *c, struct biss_encoder_config *e, char *err,
                    size_t errlen);

/* The chain as the encoder firmware runs it: each slave that moves with
 * time (speed_cps) moves by counts per frame instead, the nearest whole
 * number of counts in frame_ps; register banks past the firmware's pool
 * (16 for the chain) are dropped, the last slaves' first (a note on
 * notes for each, unless NULL). The model beside the firmware runs the
 * same chain. */
void slave_fw_chain(biss_chain_cfg *c, double frame_ps, FILE *notes);

/* slave_fw_config, then the register files and banks of the chain's
 * models and the configuration block with CFG_SEQ one up: 0, or -1 with
 * err set (a transfer's failure included). */
int slave_fw_load(const struct biss_proto_io *io, const biss_chain_cfg *c, char *err,
                  size_t errlen);

#endif
