/* sim_pair.c - two encoders on the two PRUs of one PRU-ICSS (sim_pair.h). */
#include "sim_pair.h"

#include "bench_fw.h"
#include "fw_check.h"
#include "sim_image.h"
#include "sim_report.h"

#include "biss/biss_shm.h"

#include <math.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

struct starts {
    int64_t *t[2];
    uint64_t n[2], cap;
};

/* A step is a quarter period: each sees at most one new frame start. */
static void note_starts(struct bench *b[2], struct starts *s) {
    for (unsigned i = 0; i < 2; i++) {
        int64_t t = bench_frame_start_ps(b[i]);
        uint64_t k = s->n[i];
        if (t >= 0 && (k == 0 || s->t[i][k - 1] != t) && k < s->cap) {
            s->t[i][s->n[i]++] = t;
        }
    }
}

static double seconds(void) {
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + (double)ts.tv_nsec * 1e-9;
}

/* Both configured; runs until both checked r->frames valid frames after
 * their first ones, noting the frame starts from there on. */
static enum pru_stop run(struct bench *b[2], struct fw_check fc[2], const struct sim_pair_run *r,
                         int64_t step, struct starts *s) {
    int64_t end = pru_time_ps(bench_core(b[0])) + r->max_ps;
    int started = 0;
    while (pru_time_ps(bench_core(b[0])) < end) {
        if (!started && fc[0].frames > r->settle && fc[1].frames > r->settle) {
            started = 1;
            for (unsigned i = 0; i < 2; i++) {
                fw_check_restart(&fc[i], r->frames);
                bench_reset_stats(b[i]);
                bench_set_frame_limit(b[i], bench_current_frame(b[i]) + r->frames + 1);
            }
        }
        if (started && fc[0].frames >= r->frames && fc[1].frames >= r->frames) {
            break;
        }
        enum pru_stop why = bench_run_until(b[0], pru_time_ps(bench_core(b[0])) + step);
        if (why != PRU_STOP_LIMIT) {
            return why;
        }
        if (started) {
            note_starts(b, s);
        }
    }
    return PRU_STOP_LIMIT;
}

/* Frame k of PRU0 and of PRU1, in order: the start differences. Lines of
 * one protocol start on the same cycle; an SSI frame's first MA edge comes
 * a fixed number of cycles after a BiSS-C frame's (its own code path), so
 * a mixed pair must keep that offset to within a cycle. */
static int report_starts(const struct starts *s, uint32_t period, bool mixed, cJSON *j) {
    uint64_t n = s->n[0] < s->n[1] ? s->n[0] : s->n[1];
    int64_t lo = INT64_MAX, hi = INT64_MIN;
    for (uint64_t k = 0; k < n; k++) {
        int64_t d = s->t[1][k] - s->t[0][k];
        lo = d < lo ? d : lo;
        hi = d > hi ? d : hi;
    }
    if (j) {
        cJSON *o = cJSON_AddObjectToObject(j, "frame_starts");
        cJSON_AddNumberToObject(o, "pairs", (double)n);
        cJSON_AddNumberToObject(o, "iep_period_ns", period * 5.0);
        cJSON_AddNumberToObject(o, "pru1_minus_pru0_min_ps", n ? (double)lo : 0);
        cJSON_AddNumberToObject(o, "pru1_minus_pru0_max_ps", n ? (double)hi : 0);
    }
    if (n == 0) {
        if (!j) {
            printf("frame starts         none measured\n");
        }
        return 5;
    }
    if (!j) {
        printf("frame starts         %llu pairs on an IEP period of %.3f us (PRU0 owns the IEP, "
               "PRU1 follows): PRU1 - PRU0 = %lld .. %lld ps%s\n",
               (unsigned long long)n, period * 5e-3, (long long)lo, (long long)hi,
               mixed ? " (BiSS-C and SSI: SSI's first edge comes later, a fixed time)" : "");
    }
    bool together = mixed ? hi - lo <= PRU_PS_PER_CYCLE
                          : llabs(lo) <= PRU_PS_PER_CYCLE && llabs(hi) <= PRU_PS_PER_CYCLE;
    return s->n[0] == s->n[1] && together ? 0 : 5;
}

int sim_pair(const struct sim_pair_run *r) {
    struct bench *b[2];
    char err[256];
    if (bench_new_pair(r->cfg, b, err, sizeof err) != 0) {
        fprintf(stderr, "biss-sim: %s\n", err);
        return 1;
    }
    uint32_t period = r->iep_period;
    if (period == 0) { /* twice the longer frame, in whole microseconds */
        double f = fmax(sim_clock_frame_ps(b[0], r->half), sim_clock_frame_ps(b[1], r->half));
        period = (uint32_t)ceil(2 * f / SIM_PS_PER_US) * 200u;
    }
    struct sim_pair_run rr = *r;
    if (rr.max_ps <= 0) { /* start-up and training take a few periods */
        rr.max_ps =
            2 * (int64_t)period * PRU_PS_PER_CYCLE * ((int64_t)(r->frames + r->settle) + 8) +
            SIM_PS_PER_MS;
    }
    if (rr.max_ps > r->cap_ps) {
        rr.max_ps = r->cap_ps;
    }
    r = &rr;
    struct fw_check fc[2];
    /* PRU0 owns the IEP; the follower's checks count its frames in the
     * owner's periods (5 ns IEP counts) */
    static const enum biss_trigger trigger[2] = {BISS_TRIGGER_IEP, BISS_TRIGGER_IEP_FOLLOW};
    int rc = 0;
    for (unsigned i = 0; i < 2 && rc == 0; i++) {
        if (bench_fw_start(b[i], r->image[i], r->bytes[i]) != 0) {
            fprintf(stderr, "biss-sim: the image does not fit PRU%u's IRAM\n", i);
            rc = 1;
            continue;
        }
        fw_check_attach(&fc[i], b[i]);
        if (i == 0 && r->checks && biss_safety_merge(&fc[0].cfg, r->checks)) {
            fprintf(stderr, "biss-sim: PRU0: more than 4 pairs checked\n");
            rc = 1;
        }
        fc[i].cfg.trigger = trigger[i];
        fc[i].cfg.iep_period_ns = period * 5u;
        fc[i].cfg.proc_limit = 1000;
        fw_check_configure(&fc[i], r->half);
        int bad = rc ? BISS_OK : biss_safety_config_check(&fc[i].cfg);
        if (bad) {
            fprintf(stderr, "biss-sim: PRU%u: safety checks: %s\n", i, sim_safety_problem(bad));
            rc = 1;
        }
    }
    struct starts s = {.cap = r->frames + 8};
    s.t[0] = calloc(s.cap, sizeof(int64_t));
    s.t[1] = calloc(s.cap, sizeof(int64_t));
    if (rc == 0 && (!s.t[0] || !s.t[1])) {
        fprintf(stderr, "biss-sim: out of memory\n");
        rc = 1;
    }
    if (rc == 0) {
        double t0 = seconds();
        int64_t step = (int64_t)period * PRU_PS_PER_CYCLE / 4;
        enum pru_stop why = run(b, fc, r, step, &s);
        double host = seconds() - t0;
        cJSON *j = r->json ? cJSON_CreateObject() : NULL;
        for (unsigned i = 0; i < 2; i++) {
            struct sim_result res = {.b = b[i],
                                     .fw = &fc[i],
                                     .why = why,
                                     .freq_hz = 100e6 / r->half,
                                     .half = r->half,
                                     .host_seconds = host,
                                     .cd = NULL,
                                     .trigger = i ? BISS_TRIG_IEP_FOLLOW : BISS_TRIG_IEP};
            if (j) {
                cJSON *one = sim_json(&res);
                cJSON_AddStringToObject(one, "trigger", i ? "iep-follow" : "iep");
                cJSON_AddItemToObject(j, i ? "pru1" : "pru0", one);
            } else {
                printf("PRU%u%s\n", i, i ? " (IEP follow)" : " (IEP)");
                sim_print_text(&res);
            }
            if (why == PRU_STOP_FAULT && pru_get_fault(bench_core(b[i]))->cause) {
                pru_print_fault(bench_core(b[i]), stderr);
                rc = 3;
            }
            if (rc == 0 && fc[i].frames < r->frames) {
                fprintf(stderr, "biss-sim: PRU%u: only %llu of %llu frames in time\n", i,
                        (unsigned long long)fc[i].frames, (unsigned long long)r->frames);
                rc = 124; /* as timeout(1), biss-sim's EXIT_TIMEOUT */
            }
            if (rc == 0 && !j && (fc[i].mismatches || fc[i].crc_errors || fc[i].bad_results)) {
                rc = 5;
            }
        }
        bool mixed = r->cfg[0].link.model != r->cfg[1].link.model;
        int starts = report_starts(&s, period, mixed, j);
        rc = rc || j ? rc : starts;
        /* each image keeps to its own bank: PRU1 never waits for PRU0 */
        uint64_t stalls = pru_spad_collisions(bench_core(b[1]));
        if (j) {
            cJSON_AddNumberToObject(j, "spad_stalls", (double)stalls);
            sim_print_json_object(j);
        } else {
            printf("scratch pad          PRU1 stalled %llu times on PRU0's bank\n",
                   (unsigned long long)stalls);
        }
        rc = rc || j ? rc : stalls ? 5 : 0;
    }
    free(s.t[0]);
    free(s.t[1]);
    bench_free(b[1]);
    bench_free(b[0]);
    return rc;
}
