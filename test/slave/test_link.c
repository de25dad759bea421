/* Check suite for the assembled far end (MA line, slave, SL line), driven
 * the way the bench drives it: MA edges in time order, SL read at times. */
#include "biss_crc.h"
#include "link_model.h"

#include "check_run.h"

#include <check.h>
#include <math.h>
#include <stdlib.h>

#define NS SIM_PS_PER_NS
#define US SIM_PS_PER_US

static link_model *make(const char *profile, double cable_m, char *why) {
    scenario sc;
    ck_assert_int_eq(profile_by_name(profile, &sc), 0);
    scenario_set_cable(&sc, cable_m);
    link_model *l = malloc(sizeof *l);
    ck_assert_ptr_nonnull(l);
    ck_assert_int_eq(link_init(l, &sc, why, 128), 0);
    return l;
}

START_TEST(ack_round_trip_delay) {
    char why[128];
    link_model *l = make("tidep0022-test-encoder", 2.0, why);
    sim_ps t0 = 10 * US, h = 500 * NS;
    link_ma(l, t0, 0);
    link_ma(l, t0 + h, 1);
    link_ma(l, t0 + 2 * h, 0);
    link_ma(l, t0 + 3 * h, 1); /* second rising edge */
    link_ma(l, t0 + 4 * h, 0);
    /* each direction: 9 ns driver + 2 m x 5 ns/m + 15 ns receiver, plus the
     * low-pass threshold delay 80 ps x ln 2 = 55 ps; SL's falling edge has
     * the 1 ns driver skew; the slave answers 20 ns after MA arrives */
    sim_ps ack = t0 + 3 * h + (34000 + 55) + 20000 + (34000 + 1000 + 55);
    ck_assert_int_eq(link_sl(l, ack - 1), 1);
    ck_assert_int_eq(link_sl(l, ack), 0);
    ck_assert_int_eq(waveform_next_after(&l->sl_master, t0), ack);
    ck_assert_int_eq(waveform_next_after(&l->sl_slave, t0), t0 + 3 * h + 34055 + 20000);
    ck_assert_int_eq(waveform_next_after(&l->ma_slave, t0), t0 + 34000 + 1000 + 55);
    link_free(l);
    free(l);
}
END_TEST

/* A simple master: clocks nclk, reads bit k at rising edge k + round trip +
 * half a period, returns the bits (k = 1..nclk) and the round trip. */
static void clock_frame(link_model *l, sim_ps t0, sim_ps h, int nclk, int *bits, sim_ps *rt) {
    for (int k = 1; k <= nclk; k++) {
        link_ma(l, t0 + (2 * k - 2) * h, 0);
        link_ma(l, t0 + (2 * k - 1) * h, 1);
    }
    sim_ps end = t0 + (2 * nclk + 4) * h + 2 * US;
    link_sl(l, end);
    sim_ps rise2 = t0 + 3 * h;
    sim_ps ack = waveform_next_after(&l->sl_master, rise2);
    *rt = ack - rise2;
    for (int k = 1; k <= nclk; k++) {
        bits[k - 1] = waveform_level_at(&l->sl_master, t0 + (2 * k - 1) * h + *rt + h / 2);
    }
}

/* Decodes a 12-bit + nE nW + CRC6 frame; returns 0 if the CRC matches. */
static int decode12(const int *bits, int nclk, uint64_t *pos) {
    int k = 2;
    while (k < nclk && bits[k] == 0) {
        k++;
    }
    if (k + 1 + 20 >= nclk) {
        return -1;
    }
    k += 2; /* start, CDS */
    uint64_t v = 0;
    for (int i = 0; i < 14; i++) {
        v = (v << 1) | (uint64_t)bits[k + i];
    }
    uint32_t crc = 0;
    for (int i = 0; i < 6; i++) {
        crc = (crc << 1) | (uint32_t)bits[k + 14 + i];
    }
    *pos = v >> 2;
    return ((~biss_crc_bits(0x43, 0, v, 14)) & 0x3f) == crc ? 0 : -1;
}

static int run_frames(const char *profile, double cable_m, sim_ps h, int frames, int *mismatches) {
    char why[128];
    link_model *l = make(profile, cable_m, why);
    int good = 0;
    *mismatches = 0;
    sim_ps t = 10 * US;
    for (int f = 0; f < frames; f++) {
        int bits[40];
        sim_ps rt;
        clock_frame(l, t, h, 30, bits, &rt);
        link_sl(l, t + 100 * US);
        const biss_frame_record *rec = biss_slave_record(link_biss(l), (uint64_t)f);
        uint64_t pos;
        if (rec && decode12(bits, 30, &pos) == 0) {
            if (pos == rec->s[0].position) {
                good++;
            } else {
                (*mismatches)++;
            }
        }
        t += 100 * US;
    }
    ck_assert_uint_eq(link_frames(l), (uint64_t)frames);
    link_free(l);
    free(l);
    return good;
}

START_TEST(frames_decode_through_short_cable) {
    int bad;
    ck_assert_int_eq(run_frames("tidep0022-test-encoder", 10.0, 500 * NS, 20, &bad), 20);
    ck_assert_int_eq(bad, 0);
    ck_assert_int_eq(run_frames("tidep0022-test-encoder", 25.0, 50 * NS, 20, &bad), 20);
}
END_TEST

START_TEST(long_cable_at_10mhz_fails) {
    int bad;
    ck_assert_int_eq(run_frames("tidep0022-test-encoder", 100.0, 50 * NS, 10, &bad), 0);
    /* the same cable at 1 MHz still works */
    ck_assert_int_eq(run_frames("tidep0022-test-encoder", 100.0, 500 * NS, 10, &bad), 10);
}
END_TEST

START_TEST(same_seed_same_waveform) {
    scenario sc;
    char why[128];
    profile_by_name("generic", &sc);
    sc.ma_line.jitter_rms_ps = sc.sl_line.jitter_rms_ps = 500;
    sc.seed = 99;
    sc.biss.s[0].pos0 = 0xa5a;
    link_model *a = malloc(sizeof *a), *b = malloc(sizeof *b);
    ck_assert_int_eq(link_init(a, &sc, why, sizeof why), 0);
    ck_assert_int_eq(link_init(b, &sc, why, sizeof why), 0);
    for (int k = 0; k < 40; k++) {
        sim_ps t = 10 * US + k * 250 * NS;
        link_ma(a, t, k & 1);
        link_ma(b, t, k & 1);
    }
    link_sl(a, 100 * US);
    link_sl(b, 100 * US);
    ck_assert_uint_eq(a->sl_master.len, b->sl_master.len);
    ck_assert_uint_gt(a->sl_master.len, 4);
    for (size_t i = 0; i < a->sl_master.len; i++) {
        ck_assert_int_eq(a->sl_master.edges[i].t, b->sl_master.edges[i].t);
    }
    link_free(a);
    link_free(b);
    free(a);
    free(b);
}
END_TEST

/* A link whose MA and SL-at-the-slave records keep no edges runs the same
 * and records SL at the master the same; the others hold their last level. */
START_TEST(records_without_history) {
    scenario sc;
    char why[128];
    profile_by_name("generic", &sc);
    sc.ma_line.jitter_rms_ps = sc.sl_line.jitter_rms_ps = 300;
    link_model *a = malloc(sizeof *a), *b = malloc(sizeof *b);
    ck_assert_int_eq(link_init(a, &sc, why, sizeof why), 0);
    ck_assert_int_eq(link_init(b, &sc, why, sizeof why), 0);
    link_keep_history(b, 1u << LINK_SL_MASTER);
    waveform *wa[4] = {&a->ma_master, &a->sl_master, &a->ma_slave, &a->sl_slave};
    waveform *wb[4] = {&b->ma_master, &b->sl_master, &b->ma_slave, &b->sl_slave};
    for (int k = 0; k < 60; k++) {
        sim_ps t = 10 * US + k * 250 * NS;
        link_ma(a, t, k & 1);
        link_ma(b, t, k & 1);
        ck_assert_int_eq(link_sl(a, t + 100 * NS), link_sl(b, t + 100 * NS));
        for (int i = 0; i < 4; i++) {
            ck_assert_int_eq(waveform_level_at(wb[i], eq_now(&b->q)),
                             waveform_level_at(wa[i], eq_now(&a->q)));
        }
    }
    link_sl(a, 100 * US);
    link_sl(b, 100 * US);
    ck_assert_uint_gt(a->ma_slave.len, 50);
    ck_assert_uint_gt(a->sl_master.len, 4);
    ck_assert_uint_eq(a->sl_master.len, b->sl_master.len);
    for (size_t i = 0; i < a->sl_master.len; i++) {
        ck_assert_int_eq(a->sl_master.edges[i].t, b->sl_master.edges[i].t);
        ck_assert_int_eq(a->sl_master.edges[i].level, b->sl_master.edges[i].level);
    }
    for (int i = 0; i < 4; i++) {
        ck_assert_uint_eq(wb[i]->len, i == LINK_SL_MASTER ? wa[i]->len : 0);
        ck_assert_int_eq(waveform_last_level(wb[i]), waveform_last_level(wa[i]));
    }
    link_free(a);
    link_free(b);
    free(a);
    free(b);
}
END_TEST

START_TEST(sl_disconnect_reads_stuck) {
    scenario sc;
    char why[128];
    profile_by_name("generic", &sc);
    sc.sl_line.fault = LINE_STUCK_LOW;
    sc.sl_line.fault_at_ps = 5 * US;
    link_model *l = malloc(sizeof *l);
    ck_assert_int_eq(link_init(l, &sc, why, sizeof why), 0);
    ck_assert_int_eq(link_sl(l, 4 * US), 1);
    ck_assert_int_eq(link_sl(l, 6 * US), 0);
    ck_assert_int_eq(link_next_change(l), SIM_NEVER);
    link_free(l);
    free(l);
}
END_TEST

START_TEST(bad_scenario_is_refused) {
    scenario sc;
    char why[128];
    profile_by_name("generic", &sc);
    sc.biss.s[0].pos_bits = 0;
    link_model *l = malloc(sizeof *l);
    ck_assert_int_eq(link_init(l, &sc, why, sizeof why), -1);
    ck_assert_str_eq(why, "biss.slaves[0].position_bits: 0 out of range 1..64");
    free(l);
}
END_TEST

int main(void) {
    Suite *s = suite_create("link");
    TCase *tc = tcase_create("link");
    tcase_add_test(tc, ack_round_trip_delay);
    tcase_add_test(tc, frames_decode_through_short_cable);
    tcase_add_test(tc, long_cable_at_10mhz_fails);
    tcase_add_test(tc, same_seed_same_waveform);
    tcase_add_test(tc, records_without_history);
    tcase_add_test(tc, sl_disconnect_reads_stuck);
    tcase_add_test(tc, bad_scenario_is_refused);
    suite_add_tcase(s, tc);
    return check_run(s);
}
