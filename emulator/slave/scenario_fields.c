/* scenario_fields.c - the scenario's own tables (lines, checks) and the
 * walk that checks a configuration against its table (scenario_fields.h;
 * MODELS.md, "Ranges", says why each range is what it is). The models'
 * tables are in their files (biss_model.c, ssi_model.c). */
#include "scenario_fields.h"

#include "biss/biss_rules.h"
#include "scenario.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

/* ---- line_params ---- */

#define L(name, kind, member, scale, lo, hi)                                                       \
    SF_FIELD(name, kind, line_params, member, scale, lo, hi)

static const char *const fault_names[] = {"none", "stuck_low", "stuck_high", "open", NULL};

/* What one line direction needs beyond the ranges. */
static int check_line(const void *obj, char *err, size_t errlen) {
    const line_params *p = obj;
    if (p->driver_delay_ps + p->receiver_delay_ps + p->length_m * p->ps_per_m <= 0.0) {
        snprintf(err, errlen, "total delay must be > 0 (every effect follows its cause)");
        return -1;
    }
    /* 0 is "for good"; an end at or before the start would read as that */
    if (p->fault_until_ps != 0 && p->fault_until_ps <= p->fault_at_ps) {
        snprintf(err, errlen, "fault_until_ns: not after fault_at_ns (0: the fault never ends)");
        return -1;
    }
    return 0;
}

static const sf_field line_fields[] = {
    L("length_m", SF_DOUBLE, length_m, 1, 0, 1000),
    L("ns_per_m", SF_DOUBLE, ps_per_m, 1000, 0, 100),
    L("driver_delay_ns", SF_PS, driver_delay_ps, 0, 0, SF_MAX_EDGE_NS),
    L("receiver_delay_ns", SF_PS, receiver_delay_ps, 0, 0, SF_MAX_EDGE_NS),
    L("rise_extra_ns", SF_PS, rise_extra_ps, 0, 0, SF_MAX_EDGE_NS),
    L("fall_extra_ns", SF_PS, fall_extra_ps, 0, 0, SF_MAX_EDGE_NS),
    L("tau0_ns", SF_DOUBLE, tau0_ps, 1000, 0, SF_MAX_EDGE_NS),
    L("tau_per_m2_ps", SF_DOUBLE, tau_per_m2_ps, 1, 0, 1000),
    L("jitter_rms_ps", SF_DOUBLE, jitter_rms_ps, 1, 0, 1e6),
    L("glitch_rate_hz", SF_DOUBLE, glitch_rate_hz, 1, 0, 1e7),
    L("glitch_width_ns", SF_PS, glitch_width_ps, 0, 0, SF_MAX_FRAME_NS),
    L("fault_at_ns", SF_PS, fault_at_ps, 0, 0, 1e12),
    L("fault_until_ns", SF_PS, fault_until_ps, 0, 0, 1e12),
    SF_CHOOSE("fault", line_params, fault, fault_names),
    SF_END,
};

const sf_table sf_line = {.fields = line_fields, .check = check_line};

/* ---- scenario_checks: the master's safety checks ---- */

static void pair_init(void *obj) {
    ((scenario_pair *)obj)->distinct_crc = true;
}

#define P(name, kind, member, lo, hi) SF_FIELD(name, kind, scenario_pair, member, 0, lo, hi)

static const sf_field pair_fields[] = {
    {.name = "a",
     .kind = SF_UNSIGNED,
     .offset = offsetof(scenario_pair, a),
     .hi = 7,
     .required = true},
    {.name = "b",
     .kind = SF_UNSIGNED,
     .offset = offsetof(scenario_pair, b),
     .hi = 7,
     .required = true},
    P("shift_a", SF_UNSIGNED, shift_a, 0, 63),
    P("shift_b", SF_UNSIGNED, shift_b, 0, 63),
    P("tolerance", SF_U64, tolerance, 0, SF_U64_MAX),
    SF_FLAG("distinct_crc", SF_BOOL, scenario_pair, distinct_crc),
    SF_END,
};

static const sf_table pair_table = {
    .fields = pair_fields, .init = pair_init, .missing = "missing (the pair's two slaves)"};

static const sf_field speed_fields[] = {
    {.name = "slave",
     .kind = SF_UNSIGNED,
     .offset = offsetof(struct sf_indexed, index),
     .hi = BISS_MAX_SLAVES - 1,
     .required = true},
    {.name = "counts_per_s",
     .kind = SF_DOUBLE,
     .offset = offsetof(struct sf_indexed, value),
     .scale = 1,
     .lo = BISS_MAX_SPEED_MIN_CPS,
     .hi = BISS_MAX_SPEED_MAX_CPS,
     .required = true},
    SF_END,
};

static const sf_table speed_table = {
    .fields = speed_fields,
    .missing = "missing (the slave and its top speed in counts per second)"};

static const sf_field checks_fields[] = {
    {.name = "life_counter",
     .kind = SF_SET,
     .offset = offsetof(scenario_checks, life),
     .hi = BISS_MAX_SLAVES - 1},
    {.name = "ew_static",
     .kind = SF_SET,
     .offset = offsetof(scenario_checks, ew_static),
     .hi = BISS_MAX_SLAVES - 1},
    {.name = "max_speed",
     .kind = SF_INDEXED,
     .offset = offsetof(scenario_checks, max_speed),
     .sub = &speed_table,
     .expect = "expected an array of {\"slave\", \"counts_per_s\"} objects"},
    {.name = "pairs",
     .kind = SF_ARRAY,
     .offset = offsetof(scenario_checks, pair),
     .lo = 0,
     .hi = SCENARIO_MAX_PAIRS,
     .sub = &pair_table,
     .elem_size = sizeof(scenario_pair),
     .count_offset = offsetof(scenario_checks, npairs),
     .expect = "expected an array of at most 4 pair objects"},
    SF_END,
};

/* Its relations to the chain are scenario_check's (they need the model). */
const sf_table sf_checks = {.fields = checks_fields};

/* ---- the walk ---- */

const sf_field *sf_find(const sf_table *t, const char *name) {
    for (const sf_field *f = t->fields; f->name; f++) {
        if (!strcmp(f->name, name)) {
            return f;
        }
    }
    return NULL;
}

bool sf_number(sf_kind k) {
    return k <= SF_U64;
}

bool sf_whole(sf_kind k) {
    return sf_number(k) && k != SF_DOUBLE && k != SF_PS;
}

void sf_format(double v, char *buf, size_t len) {
    if (v == floor(v) && fabs(v) < 1e20) {
        snprintf(buf, len, "%.0f", v);
    } else {
        snprintf(buf, len, "%g", v);
    }
}

int sf_check(const sf_field *f, double v, char *err, size_t errlen) {
    char sv[32], slo[32], shi[32];
    sf_format(v, sv, sizeof sv);
    if (!isfinite(v)) {
        snprintf(err, errlen, "not a finite number");
        return -1;
    }
    if (!(v >= f->lo && v <= f->hi)) {
        sf_format(f->lo, slo, sizeof slo);
        sf_format(f->hi, shi, sizeof shi);
        if (f->kind == SF_U64) { /* the double rounds 2^64 - 1 up */
            snprintf(shi, sizeof shi, "%llu", (unsigned long long)UINT64_MAX);
        }
        snprintf(err, errlen, "%s out of range %s..%s", sv, slo, shi);
        return -1;
    }
    if (sf_whole(f->kind) && v != floor(v)) {
        snprintf(err, errlen, "%s is not a whole number", sv);
        return -1;
    }
    return 0;
}

void sf_store(const sf_field *f, void *obj, double v, uint64_t u) {
    char *p = (char *)obj + f->offset;
    switch (f->kind) {
    case SF_DOUBLE:
        *(double *)p = v * f->scale;
        break;
    case SF_PS:
        *(sim_ps *)p = (sim_ps)llround(v * (double)SIM_PS_PER_NS);
        break;
    case SF_UNSIGNED:
        *(unsigned *)p = (unsigned)v;
        break;
    case SF_U8:
        *(uint8_t *)p = (uint8_t)v;
        break;
    case SF_U32:
        *(uint32_t *)p = (uint32_t)v;
        break;
    case SF_I64:
        *(int64_t *)p = (int64_t)v;
        break;
    case SF_U64:
        *(uint64_t *)p = u;
        break;
    default:
        break;
    }
}

/* A stored number in JSON units (SF_U64: always in range, reported as 0). */
static double load(const sf_field *f, const void *obj) {
    const char *p = (const char *)obj + f->offset;
    switch (f->kind) {
    case SF_DOUBLE:
        return *(const double *)p / f->scale;
    case SF_PS:
        return (double)*(const sim_ps *)p / (double)SIM_PS_PER_NS;
    case SF_UNSIGNED:
        return *(const unsigned *)p;
    case SF_U8:
        return *(const uint8_t *)p;
    case SF_U32:
        return *(const uint32_t *)p;
    case SF_I64:
        return (double)*(const int64_t *)p;
    default:
        return 0;
    }
}

/* A stored choice's index. */
static unsigned load_choice(const sf_field *f, const void *obj) {
    const char *p = (const char *)obj + f->offset;
    return f->size == sizeof(bool) ? *(const bool *)p : (unsigned)*(const int *)p;
}

static int check_field(const sf_field *f, const void *obj, const char *prefix, char *err,
                       size_t errlen) {
    char what[128]; /* sf_check writes at most 110 bytes */
    char path[160];
    if (sf_number(f->kind)) {
        if (sf_check(f, load(f, obj), what, sizeof what)) {
            snprintf(err, errlen, "%s%s: %s", prefix, f->name, what);
            return -1;
        }
    } else if (f->kind == SF_CHOICE) {
        unsigned n = 0, v = load_choice(f, obj);
        while (f->names[n]) {
            n++;
        }
        if (v >= n) {
            snprintf(err, errlen, "%s%s: %u is none of its %u choices", prefix, f->name, v, n);
            return -1;
        }
    } else if (f->kind == SF_OBJECT) {
        snprintf(path, sizeof path, "%s%s.", prefix, f->name);
        return sf_check_object(f->sub, (const char *)obj + f->offset, path, err, errlen);
    } else if (f->kind == SF_ARRAY) {
        unsigned n = *(const unsigned *)((const char *)obj + f->count_offset);
        if (n < f->lo || n > f->hi) {
            char slo[32], shi[32];
            sf_format(f->lo, slo, sizeof slo);
            sf_format(f->hi, shi, sizeof shi);
            snprintf(err, errlen, "%s%s: %u out of range %s..%s", prefix, f->name, n, slo, shi);
            return -1;
        }
        for (unsigned i = 0; i < n; i++) {
            snprintf(path, sizeof path, "%s%s[%u].", prefix, f->name, i);
            if (sf_check_object(f->sub, (const char *)obj + f->offset + i * f->elem_size, path, err,
                                errlen)) {
                return -1;
            }
        }
    }
    return 0;
}

int sf_check_object(const sf_table *t, const void *obj, const char *prefix, char *err,
                    size_t errlen) {
    for (const sf_field *f = t->fields; f->name; f++) {
        if (!f->unchecked && check_field(f, obj, prefix, err, errlen)) {
            return -1;
        }
    }
    char what[200];
    if (t->check && t->check(obj, what, sizeof what)) {
        snprintf(err, errlen, "%s%s", prefix, what);
        return -1;
    }
    return 0;
}
