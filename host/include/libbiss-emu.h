/*
 * libbiss-emu.h - the emulator target of libbiss: the firmware running on
 * the emulated PRU core, wired through the cable and encoder models (the
 * bench). libbiss-emu adds this backend to libbiss; an application for a
 * board links libbiss alone (<libbiss.h>).
 */
#ifndef LIBBISS_EMU_H
#define LIBBISS_EMU_H

#include "libbiss.h"

#ifdef __cplusplus
extern "C" {
#endif

/* biss_open for every target, the emulator ("emu") included: its profile,
 * scenario file, cable length and seed come from p. */
int biss_emu_open(const struct biss_open_params *p, biss_t **out);

/* The slave layout of the bench's encoder(s), into c->nslaves and
 * c->slave[] (and, for an SSI encoder, c->ssi_delay_ns: the bench line's
 * round trip); the rest of c is left alone. BISS_E_NOT_EMU for hardware. */
int biss_config_from_emu(biss_t *h, struct biss_config *c);

/* Two handles on the two PRUs of one emulated PRU-ICSS: h[0] drives PRU0
 * with the line and encoder(s) of p[0], h[1] PRU1 with those of p[1];
 * both run the firmware, share the IEP and run cycle by cycle together
 * (any blocking call on either lets time pass for both). Each p's target
 * must be "emu"; its pru field is ignored; p[0] sets the SoC and the
 * timeout. Close both (either order). 0, or an error with h[] NULL. */
int biss_emu_open_pair(const struct biss_open_params p[2], biss_t *h[2]);

struct bench;
/* The bench behind an emulator handle (NULL for hardware). Use it only
 * while no other thread is inside a call on h. */
struct bench *biss_emu_bench(biss_t *h);

#ifdef __cplusplus
}
#endif

#endif
