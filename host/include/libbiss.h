/*
 * libbiss.h - the ARM-host API of the PRU BiSS-C master.
 *
 * One handle drives one PRU0 running biss_master.bin, either emulated in
 * process (target "emu": PRU core + cable + encoder models, opened with
 * biss_emu_open from libbiss-emu, <libbiss-emu.h>) or on an AM335x/AM437x
 * PRU-ICSS mapped through /dev/mem (or any file standing in for it). This
 * library (libbiss) holds the Linux backends only. The same protocol code serves both: the firmware
 * and the host meet in PRU0's data RAM (include/biss/biss_shm.h).
 *
 * The values it passes (the configuration, a sample, the error codes) are
 * the contract's, <biss/biss_types.h>, and so are the rules on them
 * (checking a configuration, the MA rate rule, what a line allows),
 * <biss/biss_rules.h>: this header includes both and adds the handle.
 *
 * Every function returns 0 (BISS_OK) or a negative BISS_E_* code;
 * biss_strerror() names it. Handles hold no global state; each call locks
 * its handle, so one handle may be shared between threads.
 *
 * Emulator time: simulated time advances only inside the blocking calls
 * (biss_open's start-up, biss_configure's wait for the firmware's ack,
 * biss_wait_sample, biss_run_ms); their timeouts count simulated ms.
 */
#ifndef LIBBISS_H
#define LIBBISS_H

#include "biss/biss_rules.h"
#include "biss/biss_types.h"

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Static text for any return value of this library (never NULL). */
const char *biss_strerror(int err);

/* ---- opening ----------------------------------------------------------- */
enum biss_target {
    BISS_TARGET_EMU,
    BISS_TARGET_AM335X,
    BISS_TARGET_AM437X_ICSS0,
    BISS_TARGET_AM437X_ICSS1,
};

/* "emu", "am335x", "am437x-icss0", "am437x-icss1" ("am437x" = ICSS0, the
 * PRU-ICSS TIDEP0022 uses; ICSS1 carries PRU Ethernet on TI's AM437x IDK). */
int biss_target_from_name(const char *name, enum biss_target *t);
const char *biss_target_name(enum biss_target t);

/* How a Linux target's firmware is loaded and started. */
enum biss_loader {
    BISS_LOADER_REMOTEPROC = 0, /* the kernel's remoteproc (pru_rproc): the default */
    BISS_LOADER_DEVMEM = 1,     /* IRAM and CONTROL written through /dev/mem */
};

/* "remoteproc", "devmem". */
int biss_loader_from_name(const char *name, enum biss_loader *l);

struct biss_open_params {
    enum biss_target target;
    enum biss_loader loader;
    /* Raw IRAM image. NULL: $BISS_FIRMWARE, else the build tree's image. */
    const char *firmware;
    /* Linux targets: file mapped at the SoC's PRU-ICSS base. NULL: /dev/mem. */
    const char *devmem;
    /* Linux targets: attach to a running firmware (no load, no restart);
     * the lock is shared with other readers until the handle changes the
     * firmware's state (configure, start, stop, control communication). */
    bool attach;
    /* Emulator: named profile (NULL: "tidep0022-test-encoder"), or a JSON
     * scenario file, which wins when both are given. */
    const char *profile;
    const char *scenario_file;
    double cable_m; /* < 0: the profile's/scenario's own length */
    bool set_seed;  /* use seed instead of the scenario's */
    uint64_t seed;
    unsigned timeout_ms; /* firmware answers (start-up, config ack); 0: 100 ms */
    /* Linux targets. sysfs_root: NULL "/sys" (remoteproc instances, the
     * pruss driver). firmware_dir: NULL "/lib/firmware". rproc_firmware:
     * the name written to the instance's firmware file (NULL: the name the
     * kernel's device tree gives that PRU, e.g. "am335x-pru0-fw").
     * lock_dir: not used (kept for compatibility): the per-PRU and IEP
     * locks are on the memory file itself, at the PRU's data RAM and the
     * IEP, so every process agrees on them whatever its environment. */
    const char *sysfs_root;
    const char *firmware_dir;
    const char *rproc_firmware;
    const char *lock_dir;
    /* If set, an open error's detail (path, errno, hint) lands here. */
    char *errbuf;
    size_t errbuf_len;
    /* Which PRU of the PRU-ICSS runs the firmware and drives this handle's
     * line: 0 (default) or 1. Each PRU has its own data RAM, so two handles
     * on PRU0 and PRU1 are two independent channels (two axes per PRU-ICSS);
     * on the emulator PRU0 stays idle when pru is 1. */
    unsigned pru;
};

void biss_open_params_default(struct biss_open_params *p);

typedef struct biss biss_t;

/* Builds the backend and starts the firmware: the emulator and the devmem
 * loader write the image into IRAM with the PRU halted, clear the shared
 * area and start the PRU; the remoteproc loader has the kernel load and
 * start the ELF and waits for the firmware's magic. With attach (Linux
 * targets) nothing is loaded: the running firmware's identification block
 * and configuration are checked and adopted. On error *out is NULL (and
 * params errbuf, if given, holds the detail). */
int biss_open(const struct biss_open_params *p, biss_t **out);
/* Releases the handle. A firmware this handle started through remoteproc
 * is stopped with it, unless biss_leave_running was called. */
void biss_close(biss_t *h);
/* The master this handle started keeps running after biss_close (and after
 * the process ends), for other handles and processes to attach to: what
 * `bissctl start` and the systemd unit do. The devmem loader never stops
 * the PRU on close; the emulated master lives in the handle and ends with
 * it whatever this says. 0, or BISS_E_INVAL for NULL. */
int biss_leave_running(biss_t *h);

enum biss_target biss_target(const biss_t *h);
/* The firmware image path this handle loaded or compared the running
 * image with ("" when none). */
const char *biss_firmware_path(const biss_t *h);
/* Linux targets: why the running image could not be compared with an image
 * file (the default one, BISS_FIRMWARE_DIR's biss_master.bin, absent or
 * unreadable: its path and the error), or "" when it was compared or
 * loaded. The handle works either way; the check is then the caller's. */
const char *biss_image_unchecked(const biss_t *h);
/* The handle attached to a running firmware (no load, no restart). */
bool biss_attached(const biss_t *h);

/* ---- configuration (struct biss_config: biss/biss_types.h) ---------------- */
/* "host", "iep", "iep-follow", "free" (or "freerun"). */
int biss_trigger_from_name(const char *name, enum biss_trigger *t);
const char *biss_trigger_name(enum biss_trigger t);

/* Validates, writes the block, bumps CFG_SEQ and waits for the firmware's
 * ack; the firmware's refusal comes back as BISS_E_FW_*. */
int biss_configure(biss_t *h, const struct biss_config *c);
/* The configuration in force (from this handle, or read back when attached). */
int biss_get_config(biss_t *h, struct biss_config *c);

/* ---- running ----------------------------------------------------------- */
/* Stop halts the PRU where it is. Start restarts the firmware from its
 * first instruction (counters cleared) and re-applies the configuration. */
int biss_start(biss_t *h);
int biss_stop(biss_t *h);
/* Host-trigger mode: asks for one frame (BISS_E_TRIGGER_PENDING, asking
 * for nothing, while the last one has not started its frame: the firmware
 * takes one request at a time). After each configuration (and after a
 * slave went missing) the firmware clocks one training frame of its
 * own, untriggered, to measure the line delay at the new rate: it is
 * published with `training` set and counts in biss_stats.training. */
int biss_trigger(biss_t *h);
/* Lets time pass: the emulator runs for ms simulated milliseconds, on
 * hardware the call sleeps. biss_run_us the same in microseconds (a reader
 * of every frame that must poll more often than once a millisecond). */
int biss_run_ms(biss_t *h, unsigned ms);
int biss_run_us(biss_t *h, unsigned us);

/* ---- samples (struct biss_sample: biss/biss_types.h) ---------------------- */
/* What the handle's last BISS_E_SHM_RESULT found in data RAM, by name
 * ("result flags: a combination the firmware never writes", "MA half
 * period: ...", "sample point: not 0..7", ...); "" when none. Checked:
 * every field of a published result and the status words, against what
 * the firmware writes (proto/biss_result_check.c). */
const char *biss_shm_problem(biss_t *h);

/* The latest published frame, consistent (ST_SEQ/ST_BUF protocol). */
int biss_read_sample(biss_t *h, struct biss_sample *s);
/* Blocks until a frame numbered after after_frame is published (at most
 * timeout_ms; BISS_E_TIMEOUT), and returns it. timeout_ms 0: one look. */
int biss_wait_sample(biss_t *h, uint32_t after_frame, unsigned timeout_ms, struct biss_sample *s);
/* The line delay of the latest frame that measured one. */
int biss_line_delay(biss_t *h, struct biss_line_delay *d);

/* ---- every frame: the result ring (biss/biss_shm.h) ---------------------- */
/* Every frame published since the last call, oldest first: at most max of
 * them into out, *n of them (0: nothing new). Each sample's seq is its
 * publication number (ST_SEQ), one more than the frame's before it unless
 * frames were lost between them. *lost counts the frames of this call's
 * span that the ring no longer held whole (the host polled too rarely:
 * overwritten before or while they were copied): never returned, never
 * silent. The first call starts at the handle's configuration (the frames
 * of the configuration before it are not of this layout) or, on a handle
 * that did not configure, at the newest frame; a later configuration
 * counts the earlier layout's frames not yet read as lost, and so does a
 * restart by this handle (biss_start), after which the reader takes the
 * new run from its first frame. However far behind (up to 2^32 - 1
 * frames), lost is the count modulo 2^32; a firmware restarted by another
 * handle shows as a counter that went back across a new configuration
 * (ST_CFG_ACK), and the reader starts at its first frame (host/README.md,
 * "Every frame"). Frames beyond
 * max wait for the next call (the ring keeps biss_ring_capacity of them).
 * Works the same on every target; on the emulator time moves only in the
 * blocking calls (biss_run_ms between reads: the host's poll period). */
int biss_ring_read(biss_t *h, struct biss_sample *out, unsigned max, unsigned *n, uint32_t *lost);
/* Frames the ring keeps for a reader at this handle's configuration (its
 * slots less the one being filled): a reader that falls further behind
 * loses frames. BISS_E_NOT_CONFIGURED without one. */
int biss_ring_capacity(biss_t *h, unsigned *frames);

/* ---- control communication (CDM/CDS, one bit per frame) ---------------- */
/* A raw program for the firmware: ops[i] is an op, 0 (send CDM 0), 1 (send
 * CDM 1), 2 (wait: CDM 0 until a frame's CDS is 1, then the next step in
 * that frame) or 3 (send the next bit of the firmware's CRC4 of the DATA
 * and ECHO bits sent, inverted), or'ed with a class: DATA (the bit into
 * that CRC, its answer into a second one), CHECK (the answer must be the
 * next bit of the second CRC, inverted), ECHO (as DATA, and the answer must
 * equal the bit sent); at most 1024 steps (include/biss/biss_shm.h has the
 * details). resp (at least (n + 7) / 8 bytes) gets bit i (byte i / 8, bit
 * i % 8) = the CDS that answered step i. A WAIT gives up after wait_limit
 * frames with CDS 0 (0: at once; at most 65535); a WAIT has no class and is
 * not followed by a WAIT or a CRC bit. The firmware first sends 14 frames
 * with CDM 0. In host-trigger mode the call triggers the frames it needs.
 * Blocks at most timeout_ms (emulator: simulated). */
#define BISS_CD_OP_0     0
#define BISS_CD_OP_1     1
#define BISS_CD_OP_WAIT  2
#define BISS_CD_OP_CRC   3
#define BISS_CD_CL_DATA  4
#define BISS_CD_CL_CHECK 8
#define BISS_CD_CL_ECHO  12
int biss_cd_run(biss_t *h, const uint8_t *ops, unsigned n, unsigned wait_limit, unsigned timeout_ms,
                uint8_t *resp);

/* Register access of the slave with control-frame ID id (0..7), addresses
 * 0x00..0x7F; n > 1 is a sequential access of n consecutive addresses (at
 * most 64; the address wraps after 0x7F as the slave's does). Each byte's
 * answer is checked (echo, CRC4); the codec is proto/biss_cd.h. A slave
 * does not tell a refused write (read-only register): read it back. */
#define BISS_REG_MAX_SEQ 64
int biss_reg_read(biss_t *h, unsigned id, uint8_t addr, uint8_t *buf, unsigned n);
int biss_reg_write(biss_t *h, unsigned id, uint8_t addr, const uint8_t *buf, unsigned n);
/* BiSS command cmd (0..3) to the slaves in ids (bit i = ID i; 0 = all,
 * a broadcast without acknowledge). *ida, if set, gets the IDA answers
 * (bit i = ID i). They must equal ids: with check_ida the firmware tests
 * them before the command's stop bit and withholds the command if they
 * differ (BISS_E_CD_WITHHELD, as iC-MB4's IDA_TEST); without it the
 * command executes and the mismatch is reported after (BISS_E_CD_IDA). */
int biss_command(biss_t *h, uint8_t ids, unsigned cmd, bool check_ida, uint8_t *ida);
/* The calls above block for at most the handle's timeout (open params
 * timeout_ms). The same accesses without blocking: *_start puts the
 * program into data RAM and returns at once with a job (NULL on error);
 * biss_cd_poll returns BISS_E_CD_BUSY while the firmware runs it, then the
 * verdict the blocking form would give (and keeps giving it). On the
 * emulator time passes only inside blocking calls: poll between
 * biss_run_ms or biss_wait_sample calls. One program runs at a time: a
 * start while one runs returns BISS_E_CD_BUSY. Freeing a running job does
 * not stop the firmware's program. */
typedef struct biss_cd_job biss_cd_job;
int biss_reg_read_start(biss_t *h, unsigned id, uint8_t addr, unsigned n, biss_cd_job **job);
int biss_reg_write_start(biss_t *h, unsigned id, uint8_t addr, const uint8_t *buf, unsigned n,
                         biss_cd_job **job);
int biss_command_start(biss_t *h, uint8_t ids, unsigned cmd, bool check_ida, biss_cd_job **job);
int biss_cd_poll(biss_t *h, biss_cd_job *job);
/* After a successful poll: the n bytes a register read got, the IDA answers. */
int biss_cd_job_bytes(const biss_cd_job *job, uint8_t *buf);
int biss_cd_job_ida(const biss_cd_job *job, uint8_t *ida);
/* After a poll that finished (any verdict): the ID fields a control frame
 * answered, as read and as they came (host/CD.md, "IDL" and "IDA": the
 * sources disagree on the slots). idl: a register access's ID lock IDL0..7
 * (bit i = ID i); header_cds: its answers to S and the 8 steps after it
 * that were 1 (bit 0 = S; IDL0 is read at S, the other reading has it at
 * CTS, bit 1). ida: a command's IDA answers (bit i = ID i); ida_cds: its
 * answers to the last header CRC step and the 8 IDA steps that were 1
 * (bit 0 = the CRC step, where IDA0 is read). */
struct biss_cd_slots {
    uint8_t idl, ida;
    uint16_t header_cds, ida_cds;
};
int biss_cd_job_slots(const biss_cd_job *job, struct biss_cd_slots *out);
void biss_cd_job_free(biss_cd_job *job);

/* ---- status and statistics --------------------------------------------- */
enum biss_fw_state {
    BISS_FW_STOPPED = 0,
    BISS_FW_RUNNING = 1,
    BISS_FW_CFG_ERROR = 2,
    BISS_FW_NO_SLAVE = 3,
};
const char *biss_fw_state_name(uint32_t state);

struct biss_status {
    bool firmware_running; /* magic present */
    bool pru_enabled;      /* CONTROL.ENABLE */
    uint32_t state;        /* BISS_STATE_* */
    uint32_t cfg_seq;      /* written by the host */
    uint32_t cfg_ack;      /* echoed by the firmware (0xffffffff: none yet) */
    uint32_t cfg_error;    /* BISS_CFGERR_* */
    uint32_t seq;          /* publications */
    uint32_t shm_version;  /* from the image identification block (0: none) */
    uint32_t image_crc;    /* CRC-32 of the IRAM image it names */
};

struct biss_stats {
    uint32_t frames, crc_errors, no_slave, proc_errors, training;
    uint32_t off_grid; /* frames refused for an SL edge off the bit grid (BISS_ST_OFF_GRID) */
};

int biss_get_status(biss_t *h, struct biss_status *st);
int biss_get_stats(biss_t *h, struct biss_stats *st);
/* The safety checks run on every sample read: the newest-sample reads
 * (biss_read_sample, biss_wait_sample) and the ring's (biss_ring_read)
 * each judged in their own frame order, so a ring frame read after a newer
 * sample is judged against the ring's frame before it; the counts
 * (biss_types.h) take each frame once. */
int biss_get_safety_stats(biss_t *h, struct biss_safety_stats *st);
/* Link quality over the frames this handle read (each frame's eye opening:
 * biss_sample.link_eye; proto/biss_link.c): the counts by eye, the
 * marginal and off-grid frames, the warnings. Each frame counts once, in
 * frame order: one older than a frame already read (the ring reader after
 * biss_read_sample on one handle) keeps its eye but is not counted. */
int biss_get_link_stats(biss_t *h, struct biss_link_stats *st);
/* The warning (biss_sample.link_warning): set once `warn` marginal frames
 * (eye <= BISS_LINK_EYE_MARGINAL) fall in one block of `window` frames
 * read, held while the last whole block had as many (defaults
 * BISS_LINK_WARN, BISS_LINK_WINDOW); both >= 1, else BISS_E_INVAL. Starts
 * a new block. */
int biss_set_link_warning(biss_t *h, uint32_t window, uint32_t warn);

/* ---- the encoder firmware on a board (pru_slave/, host/lib/biss_enc.c) ----
 * Its configuration and limits: biss/biss_types.h, biss/biss_rules.h. */

/* The handle drives one PRU's encoder; the master
 * on the other PRU is a biss_t of its own (biss_open). */
typedef struct biss_encoder biss_encoder_t;

/* Loads and starts the encoder firmware on PRU p->pru of a Linux target,
 * as biss_open does the master (p->target, loader, devmem, sysfs_root,
 * firmware_dir, timeout_ms, errbuf alike): the image p->firmware, else
 * $BISS_ENCODER_FIRMWARE, else biss_encoder.bin or biss_encoder_pru1.bin
 * of the build tree or the firmware directory; through remoteproc the
 * ELF p->rproc_firmware, else biss_encoder.elf or biss_encoder_pru1.elf.
 * Waits for its magic and checks it was assembled for that PRU. With
 * p->attach nothing is loaded: the running encoder is adopted. The
 * emulator target is refused (BISS_E_TARGET): there the encoder runs
 * beside the master, `biss-sim --encoder`. */
int biss_encoder_open(const struct biss_open_params *p, biss_encoder_t **out);
/* Releases the handle; an encoder it started through remoteproc stops
 * with it unless biss_encoder_leave_running was called. */
void biss_encoder_close(biss_encoder_t *e);
int biss_encoder_leave_running(biss_encoder_t *e);
/* Halts its PRU (SL then stays where it was: take the line off first). */
int biss_encoder_stop(biss_encoder_t *e);
/* Checks c (biss_encoder_config_check), writes it with CFG_SEQ one up and
 * waits for the firmware's ack; its refusal is BISS_E_ENC_REFUSED. Register
 * files and the table are kept (set them before or after). */
int biss_encoder_configure(biss_encoder_t *e, const struct biss_encoder_config *c);
/* nE / nW of slave i sent active or not, from the next frame on. */
int biss_encoder_set_ew(biss_encoder_t *e, unsigned slave, bool error, bool warning);
/* n positions into the table from entry start (BISS_ENC_TABLE_ENTRIES). */
int biss_encoder_table(biss_encoder_t *e, unsigned start, const uint64_t *pos, unsigned n);
/* A byte of a slave's register file as the host sets it (no access rights
 * applied): addr 0x40..0x7F is the slave's direct register; 0x00..0x3F is
 * in its register bank `bank` (< its banks in the configuration in force,
 * read back from data RAM). read_only / write_protected: the register's
 * rights for control frames (protected ones refuse writes when the slave's
 * protect is set). */
int biss_encoder_reg_set(biss_encoder_t *e, unsigned slave, unsigned bank, uint8_t addr,
                         uint8_t value, bool read_only, bool write_protected);
int biss_encoder_reg_get(biss_encoder_t *e, unsigned slave, unsigned bank, uint8_t addr,
                         uint8_t *value);

/* What the encoder did since its configuration. */
struct biss_encoder_status {
    unsigned pru, ma_bit;        /* the PRU it was assembled for, its MA input (R31 bit) */
    uint32_t cfg_seq, cfg_error; /* the configuration in force (or refused), BISS_SLV_CFGERR_* */
    uint32_t frames;             /* frames begun (an MA fall while idle) */
    uint32_t latches;            /* ... with the first rising edge (data latched) */
    uint32_t cd_frames;          /* ... that brought a CDM */
    int cdm;                     /* the last CDM, -1 none yet */
    unsigned cds;                /* the next frame's CDS */
    unsigned ctrl_state;         /* BISS_SLV_CS_* of biss_slave_shm.h */
    unsigned cancels, header_crc_errors;
    uint32_t period_ns;  /* the last frame's MA period (0: none) */
    uint32_t timeout_ns; /* the next frame's timeout after its ACK */
    unsigned work_cycles, work_pad_cycles;
    struct biss_encoder_slave_status {
        unsigned reads, writes, refused, write_crc_errors, commands, dropped;
        int last_cmd, last_addr, last_value; /* -1: none */
    } slave[BISS_ENC_MAX_SLAVES];
};
int biss_encoder_get_status(biss_encoder_t *e, struct biss_encoder_status *st);

#ifdef __cplusplus
}
#endif

#endif
