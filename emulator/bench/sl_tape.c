/* sl_tape.c - SL at the master's pin on tape (sl_tape.h). */
#define _DEFAULT_SOURCE /* MAP_POPULATE (Linux; elsewhere the pages come as read) */
#include "sl_tape.h"

#include <errno.h>
#include <fcntl.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#ifndef MAP_POPULATE
#define MAP_POPULATE 0
#endif

static const char MAGIC[8] = {'B', 'I', 'S', 'S', 'S', 'L', 'T', '1'};
/* after the edges: above every edge, so a look-up stops there */
#define END_MARK INT64_MAX

/* FNV-1a over the PRU-ICSS's data RAMs and shared RAM as the host reads
 * them: the results the firmware published (whichever PRU it runs on). */
static uint64_t ram_hash(struct pru_core *c, uint32_t base) {
    static const uint32_t ofs[] = {PRU_OFS_DRAM0, PRU_OFS_DRAM1, PRU_OFS_SHARED};
    uint32_t sizes[] = {pru_dram_bytes(c), pru_dram_bytes(c), pru_shared_bytes(c)};
    uint64_t h = UINT64_C(14695981039346656037);
    uint8_t buf[256];
    for (size_t k = 0; k < sizeof ofs / sizeof ofs[0]; k++) {
        for (uint32_t a = 0; a < sizes[k]; a += sizeof buf) {
            uint32_t n = sizes[k] - a < sizeof buf ? sizes[k] - a : (uint32_t)sizeof buf;
            if (pru_host_read(c, base + ofs[k] + a, buf, n) != 0) {
                memset(buf, 0, n);
            }
            for (uint32_t i = 0; i < n; i++) {
                h = (h ^ buf[i]) * UINT64_C(1099511628211);
            }
        }
    }
    return h;
}

/* ---- recording ---------------------------------------------------------- */

static void put(struct sl_tape_writer *w, int64_t v) {
    if (!w->err && fwrite(&v, sizeof v, 1, w->f) != 1) {
        w->err = errno ? errno : EIO;
    }
}

int sl_tape_create(struct sl_tape_writer *w, const char *path, int initial, char *err,
                   size_t errlen) {
    *w = (struct sl_tape_writer){.path = path, .last = -1};
    w->f = fopen(path, "wb");
    if (!w->f) {
        snprintf(err, errlen, "%s: %s", path, strerror(errno));
        return -1;
    }
    if (fwrite(MAGIC, sizeof MAGIC, 1, w->f) != 1) {
        w->err = errno ? errno : EIO;
    }
    put(w, initial ? 1 : 0);
    return 0;
}

void sl_tape_append(struct sl_tape_writer *w, const waveform *wf) {
    for (size_t i = waveform_index_after(wf, w->last); i < wf->len; i++) {
        put(w, wf->edges[i].t * 2 + (wf->edges[i].level ? 1 : 0));
        w->last = wf->edges[i].t;
    }
}

int sl_tape_finish(struct sl_tape_writer *w, struct pru_core *c, uint32_t base, char *err,
                   size_t errlen) {
    put(w, END_MARK);
    put(w, (int64_t)pru_instructions(c));
    put(w, pru_cycles(c));
    put(w, (int64_t)ram_hash(c, base));
    if (fclose(w->f) != 0 && !w->err) {
        w->err = errno ? errno : EIO;
    }
    w->f = NULL;
    if (w->err) {
        snprintf(err, errlen, "%s: %s", w->path, strerror(w->err));
        return -1;
    }
    return 0;
}

/* ---- playback ----------------------------------------------------------- */

static int not_a_tape(const char *path, const char *what, char *err, size_t errlen) {
    snprintf(err, errlen, "%s: not an SL tape of biss-sim --sl-record (%s)", path, what);
    return -1;
}

/* What is wrong with the mapped file w[0 .. n) (n >= 6, the header right)
 * as a tape, or NULL: initial level, edges (increasing), END_MARK,
 * instructions, cycles, hash. */
static const char *tape_problem(const int64_t *w, size_t n, char *what, size_t len) {
    if (w[n - 4] != END_MARK) {
        return "no end";
    }
    if (w[1] != 0 && w[1] != 1) {
        return "initial level";
    }
    for (size_t i = 2; i < n - 4; i++) {
        if (w[i] < 0 || (i > 2 && w[i] / 2 <= w[i - 1] / 2)) {
            snprintf(what, len, "edge %zu out of order", i - 1);
            return what;
        }
    }
    return NULL;
}

int sl_tape_load(struct sl_tape *t, const char *path, char *err, size_t errlen) {
    *t = (struct sl_tape){0};
    /* mapped, not read: a tape of a second of clocking is some 20 MB, and
     * the replay's time is what it measures */
    int fd = open(path, O_RDONLY);
    struct stat st;
    if (fd < 0 || fstat(fd, &st) != 0) {
        snprintf(err, errlen, "%s: %s", path, strerror(errno));
        if (fd >= 0) {
            close(fd);
        }
        return -1;
    }
    if (!S_ISREG(st.st_mode)) {
        close(fd);
        snprintf(err, errlen, "%s: %s", path, strerror(S_ISDIR(st.st_mode) ? EISDIR : EINVAL));
        return -1;
    }
    size_t bytes = (size_t)st.st_size;
    if (bytes < sizeof MAGIC) {
        close(fd);
        return not_a_tape(path, "no header", err, errlen);
    }
    void *map = mmap(NULL, bytes, PROT_READ, MAP_PRIVATE | MAP_POPULATE, fd, 0);
    int e = errno;
    close(fd);
    if (map == MAP_FAILED) {
        snprintf(err, errlen, "%s: %s", path, strerror(e));
        return -1;
    }
    const int64_t *w = map;
    size_t n = bytes / sizeof(int64_t);
    char what[64];
    const char *bad = memcmp(w, MAGIC, sizeof MAGIC) != 0 ? "no header"
                      : bytes % sizeof(int64_t) != 0 || n < 6
                          ? "cut short"
                          : tape_problem(w, n, what, sizeof what);
    if (bad) {
        munmap(map, bytes);
        return not_a_tape(path, bad, err, errlen);
    }
    t->map = map;
    t->bytes = bytes;
    t->initial = (int)w[1];
    t->edge = w + 2;
    t->n = n - 6;
    t->insns = (uint64_t)w[n - 3];
    t->cycles = w[n - 2];
    t->ram_hash = (uint64_t)w[n - 1];
    return 0;
}

void sl_tape_free(struct sl_tape *t) {
    if (t->map) {
        munmap(t->map, t->bytes);
    }
    *t = (struct sl_tape){0};
}

/* SL at time ps, and in *next its next change after ps (INT64_MAX: none
 * recorded). Times asked for mostly go forward by little: from the last
 * place, forward or back. */
static int level_at(struct sl_tape *t, int64_t ps, int64_t *next) {
    size_t i = t->at;
    int64_t key = ps * 2 + 1; /* an edge at ps is in effect at ps */
    while (i > 0 && t->edge[i - 1] > key) {
        i--;
    }
    while (t->edge[i] <= key) { /* the end mark stops it */
        i++;
    }
    t->at = i;
    *next = i < t->n ? t->edge[i] / 2 : INT64_MAX;
    return i ? (int)(t->edge[i - 1] & 1) : t->initial;
}

static uint32_t tape_inputs_at(void *ctx, int64_t ps) {
    int64_t next;
    return (uint32_t)level_at(ctx, ps, &next);
}

static int64_t tape_next_change(void *ctx, int64_t ps) {
    int64_t next;
    level_at(ctx, ps, &next);
    return next;
}

static uint32_t tape_inputs_run(void *ctx, int64_t ps, int64_t *next) {
    return (uint32_t)level_at(ctx, ps, next);
}

static void tape_outputs(void *ctx, int64_t ps, uint32_t r30) {
    (void)ctx, (void)ps, (void)r30;
}

struct pru_pins sl_tape_pins(struct sl_tape *t) {
    return (struct pru_pins){.ctx = t,
                             .inputs_at = tape_inputs_at,
                             .next_input_change = tape_next_change,
                             .outputs_changed = tape_outputs,
                             .inputs_run = tape_inputs_run};
}

bool sl_tape_same(const struct sl_tape *t, struct pru_core *c, uint32_t base) {
    return pru_instructions(c) == t->insns && pru_cycles(c) == t->cycles &&
           ram_hash(c, base) == t->ram_hash;
}
