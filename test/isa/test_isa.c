/* Check suite for the instruction table: known encodings, the codec's
 * round trip over the word space, invalid words, disassembly text. */
#include "pru_isa.h"

#include "check_run.h"

#include <check.h>
#include <stdlib.h>
#include <string.h>

/* Words produced by pasm 0.87 -V3 (docs/pru-facts.md §1.9 and more checked
 * against it), with the text our disassembler prints for them at pc. */
static const struct {
    uint32_t word;
    uint32_t pc;
    const char *text;
} known[] = {
    {0x00e3e2e1u, 0, "add r1, r2, r3"},
    {0x01ffa221u, 0, "add r1.b1, r2.w1, 0xff"},
    {0x0305e2e1u, 0, "adc r1, r2, 5"},
    {0x048564c3u, 0, "sub r3.w2, r4.b3, r5.w0"},
    {0x091fe1e1u, 0, "lsl r1, r1, 0x1f"},
    {0x0a02e1e1u, 0, "lsr r1, r1, r2.b0"},
    {0x0d07e2e1u, 0, "rsb r1, r2, 7"},
    {0x1301e2e1u, 0, "or r1, r2, 1"},
    {0x1b09e2e1u, 0, "max r1, r2, 9"},
    {0x1700e2e1u, 0, "not r1, r2"},
    {0x10e2e2e1u, 0, "and r1, r2, r2"},
    {0x10222281u, 0, "and r1.w0, r2.b1, r2.b1"},
    {0x1d05fefeu, 0, "clr r30, r30, 5"},
    {0x1f05fefeu, 0, "set r30, r30, 5"},
    {0x1d050121u, 0, "clr r1.b1, r1.b0, 5"},
    {0x240012e1u, 0, "ldi r1, 0x12"},
    {0x241234c1u, 0, "ldi r1.w2, 0x1234"},
    {0x2400ab41u, 0, "ldi r1.b2, 0xab"},
    {0x2401ff01u, 0, "ldi r1.b0, 0x1ff"},
    {0x2701e2e1u, 0, "lmbd r1, r2, 1"},
    {0x21000000u, 0, "jmp 0"},
    {0x20820000u, 0, "jmp r2.w0"},
    {0x22e400c3u, 0, "jal r3.w2, r4"},
    {0x2300009eu, 0, "jal r30.w0, 0"},
    {0x209e0000u, 0, "jmp r30.w0"},
    {0x2a000000u, 0, "halt"},
    {0x3e000000u, 0, "slp 0"},
    {0x3e800000u, 0, "slp 1"},
    {0x2e850382u, 0, "xin 10, r2, 8"},
    {0x2f073f42u, 0, "xout 14, r2.b2, b2"},
    {0x2f863d84u, 0, "xchg 12, r4, 124"},
    {0x2e854382u, 0, "sxin 10, r2, 8"},
    {0x2e850182u, 0, "xin 10, r2, 4"},
    {0x2eff8380u, 0, "zero 0, 8"},
    {0x2eff0182u, 0, "fill 8, 4"},
    {0x2effbb81u, 0, "zero 4, 120"},
    {0x31040002u, 0x10, "loop 0x12, 5"},
    {0x30020002u, 0x10, "loop 0x12, r2.b0"},
    {0x31ff8002u, 0x10, "iloop 0x12, 256"},
    {0x2c2001e2u, 0, "mvib r2, *r1.b0"},
    {0x2d02ee01u, 0, "mvid *r1.b0++, r14"},
    {0x2d82ee01u, 0, "mvid *--r1.b0, r14"},
    {0x60e2e100u, 7, "qbgt 7, r1, r2"},
    {0x71ff010au, 0, "qbge 0xa, r1.b0, 0xff"},
    {0x7f0000fau, 10, "qba 4"},
    {0x58e2e108u, 0, "qble 8, r1, r2"},
    {0x5700e1fcu, 0x14, "qbeq 0x10, r1, 0"},
    {0x68a2e106u, 0, "qbne 6, r1, r2.w1"},
    {0xd71efff9u, 0x20, "qbbs 0x19, r31, 0x1e"},
    {0xc91fff03u, 0, "qbbc 3, r31, 0x1f"},
    {0xc91eff00u, 5, "qbbc 5, r31, 0x1e"},
    {0xd103ff00u, 5, "qbbs 5, r31, 3"},
    {0xf1056182u, 0, "lbbo r2, r1, 5, 8"},
    {0xfe83c102u, 0, "lbbo r2, r1, r3.w0, b0"},
    {0xef00a1a2u, 0, "sbbo r2.b1, r1, 0, 124"},
    {0x91003883u, 0, "lbco r3, c24, 0, 4"},
    {0x8ee4ff83u, 0, "sbco r3, c31, r4, b3"},
    {0xa0e3e2e1u, 0, "nop0 r1, r2, r3"},
};

START_TEST(test_known_words_decode_encode_disasm) {
    for (size_t i = 0; i < sizeof(known) / sizeof(known[0]); i++) {
        struct pru_insn in;
        char text[64];
        ck_assert_msg(pru_decode(known[i].word, &in) == 0, "0x%08x must decode", known[i].word);
        ck_assert_uint_eq(pru_encode(&in), known[i].word);
        ck_assert_int_gt(pru_disasm(known[i].word, known[i].pc, text, sizeof(text)), 0);
        ck_assert_str_eq(text, known[i].text);
    }
}
END_TEST

START_TEST(test_decoded_fields) {
    struct pru_insn in;
    ck_assert_int_eq(pru_decode(0xfe83c102u, &in), 0); /* lbbo &r2, r1, r3.w0, b0 */
    ck_assert_int_eq(in.op, PRU_OP_LBBO);
    ck_assert_uint_eq(in.len, 124);
    ck_assert_uint_eq(in.rx, 2);
    ck_assert_uint_eq(in.base, 1);
    ck_assert_uint_eq(in.io, 0);
    ck_assert_uint_eq(in.rs2, 3);
    ck_assert_uint_eq(in.rs2sel, PRU_SEL_W0);

    ck_assert_int_eq(pru_decode(0x7f0000fau, &in), 0); /* qba -6 */
    ck_assert_int_eq(in.broff, -6);
    ck_assert_int_eq(pru_decode(0x7f0000ffu, &in), 0);
    ck_assert_int_eq(in.broff, -1); /* 0x3ff */
    ck_assert_int_eq(pru_decode(0x79000000u | (1u << 25) | 0xffu, &in), 0);
    ck_assert_int_eq(in.broff, 511); /* 0x1ff: the largest forward branch */
    ck_assert_int_eq(pru_decode(0x79000000u | (2u << 25), &in), 0);
    ck_assert_int_eq(in.broff, -512); /* 0x200: the largest backward branch */

    ck_assert_int_eq(pru_decode(0x31ff8002u, &in), 0); /* iloop +2, 256 */
    ck_assert_int_eq(in.op, PRU_OP_ILOOP);
    ck_assert_uint_eq(in.imm, 255);
    ck_assert_uint_eq(in.loop_end, 2);
    ck_assert_uint_eq(in.flag, 1);

    ck_assert_int_eq(pru_decode(0x2d82ee01u, &in), 0); /* mvid *--r1.b0, r14 */
    ck_assert_int_eq(in.op, PRU_OP_MVID);
    ck_assert_uint_eq(in.mvi_dmode, PRU_MVI_PREDEC);
    ck_assert_uint_eq(in.mvi_smode, PRU_MVI_DIRECT);
    ck_assert_uint_eq(in.rd, 1);
    ck_assert_uint_eq(in.rdsel, PRU_SEL_B0);
    ck_assert_uint_eq(in.rs1, 14);
}
END_TEST

START_TEST(test_invalid_words) {
    static const uint32_t bad[] = {
        0x40000000u, /* quick branch with GT=EQ=LT=0 ("never") */
        0xc0000000u, /* bit test with neither BS nor BC */
        0xd8000000u, /* bit test with both */
        0x28000000u, /* SCAN: core V1 only */
        0x32000000u, /* format 2 sub-op 9: reserved */
        0x3c000000u, /* sub-op 14: reserved (RFI) */
        0x2e000000u, /* XFR with kind 00 */
        0x2a000001u, /* HALT with junk */
        0x3e000100u, /* SLP with junk */
        0x21000001u, /* JMP with bits 7:0 set */
        0x20820100u, /* JMP register form with bits 15:8 set */
        0x25000000u, /* LDI with bit 24 set */
        0x2c030000u, /* MVI size 3 */
        0x2c040000u, /* MVI reserved bit 18 */
        0x30000100u, /* LOOP with bits 14:8 set */
    };
    for (size_t i = 0; i < sizeof(bad) / sizeof(bad[0]); i++) {
        struct pru_insn in;
        char text[64];
        ck_assert_msg(pru_decode(bad[i], &in) == -1, "0x%08x must not decode", bad[i]);
        ck_assert_int_lt(pru_disasm(bad[i], 0, text, sizeof(text)), 0);
        ck_assert(strncmp(text, ".codeword 0x", 12) == 0);
    }
}
END_TEST

/* encode(decode(w)) == w for every word that decodes: sample the word
 * space with a fixed-seed generator, plus every top-byte pattern. */
START_TEST(test_round_trip) {
    uint64_t s = 0x9e3779b97f4a7c15u;
    unsigned decoded = 0;
    for (unsigned i = 0; i < 1000000; i++) {
        s ^= s << 13;
        s ^= s >> 7;
        s ^= s << 17;
        uint32_t w = (uint32_t)(s >> 16);
        if (i < 65536) {
            w = (i << 16) | (w & 0xffffu);
        }
        struct pru_insn in;
        if (pru_decode(w, &in) == 0) {
            decoded++;
            ck_assert_msg(pru_encode(&in) == w, "round trip of 0x%08x gave 0x%08x", w,
                          pru_encode(&in));
            char text[64];
            ck_assert_int_gt(pru_disasm(w, 0, text, sizeof(text)), 0);
        }
    }
    ck_assert_uint_gt(decoded, 250000);
}
END_TEST

START_TEST(test_lookup_and_helpers) {
    ck_assert_int_eq(pru_op_lookup("QBBS"), PRU_OP_QBBS);
    ck_assert_int_eq(pru_op_lookup("lbco"), PRU_OP_LBCO);
    ck_assert_int_eq(pru_op_lookup("nopf"), PRU_OP_NOPF);
    ck_assert_int_eq(pru_op_lookup("MOV"), PRU_OP_MOV); /* pseudo-instructions are rows too */
    ck_assert_int_eq(pru_op_lookup("scan"), PRU_OP_SCAN);
    ck_assert_int_eq(pru_op_lookup("nop"), -1);
    ck_assert_int_eq(pru_op_lookup(""), -1);
    ck_assert_int_eq(pru_op_lookup("averyverylongname"), -1);
    ck_assert_uint_eq(pru_len_bytes(0, 0), 1);
    ck_assert_uint_eq(pru_len_bytes(123, 0), 124);
    ck_assert_uint_eq(pru_len_bytes(126, 0x00420000u), 0x42);
    ck_assert_uint_eq(pru_sel_mask(PRU_SEL_W1), 0xffffu);
    ck_assert_uint_eq(pru_sel_shift(PRU_SEL_W1), 8);
    ck_assert_uint_eq(pru_sel_width(PRU_SEL_R), 32);
    char buf[8];
    ck_assert_str_eq(pru_reg_name(30, PRU_SEL_W0, buf), "r30.w0");
    /* every row's match lies within its own mask, its name finds it, its
     * core range is sane, pseudo rows have no bits, and no two rows that
     * decode overlap */
    for (int a = 0; a < PRU_OP_COUNT; a++) {
        ck_assert_uint_eq(pru_optable[a].match & ~pru_optable[a].mask, 0);
        ck_assert_int_eq(pru_op_lookup(pru_optable[a].name), a);
        ck_assert_uint_le(pru_optable[a].min_core, pru_optable[a].max_core);
        ck_assert_uint_le(pru_optable[a].max_core, 3);
        if (pru_optable[a].fmt == PRU_FMT_PSEUDO) {
            ck_assert_uint_eq(pru_optable[a].mask, 0);
            ck_assert(!pru_op_decodes(a));
        }
        if (!pru_op_decodes(a))
            continue;
        for (int b = a + 1; b < PRU_OP_COUNT; b++) {
            if (!pru_op_decodes(b))
                continue;
            uint32_t common = pru_optable[a].mask & pru_optable[b].mask;
            ck_assert_msg((pru_optable[a].match & common) != (pru_optable[b].match & common),
                          "%s overlaps %s", pru_optable[a].name, pru_optable[b].name);
        }
    }
}
END_TEST

int main(void) {
    Suite *s = suite_create("isa");
    TCase *tc = tcase_create("codec");
    tcase_set_timeout(tc, 60);
    tcase_add_test(tc, test_known_words_decode_encode_disasm);
    tcase_add_test(tc, test_decoded_fields);
    tcase_add_test(tc, test_invalid_words);
    tcase_add_test(tc, test_round_trip);
    tcase_add_test(tc, test_lookup_and_helpers);
    suite_add_tcase(s, tc);
    return check_run(s);
}
