/* biss_ring.c - every frame: the publications after a reader's cursor,
 * copied from the firmware's result ring (biss_shm.h, "Every frame"). */
#include "biss_proto.h"

#include <stdatomic.h>
#include <string.h>

/* A publication takes the firmware a few hundred ns; a reader racing it
 * many times in a row means something else is wrong. */
#define MAX_TRIES 1000

static int rd(const struct biss_proto_io *io, uint32_t off, void *buf, size_t n) {
    return io->read(io->ctx, off, buf, n);
}

/* The newest publication: its number, its slot and the slave count of its
 * layout, consistent: the slot ST_BUF names holds that number
 * (biss_proto_slot_seq: ST_SEQ's, or one more while the firmware is
 * between its stores of ST_BUF and ST_SEQ). */
struct ring_head {
    bool any; /* anything published since the start (biss_proto_pub_seq_any) */
    uint32_t seq;
    uint32_t slot;
    unsigned nslaves;
};

static int ring_head(const struct biss_proto_io *io, struct ring_head *h) {
    for (int i = 0; i < MAX_TRIES; i++) {
        uint32_t buf;
        struct biss_shm_result hdr; /* its header only */
        int rc = biss_proto_pub_seq_any(io, &h->seq, &h->any);
        if (rc || !h->any) {
            return rc;
        }
        atomic_thread_fence(memory_order_acquire);
        rc = rd(io, BISS_ST_BUF, &buf, 4);
        if (!rc && biss_proto_slot_check(buf, 0) != BISS_OK) {
            return BISS_E_SHM_RESULT;
        }
        if (!rc) {
            rc = rd(io, buf, &hdr, BISS_R_SLAVE0);
        }
        if (rc) {
            return rc;
        }
        const struct biss_shm_result *r = &hdr;
        h->seq = biss_proto_slot_seq(h->seq, r->frame);
        if (r->frame != h->seq) {
            continue; /* publications in between */
        }
        if (r->nslaves == 0 || biss_proto_slot_check(buf, r->nslaves) != BISS_OK) {
            return BISS_E_SHM_RESULT;
        }
        h->slot = buf;
        h->nslaves = r->nslaves;
        return BISS_OK;
    }
    return BISS_E_RETRY;
}

int biss_proto_ring_read(const struct biss_proto_io *io, uint32_t *cursor,
                         struct biss_shm_result *out, unsigned max, unsigned *n, uint32_t *lost) {
    *n = 0;
    *lost = 0;
    struct ring_head h;
    int rc = ring_head(io, &h);
    if (rc || !h.any || h.seq == *cursor) {
        return rc;
    }
    const uint32_t stride = BISS_RING_STRIDE(h.nslaves);
    const uint32_t slots = BISS_RING_SLOTS(h.nslaves);
    /* The publications after the cursor, modulo 2^32: a reader 2^31 or
     * more behind is behind (a counter that went back is the caller's to
     * tell, biss_proto_ring_restarted). The slot after the newest may be
     * being filled already: slots - 1 publications at most are whole. */
    uint32_t pending = h.seq - *cursor;
    if (pending > slots - 1) {
        *lost = pending - (slots - 1);
        *cursor += *lost;
        pending = slots - 1;
    }
    uint32_t take = pending < max ? pending : max;
    if (take == 0) {
        return BISS_OK;
    }
    /* Their slots, oldest first: in one run, or two where the ring wraps. */
    uint8_t copy[BISS_RING_END - BISS_RING0];
    uint32_t newest = (h.slot - BISS_RING0) / stride;
    uint32_t first = (newest + slots - (h.seq - (*cursor + 1)) % slots) % slots;
    uint32_t run = slots - first < take ? slots - first : take;
    atomic_thread_fence(memory_order_acquire);
    rc = rd(io, BISS_RING0 + first * stride, copy, run * stride);
    if (!rc && run < take) {
        rc = rd(io, BISS_RING0, copy + run * stride, (take - run) * stride);
    }
    uint32_t seq2 = 0;
    atomic_thread_fence(memory_order_acquire);
    if (!rc) {
        rc = rd(io, BISS_ST_SEQ, &seq2, 4);
    }
    if (rc) {
        return rc;
    }
    /* Publication s is whole if the firmware had not yet published
     * s + slots - 1 when the copy ended (only then does it refill s's slot). */
    uint32_t oldest_whole = seq2 - (slots - 2);
    for (uint32_t i = 0; i < take; i++) {
        uint32_t s = *cursor + 1 + i;
        const uint8_t *slot = copy + i * stride;
        struct biss_shm_result *r = &out[*n];
        memset(r, 0, sizeof *r);
        memcpy(r, slot, stride);
        if ((int32_t)(s - oldest_whole) < 0 || r->frame != s || r->nslaves != h.nslaves) {
            ++*lost;
            continue;
        }
        ++*n;
    }
    *cursor += take;
    return BISS_OK;
}

int biss_proto_ring_look(const struct biss_proto_io *io, struct biss_ring_look *look) {
    /* ST_SEQ to ST_CFG_ACK in one transfer: three words */
    _Static_assert(BISS_ST_CFG_ACK > BISS_ST_SEQ, "ST_CFG_ACK after ST_SEQ");
    uint32_t w[(BISS_ST_CFG_ACK - BISS_ST_SEQ) / 4 + 1];
    int rc = rd(io, BISS_ST_SEQ, w, sizeof w);
    if (!rc) {
        look->seq = w[0];
        look->cfg_ack = w[(BISS_ST_CFG_ACK - BISS_ST_SEQ) / 4];
    }
    return rc;
}

bool biss_proto_ring_restarted(const struct biss_ring_look *then,
                               const struct biss_ring_look *now) {
    return now->cfg_ack != then->cfg_ack && now->seq - then->seq >= 0x80000000u;
}
