/*
 * test_asm_errors.c - error messages (file:line: Error: text, as pasm 0.87
 * prints them; each expected text was checked against pasm) and malformed
 * input of every kind: binary junk, a 1 MB line, include and macro
 * recursion, deep #define chains, out-of-range values. Each must end in a
 * clear error, never a crash, a hang or an image.
 */
#include "check_run.h"

#include <check.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "asm_test_util.h"

struct err {
    const char *src;
    const char *first_error;
};

static const struct err errs[] = {
    {".origin 0\nadd r1, r2\nhalt\n", "t.p:2: Error: Expected 3 operands"},
    {".origin 0\nadd r1, r2, 256\nhalt\n",
     "t.p:2: Error: Operand 3 immediate value out of range (0-255)"},
    {".origin 0\nsub r1, r1, -1\nhalt\n",
     "t.p:2: Error: Operand 3 immediate value out of range (0-255)"},
    {".origin 0\nadd r32, r1, r2\nhalt\n",
     "t.p:2: Error: Operand 1 'r32' invalid register or register mode"},
    {".origin 0\nadd r1.w3, r1, r2\nhalt\n",
     "t.p:2: Error: Operand 1 'r1.w3' invalid register or register mode"},
    {".origin 0\nfoo r1, r2\nhalt\n", "t.p:2: Error: Invalid opcode"},
    {".origin 0\nnop\nhalt\n", "t.p:2: Error: Invalid opcode"},
    {".origin 0\nqba nowhere\nhalt\n", "t.p:2: Error: Not found: 'nowhere'"},
    {".origin 0\nlbbo r1, r2.w0, 0, 4\nhalt\n",
     "t.p:2: Error: Register fields not allowed on operand 2"},
    {".origin 0\nlbbo r1, r2, 0, r0.b0\nhalt\n",
     "t.p:2: Error: Operand 4 invalid byte count 'r0.b0'"},
    {".origin 0\nlbbo r1, r2, 0, 125\nhalt\n",
     "t.p:2: Error: Operand 4 immediate value out of range (1-124)"},
    {".origin 0\nxin 254, r1, 4\nhalt\n",
     "t.p:2: Error: Operand 1 immediate value out of range (0-253)"},
    {".origin 0\nxin 10, r31, 4\nhalt\n", "t.p:2: Error: Operand 2 R31 is illegal"},
    {".origin 0\nloop x, 0\nadd r0,r0,r0\nx:\nhalt\n", "t.p:2: Error: Null loop count"},
    {".origin 0\nloop x, 5\nx:\nhalt\n", "t.p:2: Error: Operand 1 invalid loop termination point"},
    {".origin 0\nldi r1, 65536\nhalt\n",
     "t.p:2: Error: Operand 2 immediate value out of range (0-65535)"},
    {".origin 0\nmov r1.b0, 256\nhalt\n",
     "t.p:2: Error: Operand 2 immediate value out of range (0-255)"},
    {".origin 0\nclr r1.b0.t8\nhalt\n",
     "t.p:2: Error: Operand 1 'r1.b0.t8' invalid register or register mode"},
    {".origin 0\nclr r1, 32\nhalt\n",
     "t.p:2: Error: Operand 2 immediate value out of range (0-31)"},
    {".origin 0\nldi r1, 5/0\nhalt\n", "t.p:2: Error: Divide by zero"},
    {".origin 0\nx: halt\nx: halt\nhalt\n", "t.p:3: Error: 'x' is already a label"},
    {".origin 0\n#define A 1\n#define A 1\nhalt\n", "t.p:3: Error: 'A' is already an equate"},
    {".origin 0\n#error custom message here\nhalt\n", "t.p:2: Error: custom message here"},
    {".origin 0\n#include \"nofile.h\"\nhalt\n",
     "t.p:2: Fatal Error: Can't open source file './nofile.h'"},
    {".origin 0\n#foo\nhalt\n", "t.p:2: Error: Unknown # directive"},
    {".origin 0\n#ifdef A\nhalt\nhalt\n", "t.p:4: Error: #endif mismatch in file"},
    {".origin 0\n#endif\nhalt\n", "t.p:2: Error: #endif without corresponding #if"},
    {".origin 0\nand r3.b0, r3.b0, ~(1<<3)\nhalt\n", "t.p:2: Error: Syntax error in parameter 3"},
    {".origin 0\nldi r1, $\nhalt\n", "t.p:2: Error: Syntax error in parameter 2"},
    {".origin 0\nldi r1, 0X10\nhalt\n", "t.p:2: Error: Operand 2 error in expression"},
    {".origin 0\n.macro m\n.mparam a\nm a\n.endm\nm r1\nhalt\n",
     "t.p:6: Error: Illegal recursive use of macro 'm'"},
    {".origin 0\n.macro m\nadd r1, r1, 1\nhalt\n", "t.p:4: Error: Missing .endm on macro"},
    {".origin 0\n.struct S\n.u32 a\n.ends\n.assign S, r1.b1, *, s\n\nhalt\n",
     "t.p:5: Error: Register alignment error on element 1"},
    {".origin 0\n.struct S\n.u16 a\n.u32 b\n.ends\n.assign S, r1, *, s\n\nhalt\n",
     "t.p:6: Error: Register alignment error on element 2"},
    {".origin 0\n.struct S\n.u32 a\n.ends\n.assign S, r1, r3, s\n\nhalt\n",
     "t.p:5: Error: Range error, parameter 3 should be 'R1'"},
    {".origin 0\nhalt\n.origin 0\nhalt\n",
     "t.p:3: Error: .origin value is less than current offset"},
    {".origin 0\nhalt\n.setcallreg r1.w0\nhalt\n",
     "t.p:3: Error: Can not use .setcallreg after code generation"},
    {".origin 0\n.setcallreg r1.b0\nhalt\n",
     "t.p:2: Error: Can not use .setcallreg after code generation"},
    {".origin 0\n.ret\nhalt\n", "t.p:2: Error: .ret illegal with specified core version, use ret"},
    {".origin 0\nqbbs x, r1.t3, 4\nx:\nhalt\n",
     "t.p:2: Error: Three operand mode may not use .T field"},
    {".origin 0\nwbs r1\nhalt\n", "t.p:2: Error: Two operand mode must specify .T field"},
    {".origin 0\nset r1\nhalt\n", "t.p:2: Error: Single operand mode must specify .T field"},
    {".origin 0\nldi r1, undefined_label\nhalt\n", "t.p:2: Error: Not found: 'undefined_label'"},
    {".origin 0\njmp 70000\nhalt\n",
     "t.p:2: Error: Operand 1 immediate value out of range (0-65535)"},
    {".origin 0\nx: qba y\n.origin 600\ny: halt\nhalt\n",
     "t.p:2: Error: Operand 1 relative jump out of range"},
    {".origin 0\nadd r1, r2, r3, r4\nhalt\n", "t.p:2: Error: Expected 3 operands"},
    {".origin 0\na: b: halt\nhalt\n", "t.p:2: Error: Two labels found on the same line"},
    {".origin 0\nldi r1, \"str\"\nhalt\n", "t.p:2: Error: Operand 2 error in expression"},
    {".origin 0\nhalt r1\nhalt\n", "t.p:2: Error: Expected no operands"},
    {".origin 0\nslp 2\nhalt\n", "t.p:2: Error: Operand 1 immediate value out of range (0-1)"},
    {".origin 0\nzero 120, 8\nhalt\n", "t.p:2: Error: Clear length exceeds register file length"},
    {".origin 0\nfill &r0, 0\nhalt\n", "t.p:2: Error: Zero length fill"},
    {".origin 0\nmvib r1, r2, b0\nhalt\n",
     "t.p:2: Error: 3 operand mode not supported on this core"},
    {".origin 0\nmvib *r2.b0, r3\nhalt\n",
     "t.p:2: Error: RegFile pointers must be R1.b0 through R1.b3"},
    {".origin 0\n.foo 1\nhalt\n", "t.p:2: Error: Unrecognized dot command"},
    {".origin 0\n.mparam x\nhalt\n", "t.p:2: Error: .mparam can not be used outside of macro"},
    {".origin 0\n.u32 x\nhalt\n", "t.p:2: Error: Can not add element - missing .struct"},
    {".origin 0\n.ends\nhalt\n", "t.p:2: Error: Structure .struct/.ends mismatch"},
    {".origin 0\nlbco r1, c32, 0, 4\nhalt\n",
     "t.p:2: Error: Operand 2 invalid constant table entry 'c32'"},
    {".origin 0\nadd r1, r2, c5\nhalt\n",
     "t.p:2: Error: Operand 3 'c5' invalid register or register mode"},
    {".origin 0\nldi r1, r2\nhalt\n", "t.p:2: Error: Operand 2 reserved word 'r2' not legal here"},
    {".origin 0\nldi r1, (1+2\nhalt\n", "t.p:2: Error: Operand 2 error in expression"},
    {".origin 0\nldi r1, 1 2\nhalt\n", "t.p:2: Error: Operand 2 error in expression"},
    {".origin 0\nr5: halt\nhalt\n", "t.p:2: Error: Illegal use of reserved word 'r5'"},
    {".origin 0\nadd: halt\nhalt\n", "t.p:2: Error: Illegal use of reserved word 'add'"},
    {".origin 0\nadd r1, , r2\nhalt\n", "t.p:2: Error: Syntax error in parameter 2"},
    {".origin 0\nhalt ; comment\n\n  \n add r1, r1, 1 // x\n ldi r1, 1)\n\nhalt\n",
     "t.p:6: Error: Operand 2 error in expression"},
    {".origin 0\n#define X\nldi r1, X\n#define Y 5\n#undef Y\nldi r2, Y\nhalt\n",
     "t.p:6: Error: Not found: 'Y'"},
    {".origin 0\n.macro m\n.mparam a, b=5\nadd r1, a, b\n.endm\nm\nm r2, 3, 4\nhalt\n",
     "t.p:6: Error: Expected at least 1 arguments on 'm'"},
    {".origin 0\n.macro m\n.mparam a=1, b\n.endm\nhalt\n",
     "t.p:3: Error: Optional macro arguments must be listed last"},
    {".origin 0\n.entrypoint 5\n.entrypoint 6\nhalt\nhalt\n",
     "t.p:3: Error: Multiple .entrypoint declarations"},
    {".origin 0\n.struct S\n.struct T\nhalt\n", "t.p:3: Error: Structure can not be nested"},
    {".origin 0\n.leave nope\nhalt\n", "t.p:2: Error: Scope name undefined"},
    {".origin 0\n.enter s1\n.enter s1\nhalt\n",
     "t.p:3: Error: 's1' is already a structure or scope"},
    {".origin 0\nldi r1, SIZE(nope)\nhalt\n",
     "t.p:2: Error: Operand 1 'nope' invalid register or register mode"},
    {".origin 0\nldi r1, SIZE nope\nhalt\n", "t.p:2: Error: Missing '(' on SIZE/OFFSET"},
    {".origin 0\n.codeword\nhalt\n", "t.p:2: Error: Expected 1 operand"},
};

START_TEST(first_error_text) {
    ck_assert_str_eq(asm_error(errs[_i].src), errs[_i].first_error);
}
END_TEST

START_TEST(binary_junk) {
    char buf[20001];
    unsigned seed = 12345u + (unsigned)_i;
    for (size_t i = 0; i < sizeof buf - 1; i++) {
        seed = seed * 1103515245u + 12345u;
        buf[i] = (char)((seed >> 16) & 0xff);
        if (!buf[i])
            buf[i] = 1; /* the string API stops at NUL; NUL is tested below */
    }
    buf[sizeof buf - 1] = 0;
    const char *e = asm_error(buf);
    ck_assert_ptr_nonnull(strstr(e, "Error"));
}
END_TEST

START_TEST(nul_bytes_in_file) {
    const char *dir = asm_tmpdir("nul");
    char path[1200];
    snprintf(path, sizeof path, "%s/n.p", dir);
    FILE *fp = fopen(path, "wb");
    ck_assert_ptr_nonnull(fp);
    static const char text[] = ".origin 0\nhalt\0\0\0junk\nhalt\n\0\xff\xfe";
    fwrite(text, 1, sizeof text - 1, fp);
    fclose(fp);
    struct pruasm_image img;
    struct pruasm_diag d = {0};
    ck_assert_int_ne(pruasm_assemble_file(NULL, path, &img, &d), 0);
    ck_assert_ptr_nonnull(strstr(d.first_error, "n.p:"));
}
END_TEST

/* pasm reads bytes as signed chars, so 0xff acts as end of file: it ends a
 * line, at the start of a line it ends the file, and in a block comment it
 * stops the scan like '*' does (checked with pasm 0.87). */
START_TEST(ff_byte_like_pasm) {
    uint32_t w[4];
    ck_assert_uint_eq(asm_words(".origin 0\nhalt\xffldi r1, 2\n\xffjunk junk\n", w, 4), 2);
    ck_assert_uint_eq(w[0], 0x2A000000);
    ck_assert_uint_eq(w[1], 0x240002E1);
    ck_assert_uint_eq(asm_words(".origin 0\n/* a \xff/ldi r1, 3\n", w, 4), 1);
    ck_assert_uint_eq(w[0], 0x240003E1);
}
END_TEST

START_TEST(megabyte_line) {
    size_t n = 1u << 20;
    char *src = malloc(n + 64);
    ck_assert_ptr_nonnull(src);
    strcpy(src, ".origin 0\nldi r1, ");
    size_t k = strlen(src);
    for (; k < n; k += 2)
        memcpy(src + k, "1+", 2);
    strcpy(src + k, "1\nhalt\n");
    ck_assert_str_eq(asm_error(src), "t.p:2: Error: Line too long");
    free(src);
}
END_TEST

START_TEST(long_statement_after_expansion) {
    /* Each use of X doubles the text: the expanded line overflows. */
    const char *src = ".origin 0\n#define A 1+1+1+1+1+1+1+1+1+1+1+1+1+1+1+1+1+1+1+1+1+1+1+1+1+1\n"
                      "#define B A+A+A+A+A+A+A+A+A+A+A+A+A+A+A+A+A+A+A+A+A+A+A+A+A+A+A+A\n"
                      "#define C B+B+B+B+B+B+B+B+B+B+B+B+B+B+B+B+B+B+B+B+B+B+B+B+B+B+B+B\n"
                      "ldi r1, C\nhalt\n";
    ck_assert_str_eq(asm_error(src), "t.p:5: Error: Line too long");
}
END_TEST

START_TEST(include_recursion) {
    const char *dir = asm_tmpdir("increc");
    char path[1200];
    asm_write(dir, "self.p", ".origin 0\n#include \"self.p\"\nhalt\n");
    snprintf(path, sizeof path, "%s/self.p", dir);
    struct pruasm_image img;
    struct pruasm_diag d = {0};
    ck_assert_int_ne(pruasm_assemble_file(NULL, path, &img, &d), 0);
    ck_assert_str_eq(d.first_error, "self.p:2: Fatal Error: Too many open files");
    ck_assert_int_ge(d.warnings, 4); /* "possible #include recursion" from 11 open files on */
}
END_TEST

START_TEST(macro_recursion) {
    ck_assert_str_eq(asm_error(".origin 0\n.macro a\nb\n.endm\n.macro b\na\n.endm\na\n"),
                     "t.p:8: Error: Illegal recursive use of macro 'a'");
}
END_TEST

START_TEST(deep_macros_and_equates) {
    /* 300 macros each using the next: deeper than the nesting bound. */
    static char src[64 * 1024];
    size_t k = (size_t)sprintf(src, ".origin 0\n");
    for (int i = 0; i < 300; i++)
        k += (size_t)sprintf(src + k, ".macro m%d\nm%d\n.endm\n", i, i + 1);
    k += (size_t)sprintf(src + k, ".macro m300\nhalt\n.endm\nm0\n");
    ck_assert_str_eq(asm_error(src), "t.p:905: Error: Macros nested too deeply at 'm256'");
    /* 2000 chained equates. */
    k = (size_t)sprintf(src, ".origin 0\n");
    for (int i = 0; i < 2000; i++)
        k += (size_t)sprintf(src + k, "#define E%d E%d\n", i, i + 1);
    sprintf(src + k, "ldi r1, E0\nhalt\n");
    ck_assert_str_eq(asm_error(src), "t.p:2002: Error: Equate 'E1024' nested too deeply");
}
END_TEST

START_TEST(unterminated_comment) {
    ck_assert_str_eq(asm_error(".origin 0\nhalt\n/* no end\nhalt\n"),
                     "t.p:4: Error: Unterminated /* comment");
}
END_TEST

START_TEST(out_of_range_values) {
    ck_assert_str_eq(asm_error(".origin 0x7fffffff\nhalt\n"),
                     "t.p:1: Fatal Error: Max program size exceeded");
    ck_assert_str_eq(asm_error(".origin 16383\nhalt\nhalt\n"),
                     "t.p:3: Fatal Error: Max program size exceeded");
    /* numbers wrap at 32 bits before the range check, as in pasm */
    ck_assert_str_eq(asm_error(".origin 0\nldi r1, 99999999999999999999\n"),
                     "t.p:2: Error: Operand 2 immediate value out of range (0-65535)");
    ck_assert_str_eq(asm_error(".origin 0\nmov r1.w0, 0x10000\n"),
                     "t.p:2: Error: Operand 2 immediate value out of range (0-65535)");
    ck_assert_str_eq(asm_error(".origin 0\nadd r99999999999999, r1, r1\n"),
                     "t.p:2: Error: Operand 1 'r99999999999999' invalid register or register mode");
    ck_assert_str_eq(asm_error(".origin 0\nqba x\n.origin 1000\nx: halt\n"),
                     "t.p:2: Error: Operand 1 relative jump out of range");
}
END_TEST

START_TEST(error_limit) {
    static char src[8192];
    size_t k = (size_t)sprintf(src, ".origin 0\n");
    for (int i = 0; i < 100; i++)
        k += (size_t)sprintf(src + k, "bogus%d\n", i);
    struct pruasm_image img;
    struct pruasm_diag d = {0};
    ck_assert_int_ne(asm_text(src, &img, &d), 0);
    ck_assert_int_eq(d.errors, 25); /* pasm gives up after 25 errors */
}
END_TEST

START_TEST(long_names) {
    static char src[4096];
    char name[200];
    memset(name, 'a', sizeof name - 1);
    name[sizeof name - 1] = 0;
    snprintf(src, sizeof src, ".origin 0\n%s: halt\n", name);
    ck_assert_str_eq(asm_error(src), "t.p:2: Error: Cmd/Opcode too long");
    snprintf(src, sizeof src, ".origin 0\nldi r1, %s\n", name);
    ck_assert_str_eq(asm_error(src), "t.p:2: Error: Parameter 2 too long");
    snprintf(src, sizeof src, ".origin 0\nadd r1, r1, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11\n");
    ck_assert_str_eq(asm_error(src), "t.p:2: Error: Too many parameters on line");
}
END_TEST

static Suite *suite(void) {
    Suite *s = suite_create("asm_errors");
    TCase *tc = tcase_create("messages");
    tcase_add_loop_test(tc, first_error_text, 0, (int)(sizeof errs / sizeof errs[0]));
    suite_add_tcase(s, tc);
    tc = tcase_create("robustness");
    tcase_add_loop_test(tc, binary_junk, 0, 20);
    tcase_add_test(tc, nul_bytes_in_file);
    tcase_add_test(tc, ff_byte_like_pasm);
    tcase_add_test(tc, megabyte_line);
    tcase_add_test(tc, long_statement_after_expansion);
    tcase_add_test(tc, include_recursion);
    tcase_add_test(tc, macro_recursion);
    tcase_add_test(tc, deep_macros_and_equates);
    tcase_add_test(tc, unterminated_comment);
    tcase_add_test(tc, out_of_range_values);
    tcase_add_test(tc, error_limit);
    tcase_add_test(tc, long_names);
    suite_add_tcase(s, tc);
    return s;
}

int main(void) {
    return check_run(suite());
}
