/* biss_io.c - data RAM access and bounded waits over the backend. */
#include "biss_priv.h"

int biss_dram_read(biss_t *h, uint32_t off, void *buf, size_t n) {
    return h->be.ops->read(h->be.ctx, ICSS_DRAM(h->be.pru) + off, buf, n);
}

int biss_dram_write(biss_t *h, uint32_t off, const void *buf, size_t n) {
    return h->be.ops->write(h->be.ctx, ICSS_DRAM(h->be.pru) + off, buf, n);
}

static int io_read(void *ctx, uint32_t off, void *buf, size_t n) {
    return biss_dram_read(ctx, off, buf, n);
}

static int io_write(void *ctx, uint32_t off, const void *buf, size_t n) {
    return biss_dram_write(ctx, off, buf, n);
}

struct biss_proto_io biss_io(biss_t *h) {
    return (struct biss_proto_io){.read = io_read, .write = io_write, .ctx = h};
}

int biss_dram_read32(biss_t *h, uint32_t off, uint32_t *v) {
    return biss_dram_read(h, off, v, 4);
}

int biss_dram_write32(biss_t *h, uint32_t off, uint32_t v) {
    return biss_dram_write(h, off, &v, 4);
}

static int advance(biss_t *h, unsigned us) {
    const struct biss_backend_ops *ops = h->be.ops;
    if (!ops->advance_sleeps) {
        return ops->advance(h->be.ctx, us);
    }
    /* a sleeping wait must not keep other threads out of the handle */
    pthread_mutex_unlock(&h->lock);
    int rc = ops->advance(h->be.ctx, us);
    pthread_mutex_lock(&h->lock);
    return rc;
}

int biss_wait_for(biss_t *h, unsigned timeout_ms, int (*done)(biss_t *h, void *arg), void *arg) {
    return biss_wait_for_us(h, (uint64_t)timeout_ms * 1000u, done, arg);
}

int biss_wait_for_us(biss_t *h, uint64_t timeout_us, int (*done)(biss_t *h, void *arg), void *arg) {
    const struct biss_backend_ops *ops = h->be.ops;
    uint64_t deadline = ops->now_us(h->be.ctx) + timeout_us;
    for (;;) {
        int rc = done(h, arg);
        if (rc < 0) {
            return rc;
        }
        if (rc > 0) {
            return BISS_OK;
        }
        uint64_t now = ops->now_us(h->be.ctx);
        if (now >= deadline) {
            return BISS_E_TIMEOUT;
        }
        uint64_t left = deadline - now;
        rc = advance(h, left < ops->poll_us ? (unsigned)left : ops->poll_us);
        if (rc) {
            return rc;
        }
    }
}
