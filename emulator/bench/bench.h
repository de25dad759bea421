/*
 * bench.h - one emulated PRU wired through a cable to BiSS-C or SSI slaves.
 *
 *   PRU R30[ma_bit] --MA line--> slave(s) --SL line--> PRU R31[0]
 *
 * The PRU core runs the image; every R30 change enters the link (line
 * models and slaves, emulator/slave/link_model.h) at its exact pin time, and
 * the core samples SL at the master from the link's record, directly or
 * through the 28-bit shift register. Before the core looks at its inputs at
 * time t the link runs up to t, which is exact because every effect comes
 * strictly after its cause.
 *
 * The bench also watches the pins: it measures MA half periods and frame
 * periods at the master pin (for the edges the slave counted as part of a
 * frame), writes MA/SL at both ends to a VCD file, and captures one frame
 * for a scope picture.
 */
#ifndef BENCH_H
#define BENCH_H

#include "iep_track.h"
#include "link_model.h"
#include "pru_core.h"
#include "sl_tape.h"
#include "waveform.h"

#include <stdbool.h>
#include <stdint.h>

struct bench_config {
    enum pru_soc soc;
    struct pru_params pru;
    unsigned ma_bit; /* R30 bit that drives MA, default 1 */
    scenario link;   /* cable, slave(s), seed */
    /* The PRU of the PRU-ICSS wired to the line: 0 (default: a core alone)
     * or 1 (PRU1 of a PRU-ICSS whose PRU0 stays idle, emulator/core/pruss.h) */
    unsigned pru_index;
    /* the fast path "sl-reach" off: the SL input's next change is the next
     * pending event of any kind (link_next_sl_change) */
    int no_sl_reach;
    /* the fast path "line-settled" off: every edge through the lines'
     * low-pass arithmetic (line_dir_set_settled_fast) */
    int no_line_settled;
    /* the fast path "slave-quick" off: every MA edge through a BiSS-C
     * chain's general step (link_set_slave_quick) */
    int no_slave_quick;
    /* the fast path "ma-ahead" on (link_set_ma_ahead; off by default): a
     * BiSS-C frame's clock edges taken by the slave when the core drives
     * them. A run that stops short of such an edge's arrival (a halt, a
     * fault) is then no longer the one the event order gives: the caller
     * asks bench_ahead_overrun() and runs again without it. Single PRU. */
    int ma_ahead;
    /* the fast path "ahead-batch" off: the edges "ma-ahead" takes are
     * measured one by one, not in batches (link_batch_ahead) */
    int no_ahead_batch;
};

/* Defaults: AM335x, MA on R30 bit 1, the "generic" profile. */
void bench_config_default(struct bench_config *c);

/* A measured time over frames: count, least, greatest and sum, in ps. */
struct bench_span {
    uint64_t n;
    int64_t min_ps, max_ps;
    int64_t sum_ps; /* (2^63 ps: three months of spans) */
};

/* What the bench measured at the master's MA pin and at the slave. */
struct bench_stats {
    uint64_t frames;         /* frames the slave closed */
    uint64_t frames_started; /* frames the master began */
    uint64_t half_periods;   /* MA half periods measured inside frames */
    int64_t half_min_ps, half_max_ps;
    uint64_t periods; /* frame-start to frame-start intervals */
    int64_t period_min_ps, period_max_ps;
    double period_sum_ps;
    uint64_t ma_edges_master; /* MA edges the PRU drove */
    uint64_t ma_edges_slave;  /* MA edges that reached the slave */
    /* Frames as the master's MA pin shows them, once bench_set_ma_half()
     * has told the bench H (emulator/bench/INSTRUMENTS.md): a frame's
     * first falling edge is an MA fall at the master pin that does not
     * close a clock period (its high phase or the low phase before it is
     * not H). */
    struct bench_span ma_high; /* the MA high phase before each first fall */
    uint64_t ma_high_short;    /* ... of those, shorter than H */
    /* SL rising at the master pin at the end of the previous frame's
     * timeout (the slave's SL rise after it, through the SL line) to the
     * first fall */
    struct bench_span restart;
    /* IEP (CMP0 resetting COUNT): the period's start (COUNT back to 0) to
     * the first fall, and the periods the first falls lie in */
    struct bench_span iep_phase;
    uint32_t iep_period;        /* cycles (IEP ticks) per period, 0: no periodic IEP seen */
    uint64_t iep_periods;       /* periods from the first frame measured to the last */
    uint64_t iep_skipped;       /* ... in which no frame started */
    uint64_t iep_crowded;       /* ... in which more than one started */
    struct iep_track iep_track; /* each frame's start against its BISS_RF_IEP_LATE */
};

struct bench;

/* Returns NULL and a message in err when cfg is invalid or memory ran out. */
struct bench *bench_new(const struct bench_config *cfg, char *err, size_t errlen);
void bench_free(struct bench *b);

/* Two lines and their slaves on the two PRUs of one PRU-ICSS: b[0] on
 * PRU0 with cfg[0], b[1] on PRU1 with cfg[1] (soc and the core
 * parameters are cfg[0]'s; the pru_index fields are ignored). Running either
 * bench runs both PRUs and both links, cycle by cycle together, sharing
 * the IEP and the RAMs. Free b[1] first, then b[0]. Returns 0, or -1 with
 * a message in err (and b[] NULL). */
int bench_new_pair(const struct bench_config cfg[2], struct bench *b[2], char *err, size_t errlen);

/* The master's PRU0 and, as the slave end of its line, the BiSS-C
 * encoder firmware (pru_slave/) on PRU1 of the same PRU-ICSS: MA at the
 * slave pin on one of PRU1's R31 bits (1 unless set), its R30 bit 0 the SL pin
 * (the one-board loop of docs/hardware.md, through the line model). The
 * scenario's slave model runs beside the firmware on the same MA: the
 * bench numbers and checks frames by it, and compares its SL with the
 * firmware's at every rising MA edge at the slave pin
 * (link_set_external_slave). cfg->pru_index is ignored. Load and start the
 * encoder (bench_encoder_core, slave_fw.h) before the master. */
struct bench *bench_new_loop(const struct bench_config *cfg, char *err, size_t errlen);
/* The encoder's core (PRU1) of a bench_new_loop bench, else NULL. */
struct pru_core *bench_encoder_core(struct bench *b);
/* The R31 bit MA comes in on at PRU1 (the image's BISS_SLV_ST_MA_BIT):
 * 0, or -1 for no encoder or a bit over 29. */
int bench_set_encoder_ma_bit(struct bench *b, unsigned bit);

/* Records MA_master, SL_master, MA_slave, SL_slave and frame (scope
 * "bench") from now on, with the timescale unit_ps (1, 10, 100 or 1000 ps:
 * vcd.h says how edges keep their order). The frame wire is high from a
 * frame's first MA edge at the master to half a period after its last (the
 * edges the slave took as that frame's): a chip select for decoders.
 * Returns 0, or -1 with errno set if the file
 * cannot be written or unit_ps is none of those. */
int bench_open_vcd(struct bench *b, const char *path, int64_t unit_ps);
/* Flushes and closes the VCD, if one is open. Returns 0 or -1. */
int bench_close_vcd(struct bench *b);
/* Why the VCD could not be opened or written: its path and the reason. */
const char *bench_vcd_error(const struct bench *b);

/* SL at the master's pin on tape (sl_tape.h). bench_tape_record: every
 * edge from the start of the run written to path as the run goes (a core
 * alone; 0, or -1 with the path and errno's text in err);
 * bench_tape_finish ends the tape with the run's end (0 or -1 as well).
 * bench_tape_play: the core reads SL from tape t instead of the link, and
 * its MA edges go nowhere (no model runs); bench_tape_same then tells
 * whether the run was the recorded one (sl_tape_same). */
int bench_tape_record(struct bench *b, const char *path, char *err, size_t errlen);
int bench_tape_finish(struct bench *b, char *err, size_t errlen);
void bench_tape_play(struct bench *b, struct sl_tape *t);
bool bench_tape_same(struct bench *b, const struct sl_tape *t);

/* The core, for loading images, host access to its memories and running. */
struct pru_core *bench_core(struct bench *b);
/* The far end: slave models (frame records, register files) and lines. */
link_model *bench_link(struct bench *b);

/* Loads a raw IRAM image and starts the PRU at PC 0. */
int bench_start_image(struct bench *b, const void *image, size_t bytes);

/* Runs the PRU (and the link) until simulated time t_ps. */
enum pru_stop bench_run_until(struct bench *b, int64_t t_ps);
/* Whether a run stopped short of an MA edge the slave took ahead (the
 * fast path "ma-ahead"): its results are not exact, run it again without. */
bool bench_ahead_overrun(const struct bench *b);

/* Runs until the slave has closed `frames` frames in all, the PRU halts or
 * faults, or max_ps of simulated time has passed. Frames beyond `frames`
 * that close within the last step are neither counted nor measured.
 * progress, if set, is called now and then with the frames so far. */
enum pru_stop bench_run_frames(struct bench *b, uint64_t frames, int64_t max_ps,
                               void (*progress)(void *ctx, uint64_t done, uint64_t total),
                               void *ctx);

const struct bench_stats *bench_stats(struct bench *b);

/* The firmware published the slave's frame `frame` with flags (BISS_RF_*):
 * for the IEP frames' judgement (iep_track.h, bench_stats' iep_track). */
void bench_iep_published(struct bench *b, uint64_t frame, uint32_t flags);

/* The MA half period H in PRU cycles the image clocks with (0: unknown,
 * the default: no frame marks), for the frame marks of bench_stats. */
void bench_set_ma_half(struct bench *b, unsigned half);

/* Starts the measurements afresh (e.g. after a start-up phase). */
void bench_reset_stats(struct bench *b);

/* Frames the slave numbers `frames` and later are not measured. */
void bench_set_frame_limit(struct bench *b, uint64_t frames);
const struct bench_config *bench_config(const struct bench *b);

/* The slave's number for the frame the master began last (its first MA
 * edge has reached the slave), or UINT64_MAX before the first. */
uint64_t bench_current_frame(struct bench *b);
/* When that frame's first MA edge left the master pin (ps), -1 before the
 * first frame measured. */
int64_t bench_frame_start_ps(struct bench *b);

/* Round trip the master sees from an MA edge to the SL answer, per the
 * models: MA line + slave output delay + SL line, nominal (no jitter). */
double bench_round_trip_ps(const struct bench *b);
/* The same to the nearest ns: what a user measures and configures as an SSI
 * encoder's line delay (the configuration's ssi_delay_ns). */
uint32_t bench_ssi_delay_ns(const struct bench *b);

/* Arms a capture of all four pins around frame k (k counts the frames the
 * slave sees, from 0) for a scope picture. */
void bench_capture_frame(struct bench *b, uint64_t k);

/* The captured pins (MA_master, SL_master, MA_slave, SL_slave) and the
 * window that shows frame k whole. Returns 0, or -1 if frame k has not been
 * captured completely. */
int bench_capture_get(struct bench *b, waveform *pins[4], sim_ps *t0, sim_ps *t1);

/* The captured frame's record (the link's model's: slave_model record),
 * kept when the frame closed: the model's own ring of records moves on.
 * NULL until the capture is complete. */
const void *bench_capture_record(const struct bench *b);

#endif
