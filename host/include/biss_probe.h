/*
 * biss_probe.h - encoder discovery: the slave layout of an unknown BiSS-C
 * encoder (or chain) from the wire, and its identification registers.
 *
 * The wire part is a pure analysis (biss_probe_analyse: no I/O) of raw
 * frames, each the bits after the start bit: CDS first, then everything
 * the chain sends. libbiss captures them with the normal firmware in a
 * capture layout (biss_probe below): 8 slaves x (64 data + 16 CRC bits),
 * no nE/nW, so the firmware clocks 640 bits after the CDS and publishes
 * the data words and, per slave, its CRC register, from which the 16 bits
 * after each word follow (host/probe/biss_probe.c). After the last slave's CRC
 * the wire reads 0: the last
 * slave's SLI input is tied low and every slave passes it on ([MB4],
 * "BiSS C Frame"; the model, emulator/slave/biss_slave.h, sends 0 on every
 * further rising edge). So the frame ends after the last bit that is ever 1.
 *
 * The public part: the analysis of frames, the handle's probe and what it
 * reports. The steps biss_probe takes inside (the registers' layout, the
 * SSI words) are host/probe/biss_probe_priv.h's.
 */
#ifndef BISS_PROBE_H
#define BISS_PROBE_H

#include "libbiss.h"

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

#define BISS_PROBE_CAPTURE_DATA 64 /* per slave of the capture layout */
#define BISS_PROBE_CAPTURE_CRC  16
/* CDS + the capture: 640 bits, the longest frame the firmware clocks */
#define BISS_PROBE_MAX_BITS                                                                        \
    (1 + BISS_API_MAX_SLAVES * (BISS_PROBE_CAPTURE_DATA + BISS_PROBE_CAPTURE_CRC))
#define BISS_PROBE_MAX_FRAMES  4096
#define BISS_PROBE_MAX_LAYOUTS 16 /* candidates kept (more are counted) */
#define BISS_PROBE_MIN_CRC     3
#define BISS_PROBE_MAX_CRC     16

/* Raw frames: bits[i * nbits + k] is bit k (0/1) of frame i, k = 0 the CDS. */
struct biss_probe_frames {
    unsigned nframes, nbits;
    const uint8_t *bits;
    /* The firmware's frame numbers (for a life counter's step); NULL: the
     * frames are consecutive. */
    const uint32_t *frame_no;
};

/* One slave as the wire shows it. */
struct biss_probe_slave {
    unsigned offset; /* first data bit, counted after the CDS */
    unsigned data_bits, crc_bits;
    uint32_t crc_poly; /* with its top term */
    uint32_t crc_start;
    unsigned support;   /* frames whose CRC fits with this polynomial and start */
    unsigned distinct;  /* different data words among the frames */
    unsigned rank;      /* linearly independent data differences (the evidence) */
    unsigned crc_stuck; /* CRC bits that never changed */
    /* Judged on the good frames (every CRC of the layout fits): */
    unsigned lc_bits; /* low bits that counted +1 per frame (0: none) */
    /* The counter may be wider than lc_bits: it never wrapped and the bit
     * above it never changed (its top, nE/nW or fill: the frames cannot
     * tell). The layout is then ambiguous. */
    bool lc_open;
    /* nE/nW proposed: the two bits above the life counter (0: the two bits
     * before the CRC) were 1 in ew_ones_pct % of the frames */
    bool has_ew;
    unsigned ew_shift; /* = lc_bits */
    unsigned ew_ones_pct;
};

struct biss_probe_layout {
    unsigned nslaves;
    struct biss_probe_slave slave[BISS_API_MAX_SLAVES];
    unsigned support;   /* the smallest of its slaves' */
    unsigned crc_total; /* CRC bits in all: more checked bits rank higher */
    /* a slave's data took fewer than 2 independent values (rank < 2): any
     * polynomial of its width fits one difference, so it proves nothing */
    bool weak;
    unsigned crc_stuck; /* its slaves' CRC bits that never changed: ranked last */
    unsigned good;      /* frames every slave's CRC fits; the others are set aside */
};

enum biss_probe_verdict {
    BISS_PROBE_UNIQUE,    /* exactly one layout fits every frame */
    BISS_PROBE_BEST,      /* several fit; the first checks more bits, with enough evidence */
    BISS_PROBE_AMBIGUOUS, /* several fit and the frames cannot tell them apart */
    BISS_PROBE_NONE,      /* cannot decide: no layout fits, or the frames say too little */
};

/* Why an analysis stopped before it had tried every split. */
enum biss_probe_stop {
    BISS_PROBE_RAN_OUT_NONE, /* it did not: every split was tried */
    BISS_PROBE_RAN_OUT_WORK, /* the work limit (steps of the search) */
    BISS_PROBE_RAN_OUT_TIME, /* the time limit (wall clock) */
};

struct biss_probe_result {
    enum biss_probe_verdict verdict;
    char reason[320];   /* why, in words */
    unsigned frames;    /* frames analysed */
    unsigned end_bit;   /* frame length: bits after the CDS up to the last ever 1 */
    unsigned dropped;   /* frames set aside as noise: the first layout's CRCs fail them */
    unsigned after_end; /* frames with 1s after end_bit (noise there): analysed, never probes */
    unsigned nlayouts;  /* layouts that fit (may exceed the ones kept) */
    unsigned nkept;     /* layout[0 .. nkept-1], best first */
    struct biss_probe_layout layout[BISS_PROBE_MAX_LAYOUTS];
    /* The cost: steps of the search (CRC register steps, frame bits read,
     * layouts walked: a measure of work that is the same on every machine),
     * the wall-clock time, and whether a limit stopped it (then the verdict
     * is ambiguous at best, and the reason says so). */
    uint64_t work;
    unsigned elapsed_ms;
    enum biss_probe_stop ran_out;
};

/* ---- limits ----------------------------------------------------------------
 * An analysis is bounded on any input: by work (deterministic: the same
 * frames stop at the same place everywhere) and by a deadline (the wall
 * clock, for a slow machine). Real encoders take far less than the default
 * work limit: the longest chain the capture holds (547 bits, 8 slaves with
 * CRC-16s) about 1/10 of it; 14 frames of garbage would otherwise search
 * for minutes. A long run reports its progress. */
#define BISS_PROBE_WORK_LIMIT    5000000000ull /* steps: 5 to 15 s on an x86-64 PC */
#define BISS_PROBE_TIME_LIMIT_MS 60000u

struct biss_probe_progress {
    uint64_t work, work_limit;
    unsigned elapsed_ms, time_limit_ms;
    unsigned offsets_searched; /* bit offsets a slave may start at, searched so far */
    unsigned end_bit;          /* ... of this many (the frame's length) */
};

struct biss_probe_limits {
    uint64_t work_limit;    /* 0: BISS_PROBE_WORK_LIMIT */
    unsigned time_limit_ms; /* 0: BISS_PROBE_TIME_LIMIT_MS */
    /* Called about once a second of a long run (NULL: never). */
    void (*progress)(void *ctx, const struct biss_probe_progress *p);
    void *ctx;
};

/* Analyses the frames within the default limits; 0, or BISS_E_INVAL for
 * bad arguments (no frames, nbits outside 2..BISS_PROBE_MAX_BITS). "Cannot
 * decide" is a verdict, not an error. */
int biss_probe_analyse(const struct biss_probe_frames *f, struct biss_probe_result *r);
/* The same within the limits lim (NULL: the defaults). */
int biss_probe_analyse_limited(const struct biss_probe_frames *f,
                               const struct biss_probe_limits *lim, struct biss_probe_result *r);
const char *biss_probe_verdict_name(enum biss_probe_verdict v);
/* A layout as a libbiss configuration (slaves only; the rest of c as is). */
void biss_probe_layout_config(const struct biss_probe_layout *l, struct biss_config *c);

/* ---- on a handle --------------------------------------------------------- */

/* The BiSS identification registers of one slave (read-only access). */
struct biss_probe_regs {
    unsigned id;
    int rc_device, rc_manufacturer, rc_profile, rc_serial; /* 0 or BISS_E_* */
    uint8_t device[6];                                     /* 0x78..0x7D */
    uint8_t manufacturer[2];                               /* 0x7E..0x7F */
    uint8_t profile[3];                                    /* 0x41..0x43: EDS bank, profile ID */
    uint8_t serial[4];                                     /* 0x44..0x47 */
};

/* ---- layout from the registers (pure) -------------------------------------
 * Some encoders describe their own format in the device-ID registers. The
 * one format known: the Hengstler AD38's ([AD38] register table of the
 * Slave ID 1 device, direct addresses): 0x78 A/D data length, 0x79 A/D CRC
 * length, 0x7A MT resolution, 0x7B ST resolution, 0x7C life-counter length,
 * 0x7D position CRC length, bits each; manufacturer 0x7E..0x7F "HE". Its
 * channels come first in the chain, each with nE/nW after its data ([AD38]
 * SCD tables: "Err + Warning 2 bit"). Polynomials and start values are not
 * in these registers: only widths are compared with the wire. */
#define BISS_PROBE_REG_CHANNELS 2

struct biss_probe_reg_channel {
    const char *what;    /* "A/D", "MT+ST position" */
    unsigned value_bits; /* the value itself (A/D, MT + ST) */
    unsigned data_bits;  /* value + nE/nW: what the wire's data word holds */
    unsigned crc_bits;
};

struct biss_probe_reg_layout {
    unsigned id;        /* the control-frame ID whose registers said it */
    const char *format; /* which document's format */
    uint8_t raw[6];     /* 0x78..0x7D as read */
    unsigned mt_bits, st_bits, lc_bits;
    unsigned nchannels; /* chain slaves described, from the first */
    struct biss_probe_reg_channel ch[BISS_PROBE_REG_CHANNELS];
};

enum biss_probe_reg_verdict {
    BISS_PROBE_REG_NONE,     /* no register set describes a layout */
    BISS_PROBE_REG_INVALID,  /* a known format, but values no frame can have */
    BISS_PROBE_REG_NO_WIRE,  /* described, but the wire gave no layout to compare */
    BISS_PROBE_REG_AGREE,    /* the wire's first candidate has the described widths */
    BISS_PROBE_REG_AGREE_K,  /* a later candidate (agree_with) has them, the first not */
    BISS_PROBE_REG_DISAGREE, /* no candidate the wire kept has them */
};

const char *biss_probe_reg_verdict_name(enum biss_probe_reg_verdict v);

/* ---- SSI (pure) -------------------------------------------------------------
 * An encoder no BiSS layout fits and whose registers do not answer may be
 * an SSI one (its word can pass for an ACK and start bit): its words
 * (64 bits captured, MSB first, from the first rising edge) are looked at
 * for their length, a CRC and the code (host/probe/biss_probe_ssi.c). */
struct biss_probe_ssi {
    bool tried;         /* an SSI capture was made */
    bool decided;       /* bits and code named (no CRC fits) */
    bool gray;          /* the code, when decided */
    unsigned frames;    /* words analysed */
    uint32_t delay_ns;  /* the round trip the words were read with (set by the caller) */
    unsigned bits;      /* word length: up to the last bit that is ever 1 */
    unsigned fixed_top; /* leading bits that never changed */
    unsigned pairs, irregular_bin, irregular_gray; /* steps looked at, irregular ones */
    bool crc_fits;                                 /* the BiSS analysis found a data + CRC split */
    unsigned crc_data_bits, crc_bits;
    uint32_t crc_poly;
    char verdict[240]; /* in words */
};

struct biss_probe_params {
    uint32_t freq_hz;      /* MA rate for the capture (must be valid for biss_rate_half) */
    unsigned frames;       /* frames to capture (2..BISS_PROBE_MAX_FRAMES); 0: 1024 */
    bool read_regs;        /* also read the identification registers */
    unsigned reg_ids;      /* control-frame IDs 0..reg_ids-1 (0: one per slave found, else 1) */
    bool no_ssi;           /* no SSI capture when no layout fits and no register answers */
    uint32_t ssi_delay_ns; /* SSI capture: the round trip (0: BISS_PROBE_SSI_DELAY_NS) */
    /* The analysis's limits; the time limit holds from the capture's start
     * to the analysis's end (a capture it ends is analysed as far as it
     * came, capture_cut). */
    struct biss_probe_limits limits;
};

struct biss_probe_report {
    struct biss_probe_result wire;
    unsigned no_slave, invalid; /* captured frames without an ACK, or not valid */
    bool capture_cut;           /* the time limit ended the capture early */
    unsigned busy_max;          /* longest processing time seen (MA clocks after the ACK) */
    double delay_ns;            /* line delay of the last frame captured (filtered) */
    unsigned nregs;
    struct biss_probe_regs regs[BISS_API_MAX_SLAVES];
    unsigned nnotes;
    char notes[8][160]; /* where wire and registers disagree, and other remarks */
    /* the first register set that describes a layout, and how it compares */
    enum biss_probe_reg_verdict reg_verdict;
    struct biss_probe_reg_layout reg_layout;
    unsigned reg_agree_with; /* candidate (1-based) with the described widths; 0: none */
    char reg_why[160];
    struct biss_probe_ssi ssi; /* when nothing BiSS-like answered (see params.no_ssi) */
};

/* The SSI capture's round trip when none is given: a few metres of cable
 * and the transceivers; the bits are read right within half a bit of it. */
#define BISS_PROBE_SSI_DELAY_NS 60

/* Configures the capture layout (free-running frames), reads the frames
 * through biss_wait_sample, analyses them, optionally reads the
 * identification registers and the layout they describe, tries the line
 * as SSI when nothing BiSS-like answered, and leaves the last capture
 * configuration in force. Returns 0 with *out filled (the verdict may still be "cannot decide"), or
 * the first library error. */
int biss_probe(biss_t *h, const struct biss_probe_params *p, struct biss_probe_report *out);

/* The layout as a JSON scenario for biss-sim --scenario and bissctl
 * --scenario (the generic profile with these slaves). 0, or BISS_E_INVAL
 * when buf is too small. */
int biss_probe_to_json(const struct biss_probe_layout *l, char *buf, size_t size);

#ifdef __cplusplus
}
#endif

#endif
