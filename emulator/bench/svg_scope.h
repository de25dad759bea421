/*
 * svg_scope.h - an oscilloscope-style SVG picture of digital traces.
 *
 * Draws each trace as a square wave over a time window, a time axis in
 * nanoseconds, and text labels under a chosen trace (e.g. the BiSS bit
 * names at the slave). Open the file in any browser.
 */
#ifndef SVG_SCOPE_H
#define SVG_SCOPE_H

#include "waveform.h"

#include <stddef.h>

struct svg_label {
    sim_ps t0, t1; /* the span the label names */
    char text[16];
};

struct svg_trace {
    const char *name;
    waveform *wave;
    const struct svg_label *labels; /* drawn under this trace, may be NULL */
    size_t nlabels;
};

/* Writes the picture of [t0, t1]. Returns 0, or -1 if the file cannot be
 * written or the window is empty. */
int svg_scope_write(const char *path, const char *title, const struct svg_trace *traces,
                    size_t ntraces, sim_ps t0, sim_ps t1);

#endif
