/*
 * biss-sim - runs a PRU image against a simulated cable and encoder(s).
 *
 * The image is a raw IRAM image (.bin) or pasm-dialect source (.p, .asm)
 * assembled in process with the rate and frame parameters as -D defines.
 * Without --image it runs the bench's clocking image, which drives BiSS
 * frames at the requested rate without decoding them.
 */
#include "bench.h"
#include "frame_labels.h"
#include "pruasm.h"
#include "scenario_json.h"
#include "svg_scope.h"

#include <cjson/cJSON.h>
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#ifndef BISS_SIM_CLOCK_IMAGE
#define BISS_SIM_CLOCK_IMAGE "clock_frames.p"
#endif

struct options {
    const char *profile;
    const char *scenario_file;
    double freq_hz;
    double cable_m; /* < 0: the profile's */
    uint64_t frames;
    uint64_t seed;
    int seed_set;
    const char *image;
    const char *soc;
    const char *vcd;
    const char *svg;
    uint64_t svg_frame;
    int json;
    double max_ms; /* simulated time limit, 0: derived */
};

static void usage(FILE *f) {
    fprintf(f, "usage: biss-sim [options]\n"
               "Runs a PRU image on the emulated PRU against a cable and BiSS-C/SSI encoder "
               "models.\n\n"
               "  --profile NAME     encoder profile (default tidep0022-test-encoder);\n"
               "                     --list-profiles prints them\n"
               "  --scenario FILE    JSON scenario: a profile plus any model parameter\n"
               "  --freq HZ          MA clock rate (default 10000000); 100 MHz / HZ must be whole\n"
               "  --cable-m M        cable length in metres, both directions (default: profile's)\n"
               "  --frames N         frames to run (default 100)\n"
               "  --seed S           random seed for noise and jitter (default: scenario's)\n"
               "  --image FILE       PRU image: raw .bin, or .p source assembled here\n"
               "                     (default: the bench's clocking image)\n"
               "  --soc NAME         am335x (default), am437x-icss0, am437x-icss1\n"
               "  --vcd FILE         write MA/SL at master and slave as VCD (scope bench)\n"
               "  --svg FILE         write a scope view of one frame as SVG\n"
               "  --svg-frame K      which frame the SVG shows (default 1)\n"
               "  --json             print the results as one JSON object\n"
               "  --max-ms T         stop after T ms of simulated time (default: ample)\n"
               "  -h, --help         this text\n");
}

/* Prints "biss-sim: <message>" and returns 1, the exit code for bad input. */
__attribute__((format(printf, 1, 2))) static int die(const char *fmt, ...) {
    va_list ap;
    va_start(ap, fmt);
    fprintf(stderr, "biss-sim: ");
    vfprintf(stderr, fmt, ap);
    fprintf(stderr, "\n");
    va_end(ap);
    return 1;
}

static int parse_double(const char *s, double *out) {
    char *end;
    errno = 0;
    double v = strtod(s, &end);
    if (errno || end == s || *end || !isfinite(v)) {
        return -1;
    }
    *out = v;
    return 0;
}

static int parse_u64(const char *s, uint64_t *out) {
    char *end;
    errno = 0;
    unsigned long long v = strtoull(s, &end, 0);
    if (errno || end == s || *end || s[0] == '-') {
        return -1;
    }
    *out = v;
    return 0;
}

static void list_profiles(void) {
    for (size_t i = 0; profile_name_at(i); i++) {
        printf("%s\n", profile_name_at(i));
    }
}

/* Options that take a value. */
static const char *const valued[] = {"--profile", "--scenario", "--freq",      "--cable-m",
                                     "--frames",  "--seed",     "--image",     "--soc",
                                     "--vcd",     "--svg",      "--svg-frame", "--max-ms"};

static int takes_value(const char *a) {
    for (size_t i = 0; i < sizeof(valued) / sizeof(valued[0]); i++) {
        if (!strcmp(a, valued[i])) {
            return 1;
        }
    }
    return 0;
}

/* One option with its value; returns 0 or 1 (message printed). */
static int set_option(struct options *o, const char *a, const char *v) {
    if (!strcmp(a, "--profile")) {
        o->profile = v;
    } else if (!strcmp(a, "--scenario")) {
        o->scenario_file = v;
    } else if (!strcmp(a, "--freq")) {
        if (parse_double(v, &o->freq_hz) || o->freq_hz <= 0) {
            return die("--freq: '%s' is not a positive rate in Hz", v);
        }
    } else if (!strcmp(a, "--cable-m")) {
        if (parse_double(v, &o->cable_m) || o->cable_m < 0 || o->cable_m > 1000) {
            return die("--cable-m: '%s' is not a length of 0..1000 m", v);
        }
    } else if (!strcmp(a, "--frames")) {
        if (parse_u64(v, &o->frames) || o->frames == 0) {
            return die("--frames: '%s' is not a positive count", v);
        }
    } else if (!strcmp(a, "--seed")) {
        if (parse_u64(v, &o->seed)) {
            return die("--seed: '%s' is not a number", v);
        }
        o->seed_set = 1;
    } else if (!strcmp(a, "--image")) {
        o->image = v;
    } else if (!strcmp(a, "--soc")) {
        o->soc = v;
    } else if (!strcmp(a, "--vcd")) {
        o->vcd = v;
    } else if (!strcmp(a, "--svg")) {
        o->svg = v;
    } else if (!strcmp(a, "--svg-frame")) {
        if (parse_u64(v, &o->svg_frame)) {
            return die("--svg-frame: '%s' is not a frame number", v);
        }
    } else if (!strcmp(a, "--max-ms")) {
        if (parse_double(v, &o->max_ms) || o->max_ms <= 0) {
            return die("--max-ms: '%s' is not a positive time", v);
        }
    }
    return 0;
}

/* Returns 0 to run, 1 for an error (message printed), 2 to exit 0. */
static int parse_args(int argc, char **argv, struct options *o) {
    *o = (struct options){.profile = "tidep0022-test-encoder",
                          .freq_hz = 10e6,
                          .cable_m = -1,
                          .frames = 100,
                          .soc = "am335x",
                          .svg_frame = 1};
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        if (!strcmp(a, "-h") || !strcmp(a, "--help")) {
            usage(stdout);
            return 2;
        } else if (!strcmp(a, "--list-profiles")) {
            list_profiles();
            return 2;
        } else if (!strcmp(a, "--json")) {
            o->json = 1;
        } else if (!takes_value(a)) {
            return die("unknown option '%s' (see --help)", a);
        } else if (i + 1 >= argc) {
            return die("option %s needs a value (see --help)", a);
        } else if (set_option(o, a, argv[++i]) != 0) {
            return 1;
        }
    }
    return 0;
}

static int build_config(const struct options *o, struct bench_config *cfg) {
    char err[256];
    bench_config_default(cfg);
    if (pru_soc_from_name(o->soc, &cfg->soc) != 0) {
        return die("--soc: unknown SoC '%s' (am335x, am437x-icss0, am437x-icss1)", o->soc);
    }
    if (o->scenario_file) {
        if (scenario_load_file(o->scenario_file, &cfg->link, err, sizeof(err)) != 0) {
            return die("%s", err);
        }
    } else if (profile_by_name(o->profile, &cfg->link) != 0) {
        return die("unknown profile '%s' (see --list-profiles)", o->profile);
    }
    if (o->cable_m >= 0) {
        scenario_set_cable(&cfg->link, o->cable_m);
    }
    if (o->seed_set) {
        cfg->link.seed = o->seed;
    }
    return 0;
}

/* MA half period in PRU cycles for the rate: 100 MHz / f, whole. */
static int half_period_cycles(double freq_hz, unsigned *half) {
    double h = 100e6 / freq_hz;
    if (fabs(h - round(h)) > 1e-9 || h < 5 || h > 258) {
        return -1;
    }
    *half = (unsigned)round(h);
    return 0;
}

/* Clocks a frame needs at the master: to the ACK, the busy time, start,
 * CDS, every slave's bits, and the round trip in whole periods. */
static unsigned frame_clocks(const struct bench_config *cfg, unsigned half, double round_trip_ps) {
    const scenario *sc = &cfg->link;
    double period_ps = 2.0 * half * 5000.0;
    unsigned bits = 0;
    if (sc->protocol == SCENARIO_SSI) {
        bits = sc->ssi.bits + 1;
    } else {
        bits = 2 + 2 + sc->biss.busy_clocks + (unsigned)ceil((double)sc->biss.busy_ps / period_ps);
        for (unsigned i = 0; i < sc->biss.n; i++) {
            bits += biss_slave_cfg_bits(&sc->biss.s[i]);
        }
    }
    return bits + (unsigned)ceil(round_trip_ps / period_ps) + 1;
}

/* Idle time after a frame: the slave's timeout and the round trip, with margin. */
static unsigned frame_gap_cycles(const struct bench_config *cfg, unsigned half,
                                 double round_trip_ps) {
    const scenario *sc = &cfg->link;
    double t_ps;
    if (sc->protocol == SCENARIO_SSI) {
        t_ps = (double)sc->ssi.monoflop_ps;
    } else if (sc->biss.timeout_mode == BISS_TIMEOUT_FIXED) {
        t_ps = (double)sc->biss.timeout_ps;
    } else {
        t_ps = sc->biss.adaptive_factor * 2.0 * half * 5000.0;
        if (t_ps < (double)sc->biss.adaptive_min_ps) {
            t_ps = (double)sc->biss.adaptive_min_ps;
        }
    }
    unsigned gap = (unsigned)ceil((t_ps + 2 * round_trip_ps) / 5000.0) + 200;
    return gap + (gap & 1); /* the image's wait loop takes 2 cycles a turn */
}

static int read_file(const char *path, uint8_t **buf, size_t *len) {
    FILE *f = fopen(path, "rb");
    if (!f) {
        return -1;
    }
    size_t cap = 4096, n = 0;
    uint8_t *b = malloc(cap);
    size_t got;
    while (b && (got = fread(b + n, 1, cap - n, f)) > 0) {
        n += got;
        if (n == cap) {
            uint8_t *nb = cap < (1u << 20) ? realloc(b, cap * 2) : NULL;
            if (!nb) {
                free(b);
                b = NULL;
                break;
            }
            b = nb;
            cap *= 2;
        }
    }
    int bad = ferror(f) || !b;
    fclose(f);
    if (bad) {
        free(b);
        return -1;
    }
    *buf = b;
    *len = n;
    return 0;
}

static int ends_with(const char *s, const char *suffix) {
    size_t n = strlen(s), m = strlen(suffix);
    return n >= m && strcmp(s + n - m, suffix) == 0;
}

/* Loads the image into words: a .bin as is, source through pruasm. */
static int load_image(const char *path, const struct bench_config *cfg, unsigned half,
                      unsigned clocks, unsigned gap, uint64_t frames, struct pruasm_image *img) {
    if (ends_with(path, ".bin")) {
        uint8_t *buf;
        size_t len;
        if (read_file(path, &buf, &len) != 0) {
            return die("cannot read image '%s'", path);
        }
        if (len == 0 || len % 4) {
            free(buf);
            return die("image '%s' is not a whole number of 32-bit words", path);
        }
        img->words = (uint32_t *)buf;
        img->nwords = len / 4;
        return 0;
    }
    char d[5][40];
    snprintf(d[0], sizeof(d[0]), "HALF=%u", half);
    snprintf(d[1], sizeof(d[1]), "CLOCKS=%u", clocks);
    snprintf(d[2], sizeof(d[2]), "GAP=%u", gap);
    snprintf(d[3], sizeof(d[3]), "FRAMES=%llu", (unsigned long long)(frames + 1));
    snprintf(d[4], sizeof(d[4]), "MA_BIT=%u", cfg->ma_bit);
    const char *defs[5] = {d[0], d[1], d[2], d[3], d[4]};
    struct pruasm_options opt = {.core = 3, .defines = defs, .ndefines = 5};
    struct pruasm_diag diag = {0};
    if (pruasm_assemble_file(&opt, path, img, &diag) != 0) {
        return die("%s", diag.first_error[0] ? diag.first_error : "assembly failed");
    }
    return 0;
}

static void progress(void *ctx, uint64_t done, uint64_t total) {
    (void)ctx;
    fprintf(stderr, "\rbiss-sim: frame %llu/%llu", (unsigned long long)done,
            (unsigned long long)total);
    fflush(stderr);
}

static const char *stop_name(enum pru_stop why) {
    switch (why) {
    case PRU_STOP_LIMIT:
        return "done";
    case PRU_STOP_HALT:
        return "halted";
    case PRU_STOP_FAULT:
        return "fault";
    case PRU_STOP_DISABLED:
        return "disabled";
    case PRU_STOP_STEP:
        return "step";
    }
    return "?";
}

/* The last frame the slave closed, per slave: what went over the wire. */
static cJSON *slaves_json(struct bench *b) {
    link_model *l = bench_link(b);
    cJSON *arr = cJSON_CreateArray();
    uint64_t n = link_frames(l);
    if (n == 0) {
        return arr;
    }
    if (l->sc.protocol == SCENARIO_SSI) {
        const ssi_frame_record *r = ssi_slave_record(&l->ssi, n - 1);
        cJSON *s = cJSON_CreateObject();
        cJSON_AddNumberToObject(s, "position", r ? (double)r->position : 0);
        cJSON_AddItemToArray(arr, s);
        return arr;
    }
    const biss_frame_record *r = biss_slave_record(&l->biss, n - 1);
    for (unsigned i = 0; r && i < l->sc.biss.n; i++) {
        cJSON *s = cJSON_CreateObject();
        cJSON_AddNumberToObject(s, "id", l->sc.biss.s[i].id);
        cJSON_AddNumberToObject(s, "position", (double)r->s[i].position);
        cJSON_AddNumberToObject(s, "nE", r->s[i].nE);
        cJSON_AddNumberToObject(s, "nW", r->s[i].nW);
        cJSON_AddNumberToObject(s, "crc", r->s[i].crc);
        cJSON_AddItemToArray(arr, s);
    }
    return arr;
}

static void add_min_mean_max(cJSON *o, const char *key, double lo, double mean, double hi) {
    cJSON *m = cJSON_AddObjectToObject(o, key);
    cJSON_AddNumberToObject(m, "min", lo);
    cJSON_AddNumberToObject(m, "mean", mean);
    cJSON_AddNumberToObject(m, "max", hi);
}

static void print_json(struct bench *b, const struct options *o, enum pru_stop why, double secs) {
    const struct bench_stats *st = bench_stats(b);
    cJSON *j = cJSON_CreateObject();
    cJSON_AddStringToObject(j, "profile", bench_link(b)->sc.profile);
    cJSON_AddNumberToObject(j, "freq_hz", o->freq_hz);
    cJSON_AddNumberToObject(j, "cable_m", bench_link(b)->sc.ma_line.length_m);
    cJSON_AddStringToObject(j, "stop", stop_name(why));
    cJSON_AddNumberToObject(j, "frames", (double)st->frames);
    /* the clocking image decodes nothing: nothing to compare yet */
    cJSON_AddNullToObject(j, "crc_errors");
    cJSON_AddNullToObject(j, "position_mismatches");
    cJSON_AddNumberToObject(j, "line_delay_ns", bench_round_trip_ps(b) / 1000.0);
    double mean = st->periods ? st->period_sum_ps / (double)st->periods : 0;
    add_min_mean_max(j, "frame_period_ns", (double)st->period_min_ps / 1000.0, mean / 1000.0,
                     (double)st->period_max_ps / 1000.0);
    cJSON *h = cJSON_AddObjectToObject(j, "ma_half_period_cycles");
    cJSON_AddNumberToObject(h, "min", (double)st->half_min_ps / PRU_PS_PER_CYCLE);
    cJSON_AddNumberToObject(h, "max", (double)st->half_max_ps / PRU_PS_PER_CYCLE);
    cJSON_AddNumberToObject(j, "pru_cycles", (double)pru_cycles(bench_core(b)));
    cJSON_AddNumberToObject(j, "host_seconds", secs);
    cJSON_AddItemToObject(j, "slaves", slaves_json(b));
    char *text = cJSON_Print(j);
    printf("%s\n", text);
    free(text);
    cJSON_Delete(j);
}

/* What the encoder(s) sent in the last closed frame. */
static void print_last_frame(link_model *l) {
    uint64_t n = link_frames(l);
    if (n == 0) {
        return;
    }
    if (l->sc.protocol == SCENARIO_SSI) {
        const ssi_frame_record *r = ssi_slave_record(&l->ssi, n - 1);
        printf("last frame sent      position %llu\n", r ? (unsigned long long)r->position : 0);
        return;
    }
    const biss_frame_record *r = biss_slave_record(&l->biss, n - 1);
    for (unsigned i = 0; r && i < l->sc.biss.n; i++) {
        printf("last frame sent      slave %u: position %llu (0x%llx) nE=%d nW=%d crc=0x%x\n", i,
               (unsigned long long)r->s[i].position, (unsigned long long)r->s[i].position,
               r->s[i].nE, r->s[i].nW, r->s[i].crc);
    }
}

static void print_text(struct bench *b, const struct options *o, enum pru_stop why, double secs) {
    const struct bench_stats *st = bench_stats(b);
    link_model *l = bench_link(b);
    printf("profile %s, %.3g MHz, %.1f m cable: %llu frames (%s)\n", l->sc.profile,
           o->freq_hz / 1e6, l->sc.ma_line.length_m, (unsigned long long)st->frames,
           stop_name(why));
    printf("round trip (model)   %.1f ns\n", bench_round_trip_ps(b) / 1000.0);
    printf("MA half period       %lld .. %lld cycles\n",
           (long long)(st->half_min_ps / PRU_PS_PER_CYCLE),
           (long long)(st->half_max_ps / PRU_PS_PER_CYCLE));
    if (st->periods) {
        printf("frame period         %.1f .. %.1f ns (mean %.1f)\n", st->period_min_ps / 1000.0,
               st->period_max_ps / 1000.0, st->period_sum_ps / (double)st->periods / 1000.0);
    }
    printf("PRU cycles           %lld in %.3f s host time\n", (long long)pru_cycles(bench_core(b)),
           secs);
    print_last_frame(l);
}

static int write_svg(struct bench *b, const struct options *o) {
    waveform *pins[4];
    sim_ps t0, t1;
    if (bench_capture_get(b, pins, &t0, &t1) != 0) {
        return die("--svg: frame %llu was not captured whole (run more frames?)",
                   (unsigned long long)o->svg_frame);
    }
    struct svg_label labels[FRAME_LABELS_MAX];
    size_t n = frame_labels(bench_link(b), o->svg_frame, pins[2], labels, FRAME_LABELS_MAX);
    static const char *const names[4] = {"MA master", "SL master", "MA slave", "SL slave"};
    struct svg_trace tr[4];
    for (int i = 0; i < 4; i++) {
        tr[i] = (struct svg_trace){names[i], pins[i], i == 3 ? labels : NULL, i == 3 ? n : 0};
    }
    char title[160];
    snprintf(title, sizeof(title), "%s, %.3g MHz, %.1f m: frame %llu", bench_link(b)->sc.profile,
             o->freq_hz / 1e6, bench_link(b)->sc.ma_line.length_m,
             (unsigned long long)o->svg_frame);
    if (svg_scope_write(o->svg, title, tr, 4, t0, t1) != 0) {
        return die("cannot write '%s'", o->svg);
    }
    return 0;
}

static double now_seconds(void) {
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + (double)ts.tv_nsec * 1e-9;
}

static int run(const struct options *o) {
    struct bench_config cfg;
    if (build_config(o, &cfg) != 0) {
        return 1;
    }
    unsigned half;
    if (half_period_cycles(o->freq_hz, &half) != 0) {
        return die("--freq %g: 100 MHz / f must be a whole number of PRU cycles, 5..258",
                   o->freq_hz);
    }
    char err[256];
    struct bench *b = bench_new(&cfg, err, sizeof(err));
    if (!b) {
        return die("%s", err);
    }
    double rt = bench_round_trip_ps(b);
    unsigned clocks = frame_clocks(&cfg, half, rt);
    unsigned gap = frame_gap_cycles(&cfg, half, rt);
    struct pruasm_image img = {0};
    int rc = load_image(o->image ? o->image : BISS_SIM_CLOCK_IMAGE, &cfg, half, clocks, gap,
                        o->frames, &img);
    if (rc == 0 && bench_start_image(b, img.words, img.nwords * 4) != 0) {
        rc = die("image of %zu words does not fit the IRAM of %s", img.nwords, o->soc);
    }
    if (rc == 0 && o->vcd && bench_open_vcd(b, o->vcd) != 0) {
        rc = die("cannot write '%s'", o->vcd);
    }
    if (rc != 0) {
        pruasm_image_free(&img);
        bench_free(b);
        return rc;
    }
    if (o->svg) {
        bench_capture_frame(b, o->svg_frame);
    }
    /* ample time: every frame at its longest, twice, plus start-up */
    double frame_ps = (2.0 * half * clocks + gap + 1000) * 5000.0;
    int64_t max_ps = o->max_ms > 0
                         ? (int64_t)(o->max_ms * 1e9)
                         : (int64_t)(2 * frame_ps * (double)(o->frames + 2)) + SIM_PS_PER_MS;
    int tty = isatty(2);
    double t_start = now_seconds();
    enum pru_stop why = bench_run_frames(b, o->frames, max_ps, tty ? progress : NULL, NULL);
    double secs = now_seconds() - t_start;
    if (tty) {
        fprintf(stderr, "\r%40s\r", "");
    }
    if (why == PRU_STOP_FAULT) {
        pru_print_fault(bench_core(b), stderr);
        rc = 3;
    }
    if (o->svg && write_svg(b, o) != 0) {
        rc = 1;
    }
    if (bench_close_vcd(b) != 0) {
        rc = die("error writing '%s'", o->vcd);
    }
    if (o->json) {
        print_json(b, o, why, secs);
    } else {
        print_text(b, o, why, secs);
        if (o->vcd) {
            printf("VCD written to %s\n", o->vcd);
        }
        if (o->svg) {
            printf("SVG scope view written to %s\n", o->svg);
        }
    }
    if (rc == 0 && bench_stats(b)->frames < o->frames) {
        fprintf(stderr, "biss-sim: only %llu of %llu frames completed\n",
                (unsigned long long)bench_stats(b)->frames, (unsigned long long)o->frames);
        rc = 2;
    }
    pruasm_image_free(&img);
    bench_free(b);
    return rc;
}

int main(int argc, char **argv) {
    struct options o;
    int rc = parse_args(argc, argv, &o);
    if (rc) {
        return rc == 2 ? 0 : rc;
    }
    return run(&o);
}
