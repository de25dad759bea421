/* biss_result_check.c - what the firmware can write to data RAM, against
 * what is read there (biss_proto.h). Data RAM is untrusted: another
 * program, another firmware or a bus error may have put anything there,
 * and a word the firmware never writes must not become a position.
 *
 * What it can write follows from where it writes it (pru_fw/results.p) and
 * from the contract (include/biss/biss_shm.h):
 *  - a frame that ran to its end (FRAME_END) is VALID, or, its ACK over
 *    half a bit from the average, ACK_JUMP instead (one clear, one set);
 *    either with CRC_ERROR when a slave's CRC failed, and only a VALID one
 *    with SMA (the average full); its line delay, sample point (0..7) and
 *    lag are this frame's, and each slave's status has only CRC_OK (set
 *    exactly when CRC_ERROR is not, for the slaves with a CRC; always for
 *    the others), nE and nW (only for a slave that sends them) and its data
 *    no bit above its data bits (the firmware masks them); under an IEP
 *    trigger any of these may carry IEP_LATE too (the frame did not start
 *    on its period's count: FRAME_END);
 *  - a frame that ended early has exactly one flag: NO_SLAVE (with SL_INIT
 *    when it was iC-MB4's INIT), PROC_ERROR, or TRAINING (which measured
 *    the line delay);
 *  - every publication carries the slave count (1..8) and the MA half
 *    period of its configuration, which the firmware accepted (its rule:
 *    biss_proto_half_check); a frame that ran waited at most the ACK limit
 *    the configuration gives (BISS_MAX_DELAY_NS) and at most the
 *    processing-time limit (PROC_LIMIT) for the slave.
 * The status words: ST_STATE one of BISS_STATE_*, ST_BUF a slot of the
 * ring (0 before the first publication), ST_PRU 0 or 1, ST_CFG_ERROR one
 * of BISS_CFGERR_*. */
#include "biss_proto.h"

static const uint32_t ended_flags[] = {
    BISS_RF_VALID,
    BISS_RF_VALID | BISS_RF_CRC_ERROR,
    BISS_RF_VALID | BISS_RF_SMA,
    BISS_RF_VALID | BISS_RF_CRC_ERROR | BISS_RF_SMA,
    BISS_RF_ACK_JUMP,
    BISS_RF_ACK_JUMP | BISS_RF_CRC_ERROR,
    /* an edge off the bit grid: as a valid frame's flags, VALID left out */
    BISS_RF_OFF_GRID,
    BISS_RF_OFF_GRID | BISS_RF_CRC_ERROR,
    BISS_RF_OFF_GRID | BISS_RF_SMA,
    BISS_RF_OFF_GRID | BISS_RF_CRC_ERROR | BISS_RF_SMA,
    BISS_RF_OFF_GRID | BISS_RF_ACK_JUMP,
    BISS_RF_OFF_GRID | BISS_RF_ACK_JUMP | BISS_RF_CRC_ERROR,
};

static const uint32_t early_flags[] = {
    BISS_RF_NO_SLAVE,
    BISS_RF_NO_SLAVE | BISS_RF_SL_INIT,
    BISS_RF_PROC_ERROR,
    BISS_RF_TRAINING,
};

static bool among(uint32_t flags, const uint32_t *set, size_t n) {
    for (size_t i = 0; i < n; i++) {
        if (flags == set[i]) {
            return true;
        }
    }
    return false;
}

bool biss_result_ran_to_end(uint32_t flags) {
    return among(flags, ended_flags, sizeof ended_flags / sizeof ended_flags[0]);
}

/* The latest ACK position of half period `half` in bit/8 units: the
 * firmware waits (BISS_MAX_DELAY_NS / 10 / H + 4) periods for the ACK
 * (pru_fw/config.p) and places it within the period after; an SSI line's
 * round trip is configured, up to 65 535 ns (CFG_SSI_DELAY_NS), instead. */
static unsigned ack_limit_eighths(unsigned half, bool ssi) {
    unsigned ns = ssi && BISS_MAX_DELAY_NS < 65535u ? 65535u : BISS_MAX_DELAY_NS;
    return 8u * (ns / 10u / half + 5u);
}

static const char *bad_line_delay(const struct biss_shm_result *r, bool ended, bool ssi) {
    unsigned most = ack_limit_eighths(r->half, ssi);
    if (r->delay_raw > most || r->delay_avg > most) {
        return "line delay (DELAY_RAW, DELAY_AVG): beyond the firmware's ACK limit";
    }
    if (!ended) {
        return NULL;
    }
    if (r->sample_point > 7) {
        return "sample point: not 0..7";
    }
    /* whole periods to the ACK, plus a few: only where the byte can hold
     * every lag the rate allows (at high rates it cannot) */
    unsigned lag_most = most / 8u + 4u;
    if (lag_most < 256 && r->lag_periods > lag_most) {
        return "lag: more periods than the firmware waits for the ACK";
    }
    return NULL;
}

static const char *bad_slave(const struct biss_slave_config *c,
                             const struct biss_shm_slave_result *s, uint32_t flags) {
    if (s->status & ~(uint32_t)(BISS_RS_CRC_OK | BISS_RS_NE | BISS_RS_NW)) {
        return "slave status: bits the firmware never sets";
    }
    if (!c) {
        return NULL;
    }
    if (!c->has_ew && (s->status & (BISS_RS_NE | BISS_RS_NW))) {
        return "slave status: nE/nW of a slave that sends none";
    }
    bool crc_ok = (s->status & BISS_RS_CRC_OK) != 0;
    if (!c->crc_bits && !crc_ok) {
        return "slave status: a CRC error of a slave without CRC";
    }
    if (!crc_ok && !(flags & BISS_RF_CRC_ERROR)) {
        return "slave status: a CRC error the frame's flags do not have";
    }
    uint64_t data = (uint64_t)s->data_hi << 32 | s->data_lo;
    if (data & ~biss_low_mask(c->data_bits)) {
        return "slave data: bits above its data bits";
    }
    return NULL;
}

const char *biss_result_problem(const struct biss_config *c, bool configured,
                                const struct biss_shm_result *r) {
    bool iep =
        !configured || c->trigger == BISS_TRIGGER_IEP || c->trigger == BISS_TRIGGER_IEP_FOLLOW;
    bool late = iep && (r->flags & BISS_RF_IEP_LATE);
    bool ended = biss_result_ran_to_end(late ? r->flags & ~(uint32_t)BISS_RF_IEP_LATE : r->flags);
    if (!ended &&
        (late || !among(r->flags, early_flags, sizeof early_flags / sizeof early_flags[0]))) {
        return "result flags: a combination the firmware never writes";
    }
    if (biss_proto_half_check(r->half) != BISS_OK) {
        return "MA half period: one the firmware never runs";
    }
    if (r->nslaves < 1 || r->nslaves > BISS_MAX_SLAVES ||
        (configured && r->nslaves != c->nslaves)) {
        return "slave count: not the configuration's";
    }
    if (ended || (r->flags & BISS_RF_TRAINING)) {
        /* an SSI line's round trip is configured, not measured */
        const char *why = bad_line_delay(r, ended, !configured || c->slave[0].ssi);
        if (why) {
            return why;
        }
    }
    if (!ended) {
        return NULL; /* older frames' words stay in an aborted frame's buffer */
    }
    if (r->cds > 1 || r->cdm > 1) {
        return "CDS or CDM: not a bit";
    }
    if (configured && r->proc_clocks > c->proc_limit) {
        return "processing time: over the limit the firmware aborts at";
    }
    bool crc_failed = false;
    for (unsigned i = 0; i < r->nslaves; i++) {
        const struct biss_slave_config *sc = configured ? &c->slave[i] : NULL;
        const char *why = bad_slave(sc, &r->slave[i], r->flags);
        if (why) {
            return why;
        }
        crc_failed = crc_failed || !(r->slave[i].status & BISS_RS_CRC_OK);
    }
    if ((r->flags & BISS_RF_CRC_ERROR) && !crc_failed) {
        return "result flags: a CRC error no slave has";
    }
    return NULL;
}

const char *biss_status_problem(const struct biss_shm_status *st, uint32_t st_pru) {
    if (st->magic != BISS_MAGIC) {
        return NULL; /* not running: nothing of it is read */
    }
    if (st->state > BISS_STATE_NO_SLAVE) {
        return "firmware state (ST_STATE): not a BISS_STATE_*";
    }
    /* ST_BUF is 0 until the first publication, a slot from then on; ST_SEQ
     * 0 with it nothing published, or the counter past 2^32 - 1 */
    if (st->buf != 0 ? biss_proto_slot_check(st->buf, 0) != BISS_OK : st->seq != 0) {
        return "result slot (ST_BUF): not a slot of the ring";
    }
    if (st->cfg_error > BISS_CFGERR_SSI) {
        return "configuration error (ST_CFG_ERROR): not a BISS_CFGERR_*";
    }
    if (st_pru > 1) {
        return "PRU (ST_PRU): not 0 or 1";
    }
    return NULL;
}
