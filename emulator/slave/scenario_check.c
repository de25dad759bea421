/* scenario_check.c - scenario_check (scenario.h): every numeric field in
 * its range (scenario_fields.h), then what the models need of the fields
 * together. */
#include "scenario.h"
#include "scenario_fields.h"

#include <stdio.h>

/* What one line direction needs beyond the ranges. */
static const char *check_line(const line_params *p) {
    if (p->driver_delay_ps + p->receiver_delay_ps + p->length_m * p->ps_per_m <= 0.0) {
        return "total delay must be > 0 (every effect follows its cause)";
    }
    /* 0 is "for good"; an end at or before the start would read as that */
    if (p->fault_until_ps != 0 && p->fault_until_ps <= p->fault_at_ps) {
        return "fault_until_ns: not after fault_at_ns (0: the fault never ends)";
    }
    return NULL;
}

static int check_lines(const scenario *s, char *err, size_t errlen) {
    static const char *const names[2] = {"ma_line", "sl_line"};
    const line_params *p[2] = {&s->ma_line, &s->sl_line};
    for (int i = 0; i < 2; i++) {
        char prefix[16];
        snprintf(prefix, sizeof prefix, "%s.", names[i]);
        if (sf_check_all(sf_line, p[i], prefix, err, errlen)) {
            return -1;
        }
        const char *e = check_line(p[i]);
        if (e) {
            snprintf(err, errlen, "%s%s", prefix, e);
            return -1;
        }
    }
    return 0;
}

static int check_biss(const biss_chain_cfg *b, char *err, size_t errlen) {
    const char *e;
    if (b->n >= 1 && b->n <= BISS_MAX_SLAVES) {
        for (unsigned i = 0; i < b->n; i++) {
            char prefix[32];
            snprintf(prefix, sizeof prefix, "biss.slaves[%u].", i);
            if (sf_check_all(sf_slave, &b->s[i], prefix, err, errlen)) {
                return -1;
            }
            if ((e = biss_slave_cfg_check(&b->s[i]))) {
                snprintf(err, errlen, "%s%s", prefix, e);
                return -1;
            }
        }
        unsigned first, second;
        if (biss_chain_shared_id(b, &first, &second)) {
            snprintf(err, errlen, "biss.slaves[%u].id: %u is slaves[%u]'s id too", second,
                     b->s[second].id, first);
            return -1;
        }
    }
    if (sf_check_all(sf_chain, b, "biss.", err, errlen) ||
        sf_check_all(sf_timeout, b, "biss.timeout.", err, errlen)) {
        return -1;
    }
    if ((e = biss_chain_cfg_check(b))) {
        snprintf(err, errlen, "biss.%s", e);
        return -1;
    }
    return 0;
}

/* The checks name slaves of the chain; a life counter checked exists; a
 * slave that never sets nE/nW has them and is not told to set them. */
static int check_checks(const scenario *s, char *err, size_t errlen) {
    const scenario_checks *c = &s->checks;
    unsigned n = s->protocol == SCENARIO_BISS ? s->biss.n : 0;
    for (unsigned i = 0; i < BISS_MAX_SLAVES; i++) {
        if (c->life[i] && i >= n) {
            snprintf(err, errlen, "checks.life_counter: slave %u is not in the chain (%u slaves)",
                     i, n);
            return -1;
        }
        if (c->life[i] && s->biss.s[i].lc_bits == 0) {
            snprintf(err, errlen,
                     "checks.life_counter: slave %u has no life counter (life_counter_bits 0)", i);
            return -1;
        }
    }
    for (unsigned i = 0; i < BISS_MAX_SLAVES; i++) {
        const biss_slave_cfg *sl = &s->biss.s[i];
        if (!c->ew_static[i]) {
            continue;
        }
        if (i >= n || !sl->has_err || !sl->has_warn) {
            snprintf(err, errlen, "checks.ew_static: slave %u %s", i,
                     i >= n ? "is not in the chain" : "sends no nE/nW (error_bit, warning_bit)");
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
        if (s->biss.s[a].pos_bits + c->pair[k].shift_a > 64 ||
            s->biss.s[b].pos_bits + c->pair[k].shift_b > 64) {
            snprintf(err, errlen, "checks.pairs[%u]: a shifted position wider than 64 bits", k);
            return -1;
        }
    }
    return 0;
}

int scenario_check(const scenario *s, char *err, size_t errlen) {
    if (sf_check_all(sf_top, s, "", err, errlen) || check_lines(s, err, errlen)) {
        return -1;
    }
    if (s->protocol == SCENARIO_SSI) {
        const char *e;
        if (sf_check_all(sf_ssi, &s->ssi, "ssi.", err, errlen)) {
            return -1;
        }
        if ((e = ssi_cfg_check(&s->ssi))) {
            snprintf(err, errlen, "ssi.%s", e);
            return -1;
        }
        return check_checks(s, err, errlen);
    }
    if (check_biss(&s->biss, err, errlen)) {
        return -1;
    }
    return check_checks(s, err, errlen);
}
