/* Check suite for the SSI slave: binary and Gray output, monoflop. */
#include "biss_proto.h"
#include "slave_rig.h"
#include "ssi_slave.h"

#include "check_run.h"

#include <check.h>
#include <stdlib.h>

#define NS SIM_PS_PER_NS
#define US SIM_PS_PER_US

/* The model's encoder against the host's decoder (proto). */
START_TEST(gray_round_trip) {
    ck_assert_uint_eq(ssi_to_gray(0x1a5), 0x1a5 ^ 0xd2);
    for (uint64_t v = 0; v < 5000; v += 7) {
        ck_assert_uint_eq(biss_proto_from_gray(ssi_to_gray(v)), v);
    }
    ck_assert_uint_eq(biss_proto_from_gray(ssi_to_gray(UINT64_MAX - 5)), UINT64_MAX - 5);
}
END_TEST

static void run(int gray, char *out) {
    rig r;
    rig_init(&r, 500 * NS);
    ssi_cfg c;
    ssi_cfg_default(&c);
    c.bits = 13;
    c.gray = gray;
    c.pos0 = 0x1a5; /* 0 0001 1010 0101 */
    ssi_slave s;
    char err[200];
    ck_assert_int_eq(ssi_cfg_check(&c, err, sizeof err), 0);
    ssi_slave_init(&s, &c, &r.q, waveform_sink(&r.sl));
    r.slave = ssi_slave_sink(&s);
    int bits[16];
    sim_ps last = rig_frame(&r, 14, 0, 0, 30 * US, bits);
    bits_str(bits, 0, 14, out);
    /* monoflop: SL back high 20 us after the last MA edge */
    ck_assert_int_eq(waveform_level_at(&r.sl, last + 20 * US + 20 * NS - 1), 0);
    ck_assert_int_eq(waveform_level_at(&r.sl, last + 20 * US + 20 * NS), 1);
    const ssi_frame_record *rec = ssi_slave_record(&s, 0);
    ck_assert_ptr_nonnull(rec);
    ck_assert_uint_eq(rec->position, 0x1a5);
    ck_assert(rec->complete);
    rig_free(&r);
}

START_TEST(binary_frame) {
    char s[32];
    run(0, s);
    ck_assert_str_eq(s, "0000110100101"
                        "0");
}
END_TEST

START_TEST(gray_frame) {
    char s[32];
    run(1, s);
    /* Gray(0x1A5) = 0x1A5 ^ 0x0D2 = 0x177 = 0 0001 0111 0111 */
    ck_assert_str_eq(s, "0000101110111"
                        "0");
}
END_TEST

int main(void) {
    Suite *s = suite_create("ssi_slave");
    TCase *tc = tcase_create("ssi");
    tcase_add_test(tc, gray_round_trip);
    tcase_add_test(tc, binary_frame);
    tcase_add_test(tc, gray_frame);
    suite_add_tcase(s, tc);
    return check_run(s);
}
