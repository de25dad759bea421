/*
 * End-to-end: the MA rate rule, the firmware's and the host's, held
 * together at every half period. The firmware decides in config.p's factor
 * loop (H in BISS_MIN_HALF..BISS_MAX_HALF, H = a * b with 2 <= a, b <= 32:
 * an exact 8x shift clock, docs/pru-facts.md §4.4, §4.5) and answers in
 * ST_CFG_ERROR; the host's one copy is proto/biss_rate.c. For every H from
 * 10 to 1024, and the corners around that range, the real firmware image
 * is configured at H on the emulated PRU and its verdict compared with
 * biss_proto_half_check, with biss_rate_half where 100 MHz / H is a whole
 * number of Hz, and with biss_config_decode reading the block back (as an
 * attaching host does). An H the firmware takes must then be the H it
 * clocks: its first published frame says so.
 */
#include "e2e_util.h"

#include "biss/biss_shm.h"

#include "check_run.h"

#include <check.h>
#include <stdio.h>

/* One configuration at H: the firmware's verdict (BISS_CFGERR_*), and, when
 * it takes H, the half period of its first frame published after it. */
static uint32_t fw_verdict(struct e2e_run *r, unsigned half, unsigned *clocked) {
    uint64_t pubs = r->fc.publications;
    e2e_configure(r, half);
    uint32_t err = bench_fw_status(r->b).cfg_error;
    *clocked = 0;
    if (err == BISS_CFGERR_NONE) {
        /* the training frame comes first: its publication is at H too */
        e2e_run_publications(r, r->fc.publications - pubs + 1, 10 * SIM_PS_PER_MS);
        *clocked = r->fc.half;
    }
    return err;
}

/* What the host says of H, against the firmware's verdict. */
static void agree(unsigned half, uint32_t fw_err, unsigned clocked) {
    int host = biss_proto_half_check(half);
    bool fw_takes = fw_err == BISS_CFGERR_NONE;
    ck_assert_msg(fw_takes == (host == BISS_OK),
                  "H = %u: the firmware %s it (ST_CFG_ERROR %u), the host's rule %s it (%d)", half,
                  fw_takes ? "takes" : "refuses", fw_err, host == BISS_OK ? "takes" : "refuses",
                  host);
    if (!fw_takes) {
        ck_assert_msg(fw_err == BISS_CFGERR_HALF, "H = %u: ST_CFG_ERROR %u, not HALF", half,
                      fw_err);
        ck_assert_ptr_nonnull(biss_proto_half_problem(half));
    } else {
        ck_assert_msg(clocked == half, "H = %u: the firmware clocked H = %u", half, clocked);
        ck_assert_ptr_null(biss_proto_half_problem(half));
    }
    /* the public rule, where a whole number of Hz names the rate */
    if (half && BISS_HALF_CLOCK_HZ % half == 0) {
        unsigned h = 0;
        int rc = biss_rate_half(BISS_HALF_CLOCK_HZ / half, &h);
        ck_assert_msg((rc == BISS_OK) == fw_takes, "H = %u: biss_rate_half %d", half, rc);
        ck_assert_uint_eq(rc == BISS_OK ? h : half, half);
    }
    /* a block at H read back: refused wherever the firmware refuses it */
    struct biss_config c;
    biss_config_default(&c);
    c.nslaves = 1;
    c.slave[0] = (struct biss_slave_config){
        .data_bits = 14, .crc_bits = 6, .crc_poly = 0x43, .has_ew = true, .ew_shift = 0};
    struct biss_shm_config blk;
    biss_config_encode_half(&c, half, &blk);
    struct biss_config back;
    const char *field = NULL;
    int rc = biss_config_decode(&blk, &back, &field);
    if (!fw_takes) {
        ck_assert_msg(rc != BISS_OK, "H = %u: the block read back is taken", half);
    } else if (BISS_HALF_CLOCK_HZ % half == 0) {
        ck_assert_msg(rc == BISS_OK, "H = %u: the block read back is refused (%s)", half, field);
        ck_assert_uint_eq(back.freq_hz, BISS_HALF_CLOCK_HZ / half);
    }
}

/* H from 10 to 1024 in eight runs of 128 (each a fresh firmware, the
 * configurations one after the other, as a host changes the rate). */
#define H_PER_RUN 128u
START_TEST(test_every_half_period) {
    unsigned first = BISS_MIN_HALF + (unsigned)_i * H_PER_RUN;
    unsigned last = first + H_PER_RUN - 1 < BISS_MAX_HALF ? first + H_PER_RUN - 1 : BISS_MAX_HALF;
    struct e2e_run r;
    e2e_bench(&r, "tidep0022-test-encoder", 2, NULL);
    r.fc.cfg.trigger = BISS_TRIGGER_FREERUN;
    r.fc.cfg.proc_limit = 1000;
    unsigned taken = 0;
    for (unsigned h = first; h <= last; h++) {
        unsigned clocked;
        uint32_t err = fw_verdict(&r, h, &clocked);
        agree(h, err, clocked);
        taken += err == BISS_CFGERR_NONE;
    }
    ck_assert_uint_gt(taken, 0);
    ck_assert_uint_eq(r.fc.mismatches, 0); /* and every frame it clocked was right */
    e2e_free(&r);
}
END_TEST

/* Outside the range: 1..9 (above 10 MHz), 1025 up to the largest the
 * block holds (0 is no rate: the block of a host that never configured);
 * and inside it 11 and 13 (primes), 1000 (8 x 125) and 1023 (3 x 11 x 31):
 * no exact shift clock. Each after a good one, so each is a change. */
START_TEST(test_corners) {
    static const unsigned halves[] = {1,    2,    5,    9,    11,   13,   1000,
                                      1023, 1025, 1026, 1088, 2048, 4096, 65535};
    struct e2e_run r;
    e2e_bench(&r, "tidep0022-test-encoder", 2, NULL);
    r.fc.cfg.trigger = BISS_TRIGGER_FREERUN;
    r.fc.cfg.proc_limit = 1000;
    for (size_t i = 0; i < sizeof halves / sizeof halves[0]; i++) {
        unsigned clocked;
        ck_assert_uint_eq(fw_verdict(&r, 10, &clocked), BISS_CFGERR_NONE);
        uint32_t err = fw_verdict(&r, halves[i], &clocked);
        agree(halves[i], err, clocked);
        ck_assert_msg(err == BISS_CFGERR_HALF, "H = %u taken", halves[i]);
    }
    e2e_free(&r);
}
END_TEST

int main(void) {
    Suite *s = suite_create("e2e_rate");
    TCase *tc = tcase_create("rate");
    tcase_add_loop_test(tc, test_every_half_period, 0,
                        (BISS_MAX_HALF - BISS_MIN_HALF + H_PER_RUN) / H_PER_RUN);
    tcase_add_test(tc, test_corners);
    suite_add_tcase(s, tc);
    return check_run(s);
}
