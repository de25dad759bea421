/*
 * svg_scope.h - an oscilloscope-style SVG picture of digital traces.
 *
 * Draws each trace as a square wave over a time window, a time axis in
 * nanoseconds, text labels under a chosen trace (e.g. the BiSS bit names
 * at the slave), marks at given instants on a trace (e.g. where the master
 * sampled), arrows between two instants with a caption (e.g. a measured
 * delay), and lines of notes under the plot. Open the file in any browser.
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
    const sim_ps *marks; /* instants marked on this trace, may be NULL */
    size_t nmarks;
    sim_ps before, after; /* a band around each mark, that long before and after it (0: none) */
};

struct svg_arrow {
    size_t trace; /* drawn above this trace */
    sim_ps t0, t1;
    char text[64];
};

struct svg_view {
    const char *title;
    const struct svg_trace *traces;
    size_t ntraces;
    const struct svg_arrow *arrows;
    size_t narrows;
    const char *mark_legend; /* what the marks are, NULL if there are none */
    const char *band_legend; /* what the bands around them are, NULL if there are none */
    char (*notes)[160];      /* lines of text under the plot */
    size_t nnotes;
    sim_ps t0, t1; /* the window */
};

/* Writes the picture (whole or not at all: safe_file.h). Returns 0, or -1
 * if the file cannot be written or the window is empty (the path and the
 * reason in err). */
int svg_scope_write(const char *path, const struct svg_view *v, char *err, size_t errlen);

#endif
