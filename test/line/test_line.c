/* Check suite for the line model: delays, low-pass distortion, jitter,
 * glitches and faults against hand-computed expectations. */
#include "line_model.h"
#include "waveform.h"

#include "check_run.h"

#include <check.h>
#include <math.h>
#include <stdlib.h>

#define NS SIM_PS_PER_NS
#define US SIM_PS_PER_US

typedef struct {
    event_queue q;
    line_dir l;
    waveform out;
} rig;

static void rig_init(rig *r, const line_params *p, uint64_t seed) {
    eq_init(&r->q);
    waveform_init(&r->out, 1);
    line_dir_init(&r->l, p, &r->q, seed, 1, waveform_sink(&r->out));
}

static void rig_free(rig *r) {
    waveform_free(&r->out);
    eq_free(&r->q);
}

/* Feeds an edge the way the bench does: advance, then input. */
static void drive(rig *r, sim_ps t, int level) {
    eq_run_until(&r->q, t);
    line_dir_input(&r->l, t, level);
}

static line_params ideal(double length_m) {
    line_params p;
    line_params_default(&p);
    p.length_m = length_m;
    p.tau_per_m2_ps = 0.0;
    p.fall_extra_ps = 0;
    return p;
}

START_TEST(delay_is_cable_plus_transceivers) {
    line_params p = ideal(10.0);
    rig r;
    rig_init(&r, &p, 1);
    drive(&r, 1 * US, 0);
    drive(&r, 2 * US, 1);
    eq_run_until(&r.q, 10 * US);
    /* 9 ns driver + 10 m * 5 ns/m + 15 ns receiver = 74 ns */
    ck_assert_uint_eq(r.out.len, 2);
    ck_assert_int_eq(r.out.edges[0].t, 1 * US + 74 * NS);
    ck_assert_int_eq(r.out.edges[0].level, 0);
    ck_assert_int_eq(r.out.edges[1].t, 2 * US + 74 * NS);
    ck_assert_double_eq_tol(line_nominal_delay_ps(&p), 74000.0, 0.5);
    rig_free(&r);
}
END_TEST

START_TEST(rise_fall_skew_changes_pulse_width) {
    line_params p = ideal(0.0);
    p.rise_extra_ps = 500;
    p.fall_extra_ps = 2500;
    rig r;
    rig_init(&r, &p, 1);
    drive(&r, 1 * US, 0);            /* falls late: +2.5 ns */
    drive(&r, 1 * US + 100 * NS, 1); /* rises +0.5 ns */
    eq_run_until(&r.q, 10 * US);
    ck_assert_uint_eq(r.out.len, 2);
    ck_assert_int_eq(r.out.edges[0].t, 1 * US + 24 * NS + 2500);
    ck_assert_int_eq(r.out.edges[1].t - r.out.edges[0].t, 100 * NS - 2000);
    rig_free(&r);
}
END_TEST

/* tau = 20 ps/m^2 * 100^2 m^2 = 200 ns; an isolated edge crosses half swing
 * after tau * ln 2. */
START_TEST(bandwidth_adds_threshold_delay) {
    line_params p = ideal(100.0);
    p.tau_per_m2_ps = 20.0;
    ck_assert_double_eq_tol(line_tau_ps(&p), 200000.0, 1e-6);
    rig r;
    rig_init(&r, &p, 1);
    drive(&r, 1 * US, 0);
    eq_run_until(&r.q, 10 * US);
    ck_assert_uint_eq(r.out.len, 1);
    sim_ps expect = 1 * US + (9 + 500 + 15) * NS + (sim_ps)llround(200000.0 * log(2.0));
    ck_assert_int_eq(r.out.edges[0].t, expect);
    rig_free(&r);
}
END_TEST

/* 50 m: tau = 50 ns. A 100 ns low pulse after a long high: the filter falls
 * to e^-2 by the end of the pulse. It crossed 1/2 at tau ln 2 = 34.657 ns
 * and climbs back through 1/2 tau ln(2(1 - e^-2)) = 27.387 ns after the
 * rising input: the output pulse is 100 - 34.657 + 27.387 = 92.73 ns. */
START_TEST(long_cable_shrinks_short_pulse) {
    line_params p = ideal(50.0);
    p.tau_per_m2_ps = 20.0;
    rig r;
    rig_init(&r, &p, 1);
    drive(&r, 1 * US, 0);
    drive(&r, 1 * US + 100 * NS, 1);
    eq_run_until(&r.q, 10 * US);
    ck_assert_uint_eq(r.out.len, 2);
    double tau = 50000.0;
    double fall = tau * log(2.0);
    double rise = tau * log(2.0 * (1.0 - exp(-2.0)));
    double width = 100000.0 - fall + rise;
    ck_assert_double_eq_tol((double)(r.out.edges[1].t - r.out.edges[0].t), width, 2.0);
    ck_assert_double_eq_tol(width, 92730.0, 5.0);
    rig_free(&r);
}
END_TEST

/* The same cable swallows a 30 ns pulse: it ends before the 34.66 ns the
 * filter needs to reach half swing. */
START_TEST(long_cable_swallows_pulse_shorter_than_tau_ln2) {
    line_params p = ideal(50.0);
    p.tau_per_m2_ps = 20.0;
    rig r;
    rig_init(&r, &p, 1);
    drive(&r, 1 * US, 0);
    drive(&r, 1 * US + 30 * NS, 1);
    drive(&r, 2 * US, 0); /* a later long pulse still passes */
    drive(&r, 3 * US, 1);
    eq_run_until(&r.q, 10 * US);
    ck_assert_uint_eq(r.l.vanished, 1);
    ck_assert_uint_eq(r.out.len, 2);
    ck_assert_int_eq(r.out.edges[0].level, 0);
    ck_assert_int_gt(r.out.edges[0].t, 2 * US);
    rig_free(&r);
}
END_TEST

/* 10 MHz clock (50 ns halves) on 100 m (tau 200 ns): the first clock pulses
 * vanish until the filter settles around half swing, so the far end counts
 * fewer clocks than were sent and such a link fails. */
START_TEST(long_cable_high_rate_loses_clocks) {
    line_params p = ideal(100.0);
    p.tau_per_m2_ps = 20.0;
    rig r;
    rig_init(&r, &p, 1);
    int in_edges = 0;
    for (int i = 0; i < 40; i++) {
        drive(&r, 1 * US + i * 50 * NS, (i & 1));
        in_edges++;
    }
    eq_run_until(&r.q, 20 * US);
    ck_assert_uint_ge(r.l.vanished, 2);
    ck_assert_uint_le(r.out.len, (size_t)in_edges - 4);
    rig_free(&r);
}
END_TEST

START_TEST(jitter_statistics_fixed_seed) {
    line_params p = ideal(10.0);
    p.jitter_rms_ps = 300.0;
    rig r;
    rig_init(&r, &p, 1234);
    const int n = 4000;
    for (int i = 0; i < n; i++) {
        drive(&r, (sim_ps)(i + 1) * US, i & 1);
    }
    eq_run_until(&r.q, (sim_ps)(n + 10) * US);
    ck_assert_uint_eq(r.out.len, (size_t)n);
    double sum = 0, sum2 = 0;
    for (int i = 0; i < n; i++) {
        double d = (double)(r.out.edges[i].t - (sim_ps)(i + 1) * US - 74 * NS);
        sum += d;
        sum2 += d * d;
    }
    double mean = sum / n, sd = sqrt(sum2 / n - mean * mean);
    ck_assert_double_lt(fabs(mean), 20.0); /* 3 sigma of the mean ~ 14 ps */
    ck_assert_double_lt(fabs(sd - 300.0), 15.0);

    /* same seed, same edges */
    rig r2;
    rig_init(&r2, &p, 1234);
    for (int i = 0; i < 100; i++) {
        drive(&r2, (sim_ps)(i + 1) * US, i & 1);
    }
    eq_run_until(&r2.q, 200 * US);
    for (int i = 0; i < 100; i++) {
        ck_assert_int_eq(r2.out.edges[i].t, r.out.edges[i].t);
    }
    rig_free(&r2);
    rig_free(&r);
}
END_TEST

START_TEST(jitter_never_reorders_edges) {
    line_params p = ideal(1.0);
    p.jitter_rms_ps = 5000.0; /* larger than the 2 ns pulses below */
    rig r;
    rig_init(&r, &p, 99);
    for (int i = 0; i < 1000; i++) {
        drive(&r, 1 * US + i * 2 * NS, !(i & 1));
    }
    eq_run_until(&r.q, 1 * SIM_PS_PER_MS);
    for (size_t i = 1; i < r.out.len; i++) {
        ck_assert_int_gt(r.out.edges[i].t, r.out.edges[i - 1].t);
    }
    rig_free(&r);
}
END_TEST

/* The settled-filter step ("line-settled") gives the same output edges,
 * to the picosecond, as the low-pass arithmetic: gaps drawn around the
 * settling gap (41 tau) and far below it (pulses that shrink or vanish),
 * with and without jitter. */
START_TEST(settled_step_is_exact) {
    for (int jitter = 0; jitter < 2; jitter++) {
        line_params p;
        line_params_default(&p);
        p.length_m = 20.0; /* tau 8 ns, settled after 328 ns */
        p.jitter_rms_ps = jitter ? 3000.0 : 0.0;
        rig on, off;
        rig_init(&on, &p, 7);
        rig_init(&off, &p, 7);
        line_dir_set_settled_fast(&off.l, 0);
        ck_assert_int_eq(off.l.settle_gap, SIM_NEVER);
        ck_assert_int_eq(on.l.settle_gap, 328000);
        uint64_t x = 12345;
        sim_ps t = 1 * US;
        for (int i = 0; i < 20000; i++) {
            x = x * 6364136223846793005ull + 1442695040888963407ull;
            unsigned r = (unsigned)(x >> 33);
            sim_ps gaps[4] = {1 + r % 10000, 300000 + r % 60000, 327990 + r % 20, 1 + r % 500000};
            t += gaps[r >> 29 & 3];
            drive(&on, t, !(i & 1));
            drive(&off, t, !(i & 1));
        }
        eq_run_until(&on.q, t + 1 * US);
        eq_run_until(&off.q, t + 1 * US);
        ck_assert_uint_gt(on.l.settled_steps, 1000);
        ck_assert_uint_eq(off.l.settled_steps, 0);
        ck_assert_uint_gt(on.l.vanished, 0);
        ck_assert_uint_eq(on.l.vanished, off.l.vanished);
        ck_assert_uint_eq(on.out.len, off.out.len);
        for (size_t i = 0; i < on.out.len; i++) {
            ck_assert_int_eq(on.out.edges[i].t, off.out.edges[i].t);
            ck_assert_int_eq(on.out.edges[i].level, off.out.edges[i].level);
        }
        rig_free(&on);
        rig_free(&off);
    }
}
END_TEST

START_TEST(glitches_are_counted_and_bounded) {
    line_params p = ideal(1.0);
    p.glitch_rate_hz = 1e6;
    p.glitch_width_ps = 10 * NS;
    rig r;
    rig_init(&r, &p, 5);
    eq_run_until(&r.q, 1 * SIM_PS_PER_MS);
    /* Poisson, mean 1000 over 1 ms: within 5 sigma */
    ck_assert_uint_gt(r.l.glitches, 840);
    ck_assert_uint_lt(r.l.glitches, 1160);
    /* each glitch is a 10 ns low pulse on the idle-high line */
    ck_assert_uint_ge(r.out.len, 2 * (size_t)r.l.glitches - 2);
    for (size_t i = 0; i + 1 < r.out.len; i += 2) {
        ck_assert_int_eq(r.out.edges[i].level, 0);
        ck_assert_int_eq(r.out.edges[i + 1].t - r.out.edges[i].t, 10 * NS);
    }
    rig_free(&r);
}
END_TEST

/* The lowest rates the scenario range takes (a denormal 1e-320 Hz: the
 * mean gap overflows a double) give no glitch, not an overflowed time
 * (llround of infinity: a glitch every few ns). */
START_TEST(glitch_rate_near_zero_gives_none) {
    const double rates[] = {1e-320, 4.9e-324, 1e-300, 1e-9};
    for (size_t i = 0; i < sizeof rates / sizeof rates[0]; i++) {
        line_params p = ideal(1.0);
        p.glitch_rate_hz = rates[i];
        rig r;
        rig_init(&r, &p, 5);
        eq_run_until(&r.q, 1 * SIM_PS_PER_MS);
        ck_assert_uint_eq(r.l.glitches, 0);
        ck_assert_uint_eq(r.out.len, 0);
        rig_free(&r);
    }
}
END_TEST

START_TEST(disconnect_stuck_low_then_reconnect) {
    line_params p = ideal(10.0);
    p.fault = LINE_STUCK_LOW;
    p.fault_at_ps = 5 * US;
    rig r;
    rig_init(&r, &p, 1);
    drive(&r, 1 * US, 0);
    drive(&r, 2 * US, 1);
    drive(&r, 6 * US, 0);
    drive(&r, 7 * US, 1); /* ignored while stuck */
    line_dir_set_fault(&r.l, 8 * US, LINE_OK);
    eq_run_until(&r.q, 20 * US);
    ck_assert_int_eq(waveform_level_at(&r.out, 5 * US - 1), 1);
    ck_assert_int_eq(waveform_level_at(&r.out, 5 * US), 0);
    ck_assert_int_eq(waveform_level_at(&r.out, 7 * US + 500 * NS), 0);
    ck_assert_int_eq(waveform_next_after(&r.out, 5 * US), 8 * US);
    ck_assert_int_eq(waveform_level_at(&r.out, 8 * US), 1);
    rig_free(&r);
}
END_TEST

START_TEST(open_line_reads_high) {
    line_params p = ideal(10.0);
    p.fault = LINE_OPEN;
    p.fault_at_ps = 3 * US;
    rig r;
    rig_init(&r, &p, 1);
    drive(&r, 1 * US, 0);
    drive(&r, 4 * US, 1);
    drive(&r, 5 * US, 0);
    eq_run_until(&r.q, 20 * US);
    ck_assert_int_eq(waveform_level_at(&r.out, 2 * US), 0);
    ck_assert_int_eq(waveform_level_at(&r.out, 3 * US), 1);
    ck_assert_int_eq(waveform_next_after(&r.out, 3 * US), SIM_NEVER);
    rig_free(&r);
}
END_TEST

/* The usable-rate verdict follows the bandwidth model: 10 MHz clocks pass
 * 10 m and 40 m but not 65 m or 100 m; 1 MHz passes 100 m. */
START_TEST(usable_rate_follows_cable_length) {
    line_params p;
    line_params_default(&p);
    const sim_ps half_10mhz = 50 * SIM_PS_PER_NS, half_1mhz = 500 * SIM_PS_PER_NS;
    p.length_m = 10;
    ck_assert_int_eq(line_usable(&p, half_10mhz), 1);
    p.length_m = 40;
    ck_assert_int_eq(line_usable(&p, half_10mhz), 1);
    p.length_m = 65;
    ck_assert_int_eq(line_usable(&p, half_10mhz), 0);
    p.length_m = 100;
    ck_assert_int_eq(line_usable(&p, half_10mhz), 0);
    ck_assert_int_eq(line_usable(&p, half_1mhz), 1);
    /* noise does not enter the verdict */
    p.jitter_rms_ps = 5000;
    p.glitch_rate_hz = 1e6;
    ck_assert_int_eq(line_usable(&p, half_1mhz), 1);
}
END_TEST

int main(void) {
    Suite *s = suite_create("line");
    TCase *tc = tcase_create("line");
    tcase_add_test(tc, delay_is_cable_plus_transceivers);
    tcase_add_test(tc, rise_fall_skew_changes_pulse_width);
    tcase_add_test(tc, bandwidth_adds_threshold_delay);
    tcase_add_test(tc, long_cable_shrinks_short_pulse);
    tcase_add_test(tc, long_cable_swallows_pulse_shorter_than_tau_ln2);
    tcase_add_test(tc, long_cable_high_rate_loses_clocks);
    tcase_add_test(tc, jitter_statistics_fixed_seed);
    tcase_add_test(tc, jitter_never_reorders_edges);
    tcase_add_test(tc, settled_step_is_exact);
    tcase_add_test(tc, glitches_are_counted_and_bounded);
    tcase_add_test(tc, glitch_rate_near_zero_gives_none);
    tcase_add_test(tc, disconnect_stuck_low_then_reconnect);
    tcase_add_test(tc, open_line_reads_high);
    tcase_add_test(tc, usable_rate_follows_cable_length);
    suite_add_tcase(s, tc);
    return check_run(s);
}
