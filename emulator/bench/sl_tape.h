/*
 * sl_tape.h - SL at the master's pin on tape: recorded from one run of the
 * bench, played back into the core of another in place of the cable and
 * slave models.
 *
 * The firmware's path depends on nothing but what it reads on R31 (and the
 * host's writes, which a run with the same options repeats), so the same
 * image with the same options, fed the recorded SL, executes the recorded
 * run again instruction for instruction, while no MA edge goes anywhere and
 * no model runs. It measures what the core costs of a run with every model
 * taken away (scripts/bench-sim). The tape ends with the recorded run's
 * PRU instructions and cycles and a hash of the PRU-ICSS's data and shared
 * RAMs at its end (what the firmware published: its timing does not depend
 * on the bits it reads, its results do), so a playback tells whether it
 * was the same run (sl_tape_same); one that is not (other options, another
 * image) says so instead of passing for it.
 *
 * The file: 8 bytes "BISSSLT1", the level before the first edge (int64),
 * each edge as int64 t_ps * 2 + level (times increasing), then INT64_MAX,
 * the instructions, the cycles and the hash (64 bits each); host byte
 * order.
 */
#ifndef SL_TAPE_H
#define SL_TAPE_H

#include "pru_core.h"
#include "sim_time.h"
#include "waveform.h"

#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>

/* A tape being recorded. */
struct sl_tape_writer {
    FILE *f;
    const char *path;
    sim_ps last; /* the last edge written (-1: none) */
    int err;     /* errno of the first failed write, 0 none */
};

/* Creates path and writes the header; 0, or -1 with the path and errno's
 * text in err. */
int sl_tape_create(struct sl_tape_writer *w, const char *path, int initial, char *err,
                   size_t errlen);
/* Appends the edges of wf later than those written (wf holds every edge
 * since the last call, and possibly older ones). */
void sl_tape_append(struct sl_tape_writer *w, const waveform *wf);
/* Writes the end (core c's instructions, cycles and RAMs now; its
 * PRU-ICSS at global address base) and closes; 0, or -1 with the path and
 * errno's text in err. */
int sl_tape_finish(struct sl_tape_writer *w, struct pru_core *c, uint32_t base, char *err,
                   size_t errlen);

/* A tape played back. */
struct sl_tape {
    void *map; /* the file, mapped */
    size_t bytes;
    const int64_t *edge; /* t_ps * 2 + level, increasing; then INT64_MAX */
    size_t n;            /* edges */
    size_t at;           /* edges at or before the last time asked for */
    int initial;
    uint64_t insns; /* the recorded run's end */
    int64_t cycles;
    uint64_t ram_hash;
};

/* Reads a tape; 0, or -1 with the path and what is wrong in err (errno's
 * text, or what is not a tape). */
int sl_tape_load(struct sl_tape *t, const char *path, char *err, size_t errlen);
void sl_tape_free(struct sl_tape *t);
/* The pins that play it: SL on R31 bit 0, R30 going nowhere. */
struct pru_pins sl_tape_pins(struct sl_tape *t);
/* Whether core c, having run from the start with these pins, made the
 * recorded run: the same instructions, cycles and RAMs at the end. */
bool sl_tape_same(const struct sl_tape *t, struct pru_core *c, uint32_t base);

#endif
