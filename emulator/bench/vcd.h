/*
 * vcd.h - a Value Change Dump writer for 1-bit wires.
 *
 * Times are picoseconds; the file's timescale is 1 ps, so every edge the
 * bench computes is written exactly. GTKWave, PulseView and Surfer open it.
 */
#ifndef BENCH_VCD_H
#define BENCH_VCD_H

#include <stdint.h>
#include <stdio.h>

#define VCD_MAX_WIRES 16

struct vcd_writer {
    FILE *f;
    int nwires;
    int started;
    int64_t last_t; /* last time stamp written */
    char names[VCD_MAX_WIRES][32];
    signed char level[VCD_MAX_WIRES]; /* last level written, -1 none */
};

/* Opens path for writing. Returns 0, or -1 with errno set. */
int vcd_open(struct vcd_writer *w, const char *path);

/* Declares a wire before the first change. Returns its index or -1. */
int vcd_add_wire(struct vcd_writer *w, const char *name);

/* Records that wire idx takes level (0/1) at t_ps. Times must not decrease
 * (earlier times are clamped to the last one written). Repeated levels are
 * dropped. The header (scope "bench") is written on the first change. */
void vcd_change(struct vcd_writer *w, int64_t t_ps, int idx, int level);

/* Writes a final time stamp and closes. Returns 0, or -1 on an I/O error. */
int vcd_close(struct vcd_writer *w, int64_t end_ps);

#endif
