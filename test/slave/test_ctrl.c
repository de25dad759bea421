/* Check suite for the CRCs and the control-frame state machine, driven one
 * CDM bit at a time; expected CDS strings were worked out by hand from the
 * frame layout in biss_ctrl.h. */
#include "biss_crc.h"
#include "biss_ctrl.h"

#include "check_run.h"

#include <check.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Feeds a string of '0'/'1' CDMs (other characters are skipped) and writes
 * the CDS answered after each into out. */
static void feed(biss_ctrl *c, const char *cdm, char *out) {
    size_t n = 0;
    for (const char *p = cdm; *p; p++) {
        if (*p == '0' || *p == '1') {
            out[n++] = (char)('0' + biss_ctrl_cdm(c, *p == '1'));
        }
    }
    out[n] = '\0';
}

static const char *ZEROS14 = "00000000000000";

static void arm(biss_ctrl *c) {
    char out[64];
    feed(c, ZEROS14, out);
}

START_TEST(crc_tidep0022_worked_examples) {
    /* CRC4 over 10001100111 (CTS, ID 000, address 0x67) is 1101 */
    ck_assert_uint_eq(biss_crc_bits(0x13, 0, 0x467, 11), 0xd);
    ck_assert_uint_eq(biss_ctrl_crc4_sent(0x467, 11), 0x2); /* sent inverted: 0010 */
    /* CRC4 over 01010111 is 1011, sent 0100 */
    ck_assert_uint_eq(biss_crc_bits(0x13, 0, 0x57, 8), 0xb);
    /* CRC6 (0x43) over 0000000000101 is 001111, sent 110000 */
    ck_assert_uint_eq(biss_crc_bits(0x43, 0, 0x5, 13), 0x0f);
    ck_assert_uint_eq(~biss_crc_bits(0x43, 0, 0x5, 13) & 0x3f, 0x30);
}
END_TEST

START_TEST(crc_widths_and_start_value) {
    ck_assert_uint_eq(biss_crc_width(0x13), 4);
    ck_assert_uint_eq(biss_crc_width(0x25), 5);
    ck_assert_uint_eq(biss_crc_width(0x43), 6);
    ck_assert_uint_eq(biss_crc_width(0x190d9), 16);
    ck_assert_uint_eq(biss_crc_width(0), 0);
    /* the corners: x^0 alone is no CRC, x^1 a one-bit one, the top term */
    ck_assert_uint_eq(biss_crc_width(1), 0);
    ck_assert_uint_eq(biss_crc_width(3), 1);
    ck_assert_uint_eq(biss_crc_width(0x80000000u), 31);
    /* a start value is the register content before the first bit */
    uint32_t a = biss_crc_bits(0x43, 0x15, 0x3a7, 12);
    uint32_t b = 0x15;
    for (int i = 11; i >= 0; i--) {
        b = biss_crc_bit(b, 0x43, (0x3a7 >> i) & 1);
    }
    ck_assert_uint_eq(a, b);
    ck_assert_uint_ne(a, biss_crc_bits(0x43, 0, 0x3a7, 12));
}
END_TEST

/* The design guide's Table 7 frames: CDM bits after S for a read of each
 * address, 32 bits MSB first. The model's header layout must reproduce them. */
START_TEST(header_matches_tidep0022_table7) {
    static const struct {
        uint8_t addr;
        uint32_t hex;
    } t7[] = {{0x44, 0x889B4000}, {0x45, 0x88BD4000}, {0x46, 0x88D74000}, {0x47, 0x88F14000},
              {0x60, 0x8C174000}, {0x67, 0x8CE54000}, {0x68, 0x8D014000}, {0x78, 0x8F0B4000},
              {0x79, 0x8F2D4000}, {0x7A, 0x8F474000}, {0x7B, 0x8F614000}, {0x7C, 0x8F934000},
              {0x7D, 0x8FB54000}};
    for (size_t i = 0; i < sizeof t7 / sizeof t7[0]; i++) {
        uint32_t hdr = biss_ctrl_reg_header(0, t7[i].addr);
        uint32_t w = (hdr << 21) | ((uint32_t)biss_ctrl_crc4_sent(hdr, 11) << 17) | (5u << 14);
        ck_assert_uint_eq(w, t7[i].hex);
    }
}
END_TEST

static regfile regs;

static void setup(void) {
    regfile_init(&regs, 4);
    regfile_poke(&regs, 0, 0x67, 0x5f);
    regfile_poke(&regs, 0, 0x68, 0xa5);
    regfile_poke(&regs, 0, 0x10, 0x03);
    regfile_poke(&regs, 2, 0x10, 0x46);
}

START_TEST(register_read) {
    biss_ctrl c;
    biss_ctrl_init(&c, 0, &regs, 0);
    arm(&c);
    char out[128];
    /* S, the Table 7 frame for 0x67, then the sequential S = 0 */
    feed(&c, "1 10001100111 0010 101 00000000 0000 0 0", out);
    /* 16 x 0 (S + header), R W S echo 1 0 1, data 0x5F, CRC4 sent 1111, P, end */
    ck_assert_str_eq(out, "10000000" /* IDL0..7 (the answers to S and 7 bits): ID 0 */
                          "00000000"
                          "101"
                          "01011111"
                          "1111"
                          "0"
                          "0");
    ck_assert_uint_eq(c.reads, 1);
    ck_assert_int_eq(c.last_value, 0x5f);
    ck_assert_int_eq(c.state, CTRL_IDLE);
}
END_TEST

START_TEST(register_write_stores_and_echoes) {
    biss_ctrl c;
    biss_ctrl_init(&c, 0, &regs, 0);
    arm(&c);
    char out[128];
    /* write 0x3A to 0x10 (bank 0): header 10000010000 CRC 0011, RWS 011,
     * data 00111010, CRC4 of 0x3A sent 1101, P, end */
    feed(&c, "1 10000010000 0011 011 00111010 1101 0 0", out);
    ck_assert_str_eq(out, "10000000" /* IDL0..7 (the answers to S and 7 bits): ID 0 */
                          "00000000"
                          "011"
                          "00111010"
                          "1101"
                          "0"
                          "0");
    ck_assert_uint_eq(c.writes, 1);
    ck_assert_uint_eq(regfile_read(&regs, 0x10), 0x3a);
}
END_TEST

START_TEST(write_with_bad_crc_is_refused_and_counted) {
    biss_ctrl c;
    biss_ctrl_init(&c, 0, &regs, 0);
    arm(&c);
    char out[128];
    feed(&c, "1 10000010000 0011 011 00111010 1100 0 0", out);
    ck_assert_uint_eq(c.writes, 0);
    ck_assert_uint_eq(c.crc_errors, 1);
    ck_assert_uint_eq(regfile_read(&regs, 0x10), 0x03);
}
END_TEST

START_TEST(header_crc_error_is_ignored_and_counted) {
    biss_ctrl c;
    biss_ctrl_init(&c, 0, &regs, 0);
    arm(&c);
    char out[128];
    feed(&c, "1 10001100111 0011 101 00000000 0000 0 0", out); /* CRC should be 0010 */
    ck_assert_str_eq(out, "10000000"                           /* IDL, before the CRC is known */
                          "0000000000000000000000000");
    ck_assert_uint_eq(c.crc_errors, 1);
    ck_assert_uint_eq(c.reads, 0);
    /* 14 zeros re-arm; a good frame then works */
    feed(&c, ZEROS14, out);
    feed(&c, "1 10001100111 0010 101 00000000 0000 0 0", out);
    ck_assert_uint_eq(c.reads, 1);
}
END_TEST

START_TEST(needs_fourteen_zeros_before_start) {
    biss_ctrl c;
    biss_ctrl_init(&c, 0, &regs, 0);
    char out[128];
    feed(&c, "0000000000000", out); /* only 13 */
    feed(&c, "1 10001100111 0010 101 00000000 0000 0 0", out);
    ck_assert_uint_eq(c.reads, 0);
    /* and again after a frame: the trailing zeros of a frame do not count */
    biss_ctrl_init(&c, 0, &regs, 0);
    arm(&c);
    feed(&c, "1 10001100111 0010 101 00000000 0000 0 0", out);
    feed(&c, "1 10001100111 0010 101 00000000 0000 0 0", out);
    ck_assert_uint_eq(c.reads, 1);
}
END_TEST

/* The other reading of the ID-lock slots (host/CD.md, "IDL"): IDL0..7 in
 * the answers to CTS and the 7 bits after it, of a register access only. */
START_TEST(id_lock_at_cts) {
    biss_ctrl c;
    char out[128];
    biss_ctrl_init(&c, 2, &regs, 0);
    c.idl_at_cts = true;
    arm(&c);
    feed(&c, "1 10001100111 0010 101 00000000 0000 0 0", out);
    ck_assert_str_eq(out, "0"
                          "00100000" /* IDL2 */
                          "000000000000000000000000");
    feed(&c, ZEROS14, out);
    feed(&c, "1 0 00100000 10 0111 00000000 1", out); /* a command: no ID lock */
    ck_assert_str_eq(out, "000000000000000"
                          "001"
                          "00000"
                          "00");
}
END_TEST

START_TEST(other_id_stays_silent) {
    biss_ctrl c;
    biss_ctrl_init(&c, 1, &regs, 0);
    arm(&c);
    char out[128];
    feed(&c, "1 10001100111 0010 101 00000000 0000 0 0", out);
    ck_assert_str_eq(out, "01000000" /* only its ID lock */
                          "0000000000000000000000000");
    ck_assert_uint_eq(c.reads, 0);
    ck_assert_uint_eq(c.crc_errors, 0);
}
END_TEST

START_TEST(late_start_bit_delays_data) {
    biss_ctrl c;
    biss_ctrl_init(&c, 0, &regs, 3);
    arm(&c);
    char out[128];
    /* after RWS the slave answers S = 0 for 3 frames, then S = 1; the
     * master holds CDM = 1 meanwhile (see late_start_zeros_cancel) */
    feed(&c, "1 10001100111 0010 101 111 00000000 0000 0 0", out);
    ck_assert_str_eq(out, "10000000" /* IDL0..7 (the answers to S and 7 bits): ID 0 */
                          "00000000"
                          "10"
                          "000"
                          "1"
                          "01011111"
                          "1111"
                          "0"
                          "0");
    ck_assert_uint_eq(c.reads, 1);
}
END_TEST

START_TEST(late_start_bit_write) {
    biss_ctrl c;
    biss_ctrl_init(&c, 0, &regs, 2);
    arm(&c);
    char out[128];
    /* the master sends the data from the frame in which it sees S = 1 */
    feed(&c, "1 10000010000 0011 011 00 00111010 1101 0 0", out);
    ck_assert_str_eq(out, "10000000" /* IDL0..7 (the answers to S and 7 bits): ID 0 */
                          "00000000"
                          "01"
                          "00"
                          "1"
                          "00111010"
                          "1101"
                          "0"
                          "0");
    ck_assert_uint_eq(regfile_read(&regs, 0x10), 0x3a);
}
END_TEST

START_TEST(sequential_read_two_registers) {
    biss_ctrl c;
    biss_ctrl_init(&c, 0, &regs, 0);
    arm(&c);
    char out[128];
    /* 0x67 then, after P and S = 1, 0x68 */
    feed(&c, "1 10001100111 0010 101 00000000 0000 0 1 00000000 0000 0 0", out);
    ck_assert_str_eq(out, "10000000" /* IDL0..7 (the answers to S and 7 bits): ID 0 */
                          "00000000"
                          "101"
                          "01011111"
                          "1111"
                          "0"
                          "1"
                          "10100101"
                          "0100"
                          "0"
                          "0");
    ck_assert_uint_eq(c.reads, 2);
    ck_assert_int_eq(c.last_addr, 0x68);
}
END_TEST

START_TEST(bank_switch_through_0x40) {
    biss_ctrl c;
    biss_ctrl_init(&c, 0, &regs, 0);
    arm(&c);
    char out[128];
    /* write 0x02 to 0x40 (header CRC 0001 from the table above) */
    char frame[128];
    uint8_t crc = biss_ctrl_crc4_sent(0x02, 8);
    snprintf(frame, sizeof frame, "1 10001000000 0001 011 00000010 %d%d%d%d 0 0", (crc >> 3) & 1,
             (crc >> 2) & 1, (crc >> 1) & 1, crc & 1);
    feed(&c, frame, out);
    ck_assert_uint_eq(regfile_read(&regs, 0x40), 2);
    arm(&c);
    /* read 0x10 now shows bank 2's byte 0x46 */
    feed(&c, "1 10000010000 0011 101 00000000 0000 0 0", out);
    ck_assert_str_eq(out, "10000000" /* IDL0..7 (the answers to S and 7 bits): ID 0 */
                          "00000000"
                          "101"
                          "01000110"
                          "0010"
                          "0"
                          "0");
}
END_TEST

START_TEST(read_only_and_write_protected) {
    regs.flags[0x68] = REG_RO;
    regs.flags[0x10] = REG_WP;
    ck_assert(!regfile_write(&regs, 0x68, 1));
    ck_assert(regfile_write(&regs, 0x10, 7));
    regs.protect = true;
    ck_assert(!regfile_write(&regs, 0x10, 8));
    ck_assert_uint_eq(regfile_read(&regs, 0x10), 7);
    regfile_write(&regs, 0x40, 9); /* bank 9 does not exist: reads 0 */
    ck_assert_uint_eq(regfile_read(&regs, 0x10), 0);
    ck_assert(!regfile_write(&regs, 0x10, 1));

    biss_ctrl c;
    regs.direct[0] = 0;
    biss_ctrl_init(&c, 0, &regs, 0);
    arm(&c);
    char out[128];
    feed(&c, "1 10000010000 0011 011 00111010 1101 0 0", out);
    ck_assert_uint_eq(c.write_refused, 1);
    ck_assert_uint_eq(regfile_read(&regs, 0x10), 7);
}
END_TEST

START_TEST(addressed_command_with_ida) {
    biss_ctrl c2, c5;
    biss_ctrl_init(&c2, 2, &regs, 0);
    biss_ctrl_init(&c5, 5, &regs, 0);
    arm(&c2);
    arm(&c5);
    const char *f = "1 0 00100000 10 0111 00000000 1"; /* EX = 1 */
    char o2[64], o5[64];
    feed(&c2, f, o2);
    feed(&c5, f, o5);
    /* S + 15 header bits: the ID lock in the first 8 (every control
     * frame's), then 0; then IDA slots 0..7 (slot 2 = 1), then P */
    ck_assert_str_eq(o2, "00100000"
                         "0000000"
                         "001"
                         "00000"
                         "00");
    ck_assert_str_eq(o5, "00000100"
                         "0000000"
                         "000"
                         "00000"
                         "00");
    ck_assert_uint_eq(c2.commands, 1);
    ck_assert_int_eq(c2.last_cmd, 2);
    ck_assert_uint_eq(c5.commands, 0);
}
END_TEST

/* The bit after the IDA slots: EX = 1 executes by default (iC-MB4 rev B2,
 * Table 31); a 0 there (a master that stopped, or withholds the command)
 * drops it. A slave with cmd_stop = 0 takes it the other way round. */
START_TEST(command_execute_bit_either_convention) {
    biss_ctrl c;
    char out[64];
    biss_ctrl_init(&c, 2, &regs, 0);
    ck_assert_uint_eq(c.cmd_stop, 1);
    arm(&c);
    feed(&c, "1 0 00100000 10 0111 00000000 0", out);
    ck_assert_uint_eq(c.commands, 0);
    ck_assert_uint_eq(c.commands_dropped, 1);
    biss_ctrl_init(&c, 2, &regs, 0);
    c.cmd_stop = 0;
    arm(&c);
    feed(&c, "1 0 00100000 10 0111 00000000 1", out);
    ck_assert_uint_eq(c.commands_dropped, 1);
    feed(&c, ZEROS14, out);
    feed(&c, "1 0 00100000 10 0111 00000000 0", out);
    ck_assert_uint_eq(c.commands, 1);
}
END_TEST

START_TEST(broadcast_command) {
    biss_ctrl c;
    biss_ctrl_init(&c, 3, &regs, 0);
    arm(&c);
    char out[64];
    feed(&c, "1 0 00000000 01 1100 00000000 1", out);
    ck_assert_str_eq(out, "0001000000000000000000000"); /* ID lock only: no IDA */
    ck_assert_uint_eq(c.commands, 1);
    ck_assert_int_eq(c.last_cmd, 1);
}
END_TEST

/* TIDEP0022 §2.1.3: any control frame is cancelled by 14 CDM = 0. A
 * master that sends 0 while the slave's S is late puts 3 + 8 + 4 zeros
 * in a row into a read: the frame is cancelled in the data, and the read
 * never completes. */
START_TEST(late_start_zeros_cancel) {
    biss_ctrl c;
    biss_ctrl_init(&c, 0, &regs, 3);
    arm(&c);
    char out[128];
    feed(&c, "1 10001100111 0010 101 000 00000000 00", out); /* 13 zeros */
    ck_assert_int_eq(c.state, CTRL_DCRC);
    feed(&c, "0", out); /* the 14th zero */
    ck_assert_int_eq(c.state, CTRL_IDLE);
    ck_assert(c.armed);
    ck_assert_uint_eq(c.cancels, 1);
    ck_assert_uint_eq(c.reads, 0);
    /* the S of a sequential access after 13 zeros is not a cancel */
    biss_ctrl_init(&c, 0, &regs, 0);
    arm(&c);
    feed(&c, "1 10001100111 0010 101 00000000 0000 0 1 00000000 0000 0 0", out);
    ck_assert_uint_eq(c.reads, 2);
    ck_assert_uint_eq(c.cancels, 0);
    ck_assert(!c.armed); /* a frame that ended wants 14 fresh zeros */
}
END_TEST

START_TEST(fourteen_zeros_cancel_a_header) {
    biss_ctrl c;
    biss_ctrl_init(&c, 0, &regs, 0);
    arm(&c);
    char out[64];
    feed(&c, "1 0 00000000000000", out); /* a command header that never ends */
    ck_assert_int_eq(c.state, CTRL_IDLE);
    ck_assert(c.armed);
}
END_TEST

int main(void) {
    Suite *s = suite_create("ctrl");
    TCase *tc = tcase_create("ctrl");
    tcase_add_checked_fixture(tc, setup, NULL);
    tcase_add_test(tc, crc_tidep0022_worked_examples);
    tcase_add_test(tc, crc_widths_and_start_value);
    tcase_add_test(tc, header_matches_tidep0022_table7);
    tcase_add_test(tc, register_read);
    tcase_add_test(tc, register_write_stores_and_echoes);
    tcase_add_test(tc, write_with_bad_crc_is_refused_and_counted);
    tcase_add_test(tc, header_crc_error_is_ignored_and_counted);
    tcase_add_test(tc, needs_fourteen_zeros_before_start);
    tcase_add_test(tc, other_id_stays_silent);
    tcase_add_test(tc, id_lock_at_cts);
    tcase_add_test(tc, late_start_bit_delays_data);
    tcase_add_test(tc, late_start_bit_write);
    tcase_add_test(tc, sequential_read_two_registers);
    tcase_add_test(tc, bank_switch_through_0x40);
    tcase_add_test(tc, read_only_and_write_protected);
    tcase_add_test(tc, addressed_command_with_ida);
    tcase_add_test(tc, broadcast_command);
    tcase_add_test(tc, command_execute_bit_either_convention);
    tcase_add_test(tc, fourteen_zeros_cancel_a_header);
    tcase_add_test(tc, late_start_zeros_cancel);
    suite_add_tcase(s, tc);
    return check_run(s);
}
