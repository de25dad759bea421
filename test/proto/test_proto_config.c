/* The configuration checks (proto/biss_config_check.c, biss_rate.c): every
 * error code of biss_config_check and biss_rate_half, found on the field
 * that causes it. */
#include "biss_proto.h"

#include "check_run.h"

#include <check.h>
#include <stdlib.h>
#include <string.h>

/* One TIDEP0022-like slave at 10 MHz: 12-bit position, nE, nW, CRC6. */
static struct biss_config good(void) {
    struct biss_config c;
    biss_config_default(&c);
    c.freq_hz = 10000000;
    c.nslaves = 1;
    c.slave[0] = (struct biss_slave_config){
        .data_bits = 14, .crc_bits = 6, .crc_poly = 0x43, .has_ew = true, .ew_shift = 0};
    return c;
}

START_TEST(test_good_config_passes) {
    struct biss_config c = good();
    ck_assert_int_eq(biss_config_check(&c), BISS_OK);
    ck_assert_int_eq(biss_config_check(NULL), BISS_E_INVAL);
}
END_TEST

/* 1, 2, 5, 10 MHz and the extremes are exact; H must split into two
 * divider ratios of 2..32. */
START_TEST(test_rates) {
    static const struct {
        uint32_t f;
        int rc;
        unsigned half;
    } t[] = {
        {10000000, BISS_OK, 10},
        {5000000, BISS_OK, 20},
        {2000000, BISS_OK, 50},
        {1000000, BISS_OK, 100},
        {97657, BISS_E_RATE_INEXACT, 0},
        {100000000 / 1024 + 1, BISS_E_RATE_INEXACT, 0},
        {100000000 / 625, BISS_OK, 625},
        {100000000 / 1000, BISS_E_RATE_SHIFT, 0},
        {0, BISS_E_RATE_RANGE, 0},
        {20000000, BISS_E_RATE_RANGE, 0},
        {10000001, BISS_E_RATE_RANGE, 0},
        {97656, BISS_E_RATE_RANGE, 0},
        {3000000, BISS_E_RATE_INEXACT, 0},
        {4000000, BISS_OK, 25},
        {12500000, BISS_E_RATE_RANGE, 0},
    };
    for (size_t i = 0; i < sizeof t / sizeof t[0]; i++) {
        unsigned half = 0;
        ck_assert_msg(biss_rate_half(t[i].f, &half) == t[i].rc, "f=%u", t[i].f);
        if (t[i].rc == BISS_OK) {
            ck_assert_uint_eq(half, t[i].half);
        }
    }
    ck_assert_int_eq(biss_rate_half(1000000, NULL), BISS_E_INVAL);
    /* H = 1024 = 32 * 32 is the slowest rate */
    unsigned half;
    ck_assert_int_eq(biss_rate_half(97656, &half), BISS_E_RATE_RANGE);
    struct biss_config c = good();
    c.freq_hz = 3000000;
    ck_assert_int_eq(biss_config_check(&c), BISS_E_RATE_INEXACT);
    c.freq_hz = 100000;
    ck_assert_int_eq(biss_config_check(&c), BISS_E_RATE_SHIFT);
    c.freq_hz = 20000000;
    ck_assert_int_eq(biss_config_check(&c), BISS_E_RATE_RANGE);
}
END_TEST

/* Every exact H the firmware accepts is exactly what biss_rate_half accepts:
 * both follow H = a*b, 2 <= a,b <= 32, 10 <= H <= 1024. */
START_TEST(test_rate_rule_exhaustive) {
    for (unsigned h = 1; h <= 2048; h++) {
        if (100000000u % h) {
            continue;
        }
        int expect = h >= 10 && h <= 1024;
        int split = 0;
        for (unsigned a = 2; a <= 32; a++) {
            split |= h % a == 0 && h / a >= 2 && h / a <= 32;
        }
        unsigned half = 0;
        int rc = biss_rate_half(100000000u / h, &half);
        if (!expect) {
            ck_assert_int_eq(rc, BISS_E_RATE_RANGE);
        } else if (!split) {
            ck_assert_int_eq(rc, BISS_E_RATE_SHIFT);
        } else {
            ck_assert_int_eq(rc, BISS_OK);
            ck_assert_uint_eq(half, h);
        }
    }
}
END_TEST

START_TEST(test_nslaves) {
    struct biss_config c = good();
    c.nslaves = 0;
    ck_assert_int_eq(biss_config_check(&c), BISS_E_NSLAVES);
    c.nslaves = 9;
    ck_assert_int_eq(biss_config_check(&c), BISS_E_NSLAVES);
    c.nslaves = 8;
    for (int i = 1; i < 8; i++) {
        c.slave[i] = c.slave[0];
    }
    ck_assert_int_eq(biss_config_check(&c), BISS_OK);
}
END_TEST

START_TEST(test_data_bits) {
    struct biss_config c = good();
    c.slave[0].data_bits = 0;
    c.slave[0].has_ew = false;
    ck_assert_int_eq(biss_config_check(&c), BISS_E_DATA_BITS);
    c.slave[0].data_bits = 65;
    ck_assert_int_eq(biss_config_check(&c), BISS_E_DATA_BITS);
    c.slave[0].data_bits = 64;
    ck_assert_int_eq(biss_config_check(&c), BISS_OK);
    c.slave[0].data_bits = 1;
    ck_assert_int_eq(biss_config_check(&c), BISS_OK);
    /* a bad second slave is found too */
    c = good();
    c.nslaves = 2;
    c.slave[1] = c.slave[0];
    c.slave[1].data_bits = 70;
    ck_assert_int_eq(biss_config_check(&c), BISS_E_DATA_BITS);
}
END_TEST

START_TEST(test_crc) {
    struct biss_config c = good();
    c.slave[0].crc_bits = 17;
    ck_assert_int_eq(biss_config_check(&c), BISS_E_CRC_BITS);
    /* datasheet polynomials, with their top term */
    c.slave[0].crc_bits = 16;
    c.slave[0].crc_poly = 0x190D9;
    ck_assert_int_eq(biss_config_check(&c), BISS_OK);
    c.slave[0].crc_bits = 5;
    c.slave[0].crc_poly = 0x25;
    ck_assert_int_eq(biss_config_check(&c), BISS_OK);
    /* without the top term, or of another degree */
    c.slave[0].crc_bits = 6;
    c.slave[0].crc_poly = 0x03;
    ck_assert_int_eq(biss_config_check(&c), BISS_E_CRC_POLY);
    c.slave[0].crc_poly = 0x25;
    ck_assert_int_eq(biss_config_check(&c), BISS_E_CRC_POLY);
    c.slave[0].crc_poly = 0x143;
    ck_assert_int_eq(biss_config_check(&c), BISS_E_CRC_POLY);
    /* even (no x^0 term): refused, as the scenario files refuse it
     * (biss/biss_rules.h, one rule) */
    c.slave[0].crc_poly = 0x42;
    ck_assert_int_eq(biss_config_check(&c), BISS_E_CRC_POLY);
    c.slave[0].crc_bits = 1;
    c.slave[0].crc_poly = 0x2;
    ck_assert_int_eq(biss_config_check(&c), BISS_E_CRC_POLY);
    c.slave[0].crc_poly = 0x3;
    ck_assert_int_eq(biss_config_check(&c), BISS_OK);
    /* no CRC: no polynomial, no start value */
    c.slave[0].crc_bits = 0;
    c.slave[0].crc_poly = 0x43;
    ck_assert_int_eq(biss_config_check(&c), BISS_E_CRC_POLY);
    c.slave[0].crc_poly = 0;
    ck_assert_int_eq(biss_config_check(&c), BISS_OK);
    c.slave[0].crc_start = 1;
    ck_assert_int_eq(biss_config_check(&c), BISS_E_CRC_START);
    /* start value wider than the CRC */
    c = good();
    c.slave[0].crc_start = 0x3f;
    ck_assert_int_eq(biss_config_check(&c), BISS_OK);
    c.slave[0].crc_start = 0x40;
    ck_assert_int_eq(biss_config_check(&c), BISS_E_CRC_START);
}
END_TEST

START_TEST(test_ew_and_position) {
    struct biss_config c = good();
    /* nE is bit ew_shift + 1: it must lie inside the 14 data bits */
    c.slave[0].ew_shift = 12;
    ck_assert_int_eq(biss_config_check(&c), BISS_OK);
    c.slave[0].ew_shift = 13;
    ck_assert_int_eq(biss_config_check(&c), BISS_E_EW);
    c.slave[0].has_ew = false; /* ew_shift means nothing then */
    ck_assert_int_eq(biss_config_check(&c), BISS_OK);
    c = good();
    c.slave[0].pos_bits = 12;
    ck_assert_int_eq(biss_config_check(&c), BISS_OK);
    c.slave[0].pos_bits = 13;
    ck_assert_int_eq(biss_config_check(&c), BISS_E_POS_BITS);
    c.slave[0].has_ew = false;
    c.slave[0].pos_bits = 14;
    ck_assert_int_eq(biss_config_check(&c), BISS_OK);
    c.slave[0].pos_bits = 15;
    ck_assert_int_eq(biss_config_check(&c), BISS_E_POS_BITS);
}
END_TEST

START_TEST(test_trigger_proc) {
    struct biss_config c = good();
    c.trigger = (enum biss_trigger)4;
    ck_assert_int_eq(biss_config_check(&c), BISS_E_TRIGGER);
    c = good();
    c.proc_limit = BISS_MAX_PROC_LIMIT; /* 65534: the firmware's count ends at 65535 */
    ck_assert_int_eq(biss_config_check(&c), BISS_OK);
    c.proc_limit = 65535;
    ck_assert_int_eq(biss_config_check(&c), BISS_E_PROC_LIMIT);
}
END_TEST

/* The firmware's rule: at least 2H (N + 8) IEP counts of 5 ns; N = 20
 * bits at H = 10 -> 560 counts = 2800 ns. */
START_TEST(test_iep_period) {
    struct biss_config c = good();
    c.trigger = BISS_TRIGGER_IEP;
    c.iep_period_ns = 2800;
    ck_assert_int_eq(biss_config_check(&c), BISS_OK);
    c.iep_period_ns = 2795;
    ck_assert_int_eq(biss_config_check(&c), BISS_E_IEP_PERIOD);
    c.iep_period_ns = 2801;
    ck_assert_int_eq(biss_config_check(&c), BISS_E_IEP_PERIOD);
    c.iep_period_ns = 0;
    ck_assert_int_eq(biss_config_check(&c), BISS_E_IEP_PERIOD);
    /* other triggers ignore it */
    c.trigger = BISS_TRIGGER_FREERUN;
    ck_assert_int_eq(biss_config_check(&c), BISS_OK);
}
END_TEST

int main(void) {
    Suite *s = suite_create("proto_config");
    TCase *tc = tcase_create("check");
    tcase_add_test(tc, test_good_config_passes);
    tcase_add_test(tc, test_rates);
    tcase_add_test(tc, test_rate_rule_exhaustive);
    tcase_add_test(tc, test_nslaves);
    tcase_add_test(tc, test_data_bits);
    tcase_add_test(tc, test_crc);
    tcase_add_test(tc, test_ew_and_position);
    tcase_add_test(tc, test_trigger_proc);
    tcase_add_test(tc, test_iep_period);
    suite_add_tcase(s, tc);
    return check_run(s);
}
