/*
 * End-to-end: the master firmware on PRU0 reads the encoder firmware
 * (pru_slave/) on PRU1 of the same PRU-ICSS through the line model
 * (bench_new_loop), the one-board loop of docs/hardware.md. The scenario's
 * slave model runs beside the encoder on the same MA: every frame the
 * master publishes is checked against the model's (positions, CRC, nE/nW),
 * the encoder's SL against the model's at every rising MA edge at the
 * slave pin, and after control frames both register files byte by byte.
 * Exact equality throughout; 10^5-frame runs: scripts/bench-encoder.
 */
#include "e2e_util.h"

#include "fw_cd.h"
#include "read_file.h"
#include "sim_encoder.h"

#include "check_run.h"

#include <check.h>
#include <stdlib.h>

#ifndef ENCODER_IMAGE_PRU1
#error "ENCODER_IMAGE_PRU1 must name the built encoder image"
#endif

struct loop {
    struct e2e_run r;
    struct sim_encoder enc;
};

/* The loop for a scenario at rate half: the chain moved by counts per
 * frame (slave_fw_chain), the encoder loaded and configured, then the
 * master started; pp: the core parameters (NULL: defaults). */
static void loop_open(struct loop *l, scenario sc, unsigned half, const struct pru_params *pp) {
    struct bench_config cfg;
    bench_config_default(&cfg);
    if (pp) {
        cfg.pru = *pp;
    }
    cfg.link = sc;
    char err[256];
    l->r.b = bench_new_loop(&cfg, err, sizeof err);
    ck_assert_msg(l->r.b, "%s", err);
    double frame_ps = (2.0 * half * 200 + 5000) * 5000.0; /* (only its order matters) */
    biss_chain_cfg c = cfg.link.biss;
    slave_fw_chain(&c, frame_ps, NULL);
    bench_free(l->r.b);
    cfg.link.biss = c;
    l->r.b = bench_new_loop(&cfg, err, sizeof err);
    ck_assert_msg(l->r.b, "%s", err);
    char *image;
    size_t n;
    ck_assert_int_eq(read_file(ENCODER_IMAGE_PRU1, 1u << 16, &image, &n), READ_FILE_OK);
    int rc = sim_encoder_start(&l->enc, l->r.b, image, n, &cfg.link.biss, err, sizeof err);
    free(image);
    ck_assert_msg(rc == 0, "%s", err);
    e2e_start_firmware(&l->r);
    fw_check_attach(&l->r.fc, l->r.b);
}

static void loop_profile(struct loop *l, const char *profile, double cable_m, unsigned half,
                         const struct pru_params *pp) {
    scenario sc;
    ck_assert_int_eq(profile_by_name(profile, &sc), 0);
    scenario_set_cable(&sc, cable_m);
    loop_open(l, sc, half, pp);
}

/* The encoder's report finds nothing: its SL the model's, its registers
 * the model's, its status readable. */
static void expect_report_clean(struct loop *l) {
    cJSON *j = cJSON_CreateObject();
    ck_assert_int_eq(sim_encoder_report(&l->enc, j), 0);
    cJSON_Delete(j);
}

/* Every frame right, the encoder's SL the model's, its registers too. */
static void expect_clean(struct loop *l, uint64_t frames) {
    const struct fw_check *fc = &l->r.fc;
    ck_assert_uint_eq(fc->frames, frames);
    ck_assert_uint_eq(fc->crc_errors, 0);
    ck_assert_uint_eq(fc->mismatches, 0);
    ck_assert_uint_eq(fc->no_slave, 0);
    ck_assert_uint_eq(fc->proc_errors, 0);
    const link_model *lm = bench_link(l->r.b);
    ck_assert_uint_gt(lm->ext_compared, frames);
    ck_assert_msg(lm->ext_differ == 0,
                  "the encoder's SL differs from the model's %llu times, "
                  "the first at %.3f us",
                  (unsigned long long)lm->ext_differ, (double)lm->ext_first_differ / 1e6);
    expect_report_clean(l);
}

static void loop_free(struct loop *l) {
    e2e_free(&l->r);
}

/* 1, 2, 5 and 10 MHz on 2 m and 50 m of cable. */
START_TEST(rates_and_cables) {
    static const unsigned halves[] = {100, 50, 20, 10};
    static const double cables[] = {2, 50};
    uint64_t frames = e2e_frames(10000) / 5;
    struct loop l;
    loop_profile(&l, "tidep0022-test-encoder", cables[_i % 2], halves[_i / 2], NULL);
    ck_assert_uint_eq(e2e_run_frames(&l.r, halves[_i / 2], 1000, frames), frames);
    expect_clean(&l, frames);
    loop_free(&l);
}
END_TEST

/* The chains and the layouts: the AD38's three slaves (CRC polynomials
 * 0x25, 0x43, 0x190D9, a life counter, processing time), a two-channel
 * safety encoder (two CRC start values), the POSITAL kit, the generic. */
START_TEST(profiles) {
    static const char *const names[] = {"hengstler-ad38", "biss-safety-two-channel",
                                        "posital-kit-layout-biss-c", "generic"};
    uint64_t frames = e2e_frames(10000) / 10;
    struct loop l;
    loop_profile(&l, names[_i], 2, 10, NULL);
    ck_assert_uint_eq(e2e_run_frames(&l.r, 10, 1000, frames), frames);
    expect_clean(&l, frames);
    loop_free(&l);
}
END_TEST

/* Runs a control program to its end, frames going on: its verdict want. */
static void run_cd(struct loop *l, const biss_cd_prog *p, struct fw_cd *cd, biss_cd_err want) {
    fw_cd_issue(cd, l->r.b, p, 20);
    int64_t end = pru_time_ps(bench_core(l->r.b)) + 200 * SIM_PS_PER_MS;
    while (!fw_cd_poll(cd) && pru_time_ps(bench_core(l->r.b)) < end) {
        ck_assert_int_eq(
            bench_run_until(l->r.b, pru_time_ps(bench_core(l->r.b)) + 20 * SIM_PS_PER_US),
            PRU_STOP_LIMIT);
    }
    ck_assert_msg(cd->done, "the control frame did not end");
    ck_assert_int_eq(cd->err, want);
}

/* Register read, write and sequential access through the master, at each
 * rate: what the master reads is what the encoder's register file holds
 * (the model's, byte for byte, after every program); a write lands in it;
 * a command reaches its slave. */
START_TEST(control) {
    static const unsigned halves[] = {100, 50, 20, 10};
    struct loop l;
    loop_profile(&l, "hengstler-ad38", 2, halves[_i], NULL);
    ck_assert_uint_eq(e2e_run_frames(&l.r, halves[_i], 1000, 10), 10);
    fw_check_restart(&l.r.fc, UINT64_MAX);
    static biss_cd_prog p;
    struct fw_cd cd;
    /* ID 1 (chain slave 1): 8 bytes from 0x78, sequential */
    ck_assert_int_eq(biss_cd_build_read(&p, 1, 0x78, 8), BISS_CD_OK);
    run_cd(&l, &p, &cd, BISS_CD_OK);
    ck_assert_uint_eq(cd.result.good_bytes, 8);
    struct biss_slv_regs fw;
    ck_assert_int_eq(biss_proto_encoder_regs_get(&l.enc.io, 1, &fw), 0);
    for (unsigned i = 0; i < 8; i++) {
        ck_assert_uint_eq(cd.result.byte[i].data, fw.direct[0x78 - 0x40 + i]);
    }
    /* ID 0 (chain slave 2): two bytes written, read back */
    static const uint8_t v[2] = {0x5a, 0xc3};
    ck_assert_int_eq(biss_cd_build_write(&p, 0, 0x6a, v, 2), BISS_CD_OK);
    run_cd(&l, &p, &cd, BISS_CD_OK);
    ck_assert_int_eq(biss_proto_encoder_regs_get(&l.enc.io, 2, &fw), 0);
    ck_assert_uint_eq(fw.direct[0x6a - 0x40], v[0]);
    ck_assert_uint_eq(fw.direct[0x6b - 0x40], v[1]);
    ck_assert_int_eq(biss_cd_build_read(&p, 0, 0x6a, 2), BISS_CD_OK);
    run_cd(&l, &p, &cd, BISS_CD_OK);
    ck_assert_uint_eq(cd.result.good_bytes, 2);
    ck_assert_uint_eq(cd.result.byte[0].data, v[0]);
    ck_assert_uint_eq(cd.result.byte[1].data, v[1]);
    /* a command to ID 1 (bit 1 of the host's mask), with the IDA test;
     * then to IDs 1 and 7, 7 silent: the master withholds it (inverts the
     * execute bit), ID 1 drops it */
    ck_assert_int_eq(biss_cd_build_command(&p, 0x02, 2, true), BISS_CD_OK);
    run_cd(&l, &p, &cd, BISS_CD_OK);
    ck_assert_uint_eq(cd.result.ida, 0x02);
    ck_assert_int_eq(biss_cd_build_command(&p, 0x82, 3, true), BISS_CD_OK);
    run_cd(&l, &p, &cd, BISS_CD_E_WITHHELD);
    /* (the encoder counts what a control frame's last bit did in the next
     * frame's tail: pru_slave/README.md, "Control communication") */
    bench_run_until(l.r.b, pru_time_ps(bench_core(l.r.b)) + SIM_PS_PER_MS);
    struct biss_slv_status st;
    ck_assert_int_eq(biss_proto_encoder_status(&l.enc.io, &st), 0);
    ck_assert_uint_eq(st.slave[1].commands, 1);
    ck_assert_uint_eq(st.slave[1].dropped, 1);
    ck_assert_uint_eq(st.slave[1].last_cmd, 2);
    ck_assert_uint_eq(st.slave[2].commands, 0);
    ck_assert_uint_eq(l.r.fc.crc_errors, 0);
    ck_assert_uint_eq(l.r.fc.mismatches, 0);
    ck_assert_uint_eq(bench_link(l.r.b)->ext_differ, 0);
    expect_report_clean(&l);
    loop_free(&l);
}
END_TEST

/* Strict mode on both cores (every rule but mvi, the master's MVIW: its
 * docs/silicon-assumptions.md A3), the encoder's clocked scope taken from
 * MA (pru_strict_inputs), a window of H cycles: frames and a control frame
 * at 10 and 1 MHz, no fault. */
START_TEST(strict_both) {
    static const unsigned halves[] = {10, 100};
    struct pru_params pp;
    pru_params_default(&pp);
    const char *bad;
    ck_assert_int_eq(pru_strict_parse("loop1,loop0,loopfield,dram,spad", &pp.strict, &bad), 0);
    pp.strict_window = halves[_i];
    struct loop l;
    loop_profile(&l, "hengstler-ad38", 2, halves[_i], &pp);
    pru_strict_inputs(bench_encoder_core(l.r.b), 1u << 1);
    ck_assert_uint_eq(e2e_run_frames(&l.r, halves[_i], 1000, 200), 200);
    fw_check_restart(&l.r.fc, UINT64_MAX);
    static biss_cd_prog p;
    struct fw_cd cd;
    ck_assert_int_eq(biss_cd_build_read(&p, 1, 0x78, 4), BISS_CD_OK);
    run_cd(&l, &p, &cd, BISS_CD_OK);
    ck_assert_uint_eq(cd.result.good_bytes, 4);
    ck_assert_uint_eq(bench_link(l.r.b)->ext_differ, 0);
    loop_free(&l);
}
END_TEST

int main(void) {
    Suite *s = suite_create("e2e_encoder");
    TCase *tc = tcase_create("frames");
    tcase_set_timeout(tc, 600);
    tcase_add_loop_test(tc, rates_and_cables, 0, 8);
    tcase_add_loop_test(tc, profiles, 0, 4);
    suite_add_tcase(s, tc);
    tc = tcase_create("control");
    tcase_set_timeout(tc, 600);
    tcase_add_loop_test(tc, control, 0, 4);
    suite_add_tcase(s, tc);
    tc = tcase_create("strict");
    tcase_set_timeout(tc, 600);
    tcase_add_loop_test(tc, strict_both, 0, 2);
    suite_add_tcase(s, tc);
    return check_run(s);
}
