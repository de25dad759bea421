/* Check suite for the codec through the real firmware: the built image of
 * pru_fw/biss_master.p run on the emulated PRU, wired to the slave model of
 * a profile. Programs go in and answers come out through the data RAM, as a
 * host would move them. */
#include "biss_cd.h"
#include "e2e_util.h"
#include "fw_cd.h"
#include "bench_fw.h"

#include "check_run.h"

#include <check.h>

/* Frames of a register access of n bytes, every slave S in time (see
 * test_cd_sim.c); late S adds the slave's processing frames per byte. */
#define REG_FRAMES(n) (20u + BISS_CD_TAIL_ZEROS + 14u * (n))

typedef struct {
    struct e2e_run run;
    uint64_t frames; /* frames the last program took, from CD_CMD to its end */
} fw_rig;

/* The built firmware on the bench with the profile's encoder, configured
 * for 10 MHz free-running frames and run for 200 us. */
static void rig_start(fw_rig *r, unsigned reg_proc_frames) {
    scenario sc;
    ck_assert_int_eq(profile_by_name("tidep0022-test-encoder", &sc), 0);
    sc.biss.s[0].reg_proc_frames = reg_proc_frames;
    struct bench_config cfg;
    bench_config_default(&cfg);
    cfg.pru.fast_forward = 1;
    e2e_bench_scenario(&r->run, &sc, &cfg.pru);
    struct biss_config c;
    bench_fw_config(r->run.b, &c);
    c.freq_hz = 10000000;
    c.trigger = BISS_TRIGGER_FREERUN;
    c.proc_limit = 200;
    bench_fw_configure(r->run.b, &c, 0);
    bench_run_until(r->run.b, pru_time_ps(bench_core(r->run.b)) + 200 * SIM_PS_PER_US);
}

/* Hands p to the firmware as a host would (fw_cd), runs until it reports
 * the end, parses. */
static biss_cd_err rig_run(fw_rig *r, const biss_cd_prog *p, uint16_t wait_limit,
                           biss_cd_result *res) {
    struct fw_cd cd;
    fw_cd_issue(&cd, r->run.b, p, wait_limit);
    struct pru_core *core = bench_core(r->run.b);
    int64_t give_up = pru_time_ps(core) + 100 * SIM_PS_PER_MS;
    while (!fw_cd_poll(&cd)) {
        ck_assert_int_lt(pru_time_ps(core), give_up);
        bench_run_until(r->run.b, pru_time_ps(core) + SIM_PS_PER_US);
    }
    r->frames = cd.frames;
    *res = cd.result;
    return cd.err;
}

static biss_cd_err rig_read(fw_rig *r, unsigned addr, unsigned n, uint16_t wait_limit,
                            biss_cd_result *res) {
    static biss_cd_prog p;
    ck_assert_int_eq(biss_cd_build_read(&p, 0, addr, n), BISS_CD_OK);
    return rig_run(r, &p, wait_limit, res);
}

static void assert_bytes(const biss_cd_result *res, const uint8_t *want, unsigned n) {
    ck_assert_uint_eq(res->good_bytes, n);
    for (unsigned i = 0; i < n; i++) {
        ck_assert_uint_eq(res->byte[i].data, want[i]);
        ck_assert(res->byte[i].crc_ok);
    }
}

/* The frame count from CD_CMD to the end: the program's frames, after at
 * most one frame before the firmware picks it up and, after an earlier
 * program, the 13 more frames of CDM 0 the slaves need. */
static void assert_frames(const fw_rig *r, unsigned want) {
    ck_assert_uint_ge(r->frames, want);
    ck_assert_uint_le(r->frames, want + BISS_CD_IDLE_ZEROS);
}

START_TEST(fw_reads_table11) {
    fw_rig r;
    rig_start(&r, 0);
    biss_cd_result res;
    const uint8_t temp = 0x5f;
    ck_assert_int_eq(rig_read(&r, 0x67, 1, 10, &res), BISS_CD_OK);
    assert_bytes(&res, &temp, 1);
    ck_assert(res.idl_answered);
    ck_assert_uint_eq(res.idl, 0x01); /* ID lock: the one slave holds ID 0 */
    ck_assert_int_eq(res.byte[0].start, BISS_CD_S_IN_TIME);
    /* back to back: the firmware starts each at once */
    ck_assert_int_eq(rig_read(&r, 0x67, 1, 10, &res), BISS_CD_OK);
    assert_frames(&r, REG_FRAMES(1));
    static const uint8_t serial[] = {0x00, 0xd9, 0x01, 0x32};
    ck_assert_int_eq(rig_read(&r, 0x44, 4, 10, &res), BISS_CD_OK);
    assert_bytes(&res, serial, 4);
    assert_frames(&r, REG_FRAMES(4));
    static const uint8_t ident[] = {0x46, 0x3a, 0xc0, 0x0c, 0x00, 0x01, 0x57, 0x41};
    ck_assert_int_eq(rig_read(&r, 0x78, 8, 10, &res), BISS_CD_OK);
    assert_bytes(&res, ident, 8);
    assert_frames(&r, REG_FRAMES(8));
    ck_assert_int_eq(rig_read(&r, 0x40, 64, 10, &res), BISS_CD_OK);
    ck_assert_uint_eq(res.good_bytes, 64);
    ck_assert_uint_eq(res.byte[0x47 - 0x40].data, 0x32);
    ck_assert_uint_eq(res.byte[0x7f - 0x40].data, 0x41);
    assert_frames(&r, REG_FRAMES(64));
    e2e_free(&r.run);
}
END_TEST

START_TEST(fw_write_read_back) {
    fw_rig r;
    rig_start(&r, 0);
    static biss_cd_prog p;
    const uint8_t d[] = {0x3c, 0xa5};
    ck_assert_int_eq(biss_cd_build_write(&p, 0, 0x10, d, 2), BISS_CD_OK);
    biss_cd_result res;
    ck_assert_int_eq(rig_run(&r, &p, 10, &res), BISS_CD_OK);
    ck_assert(res.byte[0].echo_ok && res.byte[1].echo_ok);
    ck_assert_int_eq(rig_read(&r, 0x10, 2, 10, &res), BISS_CD_OK);
    assert_bytes(&res, d, 2);
    e2e_free(&r.run);
}
END_TEST

START_TEST(fw_late_start) {
    fw_rig r;
    rig_start(&r, 3);
    biss_cd_result res;
    static const uint8_t serial[] = {0x00, 0xd9, 0x01, 0x32};
    ck_assert_int_eq(rig_read(&r, 0x44, 4, 10, &res), BISS_CD_OK);
    ck_assert_int_eq(rig_read(&r, 0x44, 4, 3, &res), BISS_CD_OK); /* just enough */
    assert_bytes(&res, serial, 4);
    ck_assert_int_eq(res.byte[3].start, BISS_CD_S_LATE);
    assert_frames(&r, REG_FRAMES(4) + 4 * 3);
    ck_assert_int_eq(rig_read(&r, 0x44, 4, 2, &res), BISS_CD_E_NO_START);
    ck_assert_int_eq(res.byte[0].start, BISS_CD_S_MISSING);
    ck_assert_uint_eq(res.good_bytes, 0);
    e2e_free(&r.run);
}
END_TEST

START_TEST(fw_commands) {
    fw_rig r;
    rig_start(&r, 0);
    static biss_cd_prog p;
    biss_cd_result res;
    ck_assert_int_eq(biss_cd_build_command(&p, 0, 2, false), BISS_CD_OK);
    ck_assert_int_eq(rig_run(&r, &p, 0, &res), BISS_CD_OK);
    ck_assert_uint_eq(res.ida, 0);
    ck_assert_int_eq(link_biss(bench_link(r.run.b))->ctrl[0].last_cmd, 2);
    ck_assert_int_eq(biss_cd_build_command(&p, 0x01, 1, false), BISS_CD_OK); /* ID 0 */
    ck_assert_int_eq(rig_run(&r, &p, 0, &res), BISS_CD_OK);
    ck_assert_uint_eq(res.ida, 0x01);
    ck_assert_int_eq(link_biss(bench_link(r.run.b))->ctrl[0].last_cmd, 1);
    ck_assert_int_eq(biss_cd_build_command(&p, 0x08, 3, false), BISS_CD_OK); /* ID 3: none */
    ck_assert_int_eq(rig_run(&r, &p, 0, &res), BISS_CD_E_IDA);
    ck_assert_uint_eq(res.ida, 0);
    /* IDs 0 and 3 with the IDA test: ID 3 does not answer, so the firmware
     * sends P inverted and slave 0, addressed, drops the command */
    const biss_ctrl *ctrl = &link_biss(bench_link(r.run.b))->ctrl[0];
    ck_assert_int_eq(biss_cd_build_command(&p, 0x09, 2, true), BISS_CD_OK);
    ck_assert_int_eq(rig_run(&r, &p, 0, &res), BISS_CD_E_WITHHELD);
    ck_assert_uint_eq(res.ida, 0x01);
    ck_assert_int_eq(ctrl->last_cmd, 1);
    /* the same test passes for ID 0 alone: executed */
    ck_assert_int_eq(biss_cd_build_command(&p, 0x01, 2, true), BISS_CD_OK);
    ck_assert_int_eq(rig_run(&r, &p, 0, &res), BISS_CD_OK);
    ck_assert_int_eq(ctrl->last_cmd, 2);
    ck_assert_uint_eq(ctrl->commands_dropped, 1); /* the withheld one */
    e2e_free(&r.run);
}
END_TEST

/* The bit after the IDA slots that executes a command, under either
 * convention (the slave's biss_ctrl cmd_stop, the host's ex): the program
 * sends the slave's value and the command is executed; with the IDA test
 * failing the firmware sends the other value, and the addressed slave (ID
 * 0) drops it. Under EX = 1 (the default) the idle zeros that follow never
 * execute it; under P = 0 nothing but the inverted bit protects it. */
START_TEST(fw_ida_test_either_execute_bit) {
    unsigned ex = (unsigned)_i;
    fw_rig r;
    rig_start(&r, 0);
    biss_ctrl *ctrl = &link_biss(bench_link(r.run.b))->ctrl[0];
    ck_assert_uint_eq(ctrl->cmd_stop, BISS_CD_EX_DEFAULT);
    ctrl->cmd_stop = (uint8_t)ex;
    static biss_cd_prog p;
    biss_cd_result res;
    ck_assert_int_eq(biss_cd_build_command_ex(&p, 0x01, 3, true, ex), BISS_CD_OK);
    ck_assert_int_eq(p.op[p.end], ex ? BISS_CDOP_1 : BISS_CDOP_0);
    ck_assert_int_eq(rig_run(&r, &p, 0, &res), BISS_CD_OK);
    bench_run_until(r.run.b, pru_time_ps(bench_core(r.run.b)) + 100 * SIM_PS_PER_US);
    ck_assert_int_eq(ctrl->last_cmd, 3);
    ck_assert_uint_eq(ctrl->commands, 1);
    ck_assert_int_eq(biss_cd_build_command_ex(&p, 0x03, 1, true, ex), BISS_CD_OK); /* ID 1: none */
    ck_assert_int_eq(rig_run(&r, &p, 0, &res), BISS_CD_E_WITHHELD);
    ck_assert_uint_eq(res.ida, 0x01);
    /* (the end is reported in the frame whose timeout carries the bit,
     * before the slave has taken it; then many idle frames) */
    bench_run_until(r.run.b, pru_time_ps(bench_core(r.run.b)) + 500 * SIM_PS_PER_US);
    ck_assert_int_eq(ctrl->last_cmd, 3);
    ck_assert_uint_eq(ctrl->commands, 1);
    ck_assert_uint_eq(ctrl->commands_dropped, 1);
    e2e_free(&r.run);
}
END_TEST

/* Programs back to back: the firmware waits for 14 frames of CDM 0 after
 * the first, as the slaves do, and both go through. */
START_TEST(fw_back_to_back) {
    fw_rig r;
    rig_start(&r, 0);
    static biss_cd_prog p;
    ck_assert_int_eq(biss_cd_build_read(&p, 0, 0x67, 1), BISS_CD_OK);
    biss_cd_result res;
    ck_assert_int_eq(rig_run(&r, &p, 10, &res), BISS_CD_OK);
    ck_assert_int_eq(rig_run(&r, &p, 10, &res), BISS_CD_OK);
    ck_assert_uint_eq(res.byte[0].data, 0x5f);
    e2e_free(&r.run);
}
END_TEST

int main(void) {
    Suite *s = suite_create("proto_cd_fw");
    TCase *tc = tcase_create("fw");
    tcase_add_test(tc, fw_reads_table11);
    tcase_add_test(tc, fw_write_read_back);
    tcase_add_test(tc, fw_late_start);
    tcase_add_test(tc, fw_commands);
    tcase_add_loop_test(tc, fw_ida_test_either_execute_bit, 0, 2);
    tcase_add_test(tc, fw_back_to_back);
    suite_add_tcase(s, tc);
    return check_run(s);
}
