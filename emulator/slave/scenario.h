/* Everything the bench needs to build the far end of a link: which slave
 * model, its configuration, both line directions and the seed. Named
 * profiles fill one in (profile_by_name); a JSON scenario file can start
 * from a profile and change any field (scenario_json.h). */
#ifndef SCENARIO_H
#define SCENARIO_H

#include "biss_slave.h"
#include "line_model.h"
#include "ssi_slave.h"

#include <stddef.h>
#include <stdint.h>

typedef enum { SCENARIO_BISS, SCENARIO_SSI } scenario_protocol;

/* The master's safety checks for this set-up (JSON "checks"): not the
 * models', but the host's (libbiss's biss_config: life_check, pair), so
 * that a scenario with a fault also says what must catch it. */
#define SCENARIO_MAX_PAIRS 4
typedef struct {
    bool life[BISS_MAX_SLAVES];        /* check slave i's life counter (its life_counter_bits) */
    bool ew_static[BISS_MAX_SLAVES];   /* slave i never sets nE/nW: either active = misframed */
    double max_speed[BISS_MAX_SLAVES]; /* slave i moves at most this, counts/s (0: unchecked) */
    unsigned npairs;
    struct {
        unsigned a, b, shift_a, shift_b;
        uint64_t tolerance;
        bool distinct_crc; /* default true: two channels, their CRCs differ */
    } pair[SCENARIO_MAX_PAIRS];
} scenario_checks;

typedef struct {
    char profile[48]; /* name of the profile it started from */
    scenario_protocol protocol;
    biss_chain_cfg biss;
    ssi_cfg ssi;
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

/* Checks the whole scenario. Returns 0, or -1 with a message naming the
 * field ("biss.slaves[1].crc_poly: ...") in err. */
int scenario_check(const scenario *s, char *err, size_t errlen);

#endif
