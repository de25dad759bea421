/* biss_link.c - how near a BiSS link is to failing, from what each frame's
 * samples showed (biss_proto.h): the eye opening of a frame, and a warning
 * that fires on marginal frames, before the CRC errors.
 *
 * The eye opening of a frame, in eighths of a bit, is how far the nearest
 * SL edge the master saw lay from the place the bits were sampled at; a
 * clean line leaves every edge on the bit grid, 4 eighths from the sample
 * points. Two observations carry it (pru_fw/README.md, "Bit grid"):
 *  - the ACK edge: this frame's position (DELAY_RAW) against the average
 *    the sample point was taken from (DELAY_AVG), both in eighths: an edge
 *    d eighths off leaves 4 - d (0 from 4 on: an ACK jump);
 *  - the bit-grid check (BISS_RF_OFF_GRID, below 10 MHz): an edge within
 *    2 eighths before a sample point or 1 after it (BISS_GRID_OLDER,
 *    BISS_GRID_NEWER: the check's window, biss_shm.h), so at most 2.
 * A frame with an eye of BISS_LINK_EYE_MARGINAL or less is marginal: its
 * bits were read at most that far from an edge. The warning counts them
 * in blocks of `window` frames judged: set from the frame that brings the
 * current block's count to `warn`, and while the last whole block's count
 * is at least `warn`. What the firmware cannot show at 10 MHz (no bit-grid
 * check there) is left to the ACK edge: one edge a frame. */
#include "biss_proto.h"

#include <ctype.h>
#include <stdlib.h>
#include <string.h>

/* An edge the check saw lies no further from the sample point than the
 * window reaches. */
_Static_assert(BISS_LINK_EYE_OFF_GRID ==
                   (BISS_GRID_OLDER > BISS_GRID_NEWER ? BISS_GRID_OLDER : BISS_GRID_NEWER),
               "the off-grid eye is the check's window");

/* A count of 1..2^32-1 in decimal digits only, up to a ',' or the end. */
static bool parse_count(const char *s, const char **end, uint32_t *out) {
    if (!isdigit((unsigned char)*s)) {
        return false;
    }
    char *e = NULL;
    unsigned long long v = strtoull(s, &e, 10);
    *end = e;
    if (v < 1 || v > UINT32_MAX) {
        return false;
    }
    *out = (uint32_t)v;
    return true;
}

int biss_link_parse(const char *arg, uint32_t *warn, uint32_t *window) {
    const char *end = NULL;
    uint32_t k, n = BISS_LINK_WINDOW;
    if (!arg || !parse_count(arg, &end, &k)) {
        return BISS_E_INVAL;
    }
    if (*end == ',' && !parse_count(end + 1, &end, &n)) {
        return BISS_E_INVAL;
    }
    if (*end) {
        return BISS_E_INVAL;
    }
    *warn = k;
    *window = n;
    return BISS_OK;
}

void biss_link_init(struct biss_link_state *st, uint32_t window, uint32_t warn) {
    memset(st, 0, sizeof *st);
    biss_link_set_warning(st, window, warn);
    st->stats.eye_min = BISS_LINK_EYE_MAX;
}

void biss_link_set_warning(struct biss_link_state *st, uint32_t window, uint32_t warn) {
    st->window = window ? window : BISS_LINK_WINDOW;
    st->warn = warn ? warn : BISS_LINK_WARN;
    st->block_frames = 0;
    st->block_marginal = 0;
}

double biss_link_eye_mean(const struct biss_link_stats *k) {
    return k->frames ? (double)k->eye_sum / k->frames : BISS_LINK_EYE_MAX;
}

int biss_link_eye(const struct biss_sample *s) {
    bool measured = s->valid || s->crc_error || s->ack_jump || s->off_grid || s->misframed;
    if (!measured || s->training) {
        return -1;
    }
    int d = (int)s->delay.raw - (int)s->delay.avg;
    d = d < 0 ? -d : d;
    int eye = d >= BISS_LINK_EYE_MAX ? 0 : BISS_LINK_EYE_MAX - d;
    if (s->off_grid && eye > BISS_LINK_EYE_OFF_GRID) {
        eye = BISS_LINK_EYE_OFF_GRID;
    }
    return eye;
}

void biss_link_check(struct biss_link_state *st, struct biss_sample *s) {
    int eye = biss_link_eye(s);
    s->link_eye = eye;
    /* no eye, or read again, or older than the last judged (the ring reader
     * and the newest-sample read on one handle): judged once, in order */
    if (eye < 0 || !biss_frame_order_next(&st->order, s->frame)) {
        s->link_warning = st->warning;
        return;
    }
    struct biss_link_stats *k = &st->stats;
    if (k->frames == UINT32_MAX) {
        /* 2^32 - 1 frames judged (30 h at 40 kHz): the counts start again
         * together, so the mean (eye_sum / frames) stays a mean */
        k->frames = 0;
        memset(k->eye, 0, sizeof k->eye);
        k->eye_sum = 0;
        k->marginal = 0;
        k->off_grid = 0;
        k->warnings = 0;
    }
    k->frames++;
    k->eye[eye]++;
    k->eye_sum += (uint64_t)eye;
    k->eye_min = (unsigned)eye < k->eye_min ? (unsigned)eye : k->eye_min;
    k->off_grid += s->off_grid;
    if (eye <= BISS_LINK_EYE_MARGINAL) {
        k->marginal++;
        st->block_marginal++;
    }
    st->warning = st->block_marginal >= st->warn || k->last_block_marginal >= st->warn;
    if (++st->block_frames == st->window) {
        k->last_block_marginal = st->block_marginal;
        st->block_frames = 0;
        st->block_marginal = 0;
    }
    k->warnings += st->warning;
    s->link_warning = st->warning;
}
