/*
 * vcd.h - a Value Change Dump writer for 1-bit wires.
 *
 * Times are picoseconds; the file's timescale is a chosen unit of 1, 10,
 * 100 or 1000 ps. Each change is written at its time rounded to the unit,
 * but never at or before the stamp of an earlier change: two edges that
 * happen one after the other stay one after the other in the file (a
 * later one moves up to the next unit), and edges at the same picosecond
 * share a stamp. So a coarse unit keeps the order the models computed,
 * and 1 ps keeps every time exact. GTKWave, PulseView and Surfer open it.
 *
 * Changes may be given out of time order within a window: they wait in a
 * queue until vcd_flush_before() says no earlier change can come. (The
 * bench learns that an MA edge began a frame only when it reaches the
 * slave, after later edges of other wires.)
 */
#ifndef BENCH_VCD_H
#define BENCH_VCD_H

#include "safe_file.h"

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#define VCD_MAX_WIRES 16

struct vcd_pending {
    int64_t t_ps;
    int idx;
    int level;
};

struct vcd_writer {
    FILE *f;                  /* out.f while open */
    struct safe_file out;     /* written whole, or not at all (safe_file.h) */
    char err[PATH_MAX + 128]; /* why the file could not be written */
    int nwires;
    int started;
    int64_t unit_ps;    /* the timescale */
    int64_t last_ps;    /* model time of the last change written */
    int64_t last_stamp; /* its stamp, in units */
    char names[VCD_MAX_WIRES][32];
    signed char level[VCD_MAX_WIRES]; /* last level written, -1 none */
    struct vcd_pending *q;            /* queued changes, in time order */
    size_t qlen, qcap;
};

/* Whether unit_ps is a timescale the writer offers: 1, 10, 100 or 1000. */
int vcd_unit_valid(int64_t unit_ps);

/* Opens path for writing with the timescale unit_ps (vcd_unit_valid).
 * Returns 0, or -1 with errno set. */
int vcd_open(struct vcd_writer *w, const char *path, int64_t unit_ps);

/* Declares a wire before the first change. Returns its index or -1. */
int vcd_add_wire(struct vcd_writer *w, const char *name);

/* Records that wire idx takes level (0/1) at t_ps. It is written by a
 * later vcd_flush_before() or vcd_close(); among changes at the same time,
 * in the order given. A change earlier than one already written is written
 * at the last stamp. Repeated levels are dropped. */
void vcd_change(struct vcd_writer *w, int64_t t_ps, int idx, int level);

/* Writes the queued changes before t_ps (after the header, scope "bench"). */
void vcd_flush_before(struct vcd_writer *w, int64_t t_ps);

/* Writes what is queued, a final time stamp, and closes. Returns 0, or -1
 * on an I/O error. */
int vcd_close(struct vcd_writer *w, int64_t end_ps);

/* Why the last vcd_open or vcd_close failed (the path and the reason). */
const char *vcd_error(const struct vcd_writer *w);

#endif
