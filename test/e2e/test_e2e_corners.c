/*
 * End-to-end: the corners of the envelope (issue 23, "Done when"). At every
 * rate/length pair of TIDEP0022's Table 5 (10 MHz up to 10 m, 5 MHz up to
 * 25 m, 2 MHz up to 60 m, 1 MHz up to 100 m) and at 2 and 10 m, under each
 * trigger (free-run, host, IEP), a register read of one byte, a write of 4
 * bytes and a sequential read of 8 succeed through the firmware image, and
 * the position frames around them stay right: none with a CRC error, a
 * wrong word, or refused for an ACK away from the average.
 *
 * The encoder is TIDEP0022's test encoder: 0x44 reads 0x00 and 0x78..0x7F
 * its identification (the design guide's Table 11); 0x10..0x13 take the
 * write, and its register file shows what was stored.
 */
#include "e2e_util.h"

#include "biss/biss_shm.h"
#include "fw_cd.h"

#include "check_run.h"

#include <check.h>
#include <stdio.h>
#include <stdlib.h>

static const struct {
    unsigned half;                                       /* H: 10 MHz = 10 cycles */
    double cable_m;                                      /* the cable */
} corners[] = {{10, 10}, {20, 25}, {50, 60}, {100, 100}, /* Table 5 */
               {10, 2},  {20, 2},  {50, 2},  {100, 2},   {20, 10}, {50, 10}, {100, 10}};
#define N_CORNERS (sizeof corners / sizeof corners[0])

static const struct {
    enum biss_trigger mode;
    const char *name;
} triggers[] = {
    {BISS_TRIGGER_FREERUN, "free"}, {BISS_TRIGGER_HOST, "host"}, {BISS_TRIGGER_IEP, "iep"}};
#define N_TRIGGERS (sizeof triggers / sizeof triggers[0])

struct corner_run {
    struct e2e_run r;
    enum biss_trigger trigger;
    char name[64];
};

/* Time passes in steps of 20 us; a host asks for the next frame whenever
 * the firmware has taken the last request. */
static void step(struct corner_run *c) {
    if (c->trigger == BISS_TRIGGER_HOST) {
        struct biss_proto_io io = bench_fw_io(c->r.b);
        uint32_t pending = 1;
        if (biss_proto_trigger_get(&io, &pending) == 0 && !pending) {
            ck_assert_int_eq(biss_proto_trigger(&io), 0);
        }
    }
    ck_assert_int_eq(bench_run_until(c->r.b, pru_time_ps(bench_core(c->r.b)) + 20 * SIM_PS_PER_US),
                     PRU_STOP_LIMIT);
}

/* The program to its end; its verdict. */
static biss_cd_err run_cd(struct corner_run *c, const biss_cd_prog *p, struct fw_cd *cd) {
    fw_cd_issue(cd, c->r.b, p, 10);
    int64_t end = pru_time_ps(bench_core(c->r.b)) + 500 * SIM_PS_PER_MS;
    while (!fw_cd_poll(cd) && pru_time_ps(bench_core(c->r.b)) < end) {
        step(c);
    }
    ck_assert_msg(cd->done, "%s: the control frame did not end", c->name);
    return cd->err;
}

static void read_expect(struct corner_run *c, unsigned addr, const uint8_t *want, unsigned n) {
    static biss_cd_prog p;
    struct fw_cd cd;
    ck_assert_int_eq(biss_cd_build_read(&p, 0, addr, n), BISS_CD_OK);
    biss_cd_err err = run_cd(c, &p, &cd);
    ck_assert_msg(err == BISS_CD_OK, "%s: reading %u bytes at 0x%02x: %s", c->name, n, addr,
                  biss_cd_strerror(err));
    ck_assert_uint_eq(cd.result.good_bytes, n);
    for (unsigned i = 0; i < n; i++) {
        ck_assert_msg(cd.result.byte[i].data == want[i], "%s: register 0x%02x: 0x%02x, not 0x%02x",
                      c->name, addr + i, cd.result.byte[i].data, want[i]);
    }
}

static void write_expect(struct corner_run *c, unsigned addr, const uint8_t *bytes, unsigned n) {
    static biss_cd_prog p;
    struct fw_cd cd;
    ck_assert_int_eq(biss_cd_build_write(&p, 0, addr, bytes, n), BISS_CD_OK);
    biss_cd_err err = run_cd(c, &p, &cd);
    ck_assert_msg(err == BISS_CD_OK, "%s: writing %u bytes at 0x%02x: %s", c->name, n, addr,
                  biss_cd_strerror(err));
    ck_assert_uint_eq(cd.result.good_bytes, n);
    const regfile *regs = &link_biss(bench_link(c->r.b))->cfg.s[0].regs;
    for (unsigned i = 0; i < n; i++) {
        ck_assert_msg(regfile_read(regs, (uint8_t)(addr + i)) == bytes[i],
                      "%s: the slave stored 0x%02x at 0x%02x, not 0x%02x", c->name,
                      regfile_read(regs, (uint8_t)(addr + i)), addr + i, bytes[i]);
    }
}

/* The bench for corner i, configured for its trigger and running: after
 * the training frame, a valid frame. */
static void corner_start(struct corner_run *c, unsigned i) {
    unsigned half = corners[i / N_TRIGGERS].half;
    double cable = corners[i / N_TRIGGERS].cable_m;
    c->trigger = triggers[i % N_TRIGGERS].mode;
    snprintf(c->name, sizeof c->name, "%g MHz on %g m, %s", 100.0 / half, cable,
             triggers[i % N_TRIGGERS].name);
    e2e_bench(&c->r, "tidep0022-test-encoder", cable, NULL);
    /* IEP: a period well above the frame (28 clocks, the 20 us timeout,
     * the line), in whole microseconds */
    uint32_t period = (uint32_t)((56u * half + 4000u + 2000u) * 2u / 200u + 1u) * 200u;
    c->r.fc.cfg.trigger = c->trigger;
    c->r.fc.cfg.iep_period_ns = c->trigger == BISS_TRIGGER_IEP ? period * 5u : 0; /* 5 ns counts */
    c->r.fc.cfg.proc_limit = 1000;
    e2e_configure(&c->r, half);
    int64_t end = pru_time_ps(bench_core(c->r.b)) + 20 * SIM_PS_PER_MS;
    while (c->r.fc.frames == 0 && pru_time_ps(bench_core(c->r.b)) < end) {
        step(c);
    }
    ck_assert_msg(c->r.fc.frames > 0, "%s: no valid frame within 20 ms", c->name);
    fw_check_restart(&c->r.fc, UINT64_MAX);
}

START_TEST(test_register_access_at_the_corners) {
    static const uint8_t serial0[] = {0x00};
    static const uint8_t id[] = {0x46, 0x3a, 0xc0, 0x0c, 0x00, 0x01, 0x57, 0x41};
    static const uint8_t bytes[] = {0x12, 0x34, 0x56, 0x78};
    struct corner_run c;
    corner_start(&c, (unsigned)_i);
    read_expect(&c, 0x44, serial0, 1);
    write_expect(&c, 0x10, bytes, 4);
    read_expect(&c, 0x78, id, 8);
    ck_assert_msg(c.r.fc.crc_errors == 0 && c.r.fc.mismatches == 0 && c.r.fc.ack_jumps == 0,
                  "%s: around the control frames %llu CRC errors, %llu wrong words, %llu frames "
                  "refused for an ACK jump",
                  c.name, (unsigned long long)c.r.fc.crc_errors,
                  (unsigned long long)c.r.fc.mismatches, (unsigned long long)c.r.fc.ack_jumps);
    e2e_free(&c.r);
}
END_TEST

int main(void) {
    Suite *s = suite_create("e2e_corners");
    TCase *tc = tcase_create("corners");
    tcase_set_timeout(tc, 600);
    tcase_add_loop_test(tc, test_register_access_at_the_corners, 0, (int)(N_CORNERS * N_TRIGGERS));
    suite_add_tcase(s, tc);
    return check_run(s);
}
