/* wrong_frame.c - a wrong frame published as valid, classified
 * (wrong_frame.h). */
#include "wrong_frame.h"

#include "bench_fw.h"
#include "biss_crc.h"
#include "biss_proto.h"

#include <stdio.h>
#include <stdlib.h>

#define MAX_BITS (64 + 16 + 1) /* data, CRC and the bit after them */

const char *wrong_class_name(enum wrong_class c) {
    switch (c) {
    case WRONG_ON_WIRE:
        return "valid on the wire";
    case WRONG_OFF_GRID:
        return "off-grid";
    case WRONG_BETWEEN:
        return "between samples";
    case WRONG_OTHER:
    case WRONG_CLASSES:
        break;
    }
    return "other";
}

/* n bits of v, MSB first, into b. */
static void put_bits(uint8_t *b, uint64_t v, unsigned n) {
    for (unsigned k = 0; k < n; k++) {
        b[k] = (uint8_t)(v >> (n - 1 - k) & 1u);
    }
}

/* How many k explain read as sent with the slave one bit ahead (dir 1)
 * or behind (dir -1) from bit k on; the first such k in *at. */
static unsigned shifts(const uint8_t *read, const uint8_t *sent, unsigned n, int dir,
                       unsigned *at) {
    unsigned count = 0;
    for (unsigned k = dir > 0 ? 0 : 1; k < n; k++) {
        bool ok = true;
        for (unsigned j = 0; j < n && ok; j++) {
            ok = read[j] == (j < k ? sent[j] : sent[(int)j + dir]);
        }
        if (ok && count++ == 0) {
            *at = k;
        }
    }
    return count;
}

#define MAX_SLIPS 3

/* The fewest slips (a sent bit skipped: the slave a clock ahead; or one
 * read twice: a clock behind) that turn sent (then zeros, as after the
 * chain) into read, with no bit flipped; MAX_SLIPS + 1 if more. */
static unsigned slips(const uint8_t *read, const uint8_t *sent, unsigned n) {
    /* d[i][j]: slips to match read[i..] from sent[j..] on */
    static unsigned d[MAX_BITS + 1][MAX_BITS + MAX_SLIPS + 2];
    unsigned m = n + MAX_SLIPS + 1; /* sent bits that may be used */
    for (unsigned j = 0; j <= m; j++) {
        d[n][j] = 0;
    }
    for (unsigned i = n; i-- > 0;) {
        for (unsigned j = m + 1; j-- > 0;) {
            unsigned best = MAX_SLIPS + 1;
            int bit = j <= n ? sent[j] : 0;
            if (j < m && read[i] == bit) {
                best = d[i + 1][j + 1];
            }
            if (j < m && d[i][j + 1] + 1 < best) {
                best = d[i][j + 1] + 1;
            }
            if (d[i + 1][j] + 1 < best) {
                best = d[i + 1][j] + 1;
            }
            d[i][j] = best;
        }
    }
    return d[0][0];
}

/* The flipped bits (read XOR sent) as a polynomial: the CRC polynomial
 * times x^k? (Both words pass the same CRC, so their difference is a
 * multiple of it; the least multiple, P itself, takes the fewest frames.) */
static int poly_shifted(const uint8_t *read, const uint8_t *sent, unsigned n, uint32_t poly) {
    unsigned first = 0, last = 0;
    bool any = false;
    for (unsigned j = 0; j < n; j++) {
        if (read[j] != sent[j]) {
            last = j;
            first = any ? first : j;
            any = true;
        }
    }
    unsigned w = biss_crc_width(poly);
    if (!any || last - first != w) {
        return 0;
    }
    for (unsigned k = 0; k <= w; k++) { /* x^w is the first flipped bit */
        if ((unsigned)(read[first + k] != sent[first + k]) != (poly >> (w - k) & 1u)) {
            return 0;
        }
    }
    return 1;
}

static int64_t circular(int64_t d, int64_t period) {
    d %= period;
    if (d > period / 2) {
        d -= period;
    } else if (d < -period / 2) {
        d += period;
    }
    return d;
}

/* Whether the master's samples saw the SL edge at t: the level at the
 * first sample instant at or after it (a sample at the edge's instant
 * takes the new level, as the waveform and the GPI do) still differs from
 * the one at the last instant before it (a pulse between the two leaves
 * no trace). */
static bool seen_by_samples(waveform *sl, const struct pru_core *core, sim_ps t) {
    int64_t before, after;
    if (!core || pru_gpi_sample_bracket(core, t - 1, &before, &after) != 0) {
        return true;
    }
    return waveform_level_at(sl, before) != waveform_level_at(sl, after);
}

/* SL at the master from the start bit to the slave's timeout: edges off
 * the grid the most of them share (within a fifth of a bit). */
static void check_wire(waveform *sl, const biss_frame_record *rec, sim_ps now, int64_t period,
                       const struct pru_core *core, struct wrong_frame *w) {
    int64_t t[512];
    unsigned n = 0;
    sim_ps end = rec->end_ps > rec->start_bit_ps ? rec->end_ps : now; /* still in its timeout */
    for (sim_ps at = waveform_next_after(sl, rec->start_bit_ps - 1);
         at != SIM_NEVER && at < end && n < sizeof t / sizeof t[0];
         at = waveform_next_after(sl, at)) {
        t[n++] = at;
    }
    w->edges = n;
    int64_t tol = period / 5, ref = 0;
    unsigned best = 0;
    for (unsigned i = 0; i < n; i++) {
        unsigned near = 0;
        for (unsigned j = 0; j < n; j++) {
            near += llabs(circular(t[j] - t[i], period)) <= tol;
        }
        if (near > best) {
            best = near;
            ref = t[i];
        }
    }
    for (unsigned i = 0; i < n; i++) {
        int64_t d = circular(t[i] - ref, period);
        if (llabs(d) > tol) {
            if (w->off_grid < WRONG_MAX_EDGES) {
                w->off_ps[w->off_grid] = d;
            }
            w->off_grid++;
            w->off_grid_seen += seen_by_samples(sl, core, t[i]);
        }
    }
}

void wrong_frame_classify(const biss_chain_cfg *cfg, const biss_frame_record *rec,
                          const uint64_t *smp_data, uint32_t frame, waveform *sl, sim_ps now,
                          int64_t period_ps, const struct pru_core *core, struct wrong_frame *w) {
    *w = (struct wrong_frame){.frame = frame, .words = WORDS_UNKNOWN, .cls = WRONG_OTHER};
    if (!rec) {
        return;
    }
    for (unsigned i = 0; i < cfg->n; i++) {
        const biss_slave_cfg *s = &cfg->s[i];
        struct biss_proto_word pw = bench_fw_word(s);
        uint64_t sent = biss_proto_word_compose(&pw, rec->s[i].position, rec->s[i].nE > 0,
                                                rec->s[i].nW > 0, rec->s[i].lc);
        if (sent == smp_data[i]) {
            continue;
        }
        unsigned d = biss_slave_cfg_data_bits(s), c = biss_crc_width(s->crc_poly), n = d + c;
        uint32_t mask = (1u << c) - 1u;
        uint8_t rb[MAX_BITS], sb[MAX_BITS];
        put_bits(rb, smp_data[i], d);
        put_bits(rb + d, ~biss_crc_bits(s->crc_poly, s->crc_start, smp_data[i], d) & mask, c);
        put_bits(sb, sent, d);
        put_bits(sb + d, rec->s[i].crc, c);
        /* the bit after: the next slave's first, or the 0 after the chain */
        sb[n] = 0;
        if (i + 1 < cfg->n) {
            const biss_slave_cfg *nx = &cfg->s[i + 1];
            struct biss_proto_word nw = bench_fw_word(nx);
            uint64_t next =
                biss_proto_word_compose(&nw, rec->s[i + 1].position, rec->s[i + 1].nE > 0,
                                        rec->s[i + 1].nW > 0, rec->s[i + 1].lc);
            sb[n] = (uint8_t)(next >> (biss_slave_cfg_data_bits(nx) - 1) & 1u);
        }
        w->slave = i;
        w->nbits = n;
        for (unsigned j = 0; j <= n; j++) {
            w->read_bits[j] = j < n ? (char)('0' + rb[j]) : '\0';
            w->sent_bits[j] = (char)('0' + sb[j]);
        }
        w->sent_bits[n + 1] = '\0';
        w->read = smp_data[i];
        w->sent = sent;
        uint64_t pr, ps;
        int e, ww;
        biss_proto_word_split(&pw, smp_data[i], &pr, &e, &ww);
        biss_proto_word_split(&pw, sent, &ps, &e, &ww);
        w->counts = (int64_t)(pr - ps);
        for (unsigned j = 0; j < n; j++) {
            w->flipped_bits += rb[j] != sb[j];
        }
        w->crc_poly_shifted = poly_shifted(rb, sb, n, s->crc_poly);
        w->slips = slips(rb, sb, n);
        if ((w->shift_run = shifts(rb, sb, n, 1, &w->shift_at)) > 0) {
            w->words = WORDS_SHIFT_AHEAD;
        } else if ((w->shift_run = shifts(rb, sb, n, -1, &w->shift_at)) > 0) {
            w->words = WORDS_SHIFT_BEHIND;
        } else {
            w->words = w->slips <= MAX_SLIPS ? WORDS_SLIPS : WORDS_FLIPPED;
        }
        break;
    }
    check_wire(sl, rec, now, period_ps, core, w);
    bool slipped = w->words != WORDS_FLIPPED && w->words != WORDS_UNKNOWN;
    w->cls = w->words == WORDS_UNKNOWN ? WRONG_OTHER
             : w->off_grid_seen        ? WRONG_OFF_GRID
             : w->off_grid             ? WRONG_BETWEEN
             : slipped                 ? WRONG_ON_WIRE
                                       : WRONG_OTHER;
}

void wrong_frame_describe(const struct wrong_frame *w, char *buf, size_t len) {
    int n = snprintf(buf, len, "frame %u: %s: ", w->frame, wrong_class_name(w->cls));
    size_t used = n > 0 ? (size_t)n : 0;
    switch (w->words) {
    case WORDS_SHIFT_AHEAD:
    case WORDS_SHIFT_BEHIND:
        n = snprintf(buf + used, used < len ? len - used : 0,
                     "slave %u one bit %s from bit %u of %u (any of %u places in a run of equal "
                     "bits)",
                     w->slave, w->words == WORDS_SHIFT_AHEAD ? "ahead" : "behind", w->shift_at,
                     w->nbits, w->shift_run);
        break;
    case WORDS_SLIPS:
        n = snprintf(buf + used, used < len ? len - used : 0,
                     "slave %u %u slips (bits gained or lost, none flipped)", w->slave, w->slips);
        break;
    case WORDS_FLIPPED:
        n = snprintf(buf + used, used < len ? len - used : 0, "slave %u no slips apart", w->slave);
        break;
    case WORDS_UNKNOWN:
        n = snprintf(buf + used, used < len ? len - used : 0, "its record was gone");
        break;
    }
    used += n > 0 ? (size_t)n : 0;
    if (w->words != WORDS_UNKNOWN) {
        n = snprintf(buf + used, used < len ? len - used : 0,
                     "; %u of %u bits differ%s; position off by %lld counts; %u SL edges, %u off "
                     "the grid (%u seen by the samples)",
                     w->flipped_bits, w->nbits,
                     w->crc_poly_shifted ? " (the CRC polynomial times x^k)" : "",
                     (long long)w->counts, w->edges, w->off_grid, w->off_grid_seen);
        used += n > 0 ? (size_t)n : 0;
    }
    for (unsigned k = 0; k < w->off_grid && k < WRONG_MAX_EDGES; k++) {
        n = snprintf(buf + used, used < len ? len - used : 0, "%s%+.1f ns", k ? ", " : " (",
                     w->off_ps[k] / 1000.0);
        used += n > 0 ? (size_t)n : 0;
    }
    if (w->off_grid) {
        n = snprintf(buf + used, used < len ? len - used : 0, ")");
        used += n > 0 ? (size_t)n : 0;
    }
    if (w->words != WORDS_UNKNOWN) {
        snprintf(buf + used, used < len ? len - used : 0, "; read %s, sent %s", w->read_bits,
                 w->sent_bits);
    }
}
