/*
 * Check suite: an encoder model outside the table of models (toy_model.c:
 * one file, registered with one call) runs through everything a model in
 * the table does: read from a JSON scenario and checked by its own table,
 * built by the link, clocked by the firmware on the emulated PRU, every
 * word the firmware publishes checked against the model's own records,
 * and its bits named on the scope picture.
 */
#include "e2e_util.h"
#include "frame_labels.h"
#include "scenario_json.h"

#include "check_run.h"

#include <check.h>
#include <string.h>

extern const slave_model toy_model;

static void scenario_of(const char *json, scenario *sc) {
    char err[256];
    ck_assert_msg(scenario_from_json(json, sc, err, sizeof err) == 0, "%s", err);
    ck_assert_ptr_eq(sc->model, &toy_model);
}

static void refused(const char *json, const char *want) {
    scenario sc;
    char err[256];
    ck_assert_int_eq(scenario_from_json(json, &sc, err, sizeof err), -1);
    ck_assert_str_eq(err, want);
}

/* The firmware reads the word every frame, and every word it publishes is
 * what the model says it sent; MA clocks at exactly the rate asked. */
START_TEST(toy_read_by_the_firmware) {
    scenario sc;
    scenario_of("{\"protocol\": \"toy\", \"toy\": {\"word\": \"0x2c93\", \"bits\": 14}}", &sc);
    struct e2e_run r;
    struct bench *b = e2e_bench_scenario(&r, &sc, NULL);
    uint64_t want = e2e_frames(10000) / 10 + 10;
    ck_assert_uint_eq(e2e_run_frames(&r, 10, 1000, want), want);
    ck_assert_uint_eq(r.fc.mismatches, 0);
    ck_assert_uint_eq(r.fc.crc_errors, 0);
    ck_assert_uint_eq(r.fc.unmatched, 0);
    ck_assert_uint_eq(r.fc.bad_results, 0);
    ck_assert_uint_eq(r.fc.data[0], 0x2c93);
    ck_assert_uint_eq(r.fc.sent[0], 0x2c93);
    const struct bench_stats *st = bench_stats(b);
    ck_assert_int_eq(st->half_min_ps, 10 * PRU_PS_PER_CYCLE);
    ck_assert_int_eq(st->half_max_ps, 10 * PRU_PS_PER_CYCLE);
    e2e_free(&r);
}
END_TEST

/* A model whose records say other than what it sent is caught on every
 * frame: the bench compares the firmware's words with the model's. */
START_TEST(toy_misreport_caught) {
    scenario sc;
    scenario_of("{\"protocol\": \"toy\", \"toy\": {\"misreport\": true}}", &sc);
    struct e2e_run r;
    e2e_bench_scenario(&r, &sc, NULL);
    ck_assert_uint_eq(e2e_run_frames(&r, 10, 1000, 50), 50);
    ck_assert_uint_eq(r.fc.mismatches, 50);
    ck_assert_uint_eq(r.fc.data[0], 0x2b5); /* the default word, as sent */
    ck_assert_uint_eq(r.fc.sent[0], 0x2b4); /* as the records say */
    e2e_free(&r);
}
END_TEST

/* The scope picture's bit names come from the model: W13 .. W0, each
 * from the rising MA edge that clocks it out plus the output delay. */
START_TEST(toy_labels) {
    scenario sc;
    scenario_of("{\"protocol\": \"toy\", \"toy\": {\"word\": 5, \"bits\": 14, "
                "\"output_delay_ns\": 30}}",
                &sc);
    struct e2e_run r;
    struct bench *b = e2e_bench_scenario(&r, &sc, NULL);
    bench_capture_frame(b, 3);
    ck_assert_uint_eq(e2e_run_frames(&r, 10, 1000, 10), 10);
    waveform *pins[4];
    sim_ps t0, t1;
    ck_assert_int_eq(bench_capture_get(b, pins, &t0, &t1), 0);
    const void *rec = bench_capture_record(b);
    ck_assert_ptr_nonnull(rec);
    static struct svg_label lab[FRAME_LABELS_MAX];
    size_t n = frame_labels(bench_link(b), rec, pins[2], lab, FRAME_LABELS_MAX);
    ck_assert_uint_eq(n, 14);
    ck_assert_str_eq(lab[0].text, "W13");
    ck_assert_str_eq(lab[13].text, "W0");
    /* the first bit from the first rise after the frame's first fall */
    size_t at = 0;
    sim_ps fall = waveform_find(pins[2], t0, 0, &at);
    sim_ps rise = waveform_find(pins[2], fall, 1, &at);
    ck_assert_int_eq(lab[0].t0, rise + 30 * SIM_PS_PER_NS);
    /* a bit a period (H = 10) long, once the line has settled to the clock */
    ck_assert_int_eq(lab[7].t1 - lab[7].t0, 2 * 10 * PRU_PS_PER_CYCLE);
    e2e_free(&r);
}
END_TEST

/* Its configuration is read and checked by its own table, with the path
 * of each field; the protocol names list it. */
START_TEST(toy_configuration_checked) {
    refused("{\"protocol\": \"toy\", \"toy\": {\"bits\": 0}}", "toy.bits: 0 out of range 1..64");
    refused("{\"protocol\": \"toy\", \"toy\": {\"word\": 1024, \"bits\": 10}}",
            "toy.word: wider than its 10 bits");
    refused("{\"protocol\": \"toy\", \"toy\": {\"monoflop_ns\": 0}}",
            "toy.monoflop_ns: must be > 0");
    refused("{\"protocol\": \"toy\", \"toy\": {\"wrd\": 1}}", "toy.wrd: unknown field");
    refused("{\"protocol\": \"tooy\"}", "protocol: expected \"biss\", \"ssi\" or \"toy\"");
    /* its configuration has a place only when it is the scenario's model */
    refused("{\"toy\": {\"bits\": 3}}",
            "toy: not the scenario's protocol (\"biss\"): its configuration has no place");
    /* no control communication: it is not BiSS-C */
    scenario sc;
    scenario_of("{\"protocol\": \"toy\"}", &sc);
    ck_assert_ptr_null(scenario_chain(&sc));
    ck_assert_int_eq(slave_model_register(&toy_model), -1); /* the name is taken */
    /* a model whose state or configuration does not fit the link's room */
    slave_model big = toy_model;
    big.name = "toy-big";
    big.state_size = sizeof(slave_state_room) + 1;
    ck_assert_int_eq(slave_model_register(&big), -1);
    big.state_size = toy_model.state_size;
    big.cfg_size = SCENARIO_EXT_BYTES + 1;
    ck_assert_int_eq(slave_model_register(&big), -1);
    ck_assert_ptr_null(slave_model_find("toy-big"));
}
END_TEST

static Suite *model_suite(void) {
    Suite *s = suite_create("e2e_model");
    TCase *t = tcase_create("toy");
    tcase_set_timeout(t, 0); /* bounded by its frames */
    tcase_add_test(t, toy_read_by_the_firmware);
    tcase_add_test(t, toy_misreport_caught);
    tcase_add_test(t, toy_labels);
    tcase_add_test(t, toy_configuration_checked);
    suite_add_tcase(s, t);
    return s;
}

int main(void) {
    if (slave_model_register(&toy_model) != 0) {
        return EXIT_FAILURE;
    }
    return check_run(model_suite());
}
