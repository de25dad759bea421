/* Check suite for the control-communication codec's pure parts: CRC4,
 * header bits, program layout, data RAM packing, and the parser on
 * answers written by hand. */
#include "biss_cd.h"
#include "biss_crc.h"

#include "check_run.h"

#include <check.h>
#include <stdlib.h>
#include <string.h>

/* The CDM the firmware sends for each step of a program (WAIT steps: -1):
 * ops 0 and 1 as they are, CRC steps the next bit of its CRC4 of the DATA
 * and ECHO bits, inverted (biss_shm.h; restarted after a WAIT). */
static void cdm_bits(const biss_cd_prog *p, int *cdm) {
    unsigned crc = 0;
    for (unsigned i = 0; i < p->len; i++) {
        unsigned op = BISS_CD_STEP_OP(p->op[i]), bit = op;
        if (op == BISS_CDOP_WAIT) {
            cdm[i] = -1;
            crc = 0;
            continue;
        }
        if (op == BISS_CDOP_CRC) {
            bit = !(crc >> 3 & 1u);
        }
        if (op == BISS_CDOP_CRC || BISS_CD_STEP_CL(p->op[i]) != BISS_CDCL_NONE) {
            crc = biss_crc_bit(crc, BISS_CRC4_POLY, (int)(bit ^ (op == BISS_CDOP_CRC)));
        }
        cdm[i] = (int)bit;
    }
}

/* Those CDM bits from step `from` on, WAIT steps left out, MSB first into
 * a word of up to 32 bits. */
static uint32_t cdm_word(const biss_cd_prog *p, unsigned from, unsigned nbits) {
    static int cdm[BISS_CD_MAX_STEPS];
    cdm_bits(p, cdm);
    uint32_t w = 0;
    unsigned got = 0;
    for (unsigned i = from; i < p->len && got < nbits; i++) {
        if (cdm[i] >= 0) {
            w = w << 1 | (unsigned)cdm[i];
            got++;
        }
    }
    ck_assert_uint_eq(got, nbits);
    return w;
}

START_TEST(crc4_worked_examples) {
    /* TIDEP0022: header 10001100111 (read 0x67) has CRC 1101, sent 0010 */
    ck_assert_uint_eq(biss_cd_crc4(0x467, 11), 0xd);
    ck_assert_uint_eq(biss_cd_crc4_line(0x467, 11), 0x2);
    /* data 01010111 has CRC 1011, sent 0100 */
    ck_assert_uint_eq(biss_cd_crc4(0x57, 8), 0xb);
    ck_assert_uint_eq(biss_cd_crc4_line(0x57, 8), 0x4);
    /* a zero message has remainder 0: sent as 1111 */
    ck_assert_uint_eq(biss_cd_crc4_line(0, 8), 0xf);
}
END_TEST

START_TEST(headers) {
    ck_assert_uint_eq(biss_cd_reg_header(0, 0x67), 0x467);
    ck_assert_uint_eq(biss_cd_reg_header(5, 0x01), 0x400 | 5 << 7 | 1);
    /* command: CTS 0, IDS with ID 0 first, CMD */
    ck_assert_uint_eq(biss_cd_cmd_header(0x01, 2), 0x80 << 2 | 2);
    ck_assert_uint_eq(biss_cd_cmd_header(0x80, 1), 0x01 << 2 | 1);
    ck_assert_uint_eq(biss_cd_cmd_header(0x00, 3), 3);
}
END_TEST

/* TIDEP0022 Table 7: the 32 CDM bits after S of each register read. */
START_TEST(table7_read_frames) {
    static const struct {
        uint8_t addr;
        uint32_t hex;
    } t7[] = {{0x44, 0x889B4000}, {0x45, 0x88BD4000}, {0x46, 0x88D74000}, {0x47, 0x88F14000},
              {0x60, 0x8C174000}, {0x67, 0x8CE54000}, {0x68, 0x8D014000}, {0x78, 0x8F0B4000},
              {0x79, 0x8F2D4000}, {0x7A, 0x8F474000}, {0x7B, 0x8F614000}, {0x7C, 0x8F934000},
              {0x7D, 0x8FB54000}};
    biss_cd_prog p;
    for (size_t i = 0; i < sizeof t7 / sizeof t7[0]; i++) {
        ck_assert_int_eq(biss_cd_build_read(&p, 0, t7[i].addr, 1), BISS_CD_OK);
        ck_assert_uint_eq(p.op[0], BISS_CDOP_1); /* S */
        ck_assert_uint_eq(cdm_word(&p, 1, 32), t7[i].hex);
        /* nothing follows the frame's final S = 0 */
        ck_assert_uint_eq(p.len, 1 + 32 + 1 + BISS_CD_TAIL_ZEROS); /* S, the 32 bits, WAIT */
    }
}
END_TEST

START_TEST(read_layout) {
    biss_cd_prog p;
    ck_assert_int_eq(biss_cd_build_read(&p, 3, 0x7e, 3), BISS_CD_OK);
    ck_assert_uint_eq(p.len, 19 + 15 * 3 + BISS_CD_TAIL_ZEROS);
    ck_assert_uint_eq(p.rw, 16);
    for (unsigned i = 0; i < 3; i++) {
        const biss_cd_byte_steps *b = &p.byte[i];
        ck_assert_uint_eq(b->start, 18 + 15 * i);
        ck_assert_uint_eq(p.op[b->start], BISS_CDOP_1);
        ck_assert_uint_eq(b->wait, b->start + 1);
        ck_assert_uint_eq(p.op[b->wait], BISS_CDOP_WAIT);
        ck_assert_uint_eq(b->data, b->wait + 1);
        ck_assert_uint_eq(b->crc, b->data + 8);
        ck_assert_uint_eq(b->stop, b->crc + 4);
        ck_assert_uint_eq(p.op[b->stop], BISS_CDOP_0);
        /* zeros out; the data into CRC_S, the slave's CRC checked */
        ck_assert_uint_eq(p.op[b->data + 7], BISS_CD_STEP(BISS_CDOP_0, BISS_CDCL_DATA));
        ck_assert_uint_eq(p.op[b->crc + 3], BISS_CD_STEP(BISS_CDOP_0, BISS_CDCL_CHECK));
    }
    /* the header CRC is the firmware's; R W are echoed */
    ck_assert_uint_eq(p.op[12], BISS_CD_STEP(BISS_CDOP_CRC, BISS_CDCL_NONE));
    ck_assert_uint_eq(p.op[p.rw], BISS_CD_STEP(BISS_CDOP_1, BISS_CDCL_ECHO));
    ck_assert_uint_eq(p.op[p.rw + 1], BISS_CD_STEP(BISS_CDOP_0, BISS_CDCL_ECHO));
    ck_assert_uint_eq(p.op[p.len - 1 - BISS_CD_TAIL_ZEROS], BISS_CDOP_0); /* final S */
    /* the longest access fits one program */
    ck_assert_int_eq(biss_cd_build_read(&p, 7, 0, 64), BISS_CD_OK);
    ck_assert_uint_le(p.len, BISS_CD_MAX_STEPS);
}
END_TEST

START_TEST(write_layout) {
    biss_cd_prog p;
    const uint8_t data[] = {0x57, 0xa0};
    ck_assert_int_eq(biss_cd_build_write(&p, 0, 0x10, data, 2), BISS_CD_OK);
    /* R W = 0 1 */
    ck_assert_uint_eq(BISS_CD_STEP_OP(p.op[p.rw]), 0);
    ck_assert_uint_eq(BISS_CD_STEP_OP(p.op[p.rw + 1]), 1);
    /* every data and CRC bit's echo is checked; the CRC is the firmware's */
    ck_assert_uint_eq(p.op[p.byte[0].data], BISS_CD_STEP(BISS_CDOP_0, BISS_CDCL_ECHO));
    ck_assert_uint_eq(p.op[p.byte[0].crc], BISS_CD_STEP(BISS_CDOP_CRC, BISS_CDCL_ECHO));
    /* data 01010111 then its line CRC 0100 */
    ck_assert_uint_eq(cdm_word(&p, p.byte[0].data, 12), 0x57u << 4 | 0x4);
    ck_assert_uint_eq(cdm_word(&p, p.byte[1].data, 8), 0xa0);
    ck_assert_uint_eq(p.wdata[1], 0xa0);
}
END_TEST

START_TEST(command_layout) {
    biss_cd_prog p;
    ck_assert_int_eq(biss_cd_build_command(&p, 0x01, 2, false), BISS_CD_OK);
    ck_assert_uint_eq(p.len, 25 + BISS_CD_TAIL_ZEROS);
    ck_assert_uint_eq(p.op[1], BISS_CD_STEP(0, BISS_CDCL_DATA)); /* CTS */
    ck_assert_uint_eq(p.op[2], BISS_CD_STEP(1, BISS_CDCL_DATA)); /* IDS: ID 0 first */
    ck_assert_uint_eq(p.op[9], BISS_CD_STEP(0, BISS_CDCL_DATA)); /* ID 7 */
    ck_assert_uint_eq(cdm_word(&p, 10, 2), 2);
    ck_assert_uint_eq(cdm_word(&p, 12, 4), biss_cd_crc4_line(biss_cd_cmd_header(0x01, 2), 11));
    ck_assert_uint_eq(p.ida, 15); /* the last CRC step */
    ck_assert_uint_eq(p.end, 24); /* P */
    ck_assert_uint_eq(biss_cd_ida_word(&p), 0);
    /* the IDA test: P's step and the IDs that must answer */
    ck_assert_int_eq(biss_cd_build_command(&p, 0x81, 1, true), BISS_CD_OK);
    ck_assert_uint_eq(biss_cd_ida_word(&p), 24u | 0x81u << 16);
}
END_TEST

START_TEST(builder_arguments) {
    biss_cd_prog p;
    uint8_t d[65] = {0};
    ck_assert_int_eq(biss_cd_build_read(&p, 8, 0, 1), BISS_CD_E_ARG);
    ck_assert_int_eq(biss_cd_build_read(&p, 0, 0x80, 1), BISS_CD_E_ARG);
    ck_assert_int_eq(biss_cd_build_read(&p, 0, 0, 0), BISS_CD_E_ARG);
    ck_assert_int_eq(biss_cd_build_read(&p, 0, 0, 65), BISS_CD_E_ARG);
    ck_assert_int_eq(biss_cd_build_write(&p, 0, 0, NULL, 1), BISS_CD_E_ARG);
    ck_assert_int_eq(biss_cd_build_write(&p, 0, 0, d, 65), BISS_CD_E_ARG);
    ck_assert_int_eq(biss_cd_build_command(&p, 0, 4, false), BISS_CD_E_ARG);
    uint8_t ops[] = {0, 1, 16};
    ck_assert_int_eq(biss_cd_build_raw(&p, ops, 3), BISS_CD_E_ARG);
    ck_assert_int_eq(biss_cd_build_raw(&p, ops, 0), BISS_CD_E_ARG);
    ck_assert_int_eq(biss_cd_build_raw(&p, ops, BISS_CD_MAX_STEPS + 1), BISS_CD_E_TOO_LONG);
    ck_assert_int_eq(biss_cd_build_raw(&p, ops, 2), BISS_CD_OK);
    ck_assert_uint_eq(p.len, 2);
}
END_TEST

START_TEST(pack_and_shm_words) {
    static uint8_t dram[BISS_DRAM_BYTES];
    memset(dram, 0, sizeof dram);
    const uint8_t ops[] = {1, 0, 2, 0xf, 5, 1};
    biss_cd_prog p;
    ck_assert_int_eq(biss_cd_build_raw(&p, ops, 6), BISS_CD_OK);
    memset(dram + BISS_CD_PROG, 0xee, BISS_CD_PROG_BYTES);
    ck_assert_int_eq(biss_cd_shm_put(&p, 0x1234, dram, sizeof dram), BISS_CD_OK);
    /* step i in the low nibble of byte i/2 (even i) or its high nibble;
     * past the end: 0 */
    ck_assert_uint_eq(dram[BISS_CD_PROG], 0x01);
    ck_assert_uint_eq(dram[BISS_CD_PROG + 1], 0xf2);
    ck_assert_uint_eq(dram[BISS_CD_PROG + 2], 0x15);
    ck_assert_uint_eq(dram[BISS_CD_PROG + 3], 0);
    ck_assert_uint_eq(dram[BISS_CD_PROG + BISS_CD_PROG_BYTES - 1], 0);
    ck_assert_uint_eq(dram[BISS_CD_IDA_STEP], 0); /* no IDA test */
    ck_assert_uint_eq(dram[BISS_CD_STEPS], 6);
    ck_assert_uint_eq(dram[BISS_CD_STEPS + 1], 0);
    ck_assert_uint_eq(dram[BISS_CD_WAIT_LIMIT], 0x34);
    ck_assert_uint_eq(dram[BISS_CD_WAIT_LIMIT + 1], 0x12);
    ck_assert_uint_eq(dram[BISS_CD_CMD], 0); /* left to the caller */
    ck_assert_int_eq(biss_cd_shm_put(&p, 0, dram, BISS_CD_RESP - 1), BISS_CD_E_ARG);

    const uint8_t st[] = {0x78, 0x56, 0x34, 0x12, BISS_CDST_DONE, 42, 0x21, 0x03};
    memcpy(dram + BISS_ST_CD_SEQ, st, sizeof st);
    dram[BISS_CD_RESP + 127] = 0x80;
    biss_cd_answer a;
    ck_assert_int_eq(biss_cd_shm_get(dram, sizeof dram, &a), BISS_CD_OK);
    ck_assert_uint_eq(a.seq, 0x12345678);
    ck_assert_uint_eq(a.status, BISS_CDST_DONE);
    ck_assert_uint_eq(a.steps, 0x321);
    ck_assert_uint_eq(a.bytes, 42);
    ck_assert_int_eq(biss_cd_answer_bit(&a, 1023), 1);
    ck_assert_int_eq(biss_cd_answer_bit(&a, 1022), 0);
}
END_TEST

static void set_bits(biss_cd_answer *a, unsigned step, unsigned value, unsigned nbits) {
    for (unsigned i = 0; i < nbits; i++) {
        unsigned s = step + i;
        if ((value >> (nbits - 1 - i)) & 1u) {
            a->resp[s / 8] |= (uint8_t)(1u << (s % 8));
        }
    }
}

/* Answers of a good read written by hand, then the firmware's own errors. */
START_TEST(parse_by_hand) {
    biss_cd_prog p;
    ck_assert_int_eq(biss_cd_build_read(&p, 0, 0x67, 1), BISS_CD_OK);
    biss_cd_answer a = {.status = BISS_CDST_DONE, .steps = p.len, .bytes = 1};
    set_bits(&a, p.rw, 2, 2);            /* R W echoed: 1 0 */
    set_bits(&a, p.byte[0].start, 1, 1); /* S in time */
    set_bits(&a, p.byte[0].data, 0x5f, 8);
    set_bits(&a, p.byte[0].crc, biss_cd_crc4_line(0x5f, 8), 4);
    biss_cd_result r;
    ck_assert_int_eq(biss_cd_parse(&p, &a, &r), BISS_CD_OK);
    ck_assert_uint_eq(r.byte[0].data, 0x5f);
    ck_assert_int_eq(r.byte[0].start, BISS_CD_S_IN_TIME);
    ck_assert_uint_eq(r.good_bytes, 1);

    a.status = BISS_CDST_ERR_STEPS;
    ck_assert_int_eq(biss_cd_parse(&p, &a, &r), BISS_CD_E_REFUSED);
    a.status = BISS_CDST_BUSY;
    ck_assert_int_eq(biss_cd_parse(&p, &a, &r), BISS_CD_E_NOT_DONE);
    /* a BiSS frame lost right after the final S = 0 went out: its answer is
     * lost, the byte came but the control frame may not have ended */
    ck_assert_uint_eq(p.end, p.byte[0].stop + 1);
    a.status = BISS_CDST_ERR_FRAME;
    a.steps = (uint16_t)(p.end + 1);
    ck_assert_int_eq(biss_cd_parse(&p, &a, &r), BISS_CD_E_FRAME);
    ck_assert_uint_eq(r.good_bytes, 1);
    /* one lost in the tail costs nothing */
    a.steps = (uint16_t)(p.end + 2);
    ck_assert_int_eq(biss_cd_parse(&p, &a, &r), BISS_CD_OK);
    /* the firmware's verdict when the answers look right (a CDS bit seen
     * wrong by the firmware, say): it wins, with its byte count */
    a.status = BISS_CDST_ERR_CRC;
    a.steps = p.len;
    a.bytes = 0;
    ck_assert_int_eq(biss_cd_parse(&p, &a, &r), BISS_CD_E_CRC);
    ck_assert_uint_eq(r.good_bytes, 0);
    ck_assert_str_eq(biss_cd_strerror(BISS_CD_E_CRC), "register data CRC error");
    ck_assert_str_eq(biss_cd_strerror((biss_cd_err)99), "unknown error");
}
END_TEST

int main(void) {
    Suite *s = suite_create("proto_cd_build");
    TCase *tc = tcase_create("build");
    tcase_add_test(tc, crc4_worked_examples);
    tcase_add_test(tc, headers);
    tcase_add_test(tc, table7_read_frames);
    tcase_add_test(tc, read_layout);
    tcase_add_test(tc, write_layout);
    tcase_add_test(tc, command_layout);
    tcase_add_test(tc, builder_arguments);
    tcase_add_test(tc, pack_and_shm_words);
    tcase_add_test(tc, parse_by_hand);
    suite_add_tcase(s, tc);
    return check_run(s);
}
