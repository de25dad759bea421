/*
 * biss_rules.h - the rules on the contract's values (biss_types.h), written
 * once so that every layer takes and refuses the same: the host (libbiss,
 * bissctl), the bench's scenario files and biss-sim. The small ones are
 * inline here; the rest (the configuration check, the MA rate rule, what a
 * line allows) are proto/'s, which libbiss carries and exports. C only
 * (the firmware's contract is biss_shm.h); installed with libbiss.h.
 */
#ifndef BISS_RULES_H
#define BISS_RULES_H

#include "biss_types.h"

#include <math.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* A CRC polynomial written with its top term, as datasheets write it
 * (0x43 = x^6 + x + 1): degree 1..16 (BISS_MAX_CRC_BITS) and odd. Every
 * BiSS CRC has the x^0 term (0x43, 0x25, 0x190D9: iC-MB4 datasheet, "CRC
 * polynomial"); without it the register's lowest bit never takes the
 * feedback and the check degenerates. */
#define BISS_CRC_POLY_MAX 0x1ffffu
static inline bool biss_crc_poly_valid(uint32_t poly) {
    return poly >= 3u && poly <= BISS_CRC_POLY_MAX && (poly & 1u);
}

/* The speed check's top speed (counts per second): from 1e-9 (a count in
 * 30 years) to 1e18, beyond any encoder at both ends; its reach over any
 * time it measures is then a finite number. */
#define BISS_MAX_SPEED_MIN_CPS 1e-9
#define BISS_MAX_SPEED_MAX_CPS 1e18
static inline bool biss_max_speed_valid(double cps) {
    return isfinite(cps) && cps >= BISS_MAX_SPEED_MIN_CPS && cps <= BISS_MAX_SPEED_MAX_CPS;
}

/* ---- the configuration and the MA rate (proto/biss_config_check.c, biss_rate.c) ---- */

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

/* Checks every field as the firmware would, and more (polynomial degree,
 * start value, position bits, the safety checks). 0 or the first specific
 * error. */
int biss_config_check(const struct biss_config *c);

/* ---- the encoder firmware's configuration (proto/biss_encoder.c) ---- */

/* One slave as the TIDEP0022 test encoder: 12-bit position from 0, step 0,
 * nE, nW, CRC6 0x43, ID 0; a fixed 20 us timeout, no processing time. */
void biss_encoder_config_default(struct biss_encoder_config *c);
/* Checks every field as the encoder firmware would, and more: 0 or the
 * first specific error (BISS_E_NSLAVES, BISS_E_POS_BITS, BISS_E_DATA_BITS,
 * BISS_E_CRC_POLY, BISS_E_CRC_START, BISS_E_ENC_*). */
int biss_encoder_config_check(const struct biss_encoder_config *c);

#ifdef __cplusplus
}
#endif

#endif
