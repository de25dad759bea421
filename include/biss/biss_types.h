/*
 * biss_types.h - the values every layer speaks: a master's configuration
 * (rate, slaves, trigger, safety checks), a slave's data-word layout, a
 * published sample and its line delay, what a line is known to be and
 * what it allows, the safety counts, the error codes and the constants
 * they rest on. The firmware's side of the same contract is biss_shm.h
 * (byte offsets; biss_shm_struct.h its C view); the rules on these values
 * are biss_rules.h (proto/ implements them); the handle API that passes
 * them is libbiss.h (host/include/).
 *
 * C only; installed with libbiss.h (<biss/biss_types.h>).
 */
#ifndef BISS_TYPES_H
#define BISS_TYPES_H

#include <stdbool.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

#define BISS_API_MAX_SLAVES 8
#define BISS_PRU_HZ         200000000u /* PRU clock: 5 ns per cycle */
#define BISS_HALF_CLOCK_HZ  100000000u /* f = 100 MHz / H */
/* the longest processing time (busy) a frame may take, MA clocks: the firmware
 * gives up at this + 1 busy clocks, a 16-bit count */
#define BISS_MAX_PROC_LIMIT 65534u

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
    BISS_E_PROC_LIMIT = -22,     /* processing-time limit above BISS_MAX_PROC_LIMIT */
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
    /* host trigger: the last one has not started its frame yet (asked for
     * again, that frame would come once) */
    BISS_E_TRIGGER_PENDING = -78,
    /* register access or a command configured for an SSI encoder, which has
     * no control communication (no CDM, no CDS); also the verdict of a
     * program an SSI configuration cut (running when it was written) */
    BISS_E_SSI_NO_CONTROL = -79,
};

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
     * from the frames' IEP timestamps (free-run, host trigger) or from the
     * frame numbers times iep_period_ns (IEP trigger; iep-follow: the
     * owning channel's period, which biss_configure reads from it). Where
     * no time is known (the count between the two frames half its range or
     * more: 2^31 IEP counts, 10.7 s; or the frames read that long apart by
     * the host's clock, so the count may have come round), the position is
     * not judged, neither passed nor refused (BISS_SAFE_POS_UNTIMED), and
     * becomes the reference for the next frame.
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
    uint32_t proc_limit;    /* longest processing time (busy) accepted, MA clocks, <= 65534 */
    uint32_t ssi_delay_ns;  /* SSI only: the line's round trip in ns (<= 65535); an SSI
                               slave sends no ACK the firmware could measure it by */
    unsigned npairs;        /* safety: position pair checks, 0..BISS_API_MAX_PAIRS */
    struct biss_pair_check pair[BISS_API_MAX_PAIRS];
};

/* ---- what a line is and allows (the rules: biss_rules.h) ---------------- */

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

/* ---- samples ----------------------------------------------------------- */
/* Round trip from an MA rising edge at the master pin to the slave's
 * answer at the master pin, from the firmware's ACK position (biss_shm.h):
 * cycles = (DELAY - BISS_DELAY_ZERO) * H / 4 - BISS_DELAY_ADJ_CYCLES,
 * bit8 = cycles / (H / 4), ns = cycles * 5. Within one bit/8 and one PRU
 * cycle of the true round trip. */
struct biss_line_delay {
    uint16_t raw, avg;                   /* the firmware's DELAY_RAW / DELAY_AVG */
    unsigned half;                       /* H of the frame */
    double bit8, cycles, ns;             /* from avg (the filtered value); 0 for a round
                                            trip under one bit/8 (H / 4 cycles) */
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
#define BISS_SAFE_POS_UNTIMED                                                                      \
    0x200 /* not compared: no time known since the last one                                        \
             accepted (max_speed); it is the reference now */
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
    bool off_grid;         /* SL's samples around a bit's sample point disagreed: an edge
                              off the bit grid, so not valid (checked below 10 MHz only:
                              BISS_RF_OFF_GRID) */
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
    uint32_t safety;   /* the slaves' BISS_SAFE_* or'ed */
    int link_eye;      /* eye opening, eighths of a bit (0..BISS_LINK_EYE_MAX): how far the
                          nearest SL edge seen lay from the sample point (-1: no ACK measured,
                          no figure); proto/biss_link.c */
    bool link_warning; /* marginal frames (eye <= BISS_LINK_EYE_MARGINAL) reached the warning
                          count in this block of frames or the last (biss_link_state) */
};

/* ---- safety counts ----------------------------------------------------- */

/* The safety checks' counts over the frames they judged: libbiss's since
 * the handle was opened, over the frames it read (biss_read_sample,
 * biss_wait_sample, biss_ring_read: each frame once, in frame order; a
 * ring frame older than one the newest-sample read judged is judged in
 * the ring's order but not counted); the bench's over every publication. */
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
    uint32_t pos_untimed[BISS_API_MAX_SLAVES];  /* max_speed: positions not compared, no
                                                   time known since the last one accepted
                                                   (BISS_SAFE_POS_UNTIMED): the reference
                                                   taken again, valid */
};

/* ---- link quality ------------------------------------------------------
 *
 * A frame's eye opening (biss_sample.link_eye) and the counts over the
 * frames judged: libbiss's since the handle was opened (the frames it
 * read), the bench's over every publication. After 2^32 - 1 frames the
 * counts from frames to warnings start again from 0, together (the eye's
 * mean, eye_sum / frames, stays the mean of the frames counted). */
/* the most a frame flagged BISS_RF_OFF_GRID has: the check's window,
 * BISS_GRID_OLDER and BISS_GRID_NEWER (biss_shm.h) */
#define BISS_LINK_EYE_OFF_GRID 2
#define BISS_LINK_EYE_MAX      4     /* eighths: an edge on the bit grid, half a bit away */
#define BISS_LINK_EYE_MARGINAL 2     /* at most this: a marginal frame */
#define BISS_LINK_WINDOW       10000 /* default block of frames the warning counts in */
#define BISS_LINK_WARN         1     /* default marginal frames in a block that warn */
struct biss_link_stats {
    uint32_t frames;                     /* frames judged (an ACK measured) */
    uint32_t eye[BISS_LINK_EYE_MAX + 1]; /* of those, by eye opening */
    uint64_t eye_sum;                    /* the sum of their eyes (mean: / frames) */
    unsigned eye_min;                    /* the least (BISS_LINK_EYE_MAX before any) */
    uint32_t marginal;                   /* eye <= BISS_LINK_EYE_MARGINAL */
    uint32_t off_grid;                   /* BISS_RF_OFF_GRID among them */
    uint32_t last_block_marginal;        /* marginal frames in the last whole block */
    uint32_t warnings;                   /* frames judged with the warning set */
};

/* ---- the encoder firmware: a PRU as a BiSS-C slave (pru_slave/) -------
 *
 * biss_encoder.bin (PRU0) and biss_encoder_pru1.bin (PRU1) make a PRU a BiSS-C
 * encoder, or a chain of up to 8: MA in on an R31 bit, SL out on R30 bit
 * 0, its data RAM laid out in include/biss/biss_slave_shm.h. With the
 * master on the other PRU of the same PRU-ICSS, two wires make a complete
 * loop on one board (docs/hardware.md §14); alone, it is an encoder simulator
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

#ifdef __cplusplus
}
#endif

#endif
