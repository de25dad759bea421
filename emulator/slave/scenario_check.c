/* scenario_check.c - the scenario's top-level table and scenario_check
 * (scenario.h): every field in its range and every table's relations
 * (scenario_fields.h), the model's configuration by the model's own
 * tables (slave_model.h), then the master's checks against the model. */
#include "scenario.h"
#include "scenario_fields.h"

#include <stdio.h>

/* The checks name slaves of a BiSS-C chain; a life counter checked exists;
 * a slave that never sets nE/nW has them and is not told to set them. */
static int check_checks(const scenario *s, char *err, size_t errlen) {
    const scenario_checks *c = &s->checks;
    const biss_chain_cfg *chain = scenario_chain(s);
    unsigned n = chain ? chain->n : 0;
    for (unsigned i = 0; i < BISS_MAX_SLAVES; i++) {
        if (c->life[i] && i >= n) {
            snprintf(err, errlen, "checks.life_counter: slave %u is not in the chain (%u slaves)",
                     i, n);
            return -1;
        }
        if (c->life[i] && chain->s[i].lc_bits == 0) {
            snprintf(err, errlen,
                     "checks.life_counter: slave %u has no life counter (life_counter_bits 0)", i);
            return -1;
        }
    }
    for (unsigned i = 0; i < BISS_MAX_SLAVES; i++) {
        if (!c->ew_static[i]) {
            continue;
        }
        const biss_slave_cfg *sl = i < n ? &chain->s[i] : NULL;
        if (!sl || !sl->has_err || !sl->has_warn) {
            snprintf(err, errlen, "checks.ew_static: slave %u %s", i,
                     !sl ? "is not in the chain" : "sends no nE/nW (error_bit, warning_bit)");
            return -1;
        }
        /* the check says the slave never sets them: a model told to is
         * a contradiction, every frame would be refused */
        if (sl->error || sl->warning) {
            snprintf(err, errlen,
                     "checks.ew_static: slave %u drives nE/nW active (error/warning true)", i);
            return -1;
        }
    }
    for (unsigned i = 0; i < BISS_MAX_SLAVES; i++) {
        if (c->max_speed[i] > 0 && i >= n) {
            snprintf(err, errlen, "checks.max_speed: slave %u is not in the chain (%u slaves)", i,
                     n);
            return -1;
        }
    }
    for (unsigned k = 0; k < c->npairs; k++) {
        unsigned a = c->pair[k].a, b = c->pair[k].b;
        if (a >= n || b >= n || a == b) {
            snprintf(err, errlen,
                     "checks.pairs[%u]: slaves %u and %u: two different slaves of the chain "
                     "(%u slaves)",
                     k, a, b, n);
            return -1;
        }
        if (chain->s[a].pos_bits + c->pair[k].shift_a > 64 ||
            chain->s[b].pos_bits + c->pair[k].shift_b > 64) {
            snprintf(err, errlen, "checks.pairs[%u]: a shifted position wider than 64 bits", k);
            return -1;
        }
    }
    return 0;
}

/* After the scenario's own fields: the model's configuration, then the
 * checks against it. */
static int check_scenario(const void *obj, char *err, size_t errlen) {
    const scenario *s = obj;
    if (!s->model) {
        snprintf(err, errlen, "protocol: no model");
        return -1;
    }
    char prefix[64];
    snprintf(prefix, sizeof prefix, "%s.", s->model->name);
    if (sf_check_object(s->model->cfg, scenario_model_cfg(s), prefix, err, errlen)) {
        return -1;
    }
    return check_checks(s, err, errlen);
}

static const sf_field scenario_fields[] = {
    SF_FIELD("seed", SF_U64, scenario, seed, 0, 0, SF_U64_MAX),
    /* "line": both directions at once, each checked under its own name */
    {.name = "line",
     .kind = SF_OBJECT,
     .offset = offsetof(scenario, ma_line),
     .offset2 = offsetof(scenario, sl_line),
     .sub = &sf_line,
     .unchecked = true},
    {.name = "ma_line", .kind = SF_OBJECT, .offset = offsetof(scenario, ma_line), .sub = &sf_line},
    {.name = "sl_line", .kind = SF_OBJECT, .offset = offsetof(scenario, sl_line), .sub = &sf_line},
    /* against the model, by check_checks */
    {.name = "checks",
     .kind = SF_OBJECT,
     .offset = offsetof(scenario, checks),
     .sub = &sf_checks,
     .unchecked = true},
    SF_END,
};

const sf_table sf_scenario = {.fields = scenario_fields, .check = check_scenario};

int scenario_check(const scenario *s, char *err, size_t errlen) {
    return sf_check_object(&sf_scenario, s, "", err, errlen);
}
