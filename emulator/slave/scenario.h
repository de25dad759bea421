/* Everything the bench needs to build the far end of a link: which slave
 * model, its configuration, both line directions and the seed. Named
 * profiles fill one in (profile_by_name); a JSON scenario file can start
 * from a profile and change any field (scenario_json.h). */
#ifndef SCENARIO_H
#define SCENARIO_H

#include "biss_slave.h"
#include "line_model.h"
#include "slave_model.h"
#include "ssi_slave.h"

#include <stddef.h>
#include <stdint.h>

/* Bytes for the configuration of a model outside the table (ext). */
#define SCENARIO_EXT_BYTES 512

/* The master's safety checks for this set-up (JSON "checks"): not the
 * models', but the host's (libbiss's biss_config: life_check, pair), so
 * that a scenario with a fault also says what must catch it. */
#define SCENARIO_MAX_PAIRS 4
typedef struct {
    unsigned a, b, shift_a, shift_b;
    uint64_t tolerance;
    bool distinct_crc; /* default true: two channels, their CRCs differ */
} scenario_pair;

typedef struct {
    bool life[BISS_MAX_SLAVES];        /* check slave i's life counter (its life_counter_bits) */
    bool ew_static[BISS_MAX_SLAVES];   /* slave i never sets nE/nW: either active = misframed */
    double max_speed[BISS_MAX_SLAVES]; /* slave i moves at most this, counts/s (0: unchecked) */
    unsigned npairs;
    scenario_pair pair[SCENARIO_MAX_PAIRS];
} scenario_checks;

typedef struct scenario {
    char profile[48];          /* name of the profile it started from */
    const slave_model *model;  /* the encoder model (JSON "protocol") */
    biss_chain_cfg biss;       /* the models' configurations: BiSS-C's, */
    ssi_cfg ssi;               /* SSI's, */
    _Alignas(16) unsigned char /* a registered model's (slave_model_register) */
        ext[SCENARIO_EXT_BYTES];
    line_params ma_line; /* master -> slave */
    line_params sl_line; /* slave -> master */
    uint64_t seed;
    scenario_checks checks;
} scenario;

/* Fills s with the named profile. Returns 0, or -1 for an unknown name. */
int profile_by_name(const char *name, scenario *s);

/* Name of profile i (0, 1, ...), NULL past the last: for --help lists. */
const char *profile_name_at(size_t i);

/* Sets both line directions' cable length. */
void scenario_set_cable(scenario *s, double length_m);

/* Makes m the scenario's model; a registered model's configuration (in
 * ext) starts from its defaults. */
void scenario_set_model(scenario *s, const slave_model *m);

/* The configuration of the scenario's model. */
static inline const void *scenario_model_cfg(const scenario *s) {
    return (const char *)s + s->model->cfg_offset;
}

/* The scenario's BiSS-C chain (slave_model chain), NULL if its model is
 * not BiSS-C. */
static inline const biss_chain_cfg *scenario_chain(const scenario *s) {
    return s->model->chain ? s->model->chain(scenario_model_cfg(s)) : NULL;
}

/* Checks the whole scenario. Returns 0, or -1 with a message naming the
 * field ("biss.slaves[1].crc_poly: ...") in err. */
int scenario_check(const scenario *s, char *err, size_t errlen);

#endif
