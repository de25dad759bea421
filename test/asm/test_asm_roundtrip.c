/*
 * Check suite: disassembly -> pruasm -> the same word, over the encoding
 * space.
 *
 * pru_disasm() promises that its text, assembled at the address it was
 * disassembled for, gives the word back: instructions as pasm syntax,
 * words pasm's syntax cannot produce (and words that are no instruction)
 * as ".codeword" lines. This suite holds it to that.
 *
 * Coverage: every row of the instruction list that has a V3 word, densely
 * sampled; not the whole 2^32 words (through the assembler that would take
 * hours). A row with at most EXHAUSTIVE_BITS free bits (those outside its
 * mask: HALT, SLP, JMP, LOOP, ILOOP) is enumerated completely; for every
 * other row: its free bits all clear, all set, each one alone set, each
 * one alone clear, and ROW_SAMPLES random patterns. Then SPACE_SAMPLES
 * random words over the whole 32-bit space (decodable or not). Every word
 * is checked; the suite prints how many.
 */
#include "asm_test_util.h"
#include "check_run.h"
#include "pru_isa.h"

#include <check.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define EXHAUSTIVE_BITS 17
#define ROW_SAMPLES     16000
#define SPACE_SAMPLES   250000
#define BASE_PC         512u  /* room for QB offsets down to -512 */
#define BATCH           8192u /* words per assembled program */
#define LINE_MAX_LEN    96

struct batch {
    uint32_t words[BATCH];
    char (*lines)[LINE_MAX_LEN];
    unsigned n;
    unsigned long checked, as_codeword;
};

static uint64_t rng = 0x243f6a8885a308d3u;

static uint32_t next_random(void) {
    rng ^= rng << 13;
    rng ^= rng >> 7;
    rng ^= rng << 17;
    return (uint32_t)(rng >> 16);
}

/* Assemble the batch as one program and compare every word. */
static void flush(struct batch *b) {
    if (b->n == 0)
        return;
    size_t cap = (size_t)b->n * (LINE_MAX_LEN + 1) + 64;
    char *src = malloc(cap);
    ck_assert_ptr_nonnull(src);
    size_t len = (size_t)snprintf(src, cap, ".origin %u\n", BASE_PC);
    for (unsigned i = 0; i < b->n; i++)
        len += (size_t)snprintf(src + len, cap - len, "%s\n", b->lines[i]);

    struct pruasm_image img;
    struct pruasm_diag diag = {0};
    int rc = asm_text(src, &img, &diag);
    if (rc != 0) {
        /* "t.p:LINE: ..." names the line; line 1 is the .origin */
        const char *colon = strchr(diag.first_error, ':');
        unsigned line = colon ? (unsigned)strtoul(colon + 1, NULL, 10) : 0;
        unsigned i = line >= 2 && line - 2 < b->n ? line - 2 : 0;
        ck_abort_msg("0x%08x at %u: '%s' does not assemble: %s", b->words[i], BASE_PC + i,
                     b->lines[i], diag.first_error);
    }
    ck_assert_uint_eq(img.nwords, BASE_PC + b->n);
    for (unsigned i = 0; i < b->n; i++) {
        ck_assert_msg(img.words[BASE_PC + i] == b->words[i],
                      "0x%08x at %u: '%s' assembles to 0x%08x", b->words[i], BASE_PC + i,
                      b->lines[i], img.words[BASE_PC + i]);
        if (strncmp(b->lines[i], ".codeword", 9) == 0)
            b->as_codeword++;
    }
    b->checked += b->n;
    pruasm_image_free(&img);
    free(src);
    b->n = 0;
}

static void add(struct batch *b, uint32_t word) {
    unsigned pc = BASE_PC + b->n;
    int len = pru_disasm(word, pc, b->lines[b->n], LINE_MAX_LEN);
    ck_assert_int_lt(len < 0 ? -len : len, LINE_MAX_LEN);
    b->words[b->n++] = word;
    if (b->n == BATCH)
        flush(b);
}

START_TEST(test_disasm_reassembles) {
    struct batch *b = calloc(1, sizeof *b);
    ck_assert_ptr_nonnull(b);
    b->lines = calloc(BATCH, LINE_MAX_LEN);
    ck_assert_ptr_nonnull(b->lines);
    unsigned rows = 0, exhaustive = 0;

    for (unsigned op = 0; op < PRU_OP_COUNT; op++) {
        if (!pru_op_decodes(op))
            continue;
        rows++;
        uint32_t match = pru_optable[op].match, free_bits = ~pru_optable[op].mask;
        unsigned nfree = (unsigned)__builtin_popcount(free_bits);
        if (nfree <= EXHAUSTIVE_BITS) {
            /* every value of the free bits: count through them */
            uint32_t v = 0;
            do {
                add(b, match | v);
                v = (v - free_bits) & free_bits;
            } while (v != 0);
            exhaustive++;
            continue;
        }
        add(b, match);
        add(b, match | free_bits);
        for (unsigned bit = 0; bit < 32; bit++) {
            if (free_bits >> bit & 1u) {
                add(b, match | 1u << bit);
                add(b, match | (free_bits & ~(1u << bit)));
            }
        }
        for (unsigned i = 0; i < ROW_SAMPLES; i++)
            add(b, match | (next_random() & free_bits));
    }
    for (unsigned i = 0; i < SPACE_SAMPLES; i++)
        add(b, next_random());
    flush(b);

    printf("round trip: %lu words (%u instruction rows, %u of them exhaustively), %lu of them "
           "as .codeword\n",
           b->checked, rows, exhaustive, b->as_codeword);
    ck_assert_uint_ge(rows, 60);
    /* most sampled words are instructions pasm can write */
    ck_assert_uint_lt(b->as_codeword, b->checked / 2);
    free(b->lines);
    free(b);
}
END_TEST

int main(void) {
    Suite *s = suite_create("asm_roundtrip");
    TCase *tc = tcase_create("roundtrip");
    tcase_set_timeout(tc, 300);
    tcase_add_test(tc, test_disasm_reassembles);
    suite_add_tcase(s, tc);
    return check_run(s);
}
