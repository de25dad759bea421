/* vcd.c - Value Change Dump writer (see vcd.h). */
#include "vcd.h"

#include <stdlib.h>
#include <string.h>

const char *vcd_error(const struct vcd_writer *w) {
    return w->err;
}

int vcd_unit_valid(int64_t unit_ps) {
    return unit_ps == 1 || unit_ps == 10 || unit_ps == 100 || unit_ps == 1000;
}

int vcd_open(struct vcd_writer *w, const char *path, int64_t unit_ps) {
    memset(w, 0, sizeof(*w));
    w->unit_ps = vcd_unit_valid(unit_ps) ? unit_ps : 1;
    if (safe_file_open(&w->out, path, w->err, sizeof w->err) != 0) {
        return -1;
    }
    w->f = w->out.f;
    memset(w->level, -1, sizeof(w->level));
    return 0;
}

int vcd_add_wire(struct vcd_writer *w, const char *name) {
    if (w->started || w->nwires >= VCD_MAX_WIRES || strlen(name) >= sizeof(w->names[0])) {
        return -1;
    }
    strcpy(w->names[w->nwires], name);
    return w->nwires++;
}

/* Identifier codes are single printable characters starting at '!'. */
static char wire_code(int idx) {
    return (char)('!' + idx);
}

static const char *unit_name(int64_t unit_ps) {
    switch (unit_ps) {
    case 10:
        return "10ps";
    case 100:
        return "100ps";
    case 1000:
        return "1ns";
    }
    return "1ps";
}

static void write_header(struct vcd_writer *w) {
    fprintf(w->f, "$version pru-biss bench $end\n$timescale %s $end\n$scope module bench $end\n",
            unit_name(w->unit_ps));
    for (int i = 0; i < w->nwires; i++) {
        fprintf(w->f, "$var wire 1 %c %s $end\n", wire_code(i), w->names[i]);
    }
    fprintf(w->f, "$upscope $end\n$enddefinitions $end\n#0\n$dumpvars\n");
    for (int i = 0; i < w->nwires; i++) {
        fprintf(w->f, "x%c\n", wire_code(i));
    }
    fprintf(w->f, "$end\n");
    w->started = 1;
    w->last_ps = 0;
    w->last_stamp = 0;
}

/* The stamp for a change at t_ps: rounded to the unit, but after the last
 * stamp when the change comes after the last one written. */
static int64_t stamp_of(struct vcd_writer *w, int64_t t_ps) {
    if (t_ps <= w->last_ps) {
        return w->last_stamp;
    }
    int64_t s = (t_ps + w->unit_ps / 2) / w->unit_ps;
    return s > w->last_stamp ? s : w->last_stamp + 1;
}

static void write_change(struct vcd_writer *w, const struct vcd_pending *c) {
    if (w->level[c->idx] == c->level) {
        return;
    }
    int64_t s = stamp_of(w, c->t_ps);
    if (s != w->last_stamp) {
        fprintf(w->f, "#%lld\n", (long long)s);
        w->last_stamp = s;
    }
    if (c->t_ps > w->last_ps) {
        w->last_ps = c->t_ps;
    }
    fprintf(w->f, "%d%c\n", c->level, wire_code(c->idx));
    w->level[c->idx] = (signed char)c->level;
}

/* Makes room for one more queued change; 0 or -1. */
static int grow(struct vcd_writer *w) {
    if (w->qlen < w->qcap) {
        return 0;
    }
    size_t cap = w->qcap ? 2 * w->qcap : 256;
    struct vcd_pending *q = realloc(w->q, cap * sizeof(*q));
    if (!q) {
        return -1;
    }
    w->q = q;
    w->qcap = cap;
    return 0;
}

void vcd_change(struct vcd_writer *w, int64_t t_ps, int idx, int level) {
    if (!w->f || idx < 0 || idx >= w->nwires) {
        return;
    }
    if (!w->started) {
        write_header(w);
    }
    struct vcd_pending c = {t_ps, idx, level ? 1 : 0};
    if (grow(w) != 0) { /* no memory: write what is queued, then this */
        vcd_flush_before(w, INT64_MAX);
        write_change(w, &c);
        return;
    }
    /* after every queued change at or before t_ps (mostly: at the end) */
    size_t i = w->qlen;
    while (i > 0 && w->q[i - 1].t_ps > t_ps) {
        i--;
    }
    memmove(w->q + i + 1, w->q + i, (w->qlen - i) * sizeof(*w->q));
    w->q[i] = c;
    w->qlen++;
}

void vcd_flush_before(struct vcd_writer *w, int64_t t_ps) {
    if (!w->f || w->qlen == 0 || w->q[0].t_ps >= t_ps) {
        return;
    }
    size_t n = 0;
    while (n < w->qlen && w->q[n].t_ps < t_ps) {
        write_change(w, &w->q[n++]);
    }
    memmove(w->q, w->q + n, (w->qlen - n) * sizeof(*w->q));
    w->qlen -= n;
}

int vcd_close(struct vcd_writer *w, int64_t end_ps) {
    if (!w->f) {
        return 0;
    }
    if (!w->started) {
        write_header(w);
    }
    vcd_flush_before(w, INT64_MAX);
    /* The end of the run, one unit after a change made at its very end
     * at the least: a viewer then shows that last value, and a decoder
     * (sigrok's) sees the last edge as an edge. */
    int64_t s = stamp_of(w, end_ps);
    fprintf(w->f, "#%lld\n", (long long)(s > w->last_stamp ? s : w->last_stamp + 1));
    int bad = safe_file_close(&w->out, w->err, sizeof w->err) != 0;
    w->f = NULL;
    free(w->q);
    w->q = NULL;
    w->qlen = w->qcap = 0;
    return bad ? -1 : 0;
}
