/*
 * End-to-end: control communication (register access, sequential access,
 * BiSS commands) through the firmware image in the emulator, one CDM bit
 * per frame, while every position frame is checked as well: no position
 * error may occur in the same runs.
 */
#include "e2e_util.h"

#include "biss/biss_shm.h"
#include "fw_cd.h"

#include "check_run.h"

#include <check.h>
#include <stdlib.h>

/* Runs the program to its end (position frames going on); returns its verdict. */
static biss_cd_err run_cd(struct e2e_run *r, const biss_cd_prog *p, uint16_t wait_limit,
                          struct fw_cd *cd) {
    fw_cd_issue(cd, r->b, p, wait_limit);
    int64_t end = pru_time_ps(bench_core(r->b)) + 500 * SIM_PS_PER_MS;
    while (!fw_cd_poll(cd) && pru_time_ps(bench_core(r->b)) < end) {
        ck_assert_int_eq(bench_run_until(r->b, pru_time_ps(bench_core(r->b)) + 20 * SIM_PS_PER_US),
                         PRU_STOP_LIMIT);
    }
    ck_assert_msg(cd->done, "the control frame did not end");
    return cd->err;
}

static void assert_positions_clean(const struct e2e_run *r) {
    ck_assert_uint_gt(r->fc.frames, 0);
    ck_assert_uint_eq(r->fc.mismatches, 0);
    ck_assert_uint_eq(r->fc.crc_errors, 0);
    ck_assert_uint_eq(r->fc.no_slave, 0);
    ck_assert_uint_eq(r->fc.proc_errors, 0);
}

static void read_expect(struct e2e_run *r, unsigned addr, const uint8_t *want, unsigned n) {
    static biss_cd_prog p;
    struct fw_cd cd;
    ck_assert_int_eq(biss_cd_build_read(&p, 0, addr, n), BISS_CD_OK);
    ck_assert_int_eq(run_cd(r, &p, 10, &cd), BISS_CD_OK);
    ck_assert_uint_eq(cd.result.good_bytes, n);
    for (unsigned i = 0; i < n; i++) {
        ck_assert_msg(cd.result.byte[i].data == want[i], "register 0x%02x: 0x%02x, not 0x%02x",
                      addr + i, cd.result.byte[i].data, want[i]);
        ck_assert(cd.result.byte[i].crc_ok);
    }
}

/* The TIDEP0022 design guide's Table 11, at 10, 5, 2 and 1 MHz. */
START_TEST(test_table11_every_rate) {
    static const unsigned halves[] = {10, 20, 50, 100};
    static const uint8_t serial[] = {0x00, 0xd9, 0x01, 0x32};
    static const uint8_t id[] = {0x46, 0x3a, 0xc0, 0x0c, 0x00, 0x01, 0x57, 0x41};
    static const uint8_t temp[] = {0x5f, 0x00}; /* 0x67 temperature, 0x68 status */
    struct e2e_run r;
    e2e_bench(&r, "tidep0022-test-encoder", 10, NULL);
    ck_assert_uint_eq(e2e_run_frames(&r, halves[_i], 1000, 10), 10);
    fw_check_restart(&r.fc, UINT64_MAX);
    read_expect(&r, 0x44, serial, 4);
    read_expect(&r, 0x67, temp, 2);
    read_expect(&r, 0x78, id, 8);
    assert_positions_clean(&r);
    e2e_free(&r);
}
END_TEST

/* 64 bytes in one control frame, across the banked (0x00-0x3F, bank 2
 * chosen through 0x40) and the direct half of a POSITAL kit's registers. */
START_TEST(test_sequential_64_across_bank_switch) {
    struct e2e_run r;
    struct bench *b = e2e_bench(&r, "posital-kit-layout-biss-c", 10, NULL);
    ck_assert_uint_eq(e2e_run_frames(&r, 10, 1000, 10), 10);
    fw_check_restart(&r.fc, UINT64_MAX);
    regfile *regs = &link_biss(bench_link(b))->cfg.s[0].regs;
    for (unsigned a = 0x20; a < 0x40; a++) {
        regfile_poke(regs, 2, (uint8_t)a, (uint8_t)(0xa0 ^ a));
    }
    static biss_cd_prog p;
    struct fw_cd cd;
    uint8_t bank = 2;
    ck_assert_int_eq(biss_cd_build_write(&p, 0, REGFILE_BANK_SEL, &bank, 1), BISS_CD_OK);
    ck_assert_int_eq(run_cd(&r, &p, 10, &cd), BISS_CD_OK);
    uint8_t want[64];
    for (unsigned i = 0; i < 64; i++) {
        want[i] = regfile_read(regs, (uint8_t)(0x20 + i));
    }
    ck_assert_uint_eq(want[0], 0xa0 ^ 0x20); /* bank 2 is in force */
    ck_assert_uint_eq(want[0x20], 2);        /* 0x40 reads back the bank */
    read_expect(&r, 0x20, want, 64);
    assert_positions_clean(&r);
    e2e_free(&r);
}
END_TEST

START_TEST(test_write_then_read_back) {
    static const uint8_t data[] = {0x12, 0x34, 0x56};
    struct e2e_run r;
    e2e_bench(&r, "tidep0022-test-encoder", 2, NULL);
    ck_assert_uint_eq(e2e_run_frames(&r, 20, 1000, 10), 10);
    fw_check_restart(&r.fc, UINT64_MAX);
    static biss_cd_prog p;
    struct fw_cd cd;
    ck_assert_int_eq(biss_cd_build_write(&p, 0, 0x10, data, 3), BISS_CD_OK);
    ck_assert_int_eq(run_cd(&r, &p, 10, &cd), BISS_CD_OK);
    ck_assert_uint_eq(cd.result.good_bytes, 3);
    read_expect(&r, 0x10, data, 3);
    assert_positions_clean(&r);
    e2e_free(&r);
}
END_TEST

/* Commands on the AD38 chain: three data channels, two register devices
 * (ID 0: chain slave 2, the life-counter channel; ID 1: chain slave 1, its
 * data channel 0 answering nothing), addressed (the IDA slots confirm the
 * addressed IDs) and broadcast (no IDA). */
START_TEST(test_commands_with_and_without_ida) {
    struct e2e_run r;
    struct bench *b = e2e_bench(&r, "hengstler-ad38", 2, NULL);
    ck_assert_uint_eq(e2e_run_frames(&r, 10, 1000, 10), 10);
    fw_check_restart(&r.fc, UINT64_MAX);
    static biss_cd_prog p;
    struct fw_cd cd;
    ck_assert_int_eq(biss_cd_build_command(&p, 0x02, 1, false), BISS_CD_OK); /* ID 1 */
    ck_assert_int_eq(run_cd(&r, &p, 10, &cd), BISS_CD_OK);
    ck_assert_uint_eq(cd.result.ida, 0x02);
    link_model *l = bench_link(b);
    ck_assert_int_eq(link_biss(l)->ctrl[1].last_cmd, 1);
    ck_assert_int_eq(link_biss(l)->ctrl[2].last_cmd, -1);
    ck_assert_int_eq(biss_cd_build_command(&p, 0x00, 2, false), BISS_CD_OK); /* broadcast */
    ck_assert_int_eq(run_cd(&r, &p, 10, &cd), BISS_CD_OK);
    ck_assert_uint_eq(cd.result.ida, 0);
    ck_assert_int_eq(link_biss(l)->ctrl[1].last_cmd, 2);
    ck_assert_int_eq(link_biss(l)->ctrl[2].last_cmd, 2);
    ck_assert_int_eq(link_biss(l)->ctrl[0].last_cmd, -1); /* data only */
    /* an ID nobody has (2, as 7): the IDA says so */
    ck_assert_int_eq(biss_cd_build_command(&p, 0x04, 1, false), BISS_CD_OK);
    ck_assert_int_eq(run_cd(&r, &p, 10, &cd), BISS_CD_E_IDA);
    ck_assert_uint_eq(cd.result.ida, 0);
    /* IDA checked before execution: IDs 1 and 7 asked, ID 7 silent, so the
     * firmware inverts the execute bit and ID 1 drops the command; IDs 0
     * and 1 pass */
    ck_assert_int_eq(biss_cd_build_command(&p, 0x82, 3, true), BISS_CD_OK);
    ck_assert_int_eq(run_cd(&r, &p, 10, &cd), BISS_CD_E_WITHHELD);
    ck_assert_uint_eq(cd.status, BISS_CDST_ERR_IDA);
    ck_assert_uint_eq(cd.result.ida, 0x02);
    ck_assert_int_eq(link_biss(l)->ctrl[1].last_cmd, 2);
    ck_assert_uint_eq(link_biss(l)->ctrl[1].commands_dropped, 1);
    ck_assert_int_eq(biss_cd_build_command(&p, 0x03, 3, true), BISS_CD_OK);
    ck_assert_int_eq(run_cd(&r, &p, 10, &cd), BISS_CD_OK);
    ck_assert_uint_eq(cd.result.ida, 0x03);
    ck_assert_int_eq(link_biss(l)->ctrl[1].last_cmd, 3);
    ck_assert_int_eq(link_biss(l)->ctrl[2].last_cmd, 3);
    assert_positions_clean(&r);
    e2e_free(&r);
}
END_TEST

/* AD38 register access reaches the device the notes' register tables
 * name: temperature 0x67 at Slave ID 0 (the life-counter channel, chain
 * slave 2), the position channel's error register 0x69 at Slave ID 1
 * (chain slave 1); ID 2 is nobody's. */
START_TEST(test_ad38_registers_by_id) {
    struct e2e_run r;
    struct bench *b = e2e_bench(&r, "hengstler-ad38", 2, NULL);
    ck_assert_uint_eq(e2e_run_frames(&r, 10, 1000, 10), 10);
    fw_check_restart(&r.fc, UINT64_MAX);
    link_model *l = bench_link(b);
    regfile_poke(&link_biss(l)->cfg.s[2].regs, 0, 0x67, 0x40);
    regfile_poke(&link_biss(l)->cfg.s[1].regs, 0, 0x69, 0x0a);
    static biss_cd_prog p;
    struct fw_cd cd;
    ck_assert_int_eq(biss_cd_build_read(&p, 0, 0x67, 1), BISS_CD_OK);
    ck_assert_int_eq(run_cd(&r, &p, 10, &cd), BISS_CD_OK);
    ck_assert_uint_eq(cd.result.byte[0].data, 0x40);
    /* the header's ID-lock answers: IDs 0 and 1 are taken */
    ck_assert(cd.result.idl_answered);
    ck_assert_uint_eq(cd.result.idl, 0x03);
    ck_assert_int_eq(biss_cd_build_read(&p, 1, 0x69, 1), BISS_CD_OK);
    ck_assert_int_eq(run_cd(&r, &p, 10, &cd), BISS_CD_OK);
    ck_assert_uint_eq(cd.result.byte[0].data, 0x0a);
    ck_assert_int_eq(biss_cd_build_read(&p, 2, 0x67, 1), BISS_CD_OK);
    ck_assert_int_eq(run_cd(&r, &p, 10, &cd), BISS_CD_E_NO_ECHO);
    ck_assert_uint_eq(link_biss(l)->ctrl[2].reads, 1);
    ck_assert_uint_eq(link_biss(l)->ctrl[1].reads, 1);
    assert_positions_clean(&r);
    e2e_free(&r);
}
END_TEST

/* A register processing time of 3 frames (late S): inside a wait limit of
 * 5 the bytes come; with a limit of 2 the firmware reports the missing S. */
START_TEST(test_late_start_bit) {
    static const uint8_t serial[] = {0x00, 0xd9};
    struct e2e_run r;
    struct bench *b = e2e_bench(&r, "tidep0022-test-encoder", 2, NULL);
    link_biss(bench_link(b))->ctrl[0].reg_proc_frames = 3;
    ck_assert_uint_eq(e2e_run_frames(&r, 10, 1000, 10), 10);
    fw_check_restart(&r.fc, UINT64_MAX);
    static biss_cd_prog p;
    struct fw_cd cd;
    ck_assert_int_eq(biss_cd_build_read(&p, 0, 0x44, 2), BISS_CD_OK);
    ck_assert_int_eq(run_cd(&r, &p, 5, &cd), BISS_CD_OK);
    ck_assert_uint_eq(cd.result.byte[0].data, serial[0]);
    ck_assert_uint_eq(cd.result.byte[1].data, serial[1]);
    ck_assert_int_eq(cd.result.byte[0].start, BISS_CD_S_LATE);
    ck_assert_int_eq(run_cd(&r, &p, 2, &cd), BISS_CD_E_NO_START);
    assert_positions_clean(&r);
    e2e_free(&r);
}
END_TEST

/* Late S of 1, 3 and 20 frames at 10 and 1 MHz, against a slave that
 * cancels a control frame on 14 CDM = 0 in any state (TIDEP0022 §2.1.3):
 * a single read and a sequential read of 4 bytes both come through, and
 * the slave never saw a cancel. (13 CDM = 0 follow every read byte: D, CRC
 * and P; a master sending 0 while it waits makes 14 with one frame.) */
START_TEST(test_late_start_never_cancels) {
    static const unsigned lates[] = {1, 3, 20};
    static const unsigned halves[] = {10, 100};
    static const uint8_t serial[] = {0x00, 0xd9, 0x01, 0x32};
    const uint8_t temp = 0x5f;
    unsigned late = lates[_i % 3], half = halves[_i / 3];
    struct e2e_run r;
    struct bench *b = e2e_bench(&r, "tidep0022-test-encoder", 2, NULL);
    biss_ctrl *ctrl = &link_biss(bench_link(b))->ctrl[0];
    ctrl->reg_proc_frames = late;
    ck_assert_uint_eq(e2e_run_frames(&r, half, 1000, 10), 10);
    fw_check_restart(&r.fc, UINT64_MAX);
    static biss_cd_prog p;
    struct fw_cd cd;
    ck_assert_int_eq(biss_cd_build_read(&p, 0, 0x67, 1), BISS_CD_OK);
    ck_assert_int_eq(run_cd(&r, &p, (uint16_t)(late + 2), &cd), BISS_CD_OK);
    ck_assert_uint_eq(cd.result.byte[0].data, temp);
    ck_assert_int_eq(cd.result.byte[0].start, BISS_CD_S_LATE);
    ck_assert_uint_eq(ctrl->reads, 1);
    ck_assert_uint_eq(ctrl->cancels, 0);
    ck_assert_int_eq(biss_cd_build_read(&p, 0, 0x44, 4), BISS_CD_OK);
    ck_assert_int_eq(run_cd(&r, &p, (uint16_t)(late + 2), &cd), BISS_CD_OK);
    ck_assert_uint_eq(cd.result.good_bytes, 4);
    for (unsigned i = 0; i < 4; i++) {
        ck_assert_uint_eq(cd.result.byte[i].data, serial[i]);
        ck_assert_int_eq(cd.result.byte[i].start, BISS_CD_S_LATE);
    }
    ck_assert_uint_eq(ctrl->reads, 5);
    ck_assert_uint_eq(ctrl->cancels, 0);
    assert_positions_clean(&r);
    e2e_free(&r);
}
END_TEST

/* Runs p and flips the slave's CDS once, in the frame that answers the
 * data bit `bit` of register byte `byte` (the slave's frame bit 0, before
 * it goes out). */
static void run_flipped(struct e2e_run *r, const biss_cd_prog *p, unsigned byte, unsigned bit,
                        struct fw_cd *cd) {
    struct bench *b = r->b;
    biss_slave *sl = link_biss(bench_link(b));
    fw_cd_issue(cd, b, p, 10);
    unsigned seen = 0; /* data bits of the byte seen (frames answering them) */
    int flipped = 0, in_bit = 0;
    int64_t end = pru_time_ps(bench_core(b)) + 100 * SIM_PS_PER_MS;
    while (!fw_cd_poll(cd) && pru_time_ps(bench_core(b)) < end) {
        int here = sl->st.in_frame && sl->bit == 0 && sl->ctrl[0].state == CTRL_DATA &&
                   sl->ctrl[0].count == bit;
        if (here && !in_bit && !flipped && seen++ == byte) {
            sl->bits[0] ^= 1;
            flipped = 1;
        }
        in_bit = here;
        ck_assert_int_eq(bench_run_until(b, pru_time_ps(bench_core(b)) + 200 * SIM_PS_PER_NS),
                         PRU_STOP_LIMIT);
    }
    ck_assert(flipped);
    ck_assert(cd->done);
}

/* A CDS bit corrupted on its way while the second data byte of a read is
 * answered: the firmware's CRC4 check fails it, one byte counts as right,
 * the control frame ends at the third byte's S, and positions are
 * untouched (the CDS is outside their CRC). */
START_TEST(test_corrupted_cds_fails_crc) {
    struct e2e_run r;
    e2e_bench(&r, "tidep0022-test-encoder", 2, NULL);
    ck_assert_uint_eq(e2e_run_frames(&r, 10, 1000, 10), 10);
    fw_check_restart(&r.fc, UINT64_MAX);
    static biss_cd_prog p;
    struct fw_cd cd;
    ck_assert_int_eq(biss_cd_build_read(&p, 0, 0x45, 3), BISS_CD_OK);
    run_flipped(&r, &p, 1, 3, &cd);
    ck_assert_int_eq(cd.err, BISS_CD_E_CRC);
    ck_assert_uint_eq(cd.status, BISS_CDST_ERR_CRC); /* the firmware's own check */
    ck_assert_uint_eq(cd.result.good_bytes, 1);
    ck_assert(cd.result.byte[0].crc_ok);
    ck_assert(!cd.result.byte[1].crc_ok);
    ck_assert_int_eq(cd.result.byte[2].start, BISS_CD_S_NOT_REACHED);
    assert_positions_clean(&r);
    /* the slave is ready for the next control frame at once */
    static const uint8_t serial[] = {0xd9, 0x01, 0x32};
    read_expect(&r, 0x45, serial, 3);
    e2e_free(&r);
}
END_TEST

/* The echo of a write's data bit corrupted on its way back: the firmware
 * reports the echo error, counts no byte, and ends the control frame
 * before the second byte. The slave got the first byte right and stored
 * it (the master cannot know that: a read-back tells). */
START_TEST(test_corrupted_echo_fails_write) {
    static const uint8_t data[] = {0x3c, 0xc3};
    struct e2e_run r;
    struct bench *b = e2e_bench(&r, "tidep0022-test-encoder", 2, NULL);
    ck_assert_uint_eq(e2e_run_frames(&r, 10, 1000, 10), 10);
    fw_check_restart(&r.fc, UINT64_MAX);
    static biss_cd_prog p;
    struct fw_cd cd;
    ck_assert_int_eq(biss_cd_build_write(&p, 0, 0x10, data, 2), BISS_CD_OK);
    run_flipped(&r, &p, 0, 5, &cd);
    ck_assert_int_eq(cd.err, BISS_CD_E_ECHO);
    ck_assert_uint_eq(cd.status, BISS_CDST_ERR_ECHO);
    ck_assert_uint_eq(cd.result.good_bytes, 0);
    ck_assert_int_eq(cd.result.byte[1].start, BISS_CD_S_NOT_REACHED);
    regfile *regs = &link_biss(bench_link(b))->cfg.s[0].regs;
    ck_assert_uint_eq(regfile_read(regs, 0x10), 0x3c);
    ck_assert_uint_ne(regfile_read(regs, 0x11), 0xc3);
    assert_positions_clean(&r);
    e2e_free(&r);
}
END_TEST

int main(void) {
    Suite *s = suite_create("e2e_cd");
    TCase *tc = tcase_create("cd");
    tcase_set_timeout(tc, 600);
    tcase_add_loop_test(tc, test_table11_every_rate, 0, 4);
    tcase_add_test(tc, test_sequential_64_across_bank_switch);
    tcase_add_test(tc, test_write_then_read_back);
    tcase_add_test(tc, test_commands_with_and_without_ida);
    tcase_add_test(tc, test_ad38_registers_by_id);
    tcase_add_test(tc, test_late_start_bit);
    tcase_add_loop_test(tc, test_late_start_never_cancels, 0, 6);
    tcase_add_test(tc, test_corrupted_cds_fails_crc);
    tcase_add_test(tc, test_corrupted_echo_fails_write);
    suite_add_tcase(s, tc);
    return check_run(s);
}
