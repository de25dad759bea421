/* biss_probe_layout.c - the slave layout from raw frames (no I/O).
 *
 * Every slave sends its data word and then its CRC, inverted, over that
 * word, from a start value ([MB4] "CRC polynomial" and start values; the
 * slave model builds frames the same way, emulator/slave/biss_slave.c).
 * A CRC is linear: for a data length d, crc(start, data) = crc(0, data) ^
 * crc(start, 0...0). So for the right split (d data bits, c CRC bits,
 * polynomial P) the value crc(0, data_i) ^ ~received_crc_i is the same
 * constant K in every frame i, and K gives the start value (undo d zero
 * steps of the CRC register). No search over start values is needed.
 *
 * The search per slave offset: every width c = 3..16 and every polynomial
 * of that degree (top term set) with an x^0 term: one without it is x
 * times another, its last CRC bit constant; no CRC uses one, and it would
 * fit any constant bits after a slave. The polynomials come from the XOR
 * of a reference frame with a few others ("probes"), where the start value
 * and the inversion cancel: one fits a probe with d data bits when it
 * divides the probe's first d + c bits read as a polynomial, so they are
 * the divisors of the probes' gcd (search_probes). Candidates are checked
 * on every frame (the support: frames whose K is the most common one). A
 * chain is a sequence of such slaves ending where the frame ends. The whole
 * of it runs within a budget of work and time (biss_probe_budget.c). */
#include "biss_probe_gf2.h"
#include "biss_probe_priv.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define MAX_PROBES       6
#define MAX_SEGS         256                 /* candidate slaves kept per offset */
#define MAX_OFFSETS      BISS_PROBE_MAX_BITS /* offsets searched (a chain's slave boundaries) */
#define MAX_COUNTED      100000
#define BEST_MIN_RANK    8   /* evidence to prefer the widest CRC (see verdict()) */
#define SUPPORT_PERMILLE 600 /* a fit needs 60 % of the frames (the rest: noise) */
#define WIN              (64 + BISS_PROBE_MAX_CRC)

struct ctx;
static void evidence(const struct ctx *x, uint32_t key, unsigned o, unsigned d, unsigned *rank,
                     unsigned *distinct);
static uint32_t gf2_mod(uint32_t a, uint32_t b);

static int cmp_u64(const void *a, const void *b) {
    uint64_t x = *(const uint64_t *)a, y = *(const uint64_t *)b;
    return x < y ? -1 : x > y;
}

struct seg {
    unsigned d, c;
    uint32_t poly, start;
    unsigned support, distinct, rank, stuck;
};

struct seglist {
    bool done;
    unsigned n;
    struct seg s[MAX_SEGS];
};

/* The layouts from one offset on, with so many slaves before it. */
struct dp {
    bool done;
    double total;  /* layouts */
    double best;   /* the highest score (score()) */
    double n_best; /* layouts with it */
};

struct ctx {
    const struct biss_probe_frames *f;
    unsigned ref;           /* the frame the probes differ from */
    const uint8_t *suspect; /* frames that look hit by noise: never a probe (see suspects()) */
    uint32_t *keys;         /* per frame: the last candidate's K (support_of) */
    unsigned end;           /* payload bits up to the last 1 */
    struct seglist *cache;  /* per payload offset */
    unsigned offsets_searched;
    bool cut;           /* a limit was reached */
    unsigned set_aside; /* fits dropped for a wider one they divide (drop_factors) */
    bool cut_counted;   /* MAX_COUNTED among the limits reached */
    bool cut_search;    /* MAX_OFFSETS or MAX_SEGS: fits never seen */
    struct dp *dp;      /* per (offset, slaves so far): see count_from */
    struct probe_budget *b;
    struct biss_probe_result *r;
    struct biss_probe_layout cur;
};

#define bit_at  probe_bit
#define word_at probe_word

static inline uint32_t crc_step(uint32_t reg, uint32_t low, unsigned c, int bit) {
    uint32_t fb = ((reg >> (c - 1)) & 1u) ^ (uint32_t)bit;
    reg = (reg << 1) & ((1u << c) - 1u);
    return fb ? reg ^ low : reg;
}

static uint32_t crc0(uint64_t data, unsigned d, uint32_t low, unsigned c) {
    uint32_t reg = 0;
    for (unsigned k = d; k > 0; k--) {
        reg = crc_step(reg, low, c, (int)((data >> (k - 1)) & 1u));
    }
    return reg;
}

/* The start value s with crc(s, d zeros) == k; false if none. An odd
 * polynomial makes the step invertible (the new LSB is the feedback). */
static bool start_of(uint32_t k, unsigned d, uint32_t low, unsigned c, uint32_t *s) {
    if (low & 1u) {
        uint32_t reg = k;
        for (unsigned i = 0; i < d; i++) {
            uint32_t fb = reg & 1u;
            uint32_t t = fb ? reg ^ low : reg;
            reg = (t >> 1) | (fb << (c - 1));
        }
        *s = reg;
        return true;
    }
    for (uint32_t cand = 0; cand < (1u << c); cand++) {
        uint32_t reg = cand;
        for (unsigned i = 0; i < d; i++) {
            reg = crc_step(reg, low, c, 0);
        }
        if (reg == k) {
            *s = cand;
            return true;
        }
    }
    return false;
}

static uint32_t key_of(const struct biss_probe_frames *f, unsigned i, unsigned o, unsigned d,
                       unsigned c, uint32_t low) {
    uint32_t mask = (1u << c) - 1u;
    return crc0(word_at(f, i, o, d), d, low, c) ^ (~(uint32_t)word_at(f, i, o + d, c) & mask);
}

#define SAMPLE 32 /* frames a candidate is first tried on */

/* Every frame: K_i = crc0(data_i) ^ ~crc_i; the most common K and how
 * many frames have it (Boyer-Moore majority, then a count). A candidate
 * is first tried on SAMPLE frames spread over the capture: one whose most
 * common K there has fewer than half of them cannot reach the support a
 * fit needs (a wrong split fits a frame by chance 1 in 2^c), and is
 * dropped without reading every frame. */
static unsigned support_of(const struct ctx *x, unsigned o, unsigned d, unsigned c, uint32_t low,
                           uint32_t *k_out) {
    const struct biss_probe_frames *f = x->f;
    if (f->nframes >= 4 * SAMPLE) {
        uint32_t k[SAMPLE];
        unsigned best = 0;
        probe_budget_spend(x->b, (uint64_t)SAMPLE * (d + c + SAMPLE / 4));
        for (unsigned j = 0; j < SAMPLE; j++) {
            k[j] = key_of(f, j * (f->nframes / SAMPLE), o, d, c, low);
        }
        for (unsigned j = 0; j < SAMPLE && best < SAMPLE / 2; j++) {
            unsigned same = 0;
            for (unsigned q = 0; q < SAMPLE; q++) {
                same += k[q] == k[j];
            }
            best = same > best ? same : best;
        }
        if (best < SAMPLE / 2) {
            return 0;
        }
    }
    uint32_t *keys = x->keys, cand = 0;
    unsigned votes = 0, count = 0;
    probe_budget_spend(x->b, (uint64_t)f->nframes * (d + c + 2));
    for (unsigned i = 0; i < f->nframes; i++) {
        keys[i] = key_of(f, i, o, d, c, low);
        if (votes == 0) {
            cand = keys[i];
        }
        votes += keys[i] == cand ? 1 : (unsigned)-1;
    }
    for (unsigned i = 0; i < f->nframes; i++) {
        count += keys[i] == cand;
    }
    *k_out = cand;
    return count;
}

static void add_seg(struct seglist *l, const struct seg *s, bool *cut) {
    if (l->n < MAX_SEGS) {
        l->s[l->n++] = *s;
    } else {
        *cut = true;
    }
}

/* Bits in [p, p + n) that never change. A real CRC bit is a linear
 * function of the data that rarely vanishes on all data differences; one
 * that never changes marks a split moved onto a constant bit (the next
 * slave's first bit, say), which fits any CRC shifted by one place. */
static unsigned stuck_bits(const struct ctx *x, uint32_t key, unsigned p, unsigned n) {
    const struct biss_probe_frames *f = x->f;
    unsigned stuck = 0, first = 0;
    while (first < f->nframes && x->keys[first] != key) {
        first++;
    }
    for (unsigned k = 0; k < n && first < f->nframes; k++) {
        unsigned i = first + 1;
        while (i < f->nframes &&
               (x->keys[i] != key || bit_at(f, i, p + k) == bit_at(f, first, p + k))) {
            i++;
        }
        stuck += i == f->nframes;
    }
    return stuck;
}

/* Frames whose bits in [o, o + WIN) differ from frame 0's, those that
 * differ earliest first (a difference that starts after a slave's CRC says
 * nothing about it): the differences every polynomial is first tried on.
 * *first gets the earliest differing bit. */
static unsigned pick_probes(const struct ctx *x, unsigned o, unsigned len,
                            uint8_t diff[MAX_PROBES][WIN], unsigned *first) {
    const struct biss_probe_frames *f = x->f;
    static _Thread_local unsigned at[BISS_PROBE_MAX_FRAMES]; /* first differing bit */
    at[x->ref] = len; /* the reference itself is never a probe */
    probe_budget_spend(x->b, (uint64_t)f->nframes * len);
    for (unsigned i = 0; i < f->nframes; i++) {
        if (i == x->ref || x->suspect[i]) {
            at[i] = len;
            continue;
        }
        unsigned p = 0;
        while (p < len && bit_at(f, i, o + p) == bit_at(f, x->ref, o + p)) {
            p++;
        }
        at[i] = p;
    }
    unsigned np = 0;
    *first = len;
    for (unsigned k = 0; k < len && np < MAX_PROBES; k++) {
        for (unsigned i = 0; i < f->nframes && np < MAX_PROBES; i++) {
            if (at[i] != k) {
                continue;
            }
            bool dup = false;
            for (unsigned j = 0; j < np && !dup; j++) {
                dup = true;
                for (unsigned q = k; q < len && dup; q++) {
                    dup = diff[j][q] == (bit_at(f, i, o + q) ^ bit_at(f, x->ref, o + q));
                }
            }
            if (dup) {
                continue;
            }
            for (unsigned q = 0; q < len; q++) {
                diff[np][q] = (uint8_t)(bit_at(f, i, o + q) ^ bit_at(f, x->ref, o + q));
            }
            *first = k < *first ? k : *first;
            np++;
        }
    }
    return np;
}

/* Data lengths (bit d-1 of the mask = length d) for which polynomial low
 * of degree c fits the probe differences: all of them, or with four probes
 * or more all but one (a frame hit by noise). */
static uint64_t fits_probes(uint8_t diff[MAX_PROBES][WIN], uint32_t win[MAX_PROBES][WIN],
                            unsigned np, unsigned dmax, uint32_t low, unsigned c) {
    uint64_t all = dmax >= 64 ? ~0ull : (1ull << dmax) - 1u;
    uint64_t failed = 0, dead = np >= 4 ? 0 : ~0ull; /* dead: a second failure kills */
    uint64_t out = 0;
    for (unsigned j = 0; j < np && out != all; j++) {
        uint32_t reg = 0;
        uint64_t miss = 0;
        for (unsigned d = 1; d <= dmax; d++) {
            reg = crc_step(reg, low, c, diff[j][d - 1]);
            if (reg != win[j][d]) {
                miss |= 1ull << (d - 1);
            }
        }
        out |= miss & (failed | dead);
        failed |= miss;
    }
    return all & ~out;
}

/* A candidate data length d for polynomial (1 << c) | low. */
struct cand {
    uint32_t low;
    unsigned d;
};

#define MAX_CANDS 2048 /* per CRC width and offset */
#define GF2_STEP  3    /* a two-word polynomial step costs about three CRC steps */

static int cand_cmp(const void *pa, const void *pb) {
    const struct cand *a = pa, *b = pb;
    if (a->low != b->low) {
        return a->low < b->low ? -1 : 1;
    }
    return a->d < b->d ? -1 : a->d > b->d;
}

/* Checks a candidate on every frame and keeps it as a slave if it fits. */
static void try_cand(struct ctx *x, unsigned o, unsigned c, const struct cand *k,
                     struct seglist *l) {
    const struct biss_probe_frames *f = x->f;
    uint32_t key = 0, start;
    unsigned sup = support_of(x, o, k->d, c, k->low, &key);
    if ((uint64_t)sup * 1000 < (uint64_t)f->nframes * SUPPORT_PERMILLE ||
        !start_of(key, k->d, k->low, c, &start)) {
        return;
    }
    struct seg s = {k->d, c, (1u << c) | k->low, start, sup, 0, 0, 0};
    probe_budget_spend(x->b, (uint64_t)f->nframes * (k->d + c));
    evidence(x, key, o, k->d, &s.rank, &s.distinct);
    s.stuck = stuck_bits(x, key, o + k->d, c);
    add_seg(l, &s, &x->cut_search);
}

/* One probe: every polynomial is run over the difference (the CRC register
 * after d bits against the received difference, all d in one pass). */
static void search_one_probe(struct ctx *x, unsigned o, unsigned avail, unsigned first,
                             uint8_t diff[MAX_PROBES][WIN], struct seglist *l) {
    static _Thread_local uint32_t win[MAX_PROBES][WIN];
    for (unsigned c = BISS_PROBE_MIN_CRC; c <= BISS_PROBE_MAX_CRC && c < avail && !x->b->ran_out;
         c++) {
        unsigned dmax = avail - c < 64 ? avail - c : 64;
        /* win[0][d]: the c-bit difference of the received CRCs after d data bits */
        for (unsigned d = 1; d <= dmax; d++) {
            uint32_t w = 0;
            for (unsigned k = 0; k < c; k++) {
                w = w << 1 | diff[0][d + k];
            }
            win[0][d] = w;
        }
        for (uint32_t low = 1; low < (1u << c); low += 2) { /* with x^0: see top */
            if (probe_budget_spend(x->b, dmax)) {
                return;
            }
            uint64_t alive = fits_probes(diff, win, 1, dmax, low, c);
            /* a split whose bits never change fits every polynomial: no evidence */
            if (first > c) {
                unsigned vacuous = first - c; /* d + c <= first */
                alive &= vacuous >= 64 ? 0 : ~0ull << vacuous;
            }
            for (unsigned d = 1; alive && d <= dmax; d++) {
                if (alive & (1ull << (d - 1))) {
                    alive &= ~(1ull << (d - 1));
                    try_cand(x, o, c, &(struct cand){low, d}, l);
                }
            }
        }
    }
}

/* The odd divisors of g (odd: no factor x) of degree c, as their low c
 * bits; through the cofactor of degree m - c when that is the smaller. */
static unsigned odd_divisors(gf2x g, unsigned c, uint32_t *out, struct probe_budget *b) {
    int m = gf2x_deg(g);
    uint64_t steps = 0;
    unsigned n = 0;
    if (m < (int)c) {
        return 0;
    }
    if (m == (int)c) {
        out[n++] = (uint32_t)g.lo & ((1u << c) - 1u);
        return n;
    }
    unsigned k = (unsigned)m - c;
    if (k < c) {
        for (uint32_t q = (1u << k) | 1u; q < (2u << k); q += 2) {
            if (gf2x_zero(gf2x_mod(g, (gf2x){0, q}, &steps))) {
                out[n++] = (uint32_t)gf2x_div(g, (gf2x){0, q}, &steps).lo & ((1u << c) - 1u);
            }
        }
    } else {
        for (uint32_t p = (1u << c) | 1u; p < (2u << c); p += 2) {
            if (gf2x_zero(gf2x_mod(g, (gf2x){0, p}, &steps))) {
                out[n++] = p & ((1u << c) - 1u);
            }
        }
    }
    probe_budget_spend(b, GF2_STEP * steps + (1ull << (k < c ? k : c)));
    return n;
}

/* Several probes. A polynomial P of degree c fits probe j's difference
 * with d data bits exactly when P divides the window of its first d + c
 * bits read as a polynomial (the CRC register after d bits is the data
 * times x^c mod P, and it must equal the next c bits). So the polynomials
 * that fit every probe divide the windows' greatest common divisor, and
 * with four probes or more those that fit all but one divide the gcd of
 * the others (a frame hit by noise). Windows the same for every probe
 * (all zero: nothing changes there) prove nothing and are skipped. A
 * random window shares no factor of degree 3 or more with another, so
 * most offsets and lengths have no candidate at all. */
static void search_probes(struct ctx *x, unsigned o, unsigned avail, unsigned np,
                          uint8_t diff[MAX_PROBES][WIN], struct seglist *l) {
    static _Thread_local struct cand cands[BISS_PROBE_MAX_CRC + 1][MAX_CANDS];
    static _Thread_local uint32_t div[1u << 15];
    unsigned ncand[BISS_PROBE_MAX_CRC + 1] = {0};
    unsigned len = avail < WIN ? avail : WIN;
    gf2x w[MAX_PROBES] = {{0, 0}};
    for (unsigned n = 1; n <= len && !x->b->ran_out; n++) {
        uint64_t steps = 0;
        for (unsigned j = 0; j < np; j++) {
            w[j] = gf2x_push(w[j], diff[j][n - 1]);
        }
        /* g[0]: the gcd of all; g[1 + j]: of all but probe j (prefix and
         * suffix gcds) */
        gf2x g[MAX_PROBES + 1], pre[MAX_PROBES + 1], suf[MAX_PROBES + 1];
        pre[0] = suf[np] = (gf2x){0, 0};
        for (unsigned j = 0; j < np; j++) {
            pre[j + 1] = gf2x_gcd(w[j], pre[j], &steps);
        }
        g[0] = pre[np];
        unsigned ng = 1;
        if (np >= 4) {
            for (unsigned j = np; j-- > 0;) {
                suf[j] = gf2x_gcd(w[j], suf[j + 1], &steps);
            }
            for (unsigned j = 0; j < np; j++) {
                g[ng++] = gf2x_gcd(pre[j], suf[j + 1], &steps);
            }
        }
        probe_budget_spend(x->b, GF2_STEP * steps + np);
        for (unsigned i = 0; i < ng; i++) {
            bool seen = gf2x_zero(g[i]);
            for (unsigned k = 0; k < i && !seen; k++) {
                seen = g[k].hi == g[i].hi && g[k].lo == g[i].lo;
            }
            if (seen) {
                continue;
            }
            gf2x odd = g[i];
            while (!(odd.lo & 1u)) {
                odd = gf2x_shr1(odd);
            }
            for (unsigned c = BISS_PROBE_MIN_CRC; c <= BISS_PROBE_MAX_CRC && c < n; c++) {
                unsigned d = n - c;
                if (d > 64 || c >= avail) {
                    continue;
                }
                unsigned nd = odd_divisors(odd, c, div, x->b);
                for (unsigned k = 0; k < nd; k++) {
                    if (ncand[c] == MAX_CANDS) {
                        x->cut_search = true;
                        break;
                    }
                    cands[c][ncand[c]++] = (struct cand){div[k], d};
                }
            }
        }
    }
    /* in the order one polynomial after another would find them */
    for (unsigned c = BISS_PROBE_MIN_CRC; c <= BISS_PROBE_MAX_CRC && !x->b->ran_out; c++) {
        qsort(cands[c], ncand[c], sizeof cands[c][0], cand_cmp);
        for (unsigned k = 0; k < ncand[c] && !x->b->ran_out; k++) {
            if (k == 0 || cand_cmp(&cands[c][k], &cands[c][k - 1]) != 0) {
                try_cand(x, o, c, &cands[c][k], l);
            }
        }
    }
}

static void search_offset(struct ctx *x, unsigned o, struct seglist *l) {
    unsigned avail = x->end - o;
    unsigned len = avail < WIN ? avail : WIN;
    static _Thread_local uint8_t diff[MAX_PROBES][WIN];
    unsigned first;
    unsigned np = pick_probes(x, o, len, diff, &first);
    if (np == 0) {
        return; /* nothing changes here: every polynomial would fit */
    }
    if (np == 1) {
        search_one_probe(x, o, avail, first, diff, l);
    } else {
        search_probes(x, o, avail, np, diff, l);
    }
}

/* The order layout_cmp ranks by, per slave. */
static int seg_cmp(const void *pa, const void *pb) {
    const struct seg *a = pa, *b = pb;
    if (a->support != b->support) {
        return a->support > b->support ? -1 : 1;
    }
    if ((a->rank < 2) != (b->rank < 2)) {
        return a->rank < 2 ? 1 : -1;
    }
    if (a->stuck != b->stuck) {
        return a->stuck < b->stuck ? -1 : 1;
    }
    if (a->c != b->c) {
        return a->c > b->c ? -1 : 1;
    }
    return 0;
}

/* Whether g makes s redundant: the same bits, a wider CRC that s's
 * polynomial divides (so s fits wherever g does: a polynomial with an even
 * number of terms is (x + 1) times one of degree one less, and that one
 * fits with one data bit more), no constant CRC bit, and the evidence
 * verdict() asks for before it prefers the wider CRC. A chain of such
 * slaves would otherwise multiply its layouts (2^8 for eight) past the
 * search limits. Support is no argument for s: the frames g fits are
 * among those s fits, and the rest are frames hit by noise that pass the
 * narrower check by chance (1 in 2^c) more often than the wider one. */
static bool dominates(const struct seg *g, const struct seg *s) {
    return g->d + g->c == s->d + s->c && g->c > s->c && gf2_mod(g->poly, s->poly) == 0 &&
           g->stuck == 0 && (g->rank >= BEST_MIN_RANK || g->rank >= g->d);
}

static void drop_factors(struct ctx *x, struct seglist *l) {
    unsigned kept = 0;
    for (unsigned i = 0; i < l->n; i++) {
        bool dropped = false;
        for (unsigned j = 0; j < l->n && !dropped; j++) {
            dropped = j != i && dominates(&l->s[j], &l->s[i]);
        }
        if (dropped) {
            x->set_aside++;
        } else {
            l->s[kept++] = l->s[i];
        }
    }
    l->n = kept;
}

static const struct seglist *segs_at(struct ctx *x, unsigned o) {
    struct seglist *l = &x->cache[o];
    if (!l->done) {
        l->done = true;
        x->b->offsets_searched++;
        if (x->offsets_searched++ >= MAX_OFFSETS) {
            x->cut = x->cut_search = true;
            return l;
        }
        search_offset(x, o, l);
        x->cut |= x->cut_search;
        drop_factors(x, l);
        /* the likeliest first: when a long chain's layouts pass the search
         * limits, the ones recorded are the best per slave */
        qsort(l->s, l->n, sizeof l->s[0], seg_cmp);
    }
    return l;
}

static int layout_cmp(const struct biss_probe_layout *a, const struct biss_probe_layout *b) {
    if (a->support != b->support) {
        return a->support > b->support ? -1 : 1;
    }
    if (a->weak != b->weak) {
        return a->weak ? 1 : -1;
    }
    if (a->crc_stuck != b->crc_stuck) {
        return a->crc_stuck < b->crc_stuck ? -1 : 1;
    }
    if (a->crc_total != b->crc_total) {
        return a->crc_total > b->crc_total ? -1 : 1;
    }
    if (a->nslaves != b->nslaves) {
        return a->nslaves < b->nslaves ? -1 : 1;
    }
    return 0;
}

/* Keeps the best BISS_PROBE_MAX_LAYOUTS, in order. */
static void record(struct ctx *x) {
    struct biss_probe_result *r = x->r;
    struct biss_probe_layout l = x->cur;
    l.support = ~0u;
    l.crc_total = 0;
    l.weak = false;
    l.crc_stuck = 0;
    for (unsigned i = 0; i < l.nslaves; i++) {
        l.crc_stuck += l.slave[i].crc_stuck;
        l.weak |= l.slave[i].rank < 2;
        l.support = l.slave[i].support < l.support ? l.slave[i].support : l.support;
        l.crc_total += l.slave[i].crc_bits;
    }
    r->nlayouts++;
    unsigned pos = r->nkept;
    while (pos > 0 && layout_cmp(&l, &r->layout[pos - 1]) < 0) {
        pos--;
    }
    if (pos >= BISS_PROBE_MAX_LAYOUTS) {
        return;
    }
    unsigned last = r->nkept < BISS_PROBE_MAX_LAYOUTS ? r->nkept : BISS_PROBE_MAX_LAYOUTS - 1;
    memmove(&r->layout[pos + 1], &r->layout[pos], (last - pos) * sizeof l);
    r->layout[pos] = l;
    if (r->nkept < BISS_PROBE_MAX_LAYOUTS) {
        r->nkept++;
    }
}

static const struct dp *count_from(struct ctx *x, unsigned o, unsigned depth);

/* Records every layout from offset o on. A slave after which no chain
 * reaches the frame's end is skipped (count_from knows): with many fits per
 * offset (garbage frames) the dead ends would otherwise be walked again
 * from every way into them. */
static void walk(struct ctx *x, unsigned o) {
    const struct seglist *l = segs_at(x, o);
    for (unsigned i = 0; i < l->n; i++) {
        const struct seg *s = &l->s[i];
        unsigned next = o + s->d + s->c;
        if (next > x->end || (next < x->end && x->cur.nslaves + 1 >= BISS_API_MAX_SLAVES)) {
            continue;
        }
        if (probe_budget_spend(x->b, 1)) {
            return;
        }
        if (next < x->end && count_from(x, next, x->cur.nslaves + 1)->total == 0) {
            continue;
        }
        if (x->r->nlayouts >= MAX_COUNTED) {
            x->cut = true;
            x->cut_counted = true;
            return;
        }
        struct biss_probe_slave *ps = &x->cur.slave[x->cur.nslaves++];
        memset(ps, 0, sizeof *ps);
        ps->offset = o;
        ps->data_bits = s->d;
        ps->crc_bits = s->c;
        ps->crc_poly = s->poly;
        ps->crc_start = s->start;
        ps->support = s->support;
        ps->rank = s->rank;
        ps->crc_stuck = s->stuck;
        ps->distinct = s->distinct;
        if (next == x->end) {
            record(x);
        } else {
            walk(x, next);
        }
        x->cur.nslaves--;
    }
}

/* ---- counting past the limit ------------------------------------------------
 * A long chain whose slaves each fit a few ways (a CRC-16 with an even
 * number of terms and a next slave whose first bits never change: the
 * split moves by a bit) has more layouts than walk() may record. They are
 * a product, so counting them is cheap: per offset and slaves so far, the
 * number of completions and how many reach the best score. */

/* layout_cmp's order after support, additive: no weak slave, fewer
 * constant CRC bits, more CRC bits. */
static double score(const struct seg *s) {
    return (s->rank < 2 ? -1e6 : 0.0) - 1000.0 * s->stuck + s->c;
}

static const struct dp *count_from(struct ctx *x, unsigned o, unsigned depth) {
    struct dp *e = &x->dp[(size_t)o * (BISS_API_MAX_SLAVES + 1) + depth];
    if (e->done) {
        return e;
    }
    e->done = true;
    e->best = -1e300;
    const struct seglist *l = segs_at(x, o);
    probe_budget_spend(x->b, l->n);
    for (unsigned i = 0; i < l->n; i++) {
        const struct seg *s = &l->s[i];
        unsigned next = o + s->d + s->c;
        if (next > x->end || (next < x->end && depth + 1 >= BISS_API_MAX_SLAVES)) {
            continue;
        }
        double total = 1.0, best = score(s), n_best = 1.0;
        if (next < x->end) {
            const struct dp *t = count_from(x, next, depth + 1);
            total = t->total;
            best += t->best;
            n_best = t->n_best;
            if (t->total == 0) {
                continue;
            }
        }
        e->total += total;
        if (best > e->best) {
            e->best = best;
            e->n_best = n_best;
        } else if (best == e->best) {
            e->n_best += n_best;
        }
    }
    return e;
}

static double layout_score(const struct biss_probe_layout *l) {
    double v = 0;
    for (unsigned i = 0; i < l->nslaves; i++) {
        const struct biss_probe_slave *s = &l->slave[i];
        struct seg g = {.c = s->crc_bits, .rank = s->rank, .stuck = s->crc_stuck};
        v += score(&g);
    }
    return v;
}

/* After walk() stopped at MAX_COUNTED alone: the exact count, and whether
 * the first layout recorded is the only one with the best score and fits
 * every frame (then no layout left unseen ranks with it). */
static bool count_layouts(struct ctx *x, double *total) {
    const struct dp *e = count_from(x, 0, 0);
    bool complete = !x->cut_search; /* no new search hit a limit */
    *total = e->total;
    const struct biss_probe_layout *a = &x->r->layout[0];
    bool first_alone = complete && x->r->nkept && e->n_best == 1.0 && layout_score(a) == e->best &&
                       a->support == x->r->frames;
    return first_alone;
}

/* ---- per slave: evidence ------------------------------------------------- */

/* Distinct data words and the rank (over GF(2)) of their differences,
 * over the frames the candidate fits (keys[i] == key): a frame hit by
 * noise would add a difference the encoder never made. */
static void evidence(const struct ctx *x, uint32_t key, unsigned o, unsigned d, unsigned *rank,
                     unsigned *distinct) {
    const struct biss_probe_frames *f = x->f;
    uint64_t *v = malloc(f->nframes * sizeof *v);
    uint64_t basis[64] = {0};
    unsigned n = 0;
    *rank = *distinct = 0;
    if (!v) {
        return;
    }
    for (unsigned i = 0; i < f->nframes; i++) {
        if (x->keys[i] != key) {
            continue;
        }
        v[n] = word_at(f, i, o, d);
        uint64_t w = v[n] ^ v[0];
        n++;
        for (int b = 63; b >= 0 && w; b--) {
            if (!(w >> b & 1u)) {
                continue;
            }
            if (!basis[b]) {
                basis[b] = w;
                (*rank)++;
                break;
            }
            w ^= basis[b];
        }
    }
    qsort(v, n, sizeof *v, cmp_u64);
    *distinct = n > 0;
    for (unsigned i = 1; i < n; i++) {
        *distinct += v[i] != v[i - 1];
    }
    free(v);
}

/* ---- verdict --------------------------------------------------------------- */

static unsigned min_rank(const struct biss_probe_layout *l) {
    unsigned r = ~0u;
    for (unsigned i = 0; i < l->nslaves; i++) {
        r = l->slave[i].rank < r ? l->slave[i].rank : r;
    }
    return r;
}

/* Remainder of a by b over GF(2) (both with their top terms, degree <= 16). */
static uint32_t gf2_mod(uint32_t a, uint32_t b) {
    int db = 31 - __builtin_clz(b);
    for (int da = a ? 31 - __builtin_clz(a) : -1; da >= db; da = a ? 31 - __builtin_clz(a) : -1) {
        a ^= b << (da - db);
    }
    return a;
}

/* Whether another fit covers the same bits with a polynomial that divides
 * this one's or is divided by it: a narrower P fits wherever P * M does. */
static bool related_fit(const struct ctx *x, const struct biss_probe_slave *s) {
    const struct seglist *l = &x->cache[s->offset];
    for (unsigned i = 0; i < l->n; i++) {
        const struct seg *g = &l->s[i];
        if (g->d + g->c != s->data_bits + s->crc_bits || g->poly == s->crc_poly) {
            continue;
        }
        if (gf2_mod(s->crc_poly, g->poly) == 0 || gf2_mod(g->poly, s->crc_poly) == 0) {
            return true;
        }
    }
    return false;
}

/* Enough evidence to name the first layout: per slave, its data
 * differences span BEST_MIN_RANK directions or all of its data word (then
 * they include the codeword P * 1 itself, so no wider multiple P * M can
 * fit), or no fit over the same bits has a related polynomial (a wider
 * P * M fitting by chance would leave the truth P as such a fit). */
static bool enough_evidence(const struct ctx *x, const struct biss_probe_layout *l) {
    for (unsigned i = 0; i < l->nslaves; i++) {
        const struct biss_probe_slave *s = &l->slave[i];
        if (s->rank < BEST_MIN_RANK && s->rank < s->data_bits && related_fit(x, s)) {
            return false;
        }
    }
    return true;
}

/* The verdict of a search a limit stopped. */
static void ran_out(struct ctx *x) {
    struct biss_probe_result *r = x->r;
    const struct probe_budget *b = x->b;
    char limit[96];
    if (b->ran_out == BISS_PROBE_RAN_OUT_TIME) {
        snprintf(limit, sizeof limit, "the time limit");
    } else {
        snprintf(limit, sizeof limit, "the work limit (%.3g steps)", (double)b->limit);
    }
    r->verdict = r->nlayouts ? BISS_PROBE_AMBIGUOUS : BISS_PROBE_NONE;
    if (r->nlayouts) {
        snprintf(r->reason, sizeof r->reason,
                 "stopped at %s after %u of %u bit offsets: %u layouts fit so far, but not every "
                 "split was tried",
                 limit, x->offsets_searched, x->end, r->nlayouts);
    } else {
        snprintf(r->reason, sizeof r->reason,
                 "stopped at %s after %u of %u bit offsets with no layout found yet: a "
                 "longer search may find one, or the frames are noise (no BiSS chain's)",
                 limit, x->offsets_searched, x->end);
    }
}

/* With several fits the one with more CRC bits is preferred only when the
 * data differences have enough independent directions: a narrower CRC P
 * always fits where P*M does (a factor of a wider polynomial), but with
 * few differences a wider P*M can fit by chance where P is the truth. */
static void verdict(struct ctx *x) {
    struct biss_probe_result *r = x->r;
    if (x->b->ran_out) { /* not every split was tried: nothing is unique or best */
        ran_out(x);
        return;
    }
    const char *cut = x->cut ? " (search limits reached: more may fit)" : "";
    if (r->nlayouts == 0) {
        r->verdict = BISS_PROBE_NONE;
        snprintf(r->reason, sizeof r->reason,
                 "no split of the %u bits into slaves of data + CRC (3..16 bits) fits the frames "
                 "(an SSI encoder, or a CRC outside 3..16 bits?)%s",
                 x->end, cut);
        return;
    }
    const struct biss_probe_layout *a = &r->layout[0];
    double total = 0;
    bool only_counted = x->cut && x->cut_counted && !x->cut_search;
    if (only_counted && count_layouts(x, &total) && !a->weak && a->crc_stuck == 0 &&
        enough_evidence(x, a)) {
        r->verdict = BISS_PROBE_BEST;
        snprintf(r->reason, sizeof r->reason,
                 "%.0f layouts fit (counted); the first is the only best one: %u CRC bits, none "
                 "constant, every slave's data moving (evidence: %u independent differences)",
                 total, a->crc_total, min_rank(a));
        return;
    }
    if (x->cut) { /* not every fit was seen: nothing can be called unique or best */
        r->verdict = BISS_PROBE_AMBIGUOUS;
        snprintf(r->reason, sizeof r->reason,
                 "%u layouts fit, and the search stopped at its limits before trying all",
                 r->nlayouts);
        return;
    }
    if (r->nlayouts == 1) {
        r->verdict = BISS_PROBE_UNIQUE;
        snprintf(r->reason, sizeof r->reason, "one layout fits %u of %u frames%s", a->good,
                 r->frames, cut);
        return;
    }
    const struct biss_probe_layout *b = &r->layout[1];
    unsigned rank = min_rank(a);
    bool ahead = a->support > b->support || (!a->weak && b->weak) || a->crc_stuck < b->crc_stuck ||
                 a->crc_total > b->crc_total;
    if (ahead && !a->weak && a->crc_stuck == 0 && enough_evidence(x, a)) {
        r->verdict = BISS_PROBE_BEST;
        snprintf(r->reason, sizeof r->reason,
                 "%u layouts fit; the first checks %u CRC bits against %u of the next%s "
                 "(evidence: %u independent differences)%s",
                 r->nlayouts, a->crc_total, b->crc_total,
                 b->weak        ? " (which has a slave whose data hardly changed)"
                 : b->crc_stuck ? " (which has CRC bits that never change)"
                                : "",
                 rank, cut);
        return;
    }
    r->verdict = BISS_PROBE_AMBIGUOUS;
    snprintf(r->reason, sizeof r->reason,
             "%u layouts fit and the frames cannot tell them apart (evidence: %u independent "
             "differences; more frames with more motion help)%s",
             r->nlayouts, rank, cut);
}

/* A split the CRCs settle with fields inside it the frames do not (a life
 * counter that may be wider) is not unique or best. */
static void settle_fields(struct biss_probe_result *r) {
    if (r->verdict != BISS_PROBE_UNIQUE && r->verdict != BISS_PROBE_BEST) {
        return;
    }
    const struct biss_probe_layout *a = &r->layout[0];
    for (unsigned i = 0; i < a->nslaves; i++) {
        const struct biss_probe_slave *s = &a->slave[i];
        if (s->lc_open) {
            r->verdict = BISS_PROBE_AMBIGUOUS;
            snprintf(r->reason, sizeof r->reason,
                     "the CRCs settle the split (%u layout%s fit), but slave %u's life counter "
                     "may be wider than the %u bits that counted: it never wrapped and bit %u "
                     "above it never changed (the counter's top, nE/nW or fill alike; more "
                     "frames show more of it)",
                     r->nlayouts, r->nlayouts == 1 ? "" : "s", i, s->lc_bits, s->lc_bits);
            return;
        }
    }
}

static unsigned frame_end(const struct biss_probe_frames *f) {
    unsigned end = 0;
    for (unsigned i = 0; i < f->nframes; i++) {
        for (unsigned p = f->nbits - 1; p > end; p--) {
            if (bit_at(f, i, p - 1)) {
                end = p;
                break;
            }
        }
    }
    return end;
}

static bool all_alike(const struct biss_probe_frames *f, unsigned end) {
    for (unsigned i = 1; i < f->nframes; i++) {
        for (unsigned p = 0; p < end; p++) {
            if (bit_at(f, i, p) != bit_at(f, 0, p)) {
                return false;
            }
        }
    }
    return true;
}

/* The layouts of frames f ending at end, with the probes taken against
 * frame ref. */
/* Frames that look hit by noise (suspect[i] = 1): a 1 after the frame's
 * end, or a bit that hardly ever changes (in fewer than 1 in 16 pairs of
 * successive frames: a position's upper bits, nE/nW, fill) reading
 * otherwise in one frame than in the frames on either side, which agree.
 * Such a frame differs early from the others where the truth does not, so
 * it would be among the first probes; left out of the probes and the
 * references, a few noise frames cannot outvote the rest (they still count
 * against a layout's support, and are set aside when its CRCs fail them). */
static void suspects(const struct biss_probe_frames *f, unsigned end, uint8_t *suspect) {
    unsigned slow = f->nframes / 16;
    for (unsigned i = 0; i < f->nframes; i++) {
        suspect[i] = 0;
        for (unsigned p = end; p + 1 < f->nbits && !suspect[i]; p++) {
            suspect[i] = (uint8_t)bit_at(f, i, p);
        }
    }
    for (unsigned p = 0; p < end; p++) {
        unsigned toggles = 0;
        for (unsigned i = 1; i < f->nframes && toggles <= slow; i++) {
            toggles += bit_at(f, i, p) != bit_at(f, i - 1, p);
        }
        for (unsigned i = 1; i + 1 < f->nframes && toggles <= slow; i++) {
            int a = bit_at(f, i - 1, p), b = bit_at(f, i, p), c = bit_at(f, i + 1, p);
            suspect[i] |= a == c && b != a;
        }
    }
}

/* The layouts of frames f ending at end, with the probes taken against
 * frame ref (or the next that is not a suspect). */
static int search(const struct biss_probe_frames *f, unsigned end, unsigned ref,
                  struct probe_budget *b, struct biss_probe_result *r) {
    unsigned after_end = r->after_end;
    memset(r, 0, sizeof *r);
    r->frames = f->nframes;
    r->end_bit = end;
    r->after_end = after_end;
    b->end_bit = end;
    struct ctx x = {.f = f, .ref = ref, .end = end, .b = b, .r = r};
    x.cache = calloc(f->nbits, sizeof *x.cache);
    x.dp = calloc((size_t)f->nbits * (BISS_API_MAX_SLAVES + 1), sizeof *x.dp);
    x.keys = malloc(f->nframes * sizeof *x.keys);
    uint8_t *good = malloc(f->nframes), *suspect = malloc(f->nframes);
    int rc = x.cache && x.dp && x.keys && good && suspect ? BISS_OK : BISS_E_NOMEM;
    if (rc == BISS_OK) {
        probe_budget_spend(b, (uint64_t)f->nframes * f->nbits);
        suspects(f, end, suspect);
        for (unsigned k = 0; k < f->nframes && suspect[x.ref]; k++) {
            x.ref = (x.ref + 1) % f->nframes;
        }
        x.suspect = suspect;
        if (count_from(&x, 0, 0)->total > 0) {
            walk(&x, 0);
        }
        for (unsigned i = 0; i < r->nkept; i++) {
            struct biss_probe_layout *l = &r->layout[i];
            l->good = biss_probe_good_frames(f, l, good);
            for (unsigned s = 0; s < l->nslaves; s++) {
                biss_probe_fields(f, good, &l->slave[s]);
            }
        }
        r->dropped = r->nkept ? f->nframes - r->layout[0].good : 0;
        verdict(&x);
        settle_fields(r);
        if (x.set_aside && !b->ran_out) {
            size_t len = strlen(r->reason);
            snprintf(r->reason + len, sizeof r->reason - len,
                     "; %u narrower CRC fits set aside (factors of a wider fitting one)",
                     x.set_aside);
        }
    }
    free(x.cache);
    free(x.dp);
    free(x.keys);
    free(good);
    free(suspect);
    return rc;
}

/* Refusals before any search; false when there is something to search. */
static bool refuse(const struct biss_probe_frames *f, struct biss_probe_result *r) {
    unsigned payload = f->nbits - 1;
    r->verdict = BISS_PROBE_NONE;
    if (r->end_bit == 0) {
        snprintf(r->reason, sizeof r->reason,
                 "no bit after the CDS was ever 1: no slave sent data");
        return true;
    }
    if (r->end_bit >= payload) {
        snprintf(r->reason, sizeof r->reason,
                 "bits up to the end of the %u-bit capture are 1: the frame is longer than the "
                 "capture, or SL never goes low",
                 payload);
        return true;
    }
    if (f->nframes < 2 || all_alike(f, r->end_bit)) {
        snprintf(r->reason, sizeof r->reason,
                 "all %u frames are alike: a CRC cannot be told from data without a changing "
                 "position (move the encoder, capture more frames)",
                 f->nframes);
        return true;
    }
    return false;
}

/* Tries three reference frames (one may have been hit by noise). */
static int search_refs(const struct biss_probe_frames *f, struct probe_budget *b,
                       struct biss_probe_result *r) {
    int rc = BISS_OK;
    unsigned refs[3] = {0, f->nframes / 3, 2 * f->nframes / 3};
    for (unsigned k = 0; k < 3 && rc == BISS_OK; k++) {
        if (k && refs[k] == refs[k - 1]) {
            continue;
        }
        rc = search(f, r->end_bit, refs[k], b, r);
        if (r->nlayouts || b->ran_out) {
            break;
        }
    }
    return rc;
}

/* Noise: glitches put lone 1s after the frame's end. The end is then the
 * last bit that is 1 in 5 % of the frames. Tried first when some frames
 * have 1s after that end (they take part, as every frame does, but never
 * as probes: see suspects()); if it finds nothing, the strict end (the
 * last 1 at all) is tried. */
static unsigned noisy_end(const struct biss_probe_frames *f) {
    unsigned payload = f->nbits - 1, need = f->nframes / 20 > 2 ? f->nframes / 20 : 2;
    for (unsigned p = payload; p > 0; p--) {
        unsigned ones = 0;
        for (unsigned i = 0; i < f->nframes; i++) {
            ones += (unsigned)bit_at(f, i, p - 1);
        }
        if (ones >= need) {
            return p;
        }
    }
    return 0;
}

static unsigned ones_after(const struct biss_probe_frames *f, unsigned end) {
    unsigned n = 0;
    for (unsigned i = 0; i < f->nframes; i++) {
        bool one = false;
        for (unsigned p = end; p + 1 < f->nbits && !one; p++) {
            one = bit_at(f, i, p);
        }
        n += one;
    }
    return n;
}

static int analyse(const struct biss_probe_frames *f, struct probe_budget *b,
                   struct biss_probe_result *r) {
    memset(r, 0, sizeof *r);
    r->frames = f->nframes;
    unsigned strict = frame_end(f);
    unsigned noisy = f->nframes >= 20 ? noisy_end(f) : strict;
    if (noisy && noisy < strict) {
        r->end_bit = noisy;
        r->after_end = ones_after(f, noisy);
        int rc = refuse(f, r) ? BISS_OK : search_refs(f, b, r);
        if (rc || r->nlayouts || b->ran_out) {
            size_t len = strlen(r->reason);
            snprintf(r->reason + len, sizeof r->reason - len,
                     "; %u frames with 1s after bit %u (noise there)", r->after_end, noisy);
            return rc;
        }
        memset(r, 0, sizeof *r);
        r->frames = f->nframes;
    }
    r->end_bit = strict;
    return refuse(f, r) ? BISS_OK : search_refs(f, b, r);
}

int biss_probe_analyse_limited(const struct biss_probe_frames *f,
                               const struct biss_probe_limits *lim, struct biss_probe_result *r) {
    if (!f || !r || !f->bits || f->nframes < 1 || f->nframes > BISS_PROBE_MAX_FRAMES ||
        f->nbits < 2 || f->nbits > BISS_PROBE_MAX_BITS) {
        return BISS_E_INVAL;
    }
    struct probe_budget b;
    probe_budget_init(&b, lim, probe_now_s());
    int rc = analyse(f, &b, r);
    r->work = b.work;
    r->elapsed_ms = probe_budget_elapsed_ms(&b);
    r->ran_out = b.ran_out;
    return rc;
}

int biss_probe_analyse(const struct biss_probe_frames *f, struct biss_probe_result *r) {
    return biss_probe_analyse_limited(f, NULL, r);
}

const char *biss_probe_verdict_name(enum biss_probe_verdict v) {
    switch (v) {
    case BISS_PROBE_UNIQUE:
        return "unique";
    case BISS_PROBE_BEST:
        return "best";
    case BISS_PROBE_AMBIGUOUS:
        return "ambiguous";
    case BISS_PROBE_NONE:
        return "cannot decide";
    }
    return "?";
}

void biss_probe_layout_config(const struct biss_probe_layout *l, struct biss_config *c) {
    c->nslaves = l->nslaves;
    for (unsigned i = 0; i < l->nslaves && i < BISS_API_MAX_SLAVES; i++) {
        const struct biss_probe_slave *s = &l->slave[i];
        c->slave[i] = (struct biss_slave_config){
            .data_bits = s->data_bits,
            .crc_bits = s->crc_bits,
            .crc_poly = s->crc_poly,
            .crc_start = s->crc_start,
            .has_ew = s->has_ew,
            .ew_shift = s->has_ew ? s->ew_shift : 0,
            /* a counter without nE/nW: the position is the bits above it */
            .pos_bits = !s->has_ew && s->lc_bits ? s->data_bits - s->lc_bits : 0,
        };
    }
}
