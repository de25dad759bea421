/* vcd.c - Value Change Dump writer (see vcd.h). */
#include "vcd.h"

#include <string.h>

int vcd_open(struct vcd_writer *w, const char *path) {
    memset(w, 0, sizeof(*w));
    w->f = fopen(path, "w");
    if (!w->f) {
        return -1;
    }
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

static void write_header(struct vcd_writer *w) {
    fprintf(w->f, "$version pru-biss bench $end\n$timescale 1ps $end\n$scope module bench $end\n");
    for (int i = 0; i < w->nwires; i++) {
        fprintf(w->f, "$var wire 1 %c %s $end\n", wire_code(i), w->names[i]);
    }
    fprintf(w->f, "$upscope $end\n$enddefinitions $end\n#0\n$dumpvars\n");
    for (int i = 0; i < w->nwires; i++) {
        fprintf(w->f, "x%c\n", wire_code(i));
    }
    fprintf(w->f, "$end\n");
    w->started = 1;
    w->last_t = 0;
}

void vcd_change(struct vcd_writer *w, int64_t t_ps, int idx, int level) {
    if (!w->f || idx < 0 || idx >= w->nwires) {
        return;
    }
    if (!w->started) {
        write_header(w);
    }
    level = level ? 1 : 0;
    if (w->level[idx] == level) {
        return;
    }
    if (t_ps < w->last_t) {
        t_ps = w->last_t;
    }
    if (t_ps != w->last_t) {
        fprintf(w->f, "#%lld\n", (long long)t_ps);
        w->last_t = t_ps;
    }
    fprintf(w->f, "%d%c\n", level, wire_code(idx));
    w->level[idx] = (signed char)level;
}

int vcd_close(struct vcd_writer *w, int64_t end_ps) {
    if (!w->f) {
        return 0;
    }
    if (!w->started) {
        write_header(w);
    }
    if (end_ps > w->last_t) {
        fprintf(w->f, "#%lld\n", (long long)end_ps);
    }
    int bad = ferror(w->f);
    bad |= fclose(w->f) != 0;
    w->f = NULL;
    return bad ? -1 : 0;
}
