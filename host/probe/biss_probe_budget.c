/* biss_probe_budget.c - the limits of one analysis: work (steps counted by
 * the search, the same on every machine) and a deadline (CLOCK_MONOTONIC),
 * and the progress report of a long run. */
#include "biss_probe_priv.h"

#include <time.h>

#define LOOK_EVERY 65536 /* steps between readings of the clock (~0.1 ms) */

double probe_now_s(void) {
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + (double)t.tv_nsec * 1e-9;
}

void probe_budget_init(struct probe_budget *b, const struct biss_probe_limits *lim,
                       double start_s) {
    unsigned ms = lim && lim->time_limit_ms ? lim->time_limit_ms : BISS_PROBE_TIME_LIMIT_MS;
    *b = (struct probe_budget){
        .limit = lim && lim->work_limit ? lim->work_limit : BISS_PROBE_WORK_LIMIT,
        .next_look = LOOK_EVERY,
        .start_s = start_s,
        .deadline_s = start_s + ms / 1000.0,
        .next_report_s = start_s + 1.0,
        .lim = lim,
    };
}

unsigned probe_budget_elapsed_ms(const struct probe_budget *b) {
    double ms = (probe_now_s() - b->start_s) * 1000.0;
    return ms > 0 ? (unsigned)ms : 0;
}

static void report(struct probe_budget *b, double now) {
    const struct biss_probe_limits *lim = b->lim;
    b->next_report_s = now + 1.0;
    if (lim && lim->progress) {
        struct biss_probe_progress p = {
            .work = b->work,
            .work_limit = b->limit,
            .elapsed_ms = (unsigned)((now - b->start_s) * 1000.0),
            .time_limit_ms = (unsigned)((b->deadline_s - b->start_s) * 1000.0 + 0.5),
            .offsets_searched = b->offsets_searched,
            .end_bit = b->end_bit,
        };
        lim->progress(lim->ctx, &p);
    }
}

bool probe_budget_spend(struct probe_budget *b, uint64_t w) {
    if (b->ran_out) {
        return true;
    }
    b->work += w;
    if (b->work >= b->limit) {
        b->ran_out = BISS_PROBE_RAN_OUT_WORK;
        return true;
    }
    if (b->work >= b->next_look) {
        b->next_look = b->work + LOOK_EVERY;
        double now = probe_now_s();
        if (now >= b->deadline_s) {
            b->ran_out = BISS_PROBE_RAN_OUT_TIME;
            return true;
        }
        if (now >= b->next_report_s) {
            report(b, now);
        }
    }
    return false;
}
