/* biss_configure.c - handing a configuration to the firmware: block first,
 * CFG_SEQ last, then the firmware's ack and verdict. */
#include "biss_priv.h"

#include "biss/biss_shm_struct.h"

#include <stdbool.h>
#include <stddef.h>

/* The firmware treats CFG_SEQ 0 as "nothing written yet" and starts with
 * ST_CFG_ACK = 0xffffffff: neither may ever be a real sequence number. */
static uint32_t next_seq(uint32_t seq) {
    do {
        seq++;
    } while (seq == 0 || seq == 0xffffffffu);
    return seq;
}

static int acked(biss_t *h, void *arg) {
    struct biss_proto_io io = biss_io(h);
    struct biss_shm_status st;
    int rc = biss_proto_status_get(&io, &st);
    if (rc) {
        return rc;
    }
    return st.cfg_ack == *(const uint32_t *)arg;
}

/* A timeout means one thing when the firmware never came up, another when
 * it runs but did not take the block. */
static int timeout_reason(biss_t *h) {
    struct biss_proto_io io = biss_io(h);
    struct biss_shm_status st = {0};
    biss_proto_status_get(&io, &st);
    return st.magic == BISS_MAGIC ? BISS_E_TIMEOUT : BISS_E_NOT_RUNNING;
}

static int write_block(biss_t *h, const struct biss_config *c, uint32_t seq) {
    struct biss_shm_config blk;
    biss_config_encode(c, &blk);
    struct biss_proto_io io = biss_io(h);
    return biss_proto_config_put(&io, &blk, seq);
}

/* The other PRU's data RAM (the IEP is one per PRU-ICSS). */
static int other_read(void *ctx, uint32_t off, void *buf, size_t n) {
    biss_t *h = ctx;
    return h->be.ops->read(h->be.ctx, ICSS_DRAM(1u - h->be.pru) + off, buf, n);
}

/* Whether the other PRU's channel owns the IEP: its firmware runs (any
 * state: without a slave it still resets the count) with the IEP trigger
 * in its block, accepted or not yet looked at (a configuration in flight
 * is taken as what it asks for; with `applied`, only one the firmware has
 * accepted: the period the IEP runs), and *period_ns is its period. Not
 * when the other PRU cannot be read (not mapped) or runs nothing. */
static bool iep_owner(biss_t *h, bool applied, uint32_t *period_ns) {
    struct biss_proto_io io = {.read = other_read, .ctx = h};
    struct biss_shm_status st;
    struct biss_shm_config blk;
    if (biss_proto_status_get(&io, &st) || st.magic != BISS_MAGIC ||
        biss_proto_config_get(&io, &blk)) {
        return false;
    }
    *period_ns = blk.iep_period * 5u; /* 5 ns IEP counts */
    bool refused = st.cfg_ack == blk.seq && st.cfg_error != BISS_CFGERR_NONE;
    bool pending = st.cfg_ack != blk.seq;
    return blk.seq != 0 && blk.trigger == BISS_TRIGGER_IEP && !refused && !(applied && pending);
}

bool biss_speed_checked(const struct biss_config *c) {
    for (unsigned i = 0; i < BISS_API_MAX_SLAVES; i++) {
        if (c->slave[i].max_speed != 0) {
            return true;
        }
    }
    return false;
}

void biss_speed_unchecked(struct biss_config *c) {
    for (unsigned i = 0; i < BISS_API_MAX_SLAVES; i++) {
        c->slave[i].max_speed = 0;
    }
}

/* The IEP as c needs it, into *c: the IEP trigger is refused while the
 * other PRU's channel owns the IEP; following, c takes that channel's
 * period (the speed check counts frames in it; a period given must be
 * that one); the speed check on the timestamps (host trigger, free-run)
 * needs a count that no IEP trigger restarts every period. Then c passes
 * the library's checks (a speed check following no owner and given no
 * period has no time to judge by: BISS_E_SAFETY_SPEED). */
static int iep_as_needed(biss_t *h, struct biss_config *c) {
    uint32_t period = 0;
    bool owned = iep_owner(h, false, &period);
    switch (c->trigger) {
    case BISS_TRIGGER_IEP:
        if (owned) {
            return BISS_E_IEP_OWNED;
        }
        break;
    case BISS_TRIGGER_IEP_FOLLOW:
        if (owned && c->iep_period_ns && c->iep_period_ns != period) {
            return BISS_E_IEP_PERIOD;
        }
        if (owned) {
            c->iep_period_ns = period;
        }
        break;
    default:
        if (owned && biss_speed_checked(c)) {
            return BISS_E_SAFETY_SPEED;
        }
    }
    return biss_config_check(c);
}

/* The owner may take another period at any time (its own configuration):
 * the frames counted from then on are that long, so a follower's speed
 * check takes it, and judges no time across the change: the frame under
 * way when it was seen may have begun in the old period (the owner's
 * configuration restarts the count), so references start two publications
 * on. */
int biss_follow_period_locked(biss_t *h) {
    uint32_t period;
    if (!h->configured || h->cfg.trigger != BISS_TRIGGER_IEP_FOLLOW ||
        !biss_speed_checked(&h->cfg)) {
        return BISS_OK;
    }
    /* every read comes here: the owner's period word alone while it is
     * the one followed, its whole blocks only when it differs */
    struct biss_proto_io other = {.read = other_read, .ctx = h};
    uint32_t counts;
    if (biss_proto_iep_period_get(&other, &counts) != BISS_OK ||
        counts * 5u == h->cfg.iep_period_ns || !iep_owner(h, true, &period) ||
        period == h->cfg.iep_period_ns) {
        return BISS_OK;
    }
    struct biss_proto_io io = biss_io(h);
    uint32_t seq;
    int rc = biss_proto_pub_seq(&io, &seq);
    if (rc) {
        return rc;
    }
    h->cfg.iep_period_ns = period;
    h->follow_from = seq + 2;
    h->follow_hold = true;
    biss_safety_readers_restart(&h->safety);
    return BISS_OK;
}

/* The configuration's exchange with the firmware (handle locked). */
static int exchange(biss_t *h, struct biss_config *c);

/* The IEP is one per PRU-ICSS: whether the other channel owns it is read
 * and this channel's block written and acked under the IEP's lock, so two
 * channels configured at once never both own it (the check apart from the
 * write let both through). */
static int configure_locked(biss_t *h, const struct biss_config *given) {
    struct biss_config cfg = *given;
    int rc = biss_exclusive(h);
    if (rc) {
        return rc;
    }
    bool locked = h->be.ops->iep_lock != NULL;
    if (locked) {
        rc = h->be.ops->iep_lock(h->be.ctx, true, h->timeout_ms);
        if (rc) {
            return rc;
        }
    }
    rc = iep_as_needed(h, &cfg);
    if (!rc) {
        rc = exchange(h, &cfg);
    }
    if (locked) {
        h->be.ops->iep_lock(h->be.ctx, false, 0);
    }
    return rc;
}

/* An SSI configuration cuts the control program that has not ended when
 * it is written (its verdict: biss_cd_check); *cut 1 and *cmd its number,
 * or 0. */
static int program_cut(biss_t *h, const struct biss_config *c, int *cut, uint32_t *cmd) {
    struct biss_proto_io io = biss_io(h);
    int rc = c->slave[0].ssi ? biss_proto_cd_running(&io, cmd) : 0;
    *cut = rc > 0;
    return rc < 0 ? rc : BISS_OK;
}

static int exchange(biss_t *h, struct biss_config *c) {
    uint32_t seq = next_seq(h->cfg_seq);
    int cut = 0;
    uint32_t cut_cmd = 0;
    /* the ring reader's look before: a restart since its last one */
    int rc = biss_ring_follow(h, false);
    if (!rc) {
        rc = program_cut(h, c, &cut, &cut_cmd);
    }
    if (!rc) {
        rc = write_block(h, c, seq);
    }
    if (rc) {
        return rc;
    }
    h->cfg_seq = seq;
    h->configured = false;
    rc = biss_wait_for(h, h->timeout_ms, acked, &seq);
    if (rc == BISS_E_TIMEOUT) {
        return timeout_reason(h);
    }
    if (rc) {
        return rc;
    }
    rc = biss_ring_follow(h, true); /* this configuration's ack: no restart */
    if (!rc) {
        rc = biss_pru_image_check(h, NULL);
    }
    struct biss_proto_io io = biss_io(h);
    struct biss_shm_status st;
    if (!rc) {
        rc = biss_proto_status_get(&io, &st);
    }
    if (!rc) {
        rc = biss_fw_cfg_error(st.cfg_error);
    }
    if (!rc) {
        h->cfg_pub_seq = st.seq; /* publications from here on are of this layout */
        h->cfg_pub_passed = false;
        if (h->ring_started) {
            h->ring_skipped += st.seq - h->ring_cursor; /* the last layout's, unread */
            h->ring_cursor = st.seq;
        }
        if (cut) {
            h->cd_cut = cut_cmd;
            h->cd_cut_set = true;
        }
        h->cfg = *c;
        h->configured = true;
        h->follow_hold = false;
        biss_safety_readers_restart(&h->safety); /* references from a new layout's frames on */
        h->cfg_pub_seq_valid = true;
    }
    return rc;
}

int biss_configure(biss_t *h, const struct biss_config *c) {
    if (!h || !c) {
        return BISS_E_INVAL;
    }
    /* following another channel's IEP, the period is that channel's
     * (configure_locked): the speed check's need of it is judged there */
    struct biss_config first = *c;
    if (first.trigger == BISS_TRIGGER_IEP_FOLLOW && !first.iep_period_ns) {
        biss_speed_unchecked(&first);
    }
    int rc = biss_config_check(&first);
    if (rc) {
        return rc;
    }
    biss_op_begin(h);
    rc = configure_locked(h, c);
    biss_op_end(h);
    return rc;
}

/* Used by biss_start after a restart: the firmware forgot everything. */
int biss_reconfigure_locked(biss_t *h) {
    if (!h->configured) {
        return BISS_OK;
    }
    struct biss_config c = h->cfg;
    return configure_locked(h, &c);
}

int biss_get_config(biss_t *h, struct biss_config *c) {
    if (!h || !c) {
        return BISS_E_INVAL;
    }
    pthread_mutex_lock(&h->lock);
    int rc = h->configured ? BISS_OK : BISS_E_NOT_CONFIGURED;
    if (!rc) {
        *c = h->cfg;
    }
    pthread_mutex_unlock(&h->lock);
    return rc;
}
