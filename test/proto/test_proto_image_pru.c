/* The PRU an image was assembled for, read from its words before it runs
 * (proto/biss_image_pru.c): both firmware images, the firmware source
 * assembled for either PRU, and start-ups written otherwise (another
 * register, a wider store, a value no LDI sets, a branch first). */
#include "biss_proto.h"
#include "pruasm.h"

#include "check_run.h"

#include <check.h>
#include <stdio.h>
#include <stdlib.h>

#ifndef FW_BIN_DIR
#error "FW_BIN_DIR must name the build's pru_fw"
#endif

static int pru_of_file(const char *path) {
    FILE *f = fopen(path, "rb");
    ck_assert_ptr_nonnull(f);
    static uint8_t buf[65536];
    size_t n = fread(buf, 1, sizeof buf, f);
    fclose(f);
    return biss_image_pru(buf, n);
}

static int pru_of_source(const char *text) {
    struct pruasm_options opt = {.core = 3};
    struct pruasm_image img;
    struct pruasm_diag diag = {0};
    ck_assert_msg(pruasm_assemble_string(&opt, "t.p", text, &img, &diag) == 0, "%s",
                  diag.first_error);
    int pru = biss_image_pru(img.words, img.nwords * 4);
    pruasm_image_free(&img);
    return pru;
}

START_TEST(test_firmware_images) {
    ck_assert_int_eq(pru_of_file(FW_BIN_DIR "/biss_master.bin"), 0);
    ck_assert_int_eq(pru_of_file(FW_BIN_DIR "/biss_master_pru1.bin"), 1);
    /* the source, assembled as biss-sim assembles it for a PRU */
    for (int pru = 0; pru < 2; pru++) {
        char def[16];
        snprintf(def, sizeof def, "PRU_NUM=%d", pru);
        const char *defs[] = {def};
        struct pruasm_options opt = {.core = 3, .defines = defs, .ndefines = 1};
        struct pruasm_image img;
        struct pruasm_diag diag = {0};
        ck_assert_msg(pruasm_assemble_file(&opt, FW_SRC_DIR "/pru_fw/biss_master.p", &img, &diag) ==
                          0,
                      "%s", diag.first_error);
        ck_assert_int_eq(biss_image_pru(img.words, img.nwords * 4), pru);
        /* a prefix that stops before the store tells nothing */
        ck_assert_int_eq(biss_image_pru(img.words, 4 * 8), -1);
        pruasm_image_free(&img);
    }
}
END_TEST

START_TEST(test_start_ups_written_otherwise) {
    /* any register, any order, other stores through C24 first */
    ck_assert_int_eq(pru_of_source("ldi r7, 1\nsbco r0, c24, 0x84, 8\nldi r9, 3\n"
                                   "sbco r7, c24, 0x7c, 4\nhalt\n"),
                     1);
    /* the word within a wider store, set through its two halves */
    ck_assert_int_eq(pru_of_source("ldi r4.w0, 0\nldi r4.w2, 0\nldi r5, 0x5353\n"
                                   "sbco r3, c24, 0x78, 12\nhalt\n"),
                     0);
    /* a LOOP whose body writes other registers leaves r1 known */
    ck_assert_int_eq(pru_of_source("ldi r1, 1\nloop E, 4\nadd r2, r2, 1\nE:\n"
                                   "sbco r1, c24, 0x7c, 4\nhalt\n"),
                     1);
    /* no value an LDI sets: the register was changed, or loaded */
    ck_assert_int_eq(pru_of_source("ldi r1, 0\nadd r1, r1, 1\nsbco r1, c24, 0x7c, 4\nhalt\n"), -1);
    ck_assert_int_eq(pru_of_source("ldi r1, 0\nlbco r1, c24, 0, 4\nsbco r1, c24, 0x7c, 4\nhalt\n"),
                     -1);
    ck_assert_int_eq(pru_of_source("ldi r1.w0, 1\nsbco r1, c24, 0x7c, 4\nhalt\n"), -1);
    /* a value that is no PRU */
    ck_assert_int_eq(pru_of_source("ldi r1, 2\nsbco r1, c24, 0x7c, 4\nhalt\n"), -1);
    /* a store that covers only part of the word */
    ck_assert_int_eq(pru_of_source("ldi r1, 1\nsbco r1, c24, 0x7e, 4\nhalt\n"), -1);
    /* a branch before the store: not followed */
    ck_assert_int_eq(pru_of_source("ldi r1, 1\nqba S\nS:\nsbco r1, c24, 0x7c, 4\nhalt\n"), -1);
    /* another constant table entry is another memory */
    ck_assert_int_eq(pru_of_source("ldi r1, 1\nsbco r1, c25, 0x7c, 4\nhalt\n"), -1);
    /* no store at all, and nothing */
    ck_assert_int_eq(pru_of_source("ldi r1, 1\nhalt\n"), -1);
    ck_assert_int_eq(biss_image_pru(NULL, 0), -1);
}
END_TEST

int main(void) {
    Suite *s = suite_create("image_pru");
    TCase *tc = tcase_create("image_pru");
    tcase_add_test(tc, test_firmware_images);
    tcase_add_test(tc, test_start_ups_written_otherwise);
    suite_add_tcase(s, tc);
    return check_run(s);
}
