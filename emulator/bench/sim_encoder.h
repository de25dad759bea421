/*
 * sim_encoder.h - biss-sim --encoder: the master firmware on PRU0 reads
 * the encoder firmware (pru_slave/) on PRU1 of the same PRU-ICSS through
 * the line model (bench_new_loop), the scenario's slave model running
 * beside the firmware on the same MA: the bench checks the master's
 * frames against the model's, and compares the model's SL with the
 * firmware's at every rising MA edge at the slave pin.
 */
#ifndef SIM_ENCODER_H
#define SIM_ENCODER_H

#include "bench.h"
#include "slave_fw.h"

#include <cjson/cJSON.h>
#include <stddef.h>
#include <stdio.h>

struct sim_encoder {
    struct bench *b;
    struct slave_fw_ram ram;
    struct biss_proto_io io;
};

/* Loads the image on PRU1 of a bench_new_loop bench, runs it to its
 * start, takes its MA bit, writes the chain (slave_fw_load) and runs
 * until the firmware has accepted it. 0, or -1 with a message in err. */
int sim_encoder_start(struct sim_encoder *e, struct bench *b, const void *image, size_t bytes,
                      const biss_chain_cfg *chain, char *err, size_t errlen);

/* The firmware's status and the comparison with the model: text lines,
 * or the object "encoder" added to j. Returns 0, or 5 when SL differed
 * from the model's or the firmware stopped. */
int sim_encoder_report(const struct sim_encoder *e, cJSON *j);

#endif
