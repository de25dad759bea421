/* svg_scope.c - SVG square-wave plot of waveforms (see svg_scope.h). */
#include "svg_scope.h"

#include <stdio.h>

#define LEFT  110.0  /* room for trace names */
#define WIDTH 1400.0 /* plot width in px */
#define ROW   70.0   /* height of one trace row */
#define SWING 30.0   /* high-to-low distance in px */
#define TOP   50.0

static double x_of(sim_ps t, sim_ps t0, sim_ps t1) {
    return LEFT + WIDTH * (double)(t - t0) / (double)(t1 - t0);
}

static void draw_trace(FILE *f, const struct svg_trace *tr, double base, sim_ps t0, sim_ps t1) {
    fprintf(f, "<text x=\"8\" y=\"%.1f\" class=\"name\">%s</text>\n", base - SWING / 2 + 5,
            tr->name);
    int level = waveform_level_at(tr->wave, t0);
    double y = base - (level ? SWING : 0);
    fprintf(f, "<polyline class=\"wave\" points=\"%.2f,%.1f", LEFT, y);
    sim_ps t = t0;
    while ((t = waveform_next_after(tr->wave, t)) <= t1) {
        double x = x_of(t, t0, t1);
        level = waveform_level_at(tr->wave, t);
        fprintf(f, " %.2f,%.1f", x, y);
        y = base - (level ? SWING : 0);
        fprintf(f, " %.2f,%.1f", x, y);
    }
    fprintf(f, " %.2f,%.1f\"/>\n", LEFT + WIDTH, y);
    for (size_t i = 0; i < tr->nlabels; i++) {
        const struct svg_label *l = &tr->labels[i];
        if (l->t1 < t0 || l->t0 > t1) {
            continue;
        }
        double xa = x_of(l->t0 < t0 ? t0 : l->t0, t0, t1);
        double xb = x_of(l->t1 > t1 ? t1 : l->t1, t0, t1);
        fprintf(f, "<line class=\"tick\" x1=\"%.2f\" y1=\"%.1f\" x2=\"%.2f\" y2=\"%.1f\"/>\n", xa,
                base + 4, xa, base + 12);
        fprintf(f, "<text x=\"%.2f\" y=\"%.1f\" class=\"bit\">%s</text>\n", (xa + xb) / 2,
                base + 22, l->text);
    }
}

static void draw_axis(FILE *f, double y, sim_ps t0, sim_ps t1) {
    double span_ns = (double)(t1 - t0) / 1000.0;
    /* the smallest step of 1, 2 or 5 times a power of ten giving <= 12 ticks */
    static const double mant[3] = {1, 2, 5};
    double step = 1;
    for (double decade = 1; span_ns / step > 12; decade *= 10) {
        for (int i = 0; i < 3 && span_ns / step > 12; i++) {
            step = mant[i] * decade;
        }
    }
    fprintf(f, "<line class=\"axis\" x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\"/>\n", LEFT, y,
            LEFT + WIDTH, y);
    for (double ns = 0; ns <= span_ns; ns += step) {
        double x = LEFT + WIDTH * ns / span_ns;
        fprintf(f, "<line class=\"grid\" x1=\"%.2f\" y1=\"%.1f\" x2=\"%.2f\" y2=\"%.1f\"/>\n", x,
                TOP - 10, x, y);
        fprintf(f, "<text x=\"%.2f\" y=\"%.1f\" class=\"time\">%.0f ns</text>\n", x, y + 16, ns);
    }
}

int svg_scope_write(const char *path, const char *title, const struct svg_trace *traces,
                    size_t ntraces, sim_ps t0, sim_ps t1) {
    if (t1 <= t0) {
        return -1;
    }
    FILE *f = fopen(path, "w");
    if (!f) {
        return -1;
    }
    double height = TOP + ROW * (double)ntraces + 40;
    fprintf(f,
            "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%.0f\" height=\"%.0f\" "
            "font-family=\"monospace\" font-size=\"12\">\n"
            "<style>.wave{fill:none;stroke:#0a6;stroke-width:1.5}.grid{stroke:#ddd}"
            ".axis{stroke:#444}.tick{stroke:#888}.name{font-weight:bold}"
            ".bit{text-anchor:middle;font-size:10px}.time{text-anchor:middle;fill:#444}"
            "</style>\n<rect width=\"100%%\" height=\"100%%\" fill=\"white\"/>\n"
            "<text x=\"8\" y=\"20\" font-size=\"14\">%s</text>\n",
            LEFT + WIDTH + 30, height, title);
    draw_axis(f, TOP + ROW * (double)ntraces, t0, t1);
    for (size_t i = 0; i < ntraces; i++) {
        draw_trace(f, &traces[i], TOP + ROW * (double)i + SWING, t0, t1);
    }
    fprintf(f, "</svg>\n");
    int bad = ferror(f);
    bad |= fclose(f) != 0;
    return bad ? -1 : 0;
}
