/* biss_run.c - starting, stopping and triggering the firmware; status and
 * counters. */
#include "biss_priv.h"

#include "biss/biss_shm_struct.h"

#include <stdatomic.h>

_Static_assert(BISS_FW_STOPPED == BISS_STATE_STOPPED && BISS_FW_RUNNING == BISS_STATE_RUNNING &&
                   BISS_FW_CFG_ERROR == BISS_STATE_CFG_ERROR &&
                   BISS_FW_NO_SLAVE == BISS_STATE_NO_SLAVE,
               "firmware state enum matches the shm codes");

static int start_locked(biss_t *h) {
    int rc = biss_exclusive(h);
    if (rc) {
        return rc;
    }
    if (h->attached && h->be.ops->pru_start) {
        /* attached through remoteproc: start what is installed */
        rc = biss_pru_load_and_start(h);
        return rc ? rc : biss_reconfigure_locked(h);
    }
    if (!h->image || h->attached) {
        /* attached to a firmware someone else loaded: resume it */
        uint32_t v = ICSS_CTRL_RESET_N | ICSS_CTRL_ENABLE;
        return h->be.ops->write(h->be.ctx, ICSS_CTRL(h->be.pru), &v, 4);
    }
    rc = biss_pru_load_and_start(h);
    if (!rc) {
        rc = biss_reconfigure_locked(h);
    }
    return rc;
}

int biss_start(biss_t *h) {
    if (!h) {
        return BISS_E_INVAL;
    }
    biss_op_begin(h);
    int rc = start_locked(h);
    biss_op_end(h);
    return rc;
}

int biss_stop(biss_t *h) {
    if (!h) {
        return BISS_E_INVAL;
    }
    pthread_mutex_lock(&h->lock);
    int rc = biss_exclusive(h);
    if (!rc) {
        rc = biss_pru_halt(h);
    }
    pthread_mutex_unlock(&h->lock);
    return rc;
}

int biss_trigger(biss_t *h) {
    if (!h) {
        return BISS_E_INVAL;
    }
    pthread_mutex_lock(&h->lock);
    int rc = BISS_OK;
    if (!h->configured) {
        rc = BISS_E_NOT_CONFIGURED;
    } else if (h->cfg.trigger != BISS_TRIGGER_HOST) {
        rc = BISS_E_NOT_HOST_TRIG;
    } else {
        /* The firmware clears CMD_TRIGGER when it starts the frame, and
         * only then: a trigger written over one still set would ask for
         * the same frame again. Read 0, no frame is owed, and the 1
         * written next is the only one. */
        atomic_thread_fence(memory_order_seq_cst);
        struct biss_proto_io io = biss_io(h);
        uint32_t pending;
        rc = biss_proto_trigger_get(&io, &pending);
        if (!rc && pending) {
            rc = BISS_E_TRIGGER_PENDING;
        }
        if (!rc) {
            rc = biss_proto_trigger(&io);
        }
    }
    pthread_mutex_unlock(&h->lock);
    return rc;
}

static int never(biss_t *h, void *arg) {
    (void)h;
    (void)arg;
    return 0;
}

static int run_for(biss_t *h, uint64_t us) {
    if (!h) {
        return BISS_E_INVAL;
    }
    pthread_mutex_lock(&h->lock);
    int rc = biss_wait_for_us(h, us, never, NULL);
    pthread_mutex_unlock(&h->lock);
    return rc == BISS_E_TIMEOUT ? BISS_OK : rc;
}

int biss_run_ms(biss_t *h, unsigned ms) {
    return run_for(h, (uint64_t)ms * 1000u);
}

int biss_run_us(biss_t *h, unsigned us) {
    return run_for(h, us);
}

/* The status words, refused (named in h->problem) where a running
 * firmware never writes them. Handle locked. */
static int status_words(biss_t *h, struct biss_shm_status *s) {
    struct biss_proto_io io = biss_io(h);
    uint32_t pru = 0;
    int rc = biss_proto_status_get(&io, s);
    if (!rc) {
        rc = biss_proto_fw_pru_get(&io, &pru);
    }
    const char *why = rc ? NULL : biss_status_problem(s, pru);
    if (why) {
        h->problem = why;
        return BISS_E_SHM_RESULT;
    }
    return rc;
}

static int status_locked(biss_t *h, struct biss_status *st) {
    struct biss_proto_io io = biss_io(h);
    struct biss_shm_status s;
    struct biss_shm_config blk;
    struct biss_shm_id id;
    int rc = status_words(h, &s);
    if (!rc) {
        rc = biss_pru_enabled(h, &st->pru_enabled);
    }
    if (!rc) {
        rc = biss_proto_config_get(&io, &blk);
    }
    if (!rc) {
        rc = biss_proto_id_get(&io, &id);
    }
    if (rc) {
        return rc;
    }
    st->cfg_seq = blk.seq;
    st->shm_version = id.magic == BISS_ID_MAGIC ? id.shm_version : 0;
    st->image_crc = id.magic == BISS_ID_MAGIC ? id.image_crc : 0;
    st->firmware_running = s.magic == BISS_MAGIC;
    st->state = s.state;
    st->cfg_ack = s.cfg_ack;
    st->cfg_error = s.cfg_error;
    st->seq = s.seq;
    return BISS_OK;
}

int biss_get_status(biss_t *h, struct biss_status *st) {
    if (!h || !st) {
        return BISS_E_INVAL;
    }
    pthread_mutex_lock(&h->lock);
    int rc = status_locked(h, st);
    pthread_mutex_unlock(&h->lock);
    return rc;
}

int biss_get_stats(biss_t *h, struct biss_stats *st) {
    if (!h || !st) {
        return BISS_E_INVAL;
    }
    struct biss_shm_status s;
    uint32_t off_grid = 0;
    pthread_mutex_lock(&h->lock);
    int rc = status_words(h, &s);
    if (!rc) {
        struct biss_proto_io io = biss_io(h);
        rc = biss_proto_off_grid_get(&io, &off_grid);
    }
    pthread_mutex_unlock(&h->lock);
    if (rc) {
        return rc;
    }
    st->frames = s.frames;
    st->crc_errors = s.crc_errors;
    st->no_slave = s.no_slave;
    st->proc_errors = s.proc_errors;
    st->training = s.training;
    st->off_grid = off_grid;
    return BISS_OK;
}
