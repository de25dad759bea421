/* probe_gen.c - random single-slave layouts from the reference documents
 * (not from the probe's code), each field drawn from what a source gives:
 *
 *   CRC      [MB4] Table 14's predefined polynomials (3..8 and 16 bits:
 *            0xB, 0x13, 0x25, 0x43, 0x89, 0x12F, 0x190D9), or an individual
 *            one (Table 15: degree up to 8, its x^0 term always set); start
 *            value 0 ("a typical default", Table 16) or any below 2^width
 *   position single-turn 10..26 bits and multi-turn 0, 12, 16 or 24 bits
 *            ([POS] MT24 + ST17, [AD38] MT12 + ST24), 1..50 revolutions a
 *            second either way (the envelope; [AD38]'s and
 *            [POS]'s shafts), from a random position
 *   fill     sometimes 1..7 zeros after the position ([POS]: 7 fill bits)
 *   nE/nW    present or not ([MB4] "BiSS C Frame": optional error and
 *            warning bits; [AD38] and [POS] have them)
 *   counter  none, 2..8 bits ([AD38] slave 3: 6) or 9..16 bits, at the
 *            word's LSB, with or without nE/nW above it
 *   timing   processing time 0 or up to 5 us and busy clocks 0..16
 *            ([TI] §2.1.2; [AD38] 2.3-2.5 us), a fixed 20 us timeout or an
 *            adaptive one with [AD38]'s 650 ns floor
 *
 * Layout k covers one corner for certain (k % 8): a counter without nE/nW,
 * one with them, nE/nW alone, neither, a counter without nE/nW and a CRC-16,
 * a counter with nE/nW and a 3..5-bit CRC, and twice all at random; and its
 * speed (k % 5): 1 rev/s, 50 rev/s, or drawn. */
#include "probe_gen.h"

#include "biss_crc.h"
#include "test_rng.h"

#include <stdio.h>

static uint32_t rnd(uint64_t *rng, uint32_t n) { /* 0..n-1 */
    return test_rng_next(rng) % n;
}

static double uniform(uint64_t *rng, double lo, double hi) {
    return lo + (hi - lo) * (test_rng_next(rng) / 4294967296.0);
}

static uint32_t crc_poly(uint64_t *rng, unsigned min_w, unsigned max_w) {
    static const uint32_t table14[] = {0xB, 0x13, 0x25, 0x43, 0x89, 0x12F, 0x190D9};
    for (;;) {
        uint32_t p;
        if (rnd(rng, 10) < 7) {
            p = table14[rnd(rng, sizeof table14 / sizeof table14[0])];
        } else { /* Table 15: degree 3..8, x^0 set */
            unsigned w = 3 + rnd(rng, 6);
            p = 1u << w | rnd(rng, 1u << w) | 1u;
        }
        unsigned w = biss_crc_width(p);
        if (w >= min_w && w <= max_w) {
            return p;
        }
    }
}

void probe_gen_layout(uint64_t *rng, unsigned k, biss_chain_cfg *cfg, char *what, size_t len) {
    biss_chain_cfg_default(cfg);
    biss_slave_cfg *s = &cfg->s[0];
    biss_slave_cfg_default(s, 0);
    unsigned corner = k % 8;
    bool lc, ew;
    unsigned cmin = 3, cmax = 16;
    switch (corner) {
    case 0:
        lc = true, ew = false;
        break;
    case 1:
        lc = true, ew = true;
        break;
    case 2:
        lc = false, ew = true;
        break;
    case 3:
        lc = false, ew = false;
        break;
    case 4:
        lc = true, ew = false, cmin = 16;
        break;
    case 5:
        lc = true, ew = true, cmax = 5;
        break;
    default:
        lc = rnd(rng, 2), ew = rnd(rng, 2);
        break;
    }
    s->crc_poly = crc_poly(rng, cmin, cmax);
    unsigned c = biss_crc_width(s->crc_poly);
    s->crc_start = rnd(rng, 2) ? 0 : rnd(rng, 1u << c);
    s->has_err = s->has_warn = ew;
    s->lc_bits = !lc ? 0 : rnd(rng, 4) ? 2 + rnd(rng, 7) : 9 + rnd(rng, 8);
    s->fill_bits = rnd(rng, 8) == 0 ? 1 + rnd(rng, 7) : 0;
    static const unsigned mt_bits[] = {0, 12, 16, 24};
    unsigned st = 10 + rnd(rng, 17), mt = mt_bits[rnd(rng, 4)];
    unsigned room = 64 - s->lc_bits - s->fill_bits - (ew ? 2 : 0);
    if (st + mt > room) {
        mt = st < room ? room - st : 0;
        st = st < room ? st : room;
    }
    s->pos_bits = st + mt;
    uint64_t mask = s->pos_bits >= 64 ? ~0ull : (1ull << s->pos_bits) - 1u;
    s->pos0 = ((uint64_t)test_rng_next(rng) << 32 | test_rng_next(rng)) & mask;
    double rps = k % 5 == 0 ? 1.0 : k % 5 == 1 ? 50.0 : uniform(rng, 1.0, 50.0);
    s->speed_cps = (rnd(rng, 2) ? 1.0 : -1.0) * rps * (double)(1ull << st);
    if (rnd(rng, 2)) {
        cfg->busy_ps = (sim_ps)rnd(rng, 5001) * SIM_PS_PER_NS;
        cfg->busy_clocks = rnd(rng, 17);
    }
    if (rnd(rng, 2)) {
        cfg->timeout_mode = BISS_TIMEOUT_ADAPTIVE;
        cfg->adaptive_factor = 1.5;
        cfg->adaptive_min_ps = 650 * SIM_PS_PER_NS;
    }
    snprintf(what, len,
             "layout %3u: pos %u (ST %u) fill %u ew %d lc %u CRC 0x%x start 0x%x, %.1f rev/s, "
             "busy %lld ns/%u, %s timeout",
             k, s->pos_bits, st, s->fill_bits, ew, s->lc_bits, s->crc_poly, s->crc_start,
             s->speed_cps / (double)(1ull << st), (long long)(cfg->busy_ps / SIM_PS_PER_NS),
             cfg->busy_clocks, cfg->timeout_mode == BISS_TIMEOUT_ADAPTIVE ? "adaptive" : "fixed");
}

int probe_gen_json(const biss_chain_cfg *cfg, char *buf, size_t len) {
    const biss_slave_cfg *s = &cfg->s[0];
    int n = snprintf(
        buf, len,
        "{\n  \"profile\": \"generic\",\n  \"biss\": {\n    \"busy_ns\": %lld, \"busy_clocks\": "
        "%u,\n    \"timeout\": { \"mode\": \"%s\", \"ns\": %lld, \"factor\": %g, \"min_ns\": "
        "%lld, \"max_ns\": %lld },\n    \"slaves\": [ { \"position_bits\": %u, \"fill_bits\": "
        "%u, \"error_bit\": %s, \"warning_bit\": %s, \"life_counter_bits\": %u, \"crc_poly\": "
        "\"0x%X\", \"crc_start\": \"0x%X\", \"position\": \"%llu\", \"speed_cps\": %.17g } ]\n  "
        "}\n}\n",
        (long long)(cfg->busy_ps / SIM_PS_PER_NS), cfg->busy_clocks,
        cfg->timeout_mode == BISS_TIMEOUT_ADAPTIVE ? "adaptive" : "fixed",
        (long long)(cfg->timeout_ps / SIM_PS_PER_NS), cfg->adaptive_factor,
        (long long)(cfg->adaptive_min_ps / SIM_PS_PER_NS),
        (long long)(cfg->adaptive_max_ps / SIM_PS_PER_NS), s->pos_bits, s->fill_bits,
        s->has_err ? "true" : "false", s->has_warn ? "true" : "false", s->lc_bits, s->crc_poly,
        s->crc_start, (unsigned long long)s->pos0, s->speed_cps);
    return n < 0 || (size_t)n >= len ? -1 : 0;
}

static bool slave_matches(const struct biss_probe_slave *p, const biss_slave_cfg *s) {
    return p->data_bits == biss_slave_cfg_data_bits(s) &&
           p->crc_bits == biss_crc_width(s->crc_poly) && p->crc_poly == s->crc_poly &&
           p->crc_start == s->crc_start;
}

bool probe_gen_layout_matches(const struct biss_probe_layout *l, const biss_chain_cfg *cfg) {
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

bool probe_gen_fields_match(const struct biss_probe_layout *l, const biss_chain_cfg *cfg) {
    for (unsigned i = 0; i < cfg->n; i++) {
        const biss_slave_cfg *s = &cfg->s[i];
        bool ew = s->has_err && s->has_warn;
        const struct biss_probe_slave *p = &l->slave[i];
        if (p->has_ew != ew || (ew && p->ew_shift != s->lc_bits) || p->lc_bits != s->lc_bits) {
            return false;
        }
    }
    return true;
}

enum probe_outcome probe_gen_judge(const struct biss_probe_result *r, const biss_chain_cfg *cfg) {
    switch (r->verdict) {
    case BISS_PROBE_UNIQUE:
    case BISS_PROBE_BEST:
        return probe_gen_layout_matches(&r->layout[0], cfg) &&
                       probe_gen_fields_match(&r->layout[0], cfg)
                   ? PROBE_RECOVERED
                   : PROBE_WRONG;
    case BISS_PROBE_AMBIGUOUS:
        for (unsigned i = 0; i < r->nkept; i++) {
            if (probe_gen_layout_matches(&r->layout[i], cfg)) {
                return PROBE_AMBIGUOUS_OK;
            }
        }
        return r->nlayouts > r->nkept ? PROBE_AMBIGUOUS_OK : PROBE_WRONG;
    case BISS_PROBE_NONE:
        return PROBE_UNDECIDED;
    }
    return PROBE_WRONG;
}
