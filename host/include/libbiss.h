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

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

#define BISS_API_MAX_SLAVES 8
#define BISS_PRU_HZ         200000000u /* PRU clock: 5 ns per cycle */
#define BISS_HALF_CLOCK_HZ  100000000u /* f = 100 MHz / H */

/* ---- errors ------------------------------------------------------------ */
enum biss_error {
    BISS_OK = 0,
    BISS_E_INVAL = -1,           /* NULL pointer or argument out of its domain */
    BISS_E_NOMEM = -2,           /* out of memory */
    BISS_E_TARGET = -3,          /* unknown target name */
    BISS_E_FIRMWARE_IO = -4,     /* firmware image cannot be read */
    BISS_E_FIRMWARE_SIZE = -5,   /* image empty, not whole words, or larger than IRAM */
    BISS_E_DEVMEM = -6,          /* devmem cannot be opened or mapped */
    BISS_E_PROFILE = -7,         /* unknown emulator profile */
    BISS_E_SCENARIO = -8,        /* scenario file unreadable or invalid */
    BISS_E_EMU = -9,             /* emulator bench cannot be built */
    BISS_E_RATE_RANGE = -10,     /* MA rate gives H outside 10..1024 (97.7 kHz..10 MHz) */
    BISS_E_RATE_INEXACT = -11,   /* 100 MHz / f is not a whole number of PRU cycles */
    BISS_E_RATE_SHIFT = -12,     /* H has no exact 8x shift clock (H = a*b, 2 <= a,b <= 32) */
    BISS_E_NSLAVES = -13,        /* slave count outside 1..8 */
    BISS_E_DATA_BITS = -14,      /* data bits outside 1..64 */
    BISS_E_CRC_BITS = -15,       /* CRC bits outside 0..16 */
    BISS_E_CRC_POLY = -16,       /* polynomial not odd, or its degree not crc_bits (or a poly
                                    without CRC) */
    BISS_E_CRC_START = -17,      /* CRC start value wider than crc_bits */
    BISS_E_EW = -18,             /* nE/nW position outside the data word */
    BISS_E_POS_BITS = -19,       /* position bits do not fit above nE/nW */
    BISS_E_TRIGGER = -20,        /* unknown trigger mode */
    BISS_E_IEP_PERIOD = -21,     /* IEP period not a multiple of 5 ns or shorter than a frame */
    BISS_E_PROC_LIMIT = -22,     /* processing-time limit above 65535 MA clocks */
    BISS_E_SSI = -23,            /* SSI: not one slave, or with CRC or nE/nW, or delay > 65535 ns */
    BISS_E_TIMEOUT = -24,        /* the firmware did not answer in time */
    BISS_E_NOT_RUNNING = -25,    /* firmware not running (no magic in data RAM) */
    BISS_E_NO_SAMPLE = -26,      /* nothing published yet */
    BISS_E_RETRY = -27,          /* no consistent sample after many tries */
    BISS_E_NOT_HOST_TRIG = -28,  /* biss_trigger outside host-trigger mode */
    BISS_E_NOT_CONFIGURED = -29, /* no configuration accepted yet */
    BISS_E_PRU_FAULT = -30,      /* the (emulated) PRU faulted or halted */
    BISS_E_IO = -31,             /* backend access outside the mapped window */
    BISS_E_NOT_EMU = -32,        /* emulator-only call on a hardware handle */
    BISS_E_STOPPED = -33,        /* the PRU is stopped */
    BISS_E_CD_BUSY = -34,        /* a control-communication program is still running */
    BISS_E_CD_WAIT = -35,        /* the slave's S did not come within the wait limit */
    BISS_E_CD_FRAME = -36,       /* a frame failed while the program ran */
    BISS_E_CD_STEPS = -37,       /* program length out of range (1..1024) */
    BISS_E_CD_CRC = -38,         /* register data came back with a wrong CRC4 */
    BISS_E_CD_NO_ECHO = -39,     /* no slave took the control frame (R/W not echoed) */
    BISS_E_CD_IDA = -40,         /* command: IDA bits differ from the addressed IDs */
    /* the firmware refused the configuration (ST_CFG_ERROR = BISS_CFGERR_*) */
    BISS_E_FW_NSLAVES = -41,
    BISS_E_FW_HALF = -42,
    BISS_E_FW_DATA_BITS = -43,
    BISS_E_FW_CRC_BITS = -44,
    BISS_E_FW_TRIGGER = -45,
    BISS_E_FW_EW = -46,
    BISS_E_FW_IEP_PERIOD = -47,
    BISS_E_FW_SSI = -48,
    BISS_E_FW_UNKNOWN = -49,  /* an ST_CFG_ERROR code this library does not know */
    BISS_E_CD_ECHO = -50,     /* a write (data or CRC4) was not echoed as sent */
    BISS_E_CD_WITHHELD = -51, /* IDA test failed: the command was withheld (not executed) */
    /* opening a real PRU: the open params' errbuf gets path, errno and a hint */
    BISS_E_NOT_POWERED = -52, /* the PRU-ICSS is not powered (pruss driver not bound) */
    BISS_E_BUSY = -53,        /* another process holds this PRU (its pid in errbuf) */
    BISS_E_RPROC = -54,       /* no usable remoteproc instance for this PRU */
    BISS_E_RPROC_BUSY = -55,  /* the remoteproc instance runs another firmware */
    /* what an attached handle reads back from data RAM */
    BISS_E_FW_ID = -56,       /* no image identification block: not this firmware */
    BISS_E_SHM_VERSION = -57, /* the firmware speaks another BISS_SHM_VERSION */
    BISS_E_FW_IMAGE = -58,    /* the running image is not the expected one (CRC-32) */
    BISS_E_SHM_CONFIG = -59,  /* the configuration block in data RAM is invalid */
    BISS_E_SHM_RESULT = -60,  /* a published result or a status word the firmware never
                                 writes (or not with this configuration): named by
                                 biss_shm_problem */
    /* safety checks (biss_config: life_check, pair) */
    BISS_E_SAFETY_LIFE = -61, /* life-counter check on no slave of the chain, or its width
                                 outside 1..32 or more than the bits below nE/nW and the
                                 position */
    BISS_E_SAFETY_PAIR = -62, /* pair check: a slave outside the chain, a slave with itself,
                                 more than BISS_API_MAX_PAIRS, a shifted position over 64 bits */
    BISS_E_SAFETY_CRC = -63,  /* pair check of two channels (distinct_crc) whose CRCs have the
                                 same polynomial and start value */
    BISS_E_SAFETY_EW = -64,   /* nE/nW check (ew_static) on a slave outside the chain or one
                                 that sends no nE/nW */
    /* two channels on one PRU-ICSS */
    BISS_E_IEP_OWNED = -65,    /* trigger iep: the other PRU's channel owns the IEP */
    BISS_E_FW_PRU = -66,       /* the image (its words, or the running one's BISS_ST_PRU) was
                                  assembled for the other PRU */
    BISS_E_SAFETY_SPEED = -67, /* speed check (max_speed) on a slave outside the chain, a
                                  speed outside 1e-9..1e18, or on a trigger with no time
                                  base (iep-follow without the owner's period) */
    /* what the line allows (biss_line_check) */
    BISS_E_LINE_TIMEOUT = -68, /* the slave's timeout is below 55 % of the MA period */
    BISS_E_LINE_DELAY = -69,   /* the line's round trip is beyond what the firmware waits for */
    /* the encoder firmware (struct biss_encoder_config) */
    BISS_E_ENC_LC_BITS = -70,  /* a life counter over 32 bits */
    BISS_E_ENC_ID = -71,       /* an ID over 7, or two answering slaves with one ID */
    BISS_E_ENC_TABLE = -72,    /* table entries past BISS_ENC_TABLE_ENTRIES */
    BISS_E_ENC_BANKS = -73,    /* register banks past BISS_ENC_POOL_BANKS */
    BISS_E_ENC_TIMEOUT = -74,  /* timeout 0 or too long, or an adaptive factor or minimum
                                  out of range */
    BISS_E_ENC_BUSY = -75,     /* processing time too long (cycles or clocks) */
    BISS_E_ENC_REG_WAIT = -76, /* register processing time over 255 frames, or an execute
                                  bit other than 0 or 1 */
    BISS_E_ENC_REFUSED = -77,  /* the encoder firmware refused the configuration */
};

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

/* ---- configuration ----------------------------------------------------- */
enum biss_trigger {
    BISS_TRIGGER_HOST = 0,    /* one frame per biss_trigger() */
    BISS_TRIGGER_IEP = 1,     /* one frame every iep_period_ns */
    BISS_TRIGGER_FREERUN = 2, /* next frame as soon as the slave is ready */
    /* one frame per IEP period that the channel on the other PRU of this
     * PRU-ICSS set up with BISS_TRIGGER_IEP, starting on the same IEP count
     * as its frames (iep_period_ns is not used: that channel owns the IEP) */
    BISS_TRIGGER_IEP_FOLLOW = 3,
};

/* "host", "iep", "iep-follow", "free" (or "freerun"). */
int biss_trigger_from_name(const char *name, enum biss_trigger *t);
const char *biss_trigger_name(enum biss_trigger t);

/* One slave's single-cycle data, as its datasheet describes it. The data
 * word is everything before the CRC, MSB first on the wire:
 *   [position][fill][nE nW][life counter ...]            (data_bits in all)
 * with nW at bit ew_shift from the LSB and nE just above it. */
struct biss_slave_config {
    unsigned data_bits; /* 1..64 */
    unsigned crc_bits;  /* 0..16; 0 = no CRC */
    uint32_t crc_poly;  /* WITH its top term, as datasheets write it: 0x43, 0x25, 0x190D9 */
    uint32_t crc_start; /* start value, < 2^crc_bits */
    bool has_ew;        /* the slave sends nE and nW */
    unsigned ew_shift;  /* bit of nW from the data word's LSB (= life-counter bits) */
    /* Position bits at the top of the data word; 0 = everything above nE
     * (or the whole word without nE/nW). Only used for decoding. */
    unsigned pos_bits;
    /* An SSI encoder (slave[0] only, alone, no CRC, no nE/nW): its code
     * word from the first rising edge, read with ssi_delay_ns below. */
    bool ssi;
    bool gray; /* SSI: the word is Gray code; positions are decoded to binary */
    /* Safety check (host side, every frame read): the life counter (sign
     * of life) at the LSB of the data word advanced by the frame-number
     * difference since the last frame read, modulo 2^width (frames the
     * host did not read are no fault). life_bits: its width, 1..32; 0 =
     * ew_shift (the bits below nW, as the firmware's layout has it). */
    bool life_check;
    unsigned life_bits;
    /* Misframing check (host side, every frame read): this slave never
     * sets nE or nW (they stay 1 on the wire), so a CRC-good word that
     * reads either active (0) was read one place off, e.g. the slave got a
     * clock the master never made and sends every later bit one period
     * early: the frame is not valid (BISS_SAFE_EW_SET, biss_sample
     * misframed). Needs has_ew. */
    bool ew_static;
    /* Plausibility check (host side, every frame read): the position
     * moves at most max_speed counts per second (the encoder's top speed),
     * so a CRC-good position further from the last one accepted than
     * max_speed times the time between them, plus one count, was read
     * wrong, e.g. one place off after a clock the master never made: the
     * frame is not valid (BISS_SAFE_POS_JUMP, biss_sample misframed).
     * Distances are modulo 2^pos_bits (a wrap is no jump). The time comes
     * from the frames' IEP timestamps (free-run, host trigger: a count that
     * went backwards, frames more than 10.7 s apart or the count restarted,
     * tells no time and the position is refused, not passed unjudged) or
     * from the frame numbers times iep_period_ns (IEP trigger; iep-follow:
     * the owning channel's period, which biss_configure reads from it).
     * Configured on a trigger with no time (iep-follow with no owner and no
     * period; host or free-run while the other channel's IEP trigger
     * restarts the count), it is refused (BISS_E_SAFETY_SPEED). 0 = off;
     * else 1e-9..1e18 (biss/biss_rules.h). */
    double max_speed;
};

/* Safety check (host side): two slaves' positions, e.g. a BiSS Safety
 * encoder's control and safety position words, agree within tolerance
 * after shifting both to one resolution: (pos_a << shift_a) and (pos_b <<
 * shift_b) are compared modulo 2^W, W the wider of the two, so a wrap of
 * one word before the other is no disagreement. */
#define BISS_API_MAX_PAIRS 4
struct biss_pair_check {
    unsigned a, b;             /* slave indices, a != b */
    unsigned shift_a, shift_b; /* left shifts to one resolution */
    uint64_t tolerance;        /* largest |difference| accepted, counts after shifting */
    /* The two words are one safety encoder's two channels: their CRCs must
     * differ (start value or polynomial), so one channel's data can never
     * pass as the other's (iC-MB4 datasheet, "CRC start value"). */
    bool distinct_crc;
};

struct biss_config {
    uint32_t freq_hz; /* MA rate: 100 MHz / H, H = a*b (2..32 each), 10 <= H <= 1024 */
    unsigned nslaves; /* 1..8; slave[0] is nearest the master */
    struct biss_slave_config slave[BISS_API_MAX_SLAVES];
    enum biss_trigger trigger;
    uint32_t iep_period_ns; /* BISS_TRIGGER_IEP: frame period, multiple of 5 ns */
    uint32_t proc_limit;    /* longest processing time (busy) accepted, MA clocks, <= 65535 */
    uint32_t ssi_delay_ns;  /* SSI only: the line's round trip in ns (<= 65535); an SSI
                               slave sends no ACK the firmware could measure it by */
    unsigned npairs;        /* safety: position pair checks, 0..BISS_API_MAX_PAIRS */
    struct biss_pair_check pair[BISS_API_MAX_PAIRS];
};

/* 1 MHz, no slaves, free-run, processing-time limit 1000 clocks. */
void biss_config_default(struct biss_config *c);

/* The MA half period H in PRU cycles for freq_hz, or a BISS_E_RATE_* error. */
int biss_rate_half(uint32_t freq_hz, unsigned *half);

/* ---- what a line allows (proto/biss_line.c) ----------------------------
 *
 * The firmware reads any line delay up to BISS_MAX_DELAY_NS (40 us) of
 * round trip at any rate: whole MA periods of delay cost it no clock, and
 * it waits that long for the ACK before it reports NO_SLAVE. What limits a
 * rate on a long cable is the cable: its losses round off and delay the
 * edges until an MA half period no longer gets through (the bench's line
 * model: a low-pass whose time constant grows with the square of the
 * length, emulator/slave/MODELS.md; 10 MHz fails there from about 60 m,
 * every MA pulse swallowed, the slave never answering). The rule is
 * TIDEP0022's (TI's BiSS-C master on the PRU, design guide, Table 5
 * "Supported Frequencies"): 10 MHz up to 10 m of cable, 5 MHz up to 25 m,
 * 2 MHz up to 60 m, 1 MHz up to 100 m. Beyond it a rate may still work on
 * a good cable: a warning, not a refusal. Two hard limits: a round trip of
 * BISS_MAX_DELAY_NS or more is never found (every frame NO_SLAVE), and a
 * slave's timeout must last at least 55 % of the MA period (iC-MB4
 * datasheet, BiSS B/C frame, item I306 "Ttos Permissible Timeout (Slave)",
 * min. 55 % TMAS), or the slave may end the frame within a clock phase.
 *
 * A measured round trip stands for a cable of about (round trip -
 * BISS_LINE_FIXED_NS) / BISS_LINE_NS_PER_M metres: 5 ns/m each way
 * (twisted pair at about 2/3 c; TIDEP0022 §2.1.1: "With a cable length up
 * to 100 meters, a cable delay of 1 us ... is possible"), after the
 * transceivers and the encoder's output (EST: 2 x (9 + 15) ns for an RS-485
 * driver and receiver each way, the SN65HVD78 class TIDEP0022 §2.3 uses,
 * plus 20 ns; the bench's line model takes the same figures). A lossy
 * cable's slow edges add to the round trip, so the estimate errs long. */
#define BISS_LINE_FIXED_NS 68.0
#define BISS_LINE_NS_PER_M 10.0

/* The longest cable in metres TIDEP0022 Table 5 gives for MA rate freq_hz:
 * a rate between two rows takes the faster row's length; 1 MHz and below
 * 100 m (the design's longest). 0 for a rate above 10 MHz. */
double biss_rate_cable_max_m(double freq_hz);
/* The cable a measured round trip (ns) stands for, in metres (>= 0). */
double biss_round_trip_cable_m(double round_trip_ns);
/* The shortest slave timeout (ns) iC-MB4's I306 permits at freq_hz: 55 %
 * of the MA period, rounded up. */
uint32_t biss_rate_timeout_min_ns(double freq_hz);

/* What is known about a line: negative or 0 fields are unknown. */
struct biss_line_facts {
    double cable_m;            /* its length, < 0 unknown */
    double round_trip_ns;      /* a measured round trip (biss_line_delay), < 0 unknown */
    double round_trip_res_ns;  /* ... and its resolution (one bit / 8), 0 exact */
    uint32_t slave_timeout_ns; /* the slaves' shortest timeout, 0 unknown */
};

#define BISS_LINE_MAX_RATES 3
/* biss_line_check's findings for a rate. */
struct biss_line_verdict {
    double freq_hz;          /* 100 MHz / H */
    bool beyond_table;       /* the cable is longer than Table 5 gives the rate (a warning) */
    bool timeout_short;      /* the timeout is below 55 % of the MA period (an error) */
    bool delay_unreadable;   /* the round trip is BISS_MAX_DELAY_NS or more (an error) */
    double cable_m;          /* the length, known or estimated (< 0: neither) */
    bool estimated;          /* cable_m comes from the round trip */
    double round_trip_ns;    /* as given (< 0: none) */
    double cable_max_m;      /* Table 5's length for the rate */
    uint32_t timeout_min_ns; /* 55 % of the MA period */
    uint32_t slave_timeout_ns;
    /* the rates (exact, biss_rate_half) nearest freq_hz that none of the
     * findings above rules out, nearest first; none if no rate would do */
    uint32_t rates[BISS_LINE_MAX_RATES];
    unsigned nrates;
};

/* Checks MA rate freq_hz against what is known of the line. Returns
 * BISS_OK (v->beyond_table may still warn), BISS_E_LINE_TIMEOUT or
 * BISS_E_LINE_DELAY (the first of them that applies; v has all), or a
 * BISS_E_RATE_* / BISS_E_INVAL for a rate or pointer no check can take. */
int biss_line_check(uint32_t freq_hz, const struct biss_line_facts *f, struct biss_line_verdict *v);
/* The verdict in words, one line without a newline, e.g. "10 MHz on 80 m
 * of cable: TIDEP0022 Table 5 gives 10 MHz up to 10 m; rates that work:
 * 1 MHz, 800 kHz, 781.25 kHz". Empty when there is nothing to say.
 * Returns what snprintf returns. */
int biss_line_text(const struct biss_line_verdict *v, char *buf, size_t len);
/* A rate as people write it: "10 MHz", "781.25 kHz", "97.65625 kHz". */
int biss_rate_text(double freq_hz, char *buf, size_t len);
/* ---- the encoder firmware: a PRU as a BiSS-C slave (pru_slave/) -------
 *
 * biss_encoder.bin (PRU0) and biss_encoder_pru1.bin (PRU1) make a PRU a BiSS-C
 * encoder, or a chain of up to 8: MA in on an R31 bit, SL out on R30 bit
 * 0, its data RAM laid out in include/biss/biss_slave_shm.h. With the
 * master on the other PRU of the same PRU-ICSS, two wires make a complete
 * loop on one board (docs/hardware.md); alone, it is an encoder simulator
 * for any BiSS-C master. */
#define BISS_ENC_MAX_SLAVES    8
#define BISS_ENC_TABLE_ENTRIES 128 /* positions in the table */
#define BISS_ENC_POOL_BANKS    16  /* register banks 0x00..0x3F the slaves share */

/* One slave: its data word, MSB first on the wire,
 *   [position][fill zeros][nE][nW][life counter]   (at most 64 bits)
 * then the CRC over it (MSB first, inverted). */
struct biss_encoder_slave {
    unsigned pos_bits;  /* 1..64 */
    unsigned fill_bits; /* zeros after the position */
    bool has_err;       /* the word has nE */
    bool has_warn;      /* ... and nW */
    unsigned lc_bits;   /* life counter, 0..32: 0 in the first frame, +1 a frame */
    uint32_t crc_poly;  /* WITH its top term (0x43, 0x190D9), degree 1..16; 0: no CRC */
    uint32_t crc_start; /* < 2^degree */
    /* The position: `position` in the first frame, then + step every frame
     * (modulo 2^pos_bits; a negative step counts down); or, with table_len
     * > 0, frame k sends the table's entry table_start + k mod table_len
     * (biss_encoder_table). Frames count from the configuration. */
    uint64_t position;
    int64_t step;
    unsigned table_start, table_len;
    bool error, warning; /* nE / nW sent active (biss_encoder_set_ew changes them live) */
    /* Control communication: its ID (0..7), unless no_control (a data
     * channel whose device answers through another slave of the same ID);
     * the execute bit of a command (1: iC-MB4's EX; 0: the stop bit P);
     * register processing time (late S, frames 0..255); its register
     * banks in the pool (addresses 0x00..0x3F, bank chosen by 0x40); with
     * protect, write-protected registers refuse writes. */
    unsigned id;
    bool no_control;
    unsigned exec_bit;
    unsigned reg_wait;
    unsigned banks, bank0;
    bool protect;
    /* The ID lock IDL0..7 in the CDS answering S and the 7 header bits
     * after it (false: the default, host/CD.md "IDL slots"), or CTS and the
     * 7 after it in a register access (true). */
    bool idl_at_cts;
};

struct biss_encoder_config {
    unsigned nslaves; /* 1..8, slave[0] nearest the master */
    struct biss_encoder_slave slave[BISS_ENC_MAX_SLAVES];
    /* The timeout: MA still this long ends the frame. Fixed: timeout_ns.
     * Adaptive: the MA period times factor16 / 16, within [timeout_min_ns,
     * timeout_ns] (the Hengstler AD38's "adaptive slave timeout"). At most
     * 1.31 ms. */
    bool adaptive;
    uint32_t timeout_ns;
    uint32_t timeout_min_ns;
    unsigned factor16; /* 1..255 (24: 1.5) */
    /* Processing time: the start bit comes no earlier than busy_ns after
     * the ACK and no earlier than busy_clocks MA clocks after it. */
    uint32_t busy_ns;
    unsigned busy_clocks;
};

/* One slave as the TIDEP0022 test encoder: 12-bit position from 0, step 0,
 * nE, nW, CRC6 0x43, ID 0; a fixed 20 us timeout, no processing time. */
void biss_encoder_config_default(struct biss_encoder_config *c);
/* Checks every field as the encoder firmware would, and more: 0 or the
 * first specific error (BISS_E_NSLAVES, BISS_E_POS_BITS, BISS_E_DATA_BITS,
 * BISS_E_CRC_POLY, BISS_E_CRC_START, BISS_E_ENC_*). */
int biss_encoder_config_check(const struct biss_encoder_config *c);

/* Running it on a board. The handle drives one PRU's encoder; the master
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

/* Checks every field as the firmware would, and more (polynomial degree,
 * start value, position bits, the safety checks). 0 or the first specific
 * error. */
int biss_config_check(const struct biss_config *c);

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
/* Host-trigger mode: asks for one frame. After each configuration (and
 * after a slave went missing) the firmware clocks one training frame of its
 * own, untriggered, to measure the line delay at the new rate: it is
 * published with `training` set and counts in biss_stats.training. */
int biss_trigger(biss_t *h);
/* Lets time pass: the emulator runs for ms simulated milliseconds, on
 * hardware the call sleeps. */
int biss_run_ms(biss_t *h, unsigned ms);

/* ---- samples ----------------------------------------------------------- */
/* Round trip from an MA rising edge at the master pin to the slave's
 * answer at the master pin, from the firmware's ACK position (biss_shm.h):
 * cycles = (DELAY - BISS_DELAY_ZERO) * H / 4 - BISS_DELAY_ADJ_CYCLES,
 * bit8 = cycles / (H / 4), ns = cycles * 5. Within one bit/8 and one PRU
 * cycle of the true round trip. */
struct biss_line_delay {
    uint16_t raw, avg;                   /* the firmware's DELAY_RAW / DELAY_AVG */
    unsigned half;                       /* H of the frame */
    double bit8, cycles, ns;             /* from avg (the filtered value) */
    double raw_bit8, raw_cycles, raw_ns; /* from raw (this frame alone) */
};

struct biss_slave_result {
    uint64_t data;     /* raw data word: everything before the CRC, right-aligned */
    uint64_t position; /* the position field of data (see biss_slave_config.pos_bits) */
    bool crc_ok;       /* CRC right (true when the slave has no CRC) */
    bool error;        /* nE active (low): the encoder reports an error */
    bool warning;      /* nW active (low) */
    uint32_t crc_reg;  /* firmware's CRC register (left-aligned) */
    uint32_t status;   /* BISS_RS_* as published */
    uint32_t safety;   /* BISS_SAFE_* of this frame (the configured checks) */
};

/* Safety verdicts per slave and frame. A check that could not run (the
 * first frame read, a word with a bad CRC, an invalid frame) sets nothing. */
#define BISS_SAFE_LC_CHECKED   0x01  /* the life counter was compared */
#define BISS_SAFE_LC_FROZEN    0x02  /* ... and had not moved */
#define BISS_SAFE_LC_SKIP      0x04  /* ... and had moved, but not by the frames run */
#define BISS_SAFE_PAIR_CHECKED 0x08  /* the position was compared with its pair's */
#define BISS_SAFE_DISAGREE     0x10  /* ... and differed by more than the tolerance */
#define BISS_SAFE_EW_CHECKED   0x20  /* nE/nW of an ew_static slave were looked at */
#define BISS_SAFE_EW_SET       0x40  /* ... and one read active: misframed, the frame not valid */
#define BISS_SAFE_POS_CHECKED  0x80  /* the position was compared with the last one accepted */
#define BISS_SAFE_POS_JUMP     0x100 /* ... and lay beyond max_speed's reach: misframed */
#define BISS_SAFE_FAULTS                                                                           \
    (BISS_SAFE_LC_FROZEN | BISS_SAFE_LC_SKIP | BISS_SAFE_DISAGREE | BISS_SAFE_EW_SET |             \
     BISS_SAFE_POS_JUMP)

struct biss_sample {
    uint32_t seq;   /* ST_SEQ as first read; the frame may be the publication in
                       progress (whole, ST_SEQ not yet bumped): seq + 1 then */
    uint32_t frame; /* frame number (all frames the firmware ran, training included) */
    uint32_t flags; /* BISS_RF_* */
    bool valid, crc_error, no_slave, proc_error, training, sma;
    bool ack_jump;         /* the ACK lay over half a bit from the average: bits read at
                              the wrong place, so not valid (a glitch, or the line changed) */
    bool misframed;        /* host check: an ew_static slave's nE or nW read active, or a
                              max_speed slave's position jumped further than it can move,
                              so its bits were read wrong; valid is cleared (flags keep
                              the firmware's BISS_RF_VALID) */
    uint32_t timestamp;    /* IEP count when the first MA edge was due */
    unsigned proc_clocks;  /* slave busy time, MA clocks */
    unsigned cds;          /* CDS bit */
    unsigned sample_point; /* 0..7 within a bit */
    unsigned lag_periods;  /* whole MA periods between a clock and its bit */
    struct biss_line_delay delay;
    unsigned nslaves;
    struct biss_slave_result slave[BISS_API_MAX_SLAVES];
    uint32_t safety; /* the slaves' BISS_SAFE_* or'ed */
};

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
};

int biss_get_status(biss_t *h, struct biss_status *st);
int biss_get_stats(biss_t *h, struct biss_stats *st);

/* The safety checks' counts since the handle was opened, over the frames
 * it read (biss_read_sample, biss_wait_sample; each frame once). */
struct biss_safety_stats {
    uint32_t lc_checked[BISS_API_MAX_SLAVES]; /* frames whose life counter was compared */
    uint32_t lc_frozen[BISS_API_MAX_SLAVES];
    uint32_t lc_skipped[BISS_API_MAX_SLAVES];
    uint32_t pair_checked[BISS_API_MAX_PAIRS]; /* frames whose pair was compared */
    uint32_t pair_disagree[BISS_API_MAX_PAIRS];
    int64_t pair_last_diff[BISS_API_MAX_PAIRS]; /* shifted a - b of the last comparison */
    uint32_t ew_checked[BISS_API_MAX_SLAVES];   /* ew_static: CRC-good words looked at */
    uint32_t ew_set[BISS_API_MAX_SLAVES];       /* ... with nE or nW active: misframed */
    uint32_t pos_checked[BISS_API_MAX_SLAVES];  /* max_speed: positions compared */
    uint32_t pos_jumped[BISS_API_MAX_SLAVES];   /* ... beyond its reach: misframed */
    uint32_t pos_resync[BISS_API_MAX_SLAVES];   /* ... beyond reach, but in reach of the
                                                   one refused before: taken as the new
                                                   reference, valid */
};
int biss_get_safety_stats(biss_t *h, struct biss_safety_stats *st);

#ifdef __cplusplus
}
#endif

#endif
