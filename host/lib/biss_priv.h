/*
 * biss_priv.h - libbiss internals: the backend boundary and the handle.
 *
 * A backend only moves bytes at offsets from the PRU-ICSS base and lets
 * time pass; loading IRAM, starting and stopping the PRU and the whole
 * shared-memory protocol are written once on top of it (PRU registers are
 * reached the same way on silicon and in the emulator).
 */
#ifndef BISS_PRIV_H
#define BISS_PRIV_H

#include "libbiss.h"

#include "biss_cd.h"
#include "biss_proto.h"
#include "biss_soc.h"

#include <pthread.h>
#include <stddef.h>
#include <stdint.h>

struct biss_backend_ops {
    /* n bytes at offset off from the PRU-ICSS base; 0 or BISS_E_*. Word
     * aligned transfers are done as 32-bit accesses. */
    int (*read)(void *ctx, uint32_t off, void *buf, size_t n);
    int (*write)(void *ctx, uint32_t off, const void *buf, size_t n);
    /* Lets about us microseconds pass (emulator: runs the bench). 0 or
     * BISS_E_PRU_FAULT. */
    int (*advance)(void *ctx, unsigned us);
    /* The backend's clock in microseconds (simulated time for the emulator). */
    uint64_t (*now_us)(void *ctx);
    void (*close)(void *ctx);
    /* Optional. exclusive: this handle may now change the firmware's state
     * (configure, start, stop); 0 or BISS_E_BUSY. pru_halt/pru_start/
     * pru_enabled: a loader that owns the PRU (remoteproc) stops, loads and
     * starts it, and says whether it runs; NULL: the CONTROL register and
     * IRAM through read/write. */
    int (*exclusive)(void *ctx);
    /* Optional. The PRU-ICSS's one IEP: taken (waiting up to timeout_ms;
     * 0 or BISS_E_BUSY) around the exchange that decides which channel owns
     * it, so that two channels never both do; released with take false. */
    int (*iep_lock)(void *ctx, bool take, unsigned timeout_ms);
    int (*pru_halt)(void *ctx);
    int (*pru_start)(void *ctx);
    int (*pru_enabled)(void *ctx, bool *on);
    /* Optional: close leaves what this handle started running. */
    void (*leave_running)(void *ctx);
    /* How long one advance() step of a wait is, microseconds. */
    unsigned poll_us;
    /* advance() only sleeps: the handle is unlocked around it so other
     * threads get in while one waits. */
    int advance_sleeps;
};

struct biss_backend {
    const struct biss_backend_ops *ops;
    void *ctx;
    uint32_t iram_bytes;
    unsigned pru;        /* the PRU driven: its data RAM, CONTROL and IRAM */
    struct bench *bench; /* emulator only */
};

struct biss {
    /* lock guards the handle and the backend. op_lock serialises the long
     * exchanges (configure, control communication, restart) whose waits
     * may drop lock while sleeping; take op_lock first. */
    pthread_mutex_t lock;
    pthread_mutex_t op_lock;
    enum biss_target target;
    struct biss_backend be;
    unsigned timeout_ms;
    char firmware[512];
    /* why the running image was not compared with an image file, or "" */
    char unchecked[640];
    uint8_t *image; /* kept for biss_start's restart */
    size_t image_bytes;
    bool configured;
    struct biss_config cfg;
    uint32_t cfg_seq;
    /* ST_SEQ when this handle's configuration was acknowledged: results
     * published up to then were made with the previous one (its slave
     * layout), so they are no sample of this configuration. */
    uint32_t cfg_pub_seq;
    bool cfg_pub_seq_valid;
    /* a newest-sample read saw a later publication: from then on every
     * one is this configuration's (ST_SEQ moves on from cfg_pub_seq; how
     * far tells nothing, the counter wraps: 2^31 frames are 12 h at 50 kHz) */
    bool cfg_pub_passed;
    bool attached;
    /* biss_ring_read: the last publication returned or counted lost, and
     * the frames of an earlier layout a configuration skipped (lost) */
    uint32_t ring_cursor;
    uint32_t ring_skipped;
    bool ring_started;
    /* the ring reader's last look at the counter and the configuration
     * (biss_ring_follow) */
    struct biss_ring_look ring_seen;
    bool ring_seen_valid;
    /* the control program an SSI configuration cut (still running when it
     * was written: SSI frames carry no CDM or CDS to go on with), whose
     * verdict is BISS_E_SSI_NO_CONTROL whatever the firmware ends it with */
    uint32_t cd_cut;
    bool cd_cut_set;
    /* what the last BISS_E_SHM_RESULT refusal found in data RAM (a static
     * text of biss_result_check.c), or NULL */
    const char *problem;
    /* the safety checks over the frames this handle read, by the newest
     * sample's reads and the ring's, each in its own order (biss_safety.c) */
    struct biss_safety_readers safety;
    /* the link's eye and warning over the frames this handle read (biss_link.c) */
    struct biss_link_state link;
    /* following another channel's IEP with a speed check: the owner's
     * period changed (biss_follow_period_locked), so the frames published
     * before follow_from may lie across the change: no time between them
     * is known, and their positions are not judged by max_speed */
    bool follow_hold;
    uint32_t follow_from;
};

/* Asks the backend for the right to change the firmware's state. */
int biss_exclusive(biss_t *h);

/* A handle around a ready backend (takes it over, closing it on error);
 * no firmware is loaded. biss_open uses it; tests use it with fakes. */
int biss_handle_new(enum biss_target t, const struct biss_backend *be, unsigned timeout_ms,
                    biss_t **out);

/* A backend's opener: fills be, or returns BISS_E_*. The backends live
 * above this library's core (host/backend/): the Linux one in libbiss
 * (backend_linux.c, which also gives biss_open), the emulator's in
 * libbiss-emu (backend_emu.c). Each hands its openers to biss_open_with. */
typedef int (*biss_backend_open_fn)(const struct biss_open_params *p, struct biss_backend *be);
struct biss_backends {
    biss_backend_open_fn linux_open; /* the am335x and am437x targets */
    biss_backend_open_fn emu;        /* target "emu" */
};
/* biss_open on the backends b offers (a NULL opener: its targets refused,
 * with a message that says where they are). */
int biss_open_with(const struct biss_open_params *p, const struct biss_backends *b, biss_t **out);
/* biss_encoder_open on the Linux backend's opener (NULL: every target
 * refused); the emulator target is refused whatever the opener. */
int biss_encoder_open_with(const struct biss_open_params *p, biss_backend_open_fn linux_open,
                           biss_encoder_t **out);

/* Register helpers over the backend (data RAM offsets are BISS_* values). */
int biss_dram_read(biss_t *h, uint32_t off, void *buf, size_t n);
int biss_dram_write(biss_t *h, uint32_t off, const void *buf, size_t n);
int biss_dram_read32(biss_t *h, uint32_t off, uint32_t *v);
int biss_dram_write32(biss_t *h, uint32_t off, uint32_t v);
/* The same as the protocol layer's reader/writer (proto/biss_proto.h). */
struct biss_proto_io biss_io(biss_t *h);

/* PRU control and image loading (biss_pru.c). */
int biss_pru_halt(biss_t *h);
int biss_pru_load_and_start(biss_t *h);
int biss_pru_enabled(biss_t *h, bool *on);
/* Writes the identification block of the handle's image (devmem loader). */
int biss_pru_write_id(biss_t *h);
/* BISS_E_FW_PRU (with a message in e, which may be NULL) when the running
 * firmware says it was assembled for the other PRU; BISS_OK when it was
 * for this one or no firmware runs (no magic). */
struct biss_errbuf;
int biss_pru_image_check(biss_t *h, struct biss_errbuf *e);
/* What every open checks first (biss_open.c): p given, its errbuf cleared
 * and taken into e, pru 0 or 1. */
int biss_open_params_check(const struct biss_open_params *p, struct biss_errbuf *e);
/* An IRAM image from path into h, checked (biss_open.c); master: also
 * assembled for h's PRU. */
int biss_read_image(biss_t *h, const char *path, bool master, struct biss_errbuf *e);

/* Following another channel's IEP with a speed check (handle locked): the
 * owning channel's period as it now runs (its block accepted), taken into
 * the configuration when it changed (biss_configure.c). */
int biss_follow_period_locked(biss_t *h);

/* A published result as a sample (seq its publication number): refused
 * as BISS_E_SHM_RESULT, named in h->problem, where the firmware never
 * writes such words; the host's safety checks run on it as `reader`
 * (BISS_READER_NEWEST or BISS_READER_RING) read it at the backend's clock
 * read_us (biss_read_clock, taken after the result was read). Handle
 * locked. */
int biss_result_to_sample(biss_t *h, const struct biss_shm_result *r, uint32_t seq, unsigned reader,
                          uint64_t read_us, struct biss_sample *s);
/* The ring reader's look at the firmware (handle locked; nothing before
 * the reader's first call): when the publication counter went back since
 * the last look, the firmware restarted (biss_proto_ring_restarted) and
 * the reader starts again from its first publication (the old run's frames
 * after the cursor cannot be known, and are not counted). own: the look
 * just after this handle's configuration, whose ack is no restart. */
int biss_ring_follow(biss_t *h, bool own);
/* This handle restarts the firmware (halted, its data RAM about to be
 * cleared): the old run's frames the ring reader did not take are lost,
 * counted, and it reads the new run from its first publication. */
int biss_ring_restart(biss_t *h);

/* Whether any slave of c has a speed check (max_speed), and c without
 * them (every max_speed 0). */
bool biss_speed_checked(const struct biss_config *c);
void biss_speed_unchecked(struct biss_config *c);

/* The backend's clock for the speed check's time between two reads
 * (proto/biss_safety.c), or BISS_SAFETY_NO_CLOCK when no speed check is
 * configured (the clock is not read). */
uint64_t biss_read_clock(biss_t *h);

/* Waits (handle locked) until done(h, arg) returns nonzero or timeout_ms
 * of backend time passed; returns 0, BISS_E_TIMEOUT, or done's error if
 * it returned a negative value. */
int biss_wait_for(biss_t *h, unsigned timeout_ms, int (*done)(biss_t *h, void *arg), void *arg);
/* The same with the timeout in microseconds. */
int biss_wait_for_us(biss_t *h, uint64_t timeout_us, int (*done)(biss_t *h, void *arg), void *arg);

/* Both locks, in order, for a long exchange with the firmware. */
void biss_op_begin(biss_t *h);
void biss_op_end(biss_t *h);

/* Re-sends the handle's configuration after a restart (handle locked). */
int biss_reconfigure_locked(biss_t *h);

/* Control communication transport (biss_control.c): puts the program in
 * data RAM, starts it, waits (triggering frames in host-trigger mode) and
 * reads the firmware's answer back. The codec (biss_cd.h) builds programs
 * and parses answers. A built frame after a program that stopped inside
 * its control frame gets CDM 0 steps first (biss_cd_lead_in): *p moves. */
int biss_cd_exchange(biss_t *h, biss_cd_prog *p, unsigned wait_limit, unsigned timeout_ms,
                     biss_cd_answer *a);
/* The same in two halves, for the non-blocking forms: begin puts the
 * program and returns its command number; check returns BISS_E_CD_BUSY
 * until the firmware has ended it (asking for frames in host-trigger mode),
 * then reads the answer. */
int biss_cd_begin(biss_t *h, biss_cd_prog *p, unsigned wait_limit, uint32_t *cmd);
int biss_cd_check(biss_t *h, uint32_t cmd, biss_cd_answer *a);
/* A codec verdict as a BISS_E_* code. */
int biss_cd_error(biss_cd_err e);

#endif
