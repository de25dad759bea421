/* biss_safety.c - the BiSS Safety checks on published frames (biss_proto.h):
 * the life counter (sign of life) and pairs of redundant position words;
 * and the misframing check of slaves that never set nE/nW.
 *
 * The life counter is judged by the firmware's frame numbers: between two
 * frames read it must have advanced by their difference (modulo its width),
 * so frames the host did not read (it polls) are no fault, and a counter
 * that stood still or jumped is. The BiSS Safety profile's two position
 * words (biss-interface.com, "BiSS Safety": control and safety position
 * word from two daisy-chained sensors, each with its own CRC) are compared
 * after shifting both to one resolution; their CRCs must differ (iC-MB4
 * datasheet, "CRC start value": start values tell single-cycle data words
 * of two sensors apart).
 *
 * nE and nW are active low (BiSS C protocol description, single-cycle data:
 * error and warning bits, low active). A slave that never sets them sends
 * 1, 1 in every frame; a slave that got one MA clock the master never made
 * (a glitch on MA) sends every later bit one period early, so the master
 * reads the bit after each one in its place: nW's place then holds the
 * first bit of what follows (life counter or inverted CRC), and a CRC6
 * still passes 1 in 64 such words. Reading either bit 0 shows such a frame
 * whatever its CRC says.
 *
 * The same frame of a slave that does set nE/nW, or whose shifted word
 * still reads 1, 1 there, is caught by where its position lies: an encoder
 * moves at most its top speed, so a position lies within max_speed times
 * the time since the last one accepted (plus a count), while a word read
 * one place off from bit k on differs in the bits below k (by up to
 * 2^(width - k)). What such a check cannot see is a misframing in the
 * lowest bits, within that reach of the truth.
 *
 * The time between two frames comes from what the firmware publishes with
 * each: in IEP trigger, and following another channel's IEP, the frame
 * numbers times the period (the count restarts every period); free-running
 * and with the host's trigger the IEP timestamps, the time from the frame
 * start that latched one position to the one that latched the other. A
 * glitch on MA that starts a slave frame the master never made lengthens
 * that time (the master waits for the slave to be ready), and the reach
 * with it, but the encoder moves while the master waits: bounding the
 * reach by the frames that ran instead would refuse positions the encoder
 * does reach (README, "Noise and faults").
 *
 * Both counts are 32 bits wide and wrap. Read modulo 2^32 as a signed
 * distance, a count under half its range (2^31: 10.7 s of IEP counts at
 * 200 MHz) is the time; from half on, a count that ran on cannot be told
 * from one that went back (another channel's IEP trigger restarting the
 * count), and one that came round more than once reads as a short time.
 * The host's clock tells the second case where the count cannot: the
 * reader passes the clock at which it read each frame, and two frames it
 * read half the count's range apart or more may lie a whole wrap further
 * apart than their count says. Where either says so, the time is not
 * known: the position is not judged (neither passed as within reach nor
 * refused: refusing on a speed that cannot be computed would refuse every
 * frame of a host that polls that slowly, the references never renewed),
 * it is counted (pos_untimed) and flagged (BISS_SAFE_POS_UNTIMED), and,
 * the frame accepted, it becomes the reference the next frame is judged
 * by. What the clock cannot see is a reference read long after its frame
 * (a host-triggered frame left unread): the count then reads short by a
 * whole wrap and the reach is smaller than the truth, which may refuse a
 * good position, never pass a wrong one (and two frames in a row that
 * agree take over, as after any refusal). */
#include "biss_proto.h"

#include "biss/biss_rules.h"

#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

unsigned biss_safety_life_width(const struct biss_slave_config *s) {
    if (s->life_bits) {
        return s->life_bits;
    }
    return s->has_ew ? s->ew_shift : 0;
}

static int check_life(const struct biss_config *c, unsigned i) {
    const struct biss_slave_config *s = &c->slave[i];
    if (!s->life_check) {
        return BISS_OK;
    }
    unsigned w = biss_safety_life_width(s);
    if (i >= c->nslaves || w < 1 || w > 32) {
        return BISS_E_SAFETY_LIFE;
    }
    unsigned below = s->data_bits - biss_proto_pos_bits(s); /* under the position */
    if (w > below || (s->has_ew && w > s->ew_shift)) {
        return BISS_E_SAFETY_LIFE;
    }
    return BISS_OK;
}

static bool same_crc(const struct biss_slave_config *a, const struct biss_slave_config *b) {
    return a->crc_bits == b->crc_bits && a->crc_poly == b->crc_poly && a->crc_start == b->crc_start;
}

static int check_pair(const struct biss_config *c, const struct biss_pair_check *p) {
    if (p->a >= c->nslaves || p->b >= c->nslaves || p->a == p->b || p->shift_a > 63 ||
        p->shift_b > 63) {
        return BISS_E_SAFETY_PAIR;
    }
    const struct biss_slave_config *a = &c->slave[p->a], *b = &c->slave[p->b];
    if (biss_proto_pos_bits(a) + p->shift_a > 64 || biss_proto_pos_bits(b) + p->shift_b > 64) {
        return BISS_E_SAFETY_PAIR;
    }
    if (p->distinct_crc && same_crc(a, b)) {
        return BISS_E_SAFETY_CRC;
    }
    return BISS_OK;
}

/* IEP-triggered frames are timed by the period alone (the count restarts
 * every period): a speed check there needs it, following another
 * channel's IEP too (that channel's period). */
static bool timed(const struct biss_config *c) {
    bool iep = c->trigger == BISS_TRIGGER_IEP || c->trigger == BISS_TRIGGER_IEP_FOLLOW;
    return !iep || c->iep_period_ns > 0;
}

int biss_safety_config_check(const struct biss_config *c) {
    for (unsigned i = 0; i < BISS_API_MAX_SLAVES; i++) {
        int rc = check_life(c, i);
        if (rc) {
            return rc;
        }
        if (c->slave[i].ew_static && (i >= c->nslaves || !c->slave[i].has_ew)) {
            return BISS_E_SAFETY_EW;
        }
        double v = c->slave[i].max_speed;
        if (v != 0 && (i >= c->nslaves || !biss_max_speed_valid(v) || !timed(c))) {
            return BISS_E_SAFETY_SPEED;
        }
    }
    if (c->npairs > BISS_API_MAX_PAIRS) {
        return BISS_E_SAFETY_PAIR;
    }
    for (unsigned k = 0; k < c->npairs; k++) {
        int rc = check_pair(c, &c->pair[k]);
        if (rc) {
            return rc;
        }
    }
    return BISS_OK;
}

void biss_safety_init(struct biss_safety_state *st) {
    memset(st, 0, sizeof *st);
}

void biss_safety_restart(struct biss_safety_state *st) {
    struct biss_safety_stats keep = st->stats;
    biss_safety_init(st);
    st->stats = keep;
}

/* One slave's life counter against the last one trusted. */
static uint32_t life(const struct biss_slave_config *c, struct biss_safety_state *st, unsigned i,
                     uint32_t frame, const struct biss_slave_result *r) {
    if (!c->life_check || !r->crc_ok) {
        return 0; /* a word with a bad CRC tells nothing; the reference stays */
    }
    uint64_t m = biss_low_mask(biss_safety_life_width(c));
    uint32_t lc = (uint32_t)(r->data & m);
    uint32_t flags = 0;
    if (st->ref[i]) {
        uint32_t want = (uint32_t)((frame - st->ref_frame[i]) & m);
        uint32_t moved = (uint32_t)((lc - st->ref_lc[i]) & m);
        flags = BISS_SAFE_LC_CHECKED;
        if (moved != want) {
            flags |= moved == 0 ? BISS_SAFE_LC_FROZEN : BISS_SAFE_LC_SKIP;
        }
        st->stats.lc_checked[i]++;
        st->stats.lc_frozen[i] += moved != want && moved == 0;
        st->stats.lc_skipped[i] += moved != want && moved != 0;
    }
    st->ref[i] = true;
    st->ref_frame[i] = frame;
    st->ref_lc[i] = lc;
    return flags;
}

/* a - b modulo 2^w as a signed number: the circular distance of two
 * w-bit positions, with its direction (a wrap of one before the other is
 * a small difference). */
static int64_t circular_diff(uint64_t a, uint64_t b, unsigned w) {
    uint64_t m = biss_low_mask(w);
    uint64_t d = (a - b) & m;
    if (w < 64 && w > 0 && (d >> (w - 1))) {
        return (int64_t)(d | ~m); /* sign-extend */
    }
    return (int64_t)d;
}

static uint64_t magnitude(int64_t d) {
    return d < 0 ? 0 - (uint64_t)d : (uint64_t)d;
}

/* (a << shift_a) - (b << shift_b) modulo 2^W, W the wider shifted
 * position. */
static int64_t pair_diff(const struct biss_config *c, const struct biss_pair_check *p,
                         const struct biss_sample *s) {
    unsigned wa = biss_proto_pos_bits(&c->slave[p->a]) + p->shift_a;
    unsigned wb = biss_proto_pos_bits(&c->slave[p->b]) + p->shift_b;
    return circular_diff(s->slave[p->a].position << p->shift_a,
                         s->slave[p->b].position << p->shift_b, wa > wb ? wa : wb);
}

static void pairs(const struct biss_config *c, struct biss_safety_state *st,
                  struct biss_sample *s) {
    for (unsigned k = 0; k < c->npairs && k < BISS_API_MAX_PAIRS; k++) {
        const struct biss_pair_check *p = &c->pair[k];
        if (p->a >= s->nslaves || p->b >= s->nslaves || !s->slave[p->a].crc_ok ||
            !s->slave[p->b].crc_ok) {
            continue;
        }
        int64_t d = pair_diff(c, p, s);
        uint64_t mag = magnitude(d);
        uint32_t flags = BISS_SAFE_PAIR_CHECKED | (mag > p->tolerance ? BISS_SAFE_DISAGREE : 0);
        s->slave[p->a].safety |= flags;
        s->slave[p->b].safety |= flags;
        st->stats.pair_checked[k]++;
        st->stats.pair_disagree[k] += mag > p->tolerance;
        st->stats.pair_last_diff[k] = d;
    }
}

/* The nE/nW of every ew_static slave: any read active makes the frame
 * misframed (counted per slave). */
static bool ew_static(const struct biss_config *c, struct biss_safety_state *st,
                      struct biss_sample *s) {
    bool misframed = false;
    for (unsigned i = 0; i < s->nslaves && i < BISS_API_MAX_SLAVES && i < c->nslaves; i++) {
        const struct biss_slave_result *r = &s->slave[i];
        if (!c->slave[i].ew_static || !c->slave[i].has_ew || !r->crc_ok) {
            continue; /* a word with a bad CRC is refused already */
        }
        bool set = r->error || r->warning;
        s->slave[i].safety |= BISS_SAFE_EW_CHECKED | (set ? BISS_SAFE_EW_SET : 0);
        st->stats.ew_checked[i]++;
        st->stats.ew_set[i] += set;
        misframed = misframed || set;
    }
    return misframed;
}

/* Seconds from the reference's frame to frame s (the module comment), or
 * -1 where no time can be told: the count between them (frame numbers
 * under the IEP triggers, IEP counts otherwise) is 0 or half its range or
 * more, or the host's clock read the two half that range apart or more
 * (the count may have come round). */
static double elapsed_s(const struct biss_config *c, const struct biss_pos_ref *ref,
                        const struct biss_sample *s, uint64_t read_us) {
    bool frames = c->trigger == BISS_TRIGGER_IEP || c->trigger == BISS_TRIGGER_IEP_FOLLOW;
    /* iep_period_ns > 0: biss_safety_config_check */
    uint32_t counts = frames ? s->frame - ref->frame : s->timestamp - ref->ts;
    uint64_t count_ns = frames ? c->iep_period_ns : 1000000000u / BISS_PRU_HZ;
    const uint32_t half = 0x80000000u;
    if (counts == 0 || counts >= half) {
        return -1;
    }
    /* the clock's microseconds against half the count's range: read that
     * long apart or more (whole microseconds, rounded up), no time */
    uint64_t half_us = (half * count_ns + 999) / 1000;
    if (read_us != BISS_SAFETY_NO_CLOCK && ref->read_us != BISS_SAFETY_NO_CLOCK &&
        (read_us < ref->read_us || read_us - ref->read_us >= half_us)) {
        return -1;
    }
    return frames ? (double)counts * c->iep_period_ns * 1e-9 : (double)counts / BISS_PRU_HZ;
}

/* Slave i's position in frame s against a reference (distances modulo
 * 2^width: a wrap is no jump). */
enum reach {
    NOT_JUDGED, /* no reference, or a reach of half the circle or more */
    UNTIMED,    /* no time known since the reference (elapsed_s) */
    WITHIN,     /* within max_speed times the time between, plus one count
                   for the two readings' rounding */
    BEYOND,
};

static enum reach judge(const struct biss_config *c, unsigned i, const struct biss_pos_ref *ref,
                        const struct biss_sample *s, uint64_t read_us) {
    if (!ref->set) {
        return NOT_JUDGED;
    }
    double dt = elapsed_s(c, ref, s, read_us);
    if (dt < 0) {
        return UNTIMED;
    }
    unsigned w = biss_proto_pos_bits(&c->slave[i]);
    double dist = (double)magnitude(circular_diff(s->slave[i].position, ref->pos, w));
    double reach = c->slave[i].max_speed * dt + 1.0;
    if (reach >= (double)(biss_low_mask(w) >> 1)) {
        return NOT_JUDGED;
    }
    return dist > reach ? BEYOND : WITHIN;
}

static struct biss_pos_ref pos_ref(const struct biss_sample *s, unsigned i, uint64_t read_us) {
    return (struct biss_pos_ref){.set = true,
                                 .frame = s->frame,
                                 .ts = s->timestamp,
                                 .pos = s->slave[i].position,
                                 .read_us = read_us};
}

/* The position of every max_speed slave against the last one accepted:
 * any beyond reach makes the frame misframed (counted per slave), unless
 * it lies within reach of the position refused last, after it: two frames
 * in a row that agree with each other and not with the reference say the
 * reference is the wrong one (a wrong position that passed within reach,
 * or the encoder set to a new position), and the check takes the newer
 * one (counted as a resync). A frame misframed by its nE/nW (ew) is no
 * such witness. A position with no time known since the reference is not
 * judged (counted, flagged): accepted, the frame renews the reference. */
static bool positions(const struct biss_config *c, struct biss_safety_state *st,
                      struct biss_sample *s, bool ew, uint64_t read_us) {
    bool misframed = false;
    for (unsigned i = 0; i < s->nslaves && i < BISS_API_MAX_SLAVES && i < c->nslaves; i++) {
        if (!c->slave[i].max_speed || !s->slave[i].crc_ok) {
            continue;
        }
        enum reach j = judge(c, i, &st->pos[i], s, read_us);
        if (j == NOT_JUDGED) {
            continue;
        }
        if (j == UNTIMED) {
            s->slave[i].safety |= BISS_SAFE_POS_UNTIMED;
            st->stats.pos_untimed[i]++;
            continue;
        }
        if (j == BEYOND && !ew) {
            if (judge(c, i, &st->refused[i], s, read_us) == WITHIN) {
                st->stats.pos_resync[i]++;
                j = WITHIN;
            } else {
                st->refused[i] = pos_ref(s, i, read_us);
            }
        }
        bool jump = j == BEYOND;
        s->slave[i].safety |= BISS_SAFE_POS_CHECKED | (jump ? BISS_SAFE_POS_JUMP : 0);
        st->stats.pos_checked[i]++;
        st->stats.pos_jumped[i] += jump;
        misframed = misframed || jump;
    }
    return misframed;
}

/* The positions of a frame accepted become the references. */
static void accept_positions(const struct biss_config *c, struct biss_safety_state *st,
                             const struct biss_sample *s, uint64_t read_us) {
    for (unsigned i = 0; i < s->nslaves && i < BISS_API_MAX_SLAVES && i < c->nslaves; i++) {
        if (c->slave[i].max_speed && s->slave[i].crc_ok) {
            st->pos[i] = pos_ref(s, i, read_us);
            st->refused[i].set = false;
        }
    }
}

/* The verdicts of the frame judged last, and what they say about it. */
static void remember(struct biss_safety_state *st, struct biss_sample *s) {
    st->seen = true;
    st->last_frame = s->frame;
    st->last_misframed = s->misframed;
    for (unsigned i = 0; i < BISS_API_MAX_SLAVES; i++) {
        st->last_flags[i] = i < s->nslaves ? s->slave[i].safety : 0;
        s->safety |= st->last_flags[i];
    }
}

void biss_safety_check(const struct biss_config *c, struct biss_safety_state *st,
                       struct biss_sample *s) {
    biss_safety_check_read(c, st, s, BISS_SAFETY_NO_CLOCK);
}

void biss_safety_check_read(const struct biss_config *c, struct biss_safety_state *st,
                            struct biss_sample *s, uint64_t read_us) {
    s->safety = 0;
    if (st->seen && s->frame == st->last_frame) {
        /* the same frame read again: the same verdicts, counted once */
        for (unsigned i = 0; i < s->nslaves && i < BISS_API_MAX_SLAVES; i++) {
            s->slave[i].safety = st->last_flags[i];
            s->safety |= st->last_flags[i];
        }
        if (st->last_misframed) {
            s->misframed = true;
            s->valid = false;
        }
        return;
    }
    if (!s->valid) {
        /* a frame the slave may not have seen (no ACK, aborted): the
         * counter's next value is not known from the frame numbers */
        if (s->no_slave || s->proc_error) {
            memset(st->ref, 0, sizeof st->ref);
        }
        return;
    }
    bool ew = ew_static(c, st, s);
    bool far = positions(c, st, s, ew, read_us);
    if (ew || far) {
        /* bits read one place off: no word of it is to be trusted, nor
         * judged (the life counters and positions keep their references) */
        s->misframed = true;
        s->valid = false;
        remember(st, s);
        return;
    }
    for (unsigned i = 0; i < s->nslaves && i < BISS_API_MAX_SLAVES && i < c->nslaves; i++) {
        s->slave[i].safety |= life(&c->slave[i], st, i, s->frame, &s->slave[i]);
    }
    pairs(c, st, s);
    accept_positions(c, st, s, read_us);
    remember(st, s);
}

/* t += after - before, count by count; the last pair difference where
 * the pair was compared. */
static void stats_add(struct biss_safety_stats *t, const struct biss_safety_stats *before,
                      const struct biss_safety_stats *after) {
    for (unsigned i = 0; i < BISS_API_MAX_SLAVES; i++) {
        t->lc_checked[i] += after->lc_checked[i] - before->lc_checked[i];
        t->lc_frozen[i] += after->lc_frozen[i] - before->lc_frozen[i];
        t->lc_skipped[i] += after->lc_skipped[i] - before->lc_skipped[i];
        t->ew_checked[i] += after->ew_checked[i] - before->ew_checked[i];
        t->ew_set[i] += after->ew_set[i] - before->ew_set[i];
        t->pos_checked[i] += after->pos_checked[i] - before->pos_checked[i];
        t->pos_jumped[i] += after->pos_jumped[i] - before->pos_jumped[i];
        t->pos_resync[i] += after->pos_resync[i] - before->pos_resync[i];
        t->pos_untimed[i] += after->pos_untimed[i] - before->pos_untimed[i];
    }
    for (unsigned k = 0; k < BISS_API_MAX_PAIRS; k++) {
        uint32_t n = after->pair_checked[k] - before->pair_checked[k];
        t->pair_checked[k] += n;
        t->pair_disagree[k] += after->pair_disagree[k] - before->pair_disagree[k];
        if (n) {
            t->pair_last_diff[k] = after->pair_last_diff[k];
        }
    }
}

void biss_safety_readers_check(const struct biss_config *c, struct biss_safety_readers *r,
                               unsigned reader, struct biss_sample *s, uint64_t read_us) {
    struct biss_safety_state *st = &r->reader[reader];
    struct biss_safety_stats before = st->stats;
    biss_safety_check_read(c, st, s, read_us);
    if (biss_frame_order_next(&r->order, s->frame)) {
        stats_add(&r->stats, &before, &st->stats);
    }
}

void biss_safety_readers_restart(struct biss_safety_readers *r) {
    for (unsigned i = 0; i < BISS_READERS; i++) {
        biss_safety_restart(&r->reader[i]);
    }
}

/* ---- the command-line spellings bissctl and biss-sim share ---- */

/* Comma-separated whole numbers: how many (at most max), or -1. */
static int numbers(const char *arg, unsigned long long *v, int max) {
    int n = 0;
    const char *p = arg;
    while (*p) {
        char *end;
        if (n == max || *p == '-' || *p == ',') {
            return -1;
        }
        errno = 0;
        v[n++] = strtoull(p, &end, 0);
        if (errno || end == p || (*end && *end != ',') || (*end == ',' && !end[1])) {
            return -1;
        }
        p = *end ? end + 1 : end;
    }
    return n;
}

int biss_safety_parse_life(const char *arg, struct biss_config *c) {
    unsigned long long v[2];
    int n = numbers(arg, v, 2);
    if (n < 1 || v[0] >= BISS_API_MAX_SLAVES || (n == 2 && (v[1] < 1 || v[1] > 32))) {
        return BISS_E_INVAL;
    }
    c->slave[v[0]].life_check = true;
    c->slave[v[0]].life_bits = n == 2 ? (unsigned)v[1] : 0;
    return BISS_OK;
}

int biss_safety_parse_pair(const char *arg, struct biss_config *c) {
    unsigned long long v[5] = {0};
    int n = numbers(arg, v, 5);
    if ((n != 3 && n != 5) || v[0] >= BISS_API_MAX_SLAVES || v[1] >= BISS_API_MAX_SLAVES ||
        v[3] > 63 || v[4] > 63) {
        return BISS_E_INVAL;
    }
    if (c->npairs >= BISS_API_MAX_PAIRS) {
        return BISS_E_SAFETY_PAIR;
    }
    c->pair[c->npairs++] = (struct biss_pair_check){.a = (unsigned)v[0],
                                                    .b = (unsigned)v[1],
                                                    .tolerance = v[2],
                                                    .shift_a = (unsigned)v[3],
                                                    .shift_b = (unsigned)v[4],
                                                    .distinct_crc = true};
    return BISS_OK;
}

int biss_safety_parse_ew(const char *arg, struct biss_config *c) {
    unsigned long long v[1];
    if (numbers(arg, v, 1) != 1 || v[0] >= BISS_API_MAX_SLAVES) {
        return BISS_E_INVAL;
    }
    c->slave[v[0]].ew_static = true;
    return BISS_OK;
}

int biss_safety_parse_speed(const char *arg, struct biss_config *c) {
    unsigned long long v[1];
    const char *comma = strchr(arg, ',');
    char slave[24];
    if (!comma || (size_t)(comma - arg) >= sizeof slave) {
        return BISS_E_INVAL;
    }
    memcpy(slave, arg, (size_t)(comma - arg));
    slave[comma - arg] = '\0';
    char *end;
    errno = 0;
    double cps = strtod(comma + 1, &end);
    if (numbers(slave, v, 1) != 1 || v[0] >= BISS_API_MAX_SLAVES || errno || end == comma + 1 ||
        *end || !biss_max_speed_valid(cps)) {
        return BISS_E_INVAL;
    }
    c->slave[v[0]].max_speed = cps;
    return BISS_OK;
}

int biss_safety_merge(struct biss_config *dst, const struct biss_config *checks) {
    for (unsigned i = 0; i < BISS_API_MAX_SLAVES; i++) {
        dst->slave[i].ew_static = dst->slave[i].ew_static || checks->slave[i].ew_static;
        if (checks->slave[i].max_speed) {
            dst->slave[i].max_speed = checks->slave[i].max_speed;
        }
        if (checks->slave[i].life_check) {
            dst->slave[i].life_check = true;
            dst->slave[i].life_bits = checks->slave[i].life_bits;
        }
    }
    for (unsigned k = 0; k < checks->npairs && k < BISS_API_MAX_PAIRS; k++) {
        if (dst->npairs >= BISS_API_MAX_PAIRS) {
            return BISS_E_SAFETY_PAIR;
        }
        dst->pair[dst->npairs++] = checks->pair[k];
    }
    return BISS_OK;
}
