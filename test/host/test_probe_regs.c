/* test_probe_regs.c - the layout from the registers (host/probe/biss_probe_regs.c)
 * on the values the AD38 notes give, on other manufacturers' device IDs
 * and on values no frame can have, and its comparison with wire layouts. */
#include "biss_probe_priv.h"
#include "check_run.h"

#include <check.h>
#include <string.h>

/* ID 1 of the AD38 ([AD38] register table; the SCD tables' widths):
 * A/D 16, CRC 5, MT 12, ST 24, life counter 6, CRC 6; "HE". */
static struct biss_probe_regs ad38_regs(void) {
    struct biss_probe_regs r = {
        .id = 1, .device = {16, 5, 12, 24, 6, 6}, .manufacturer = {'H', 'E'}};
    return r;
}

/* The AD38 chain as the wire shows it (test_probe_emu finds this). */
static struct biss_probe_layout ad38_wire(void) {
    struct biss_probe_layout l = {.nslaves = 3};
    l.slave[0] = (struct biss_probe_slave){.data_bits = 18, .crc_bits = 5, .has_ew = true};
    l.slave[1] =
        (struct biss_probe_slave){.offset = 23, .data_bits = 38, .crc_bits = 6, .has_ew = true};
    l.slave[2] = (struct biss_probe_slave){
        .offset = 67, .data_bits = 17, .crc_bits = 16, .has_ew = true, .ew_shift = 6, .lc_bits = 6};
    return l;
}

START_TEST(ad38_values) {
    struct biss_probe_regs r = ad38_regs();
    struct biss_probe_reg_layout rl;
    char why[160];
    ck_assert(biss_probe_reg_layout_decode(&r, &rl, why, sizeof why));
    ck_assert_str_eq(why, "");
    ck_assert_uint_eq(rl.id, 1);
    ck_assert_uint_eq(rl.nchannels, 2);
    ck_assert_uint_eq(rl.ch[0].value_bits, 16);
    ck_assert_uint_eq(rl.ch[0].data_bits, 18); /* + nE/nW */
    ck_assert_uint_eq(rl.ch[0].crc_bits, 5);
    ck_assert_uint_eq(rl.mt_bits, 12);
    ck_assert_uint_eq(rl.st_bits, 24);
    ck_assert_uint_eq(rl.ch[1].value_bits, 36);
    ck_assert_uint_eq(rl.ch[1].data_bits, 38);
    ck_assert_uint_eq(rl.ch[1].crc_bits, 6);
    ck_assert_uint_eq(rl.lc_bits, 6);
    /* the single-channel AD38: no A/D word */
    r.device[0] = 0;
    ck_assert(biss_probe_reg_layout_decode(&r, &rl, why, sizeof why));
    ck_assert_uint_eq(rl.nchannels, 1);
    ck_assert_uint_eq(rl.ch[0].data_bits, 38);
}
END_TEST

/* Other manufacturers' 0x78..0x7D are a device ID, a name: no layout. */
START_TEST(other_manufacturers) {
    struct biss_probe_reg_layout rl;
    char why[160];
    struct biss_probe_regs ti = {.device = {0x46, 0x3A, 0xC0, 0x0C, 0x00, 0x01},
                                 .manufacturer = {0x57, 0x41}}; /* [TI] Table 11 */
    ck_assert(!biss_probe_reg_layout_decode(&ti, &rl, why, sizeof why));
    struct biss_probe_regs pos = {.device = {0x01, 0x01, 0x68, 0x11, 0x00, 0x01},
                                  .manufacturer = {0x46, 0x72}}; /* [POS] §8.1.1 */
    ck_assert(!biss_probe_reg_layout_decode(&pos, &rl, why, sizeof why));
    /* "HE" that could not be read is no description either */
    struct biss_probe_regs r = ad38_regs();
    r.rc_device = BISS_E_CD_CRC;
    ck_assert(!biss_probe_reg_layout_decode(&r, &rl, why, sizeof why));
}
END_TEST

/* Values no frame has: described, but invalid, and the reason names the
 * register. */
START_TEST(impossible_values) {
    struct biss_probe_reg_layout rl;
    char why[160];
    static const struct {
        unsigned at, value;
        const char *named;
    } bad[] = {{0, 63, "0x78"},       {1, 2, "0x79"}, {1, 17, "0x79"}, {2, 0xFF, "0x7A"},
               {3, 0, "0x7A + 0x7B"}, {5, 0, "0x7D"}, {4, 40, "0x7C"}};
    for (unsigned i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        struct biss_probe_regs r = ad38_regs();
        r.device[bad[i].at] = (uint8_t)bad[i].value;
        if (bad[i].at == 3) {
            r.device[2] = 0; /* MT + ST = 0 */
        }
        ck_assert(biss_probe_reg_layout_decode(&r, &rl, why, sizeof why));
        ck_assert_uint_eq(rl.nchannels, 0);
        ck_assert_msg(strstr(why, bad[i].named), "case %u: %s", i, why);
    }
    struct biss_probe_result w = {.verdict = BISS_PROBE_UNIQUE, .nkept = 1};
    unsigned k;
    ck_assert_int_eq(biss_probe_reg_compare(&rl, &w, &k, why, sizeof why), BISS_PROBE_REG_INVALID);
}
END_TEST

START_TEST(compare_with_wire) {
    struct biss_probe_regs r = ad38_regs();
    struct biss_probe_reg_layout rl;
    char why[160];
    ck_assert(biss_probe_reg_layout_decode(&r, &rl, why, sizeof why));
    struct biss_probe_result w = {.verdict = BISS_PROBE_UNIQUE, .nkept = 1};
    w.layout[0] = ad38_wire();
    unsigned k;
    ck_assert_int_eq(biss_probe_reg_compare(&rl, &w, &k, why, sizeof why), BISS_PROBE_REG_AGREE);
    ck_assert_uint_eq(k, 1);
    /* the wire's second candidate has them: the registers pick it */
    w.verdict = BISS_PROBE_AMBIGUOUS;
    w.nkept = 2;
    w.layout[1] = w.layout[0];
    w.layout[0].slave[0].data_bits = 17;
    w.layout[0].slave[0].crc_bits = 6;
    ck_assert_int_eq(biss_probe_reg_compare(&rl, &w, &k, why, sizeof why), BISS_PROBE_REG_AGREE_K);
    ck_assert_uint_eq(k, 2);
    ck_assert_msg(strstr(why, "candidate 2") && strstr(why, "slave 0"), "%s", why);
    /* registers that lie: an A/D word of 20 bits */
    w.layout[0] = w.layout[1];
    w.nkept = 1;
    r.device[0] = 20;
    ck_assert(biss_probe_reg_layout_decode(&r, &rl, why, sizeof why));
    ck_assert_int_eq(biss_probe_reg_compare(&rl, &w, &k, why, sizeof why), BISS_PROBE_REG_DISAGREE);
    ck_assert_uint_eq(k, 0);
    ck_assert_msg(strstr(why, "22 data bits") && strstr(why, "wire 18"), "%s", why);
    /* a life counter the wire does not show */
    r.device[0] = 16;
    r.device[4] = 7;
    ck_assert(biss_probe_reg_layout_decode(&r, &rl, why, sizeof why));
    ck_assert_int_eq(biss_probe_reg_compare(&rl, &w, &k, why, sizeof why), BISS_PROBE_REG_DISAGREE);
    ck_assert_msg(strstr(why, "7-bit life counter") && strstr(why, "6 bits"), "%s", why);
    /* nE/nW missing on the wire */
    r.device[4] = 6;
    ck_assert(biss_probe_reg_layout_decode(&r, &rl, why, sizeof why));
    w.layout[0].slave[1].has_ew = false;
    ck_assert_int_eq(biss_probe_reg_compare(&rl, &w, &k, why, sizeof why), BISS_PROBE_REG_DISAGREE);
    ck_assert_msg(strstr(why, "slave 1") && strstr(why, "nE/nW"), "%s", why);
    /* fewer slaves on the wire than channels described */
    w.layout[0] = ad38_wire();
    w.layout[0].nslaves = 1;
    ck_assert_int_eq(biss_probe_reg_compare(&rl, &w, &k, why, sizeof why), BISS_PROBE_REG_DISAGREE);
    /* no wire layout: the registers stand alone */
    w.verdict = BISS_PROBE_NONE;
    ck_assert_int_eq(biss_probe_reg_compare(&rl, &w, &k, why, sizeof why), BISS_PROBE_REG_NO_WIRE);
}
END_TEST

int main(void) {
    Suite *s = suite_create("probe_regs");
    TCase *tc = tcase_create("regs");
    tcase_add_test(tc, ad38_values);
    tcase_add_test(tc, other_manufacturers);
    tcase_add_test(tc, impossible_values);
    tcase_add_test(tc, compare_with_wire);
    suite_add_tcase(s, tc);
    return check_run(s);
}
