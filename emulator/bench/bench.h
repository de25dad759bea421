/*
 * bench.h - one emulated PRU wired through a cable to BiSS-C or SSI slaves.
 *
 *   PRU R30[ma_bit] --MA line--> slave(s) --SL line--> PRU R31[0]
 *
 * The PRU core runs the image; every R30 change enters the MA line model at
 * its exact pin time, the slave reacts to MA as it arrives, and its SL edges
 * travel back through the SL line model into a waveform that the core
 * samples (directly or through the 28-bit shift register). All models share
 * one event queue in picoseconds; before the core looks at its inputs at
 * time t the queue is run up to t, which is exact because every effect comes
 * strictly after its cause.
 *
 * The bench also watches the wire: it counts frames as the slave closes
 * them, measures MA half periods and frame periods at the master pin, and
 * can record MA/SL at both ends into a VCD file.
 */
#ifndef BENCH_H
#define BENCH_H

#include "biss_slave.h"
#include "line_model.h"
#include "pru_core.h"
#include "ssi_slave.h"

#include <stdbool.h>
#include <stdint.h>

enum bench_slave_kind { BENCH_SLAVE_BISS, BENCH_SLAVE_SSI };

struct bench_config {
    enum pru_soc soc;
    struct pru_params pru;
    unsigned ma_bit;            /* R30 bit that drives MA, default 1 */
    line_params ma_line;        /* master -> slave */
    line_params sl_line;        /* slave -> master */
    enum bench_slave_kind kind;
    biss_chain_cfg chain;       /* kind == BENCH_SLAVE_BISS */
    ssi_cfg ssi;                /* kind == BENCH_SLAVE_SSI */
    uint64_t seed;
};

/* Defaults: AM335x, MA on R30 bit 1, 0 m of cable with default
 * transceivers, one default BiSS-C slave, seed 1. */
void bench_config_default(struct bench_config *c);

/* Sets both directions of the cable to length_m. */
void bench_config_set_cable(struct bench_config *c, double length_m);

/* What the bench measured at the master's MA pin and at the slave. */
struct bench_stats {
    uint64_t frames;           /* frames the slave closed */
    uint64_t frames_started;   /* frames the master began */
    uint64_t half_periods;     /* MA half periods measured inside frames */
    int64_t half_min_ps, half_max_ps;
    uint64_t periods;          /* frame-start to frame-start intervals */
    int64_t period_min_ps, period_max_ps;
    double period_sum_ps;
    uint64_t ma_edges_master;  /* MA edges the PRU drove */
    uint64_t ma_edges_slave;   /* MA edges that reached the slave */
};

struct bench;

/* Returns NULL and a message in err when cfg is invalid or memory ran out. */
struct bench *bench_new(const struct bench_config *cfg, char *err, size_t errlen);
void bench_free(struct bench *b);

/* Records MA_master, SL_master, MA_slave, SL_slave (scope "bench") from now
 * on. Returns 0, or -1 if the file cannot be written. */
int bench_open_vcd(struct bench *b, const char *path);

/* The core, for loading images, host access to its memories and running. */
struct pru_core *bench_core(struct bench *b);

/* Loads a raw IRAM image and starts the PRU at PC 0. */
int bench_start_image(struct bench *b, const void *image, size_t bytes);

/* Runs the PRU (and the models) until simulated time t_ps. */
enum pru_stop bench_run_until(struct bench *b, int64_t t_ps);

/* Runs until the slave has closed `frames` frames in all, the PRU halts or
 * faults, or max_ps of simulated time has passed. progress, if set, is
 * called now and then with the frames so far. */
enum pru_stop bench_run_frames(struct bench *b, uint64_t frames, int64_t max_ps,
                               void (*progress)(void *ctx, uint64_t done, uint64_t total),
                               void *ctx);

const struct bench_stats *bench_stats(struct bench *b);
const struct bench_config *bench_config(const struct bench *b);

/* The slave models, to read what they sent (frame records) and to steer them. */
biss_slave *bench_biss(struct bench *b); /* NULL unless kind == BENCH_SLAVE_BISS */
ssi_slave *bench_ssi(struct bench *b);   /* NULL unless kind == BENCH_SLAVE_SSI */

/* Round trip the master sees from an MA edge to the SL answer, per the
 * models: MA line + slave output delay + SL line, nominal (no jitter). */
double bench_round_trip_ps(const struct bench *b);

/* The MA and SL line models (for fault injection and their counters). */
line_dir *bench_ma_line(struct bench *b);
line_dir *bench_sl_line(struct bench *b);

/* Flushes and closes the VCD, if one is open. Returns 0 or -1. */
int bench_close_vcd(struct bench *b);

#endif
