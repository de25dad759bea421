/* test_probe_layout.c - the probe's wire analysis (host/probe/biss_probe_layout.c,
 * biss_probe_fields.c) on frames the slave model sends: every BiSS profile
 * and random layouts drawn from the documents (probe_gen.c). The probe must
 * name the layout the model was given, or say it is ambiguous or cannot
 * decide; it must never name a wrong one as unique or best. */
#include "biss_probe.h"
#include "check_run.h"
#include "probe_frames.h"
#include "probe_gen.h"
#include "scenario.h"
#include "scenario_json.h"

#include "biss_crc.h"
#include "test_rng.h"

#include <check.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define NBITS          (1 + 8 * 64) /* the capture layout: CDS + 8 x 64 */
#define RANDOM_NBITS   (1 + 2 * 64) /* one slave: 80 bits at most, then zeros */
#define NFRAMES        1024         /* the AD38's A/D word moves 1000 counts/s: it needs ~80 ms */
#define RANDOM_LAYOUTS 240
#define NOISY_LAYOUTS  60
#define HALF           (50 * SIM_PS_PER_NS) /* 10 MHz */
#define PERIOD         (80 * SIM_PS_PER_US)

static bool last_lc_open; /* the last result's first layout had a counter that may be wider */

static void print_result(const char *what, const struct biss_probe_result *r) {
    printf("%s: %s (%s) [%.3g steps, %u ms]", what, biss_probe_verdict_name(r->verdict), r->reason,
           (double)r->work, r->elapsed_ms);
    for (unsigned k = 0; k < r->nkept && k < (r->verdict == BISS_PROBE_AMBIGUOUS ? 3u : 1u); k++) {
        const struct biss_probe_layout *l = &r->layout[k];
        printf(" #%u", k + 1);
        for (unsigned i = 0; i < l->nslaves; i++) {
            const struct biss_probe_slave *s = &l->slave[i];
            printf(" [%u,%u,0x%x,0x%x ew=%d/%u lc=%u%s rank=%u]", s->data_bits, s->crc_bits,
                   s->crc_poly, s->crc_start, s->has_ew, s->ew_shift, s->lc_bits,
                   s->lc_open ? "+" : "", s->rank);
        }
    }
    printf("\n");
}

/* The scenario the probe writes for a layout builds the same frames: its
 * slaves read back with the truth's word (the position takes the fill
 * bits, which the wire cannot tell from position bits that never moved),
 * nE/nW, counter and CRC. */
static void scenario_matches(const char *what, const struct biss_probe_layout *l,
                             const biss_chain_cfg *cfg) {
    char json[4096], err[256];
    ck_assert_int_eq(biss_probe_to_json(l, json, sizeof json), BISS_OK);
    static scenario sc;
    ck_assert_msg(scenario_from_json(json, &sc, err, sizeof err) == 0, "%s: %s", what, err);
    ck_assert_uint_eq(sc.biss.n, cfg->n);
    for (unsigned i = 0; i < cfg->n; i++) {
        const biss_slave_cfg *a = &sc.biss.s[i], *t = &cfg->s[i];
        ck_assert_msg(
            a->pos_bits + a->fill_bits == t->pos_bits + t->fill_bits && a->has_err == t->has_err &&
                a->has_warn == t->has_warn && a->lc_bits == t->lc_bits &&
                a->crc_poly == t->crc_poly && a->crc_start == t->crc_start,
            "%s: scenario slave %u: pos %u+%u ew %d/%d lc %u CRC 0x%x/0x%x", what, i, a->pos_bits,
            a->fill_bits, a->has_err, a->has_warn, a->lc_bits, a->crc_poly, a->crc_start);
    }
}

static enum probe_outcome probe_chain(const char *what, const biss_chain_cfg *cfg, unsigned nframes,
                                      unsigned nbits, bool *ew_ok) {
    static uint8_t bits[NFRAMES * NBITS];
    static uint32_t fno[NFRAMES];
    ck_assert_int_eq(probe_frames_from_model(cfg, nframes, nbits, HALF, PERIOD, bits, fno), 0);
    struct biss_probe_frames f = {nframes, nbits, bits, fno};
    static struct biss_probe_result r;
    ck_assert_int_eq(biss_probe_analyse(&f, &r), 0);
    print_result(what, &r);
    enum probe_outcome o = probe_gen_judge(&r, cfg);
    *ew_ok = o == PROBE_RECOVERED && probe_gen_fields_match(&r.layout[0], cfg);
    if (*ew_ok) {
        scenario_matches(what, &r.layout[0], cfg);
    }
    last_lc_open = false;
    for (unsigned i = 0; r.nkept && i < r.layout[0].nslaves; i++) {
        last_lc_open |= r.layout[0].slave[i].lc_open;
    }
    return o;
}

START_TEST(every_profile) {
    unsigned biss = 0, recovered = 0, ew = 0;
    for (size_t i = 0; profile_name_at(i); i++) {
        scenario s;
        ck_assert_int_eq(profile_by_name(profile_name_at(i), &s), 0);
        if (s.model != &slave_model_biss) {
            continue; /* SSI: no start bit, nothing for this analysis (see the e2e test) */
        }
        biss++;
        bool ew_ok;
        enum probe_outcome o = probe_chain(profile_name_at(i), &s.biss, NFRAMES, NBITS, &ew_ok);
        ck_assert_msg(o != PROBE_WRONG, "%s: a wrong layout named", profile_name_at(i));
        recovered += o == PROBE_RECOVERED;
        ew += ew_ok;
    }
    printf("profiles: %u BiSS, %u recovered, %u with nE/nW right\n", biss, recovered, ew);
    ck_assert_uint_eq(biss, 5);
    ck_assert_uint_eq(recovered, biss);
    ck_assert_uint_eq(ew, biss);
}
END_TEST

/* Layouts drawn from the documents (probe_gen.c), each through the slave
 * model, 1024 frames (what bissctl probe captures) 80 us apart: counters with
 * and without nE/nW, 3..16-bit CRCs, non-zero start values, 1 and 50 rev/s.
 * A verdict of unique or best must name every field right: the split, the
 * CRC, nE/nW and the life counter's width. */
START_TEST(random_layouts) {
    uint64_t rng = 0x5eed2026u;
    unsigned n[4] = {0}, open = 0, lc_no_ew = 0;
    for (unsigned k = 0; k < RANDOM_LAYOUTS; k++) {
        biss_chain_cfg cfg;
        char what[200];
        probe_gen_layout(&rng, k, &cfg, what, sizeof what);
        char why[200];
        ck_assert_msg(biss_chain_cfg_check(&cfg, why, sizeof why) == 0, "%s: %s", what, why);
        bool ew_ok;
        enum probe_outcome o = probe_chain(what, &cfg, NFRAMES, RANDOM_NBITS, &ew_ok);
        ck_assert_msg(o != PROBE_WRONG, "%s: a wrong layout named", what);
        ck_assert_msg(o != PROBE_RECOVERED || ew_ok, "%s: nE/nW or life counter wrong", what);
        n[o]++;
        open += last_lc_open;
        lc_no_ew += o == PROBE_RECOVERED && cfg.s[0].lc_bits && !cfg.s[0].has_err;
    }
    printf("random layouts: %u recovered (%u with a counter and no nE/nW), %u ambiguous (%u of "
           "them a counter that never wrapped), %u undecided, %u wrong\n",
           n[PROBE_RECOVERED], lc_no_ew, n[PROBE_AMBIGUOUS_OK], open, n[PROBE_UNDECIDED],
           n[PROBE_WRONG]);
    ck_assert_uint_eq(n[PROBE_WRONG], 0);
    ck_assert_uint_ge(n[PROBE_RECOVERED], RANDOM_LAYOUTS * 8 / 10);
    ck_assert_uint_gt(lc_no_ew, RANDOM_LAYOUTS / 10);
}
END_TEST

/* A chain longer than 8 x 64 bits (547), as the 640-bit capture reads it:
 * 8 slaves, CRC-16s with an even number of terms (so each also fits
 * (x + 1)-factor splits) and positions whose top bits never move. The
 * layouts that fit pass the listing limit; counted, the truth is the only
 * best one. (Slave 2's speed is not 9e5: 72 counts per 80 us frame, a
 * multiple of 8, would step its position bits above nE/nW in step with the
 * life counter, and a 9-bit counter would fit 63 of 64 steps.) */
START_TEST(long_chain) {
    static const struct {
        unsigned pos, lc;
        bool ew;
        uint32_t poly, start;
        double speed;
    } sl[8] = {{60, 0, true, 0x190D9, 0, 1e6},
               {62, 0, false, 0x18005, 0x1234, 7e5},
               {48, 6, true, 0x190D9, 0x5A5A, 9.13e5},
               {40, 0, true, 0x43, 0, 8e5},
               {58, 0, true, 0x190D9, 0, -1e6},
               {62, 0, true, 0x11021, 0xFFFF, 6e5},
               {30, 0, true, 0x25, 0, 5e5},
               {60, 0, true, 0x190D9, 0x0F0F, 1.1e6}};
    biss_chain_cfg cfg;
    biss_chain_cfg_default(&cfg);
    cfg.n = 8;
    unsigned bits = 0;
    for (unsigned i = 0; i < 8; i++) {
        biss_slave_cfg *c = &cfg.s[i];
        biss_slave_cfg_default(c, i);
        c->pos_bits = sl[i].pos;
        c->lc_bits = sl[i].lc;
        c->has_err = c->has_warn = sl[i].ew;
        c->crc_poly = sl[i].poly;
        c->crc_start = sl[i].start;
        c->speed_cps = sl[i].speed;
        bits += biss_slave_cfg_data_bits(c) + biss_crc_width(c->crc_poly);
    }
    char why[200];
    ck_assert_msg(biss_chain_cfg_check(&cfg, why, sizeof why) == 0, "%s", why);
    ck_assert_uint_eq(bits, 547);
    static uint8_t frames[NFRAMES * BISS_PROBE_MAX_BITS];
    static uint32_t fno[NFRAMES];
    ck_assert_int_eq(
        probe_frames_from_model(&cfg, NFRAMES, BISS_PROBE_MAX_BITS, HALF, PERIOD, frames, fno), 0);
    struct biss_probe_frames f = {NFRAMES, BISS_PROBE_MAX_BITS, frames, fno};
    static struct biss_probe_result r;
    ck_assert_int_eq(biss_probe_analyse(&f, &r), 0);
    print_result("long chain", &r);
    ck_assert_uint_eq(r.end_bit, 547);
    ck_assert_int_eq(r.verdict, BISS_PROBE_BEST);
    ck_assert_uint_gt(r.nlayouts, r.nkept); /* more than listed: counted */
    ck_assert_int_eq(probe_gen_judge(&r, &cfg), PROBE_RECOVERED);
    ck_assert(probe_gen_fields_match(&r.layout[0], &cfg));
}
END_TEST

/* Frames hit by noise: in `permille` of the frames, one of a glitch's
 * marks (drawn per frame): one to three flipped bits anywhere in the frame
 * or after it, or the frame read one bit late from a point on (a clock the
 * slave saw and the master did not). */
static void corrupt(uint8_t *bits, unsigned nframes, unsigned nbits, unsigned permille,
                    uint64_t *rng, unsigned *hit) {
    *hit = 0;
    for (unsigned i = 0; i < nframes; i++) {
        if (test_rng_next(rng) % 1000 >= permille) {
            continue;
        }
        (*hit)++;
        uint8_t *b = bits + (size_t)i * nbits;
        unsigned kind = test_rng_next(rng) % 4;
        if (kind < 3) {
            for (unsigned k = 0; k <= kind; k++) {
                b[1 + test_rng_next(rng) % (nbits - 1)] ^= 1;
            }
        } else {
            unsigned from = 1 + test_rng_next(rng) % (nbits - 2);
            memmove(b + from + 1, b + from, nbits - from - 1);
        }
    }
}

/* Layouts from the documents with 1, 3 and 5 % of their frames hit by
 * noise: decided on the good frames, the others set aside and counted. */
START_TEST(noisy_frames) {
    static const unsigned rates[] = {10, 30, 50};
    uint64_t rng = 0xbadf4a3e5u, noise = 0x6e015eu;
    unsigned n[4] = {0};
    for (unsigned k = 0; k < NOISY_LAYOUTS; k++) {
        biss_chain_cfg cfg;
        char what[200];
        probe_gen_layout(&rng, k, &cfg, what, sizeof what);
        static uint8_t bits[NFRAMES * RANDOM_NBITS];
        static uint32_t fno[NFRAMES];
        ck_assert_int_eq(
            probe_frames_from_model(&cfg, NFRAMES, RANDOM_NBITS, HALF, PERIOD, bits, fno), 0);
        unsigned hit, rate = rates[k % 3];
        corrupt(bits, NFRAMES, RANDOM_NBITS, rate, &noise, &hit);
        struct biss_probe_frames f = {NFRAMES, RANDOM_NBITS, bits, fno};
        static struct biss_probe_result r;
        ck_assert_int_eq(biss_probe_analyse(&f, &r), 0);
        char w2[260];
        snprintf(w2, sizeof w2, "%s, %u frames hit (%.0f%%)", what, hit, rate / 10.0);
        print_result(w2, &r);
        enum probe_outcome o = probe_gen_judge(&r, &cfg);
        ck_assert_msg(o != PROBE_WRONG, "%s: a wrong layout named", w2);
        if (o == PROBE_RECOVERED) { /* the frames hit were set aside and counted */
            ck_assert_uint_eq(r.dropped, r.frames - r.layout[0].good);
            ck_assert_uint_le(r.dropped, hit);
        }
        n[o]++;
    }
    printf("noisy frames: %u recovered, %u ambiguous, %u undecided, %u wrong\n", n[PROBE_RECOVERED],
           n[PROBE_AMBIGUOUS_OK], n[PROBE_UNDECIDED], n[PROBE_WRONG]);
    /* usable: decided on the good frames (the ambiguous ones: counters
     * that never wrapped, as without noise) */
    ck_assert_uint_ge(n[PROBE_RECOVERED], NOISY_LAYOUTS * 8 / 10);
}
END_TEST

/* Garbage a line may carry, or a fuzzer: each frame `nbits` long (the
 * CDS first). kind 0: one period-5 pattern, shifted by 3 bits a frame;
 * 1: the low bit of a xorshift (a linear recurrence, as a CRC is); 2: a
 * pattern whose period grows with the frame; 3: bytes of a nonlinear
 * generator (test_rng). The last bit of each frame is 0, so the frame ends
 * inside the capture. */
static void garbage(uint8_t *bits, unsigned nframes, unsigned nbits, unsigned kind) {
    uint64_t x = 12345, rng = 0x9a5b4e;
    for (unsigned i = 0; i < nframes; i++) {
        for (unsigned k = 0; k + 1 < nbits; k++) {
            unsigned v;
            if (kind == 0) {
                v = (k * 7 + i * 3) % 5 < 2;
            } else if (kind == 1) {
                x ^= x << 13;
                x ^= x >> 7;
                x ^= x << 17;
                v = x & 1u;
            } else if (kind == 2) {
                v = (k + i) % (3 + i % 4) == 0;
            } else {
                v = test_rng_next(&rng) & 1u;
            }
            bits[(size_t)i * nbits + k] = (uint8_t)v;
        }
        bits[(size_t)i * nbits + nbits - 1] = 0;
    }
}

static unsigned progress_calls;
static void count_progress(void *ctx, const struct biss_probe_progress *p) {
    (void)ctx;
    ck_assert_uint_le(p->work, p->work_limit);
    ck_assert_uint_le(p->offsets_searched, p->end_bit);
    progress_calls++;
}

/* The most one step of the search adds past a limit (a whole capture read
 * once: 4096 frames of 641 bits). */
#define OVERSHOOT ((uint64_t)BISS_PROBE_MAX_FRAMES * BISS_PROBE_MAX_BITS)

/* Adversarial frames that ran for minutes before the search had limits
 * (14 frames of period-5 garbage, 514 bits: over 5 minutes; 2 of them:
 * 9.7 s): with the default limits the search stops at its work limit,
 * reports progress on the way, and names nothing unique or best; the
 * verdict says what stopped it. */
START_TEST(garbage_default_limits) {
    static uint8_t bits[14 * 514];
    garbage(bits, 14, 514, 0);
    struct biss_probe_frames f = {14, 514, bits, NULL};
    struct biss_probe_limits lim = {.progress = count_progress};
    static struct biss_probe_result r;
    progress_calls = 0;
    ck_assert_int_eq(biss_probe_analyse_limited(&f, &lim, &r), 0);
    print_result("14 frames of period-5 garbage", &r);
    ck_assert_int_eq(r.ran_out, BISS_PROBE_RAN_OUT_WORK);
    ck_assert_uint_ge(r.work, BISS_PROBE_WORK_LIMIT);
    ck_assert_uint_le(r.work, BISS_PROBE_WORK_LIMIT + OVERSHOOT);
    ck_assert(r.verdict == BISS_PROBE_NONE || r.verdict == BISS_PROBE_AMBIGUOUS);
    ck_assert_ptr_nonnull(strstr(r.reason, "stopped at the work limit"));
    ck_assert_uint_gt(progress_calls, 0); /* 5e9 steps take seconds anywhere */
}
END_TEST

/* Every kind of garbage, from 2 frames to the most a capture holds, under
 * a small work limit: the limit holds on each, and a verdict of unique or
 * best comes only from frames a layout really fits (kinds 0 and 1 are
 * linear, as CRCs are: some fit). A 1 ms time limit stops the search by
 * the clock. */
START_TEST(garbage_bounded) {
    static const unsigned counts[] = {2, 14, 200, BISS_PROBE_MAX_FRAMES};
    static uint8_t bits[BISS_PROBE_MAX_FRAMES * BISS_PROBE_MAX_BITS];
    static struct biss_probe_result r;
    for (unsigned kind = 0; kind < 4; kind++) {
        for (unsigned c = 0; c < 4; c++) {
            unsigned nbits = c == 3 ? BISS_PROBE_MAX_BITS : 514;
            garbage(bits, counts[c], nbits, kind);
            struct biss_probe_frames f = {counts[c], nbits, bits, NULL};
            struct biss_probe_limits lim = {.work_limit = 50000000};
            ck_assert_int_eq(biss_probe_analyse_limited(&f, &lim, &r), 0);
            char what[64];
            snprintf(what, sizeof what, "garbage kind %u, %u frames", kind, counts[c]);
            print_result(what, &r);
            ck_assert_uint_le(r.work, lim.work_limit + OVERSHOOT);
            ck_assert(r.ran_out == BISS_PROBE_RAN_OUT_NONE || r.verdict == BISS_PROBE_NONE ||
                      r.verdict == BISS_PROBE_AMBIGUOUS);
            if (kind >= 2) {
                ck_assert(r.verdict == BISS_PROBE_NONE || r.verdict == BISS_PROBE_AMBIGUOUS);
            }
            for (unsigned k = 0; r.verdict <= BISS_PROBE_BEST && k < r.layout[0].nslaves; k++) {
                ck_assert_uint_ge(r.layout[0].good * 1000u, r.frames * 600u);
            }
        }
    }
    garbage(bits, 14, 514, 0);
    struct biss_probe_frames f = {14, 514, bits, NULL};
    struct biss_probe_limits lim = {.time_limit_ms = 1};
    ck_assert_int_eq(biss_probe_analyse_limited(&f, &lim, &r), 0);
    print_result("1 ms", &r);
    ck_assert_int_eq(r.ran_out, BISS_PROBE_RAN_OUT_TIME);
    ck_assert_ptr_nonnull(strstr(r.reason, "stopped at the time limit"));
}
END_TEST

/* What the analysis refuses to guess. */
START_TEST(cannot_decide) {
    static uint8_t bits[8 * NBITS];
    struct biss_probe_frames f = {8, NBITS, bits, NULL};
    struct biss_probe_result r;
    ck_assert_int_eq(biss_probe_analyse(&f, &r), 0); /* all zeros: no data */
    ck_assert_int_eq(r.verdict, BISS_PROBE_NONE);
    ck_assert_ptr_nonnull(strstr(r.reason, "no slave sent data"));
    for (unsigned i = 0; i < 8; i++) { /* alike frames: nothing to tell CRC from data */
        memcpy(bits + i * NBITS, (const uint8_t[]){0, 1, 0, 1, 1, 0, 1, 1, 1, 0, 0, 1}, 12);
    }
    ck_assert_int_eq(biss_probe_analyse(&f, &r), 0);
    ck_assert_int_eq(r.verdict, BISS_PROBE_NONE);
    ck_assert_ptr_nonnull(strstr(r.reason, "alike"));
    bits[3 * NBITS + NBITS - 1] = 1; /* a 1 in the last captured bit */
    ck_assert_int_eq(biss_probe_analyse(&f, &r), 0);
    ck_assert_int_eq(r.verdict, BISS_PROBE_NONE);
    ck_assert_ptr_nonnull(strstr(r.reason, "longer than the capture"));
    f.nbits = 1;
    ck_assert_int_eq(biss_probe_analyse(&f, &r), BISS_E_INVAL);
    f.nbits = NBITS;
    f.nframes = 0;
    ck_assert_int_eq(biss_probe_analyse(&f, &r), BISS_E_INVAL);
    ck_assert_int_eq(biss_probe_analyse(NULL, &r), BISS_E_INVAL);
}
END_TEST

int main(void) {
    Suite *s = suite_create("probe_layout");
    TCase *tc = tcase_create("analysis");
    tcase_set_timeout(tc, 600);
    tcase_add_test(tc, every_profile);
    tcase_add_test(tc, random_layouts);
    tcase_add_test(tc, noisy_frames);
    tcase_add_test(tc, long_chain);
    tcase_add_test(tc, cannot_decide);
    suite_add_tcase(s, tc);
    TCase *lim = tcase_create("limits");
    tcase_set_timeout(lim, 600);
    tcase_add_test(lim, garbage_default_limits);
    tcase_add_test(lim, garbage_bounded);
    suite_add_tcase(s, lim);
    return check_run(s);
}
