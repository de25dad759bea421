/* sim_image.c - loading biss-sim's PRU image (see sim_image.h). */
#include "sim_image.h"

#include "read_file.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int ends_with(const char *s, const char *suffix) {
    size_t n = strlen(s), m = strlen(suffix);
    return n >= m && strcmp(s + n - m, suffix) == 0;
}

int sim_load_image(const char *path, const struct sim_defines *d, struct pruasm_image *img,
                   char *err, size_t errlen) {
    memset(img, 0, sizeof(*img));
    if (ends_with(path, ".bin")) {
        char *buf;
        size_t len;
        if (read_file(path, 1u << 20, &buf, &len) != READ_FILE_OK) {
            snprintf(err, errlen, "cannot read image '%s'", path);
            return -1;
        }
        if (len == 0 || len % 4) {
            free(buf);
            snprintf(err, errlen, "image '%s' is not a whole number of 32-bit words", path);
            return -1;
        }
        img->words = (uint32_t *)buf;
        img->nwords = len / 4;
        return 0;
    }
    const char *defs[SIM_MAX_DEFINES];
    for (size_t i = 0; i < d->n; i++) {
        defs[i] = d->text[i];
    }
    struct pruasm_options opt = {.core = 3, .defines = defs, .ndefines = d->n};
    struct pruasm_diag diag = {0};
    if (pruasm_assemble_file(&opt, path, img, &diag) != 0) {
        snprintf(err, errlen, "%s", diag.first_error[0] ? diag.first_error : "assembly failed");
        return -1;
    }
    return 0;
}

/* Clocks a frame needs at the master: the model's (to the ACK, the busy
 * time, start, CDS, every slave's bits), and the round trip in whole
 * periods. */
static unsigned frame_clocks(struct bench *b, unsigned half) {
    const scenario *sc = &bench_link(b)->sc;
    double period_ps = 2.0 * half * 5000.0;
    unsigned bits = sc->model->clocks(scenario_model_cfg(sc), (sim_ps)period_ps);
    return bits + (unsigned)ceil(bench_round_trip_ps(b) / period_ps) + 1;
}

/* Idle time after a frame: the slave's timeout and the round trip, with margin. */
static unsigned frame_gap_cycles(struct bench *b, unsigned half) {
    const scenario *sc = &bench_link(b)->sc;
    double t_ps = (double)sc->model->timeout(scenario_model_cfg(sc), 2 * (sim_ps)half * 5000);
    unsigned gap = (unsigned)ceil((t_ps + 2 * bench_round_trip_ps(b)) / 5000.0) + 200;
    return gap + (gap & 1); /* the image's wait loop takes 2 cycles a turn */
}

void sim_clock_defines(struct bench *b, unsigned half, uint64_t frames, struct sim_defines *d) {
    d->n = 5;
    snprintf(d->text[0], sizeof(d->text[0]), "HALF=%u", half);
    snprintf(d->text[1], sizeof(d->text[1]), "CLOCKS=%u", frame_clocks(b, half));
    snprintf(d->text[2], sizeof(d->text[2]), "GAP=%u", frame_gap_cycles(b, half));
    snprintf(d->text[3], sizeof(d->text[3]), "FRAMES=%llu", (unsigned long long)(frames + 1));
    snprintf(d->text[4], sizeof(d->text[4]), "MA_BIT=%u", bench_config(b)->ma_bit);
}

double sim_clock_frame_ps(struct bench *b, unsigned half) {
    return (2.0 * half * frame_clocks(b, half) + frame_gap_cycles(b, half) + 1000) * 5000.0;
}
