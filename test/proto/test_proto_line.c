/*
 * Check suite: what a line allows (proto/biss_line.c, libbiss.h): TIDEP0022
 * Table 5 by cable length and by a measured round trip, iC-MB4's shortest
 * slave timeout (I306), the firmware's longest round trip
 * (BISS_MAX_DELAY_NS), the rates that would work, and the words.
 */
#include "check_run.h"
#include "biss_proto.h"
#include "libbiss.h" /* biss_strerror: each code has its text */

#include <stdio.h>
#include <string.h>

static struct biss_line_facts cable(double m) {
    return (struct biss_line_facts){.cable_m = m, .round_trip_ns = -1};
}

static const char *text_of(const struct biss_line_verdict *v) {
    static char buf[1024];
    biss_line_text(v, buf, sizeof buf);
    return buf;
}

/* Table 5: 10 MHz up to 10 m, 5 MHz up to 25 m, 2 MHz up to 60 m, 1 MHz up
 * to 100 m; a rate between rows takes the faster row's length. */
START_TEST(table5_lengths) {
    static const struct {
        double hz, m;
    } want[] = {{10e6, 10}, {9e6, 10},   {6.25e6, 10},    {5e6, 25},
                {4e6, 25},  {2.5e6, 25}, {2e6, 60},       {1.5625e6, 60},
                {1e6, 100}, {5e5, 100},  {97656.25, 100}, {10.000001e6, 0}};
    for (size_t i = 0; i < sizeof want / sizeof want[0]; i++)
        ck_assert_msg(biss_rate_cable_max_m(want[i].hz) == want[i].m, "%g Hz: %g m, want %g",
                      want[i].hz, biss_rate_cable_max_m(want[i].hz), want[i].m);
}
END_TEST

/* iC-MB4 I306: 55 % of the MA period, rounded up to a whole ns. */
START_TEST(timeout_minimum) {
    ck_assert_uint_eq(biss_rate_timeout_min_ns(1e6), 550);
    ck_assert_uint_eq(biss_rate_timeout_min_ns(10e6), 55);
    ck_assert_uint_eq(biss_rate_timeout_min_ns(3e6), 184); /* 183.33 */
    ck_assert_uint_eq(biss_rate_timeout_min_ns(97656.25), 5632);
}
END_TEST

/* The corners of Table 5 with the length known: at the row's length the
 * rate is in, a centimetre more and it is out, with the nearest rates that
 * take that cable (the example of the issue: 5 MHz, 4 MHz, ...). */
START_TEST(cable_known) {
    struct biss_line_verdict v;
    struct biss_line_facts f = cable(10);
    ck_assert_int_eq(biss_line_check(10000000, &f, &v), BISS_OK);
    ck_assert(!v.beyond_table);
    ck_assert_uint_eq(v.nrates, 0);
    ck_assert_str_eq(text_of(&v), "");
    f = cable(10.01);
    ck_assert_int_eq(biss_line_check(10000000, &f, &v), BISS_OK); /* a warning, not a refusal */
    ck_assert(v.beyond_table && !v.estimated);
    ck_assert_uint_eq(v.nrates, 3);
    ck_assert_uint_eq(v.rates[0], 5000000);
    ck_assert_uint_eq(v.rates[1], 4000000);
    ck_assert_uint_eq(v.rates[2], 3125000);
    ck_assert_str_eq(text_of(&v), "10 MHz on 10.01 m of cable: TIDEP0022 Table 5 gives 10 MHz up "
                                  "to 10 m; rates that work: 5 MHz, 4 MHz, 3.125 MHz");
}
END_TEST

/* The 10 MHz on 80 m; Table 5's last row and past it. */
START_TEST(cable_80m) {
    struct biss_line_verdict v;
    struct biss_line_facts f = cable(80);
    ck_assert_int_eq(biss_line_check(10000000, &f, &v), BISS_OK);
    ck_assert_str_eq(text_of(&v), "10 MHz on 80 m of cable: TIDEP0022 Table 5 gives 10 MHz up to "
                                  "10 m; rates that work: 1 MHz, 800 kHz, 781.25 kHz");
    f = cable(100);
    ck_assert_int_eq(biss_line_check(1000000, &f, &v), BISS_OK);
    ck_assert(!v.beyond_table);
    f = cable(101);
    ck_assert_int_eq(biss_line_check(500000, &f, &v), BISS_OK);
    ck_assert(v.beyond_table);
    ck_assert_uint_eq(v.nrates, 0);
    ck_assert_str_eq(text_of(&v), "500 kHz on 101 m of cable: TIDEP0022 Table 5 goes no further "
                                  "than 100 m (1 MHz and slower)");
}
END_TEST

/* Every rate proposed is one the firmware clocks exactly and one the same
 * facts pass. */
START_TEST(proposed_rates_work) {
    static const double cables[] = {0, 9.9, 10.5, 24, 26, 59, 61, 99};
    static const uint32_t timeouts[] = {0, 60, 300, 650, 5000};
    static const uint32_t rates[] = {10000000, 6250000, 5000000, 2000000, 1000000, 500000, 125000};
    unsigned proposed = 0;
    for (size_t i = 0; i < sizeof cables / sizeof cables[0]; i++)
        for (size_t j = 0; j < sizeof timeouts / sizeof timeouts[0]; j++)
            for (size_t k = 0; k < sizeof rates / sizeof rates[0]; k++) {
                struct biss_line_facts f = cable(cables[i]);
                f.slave_timeout_ns = timeouts[j];
                struct biss_line_verdict v, w;
                int rc = biss_line_check(rates[k], &f, &v);
                ck_assert(rc == BISS_OK || rc == BISS_E_LINE_TIMEOUT);
                ck_assert_int_eq(rc == BISS_E_LINE_TIMEOUT, v.timeout_short);
                for (unsigned r = 0; r < v.nrates; r++, proposed++) {
                    unsigned half;
                    ck_assert_int_eq(biss_rate_half(v.rates[r], &half), BISS_OK);
                    ck_assert_int_eq(biss_line_check(v.rates[r], &f, &w), BISS_OK);
                    ck_assert(!w.beyond_table && !w.timeout_short);
                    /* nearest first */
                    if (r > 0) {
                        double a = (double)v.rates[r - 1] - rates[k],
                               b = (double)v.rates[r] - rates[k];
                        ck_assert(a * a <= b * b);
                    }
                }
            }
    ck_assert_uint_gt(proposed, 100);
}
END_TEST

/* I306 at its corner: 550 ns at 1 MHz is in, 549 ns refused, with the
 * faster rates that a 650 ns timeout takes at 500 kHz; with a cable too,
 * only the rates both allow, or none. */
START_TEST(timeout_rule) {
    struct biss_line_verdict v;
    struct biss_line_facts f = cable(-1);
    f.slave_timeout_ns = 550;
    ck_assert_int_eq(biss_line_check(1000000, &f, &v), BISS_OK);
    f.slave_timeout_ns = 549;
    ck_assert_int_eq(biss_line_check(1000000, &f, &v), BISS_E_LINE_TIMEOUT);
    f.slave_timeout_ns = 650;
    ck_assert_int_eq(biss_line_check(500000, &f, &v), BISS_E_LINE_TIMEOUT);
    ck_assert_uint_eq(v.timeout_min_ns, 1100);
    ck_assert_str_eq(
        text_of(&v),
        "a slave timeout of 650 ns is below 55 % of the MA period at 500 kHz (1100 ns, "
        "iC-MB4 I306): the slave may end the frame within a clock phase; rates that "
        "work: 1 MHz, 1.25 MHz, 1.5625 MHz");
    f = cable(30);            /* 2 MHz and slower ... */
    f.slave_timeout_ns = 300; /* ... 1.83 MHz and faster */
    ck_assert_int_eq(biss_line_check(1000000, &f, &v), BISS_E_LINE_TIMEOUT);
    ck_assert_uint_eq(v.nrates, 1);
    ck_assert_uint_eq(v.rates[0], 2000000);
    f = cable(80);
    f.slave_timeout_ns = 300;
    ck_assert_int_eq(biss_line_check(1000000, &f, &v), BISS_E_LINE_TIMEOUT);
    ck_assert_uint_eq(v.nrates, 0);
    ck_assert(strstr(text_of(&v), "no rate the firmware clocks suits both"));
}
END_TEST

/* The firmware waits BISS_MAX_DELAY_NS for the ACK: a round trip that long
 * is refused whatever the rate, and no rate is proposed. */
START_TEST(delay_rule) {
    struct biss_line_verdict v;
    struct biss_line_facts f = {.cable_m = -1, .round_trip_ns = 39999};
    ck_assert_int_eq(biss_line_check(125000, &f, &v), BISS_OK);
    f.round_trip_ns = 40000;
    ck_assert_int_eq(biss_line_check(125000, &f, &v), BISS_E_LINE_DELAY);
    ck_assert_uint_eq(v.nrates, 0);
    ck_assert_str_eq(text_of(&v), "a round trip of 40000 ns is beyond the 40000 ns the firmware "
                                  "waits for the ACK (BISS_MAX_DELAY_NS): no slave answers at any "
                                  "rate");
}
END_TEST

/* A measured round trip stands for (rt - 68 ns) / 10 ns per metre; beyond
 * Table 5 only by more than the measurement's own step (one bit / 8). */
START_TEST(round_trip_estimate) {
    ck_assert(biss_round_trip_cable_m(168) == 10);
    ck_assert(biss_round_trip_cable_m(20) == 0);
    struct biss_line_verdict v;
    struct biss_line_facts f = {.cable_m = -1, .round_trip_ns = 168};
    ck_assert_int_eq(biss_line_check(10000000, &f, &v), BISS_OK);
    ck_assert(!v.beyond_table && v.estimated);
    f.round_trip_ns = 185;
    ck_assert_int_eq(biss_line_check(10000000, &f, &v), BISS_OK);
    ck_assert(v.beyond_table);
    f.round_trip_ns = 178;
    f.round_trip_res_ns = 12.5; /* one bit / 8 at 10 MHz: 11 m less 1.25 m */
    ck_assert_int_eq(biss_line_check(10000000, &f, &v), BISS_OK);
    ck_assert(!v.beyond_table);
    f.round_trip_ns = 1046;
    ck_assert_int_eq(biss_line_check(10000000, &f, &v), BISS_OK);
    ck_assert(v.beyond_table);
    ck_assert_str_eq(text_of(&v),
                     "10 MHz on a line with a round trip of 1046 ns (about 98 m of cable: 5 ns/m "
                     "each way after 68 ns of transceivers): TIDEP0022 Table 5 gives 10 MHz up to "
                     "10 m (a round trip up to about 168 ns); rates that work: 1 MHz, 800 kHz, "
                     "781.25 kHz");
    /* a known length wins over the measurement */
    f.cable_m = 5;
    ck_assert_int_eq(biss_line_check(10000000, &f, &v), BISS_OK);
    ck_assert(!v.beyond_table && !v.estimated);
}
END_TEST

START_TEST(words_and_errors) {
    char buf[32];
    biss_rate_text(10e6, buf, sizeof buf);
    ck_assert_str_eq(buf, "10 MHz");
    biss_rate_text(781250, buf, sizeof buf);
    ck_assert_str_eq(buf, "781.25 kHz");
    biss_rate_text(1562500, buf, sizeof buf);
    ck_assert_str_eq(buf, "1.5625 MHz");
    biss_rate_text(97656.25, buf, sizeof buf);
    ck_assert_str_eq(buf, "97.65625 kHz");
    struct biss_line_verdict v;
    struct biss_line_facts f = cable(1);
    ck_assert_int_eq(biss_line_check(20000000, &f, &v), BISS_E_RATE_RANGE);
    ck_assert_int_eq(biss_line_check(1000000, NULL, &v), BISS_E_INVAL);
    ck_assert_str_ne(biss_strerror(BISS_E_LINE_TIMEOUT), "unknown error");
    ck_assert_str_ne(biss_strerror(BISS_E_LINE_DELAY), "unknown error");
    /* a short buffer: cut, terminated, the whole length returned */
    f = cable(80);
    biss_line_check(10000000, &f, &v);
    char small[16];
    int n = biss_line_text(&v, small, sizeof small);
    ck_assert_int_gt(n, (int)sizeof small);
    ck_assert_uint_eq(strlen(small), sizeof small - 1);
}
END_TEST

int main(void) {
    Suite *s = suite_create("line");
    TCase *t = tcase_create("line");
    tcase_add_test(t, table5_lengths);
    tcase_add_test(t, timeout_minimum);
    tcase_add_test(t, cable_known);
    tcase_add_test(t, cable_80m);
    tcase_add_test(t, proposed_rates_work);
    tcase_add_test(t, timeout_rule);
    tcase_add_test(t, delay_rule);
    tcase_add_test(t, round_trip_estimate);
    tcase_add_test(t, words_and_errors);
    suite_add_tcase(s, t);
    return check_run(s);
}
