/*
 * biss_proto.h - the host side of the firmware's shared-memory contract
 * (include/biss/biss_shm.h), written once: configuration encoding and
 * validation (with the MA rate / shift-clock rule), the slave data-word
 * layout, sample and line-delay decoding (Gray too), and the transfers of
 * the configuration block, the control-communication program and a
 * published result through any data-RAM reader/writer. The control
 * program codec is biss_cd.h; the PRU-ICSS/SoC map is biss_soc.h.
 *
 * libbiss drives the firmware through it on silicon and in the emulator;
 * the bench and the end-to-end tests drive it through it on the emulated
 * PRU. Nothing here does I/O of its own or knows the emulator, and nothing
 * here knows the host: its values are the contract's (include/biss/
 * biss_types.h, the public rules on them biss_rules.h), as is everything
 * it includes.
 */
#ifndef BISS_PROTO_H
#define BISS_PROTO_H

#include "biss/biss_rules.h"
#include "biss/biss_shm_struct.h"
#include "biss/biss_slave_shm_struct.h"
#include "biss/biss_types.h"
#include "biss_cd.h"

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

/* The layer's own calls are no part of libbiss.so's API (libbiss.map). */
#pragma GCC visibility push(hidden)

/* ---- configuration (biss_config_encode.c, biss_rate.c) ---- */

/* A checked config into the shm block (out->seq left 0: the caller writes
 * CFG_SEQ last, on its own). */
void biss_config_encode(const struct biss_config *c, struct biss_shm_config *out);
/* The same with the MA half period H given instead of c->freq_hz's, as it
 * is: a rate the firmware clocks that no whole number of Hz names (H = 12:
 * 8.33 MHz; 1024: 97.66 kHz), or one it refuses (its refusal tests). */
void biss_config_encode_half(const struct biss_config *c, unsigned half,
                             struct biss_shm_config *out);
/* Decodes a block read back from data RAM, as untrusted input: 0,
 * BISS_E_NOT_CONFIGURED (no rate: never configured) or BISS_E_SHM_CONFIG
 * (*field names the first bad field). */
int biss_config_decode(const struct biss_shm_config *in, struct biss_config *c, const char **field);
/* Maps ST_CFG_ERROR to BISS_E_FW_* (0 stays 0). */
int biss_fw_cfg_error(uint32_t cfgerr);
/* "BISS_CFGERR_HALF: ..." for a code the firmware reports in
 * BISS_ST_CFG_ERROR. */
const char *biss_proto_cfg_error_text(uint32_t code);
/* The MA rate rule, once (biss_rate.c; biss_rate_half, biss/biss_rules.h,
 * is its public face). The firmware's rule for an MA half period in PRU
 * cycles: BISS_OK, or BISS_E_RATE_RANGE (outside
 * BISS_MIN_HALF..BISS_MAX_HALF) or BISS_E_RATE_SHIFT (no exact 8x shift
 * clock). */
int biss_proto_half_check(unsigned half);
/* The same as a sentence, NULL when the firmware takes it. */
const char *biss_proto_half_problem(unsigned half);
/* H to the rate a biss_config names, 100 MHz / H in whole Hz (freq_hz may
 * be NULL): BISS_OK, the firmware's refusal of H, or BISS_E_RATE_INEXACT
 * (the firmware clocks it, but no whole number of Hz names it). */
int biss_proto_half_rate(unsigned half, uint32_t *freq_hz);
/* Any rate in Hz (biss-sim's --freq takes 97656.25) to H: BISS_OK when
 * 100 MHz / freq_hz is a whole number of PRU cycles (to 1e-9) up to 65535,
 * else BISS_E_RATE_INEXACT or BISS_E_RATE_RANGE (BISS_E_INVAL: not above
 * 0). Whether the firmware clocks that H is biss_proto_half_check's. */
int biss_proto_freq_half(double freq_hz, unsigned *half);
/* biss_line_check for any half period the firmware clocks, 100 MHz / H
 * whole in Hz or not (biss-sim takes 97656.25 Hz). */
int biss_proto_line_check(unsigned half, const struct biss_line_facts *f,
                          struct biss_line_verdict *v);

/* ---- the firmware image (biss_image_pru.c) ---- */

/* The PRU (0 or 1) a raw IRAM image was assembled for, from its words:
 * the PRU_NUM its start-up stores to BISS_ST_PRU, followed through the
 * straight-line code from address 0; -1 when the words do not tell (no
 * such store before a branch, or its value not an LDI's). */
int biss_image_pru(const void *image, size_t bytes);

/* ---- the slave's data word (biss_layout.c) ---- */

/* A BiSS slave's single-cycle data, MSB first on the wire: position, fill
 * bits, nE, nW, life counter, then the CRC. */
struct biss_proto_word {
    unsigned pos_bits, fill_bits, lc_bits;
    bool has_err, has_warn;
};

/* The firmware's view of such a slave: data_bits, the nW bit (the
 * firmware knows nE and nW only as a pair), CRC width from the polynomial
 * written with its top term (0 for none). */
void biss_proto_slave_layout(const struct biss_proto_word *w, uint32_t crc_poly, uint32_t crc_start,
                             struct biss_slave_config *o);
/* The data word for those fields (nE/nW: 1 = no error / no warning, as on
 * the line). */
uint64_t biss_proto_word_compose(const struct biss_proto_word *w, uint64_t position, int nE, int nW,
                                 uint32_t lc);
/* And back: position (fill dropped), nE, nW (1 when the slave has none). */
void biss_proto_word_split(const struct biss_proto_word *w, uint64_t word, uint64_t *position,
                           int *nE, int *nW);
/* Width of the position field of a configured slave (its pos_bits, or
 * everything above nE/nW, or the whole word without them). */
unsigned biss_proto_pos_bits(const struct biss_slave_config *c);
/* Gray code to binary (SSI encoders). */
uint64_t biss_proto_from_gray(uint64_t g);
/* Degree of a CRC polynomial written with its top term (0x43 -> 6), 0 for 0. */
unsigned biss_proto_crc_bits(uint32_t poly);

/* ---- what the firmware can write (biss_result_check.c) ---- */

/* A published result the firmware cannot have written, named (NULL: it
 * can have): flags, half period, slave count, line delay, sample point,
 * lag, CDS/CDM, processing time, each slave's status and data (the
 * configuration's layout when configured). */
const char *biss_result_problem(const struct biss_config *c, bool configured,
                                const struct biss_shm_result *r);
/* Whether result flags are a frame's that ran to its end (VALID or
 * ACK_JUMP, with CRC_ERROR, SMA). */
bool biss_result_ran_to_end(uint32_t flags);
/* Status words a running firmware (magic) cannot have written, named, or
 * NULL; st_pru is BISS_ST_PRU. */
const char *biss_status_problem(const struct biss_shm_status *st, uint32_t st_pru);

/* ---- samples and line delay (biss_sample_decode.c) ---- */

/* 0, or BISS_E_SHM_RESULT for a result no firmware with this
 * configuration publishes (biss_result_problem). configured false: no
 * layout, the whole words and no nE/nW claims. */
int biss_sample_decode(const struct biss_config *c, bool configured, uint32_t seq,
                       const struct biss_shm_result *r, struct biss_sample *s);
void biss_delay_decode(uint16_t raw, uint16_t avg, unsigned half, struct biss_line_delay *d);

/* ---- safety checks (biss_safety.c) ---- */

/* The host's clock at which a frame was read, microseconds (any monotonic
 * clock: only differences count), or this: not known. */
#define BISS_SAFETY_NO_CLOCK UINT64_MAX

/* A position the speed check compares with: its frame, IEP timestamp and
 * the host's clock when it was read. */
struct biss_pos_ref {
    bool set;
    uint32_t frame, ts;
    uint64_t pos;
    uint64_t read_us;
};

/* What the checks remember between frames: per slave the last life
 * counter trusted (CRC good) and its frame number, the last position
 * accepted and the last one refused since; the last frame judged
 * (read again, it keeps its verdict and is not counted twice); the counts. */
struct biss_safety_state {
    bool ref[BISS_API_MAX_SLAVES];
    uint32_t ref_frame[BISS_API_MAX_SLAVES], ref_lc[BISS_API_MAX_SLAVES];
    struct biss_pos_ref pos[BISS_API_MAX_SLAVES], refused[BISS_API_MAX_SLAVES];
    bool seen;
    uint32_t last_frame;
    uint32_t last_flags[BISS_API_MAX_SLAVES];
    bool last_misframed;
    struct biss_safety_stats stats;
};

/* Counts that take each frame once, in frame order, whichever reader
 * brings it (the ring reader and the newest-sample read on one handle):
 * the newest frame counted so far. */
struct biss_frame_order {
    bool seen;
    uint32_t last;
};
/* True, and frame the newest, when frame is newer than every one before
 * (or the first; frame numbers wrap, so "newer" is a signed distance);
 * false for a frame read again or older. */
static inline bool biss_frame_order_next(struct biss_frame_order *o, uint32_t frame) {
    if (o->seen && (int32_t)(frame - o->last) <= 0) {
        return false;
    }
    o->seen = true;
    o->last = frame;
    return true;
}

/* Link quality (biss_link.c): the warning's block and count, the block in
 * progress, the frames judged, the counts. */
struct biss_link_state {
    uint32_t window, warn;
    uint32_t block_frames, block_marginal;
    bool warning;
    struct biss_frame_order order;
    struct biss_link_stats stats;
};
/* Command-line spelling "K[,N]": the warning after K marginal frames in a
 * block of N (default BISS_LINK_WINDOW), both 1..2^32-1: 0 or BISS_E_INVAL. */
int biss_link_parse(const char *arg, uint32_t *warn, uint32_t *window);
/* Counts cleared; the warning after `warn` marginal frames in a block of
 * `window` (0: BISS_LINK_WARN, BISS_LINK_WINDOW). */
void biss_link_init(struct biss_link_state *st, uint32_t window, uint32_t warn);
/* The warning's count and block (0: the default) from here on, a new
 * block begun; the counts kept. */
void biss_link_set_warning(struct biss_link_state *st, uint32_t window, uint32_t warn);
/* The mean eye of the frames counted (BISS_LINK_EYE_MAX before any). */
double biss_link_eye_mean(const struct biss_link_stats *k);
/* A decoded sample's eye opening, eighths of a bit; -1 when its ACK was
 * not measured (no slave, aborted, training). */
int biss_link_eye(const struct biss_sample *s);
/* Judges a decoded sample: sets s->link_eye and s->link_warning, counts
 * (a frame read again, or one older than the last judged, gets the
 * warning as it stands and is not counted). */
void biss_link_check(struct biss_link_state *st, struct biss_sample *s);

/* The safety fields of a configuration against its layout: 0,
 * BISS_E_SAFETY_LIFE, BISS_E_SAFETY_PAIR, BISS_E_SAFETY_CRC or
 * BISS_E_SAFETY_EW or BISS_E_SAFETY_SPEED. */
int biss_safety_config_check(const struct biss_config *c);
/* Width of a slave's life counter: life_bits, else ew_shift (0 without nE/nW). */
unsigned biss_safety_life_width(const struct biss_slave_config *s);
/* Everything forgotten, counts cleared. */
void biss_safety_init(struct biss_safety_state *st);
/* A new configuration: the references forgotten, the counts kept. */
void biss_safety_restart(struct biss_safety_state *st);
/* Judges a decoded sample: sets s->slave[i].safety and s->safety, counts.
 * Frames need not be consecutive (the frame numbers say how many ran); a
 * no-slave or aborted frame forgets the life counters (the slave may not
 * have counted it). An ew_static slave's CRC-good word with nE or nW
 * active, or a max_speed slave's CRC-good position further from the last
 * one accepted than it can move in the time between, makes the frame misframed:
 * s->misframed set, s->valid cleared, and no life or pair check on it (nor
 * does its position become the reference). */
void biss_safety_check(const struct biss_config *c, struct biss_safety_state *st,
                       struct biss_sample *s);
/* The same for a frame read at the host's clock read_us (microseconds;
 * BISS_SAFETY_NO_CLOCK: not known, which biss_safety_check passes): a
 * max_speed position whose time since the reference is not known (the
 * count between them half its range or more, or the two frames read half
 * that range apart or more: biss_safety.c) is not judged, neither passed
 * nor refused: BISS_SAFE_POS_UNTIMED, counted in pos_untimed, and it
 * becomes the reference when the frame is accepted. */
void biss_safety_check_read(const struct biss_config *c, struct biss_safety_state *st,
                            struct biss_sample *s, uint64_t read_us);
/* One handle's frames taken by two readers: the newest sample now and
 * then (BISS_READER_NEWEST) and the ring, every frame in order
 * (BISS_READER_RING). Each reader's frames are judged against its own
 * references, in its own frame order (a ring frame older than the newest
 * one read is no step back in time); the counts are the handle's, each
 * frame counted once: the first time a frame newer than every one counted
 * is judged (as biss_link_check counts). */
enum { BISS_READER_NEWEST, BISS_READER_RING, BISS_READERS };
struct biss_safety_readers {
    struct biss_safety_state reader[BISS_READERS];
    struct biss_safety_stats stats;
    struct biss_frame_order order; /* the frames counted */
};
/* biss_safety_check_read by `reader`'s state; its counts added to
 * r->stats when s->frame is newer than every frame counted. */
void biss_safety_readers_check(const struct biss_config *c, struct biss_safety_readers *r,
                               unsigned reader, struct biss_sample *s, uint64_t read_us);
/* A new configuration: both readers' references forgotten, the counts kept. */
void biss_safety_readers_restart(struct biss_safety_readers *r);
/* Command-line spellings: "S[,BITS]" (life counter of slave S, width
 * BITS, default its ew_shift) and "A,B,TOL[,SHIFT_A,SHIFT_B]" (a pair,
 * distinct_crc set) into c: 0, BISS_E_INVAL (not that form) or
 * BISS_E_SAFETY_PAIR (too many pairs). */
int biss_safety_parse_life(const char *arg, struct biss_config *c);
int biss_safety_parse_pair(const char *arg, struct biss_config *c);
/* "S": slave S never sets nE/nW (ew_static): 0 or BISS_E_INVAL. */
int biss_safety_parse_ew(const char *arg, struct biss_config *c);
/* "S,CPS": slave S's position moves at most CPS counts per second (a
 * number above 0; max_speed): 0 or BISS_E_INVAL. */
int biss_safety_parse_speed(const char *arg, struct biss_config *c);
/* The checks of `checks` added to dst (a layout from elsewhere): 0 or
 * BISS_E_SAFETY_PAIR (too many pairs). */
int biss_safety_merge(struct biss_config *dst, const struct biss_config *checks);

/* ---- transfers through data RAM (biss_proto_io.c) ---- */

/* Reads and writes n bytes at a data-RAM offset (0 or a negative code);
 * word-aligned transfers of whole words. */
struct biss_proto_io {
    int (*read)(void *ctx, uint32_t off, void *buf, size_t n);
    int (*write)(void *ctx, uint32_t off, const void *buf, size_t n);
    void *ctx;
};

/* The block (all but its seq), then CFG_SEQ = seq. */
int biss_proto_config_put(const struct biss_proto_io *io, const struct biss_shm_config *blk,
                          uint32_t seq);
/* The configuration block as it is in data RAM. */
int biss_proto_config_get(const struct biss_proto_io *io, struct biss_shm_config *blk);
/* The firmware's status words. */
int biss_proto_status_get(const struct biss_proto_io *io, struct biss_shm_status *st);
/* The identification block. */
int biss_proto_id_get(const struct biss_proto_io *io, struct biss_shm_id *id);
/* The block and the remoteproc resource table after it (16 bytes), as the
 * kernel's loader puts them from the ELF. */
int biss_proto_id_put(const struct biss_proto_io *io, const struct biss_shm_id *id,
                      const uint8_t rsc[16]);
/* ST_PRU: the PRU (0 or 1) the running image was assembled for. */
int biss_proto_fw_pru_get(const struct biss_proto_io *io, uint32_t *pru);
/* ST_OFF_GRID: the frames refused for an SL edge off the bit grid. */
int biss_proto_off_grid_get(const struct biss_proto_io *io, uint32_t *frames);
/* CFG_IEP_PERIOD alone: the block's IEP period, in counts of 5 ns. */
int biss_proto_iep_period_get(const struct biss_proto_io *io, uint32_t *counts);
/* CMD_TRIGGER: read (nonzero while a frame is pending) and set. */
int biss_proto_trigger_get(const struct biss_proto_io *io, uint32_t *pending);
int biss_proto_trigger(const struct biss_proto_io *io);
/* The publication counter alone. */
int biss_proto_pub_seq(const struct biss_proto_io *io, uint32_t *seq);
/* The publication counter, and whether the firmware published anything
 * since it started: the counter wraps from 2^32 - 1 to 0 (the frame
 * published then is frame 0), so 0 alone does not say "nothing"; ST_BUF
 * does (the start-up clears it, the first publication names its slot there
 * before it bumps ST_SEQ). Reads ST_BUF only when ST_SEQ is 0. */
int biss_proto_pub_seq_any(const struct biss_proto_io *io, uint32_t *seq, bool *any);
/* The result slot ST_BUF names, its header and nslaves slave results
 * (the rest zeroed): 0, or BISS_E_SHM_RESULT for an offset that is no
 * slot of the ring. */
int biss_proto_result_get(const struct biss_proto_io *io, unsigned nslaves,
                          struct biss_shm_result *r);
/* Whether slot (a data-RAM offset) starts a slot of the ring laid out for
 * nslaves (1..8; 0: for some slave count, not known): 0, or
 * BISS_E_SHM_RESULT. */
int biss_proto_slot_check(uint32_t slot, unsigned nslaves);

/* The publication number of the slot ST_BUF named after ST_SEQ read st_seq:
 * the slot's own (R_FRAME, slot_frame) when it is one ahead, published with
 * ST_SEQ not yet bumped (whole: every store to it precedes ST_BUF's; the
 * emulator's PRU may stand still there while the host reads), else st_seq.
 * A slot whose frame is neither is a publication further on. */
static inline uint32_t biss_proto_slot_seq(uint32_t st_seq, uint32_t slot_frame) {
    return slot_frame == st_seq + 1 ? slot_frame : st_seq;
}

/* ---- every frame: the result ring (biss_ring.c) ---- */

/* Reads the publications after *cursor (ST_SEQ numbers; 0: from the
 * first; however far behind, modulo 2^32), oldest first, at most max of
 * them, into out (each a slot as the firmware wrote it: out[i].frame is
 * its publication number), *n of them; *cursor moves past those returned
 * and those lost. *lost (set, not added to) counts the publications after
 * *cursor the ring no longer held whole: overwritten before this call, or
 * while it copied them (ST_SEQ read after the copy, biss_shm.h), or not of
 * the ring's layout now (a configuration since restarted it). Returns 0 (also with *n = 0: nothing
 * new, or nothing published yet), BISS_E_RETRY (the newest slot never
 * settled: racing publications 1000 times), BISS_E_SHM_RESULT (ST_BUF or
 * the newest slot's slave count is nothing the firmware writes) or the
 * transfer's error. */
int biss_proto_ring_read(const struct biss_proto_io *io, uint32_t *cursor,
                         struct biss_shm_result *out, unsigned max, unsigned *n, uint32_t *lost);
/* A ring reader's look at the firmware between its reads: the publication
 * counter and the configuration in force (ST_SEQ, ST_CFG_ACK). */
struct biss_ring_look {
    uint32_t seq, cfg_ack;
};
int biss_proto_ring_look(const struct biss_proto_io *io, struct biss_ring_look *look);
/* Whether the publication counter went back between two looks (the
 * firmware restarted) rather than moved on by now->seq - then->seq
 * (modulo 2^32, however far): it reads as behind (2^31 or more on) and a
 * configuration was acknowledged in between (ST_CFG_ACK changed: a
 * restarted firmware publishes nothing before one, and its start-up sets
 * ST_CFG_ACK to 0xffffffff; libbiss numbers a restart's configuration on
 * from the last one). What this cannot tell: a restart whose configuration
 * took the number of the one before, not looked at in between (the
 * firmware restarted by something else and configured by a handle new to
 * it), which reads as far behind; and a reader 2^31 or more behind across
 * another handle's configuration, which reads as a restart. */
bool biss_proto_ring_restarted(const struct biss_ring_look *then, const struct biss_ring_look *now);
/* A control program: BISS_E_CD_STEPS for a length outside
 * 1..BISS_CD_MAX_STEPS, BISS_E_CD_BUSY while the last one runs, else puts
 * PROG, STEPS, WAIT_LIMIT and the IDA test, then CD_CMD = *cmd (the next
 * command number, never 0: the firmware's "none"). */
int biss_proto_cd_put(const struct biss_proto_io *io, const biss_cd_prog *p, unsigned wait_limit,
                      uint32_t *cmd);
/* The program's words alone (PROG, STEPS and WAIT_LIMIT, the IDA test),
 * CD_CMD left alone. */
int biss_proto_cd_load(const struct biss_proto_io *io, const biss_cd_prog *p, unsigned wait_limit);
/* The firmware's answer words (ST_CD_*, the answers), whatever their seq. */
int biss_proto_cd_answer(const struct biss_proto_io *io, biss_cd_answer *a);
/* Whether the firmware has ended command cmd (1, 0 not yet, or an error);
 * with 1 the answer is read into *a. */
int biss_proto_cd_ended(const struct biss_proto_io *io, uint32_t cmd, biss_cd_answer *a);
/* Whether a program was put that the firmware has not ended (CD_CMD past
 * ST_CD_SEQ: waiting for its zeros, or running): 1 with its number in
 * *cmd, 0 none, or the transfer's error. */
int biss_proto_cd_running(const struct biss_proto_io *io, uint32_t *cmd);

/* ---- the encoder firmware (biss_encoder.c; include/biss/biss_slave_shm.h) ---- */

/* A checked configuration (biss_encoder_config_check) into the firmware's
 * block (out->seq left 0), the live nE/nW bits included. */
void biss_encoder_encode(const struct biss_encoder_config *c, struct biss_slv_config *out);
/* A slave's live nE/nW bits (BISS_SLV_EW_*). */
uint8_t biss_encoder_ew_bits(const struct biss_encoder_slave *s);
/* ST_CFG_ERROR as a return value: 0, or BISS_E_ENC_REFUSED. */
int biss_encoder_fw_error(uint32_t cfgerr);
/* "BISS_SLV_CFGERR_TABLE: ..." for a code the firmware reports. */
const char *biss_encoder_cfg_error_text(uint32_t code);
/* The block (all but its seq), then CFG_SEQ = seq. */
int biss_proto_encoder_put(const struct biss_proto_io *io, const struct biss_slv_config *blk,
                           uint32_t seq);
int biss_proto_encoder_seq_get(const struct biss_proto_io *io, uint32_t *seq);
/* LIVE_EW: every slave's nE/nW bits, taken from the next frame on. */
int biss_proto_encoder_ew_put(const struct biss_proto_io *io,
                              const uint8_t live[BISS_SLV_MAX_SLAVES]);
/* The status block; the next frame's record. */
int biss_proto_encoder_status(const struct biss_proto_io *io, struct biss_slv_status *st);
int biss_proto_encoder_rec(const struct biss_proto_io *io, struct biss_slv_frame_rec *rec);
/* A slave's register file (0x40..0x7F, the read-only and write-protected
 * bits); a bank of the pool (0x00..0x3F of the slave whose bank it is);
 * n positions into the table from entry start. BISS_E_INVAL out of range. */
int biss_proto_encoder_regs_put(const struct biss_proto_io *io, unsigned slave,
                                const struct biss_slv_regs *r);
int biss_proto_encoder_regs_get(const struct biss_proto_io *io, unsigned slave,
                                struct biss_slv_regs *r);
int biss_proto_encoder_bank_put(const struct biss_proto_io *io, unsigned bank,
                                const uint8_t bytes[BISS_SLV_BANK_SIZE]);
int biss_proto_encoder_bank_get(const struct biss_proto_io *io, unsigned bank,
                                uint8_t bytes[BISS_SLV_BANK_SIZE]);
int biss_proto_encoder_table_put(const struct biss_proto_io *io, unsigned start,
                                 const uint64_t *pos, unsigned n);

/* The low `bits` bits set (all 64 for bits >= 64). */
static inline uint64_t biss_low_mask(unsigned bits) {
    return bits >= 64 ? ~0ull : (1ull << bits) - 1u;
}

#pragma GCC visibility pop

#endif
