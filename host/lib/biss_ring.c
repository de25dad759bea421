/* biss_ring.c - every frame: the result ring read through the protocol
 * layer (proto/biss_ring.c), each frame checked and decoded as a sample. */
#include "biss_priv.h"

#include "biss/biss_shm_struct.h"

/* The first call's cursor: the configuration's first publication, or, on
 * a handle that did not configure, the newest one (returned). */
static int ring_start(biss_t *h) {
    if (h->configured && h->cfg_pub_seq_valid) {
        h->ring_cursor = h->cfg_pub_seq;
    } else {
        struct biss_proto_io io = biss_io(h);
        uint32_t seq;
        bool any;
        int rc = biss_proto_pub_seq_any(&io, &seq, &any);
        if (rc) {
            return rc;
        }
        h->ring_cursor = any ? seq - 1 : 0;
    }
    h->ring_started = true;
    return BISS_OK;
}

int biss_ring_follow(biss_t *h, bool own) {
    if (!h->ring_started) {
        return BISS_OK;
    }
    struct biss_proto_io io = biss_io(h);
    struct biss_ring_look now;
    int rc = biss_proto_ring_look(&io, &now);
    if (rc) {
        return rc;
    }
    if (!own && h->ring_seen_valid && biss_proto_ring_restarted(&h->ring_seen, &now)) {
        h->ring_cursor = 0;
    }
    h->ring_seen = now;
    h->ring_seen_valid = true;
    return BISS_OK;
}

int biss_ring_restart(biss_t *h) {
    if (!h->ring_started) {
        return BISS_OK;
    }
    struct biss_proto_io io = biss_io(h);
    uint32_t seq;
    int rc = biss_proto_pub_seq(&io, &seq);
    if (rc) {
        return rc;
    }
    h->ring_skipped += seq - h->ring_cursor;
    h->ring_cursor = 0;
    h->ring_seen_valid = false;
    return BISS_OK;
}

/* Chunks of at most one ring's worth (the protocol layer's copy). */
#define CHUNK BISS_RING_SLOTS(1)

static int ring_read_locked(biss_t *h, struct biss_sample *out, unsigned max, unsigned *n,
                            uint32_t *lost) {
    int rc = biss_follow_period_locked(h);
    if (!rc && !h->ring_started) {
        rc = ring_start(h);
    }
    if (!rc) {
        rc = biss_ring_follow(h, false);
    }
    *lost = h->ring_skipped;
    h->ring_skipped = 0;
    struct biss_proto_io io = biss_io(h);
    struct biss_shm_result raw[CHUNK];
    while (!rc && *n < max) {
        unsigned want = max - *n < CHUNK ? max - *n : CHUNK;
        unsigned got;
        uint32_t gone;
        rc = biss_proto_ring_read(&io, &h->ring_cursor, raw, want, &got, &gone);
        *lost += gone;
        uint64_t read_us = got ? biss_read_clock(h) : BISS_SAFETY_NO_CLOCK; /* after the copy */
        for (unsigned i = 0; !rc && i < got; i++) {
            rc = biss_result_to_sample(h, &raw[i], raw[i].frame, BISS_READER_RING, read_us,
                                       &out[*n]);
            *n += !rc;
        }
        if (got + gone < want) {
            break; /* caught up with the firmware */
        }
    }
    return rc;
}

int biss_ring_read(biss_t *h, struct biss_sample *out, unsigned max, unsigned *n, uint32_t *lost) {
    if (!h || (!out && max) || !n || !lost) {
        return BISS_E_INVAL;
    }
    *n = 0;
    pthread_mutex_lock(&h->lock);
    int rc = ring_read_locked(h, out, max, n, lost);
    pthread_mutex_unlock(&h->lock);
    return rc;
}

int biss_ring_capacity(biss_t *h, unsigned *frames) {
    struct biss_config c;
    int rc = frames ? biss_get_config(h, &c) : BISS_E_INVAL;
    if (!rc) {
        *frames = BISS_RING_SLOTS(c.nslaves) - 1;
    }
    return rc;
}
