/* libbiss control communication: the codec's CDM program as bytes in data
 * RAM, the firmware's verdicts, and register access end to end on the
 * emulator against the slave model's register file. */
#include "fake_backend.h"
#include "libbiss-emu.h"

#include "bench.h"
#include "biss/biss_shm.h"

#include "check_run.h"

#include <check.h>
#include <stdlib.h>
#include <string.h>

static struct biss_config one_slave(enum biss_trigger t) {
    struct biss_config c;
    biss_config_default(&c);
    c.freq_hz = 10000000;
    c.nslaves = 1;
    c.trigger = t;
    c.slave[0] = (struct biss_slave_config){
        .data_bits = 14, .crc_bits = 6, .crc_poly = 0x43, .has_ew = true};
    return c;
}

static biss_t *configured_fake(struct fake **f) {
    biss_t *h = fake_handle(f);
    (*f)->acks = true;
    fake_set_dram32(*f, BISS_ST_MAGIC, BISS_MAGIC);
    struct biss_config c = one_slave(BISS_TRIGGER_FREERUN);
    ck_assert_int_eq(biss_configure(h, &c), BISS_OK);
    return h;
}

/* A register read of ID 2, address 0x45: the codec's program, packed, is
 * what lands in BISS_CD_PROG; then its length, the wait limit, CD_CMD. */
START_TEST(test_register_read_program) {
    struct fake *f;
    biss_t *h = configured_fake(&f);
    uint8_t b;
    /* nobody runs it: the program stays in data RAM to look at */
    ck_assert_int_eq(biss_reg_read(h, 2, 0x45, &b, 1), BISS_E_TIMEOUT);
    static biss_cd_prog p;
    ck_assert_int_eq(biss_cd_build_read(&p, 2, 0x45, 1), BISS_CD_OK);
    uint8_t want[BISS_CD_PROG_BYTES];
    biss_cd_pack(&p, want);
    unsigned used = (p.len + 15u) / 16u * 4u; /* whole words with steps */
    ck_assert_mem_eq(f->mem + BISS_CD_PROG, want, used);
    ck_assert_uint_eq(fake_dram32(f, BISS_CD_STEPS) & 0xffff, p.len);
    ck_assert_uint_gt(fake_dram32(f, BISS_CD_STEPS) >> 16, 0); /* wait limit */
    ck_assert_uint_eq(fake_dram32(f, BISS_CD_CMD), 1);
    /* still running (no echo): a second program must wait */
    ck_assert_int_eq(biss_reg_read(h, 2, 0x45, &b, 1), BISS_E_CD_BUSY);
    biss_close(h);
}
END_TEST

START_TEST(test_firmware_verdicts) {
    struct fake *f;
    biss_t *h = configured_fake(&f);
    f->cd_answers = true;
    uint8_t ops[3] = {BISS_CD_OP_1, BISS_CD_OP_0, BISS_CD_OP_CRC | BISS_CD_CL_ECHO}, resp[1];
    f->cd_status = BISS_CDST_DONE;
    f->mem[BISS_CD_RESP] = 0x5;
    ck_assert_int_eq(biss_cd_run(h, ops, 3, 10, 5, resp), BISS_OK);
    ck_assert_uint_eq(resp[0], 0x5);
    f->cd_status = BISS_CDST_ERR_WAIT;
    ck_assert_int_eq(biss_cd_run(h, ops, 3, 10, 5, resp), BISS_E_CD_WAIT);
    f->cd_status = BISS_CDST_ERR_FRAME;
    ck_assert_int_eq(biss_cd_run(h, ops, 3, 10, 5, resp), BISS_E_CD_FRAME);
    f->cd_status = BISS_CDST_ERR_STEPS;
    ck_assert_int_eq(biss_cd_run(h, ops, 3, 10, 5, resp), BISS_E_CD_STEPS);
    f->cd_status = BISS_CDST_ERR_CRC;
    ck_assert_int_eq(biss_cd_run(h, ops, 3, 10, 5, resp), BISS_E_CD_CRC);
    f->cd_status = BISS_CDST_ERR_ECHO;
    ck_assert_int_eq(biss_cd_run(h, ops, 3, 10, 5, resp), BISS_E_CD_ECHO);
    f->cd_status = BISS_CDST_ERR_IDA;
    ck_assert_int_eq(biss_cd_run(h, ops, 3, 10, 5, resp), BISS_E_CD_WITHHELD);
    ck_assert_uint_eq(fake_dram32(f, BISS_CD_CMD), 7);
    /* refused before the firmware sees them */
    ck_assert_int_eq(biss_cd_run(h, ops, 0, 10, 5, resp), BISS_E_CD_STEPS);
    ck_assert_int_eq(biss_cd_run(h, ops, BISS_CD_MAX_STEPS + 1, 10, 5, resp), BISS_E_CD_STEPS);
    ck_assert_int_eq(biss_cd_run(h, ops, 3, 0x10000, 5, resp), BISS_E_INVAL);
    uint8_t waits[3] = {BISS_CD_OP_WAIT, BISS_CD_OP_WAIT, BISS_CD_OP_0};
    ck_assert_int_eq(biss_cd_run(h, waits, 3, 10, 5, resp), BISS_E_INVAL);
    uint8_t wait_crc[2] = {BISS_CD_OP_WAIT, BISS_CD_OP_CRC};
    ck_assert_int_eq(biss_cd_run(h, wait_crc, 2, 10, 5, resp), BISS_E_INVAL);
    uint8_t wait_class[1] = {BISS_CD_OP_WAIT | BISS_CD_CL_DATA};
    ck_assert_int_eq(biss_cd_run(h, wait_class, 1, 10, 5, resp), BISS_E_INVAL);
    uint8_t bad[1] = {16};
    ck_assert_int_eq(biss_cd_run(h, bad, 1, 10, 5, resp), BISS_E_INVAL);
    uint8_t b[2];
    ck_assert_int_eq(biss_reg_read(h, 8, 0x10, b, 1), BISS_E_INVAL);
    ck_assert_int_eq(biss_reg_read(h, 0, 0x80, b, 1), BISS_E_INVAL);
    ck_assert_int_eq(biss_reg_read(h, 0, 0x10, b, 0), BISS_E_INVAL);
    ck_assert_int_eq(biss_reg_read(h, 0, 0x00, b, BISS_REG_MAX_SEQ + 1), BISS_E_INVAL);
    ck_assert_uint_eq(fake_dram32(f, BISS_CD_CMD), 7);
    /* a done program whose answers are all zero: no R/W echo */
    f->cd_status = BISS_CDST_DONE;
    memset(f->mem + BISS_CD_RESP, 0, BISS_CD_MAX_STEPS / 8);
    ck_assert_int_eq(biss_reg_read(h, 0, 0x10, b, 1), BISS_E_CD_NO_ECHO);
    biss_close(h);
}
END_TEST

START_TEST(test_needs_a_configuration) {
    struct fake *f;
    biss_t *h = fake_handle(&f);
    uint8_t ops[1] = {BISS_CD_OP_0}, resp[1];
    ck_assert_int_eq(biss_cd_run(h, ops, 1, 10, 5, resp), BISS_E_NOT_CONFIGURED);
    biss_close(h);
}
END_TEST

/* ---- end to end on the emulator ----------------------------------------- */
static biss_t *emu(enum biss_trigger t) {
    struct biss_open_params p;
    biss_open_params_default(&p);
    p.profile = "tidep0022-test-encoder";
    p.cable_m = 2.0;
    biss_t *h;
    ck_assert_int_eq(biss_emu_open(&p, &h), BISS_OK);
    struct biss_config c;
    biss_config_default(&c);
    c.freq_hz = 10000000;
    c.trigger = t;
    ck_assert_int_eq(biss_config_from_emu(h, &c), BISS_OK);
    ck_assert_int_eq(biss_configure(h, &c), BISS_OK);
    return h;
}

static regfile *slave_regs(biss_t *h) {
    return link_biss(bench_link(biss_emu_bench(h)))->ctrl[0].regs;
}

START_TEST(test_emu_register_read) {
    biss_t *h = emu(BISS_TRIGGER_FREERUN);
    uint8_t b[8];
    int rc = biss_reg_read(h, 0, 0x78, b, 8);
    ck_assert_msg(rc == BISS_OK, "%s", biss_strerror(rc));
    for (unsigned i = 0; i < 8; i++) {
        ck_assert_uint_eq(b[i], regfile_read(slave_regs(h), 0x78 + i));
    }
    ck_assert_uint_eq(b[0], 0x46); /* the TIDEP0022 encoder's 0x78 */
    /* position frames kept coming meanwhile, all right */
    struct biss_stats st;
    ck_assert_int_eq(biss_get_stats(h, &st), BISS_OK);
    ck_assert_uint_eq(st.crc_errors, 0);
    ck_assert_uint_gt(st.frames, 14 + 8 * 15);
    biss_close(h);
}
END_TEST

START_TEST(test_emu_register_write) {
    biss_t *h = emu(BISS_TRIGGER_FREERUN);
    uint8_t w[2] = {0x5a, 0xc3}, r[2] = {0};
    int rc = biss_reg_write(h, 0, 0x60, w, 2);
    ck_assert_msg(rc == BISS_OK, "%s", biss_strerror(rc));
    ck_assert_uint_eq(regfile_read(slave_regs(h), 0x60), 0x5a);
    ck_assert_uint_eq(regfile_read(slave_regs(h), 0x61), 0xc3);
    ck_assert_int_eq(biss_reg_read(h, 0, 0x60, r, 2), BISS_OK);
    ck_assert_mem_eq(r, w, 2);
    /* back to back, as fast as the slave takes them */
    for (uint8_t v = 0; v < 4; v++) {
        ck_assert_int_eq(biss_reg_write(h, 0, 0x62, &v, 1), BISS_OK);
        ck_assert_int_eq(biss_reg_read(h, 0, 0x62, r, 1), BISS_OK);
        ck_assert_uint_eq(r[0], v);
    }
    biss_close(h);
}
END_TEST

/* No slave with ID 5: nobody echoes R and W (and the firmware's WAIT for
 * the slave's S gives up). */
START_TEST(test_emu_wrong_id) {
    biss_t *h = emu(BISS_TRIGGER_FREERUN);
    uint8_t b;
    ck_assert_int_eq(biss_reg_read(h, 5, 0x78, &b, 1), BISS_E_CD_NO_ECHO);
    /* and the next access works */
    ck_assert_int_eq(biss_reg_read(h, 0, 0x78, &b, 1), BISS_OK);
    ck_assert_uint_eq(b, 0x46);
    biss_close(h);
}
END_TEST

/* Host-trigger mode: the call triggers the frames the program needs. */
START_TEST(test_emu_register_read_host_trigger) {
    biss_t *h = emu(BISS_TRIGGER_HOST);
    uint8_t b;
    int rc = biss_reg_read(h, 0, 0x79, &b, 1);
    ck_assert_msg(rc == BISS_OK, "%s", biss_strerror(rc));
    ck_assert_uint_eq(b, regfile_read(slave_regs(h), 0x79));
    biss_close(h);
}
END_TEST

/* A BiSS command to ID 0: the slave acknowledges in its IDA slot. */
START_TEST(test_emu_command) {
    biss_t *h = emu(BISS_TRIGGER_FREERUN);
    uint8_t ida = 0xff;
    int rc = biss_command(h, 0x01, 0, false, &ida);
    ck_assert_msg(rc == BISS_OK, "%s", biss_strerror(rc));
    ck_assert_uint_eq(ida, 0x01);
    const biss_ctrl *ctrl = &link_biss(bench_link(biss_emu_bench(h)))->ctrl[0];
    ck_assert_int_eq(ctrl->last_cmd, 0);
    ck_assert_int_eq(biss_command(h, 0x01, 4, false, &ida), BISS_E_INVAL);
    /* IDs 0 and 1, only 0 present: executed and reported after the fact,
     * or withheld by the firmware's IDA test */
    ck_assert_int_eq(biss_command(h, 0x03, 1, false, &ida), BISS_E_CD_IDA);
    ck_assert_uint_eq(ida, 0x01);
    ck_assert_int_eq(ctrl->last_cmd, 1);
    ck_assert_int_eq(biss_command(h, 0x03, 2, true, &ida), BISS_E_CD_WITHHELD);
    ck_assert_int_eq(ctrl->last_cmd, 1);
    ck_assert_int_eq(biss_command(h, 0x01, 2, true, &ida), BISS_OK);
    ck_assert_int_eq(ctrl->last_cmd, 2);
    /* (the withheld one's execute bit went out in the frame that reported
     * its end; the slave has taken it since) */
    ck_assert_uint_eq(ctrl->commands_dropped, 1);
    biss_close(h);
}
END_TEST

/* The non-blocking forms: start, poll while simulated time passes, then
 * the same bytes and verdicts as the blocking calls; one program at a time. */
START_TEST(test_emu_nonblocking) {
    biss_t *h = emu(BISS_TRIGGER_FREERUN);
    biss_cd_job *j = NULL;
    ck_assert_int_eq(biss_reg_read_start(h, 0, 0x78, 8, &j), BISS_OK);
    ck_assert_ptr_nonnull(j);
    biss_cd_job *other = (biss_cd_job *)1;
    ck_assert_int_eq(biss_command_start(h, 0x01, 0, false, &other), BISS_E_CD_BUSY);
    ck_assert_ptr_null(other);
    uint8_t b[8];
    ck_assert_int_eq(biss_cd_job_bytes(j, b), BISS_E_CD_BUSY);
    unsigned polls = 0;
    int rc;
    while ((rc = biss_cd_poll(h, j)) == BISS_E_CD_BUSY) {
        polls++;
        ck_assert_uint_lt(polls, 1000);
        ck_assert_int_eq(biss_run_ms(h, 1), BISS_OK);
    }
    ck_assert_msg(rc == BISS_OK, "%s", biss_strerror(rc));
    ck_assert_uint_gt(polls, 0); /* 8 bytes take a few ms at 10 MHz */
    ck_assert_int_eq(biss_cd_job_bytes(j, b), BISS_OK);
    for (unsigned i = 0; i < 8; i++) {
        ck_assert_uint_eq(b[i], regfile_read(slave_regs(h), 0x78 + i));
    }
    /* the ID lock of the one slave (ID 0): IDL0, in the answer to S */
    struct biss_cd_slots sl;
    ck_assert_int_eq(biss_cd_job_slots(j, &sl), BISS_OK);
    ck_assert_uint_eq(sl.idl, 0x01);
    ck_assert_uint_eq(sl.header_cds, 0x001);
    ck_assert_int_eq(biss_cd_poll(h, j), BISS_OK); /* the verdict stays */
    biss_cd_job_free(j);

    static const uint8_t w[2] = {0x5a, 0xa5};
    ck_assert_int_eq(biss_reg_write_start(h, 0, 0x60, w, 2, &j), BISS_OK);
    while ((rc = biss_cd_poll(h, j)) == BISS_E_CD_BUSY) {
        ck_assert_int_eq(biss_run_ms(h, 1), BISS_OK);
    }
    ck_assert_int_eq(rc, BISS_OK);
    biss_cd_job_free(j);
    ck_assert_uint_eq(regfile_read(slave_regs(h), 0x60), 0x5a);

    ck_assert_int_eq(biss_command_start(h, 0x01, 0, true, &j), BISS_OK);
    while ((rc = biss_cd_poll(h, j)) == BISS_E_CD_BUSY) {
        ck_assert_int_eq(biss_run_ms(h, 1), BISS_OK);
    }
    uint8_t ida = 0;
    ck_assert_int_eq(rc, BISS_OK);
    ck_assert_int_eq(biss_cd_job_ida(j, &ida), BISS_OK);
    ck_assert_uint_eq(ida, 0x01);
    /* IDA0 in the answer to the last header CRC step; the ID lock came in
     * the first header slot, as in every control frame */
    ck_assert_int_eq(biss_cd_job_slots(j, &sl), BISS_OK);
    ck_assert_uint_eq(sl.ida, 0x01);
    ck_assert_uint_eq(sl.ida_cds, 0x001);
    biss_cd_job_free(j);

    /* an error comes back from poll as the blocking call returns it */
    ck_assert_int_eq(biss_reg_read_start(h, 5, 0x78, 1, &j), BISS_OK);
    while ((rc = biss_cd_poll(h, j)) == BISS_E_CD_BUSY) {
        ck_assert_int_eq(biss_run_ms(h, 1), BISS_OK);
    }
    ck_assert_int_eq(rc, BISS_E_CD_NO_ECHO);
    ck_assert_int_eq(biss_cd_job_bytes(j, b), BISS_E_CD_NO_ECHO);
    biss_cd_job_free(j);
    ck_assert_int_eq(biss_cd_job_slots(NULL, &sl), BISS_E_INVAL);
    ck_assert_int_eq(biss_reg_read_start(h, 8, 0x78, 1, &j), BISS_E_INVAL);
    ck_assert_int_eq(biss_reg_read_start(h, 0, 0x78, 0, &j), BISS_E_INVAL);
    biss_close(h);
}
END_TEST

/* Runs until n more frames are published. */
static void run_frames(biss_t *h, uint32_t n) {
    struct biss_stats s0, s;
    ck_assert_int_eq(biss_get_stats(h, &s0), BISS_OK);
    do {
        ck_assert_int_eq(biss_run_us(h, 5), BISS_OK);
        ck_assert_int_eq(biss_get_stats(h, &s), BISS_OK);
    } while (s.frames - s0.frames < n);
}

/* A new configuration while a register read runs, at every point of it:
 * the new rate's training frame (two clocks) fails the program
 * (BISS_E_CD_FRAME) from its S on, and leaves the slave wherever it was in
 * its control frame. The next read works all the same: its S waits until
 * the slave is armed again (biss_cd_lead_in), whether the firmware's 14
 * zeros cancelled its frame or it ended the frame on one of them. */
START_TEST(test_emu_reconfigure_mid_read) {
    biss_t *h = emu(BISS_TRIGGER_FREERUN);
    struct biss_config c;
    ck_assert_int_eq(biss_get_config(h, &c), BISS_OK);
    uint8_t want[8];
    for (unsigned i = 0; i < 8; i++) {
        want[i] = regfile_read(slave_regs(h), 0x78 + i);
    }
    unsigned failed = 0;
    /* 14 zeros, then S, the header, R W and 8 bytes of 15 steps */
    for (uint32_t k = 1; k <= 14 + 19 + 8 * 15; k += 4) {
        biss_cd_job *j;
        ck_assert_int_eq(biss_reg_read_start(h, 0, 0x78, 8, &j), BISS_OK);
        run_frames(h, k);
        c.freq_hz = c.freq_hz == 10000000 ? 1000000 : 10000000;
        ck_assert_int_eq(biss_configure(h, &c), BISS_OK);
        int rc;
        while ((rc = biss_cd_poll(h, j)) == BISS_E_CD_BUSY) {
            ck_assert_int_eq(biss_run_us(h, 50), BISS_OK);
        }
        ck_assert_msg(rc == BISS_OK || rc == BISS_E_CD_FRAME, "%u frames in: %s", k,
                      biss_strerror(rc));
        failed += rc == BISS_E_CD_FRAME;
        biss_cd_job_free(j);
        uint8_t b[8];
        rc = biss_reg_read(h, 0, 0x78, b, 8);
        ck_assert_msg(rc == BISS_OK, "reconfigured %u frames into a read: the next read: %s", k,
                      biss_strerror(rc));
        ck_assert_mem_eq(b, want, 8);
        /* and the next after it, started as usual (the last one ended well) */
        ck_assert_int_eq(biss_reg_read(h, 0, 0x79, b, 1), BISS_OK);
        ck_assert_uint_eq(b[0], want[1]);
    }
    ck_assert_uint_gt(failed, 20);
    biss_close(h);
}
END_TEST

int main(void) {
    Suite *s = suite_create("host_cd");
    TCase *tc = tcase_create("cd");
    tcase_set_timeout(tc, 120);
    tcase_add_test(tc, test_register_read_program);
    tcase_add_test(tc, test_firmware_verdicts);
    tcase_add_test(tc, test_needs_a_configuration);
    tcase_add_test(tc, test_emu_register_read);
    tcase_add_test(tc, test_emu_register_write);
    tcase_add_test(tc, test_emu_wrong_id);
    tcase_add_test(tc, test_emu_register_read_host_trigger);
    tcase_add_test(tc, test_emu_command);
    tcase_add_test(tc, test_emu_nonblocking);
    tcase_add_test(tc, test_emu_reconfigure_mid_read);
    suite_add_tcase(s, tc);
    return check_run(s);
}
