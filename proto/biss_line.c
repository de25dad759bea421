/* biss_line.c - what a line allows: TIDEP0022 Table 5 (rate against cable
 * length), the firmware's longest round trip, iC-MB4's shortest slave
 * timeout, and the rates that would work (biss/biss_rules.h, "what a line
 * allows"). The one copy of these rules: bissctl and biss-sim name them
 * in these words. */
#include "biss_proto.h"

#include "biss/biss_shm.h"

#include <stdarg.h>
#include <stdio.h>
#include <string.h>

/* TIDEP0022 §3.2.2, Table 5 "Supported Frequencies": rate, longest cable. */
static const struct {
    uint32_t freq_hz;
    double cable_m;
} table5[] = {{10000000u, 10.0}, {5000000u, 25.0}, {2000000u, 60.0}, {1000000u, 100.0}};
#define TABLE5_ROWS (sizeof table5 / sizeof table5[0])

/* iC-MB4 item I306: the slave's timeout, at least 55 % of the MA period. */
#define TIMEOUT_PERMILLE 550u

double biss_rate_cable_max_m(double freq_hz) {
    if (freq_hz > table5[0].freq_hz) {
        return 0;
    }
    double m = table5[0].cable_m;
    for (unsigned i = 1; i < TABLE5_ROWS; i++) {
        if (freq_hz <= table5[i].freq_hz) {
            m = table5[i].cable_m; /* as slow as this row or slower */
        }
    }
    return m;
}

double biss_round_trip_cable_m(double round_trip_ns) {
    double m = (round_trip_ns - BISS_LINE_FIXED_NS) / BISS_LINE_NS_PER_M;
    return m > 0 ? m : 0;
}

uint32_t biss_rate_timeout_min_ns(double freq_hz) {
    if (!(freq_hz > 0)) {
        return UINT32_MAX;
    }
    double ns = TIMEOUT_PERMILLE * 1e6 / freq_hz; /* 0.55 / f in ns, rounded up */
    uint32_t n = (uint32_t)ns;
    return n + (n < ns);
}

int biss_rate_text(double freq_hz, char *buf, size_t len) {
    if (freq_hz >= 1e6) {
        return snprintf(buf, len, "%.10g MHz", freq_hz / 1e6);
    }
    return snprintf(buf, len, "%.10g kHz", freq_hz / 1e3);
}

/* Whether rate f suits a cable of cable_m (< 0: unknown) and v's slave
 * timeout. */
static bool rate_works(uint32_t f, double cable_m, const struct biss_line_verdict *v) {
    if (cable_m >= 0 && biss_rate_cable_max_m(f) < cable_m) {
        return false;
    }
    return !v->slave_timeout_ns || biss_rate_timeout_min_ns(f) <= v->slave_timeout_ns;
}

/* The exact rates (100 MHz / H, whole Hz) nearest v->freq_hz that suit a
 * cable of cable_m, nearest first. */
static void nearest_rates(struct biss_line_verdict *v, double cable_m) {
    v->nrates = 0;
    if (v->delay_unreadable) {
        return; /* no rate shortens the line */
    }
    double dist[BISS_LINE_MAX_RATES];
    for (unsigned h = BISS_MIN_HALF; h <= BISS_MAX_HALF; h++) {
        uint32_t f;
        if (biss_proto_half_rate(h, &f) != BISS_OK || !rate_works(f, cable_m, v)) {
            continue;
        }
        double d = (double)f > v->freq_hz ? (double)f - v->freq_hz : v->freq_hz - (double)f;
        unsigned at = v->nrates;
        while (at > 0 && dist[at - 1] > d) {
            at--;
        }
        if (at >= BISS_LINE_MAX_RATES) {
            continue;
        }
        unsigned last = v->nrates < BISS_LINE_MAX_RATES ? v->nrates : BISS_LINE_MAX_RATES - 1;
        for (unsigned k = last; k > at; k--) {
            dist[k] = dist[k - 1];
            v->rates[k] = v->rates[k - 1];
        }
        dist[at] = d;
        v->rates[at] = f;
        v->nrates += v->nrates < BISS_LINE_MAX_RATES;
    }
}

int biss_line_check(uint32_t freq_hz, const struct biss_line_facts *f,
                    struct biss_line_verdict *v) {
    if (v) {
        memset(v, 0, sizeof *v); /* nothing to say, whatever comes back */
    }
    unsigned half;
    int rc = biss_rate_half(freq_hz, &half);
    return rc != BISS_OK ? rc : biss_proto_line_check(half, f, v);
}

int biss_proto_line_check(unsigned half, const struct biss_line_facts *f,
                          struct biss_line_verdict *v) {
    if (v) {
        memset(v, 0, sizeof *v);
    }
    if (!f || !v) {
        return BISS_E_INVAL;
    }
    int rc = biss_proto_half_check(half);
    if (rc != BISS_OK) {
        return rc;
    }
    double freq_hz = (double)BISS_HALF_CLOCK_HZ / half;
    memset(v, 0, sizeof *v);
    v->freq_hz = freq_hz;
    v->round_trip_ns = f->round_trip_ns;
    v->cable_max_m = biss_rate_cable_max_m(freq_hz);
    v->timeout_min_ns = biss_rate_timeout_min_ns(freq_hz);
    v->slave_timeout_ns = f->slave_timeout_ns;
    v->cable_m = f->cable_m;
    double slack_m = 0;
    if (f->cable_m < 0 && f->round_trip_ns >= 0) {
        v->cable_m = biss_round_trip_cable_m(f->round_trip_ns);
        v->estimated = true;
        slack_m = f->round_trip_res_ns / BISS_LINE_NS_PER_M; /* the measurement's own step */
    }
    /* an estimate counts only beyond its own resolution */
    double sure_m = v->cable_m >= 0 ? v->cable_m - slack_m : -1;
    v->beyond_table = v->cable_m >= 0 && sure_m > v->cable_max_m;
    v->timeout_short = f->slave_timeout_ns && f->slave_timeout_ns < v->timeout_min_ns;
    v->delay_unreadable = f->round_trip_ns >= BISS_MAX_DELAY_NS;
    if (v->beyond_table || v->timeout_short) {
        nearest_rates(v, sure_m);
    }
    return v->timeout_short      ? BISS_E_LINE_TIMEOUT
           : v->delay_unreadable ? BISS_E_LINE_DELAY
                                 : BISS_OK;
}

/* Appends to buf at *at (snprintf's way: *at may pass len). */
__attribute__((format(printf, 4, 5))) static void put(char *buf, size_t len, size_t *at,
                                                      const char *fmt, ...) {
    va_list ap;
    va_start(ap, fmt);
    int n = vsnprintf(*at < len ? buf + *at : NULL, *at < len ? len - *at : 0, fmt, ap);
    va_end(ap);
    *at += n > 0 ? (size_t)n : 0;
}

int biss_line_text(const struct biss_line_verdict *v, char *buf, size_t len) {
    size_t at = 0;
    char rate[32];
    biss_rate_text(v->freq_hz, rate, sizeof rate);
    if (len) {
        buf[0] = '\0';
    }
    const char *sep = "";
    if (v->delay_unreadable) {
        put(buf, len, &at,
            "a round trip of %.0f ns is beyond the %u ns the firmware waits for the ACK "
            "(BISS_MAX_DELAY_NS): no slave answers at any rate",
            v->round_trip_ns, (unsigned)BISS_MAX_DELAY_NS);
        sep = "; ";
    }
    if (v->beyond_table && !v->delay_unreadable) {
        if (v->estimated) {
            put(buf, len, &at,
                "%s%s on a line with a round trip of %.0f ns (about %.0f m of cable: %g ns/m "
                "each way after %g ns of transceivers): ",
                sep, rate, v->round_trip_ns, v->cable_m, BISS_LINE_NS_PER_M / 2,
                BISS_LINE_FIXED_NS);
        } else {
            put(buf, len, &at, "%s%s on %g m of cable: ", sep, rate, v->cable_m);
        }
        bool past_table = v->cable_m > table5[TABLE5_ROWS - 1].cable_m;
        if (past_table) {
            put(buf, len, &at, "TIDEP0022 Table 5 goes no further than %g m (1 MHz and slower)",
                table5[TABLE5_ROWS - 1].cable_m);
        } else if (v->cable_max_m > 0) {
            put(buf, len, &at, "TIDEP0022 Table 5 gives %s up to %g m", rate, v->cable_max_m);
        } else {
            put(buf, len, &at, "TIDEP0022 Table 5 gives no rate above 10 MHz");
        }
        if (v->estimated && v->cable_max_m > 0 && !past_table) {
            put(buf, len, &at, " (a round trip up to about %.0f ns)",
                BISS_LINE_FIXED_NS + BISS_LINE_NS_PER_M * v->cable_max_m);
        }
        sep = "; ";
    }
    if (v->timeout_short) {
        put(buf, len, &at,
            "%sa slave timeout of %u ns is below 55 %% of the MA period at %s (%u ns, iC-MB4 "
            "I306): the slave may end the frame within a clock phase",
            sep, v->slave_timeout_ns, rate, v->timeout_min_ns);
        sep = "; ";
    }
    if (v->delay_unreadable) {
        return (int)at;
    }
    if (v->beyond_table || v->timeout_short) {
        if (v->nrates == 0 && v->beyond_table && v->cable_m > table5[TABLE5_ROWS - 1].cable_m) {
            /* said above */
        } else if (v->nrates == 0) {
            put(buf, len, &at, "; no rate the firmware clocks suits both");
        } else {
            put(buf, len, &at, "; rates that work: ");
            for (unsigned i = 0; i < v->nrates; i++) {
                biss_rate_text(v->rates[i], rate, sizeof rate);
                put(buf, len, &at, "%s%s", i ? ", " : "", rate);
            }
        }
    }
    return (int)at;
}
