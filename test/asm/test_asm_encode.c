/*
 * test_asm_encode.c - every instruction and operand form pruasm accepts
 * produces the words pasm 0.87 -V3 produces. Each snippet is assembled after
 * ".origin 0"; the expected words were checked against pasm 0.87 (and the
 * VER table of docs/pru-facts.md §1.9).
 */
#include "check_run.h"

#include <check.h>
#include <stdio.h>
#include <stdlib.h>

#include "asm_test_util.h"

struct enc {
    const char *src;
    uint32_t words[4]; /* all words, or (tail) only the last one */
    size_t n;          /* word count of the image */
    int tail;
};

static const struct enc table[] = {
    {"add r1, r2, r3", {0x00E3E2E1}, 1, 0},
    {"add r1.b1, r2.w1, 0xff", {0x01FFA221}, 1, 0},
    {"adc r1, r2, 5", {0x0305E2E1}, 1, 0},
    {"sub r3.w2, r4.b3, r5.w0", {0x048564C3}, 1, 0},
    {"suc r1, r2, r3.w2", {0x06C3E2E1}, 1, 0},
    {"lsl r1, r1, 31", {0x091FE1E1}, 1, 0},
    {"lsl r1, r1, 32", {0x0920E1E1}, 1, 0},
    {"lsr r1, r1, r2.b0", {0x0A02E1E1}, 1, 0},
    {"rsb r1, r2, 7", {0x0D07E2E1}, 1, 0},
    {"rsc r1.b3, r2.b2, r3.b1", {0x0E234261}, 1, 0},
    {"and r1, r2, 0", {0x1100E2E1}, 1, 0},
    {"or r1, r2, 1", {0x1301E2E1}, 1, 0},
    {"xor r1.w1, r2.w2, r3.w0", {0x1483C2A1}, 1, 0},
    {"not r1, r2", {0x1700E2E1}, 1, 0},
    {"not r1, r2, r3", {0x16E3E2E1}, 1, 0},
    {"min r1, r2, r3", {0x18E3E2E1}, 1, 0},
    {"max r1, r2, 9", {0x1B09E2E1}, 1, 0},
    {"add r1.w1.b1, r2.w2.b0, r3.b3", {0x00634241}, 1, 0},
    {"add r31, r30.w0, r29.w1.b0", {0x003D9EFF}, 1, 0},
    {"clr r30.t5", {0x1D05FEFE}, 1, 0},
    {"clr r1, r1, 32", {0x1D20E1E1}, 1, 0},
    {"clr r1.b1, r1.b0.t5", {0x1D050121}, 1, 0},
    {"clr r2, 7", {0x1D07E2E2}, 1, 0},
    {"clr r2, r3, r4.b1", {0x1C24E3E2}, 1, 0},
    {"set r30, 5", {0x1F05FEFE}, 1, 0},
    {"set r1.w1.t15", {0x1F0FA1A1}, 1, 0},
    {"set r1, r2.t31", {0x1F1FE2E1}, 1, 0},
    {"set r1, r2, r3.b2", {0x1E43E2E1}, 1, 0},
    {"nop0 r1, r2, r3", {0xA0E3E2E1}, 1, 0},
    {"nop7 r0, r0, 0", {0xAF00E0E0}, 1, 0},
    {"nopf r1.w1, r2.b3, 200", {0xBFC862A1}, 1, 0},
    {"ldi r1, 0x1234", {0x241234E1}, 1, 0},
    {"ldi r1.b0, 0x1ff", {0x2401FF01}, 1, 0},
    {"ldi r30.b0, &r2", {0x2400081E}, 1, 0},
    {"ldi r1, &r3.w1", {0x24000DE1}, 1, 0},
    {"ldi r1, &r5.w1.b1", {0x240016E1}, 1, 0},
    {"ldi r1, #5", {0x240005E1}, 1, 0},
    {"mov r1, r2", {0x10E2E2E1}, 1, 0},
    {"mov r1.w0, r2.b1", {0x10222281}, 1, 0},
    {"mov r1, 0x12", {0x240012E1}, 1, 0},
    {"mov r1, 0xffff", {0x24FFFFE1}, 1, 0},
    {"mov r1, 0x10000", {0x240001C1, 0x24000081}, 2, 0},
    {"mov r1, 0x12345678", {0x241234C1, 0x24567881}, 2, 0},
    {"mov r1.b2, 0xab", {0x2400AB41}, 1, 0},
    {"mov r1.w1, 0xabcd", {0x24ABCDA1}, 1, 0},
    {"mov r1, &r4", {0x240010E1}, 1, 0},
    {"lmbd r1, r2, 1", {0x2701E2E1}, 1, 0},
    {"lmbd r1.b0, r2.w1, r3.b0", {0x2603A201}, 1, 0},
    {"start: jmp start", {0x21000000}, 1, 0},
    {"jmp r2.w0", {0x20820000}, 1, 0},
    {"jmp 0xffff", {0x21FFFF00}, 1, 0},
    {"jal r3.w2, r4", {0x22E400C3}, 1, 0},
    {"jal r30.w0, 100", {0x2300649E}, 1, 0},
    {"start: call start", {0x2300009E}, 1, 0},
    {"call r5.w1", {0x22A5009E}, 1, 0},
    {"ret", {0x209E0000}, 1, 0},
    {"halt", {0x2A000000}, 1, 0},
    {"slp 0", {0x3E000000}, 1, 0},
    {"slp 1", {0x3E800000}, 1, 0},
    {"xin 10, r2, 8", {0x2E850382}, 1, 0},
    {"xin 10, 8, 4", {0x2E850182}, 1, 0},
    {"xout 14, r2.b2, b2", {0x2F073F42}, 1, 0},
    {"xchg 12, r4, 124", {0x2F863D84}, 1, 0},
    {"sxin 10, r2, 8", {0x2E854382}, 1, 0},
    {"sxout 11, r3.w1, b0", {0x2F05FE23}, 1, 0},
    {"sxchg 253, r29, 1", {0x2FFEC01D}, 1, 0},
    {"zero &r0, 8", {0x2EFF8380}, 1, 0},
    {"zero 4, 120", {0x2EFFBB81}, 1, 0},
    {"zero &r1.b1, 3", {0x2EFF8121}, 1, 0},
    {"fill &r2, 4", {0x2EFF0182}, 1, 0},
    {"fill 0, 124", {0x2EFF3D80}, 1, 0},
    {"lbbo r2, r1, 5, 8", {0xF1056182}, 1, 0},
    {"lbbo &r2, r1, r3.w0, b0", {0xFE83C102}, 1, 0},
    {"lbbo r2.w1, r1, 255, 1", {0xF1FF0122}, 1, 0},
    {"sbbo r2.b1, r1, 0, 124", {0xEF00A1A2}, 1, 0},
    {"sbbo 17, r5, r6.b2, b1", {0xEE46C5A4}, 1, 0},
    {"lbco r3, c24, 0, 4", {0x91003883}, 1, 0},
    {"lbco r0.b3, c0, r1.w2, 2", {0x90C100E0}, 1, 0},
    {"sbco r3, c31, r4, b3", {0x8EE4FF83}, 1, 0},
    {"mvib r2, *r1.b0", {0x2C2001E2}, 1, 0},
    {"mvid *r1.b0++, r14", {0x2D02EE01}, 1, 0},
    {"mvid *--r1.b0, r14", {0x2D82EE01}, 1, 0},
    {"mviw *r1.b1, *r1.b2++", {0x2CC14121}, 1, 0},
    {"mvib *&r3, *r1.b3", {0x2C206103}, 1, 0},
    {"mvib r2, r3", {0x100303E2}, 1, 0},
    {"mviw r2, r3", {0x108383E2}, 1, 0},
    {"mvid r2, r3", {0x10E3E3E2}, 1, 0},
    {"mvib r2, r3.w2", {0x104343E2}, 1, 0},
    {"loop e, 5\nadd r1, r1, 1\ne:", {0x31040002, 0x0101E1E1}, 2, 0},
    {"loop e, r2.b0\nsub r2, r2, 1\ne:", {0x30020002, 0x0501E2E2}, 2, 0},
    {"iloop e, 256\nadd r0, r0, r0\ne:", {0x31FF8002, 0x00E0E0E0}, 2, 0},
    {"loop e, 1\nadd r0, r0, r0\ne:", {0x31000002, 0x00E0E0E0}, 2, 0},
    {"b: qbgt b, r1, r2", {0x60E2E100}, 1, 0},
    {"qbge f, r1.b0, 0xff\nhalt\nf:", {0x71FF0102, 0x2A000000}, 2, 0},
    {"b: halt\nqblt b, r1.w1, r0", {0x2A000000, 0x4EE0A1FF}, 2, 0},
    {"b: halt\nhalt\nhalt\nhalt\nqbeq b, r1, 0", {0x5700E1FC}, 5, 1},
    {"qble f, r1, r2\n.origin 8\nf:", {0x00000000}, 8, 1},
    {"qbne f, r1, r2.w1\n.origin 6\nf:", {0x00000000}, 6, 1},
    {"b: halt\nhalt\nhalt\nhalt\nhalt\nhalt\nqba b", {0x7F0000FA}, 7, 1},
    {"qba f\n.origin 511\nf:", {0x00000000}, 511, 1},
    {"b: .origin 512\nqba b", {0x7D000000}, 513, 1},
    {"b: halt\nhalt\nhalt\nhalt\nhalt\nhalt\nhalt\nqbbs b, r31, 30", {0xD71EFFF9}, 8, 1},
    {"qbbc f, r31.t31\nhalt\nhalt\nf:", {0xC91FFF03, 0x2A000000, 0x2A000000}, 3, 0},
    {"qbbs f, r5.w1.t15\nf:", {0xD10FA501}, 1, 0},
    {"b: qbbc b, r5, r6", {0xC8E6E500}, 1, 0},
    {"wbs r31.t30", {0xC91EFF00}, 1, 0},
    {"wbc r31, 3", {0xD103FF00}, 1, 0},
    {"wbs r1.b2.t7", {0xC9074100}, 1, 0},
    {"wbc r1, r2.b0", {0xD002E100}, 1, 0},
    {".codeword 0xdeadbeef", {0xDEADBEEF}, 1, 0},
    {".codeword 8>>1+1", {0x00000002}, 1, 0},
    {".codeword 10-2-3", {0x00000005}, 1, 0},
    {".codeword -1&0xff", {0x000000FF}, 1, 0},
    {".codeword 017", {0x0000000F}, 1, 0},
    {".codeword 0b101", {0x00000005}, 1, 0},
    {".codeword (~(1<<3))&0xff", {0x000000F7}, 1, 0},
    {".codeword 7%3*5", {0x00000005}, 1, 0},
    {".codeword -1", {0xFFFFFFFF}, 1, 0},
    {".codeword 0xffffffff+2", {0x00000001}, 1, 0},
    {".codeword 1<<33", {0x00000002}, 1, 0},
    {".codeword 100/7", {0x0000000E}, 1, 0},
    {".codeword 6^5", {0x00000003}, 1, 0},
    {".codeword --5", {0x00000005}, 1, 0},
};

START_TEST(encodes_like_pasm) {
    const struct enc *e = &table[_i];
    char src[512];
    uint32_t w[600];
    snprintf(src, sizeof src, ".origin 0\n%s\n", e->src);
    size_t n = asm_words(src, w, 600);
    ck_assert_msg(n == e->n, "%s: %zu words, want %zu", e->src, n, e->n);
    if (e->tail) {
        ck_assert_msg(w[n - 1] == e->words[0], "%s: last word 0x%08x, want 0x%08x", e->src,
                      (unsigned)w[n - 1], (unsigned)e->words[0]);
        return;
    }
    for (size_t i = 0; i < n; i++)
        ck_assert_msg(w[i] == e->words[i], "%s: word %zu is 0x%08x, want 0x%08x", e->src, i,
                      (unsigned)w[i], (unsigned)e->words[i]);
}
END_TEST

/* Mnemonics, register names and field suffixes are case-insensitive. */
START_TEST(case_insensitive) {
    uint32_t a[4], b[4];
    asm_words(".origin 0\nADD R1.W1, R2.B3, 0xFF\nLbBo R2, R1, 5, 8\n", a, 4);
    asm_words(".origin 0\nadd r1.w1, r2.b3, 0xff\nlbbo r2, r1, 5, 8\n", b, 4);
    ck_assert_uint_eq(a[0], b[0]);
    ck_assert_uint_eq(a[1], b[1]);
}
END_TEST

/* The default origin is 8: eight zero words come first. */
START_TEST(default_origin) {
    uint32_t w[16];
    size_t n = asm_words("start: add r1, r2, r3\nhalt\n", w, 16);
    ck_assert_uint_eq(n, 10);
    for (int i = 0; i < 8; i++)
        ck_assert_uint_eq(w[i], 0);
    ck_assert_uint_eq(w[8], 0x00E3E2E1);
    ck_assert_uint_eq(w[9], 0x2A000000);
}
END_TEST

/* Core versions: SLP gets a trailing no-op before V3, ZERO is LDIs on V1. */
START_TEST(core_versions) {
    struct pruasm_options o = {.core = 2};
    struct pruasm_image img;
    struct pruasm_diag d = {0};
    ck_assert_int_eq(pruasm_assemble_string(&o, "t.p", ".origin 0\nslp 1\n", &img, &d), 0);
    ck_assert_uint_eq(img.nwords, 2);
    ck_assert_uint_eq(img.words[0], 0x3E800000);
    ck_assert_uint_eq(img.words[1], 0x10000000);
    pruasm_image_free(&img);
    o.core = 1;
    ck_assert_int_eq(pruasm_assemble_string(&o, "t.p", ".origin 0\nzero &r1.b1, 7\n", &img, &d), 0);
    ck_assert_uint_eq(img.nwords, 3); /* r1.w1 (bytes 1-2), r1.b3, r2.w0 */
    ck_assert_uint_eq(img.words[0], 0x240000A1);
    ck_assert_uint_eq(img.words[1], 0x24000061);
    ck_assert_uint_eq(img.words[2], 0x240000E2);
    pruasm_image_free(&img);
    ck_assert_int_ne(pruasm_assemble_string(&o, "t.p", ".origin 0\nloop x, 2\nx:\n", &img, &d), 0);
    ck_assert_str_eq(d.first_error,
                     "t.p:2: Error: Instruction illegal with specified core version");
}
END_TEST

/* -E (big-endian core): register-file byte numbering flips for &reg, burst
 * start bytes, MVI addresses, ZERO and structure fields (checked with pasm
 * 0.87 -V3 -E). */
START_TEST(big_endian) {
    static const char src[] = ".origin 0\nzero &r1.b1, 7\nzero 0, 11\nzero 2,2\nzero 3,1\n"
                              "mvib *&r3.b1, *r1.b3\nmviw *&r3.w1, *r1.b3\nldi r1, &r2.b0\n"
                              "ldi r1, &r2.w1\nldi r1, &r2.w1.b0\nlbbo r2.b0, r1, 0, 4\n"
                              "lbbo r2.w0, r1, 0, 4\nlbbo r2.b2, r1, 0, 4\n"
                              ".struct S\n.u8 a\n.u16 b\n.u8 c\n.u32 d\n.ends\n"
                              ".assign S, r4, r5, s\nmov s.a, 1\nmov s.b, 2\nmov s.c, 3\n"
                              "mov s.d, 4\nldi r1, OFFSET(s.b.b1)\nldi r1, OFFSET(s.d.w0)\n"
                              "ldi r1, OFFSET(S.d.b3)\n";
    static const uint32_t want[] = {0x2eff8341, 0x2eff8500, 0x2eff80c0, 0x2eff8060, 0x2c206123,
                                    0x2c2161a3, 0x24000be1, 0x240009e1, 0x24000ae1, 0xf10021e2,
                                    0xf10021c2, 0xf10021a2, 0x24000164, 0x240002a4, 0x24000304,
                                    0x240004e5, 0x240001e1, 0x240006e1, 0x240004e1};
    struct pruasm_options o = {.core = 3, .big_endian = 1};
    struct pruasm_image img;
    struct pruasm_diag d = {0};
    ck_assert_int_eq(pruasm_assemble_string(&o, "be.p", src, &img, &d), 0);
    ck_assert_uint_eq(img.nwords, sizeof want / sizeof want[0]);
    for (size_t i = 0; i < img.nwords; i++)
        ck_assert_msg(img.words[i] == want[i], "word %zu is 0x%08x", i, (unsigned)img.words[i]);
    pruasm_image_free(&img);
}
END_TEST

static Suite *suite(void) {
    Suite *s = suite_create("asm_encode");
    TCase *tc = tcase_create("encode");
    tcase_add_loop_test(tc, encodes_like_pasm, 0, (int)(sizeof table / sizeof table[0]));
    tcase_add_test(tc, case_insensitive);
    tcase_add_test(tc, default_origin);
    tcase_add_test(tc, core_versions);
    tcase_add_test(tc, big_endian);
    suite_add_tcase(s, tc);
    return s;
}

int main(void) {
    return check_run(suite());
}
