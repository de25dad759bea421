/*
 * fw_check.h - checks every frame the BiSS-C master firmware publishes
 * (include/biss/biss_shm.h) against what the slave models sent in it.
 *
 * A store watch on the firmware's publication counter (BISS_ST_SEQ) fires
 * at the instant of each publication; the frame it publishes is the one the
 * master began last (bench_current_frame), whose record the slave model
 * holds (closed, or still in its timeout). The published buffer is read
 * and decoded by the protocol layer (proto/biss_proto.h), as libbiss does;
 * a data word the firmware passes as right (its CRC checked) must equal
 * the word the model put on the wire (proto's layout rule); one whose CRC
 * failed counts as a CRC error, not a mismatch.
 */
#ifndef FW_CHECK_H
#define FW_CHECK_H

#include "bench.h"
#include "bench_fw.h"
#include "wrong_frame.h"

#include <stdint.h>

/* One publication as the firmware wrote it (proto's decoding). */
struct fw_frame {
    int seen; /* 0: not published (yet) */
    uint32_t frame, flags, timestamp;
    unsigned delay_raw, delay_avg, sample_point, lag, half, nslaves;
    uint64_t data[8];
    uint32_t status[8];
    struct biss_sample sample; /* the whole of it */
};

struct fw_check {
    struct bench *b;
    struct biss_config cfg; /* the chain's layout (bench_fw_layout), to decode by
                               (freq_hz unused: the rate comes with each result) */
    uint64_t bad_results;   /* publications proto refused (slave count, buffer index) */
    uint64_t publications;  /* every publication */
    uint64_t frames;        /* valid frames, compared */
    uint64_t crc_errors;    /* frames flagged with a CRC error */
    uint64_t mismatches;    /* frames with a word passed as right (CRC) but unlike what was sent */
    uint64_t no_slave, proc_errors, training;
    uint64_t ack_jumps;          /* frames refused for an ACK away from the average */
    uint64_t ack_jump_good;      /* of those, frames whose every word was right: good frames lost */
    struct biss_link_state link; /* the link's eye and warning over every publication */
    uint64_t off_grid;           /* frames refused for an SL edge off the bit grid */
    uint64_t off_grid_good;      /* of those, frames whose every word was right */
    uint64_t delay_frames;       /* publications with a line delay (valid or training) */
    uint64_t unmatched;          /* valid frames whose slave record was gone */
    uint32_t last_flags;
    unsigned delay_raw, delay_avg, sample_point, lag, half;
    uint32_t delay_frame; /* the frame (the firmware's number, 1 the first) of those five */
    unsigned delay_raw_min, delay_raw_max; /* raw ACK positions of the valid frames */
    unsigned proc_clocks_max;
    unsigned nslaves;
    uint64_t data[8];              /* last valid frame: data word per slave */
    uint32_t status[8];            /* and its status (BISS_RS_*) */
    uint64_t sent[8];              /* and the position the encoder sent in it */
    uint64_t first_mismatch_frame; /* publication number, 0 none */
    uint64_t limit;                /* valid frames to check; later publications are ignored */
    uint64_t watch;                /* the slave's number of a frame to keep, UINT64_MAX none */
    struct fw_frame watched;       /* what the firmware published for it */
    /* the host's safety checks (fc->cfg's life_check, ew_static and pairs, by proto as
     * libbiss runs them) over every publication */
    struct biss_safety_state safety;
    uint64_t safety_faults;      /* publications with a fault flagged */
    uint32_t safety_first_fault; /* the firmware's number of the first, 0 none */
    uint64_t misframed;          /* valid publications the nE/nW check (ew_static) refused */
    uint64_t misframed_good;     /* of those, frames whose every word was right: good lost */
    /* The publication of each valid frame (the cycle its ST_SEQ store
     * issues in; emulator/bench/INSTRUMENTS.md) after the start of its
     * last bit at the master's SL pin (the slave's rise that clocked it
     * out, its output delay, the SL line's nominal delay), and after the
     * position's latch (the first MA rise at the slave). */
    struct bench_span latency;
    struct bench_span age;
    sim_ps sl_delay_ps; /* the SL line's nominal delay (the scenario's, fixed) */
    /* each slave's word (the model's words) and its layout (proto's rule),
     * taken once: the configuration is fixed for the run */
    slave_word words[SLAVE_MAX_WORDS];
    struct biss_proto_word layout[SLAVE_MAX_WORDS];
    unsigned nwords;
    /* the mismatches (wrong but valid), each classified (wrong_frame.h):
     * counts per class, and the first FW_CHECK_WRONG_KEPT in full */
    uint64_t wrong_by_class[WRONG_CLASSES];
    unsigned nwrong;
    struct wrong_frame wrong[16];
};
#define FW_CHECK_WRONG_KEPT 16

/* Starts checking the bench's publications from now on (no limit). */
void fw_check_attach(struct fw_check *fc, struct bench *b);

/* Configures the firmware with fc->cfg (fw_check_attach's: the chain's
 * layout; the caller sets its rate, trigger, IEP period, processing-time
 * limit and safety checks) through bench_fw_configure (half: 0 for
 * cfg.freq_hz's H; 0 or a negative code), and times the host's checks as
 * its trigger does: by the frame numbers times cfg.iep_period_ns for
 * BISS_TRIGGER_IEP and BISS_TRIGGER_IEP_FOLLOW (for which it is the owning
 * channel's period: the firmware takes none), else by the timestamps. The
 * checks start afresh, as libbiss's do after a configuration. */
int fw_check_configure(struct fw_check *fc, unsigned half);

/* Keeps the publication of the frame the slave numbers k (from 0) in
 * fc->watched, whatever the limit. */
void fw_check_watch(struct fw_check *fc, uint64_t k);

/* Starts counting afresh, checking at most `limit` more valid frames (the
 * watched frame stays). */
void fw_check_restart(struct fw_check *fc, uint64_t limit);

#endif
