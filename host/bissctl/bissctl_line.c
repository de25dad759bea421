/* bissctl_line.c - the MA rate against the line, in proto's words
 * (libbiss.h, "what a line allows"). bissctl knows of the line what the
 * command line says (--cable-m, --slave-timeout-ns) before it configures,
 * and what the firmware measured after the training frame: the same on
 * the emulator as on a board. */
#include "bissctl.h"

#include <stdio.h>

/* What the frames read so far showed (bissctl_line_note). */
static struct {
    bool delay, no_slave;
    double round_trip_ns, res_ns; /* the first measured, and one bit / 8 */
} seen;

static struct biss_line_facts given_facts(const struct bissctl_opts *o) {
    return (struct biss_line_facts){.cable_m = o->open.cable_m,
                                    .round_trip_ns = o->round_trip_ns,
                                    .slave_timeout_ns = o->slave_timeout_ns};
}

/* One bit / 8 of half period H, in ns: the step of a measured round trip. */
static double res_ns(unsigned half) {
    return half * 2.0 * 5.0 / 8.0;
}

int bissctl_line_before(const struct bissctl_opts *o) {
    struct biss_line_facts f = given_facts(o);
    struct biss_line_verdict v;
    int rc = biss_line_check(o->cfg.freq_hz, &f, &v);
    if (rc != BISS_OK && rc != BISS_E_LINE_TIMEOUT && rc != BISS_E_LINE_DELAY) {
        return BISSCTL_OK; /* a rate error is configure's to report */
    }
    char text[512];
    biss_line_text(&v, text, sizeof text);
    if (rc != BISS_OK) {
        fprintf(stderr, "bissctl: configuration: %s\n", text);
        return BISSCTL_FAIL;
    }
    if (v.beyond_table) {
        fprintf(stderr, "bissctl: warning: %s\n", text);
    }
    return BISSCTL_OK;
}

void bissctl_line_note(const struct biss_sample *s) {
    if ((s->valid || s->training) && !s->no_slave && !seen.delay) {
        seen.delay = true;
        seen.round_trip_ns = s->delay.ns;
        seen.res_ns = res_ns(s->delay.half);
    }
    seen.no_slave = seen.no_slave || s->no_slave;
}

/* The line's round trip measured at 1 MHz, as TIDEP0022's start-up does
 * (§3.2.4.1), with the configuration put back after: a training frame
 * of the slower rate. false if none came. */
static bool measure_at_1mhz(biss_t *h, const struct bissctl_opts *o, double *rt_ns) {
    struct biss_config c, slow;
    if (biss_get_config(h, &c) != BISS_OK) {
        return false;
    }
    slow = c;
    slow.freq_hz = 1000000;
    struct biss_sample s = {0};
    uint32_t after = biss_read_sample(h, &s) == BISS_OK ? s.frame : 0;
    bool got = false;
    if (biss_configure(h, &slow) == BISS_OK) {
        for (int tries = 0; tries < 8 && !got; tries++) {
            if (biss_wait_sample(h, after, o->timeout_ms, &s) != BISS_OK) {
                break;
            }
            got = s.training && !s.no_slave && s.delay.half == 100;
            after = s.frame;
        }
    }
    biss_configure(h, &c);
    *rt_ns = s.delay.ns;
    return got;
}

void bissctl_line_report(biss_t *h, const struct bissctl_opts *o) {
    struct biss_config c;
    if (biss_get_config(h, &c) != BISS_OK || c.slave[0].ssi) {
        return; /* an SSI line measures nothing */
    }
    struct biss_line_facts f = given_facts(o);
    struct biss_line_verdict v;
    char text[512];
    if (seen.delay && f.cable_m < 0) {
        f.round_trip_ns = seen.round_trip_ns;
        f.round_trip_res_ns = seen.res_ns;
        if (biss_line_check(c.freq_hz, &f, &v) == BISS_OK && v.beyond_table) {
            biss_line_text(&v, text, sizeof text);
            fprintf(stderr, "bissctl: warning: %s\n", text);
        }
        return;
    }
    if (!seen.no_slave || seen.delay) {
        return;
    }
    char rate[32];
    biss_rate_text(c.freq_hz, rate, sizeof rate);
    if (f.cable_m < 0 && c.freq_hz > 1000000) {
        double rt;
        if (!measure_at_1mhz(h, o, &rt)) {
            fprintf(stderr,
                    "bissctl: no slave answered at %s, nor at 1 MHz: no slave on the "
                    "line, or one whose round trip is beyond %u ns\n",
                    rate, (unsigned)BISS_MAX_DELAY_NS);
            return;
        }
        f.round_trip_ns = rt;
        f.round_trip_res_ns = res_ns(100);
        fprintf(stderr,
                "bissctl: no slave answered at %s; at 1 MHz the line's round trip is "
                "%.0f ns\n",
                rate, rt);
    }
    int rc = biss_line_check(c.freq_hz, &f, &v);
    if (rc == BISS_OK && !v.beyond_table) {
        fprintf(stderr, "bissctl: no slave answered at %s%s\n", rate,
                f.cable_m >= 0 ? " (within TIDEP0022 Table 5 for the cable)" : "");
        return;
    }
    biss_line_text(&v, text, sizeof text);
    fprintf(stderr, "bissctl: no slave answered: %s\n", text);
}

int bissctl_rates(const struct bissctl_opts *o) {
    struct biss_line_facts f = given_facts(o);
    if (f.cable_m < 0 && f.round_trip_ns < 0 && !f.slave_timeout_ns) {
        return bissctl_usage_error("rates needs --cable-m, --round-trip-ns or --slave-timeout-ns");
    }
    printf("TIDEP0022 Table 5: 10 MHz up to 10 m of cable, 5 MHz up to 25 m, 2 MHz up to 60 m, "
           "1 MHz up to 100 m\n");
    if (f.cable_m < 0 && f.round_trip_ns >= 0) {
        double cable = biss_round_trip_cable_m(f.round_trip_ns);
        printf("round trip %.0f ns: about %.0f m of cable (%g ns/m each way after %g ns of "
               "transceivers)\n",
               f.round_trip_ns, cable, BISS_LINE_NS_PER_M / 2, BISS_LINE_FIXED_NS);
    }
    /* the exact rates the firmware clocks that the line allows, fastest first */
    unsigned n = 0;
    printf("rates_hz=");
    for (unsigned h = BISS_MIN_HALF; h <= BISS_MAX_HALF; h++) {
        uint32_t hz;
        struct biss_line_verdict v;
        if (biss_proto_half_rate(h, &hz) != BISS_OK || biss_line_check(hz, &f, &v) != BISS_OK ||
            v.beyond_table) {
            continue;
        }
        printf("%s%u", n++ ? "," : "", hz);
    }
    printf("\n");
    if (o->cfg.freq_hz && o->config_given) {
        struct biss_line_verdict v;
        int rc = biss_line_check(o->cfg.freq_hz, &f, &v);
        if (rc != BISS_OK && rc != BISS_E_LINE_TIMEOUT && rc != BISS_E_LINE_DELAY) {
            return bissctl_fail("rates", rc);
        }
        char text[512], rate[32];
        biss_line_text(&v, text, sizeof text);
        biss_rate_text(o->cfg.freq_hz, rate, sizeof rate);
        printf("%s: %s\n", rate, text[0] ? text : "within TIDEP0022 Table 5 for this line");
        return rc == BISS_OK ? BISSCTL_OK : BISSCTL_FAIL;
    }
    return n ? BISSCTL_OK : BISSCTL_FAIL;
}
