/* test_probe_layout.c - the probe's wire analysis (host/biss_probe_layout.c)
 * on frames the slave model sends: every BiSS profile and 50 random
 * layouts. The probe must name the layout the model was given, or say it
 * cannot decide; it must never name a wrong one as unique or best. */
#include "biss_probe.h"
#include "check_run.h"
#include "probe_frames.h"
#include "scenario.h"
#include "test_rng.h"

#include "biss_crc.h"

#include <check.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define NBITS   (1 + 8 * 64)         /* the capture layout: CDS + 8 x 64 */
#define NFRAMES 1024                 /* the AD38's A/D word moves 1000 counts/s: it needs ~80 ms */
#define HALF    (50 * SIM_PS_PER_NS) /* 10 MHz */
#define PERIOD  (80 * SIM_PS_PER_US)

enum outcome { RECOVERED, AMBIGUOUS_OK, UNDECIDED, WRONG };

static bool slave_matches(const struct biss_probe_slave *p, const biss_slave_cfg *s) {
    unsigned c = biss_crc_width(s->crc_poly);
    bool ew = s->has_err && s->has_warn;
    return p->data_bits == biss_slave_cfg_data_bits(s) && p->crc_bits == c &&
           p->crc_poly == s->crc_poly && p->crc_start == s->crc_start;
    (void)ew;
}

static bool layout_matches(const struct biss_probe_layout *l, const biss_chain_cfg *cfg) {
    if (l->nslaves != cfg->n) {
        return false;
    }
    for (unsigned i = 0; i < cfg->n; i++) {
        if (!slave_matches(&l->slave[i], &cfg->s[i])) {
            return false;
        }
    }
    return true;
}

/* nE/nW as the model has them: both flags, above lc_bits of life counter. */
static bool ew_matches(const struct biss_probe_layout *l, const biss_chain_cfg *cfg) {
    for (unsigned i = 0; i < cfg->n; i++) {
        const biss_slave_cfg *s = &cfg->s[i];
        bool ew = s->has_err && s->has_warn;
        const struct biss_probe_slave *p = &l->slave[i];
        if (p->has_ew != ew || (ew && p->ew_shift != s->lc_bits)) {
            return false;
        }
    }
    return true;
}

static enum outcome judge(const struct biss_probe_result *r, const biss_chain_cfg *cfg) {
    switch (r->verdict) {
    case BISS_PROBE_UNIQUE:
    case BISS_PROBE_BEST:
        return layout_matches(&r->layout[0], cfg) ? RECOVERED : WRONG;
    case BISS_PROBE_AMBIGUOUS:
        /* the truth must be among the candidates (unless more fit than are kept) */
        for (unsigned i = 0; i < r->nkept; i++) {
            if (layout_matches(&r->layout[i], cfg)) {
                return AMBIGUOUS_OK;
            }
        }
        return r->nlayouts > r->nkept ? AMBIGUOUS_OK : WRONG;
    case BISS_PROBE_NONE:
        return UNDECIDED;
    }
    return WRONG;
}

static void print_result(const char *what, const struct biss_probe_result *r) {
    printf("%s: %s (%s)", what, biss_probe_verdict_name(r->verdict), r->reason);
    for (unsigned k = 0; k < r->nkept && k < (r->verdict == BISS_PROBE_AMBIGUOUS ? 3u : 1u); k++) {
        const struct biss_probe_layout *l = &r->layout[k];
        printf(" #%u", k + 1);
        for (unsigned i = 0; i < l->nslaves; i++) {
            const struct biss_probe_slave *s = &l->slave[i];
            printf(" [%u,%u,0x%x,0x%x ew=%d/%u rank=%u]", s->data_bits, s->crc_bits, s->crc_poly,
                   s->crc_start, s->has_ew, s->ew_shift, s->rank);
        }
    }
    printf("\n");
}

static enum outcome probe_chain(const char *what, const biss_chain_cfg *cfg, unsigned nframes,
                                bool *ew_ok) {
    static uint8_t bits[NFRAMES * NBITS];
    static uint32_t fno[NFRAMES];
    ck_assert_int_eq(probe_frames_from_model(cfg, nframes, NBITS, HALF, PERIOD, bits, fno), 0);
    struct biss_probe_frames f = {nframes, NBITS, bits, fno};
    static struct biss_probe_result r;
    ck_assert_int_eq(biss_probe_analyse(&f, &r), 0);
    print_result(what, &r);
    enum outcome o = judge(&r, cfg);
    *ew_ok = o == RECOVERED && ew_matches(&r.layout[0], cfg);
    return o;
}

START_TEST(every_profile) {
    unsigned biss = 0, recovered = 0, ew = 0;
    for (size_t i = 0; profile_name_at(i); i++) {
        scenario s;
        ck_assert_int_eq(profile_by_name(profile_name_at(i), &s), 0);
        if (s.protocol != SCENARIO_BISS) {
            continue; /* SSI: no start bit, nothing for this analysis (see the e2e test) */
        }
        biss++;
        bool ew_ok;
        enum outcome o = probe_chain(profile_name_at(i), &s.biss, NFRAMES, &ew_ok);
        ck_assert_msg(o != WRONG, "%s: a wrong layout named", profile_name_at(i));
        recovered += o == RECOVERED;
        ew += ew_ok;
    }
    printf("profiles: %u BiSS, %u recovered, %u with nE/nW right\n", biss, recovered, ew);
    ck_assert_uint_eq(biss, 5);
    ck_assert_uint_eq(recovered, biss);
    ck_assert_uint_eq(ew, biss);
}
END_TEST

static uint64_t rng = 0x5eed2026u;
static uint32_t rnd(uint32_t n) { /* 0..n-1 */
    return test_rng_next(&rng) % n;
}

/* Data 1..64 bits, CRC 3..16 bits with a random odd polynomial (the model
 * takes odd ones only: an even generator's last CRC bit is constant) and a
 * random start, half with nE/nW (some of those with a life counter). */
static void random_slave(biss_slave_cfg *s) {
    biss_slave_cfg_default(s, 0);
    unsigned data = 1 + rnd(64);
    s->has_err = s->has_warn = data >= 3 && rnd(2);
    unsigned ew = s->has_err ? 2 : 0;
    s->lc_bits = ew && data >= 6 && rnd(3) == 0 ? 1 + rnd(data - 4 < 8 ? data - 4 : 8) : 0;
    s->fill_bits = data - ew - s->lc_bits >= 4 && rnd(4) == 0 ? rnd(4) : 0;
    s->pos_bits = data - ew - s->lc_bits - s->fill_bits;
    unsigned c = 3 + rnd(14);
    s->crc_poly = (1u << c) | (rnd(1u << c) | 1u);
    s->crc_start = rnd(1u << c);
    s->pos0 = ((uint64_t)rnd(1u << 31) << 32 | rnd(1u << 31)) &
              (s->pos_bits >= 64 ? ~0ull : (1ull << s->pos_bits) - 1u);
    s->speed_cps = 20000.0 + rnd(2000000);
}

START_TEST(random_layouts) {
    unsigned n[4] = {0}, ew = 0, with_ew = 0;
    for (unsigned k = 0; k < 50; k++) {
        biss_chain_cfg cfg;
        biss_chain_cfg_default(&cfg);
        random_slave(&cfg.s[0]);
        ck_assert_ptr_null(biss_chain_cfg_check(&cfg));
        char what[96];
        const biss_slave_cfg *s = &cfg.s[0];
        snprintf(what, sizeof what, "random %2u: D=%u (lc %u) C=%u 0x%x start 0x%x ew=%d", k,
                 biss_slave_cfg_data_bits(s), s->lc_bits, biss_crc_width(s->crc_poly), s->crc_poly,
                 s->crc_start, s->has_err);
        bool ew_ok;
        enum outcome o = probe_chain(what, &cfg, 256, &ew_ok);
        n[o]++;
        ew += ew_ok;
        with_ew += s->has_err;
    }
    printf("random layouts: %u recovered (%u with nE/nW right), %u ambiguous, %u undecided, %u "
           "wrong; %u had nE/nW\n",
           n[RECOVERED], ew, n[AMBIGUOUS_OK], n[UNDECIDED], n[WRONG], with_ew);
    ck_assert_uint_eq(n[WRONG], 0);
    ck_assert_uint_ge(n[RECOVERED], 45);
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
    ck_assert_ptr_null(biss_chain_cfg_check(&cfg));
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
    ck_assert_int_eq(judge(&r, &cfg), RECOVERED);
    ck_assert(ew_matches(&r.layout[0], &cfg));
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
    tcase_add_test(tc, long_chain);
    tcase_add_test(tc, cannot_decide);
    suite_add_tcase(s, tc);
    return check_run(s);
}
