/* test_wrong_frame.c - the classes of a wrong frame published as valid
 * (emulator/bench/wrong_frame.h), on frames built here: the default slave
 * (12-bit position, nE/nW, CRC6 0x43), SL at the master drawn on a 100 ns
 * bit grid, a glitch's edge drawn off it. */
#include "biss_crc.h"
#include "check_run.h"
#include "wrong_frame.h"

#include <check.h>
#include <stdio.h>
#include <string.h>

#define T    100000 /* ps: 10 MHz */
#define T0   1000000
#define NB   20 /* 14 data + 6 CRC bits */
#define DATA 14

static biss_chain_cfg cfg;

static void setup(void) {
    biss_chain_cfg_default(&cfg);
}

/* The default slave's word for a position (nE, nW 1) and its bits with
 * the CRC as sent. */
static uint64_t word_of(uint64_t pos) {
    return pos << 2 | 3u;
}

static void bits_of(uint64_t word, uint8_t *b) {
    uint32_t crc = ~biss_crc_bits(0x43, 0, word, DATA) & 0x3fu;
    for (unsigned k = 0; k < DATA; k++) {
        b[k] = (uint8_t)(word >> (DATA - 1 - k) & 1u);
    }
    for (unsigned k = 0; k < 6; k++) {
        b[DATA + k] = (uint8_t)(crc >> (5 - k) & 1u);
    }
    b[NB] = 0; /* after the chain */
}

static uint64_t word_from(const uint8_t *b) {
    uint64_t w = 0;
    for (unsigned k = 0; k < DATA; k++) {
        w = w << 1 | b[k];
    }
    return w;
}

/* Whether b (NB bits) is a word whose CRC passes. */
static bool passes(const uint8_t *b) {
    uint8_t again[NB + 1];
    bits_of(word_from(b), again);
    return memcmp(again, b, NB) == 0;
}

/* SL at the master: the start bit, then bits[], each from the grid point
 * of its period; at the times extra[], an edge to extra_level, or (pulse)
 * a 20 ns inversion (a glitch on SL). */
static void draw(waveform *w, const uint8_t *bits, const int64_t *extra, unsigned nextra,
                 int extra_level, bool pulse) {
    waveform_init(w, 0);
    int64_t t = T0;
    waveform_append(w, t, 1); /* start bit */
    t += T;
    waveform_append(w, t, 0); /* CDS */
    int level = 0;
    for (unsigned k = 0; k < NB; k++) {
        t += T;
        for (unsigned e = 0; e < nextra; e++) {
            if (extra[e] > t - T && extra[e] < t) {
                waveform_append(w, extra[e], pulse ? !level : extra_level);
                waveform_append(w, extra[e] + 20000, pulse ? level : extra_level);
            }
        }
        waveform_append(w, t, bits[k]);
        level = bits[k];
    }
    waveform_append(w, t + T, 0);
}

static biss_frame_record record_of(uint64_t pos) {
    biss_frame_record r = {0};
    r.start_bit_ps = T0;
    r.end_ps = T0 + (NB + 10) * T;
    r.s[0].position = pos;
    r.s[0].nE = r.s[0].nW = 1;
    uint64_t w = word_of(pos);
    r.s[0].crc = ~biss_crc_bits(0x43, 0, w, DATA) & 0x3fu;
    return r;
}

/* A position and a place k where the slave one bit ahead gives a word
 * whose CRC passes, with sent[k] == sent[k + 1] (in_run) or not. */
static bool find_shift(bool in_run, uint64_t *pos, unsigned *k, uint8_t *read) {
    for (uint64_t p = 1; p < 4096; p++) {
        uint8_t s[NB + 1];
        bits_of(word_of(p), s);
        for (unsigned j = 2; j < DATA - 2; j++) {
            if ((s[j] == s[j + 1]) != in_run) {
                continue;
            }
            for (unsigned i = 0; i < NB; i++) {
                read[i] = i < j ? s[i] : s[i + 1];
            }
            if (passes(read) && word_from(read) != word_of(p)) {
                *pos = p;
                *k = j;
                return true;
            }
        }
    }
    return false;
}

/* A shift inside a run of equal bits: SL at the master is exactly a valid
 * frame of the other word, every edge on the grid. */
START_TEST(shift_in_a_run_is_valid_on_the_wire) {
    uint64_t pos;
    unsigned k;
    uint8_t read[NB + 1];
    ck_assert(find_shift(true, &pos, &k, read));
    biss_frame_record r = record_of(pos);
    waveform sl;
    draw(&sl, read, NULL, 0, 0, false);
    uint64_t data = word_from(read);
    struct wrong_frame w;
    wrong_frame_classify(&cfg, &r, &data, 7, &sl, r.end_ps, T, NULL, &w);
    char line[512];
    wrong_frame_describe(&w, line, sizeof line);
    printf("%s\n", line);
    ck_assert_int_eq(w.cls, WRONG_ON_WIRE);
    ck_assert_int_eq(w.words, WORDS_SHIFT_AHEAD);
    ck_assert_uint_le(w.shift_at, k);
    ck_assert_uint_ge(w.shift_run, 2);
    ck_assert_uint_eq(w.off_grid, 0);
    ck_assert_uint_eq(w.frame, 7);
    waveform_free(&sl);
}
END_TEST

/* A shift at a run's end: SL changes at the glitch, half a bit off the
 * grid. */
START_TEST(shift_at_a_boundary_is_off_grid) {
    uint64_t pos;
    unsigned k;
    uint8_t read[NB + 1];
    ck_assert(find_shift(false, &pos, &k, read));
    biss_frame_record r = record_of(pos);
    /* in period k the slave changes to sent[k + 1] at the glitch */
    uint8_t sent[NB + 1];
    bits_of(word_of(pos), sent);
    int64_t glitch = T0 + (int64_t)(k + 2) * T + T / 2;
    uint8_t drawn[NB + 1];
    memcpy(drawn, read, sizeof drawn);
    drawn[k] = sent[k]; /* the first half of period k, then the glitch's edge */
    waveform sl;
    draw(&sl, drawn, &glitch, 1, sent[k + 1], false);
    uint64_t data = word_from(read);
    struct wrong_frame w;
    wrong_frame_classify(&cfg, &r, &data, 8, &sl, r.end_ps, T, NULL, &w);
    char line[512];
    wrong_frame_describe(&w, line, sizeof line);
    printf("%s\n", line);
    ck_assert_int_eq(w.cls, WRONG_OFF_GRID);
    ck_assert_int_eq(w.words, WORDS_SHIFT_AHEAD);
    /* the words alone place the shift anywhere in the run that ends at k */
    ck_assert_uint_le(w.shift_at, k);
    ck_assert_uint_eq(w.shift_at + w.shift_run - 1, k);
    ck_assert_uint_ge(w.off_grid, 1);
    ck_assert_int_eq(w.off_ps[0] < 0 ? -w.off_ps[0] : w.off_ps[0], T / 2);
    waveform_free(&sl);
}
END_TEST

/* Position 0x5a3's frame with three bits flipped in the pattern of the
 * CRC6 polynomial (at bits 3, 8, 9: x^6 + x + 1 times x^(NB - 1 - 9)): the
 * bits sent and read, the record, and SL drawn with a 20 ns glitch in the
 * middle of each flipped bit (40 ns past its start). Returns the word read. */
static uint64_t crc_flips(uint8_t *sent, uint8_t *read, biss_frame_record *r, waveform *sl) {
    uint64_t pos = 0x5a3;
    bits_of(word_of(pos), sent);
    memcpy(read, sent, NB + 1);
    unsigned at = 3;
    read[at] ^= 1;
    read[at + 5] ^= 1;
    read[at + 6] ^= 1;
    *r = record_of(pos);
    int64_t glitches[3] = {T0 + (at + 2) * T + 40000, T0 + (at + 7) * T + 40000,
                           T0 + (at + 8) * T + 40000};
    draw(sl, read, glitches, 3, 0, true);
    return word_from(read);
}

/* Three bits flipped in the pattern of the CRC6 polynomial (x^6 + x + 1,
 * at x^k): the same CRC passes; the SL glitches that flipped them put
 * their edges off the grid. Drawn clean instead (the frame as sent, every
 * edge on the grid), the master misread it: other. */
START_TEST(crc_polynomial_flips) {
    uint8_t sent[NB + 1], read[NB + 1];
    biss_frame_record r;
    waveform sl;
    uint64_t data = crc_flips(sent, read, &r, &sl);
    ck_assert(passes(read));
    struct wrong_frame w;
    wrong_frame_classify(&cfg, &r, &data, 9, &sl, r.end_ps, T, NULL, &w);
    char line[512];
    wrong_frame_describe(&w, line, sizeof line);
    printf("%s\n", line);
    ck_assert_uint_eq(w.flipped_bits, 3);
    ck_assert(w.crc_poly_shifted);
    ck_assert_int_eq(w.cls, WRONG_OFF_GRID);
    ck_assert_uint_eq(w.off_grid, 6);
    waveform_free(&sl);
    if (w.words == WORDS_FLIPPED) { /* not a slip pattern too: a clean frame as sent, misread */
        draw(&sl, sent, NULL, 0, 0, false);
        wrong_frame_classify(&cfg, &r, &data, 9, &sl, r.end_ps, T, NULL, &w);
        ck_assert_int_eq(w.cls, WRONG_OTHER);
        waveform_free(&sl);
    }
}
END_TEST

/* The same frame's three 20 ns pulses (each starting 15 ns past a 25 ns
 * mark) against the master's sample instants (the GPI's shift clock less
 * its 2-cycle synchronizer): at 80 MHz (every 12.5 ns) a sample falls in
 * each, off-grid; at 40 MHz (every 25 ns) set up 4 cycles in, the instants
 * fall 5 ns before each pulse and at its end, so no sample saw one and the
 * samples were a clean frame: between samples. */
START_TEST(pulses_between_samples) {
    uint8_t sent[NB + 1], read[NB + 1];
    biss_frame_record r;
    waveform sl;
    uint64_t data = crc_flips(sent, read, &r, &sl);
    struct pru_core *c = pru_core_new(PRU_SOC_AM335X, NULL);
    ck_assert_int_eq(pru_host_write32(c, 0x4A326008u, 2u | 3u << 3), 0); /* GPCFG0: 80 MHz */
    struct wrong_frame w;
    wrong_frame_classify(&cfg, &r, &data, 9, &sl, r.end_ps, T, c, &w);
    ck_assert_int_eq(w.cls, WRONG_OFF_GRID);
    ck_assert_uint_eq(w.off_grid, 6);
    ck_assert_uint_eq(w.off_grid_seen, 6);
    pru_run_until_cycle(c, 4);
    ck_assert_int_eq(pru_host_write32(c, 0x4A326008u, 2u | 8u << 3), 0); /* 40 MHz: 5 x 1 */
    wrong_frame_classify(&cfg, &r, &data, 9, &sl, r.end_ps, T, c, &w);
    char line[512];
    wrong_frame_describe(&w, line, sizeof line);
    printf("%s\n", line);
    ck_assert_int_eq(w.cls, WRONG_BETWEEN);
    ck_assert_uint_eq(w.off_grid, 6);
    ck_assert_uint_eq(w.off_grid_seen, 0);
    ck_assert_str_eq(wrong_class_name(w.cls), "between samples");
    pru_core_free(c);
    waveform_free(&sl);
}
END_TEST

/* No record of the frame: nothing to compare, said so. */
START_TEST(no_record) {
    waveform sl;
    waveform_init(&sl, 1);
    uint64_t data = 0;
    struct wrong_frame w;
    wrong_frame_classify(&cfg, NULL, &data, 1, &sl, 0, T, NULL, &w);
    ck_assert_int_eq(w.words, WORDS_UNKNOWN);
    ck_assert_int_eq(w.cls, WRONG_OTHER);
    ck_assert_str_eq(wrong_class_name(WRONG_ON_WIRE), "valid on the wire");
    ck_assert_str_eq(wrong_class_name(WRONG_OFF_GRID), "off-grid");
    waveform_free(&sl);
}
END_TEST

int main(void) {
    Suite *s = suite_create("wrong_frame");
    TCase *tc = tcase_create("classify");
    tcase_add_checked_fixture(tc, setup, NULL);
    tcase_add_test(tc, shift_in_a_run_is_valid_on_the_wire);
    tcase_add_test(tc, shift_at_a_boundary_is_off_grid);
    tcase_add_test(tc, crc_polynomial_flips);
    tcase_add_test(tc, pulses_between_samples);
    tcase_add_test(tc, no_record);
    suite_add_tcase(s, tc);
    return check_run(s);
}
