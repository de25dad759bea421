/* probe_gen.h - random encoder layouts drawn from the reference documents,
 * for the discovery tests: what a master may meet on a real line. */
#ifndef PROBE_GEN_H
#define PROBE_GEN_H

#include "biss_probe.h"
#include "biss_slave.h"

#include <stddef.h>
#include <stdint.h>

/* Layout k of a run (k picks the corner it covers, see probe_gen.c; the
 * rest is drawn from *rng): one slave and its chain's timing in cfg, a
 * one-line description in what. */
void probe_gen_layout(uint64_t *rng, unsigned k, biss_chain_cfg *cfg, char *what, size_t len);

/* The chain as a scenario file's JSON (generic profile). 0, or -1 when buf
 * is too small. */
int probe_gen_json(const biss_chain_cfg *cfg, char *buf, size_t len);

/* The probe's answer against the truth. Unique or best claims every field
 * (the split, CRC, start, nE/nW, the counter's width); ambiguous must list
 * the truth's split among its candidates (unless more fit than are kept). */
enum probe_outcome { PROBE_RECOVERED, PROBE_AMBIGUOUS_OK, PROBE_UNDECIDED, PROBE_WRONG };
enum probe_outcome probe_gen_judge(const struct biss_probe_result *r, const biss_chain_cfg *cfg);
/* The data + CRC split and the CRC of every slave. */
bool probe_gen_layout_matches(const struct biss_probe_layout *l, const biss_chain_cfg *cfg);
/* The fields inside each word: nE/nW (both flags) above the counter, and
 * the counter's width. */
bool probe_gen_fields_match(const struct biss_probe_layout *l, const biss_chain_cfg *cfg);

#endif
