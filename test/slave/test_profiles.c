/* Check suite for the named profiles and the JSON scenario loader. */
#include "biss_ctrl.h"
#include "scenario_json.h"

#include "check_run.h"

#include <check.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static scenario sc;
static char err[256];

START_TEST(every_profile_loads_and_checks) {
    size_t n = 0;
    for (const char *name; (name = profile_name_at(n)); n++) {
        ck_assert_int_eq(profile_by_name(name, &sc), 0);
        ck_assert_str_eq(sc.profile, name);
        ck_assert_msg(scenario_check(&sc, err, sizeof err) == 0, "%s: %s", name, err);
    }
    ck_assert_uint_eq(n, 6);
    ck_assert_int_eq(profile_by_name("nope", &sc), -1);
}
END_TEST

/* Reads an address with a real control frame through the state machine. */
static int ctrl_read(regfile *r, uint8_t addr) {
    biss_ctrl c;
    biss_ctrl_init(&c, 0, r, 0);
    for (int i = 0; i < 14; i++) {
        biss_ctrl_cdm(&c, 0);
    }
    uint32_t hdr = biss_ctrl_reg_header(0, addr);
    uint32_t bits = (1u << 17) | (hdr << 6) | ((uint32_t)biss_ctrl_crc4_sent(hdr, 11) << 2) | 2u;
    /* S, header, CRC, R W: 17 bits; then S */
    for (int i = 17; i >= 0; i--) {
        biss_ctrl_cdm(&c, (int)((bits >> i) & 1u));
    }
    biss_ctrl_cdm(&c, 1); /* S */
    int v = 0;
    for (int i = 0; i < 8; i++) {
        v = (v << 1) | biss_ctrl_cdm(&c, 0);
    }
    return v;
}

START_TEST(tidep0022_registers_match_table11) {
    ck_assert_int_eq(profile_by_name("tidep0022-test-encoder", &sc), 0);
    static const struct {
        uint8_t addr, value;
    } t11[] = {{0x44, 0x00}, {0x45, 0xD9}, {0x46, 0x01}, {0x47, 0x32}, {0x60, 0x0B},
               {0x67, 0x5F}, {0x68, 0x00}, {0x78, 0x46}, {0x79, 0x3A}, {0x7A, 0xC0},
               {0x7B, 0x0C}, {0x7C, 0x00}, {0x7D, 0x01}, {0x7E, 0x57}, {0x7F, 0x41}};
    for (size_t i = 0; i < sizeof t11 / sizeof t11[0]; i++) {
        ck_assert_int_eq(ctrl_read(&sc.biss.s[0].regs, t11[i].addr), t11[i].value);
    }
    biss_slave_cfg *s = &sc.biss.s[0];
    ck_assert_uint_eq(s->pos_bits, 12);
    ck_assert_uint_eq(s->crc_poly, 0x43);
    ck_assert(s->has_err && s->has_warn);
    ck_assert(!regfile_write(&s->regs, 0x45, 1));
    ck_assert(regfile_write(&s->regs, 0x60, 1));
}
END_TEST

START_TEST(posital_layout_and_registers) {
    /* the kit is a BiSS Line encoder: no profile claims to be it */
    ck_assert_int_eq(profile_by_name("posital-kit", &sc), -1);
    ck_assert_int_eq(profile_by_name("posital-kit-layout-biss-c", &sc), 0);
    biss_slave_cfg *s = &sc.biss.s[0];
    ck_assert_uint_eq(biss_slave_cfg_bits(s), 24 + 17 + 7 + 2 + 6);
    ck_assert_int_eq(ctrl_read(&s->regs, 0x42), 0x61);
    ck_assert_int_eq(ctrl_read(&s->regs, 0x7E), 0x46);
    ck_assert_int_eq(ctrl_read(&s->regs, 0x7F), 0x72);
    ck_assert_int_eq(ctrl_read(&s->regs, 0x7A), 0x68);
    ck_assert_uint_eq(s->regs.nbanks, 68);
    ck_assert(regfile_write(&s->regs, 0x40, 67)); /* last bank exists */
    ck_assert(regfile_write(&s->regs, 0x10, 0x99));
    ck_assert(!regfile_write(&s->regs, 0x41, 0));
}
END_TEST

START_TEST(ad38_chain) {
    ck_assert_int_eq(profile_by_name("hengstler-ad38", &sc), 0);
    biss_chain_cfg *b = &sc.biss;
    ck_assert_uint_eq(b->n, 3);
    ck_assert_uint_eq(biss_slave_cfg_bits(&b->s[0]), 16 + 2 + 5);
    ck_assert_uint_eq(biss_slave_cfg_bits(&b->s[1]), 36 + 2 + 6);
    ck_assert_uint_eq(biss_slave_cfg_bits(&b->s[2]), 9 + 2 + 6 + 16);
    ck_assert_int_eq(b->timeout_mode, BISS_TIMEOUT_ADAPTIVE);
    ck_assert_int_eq(b->busy_ps, 2400 * SIM_PS_PER_NS);
    /* two register devices ([AD38] register tables): ID 0 the life-counter
     * channel, ID 1 the A/D and position channels (slave 1 answers) */
    ck_assert_uint_eq(b->s[2].id, 0);
    ck_assert_uint_eq(b->s[1].id, 1);
    ck_assert_uint_eq(b->s[0].id, 1);
    ck_assert(b->s[0].no_control && !b->s[1].no_control && !b->s[2].no_control);
    /* two answering slaves with one ID are refused */
    b->s[0].no_control = false;
    char err[200];
    ck_assert_int_eq(biss_chain_cfg_check(b, err, sizeof err), -1);
    ck_assert_str_eq(err, "slaves[1].id: 1 is slaves[0]'s id too");
}
END_TEST

START_TEST(json_file_overrides_profile) {
    /* the path comes from the build, so the suite runs from any directory */
    const char *path = SCENARIO_DIR "/ad38_long_cable.json";
    ck_assert_msg(scenario_load_file(path, &sc, err, sizeof err) == 0, "%s", err);
    ck_assert_uint_eq(sc.seed, 7);
    ck_assert_double_eq(sc.ma_line.length_m, 50.0);
    ck_assert_double_eq(sc.sl_line.jitter_rms_ps, 200.0);
    ck_assert_int_eq(sc.sl_line.fault, LINE_STUCK_LOW);
    ck_assert_int_eq(sc.ma_line.fault, LINE_OK);
    ck_assert_int_eq(sc.sl_line.fault_at_ps, 5000000000LL);
    ck_assert_int_eq(sc.biss.busy_ps, 2500000);
    ck_assert_int_eq(sc.biss.adaptive_min_ps, 650000);
    ck_assert_uint_eq(sc.biss.n, 3);
    ck_assert_uint_eq(sc.biss.s[0].pos0, 0x1234);
    ck_assert_double_eq(sc.biss.s[0].speed_cps, 0.0);
    ck_assert_uint_eq(sc.biss.s[0].crc_poly, 0x25); /* kept from the profile */
    ck_assert_uint_eq(regfile_read(&sc.biss.s[1].regs, 0x44), 0xAB);
    ck_assert(sc.biss.s[1].regs.flags[0x44] & REG_RO);
    ck_assert_uint_eq(sc.biss.s[1].regs.bank[1][0x10], 5);
    ck_assert(sc.biss.s[2].error);
}
END_TEST

static void expect_error(const char *json, const char *msg) {
    ck_assert_int_eq(scenario_from_json(json, &sc, err, sizeof err), -1);
    ck_assert_msg(strcmp(err, msg) == 0, "got \"%s\", want \"%s\"", err, msg);
}

START_TEST(json_errors_name_the_field) {
    expect_error("{", "not valid JSON (near byte 1)");
    expect_error("[]", "the scenario must be a JSON object");
    expect_error("{\"profile\": \"nope\"}", "profile: unknown profile \"nope\"");
    expect_error("{\"sede\": 1}", "sede: unknown field");
    expect_error("{\"line\": {\"length_m\": -3}}", "line.length_m: -3 out of range 0..1000");
    expect_error("{\"line\": {\"fault\": \"cut\"}}",
                 "line.fault: expected \"none\", \"stuck_low\", \"stuck_high\" or \"open\"");
    expect_error("{\"biss\": {\"slaves\": [{\"crc_poly\": \"0x42\"}]}}",
                 "biss.slaves[0].crc_poly: must be an odd polynomial of degree 1..16 (with its "
                 "top term)");
    expect_error("{\"biss\": {\"slaves\": [{}, {\"position_bits\": true}]}}",
                 "biss.slaves[1].position_bits: expected a number (or a string like \"0x43\")");
    expect_error("{\"biss\": {\"slaves\": [{\"id\": 9}]}}",
                 "biss.slaves[0].id: 9 out of range 0..7");
    expect_error("{\"biss\": {\"slaves\": []}}",
                 "biss.slaves: expected an array of 1 to 8 slave objects");
    expect_error("{\"biss\": {\"timeout\": {\"mode\": \"slow\"}}}",
                 "biss.timeout.mode: expected \"fixed\" or \"adaptive\"");
    expect_error("{\"biss\": {\"slaves\": [{\"registers\": {\"0x80\": 1}}]}}",
                 "biss.slaves[0].registers: address \"0x80\": expected 0x00..0x7F (banked: "
                 "0x00..0x3F)");
    expect_error("{\"ssi\": {\"gray\": 1}}", "ssi.gray: expected true or false");
    expect_error("{\"protocol\": \"ssi\", \"ssi\": {\"bits\": 0}}",
                 "ssi.bits: 0 out of range 1..64");
}
END_TEST

/* Issue 16's inputs: each refused with the field, the value and the
 * range, before a model overflows on it or a run cannot end. */
START_TEST(json_ranges) {
    expect_error("{\"line\": {\"length_m\": 1e300}}", "line.length_m: 1e+300 out of range 0..1000");
    expect_error("{\"line\": {\"length_m\": 1e999}}", "line.length_m: not a finite number");
    expect_error("{\"line\": {\"length_m\": 1e6}}", "line.length_m: 1000000 out of range 0..1000");
    expect_error("{\"sl_line\": {\"glitch_rate_hz\": 1e15, \"glitch_width_ns\": 0}}",
                 "sl_line.glitch_rate_hz: 1000000000000000 out of range 0..10000000");
    expect_error("{\"ma_line\": {\"jitter_rms_ps\": 1e300}}",
                 "ma_line.jitter_rms_ps: 1e+300 out of range 0..1000000");
    expect_error("{\"line\": {\"tau0_ns\": 1e300}}", "line.tau0_ns: 1e+300 out of range 0..10000");
    expect_error("{\"line\": {\"ns_per_m\": 1e300}}", "line.ns_per_m: 1e+300 out of range 0..100");
    expect_error("{\"line\": {\"fault_at_ns\": -1}}",
                 "line.fault_at_ns: -1 out of range 0..1000000000000");
    expect_error("{\"sl_line\": {\"fault\": \"open\", \"fault_at_ns\": 5000, "
                 "\"fault_until_ns\": 4000}}",
                 "sl_line.fault_until_ns: not after fault_at_ns (0: the fault never ends)");
    expect_error("{\"line\": {\"fault\": \"stuck_low\", \"fault_at_ns\": 5000, "
                 "\"fault_until_ns\": 5000}}",
                 "ma_line.fault_until_ns: not after fault_at_ns (0: the fault never ends)");
    expect_error("{\"biss\": {\"timeout\": {\"ns\": 9e9}}}",
                 "biss.timeout.ns: 9000000000 out of range 0..1000000");
    expect_error("{\"biss\": {\"busy_ns\": 9e9}}",
                 "biss.busy_ns: 9000000000 out of range 0..1000000");
    expect_error("{\"biss\": {\"output_delay_ns\": 9e9}}",
                 "biss.output_delay_ns: 9000000000 out of range 0..10000");
    expect_error("{\"biss\": {\"timeout\": {\"mode\": \"adaptive\", \"factor\": 1e999}}}",
                 "biss.timeout.factor: not a finite number");
    expect_error("{\"biss\": {\"slaves\": [{\"speed_cps\": 1e300}]}}",
                 "biss.slaves[0].speed_cps: 1e+300 out of range -1000000000000..1000000000000");
    expect_error("{\"ssi\": {\"speed_cps\": -1e13}}",
                 "ssi.speed_cps: -10000000000000 out of range -1000000000000..1000000000000");
    expect_error("{\"biss\": {\"slaves\": [{\"position_bits\": 64, \"fill_bits\": 64, "
                 "\"life_counter_bits\": 32}]}}",
                 "biss.slaves[0].fill_bits: 64 out of range 0..63");
    expect_error("{\"biss\": {\"slaves\": [{\"position_bits\": 60, \"life_counter_bits\": 4}]}}",
                 "biss.slaves[0].position_bits: with fill_bits, nE, nW and life_counter_bits more "
                 "than 64 data bits before the CRC");
    expect_error("{\"biss\": {\"slaves\": [{\"id\": 2.5}]}}",
                 "biss.slaves[0].id: 2.5 is not a whole number");
    expect_error("{\"biss\": {\"slaves\": [{\"id\": 1}, {\"id\": 1}]}}",
                 "biss.slaves[1].id: 1 is slaves[0]'s id too");
    expect_error("{\"biss\": {\"slaves\": [{\"position\": \"-1\"}]}}",
                 "biss.slaves[0].position: expected a number (or a string like \"0x43\")");
    expect_error("{\"biss\": {\"slaves\": [{\"registers\": {\"0x44\": 1, \"bank1:0x10\": 256}}]}}",
                 "biss.slaves[0].registers.bank1:0x10: 256 out of range 0..255");
    expect_error("{\"biss\": {\"slaves\": [{\"banks\": 73}]}}",
                 "biss.slaves[0].banks: 73 out of range 0..72");
    /* the document itself: nothing after the object, no key twice */
    expect_error("{\"seed\": 1} garbage", "text after the JSON object (at byte 12)");
    expect_error("{\"seed\": 1}{}", "text after the JSON object (at byte 11)");
    expect_error("{\"biss\": {\"slaves\": [{}, {\"id\": 3, \"id\": 4}]}}",
                 "biss.slaves[1].id: given twice");
    expect_error("{\"seed\": 1, \"seed\": 2}", "seed: given twice");
    /* a ranged field set in code is caught by scenario_check */
    ck_assert_int_eq(profile_by_name("generic", &sc), 0);
    sc.sl_line.jitter_rms_ps = NAN;
    ck_assert_int_eq(scenario_check(&sc, err, sizeof err), -1);
    ck_assert_str_eq(err, "sl_line.jitter_rms_ps: not a finite number");
    ck_assert_int_eq(profile_by_name("generic", &sc), 0);
    sc.biss.busy_ps = 9000 * SIM_PS_PER_MS;
    ck_assert_int_eq(scenario_check(&sc, err, sizeof err), -1);
    ck_assert_str_eq(err, "biss.busy_ns: 9000000000 out of range 0..1000000");
    /* where a slave answers its ID lock (host/CD.md, "IDL slots") */
    expect_error("{\"biss\": {\"slaves\": [{\"id_lock_slot\": \"adr\"}]}}",
                 "biss.slaves[0].id_lock_slot: expected \"s\" (IDL0 answers S) or \"cts\" (it "
                 "answers CTS)");
    ck_assert_int_eq(scenario_from_json("{\"biss\": {\"slaves\": [{\"id_lock_slot\": \"cts\"}]}}",
                                        &sc, err, sizeof err),
                     0);
    ck_assert(sc.biss.s[0].idl_at_cts);
    ck_assert_int_eq(scenario_from_json("{\"biss\": {\"slaves\": [{\"id_lock_slot\": \"s\"}]}}",
                                        &sc, err, sizeof err),
                     0);
    ck_assert(!sc.biss.s[0].idl_at_cts);
    /* trailing white space is fine */
    ck_assert_int_eq(scenario_from_json("{\"seed\": 2}\n\t \n", &sc, err, sizeof err), 0);
}
END_TEST

/* Many keys: the duplicate found (and a document without one refused for
 * its first unknown key) in n log n; a scan of every pair takes minutes
 * over 200 000 keys, past the case's timeout. */
START_TEST(json_many_keys) {
    enum { N = 200000 };
    size_t cap = (size_t)N * 16 + 64;
    char *text = malloc(cap);
    ck_assert_ptr_nonnull(text);
    size_t n = (size_t)snprintf(text, cap, "{");
    for (unsigned i = 0; i < N; i++) {
        n += (size_t)snprintf(text + n, cap - n, "\"k%u\": 0, ", i);
    }
    snprintf(text + n, cap - n, "\"k%u\": 1}", N / 2);
    expect_error(text, "k100000: given twice");
    snprintf(text + n - 2, cap - n + 2, "}");
    expect_error(text, "k0: unknown field");
    free(text);
}
END_TEST

/* 64-bit seeds and positions: exact as strings; as JSON numbers only below
 * 2^53, where a double still holds every integer. */
START_TEST(json_exact_64_bit) {
    expect_error("{\"seed\": 18446744073709551615}",
                 "seed: a JSON number is exact only below 2^53 (this one reads as "
                 "18446744073709551616): give it as a string, \"18446744073709551615\" or "
                 "\"0xffffffffffffffff\"");
    expect_error("{\"biss\": {\"slaves\": [{\"position_bits\": 64, \"position\": "
                 "9007199254740993}]}}",
                 "biss.slaves[0].position: a JSON number is exact only below 2^53 (this one reads "
                 "as 9007199254740992): give it as a string, \"18446744073709551615\" or "
                 "\"0xffffffffffffffff\"");
    int r = scenario_from_json("{\"seed\": \"18446744073709551615\", \"biss\": {\"slaves\": "
                               "[{\"position_bits\": 64, \"error_bit\": false, \"warning_bit\": "
                               "false, \"position\": \"0xfffffffffffffffe\"}]}}",
                               &sc, err, sizeof err);
    ck_assert_msg(r == 0, "%s", err);
    ck_assert_uint_eq(sc.seed, UINT64_MAX);
    ck_assert_uint_eq(sc.biss.s[0].pos0, UINT64_MAX - 1);
    ck_assert_int_eq(scenario_from_json("{\"seed\": 9007199254740991}", &sc, err, sizeof err), 0);
    ck_assert_uint_eq(sc.seed, 9007199254740991u);
    expect_error("{\"seed\": \"18446744073709551616\"}",
                 "seed: expected a number (or a string like \"0x43\")");
    expect_error("{\"seed\": -1}", "seed: -1 out of range 0..18446744073709551615");
}
END_TEST

START_TEST(json_ssi_scenario) {
    ck_assert_int_eq(scenario_from_json("{\"profile\": \"ssi\", \"ssi\": {\"bits\": 25, \"gray\": "
                                        "true, \"monoflop_ns\": 30000}}",
                                        &sc, err, sizeof err),
                     0);
    ck_assert_ptr_eq(sc.model, &slave_model_ssi);
    ck_assert_uint_eq(sc.ssi.bits, 25);
    ck_assert(sc.ssi.gray);
    ck_assert_int_eq(sc.ssi.monoflop_ps, 30 * SIM_PS_PER_US);
}
END_TEST

int main(void) {
    Suite *s = suite_create("profiles");
    TCase *tc = tcase_create("profiles");
    tcase_add_test(tc, every_profile_loads_and_checks);
    tcase_add_test(tc, tidep0022_registers_match_table11);
    tcase_add_test(tc, posital_layout_and_registers);
    tcase_add_test(tc, ad38_chain);
    tcase_add_test(tc, json_file_overrides_profile);
    tcase_add_test(tc, json_errors_name_the_field);
    tcase_add_test(tc, json_ssi_scenario);
    tcase_add_test(tc, json_ranges);
    tcase_add_test(tc, json_many_keys);
    tcase_add_test(tc, json_exact_64_bit);
    suite_add_tcase(s, tc);
    return check_run(s);
}
