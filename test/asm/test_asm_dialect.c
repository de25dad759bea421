/*
 * test_asm_dialect.c - the pasm source dialect (docs/pru-facts.md
 * §2): comments, #define and conditionals, -D, labels, .origin,
 * .entrypoint, macros with label renaming, structures, scopes, SIZE/OFFSET,
 * .setcallreg, .codeword, .proc, &register, #include with "" and <>, and the
 * in-process API. Expected words were checked against pasm 0.87 -V3.
 */
#include "check_run.h"

#include <check.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "asm_test_util.h"

struct prog {
    const char *name;
    const char *src;
    const char *defines[4];
    uint32_t words[16];
};

static const struct prog progs[] = {
    {"comments",
     ".origin 0\n"
     "// line comment\n"
     "ldi r1, 1 // trailing\n"
     "ldi r2, 2 ; semicolon\n"
     "/* block\n"
     "   over lines */ldi r3, 3\n"
     "ldi r4, /* mid */ 4\n"
     "add r1, r1, \\\n"
     "    5\n"
     "",
     {},
     {0x240001E1, 0x240002E2, 0x240003E3, 0x240004E4, 0x0105E1E1}},
    {"equates",
     ".origin 0\n"
     "#define TWO 2\n"
     "#define FOUR TWO*2\n"
     "#define NOPX mov r0, r0\n"
     "#define REG r5.w1\n"
     "ldi REG, FOUR+1\n"
     "NOPX\n"
     "#undef TWO\n"
     "#define TWO 7\n"
     "ldi r1, TWO\n"
     "#define EMPTY\n"
     "ldi r2, EMPTY\n"
     "",
     {},
     {0x240005A5, 0x10E0E0E0, 0x240007E1, 0x240001E2}},
    {"cmdline",
     ".origin 0\n"
     "ldi r1, VAL\n"
     "#ifdef FLAG\n"
     "ldi r2, 1\n"
     "#else\n"
     "ldi r2, 2\n"
     "#endif\n"
     "#ifndef FLAG\n"
     "ldi r3, 3\n"
     "#endif\n"
     "",
     {"VAL=0x42", "FLAG"},
     {0x240042E1, 0x240001E2}},
    {"nested_if",
     ".origin 0\n"
     "#define A\n"
     "#ifdef A\n"
     "#ifdef B\n"
     "ldi r1, 1\n"
     "#else\n"
     "ldi r1, 2\n"
     "#endif\n"
     "#else\n"
     "#ifdef A\n"
     "ldi r1, 3\n"
     "#endif\n"
     "#endif\n"
     "",
     {},
     {0x240002E1}},
    {"labels",
     "start: ldi r1, start\n"
     "next: ldi r2, next\n"
     "qba start\n"
     "jmp fwd\n"
     "fwd: halt\n"
     "",
     {},
     {0x00000000, 0x00000000, 0x00000000, 0x00000000, 0x00000000, 0x00000000, 0x00000000,
      0x00000000, 0x240008E1, 0x240009E2, 0x7F0000FE, 0x21000C00, 0x2A000000}},
    {"origin",
     ".origin 4\n"
     ".entrypoint main\n"
     "main: halt\n"
     ".origin 10\n"
     "ldi r1, main\n"
     "",
     {},
     {0x00000000, 0x00000000, 0x00000000, 0x00000000, 0x2A000000, 0x00000000, 0x00000000,
      0x00000000, 0x00000000, 0x00000000, 0x240004E1}},
    {"macro",
     ".origin 0\n"
     ".macro wait\n"
     ".mparam cnt, reg=r20\n"
     "    ldi reg, cnt\n"
     "lp: sub reg, reg, 1\n"
     "    qbne lp, reg, 0\n"
     ".endm\n"
     "wait 10\n"
     "wait 20, r21\n"
     "ldi r1, _lp_0_2_\n"
     "",
     {},
     {0x24000AF4, 0x0501F4F4, 0x6F00F4FF, 0x240014F5, 0x0501F5F5, 0x6F00F5FF, 0x240004E1}},
    {"macro_nested",
     ".origin 0\n"
     ".macro inner\n"
     ".mparam x\n"
     " add x, x, 1\n"
     ".endm\n"
     ".macro outer\n"
     ".mparam y\n"
     " inner y\n"
     " inner y\n"
     ".endm\n"
     "outer r3\n"
     "",
     {},
     {0x0101E3E3, 0x0101E3E3}},
    {"struct",
     ".origin 0\n"
     ".struct Frame\n"
     "    .u32 pos\n"
     "    .u16 crc\n"
     "    .u8  flags\n"
     "    .u8  status\n"
     ".ends\n"
     ".assign Frame, r10, r11, fr\n"
     "mov fr.pos, r1\n"
     "mov fr.crc, 0x1234\n"
     "mov fr.flags, 3\n"
     "ldi r1, SIZE(Frame)\n"
     "ldi r1, OFFSET(Frame.status)\n"
     "ldi r1, SIZE(fr.crc)\n"
     "ldi r1, OFFSET(fr.pos.w2)\n"
     "ldi r1, SIZE(r2.w1)\n"
     "mov r1, fr.crc.b1\n"
     "set fr.flags.t3\n"
     "",
     {},
     {0x10E1E1EA, 0x2412348B, 0x2400034B, 0x240008E1, 0x240007E1, 0x240002E1, 0x240002E1,
      0x240002E1, 0x102B2BE1, 0x1F034B4B}},
    {"scopes",
     ".origin 0\n"
     ".struct P\n"
     ".u16 a\n"
     ".u16 b\n"
     ".ends\n"
     ".enter S1\n"
     ".assign P, r4, *, p\n"
     "mov p.b, 1\n"
     ".leave S1\n"
     ".enter S2\n"
     ".assign P, r6.w0, r6.w2, p\n"
     "mov p.b, 2\n"
     ".leave S2\n"
     ".using S1\n"
     "mov p.a, 3\n"
     ".leave S1\n"
     "",
     {},
     {0x240001C4, 0x240002C6, 0x24000384}},
    {"callreg",
     ".setcallreg r29.w2\n"
     ".origin 0\n"
     "s: call s\n"
     "ret\n"
     "call r3.w0\n"
     "",
     {},
     {0x230000DD, 0x20DD0000, 0x228300DD}},
    {"codeword",
     ".origin 0\n"
     ".codeword 0xdeadbeef\n"
     ".codeword 017+0b11\n"
     ".codeword -2\n"
     "",
     {},
     {0xDEADBEEF, 0x00000012, 0xFFFFFFFE}},
    {"proc",
     ".origin 0\n"
     ".proc myproc\n"
     "jmp .myproc\n"
     ".main \"proc.p\"\n"
     ".end\n"
     "",
     {},
     {0x21000000}},
    {"amp",
     ".origin 0\n"
     "ldi r1, &r3.w1\n"
     "mov r2, &r31.b3\n"
     "zero &r2.b1, 3\n"
     "lbbo &r4, r1, 0, 4\n"
     "xin 10, &r5.w1, 2\n"
     "",
     {},
     {0x24000DE1, 0x24007FE2, 0x2EFF8122, 0xF1002184, 0x2E8500A5}},
};

static size_t count_defines(const struct prog *p) {
    size_t n = 0;
    while (n < 4 && p->defines[n])
        n++;
    return n;
}

START_TEST(program_words) {
    const struct prog *p = &progs[_i];
    struct pruasm_options opt = {.core = 3, .defines = p->defines, .ndefines = count_defines(p)};
    struct pruasm_image img;
    struct pruasm_diag diag = {0};
    char name[64];
    snprintf(name, sizeof name, "%s.p", p->name);
    int rc = pruasm_assemble_string(&opt, name, p->src, &img, &diag);
    ck_assert_msg(rc == 0, "%s: %s", p->name, diag.first_error);
    size_t want = 16;
    while (want > 0 && p->words[want - 1] == 0)
        want--;
    ck_assert_uint_ge(img.nwords, want);
    for (size_t i = 0; i < img.nwords; i++)
        ck_assert_msg(img.words[i] == (i < 16 ? p->words[i] : 0), "%s: word %zu = 0x%08x", p->name,
                      i, (unsigned)img.words[i]);
    pruasm_image_free(&img);
}
END_TEST

START_TEST(entry_point) {
    struct pruasm_image img;
    struct pruasm_diag d = {0};
    ck_assert_int_eq(asm_text(".origin 4\n.entrypoint main\nhalt\nmain: halt\n", &img, &d), 0);
    ck_assert_int_eq(img.entry_point, 5);
    pruasm_image_free(&img);
    ck_assert_int_eq(asm_text(".origin 3\nhalt\n", &img, &d), 0);
    ck_assert_int_eq(img.entry_point, 3);
    pruasm_image_free(&img);
    ck_assert_int_eq(asm_text("halt\n", &img, &d), 0);
    ck_assert_int_eq(img.entry_point, 8);
    ck_assert_int_eq(d.warnings, 1); /* "Using default code origin of 8" */
    pruasm_image_free(&img);
}
END_TEST

/* Labels inside a macro become _<label>_<macro id>_<use>_ (checked with pasm). */
START_TEST(macro_label_names) {
    struct pruasm_options opt = {.core = 3, .want_listing = 1};
    struct pruasm_image img;
    struct pruasm_diag d = {0};
    const char *src = ".origin 0\n.macro a\nx: halt\n.endm\n.macro b\ny: halt\n.endm\n"
                      "b\nb\na\n";
    ck_assert_int_eq(pruasm_assemble_string(&opt, "m.p", src, &img, &d), 0);
    ck_assert_ptr_nonnull(strstr(img.listing, "m.p(    8) : 0x0000 = Label      : _y_1_1_:\n"));
    ck_assert_ptr_nonnull(strstr(img.listing, "m.p(    9) : 0x0001 = Label      : _y_1_2_:\n"));
    ck_assert_ptr_nonnull(strstr(img.listing, "m.p(   10) : 0x0002 = Label      : _x_0_1_:\n"));
    pruasm_image_free(&img);
}
END_TEST

START_TEST(includes) {
    const char *dir = asm_tmpdir("inc");
    char sub[1100], path[1200];
    snprintf(sub, sizeof sub, "%s/sys", dir);
    asm_write(dir, "local.hp", "#define LOCAL 5\n");
    ck_assert_int_eq(system((snprintf(path, sizeof path, "mkdir -p '%s'", sub), path)), 0);
    asm_write(sub, "sys.hp",
              "#ifndef SYS_HP\n#define SYS_HP\n.macro inc1\n.mparam r\n"
              "add r, r, 1\n.endm\n#endif\n");
    asm_write(dir, "main.p",
              ".origin 0\n#include \"local.hp\"\n#include <sys.hp>\n"
              "#include <sys.hp>\nldi r1, LOCAL\ninc1 r1\n");
    const char *inc[] = {sub};
    struct pruasm_options opt = {.core = 3, .include_dirs = inc, .ninclude_dirs = 1};
    struct pruasm_image img;
    struct pruasm_diag d = {0};
    snprintf(path, sizeof path, "%s/main.p", dir);
    ck_assert_int_eq(pruasm_assemble_file(&opt, path, &img, &d), 0);
    ck_assert_uint_eq(img.nwords, 2);
    ck_assert_uint_eq(img.words[0], 0x240005E1);
    ck_assert_uint_eq(img.words[1], 0x0101E1E1);
    pruasm_image_free(&img);

    /* Without -I the <> include is not found. */
    opt.ninclude_dirs = 0;
    ck_assert_int_ne(pruasm_assemble_file(&opt, path, &img, &d), 0);
    ck_assert_str_eq(d.first_error,
                     "main.p:3: Fatal Error: Could not find 'sys.hp' in include paths");
}
END_TEST

/* The string API and the file API agree; the diag callback sees messages. */
static int seen;
static void count_msg(void *ctx, enum pruasm_level level, const char *file, unsigned line,
                      const char *text) {
    (void)ctx;
    (void)file;
    (void)line;
    (void)text;
    if (level == PRUASM_WARNING)
        seen++;
}

START_TEST(api_basics) {
    struct pruasm_image img;
    struct pruasm_diag d = {.emit = count_msg};
    seen = 0;
    ck_assert_int_eq(pruasm_assemble_string(NULL, NULL, "halt\n", &img, &d), 0);
    ck_assert_int_eq(seen, 1);
    ck_assert_uint_eq(img.nwords, 9);
    ck_assert_ptr_null(img.listing);
    pruasm_image_free(&img);
    pruasm_image_free(&img); /* safe twice */
    /* No code at all is a failure, as in pasm (exit status 1). */
    ck_assert_int_ne(pruasm_assemble_string(NULL, "e.p", "// nothing\n", &img, NULL), 0);
    ck_assert_int_ne(pruasm_assemble_string(NULL, "e.p", "", &img, &d), 0);
    ck_assert_str_eq(d.first_error, "No code generated");
}
END_TEST

static Suite *suite(void) {
    Suite *s = suite_create("asm_dialect");
    TCase *tc = tcase_create("dialect");
    tcase_add_loop_test(tc, program_words, 0, (int)(sizeof progs / sizeof progs[0]));
    tcase_add_test(tc, entry_point);
    tcase_add_test(tc, macro_label_names);
    tcase_add_test(tc, includes);
    tcase_add_test(tc, api_basics);
    suite_add_tcase(s, tc);
    return s;
}

int main(void) {
    return check_run(suite());
}
