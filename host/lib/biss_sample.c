/* biss_sample.c - consistent reads of the published results (the ST_SEQ /
 * ST_BUF protocol of biss_shm.h) and waiting for a newer one. */
#include "biss_priv.h"

#include "biss/biss_shm_struct.h"

#include <stdatomic.h>
#include <stddef.h>

/* A publication takes the firmware a few hundred ns; a reader racing it
 * many times in a row means something else is wrong. */
#define MAX_TRIES 1000

/* Reads ST_SEQ, ST_BUF, that buffer, ST_SEQ again; equal sequence numbers
 * mean the firmware did not start refilling the buffer meanwhile (it only
 * does so after publishing the other one, which bumps ST_SEQ). The
 * sample's seq is the slot's publication number (biss_proto_slot_seq), as
 * the ring reader gives it. */
static int read_consistent(biss_t *h, struct biss_shm_result *r, uint32_t *seq) {
    struct biss_proto_io io = biss_io(h);
    unsigned n = h->configured ? h->cfg.nslaves : BISS_MAX_SLAVES;
    for (int i = 0; i < MAX_TRIES; i++) {
        uint32_t s1, s2;
        bool any;
        int rc = biss_proto_pub_seq_any(&io, &s1, &any);
        if (rc) {
            return rc;
        }
        if (!any) {
            return BISS_E_NO_SAMPLE;
        }
        atomic_thread_fence(memory_order_acquire);
        rc = biss_proto_result_get(&io, n, r);
        if (rc) {
            return rc;
        }
        atomic_thread_fence(memory_order_acquire);
        rc = biss_proto_pub_seq(&io, &s2);
        if (rc) {
            return rc;
        }
        if (s1 == s2) {
            *seq = biss_proto_slot_seq(s1, r->frame);
            return BISS_OK;
        }
    }
    return BISS_E_RETRY;
}

/* Frames a reader may still return from before follow_from: the ring's
 * (one slot is being filled) and the frame under way. */
#define FOLLOW_WINDOW (BISS_RING_SLOTS(1) + 2u)

/* The configuration s is judged by: a follower's frames from before the
 * owner's new period are judged without max_speed (biss_priv.h). */
static const struct biss_config *judged_by(biss_t *h, uint32_t seq, struct biss_config *tmp) {
    if (!h->follow_hold) {
        return &h->cfg;
    }
    uint32_t before = h->follow_from - seq; /* 1.. for frames before it */
    if (before == 0 || before > FOLLOW_WINDOW) {
        if (seq - h->follow_from > FOLLOW_WINDOW && seq - h->follow_from < 0x80000000u) {
            h->follow_hold = false; /* every reader is past it */
        }
        return &h->cfg;
    }
    *tmp = h->cfg;
    biss_speed_unchecked(tmp);
    return tmp;
}

uint64_t biss_read_clock(biss_t *h) {
    if (h->configured && biss_speed_checked(&h->cfg)) {
        return h->be.ops->now_us(h->be.ctx);
    }
    return BISS_SAFETY_NO_CLOCK; /* no speed check to tell */
}

int biss_result_to_sample(biss_t *h, const struct biss_shm_result *r, uint32_t seq, unsigned reader,
                          uint64_t read_us, struct biss_sample *s) {
    const char *why = biss_result_problem(&h->cfg, h->configured, r);
    if (why) {
        h->problem = why; /* the firmware never writes it: junk, named */
        return BISS_E_SHM_RESULT;
    }
    int rc = biss_sample_decode(&h->cfg, h->configured, seq, r, s);
    if (!rc && h->configured) {
        struct biss_config tmp;
        biss_safety_readers_check(judged_by(h, seq, &tmp), &h->safety, reader, s, read_us);
    }
    if (!rc) {
        biss_link_check(&h->link, s);
    }
    return rc;
}

static int read_sample_locked(biss_t *h, struct biss_sample *s) {
    struct biss_shm_result r;
    uint32_t seq = 0;
    int rc = biss_follow_period_locked(h);
    if (!rc) {
        rc = read_consistent(h, &r, &seq);
    }
    if (!rc && h->configured && h->cfg_pub_seq_valid && !h->cfg_pub_passed) {
        if (seq == h->cfg_pub_seq) {
            return BISS_E_NO_SAMPLE; /* published under the previous configuration */
        }
        h->cfg_pub_passed = true;
    }
    return rc ? rc : biss_result_to_sample(h, &r, seq, BISS_READER_NEWEST, biss_read_clock(h), s);
}

int biss_read_sample(biss_t *h, struct biss_sample *s) {
    if (!h || !s) {
        return BISS_E_INVAL;
    }
    pthread_mutex_lock(&h->lock);
    int rc = read_sample_locked(h, s);
    pthread_mutex_unlock(&h->lock);
    return rc;
}

struct wait_arg {
    uint32_t after_frame;
    uint32_t last_seq; /* ST_SEQ at the last full read */
    bool read_once;
    struct biss_sample *s;
};

/* Cheap poll of ST_SEQ; the whole sample only when it moved (or nothing
 * was read yet: read_sample_locked tells whether anything was published).
 * Frame numbers wrap, so "newer" is a signed distance. */
static int newer_published(biss_t *h, void *arg) {
    struct wait_arg *w = arg;
    uint32_t seq;
    struct biss_proto_io io = biss_io(h);
    int rc = biss_proto_pub_seq(&io, &seq);
    if (rc) {
        return rc;
    }
    if (w->read_once && seq == w->last_seq) {
        return 0;
    }
    rc = read_sample_locked(h, w->s);
    if (rc == BISS_E_NO_SAMPLE) {
        return 0; /* the previous configuration's: not yet */
    }
    if (rc) {
        return rc;
    }
    w->read_once = true;
    w->last_seq = w->s->seq;
    return (int32_t)(w->s->frame - w->after_frame) > 0;
}

int biss_wait_sample(biss_t *h, uint32_t after_frame, unsigned timeout_ms, struct biss_sample *s) {
    if (!h || !s) {
        return BISS_E_INVAL;
    }
    struct wait_arg w = {.after_frame = after_frame, .s = s};
    pthread_mutex_lock(&h->lock);
    int rc = biss_wait_for(h, timeout_ms, newer_published, &w);
    pthread_mutex_unlock(&h->lock);
    return rc;
}

int biss_line_delay(biss_t *h, struct biss_line_delay *d) {
    if (!h || !d) {
        return BISS_E_INVAL;
    }
    struct biss_sample s;
    int rc = biss_read_sample(h, &s);
    if (rc) {
        return rc;
    }
    /* aborted frames keep an older frame's delay in their buffer */
    if (!s.valid && !s.training) {
        return BISS_E_NO_SAMPLE;
    }
    *d = s.delay;
    return BISS_OK;
}

const char *biss_shm_problem(biss_t *h) {
    if (!h) {
        return "";
    }
    pthread_mutex_lock(&h->lock);
    const char *why = h->problem ? h->problem : "";
    pthread_mutex_unlock(&h->lock);
    return why;
}

int biss_get_link_stats(biss_t *h, struct biss_link_stats *st) {
    if (!h || !st) {
        return BISS_E_INVAL;
    }
    pthread_mutex_lock(&h->lock);
    *st = h->link.stats;
    pthread_mutex_unlock(&h->lock);
    return BISS_OK;
}

int biss_set_link_warning(biss_t *h, uint32_t window, uint32_t warn) {
    if (!h || window == 0 || warn == 0) {
        return BISS_E_INVAL;
    }
    pthread_mutex_lock(&h->lock);
    biss_link_set_warning(&h->link, window, warn);
    pthread_mutex_unlock(&h->lock);
    return BISS_OK;
}

int biss_get_safety_stats(biss_t *h, struct biss_safety_stats *st) {
    if (!h || !st) {
        return BISS_E_INVAL;
    }
    pthread_mutex_lock(&h->lock);
    *st = h->safety.stats;
    pthread_mutex_unlock(&h->lock);
    return BISS_OK;
}
