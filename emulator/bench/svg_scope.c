/* svg_scope.c - SVG square-wave plot of waveforms (see svg_scope.h). */
#include "svg_scope.h"

#include "safe_file.h"

#include <stdio.h>

#define LEFT  110.0  /* room for trace names */
#define WIDTH 1400.0 /* plot width in px */
#define ROW   70.0   /* height of one trace row */
#define SWING 30.0   /* high-to-low distance in px */
#define TOP   50.0
#define NOTE  16.0 /* height of one line of notes */

static double x_of(sim_ps t, sim_ps t0, sim_ps t1) {
    return LEFT + WIDTH * (double)(t - t0) / (double)(t1 - t0);
}

static double base_of(size_t trace) {
    return TOP + ROW * (double)trace + SWING;
}

static void draw_labels(FILE *f, const struct svg_trace *tr, double base, sim_ps t0, sim_ps t1) {
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

/* A short vertical line through the trace and a dot at its middle. */
static void draw_marks(FILE *f, const struct svg_trace *tr, double base, sim_ps t0, sim_ps t1) {
    for (size_t i = 0; i < tr->nmarks; i++) {
        if (tr->marks[i] < t0 || tr->marks[i] > t1) {
            continue;
        }
        double x = x_of(tr->marks[i], t0, t1);
        if (tr->before || tr->after) {
            double xa = x_of(tr->marks[i] - tr->before, t0, t1);
            double xb = x_of(tr->marks[i] + tr->after, t0, t1);
            fprintf(f,
                    "<rect class=\"band\" x=\"%.2f\" y=\"%.1f\" width=\"%.2f\" "
                    "height=\"%.1f\"/>\n",
                    xa, base - SWING - 4, xb - xa, SWING + 8);
        }
        fprintf(f, "<line class=\"mark\" x1=\"%.2f\" y1=\"%.1f\" x2=\"%.2f\" y2=\"%.1f\"/>\n", x,
                base - SWING - 4, x, base + 4);
        fprintf(f, "<circle class=\"mark\" cx=\"%.2f\" cy=\"%.1f\" r=\"2.5\"/>\n", x,
                base - SWING / 2);
    }
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
    draw_labels(f, tr, base, t0, t1);
    draw_marks(f, tr, base, t0, t1);
}

/* A double-headed arrow over the trace, its caption above it. */
static void draw_arrow(FILE *f, const struct svg_arrow *a, sim_ps t0, sim_ps t1) {
    double y = base_of(a->trace) - SWING - 8;
    double xa = x_of(a->t0, t0, t1), xb = x_of(a->t1, t0, t1);
    fprintf(f,
            "<line class=\"arrow\" x1=\"%.2f\" y1=\"%.1f\" x2=\"%.2f\" y2=\"%.1f\" "
            "marker-start=\"url(#head)\" marker-end=\"url(#head)\"/>\n",
            xa, y, xb, y);
    fprintf(f, "<text x=\"%.2f\" y=\"%.1f\" class=\"atext\">%s</text>\n", xb + 4, y + 4, a->text);
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

static void draw_notes(FILE *f, const struct svg_view *v, double y) {
    if (v->mark_legend) {
        fprintf(f, "<circle class=\"mark\" cx=\"14\" cy=\"%.1f\" r=\"2.5\"/>\n", y - 4);
        fprintf(f, "<text x=\"24\" y=\"%.1f\">%s</text>\n", y, v->mark_legend);
        y += NOTE;
    }
    if (v->band_legend) {
        fprintf(f, "<rect class=\"band\" x=\"9\" y=\"%.1f\" width=\"10\" height=\"10\"/>\n", y - 9);
        fprintf(f, "<text x=\"24\" y=\"%.1f\">%s</text>\n", y, v->band_legend);
        y += NOTE;
    }
    for (size_t i = 0; i < v->nnotes; i++, y += NOTE) {
        fprintf(f, "<text x=\"8\" y=\"%.1f\" xml:space=\"preserve\">%s</text>\n", y, v->notes[i]);
    }
}

int svg_scope_write(const char *path, const struct svg_view *v, char *err, size_t errlen) {
    if (v->t1 <= v->t0) {
        snprintf(err, errlen, "%s: no time to draw", path);
        return -1;
    }
    struct safe_file out;
    if (safe_file_open(&out, path, err, errlen) != 0) {
        return -1;
    }
    FILE *f = out.f;
    double axis = TOP + ROW * (double)v->ntraces;
    double notes_y = axis + 44;
    double height =
        notes_y + NOTE * (double)(v->nnotes + (v->mark_legend ? 1 : 0) + (v->band_legend ? 1 : 0)) +
        10;
    fprintf(f,
            "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%.0f\" height=\"%.0f\" "
            "font-family=\"monospace\" font-size=\"12\">\n"
            "<defs><marker id=\"head\" viewBox=\"0 0 10 10\" refX=\"10\" refY=\"5\" "
            "markerWidth=\"7\" markerHeight=\"7\" orient=\"auto-start-reverse\">"
            "<path d=\"M0,0 L10,5 L0,10 z\" fill=\"#c40\"/></marker></defs>\n"
            "<style>.wave{fill:none;stroke:#0a6;stroke-width:1.5}.grid{stroke:#ddd}"
            ".axis{stroke:#444}.tick{stroke:#888}.name{font-weight:bold}"
            ".bit{text-anchor:middle;font-size:10px}.time{text-anchor:middle;fill:#444}"
            "line.mark{stroke:#d22;stroke-width:0.8}circle.mark{fill:#d22}"
            "rect.band{fill:#d22;fill-opacity:0.12}"
            ".arrow{stroke:#c40;stroke-width:1.2}.atext{fill:#c40}"
            "</style>\n<rect width=\"100%%\" height=\"100%%\" fill=\"white\"/>\n"
            "<text x=\"8\" y=\"20\" font-size=\"14\">%s</text>\n",
            LEFT + WIDTH + 30, height, v->title);
    draw_axis(f, axis, v->t0, v->t1);
    for (size_t i = 0; i < v->ntraces; i++) {
        draw_trace(f, &v->traces[i], base_of(i), v->t0, v->t1);
    }
    for (size_t i = 0; i < v->narrows; i++) {
        draw_arrow(f, &v->arrows[i], v->t0, v->t1);
    }
    draw_notes(f, v, notes_y);
    fprintf(f, "</svg>\n");
    return safe_file_close(&out, err, errlen);
}
