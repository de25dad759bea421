/* test_probe_ssi.c - SSI words (host/probe/biss_probe_ssi.c): the word length,
 * Gray or binary from the steps, a CRC looked for, and what it refuses to
 * guess. Words are left-aligned, as the 64-bit SSI capture reads them. */
#include "biss_probe_priv.h"
#include "check_run.h"

#include <check.h>
#include <string.h>

#define N 256

static uint64_t to_gray(uint64_t b) {
    return b ^ (b >> 1);
}

/* A shaft at a steady speed: `step` counts per frame (in 1/16 counts, so
 * slow speeds leave frames without motion), bits-bit words. */
static void words(uint64_t *w, unsigned bits, unsigned step16, bool gray, uint64_t start) {
    for (unsigned i = 0; i < N; i++) {
        uint64_t v = (start + (uint64_t)i * step16 / 16) & ((1ull << bits) - 1u);
        w[i] = (gray ? to_gray(v) : v) << (64 - bits);
    }
}

static void analyse(const uint64_t *w, struct biss_probe_ssi *s) {
    memset(s, 0, sizeof *s);
    ck_assert_int_eq(biss_probe_ssi_analyse(w, NULL, N, s), BISS_OK);
}

START_TEST(binary_and_gray) {
    static uint64_t w[N];
    struct biss_probe_ssi s;
    static const struct {
        unsigned bits, step16;
    } cases[] = {{13, 21}, {25, 3}, {12, 16 * 40}, {32, 16 * 7}};
    for (unsigned k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        for (int gray = 0; gray < 2; gray++) {
            words(w, cases[k].bits, cases[k].step16, gray, 5);
            analyse(w, &s);
            ck_assert_msg(s.decided && s.gray == gray && s.bits == cases[k].bits,
                          "%u bits, step %u/16, %s: %s", cases[k].bits, cases[k].step16,
                          gray ? "Gray" : "binary", s.verdict);
            ck_assert(!s.crc_fits);
            ck_assert_ptr_nonnull(strstr(s.verdict, "SSI-like"));
        }
    }
    /* 12 bits moving from 5 up to ~1900 never touch the top bit */
    words(w, 12, 16 * 7, false, 5);
    analyse(w, &s);
    ck_assert_uint_eq(s.fixed_top, 1);
}
END_TEST

/* Steps that jump about either way: no code named. */
START_TEST(cannot_tell) {
    static uint64_t w[N];
    struct biss_probe_ssi s;
    uint64_t x = 0x1234567;
    for (unsigned i = 0; i < N; i++) {
        x = x * 6364136223846793005ull + 1442695040888963407ull;
        w[i] = (x >> 50) << 50; /* 14 random bits */
    }
    analyse(w, &s);
    ck_assert(!s.decided);
    ck_assert_ptr_nonnull(strstr(s.verdict, "cannot tell"));
}
END_TEST

START_TEST(refusals) {
    static uint64_t w[N];
    struct biss_probe_ssi s;
    memset(w, 0, sizeof w);
    analyse(w, &s);
    ck_assert(!s.decided);
    ck_assert_ptr_nonnull(strstr(s.verdict, "ever 1"));
    for (unsigned i = 0; i < N; i++) {
        w[i] = 0xABCull << 40;
    }
    analyse(w, &s);
    ck_assert(!s.decided);
    ck_assert_ptr_nonnull(strstr(s.verdict, "alike"));
    w[3] |= 1; /* the 64th bit: longer than the capture */
    analyse(w, &s);
    ck_assert(!s.decided);
    ck_assert_ptr_nonnull(strstr(s.verdict, "longer than the capture"));
    ck_assert_int_eq(biss_probe_ssi_analyse(NULL, NULL, N, &s), BISS_E_INVAL);
    ck_assert_int_eq(biss_probe_ssi_analyse(w, NULL, 0, &s), BISS_E_INVAL);
}
END_TEST

int main(void) {
    Suite *s = suite_create("probe_ssi");
    TCase *tc = tcase_create("ssi");
    tcase_set_timeout(tc, 120);
    tcase_add_test(tc, binary_and_gray);
    tcase_add_test(tc, cannot_tell);
    tcase_add_test(tc, refusals);
    suite_add_tcase(s, tc);
    return check_run(s);
}
