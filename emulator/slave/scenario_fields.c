/* scenario_fields.c - ranges of the scenario's numeric fields (see
 * scenario_fields.h; MODELS.md, "Ranges", says why each range is what it
 * is). */
#include "scenario_fields.h"

#include "scenario.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#define F(name, kind, type, member, scale, lo, hi)                                                 \
    { name, kind, offsetof(type, member), scale, lo, hi }
#define L(name, kind, member, scale, lo, hi) F(name, kind, line_params, member, scale, lo, hi)
#define C(name, kind, member, scale, lo, hi) F(name, kind, biss_chain_cfg, member, scale, lo, hi)
#define S(name, kind, member, scale, lo, hi) F(name, kind, biss_slave_cfg, member, scale, lo, hi)
#define I(name, kind, member, scale, lo, hi) F(name, kind, ssi_cfg, member, scale, lo, hi)
#define END                                                                                        \
    { NULL, SF_DOUBLE, 0, 0, 0, 0 }

/* The longest delays: 10 us for anything a transceiver or a slave output
 * adds, 1 ms for a slave's busy and timeout times (the longest the firmware
 * waits, BISS_MAX_HALF clocks, is 10 ms at 97.7 kHz): each frame then ends
 * within milliseconds of simulated time. */
#define MAX_EDGE_NS  1e4
#define MAX_FRAME_NS 1e6
/* Counts per second: times the longest simulated time (PRU_MAX_CYCLE,
 * 2.3e6 s) this stays below 2^63. */
#define MAX_SPEED 1e12
#define U64_MAX_D 18446744073709551615.0
/* Frame numbers as biss-sim counts them (1 = the first), in an unsigned. */
#define MAX_FRAME_NO 4294967295.0
/* Counts a frame: every whole number a JSON number holds exactly. */
#define MAX_STEP 9007199254740991.0

const sf_field sf_line[] = {
    L("length_m", SF_DOUBLE, length_m, 1, 0, 1000),
    L("ns_per_m", SF_DOUBLE, ps_per_m, 1000, 0, 100),
    L("driver_delay_ns", SF_PS, driver_delay_ps, 0, 0, MAX_EDGE_NS),
    L("receiver_delay_ns", SF_PS, receiver_delay_ps, 0, 0, MAX_EDGE_NS),
    L("rise_extra_ns", SF_PS, rise_extra_ps, 0, 0, MAX_EDGE_NS),
    L("fall_extra_ns", SF_PS, fall_extra_ps, 0, 0, MAX_EDGE_NS),
    L("tau0_ns", SF_DOUBLE, tau0_ps, 1000, 0, MAX_EDGE_NS),
    L("tau_per_m2_ps", SF_DOUBLE, tau_per_m2_ps, 1, 0, 1000),
    L("jitter_rms_ps", SF_DOUBLE, jitter_rms_ps, 1, 0, 1e6),
    L("glitch_rate_hz", SF_DOUBLE, glitch_rate_hz, 1, 0, 1e7),
    L("glitch_width_ns", SF_PS, glitch_width_ps, 0, 0, MAX_FRAME_NS),
    L("fault_at_ns", SF_PS, fault_at_ps, 0, 0, 1e12),
    L("fault_until_ns", SF_PS, fault_until_ps, 0, 0, 1e12),
    END,
};

const sf_field sf_chain[] = {
    C("output_delay_ns", SF_PS, out_delay_ps, 0, 0, MAX_EDGE_NS),
    C("busy_ns", SF_PS, busy_ps, 0, 0, MAX_FRAME_NS),
    C("busy_clocks", SF_UNSIGNED, busy_clocks, 0, 0, 10000),
    END,
};

const sf_field sf_timeout[] = {
    C("ns", SF_PS, timeout_ps, 0, 0, MAX_FRAME_NS),
    C("factor", SF_DOUBLE, adaptive_factor, 1, 0, 100),
    C("min_ns", SF_PS, adaptive_min_ps, 0, 0, MAX_FRAME_NS),
    C("max_ns", SF_PS, adaptive_max_ps, 0, 0, MAX_FRAME_NS),
    END,
};

const sf_field sf_slave[] = {
    S("id", SF_U8, id, 0, 0, 7),
    S("position_bits", SF_UNSIGNED, pos_bits, 0, 1, 64),
    S("fill_bits", SF_UNSIGNED, fill_bits, 0, 0, 63),
    S("life_counter_bits", SF_UNSIGNED, lc_bits, 0, 0, 32),
    S("crc_poly", SF_U32, crc_poly, 0, 0, 0x1ffff),
    S("crc_start", SF_U32, crc_start, 0, 0, 0xffff),
    S("position", SF_U64, pos0, 0, 0, U64_MAX_D),
    S("speed_cps", SF_DOUBLE, speed_cps, 1, -MAX_SPEED, MAX_SPEED),
    S("counts_per_frame", SF_I64, counts_per_frame, 0, -MAX_STEP, MAX_STEP),
    S("register_processing_frames", SF_UNSIGNED, reg_proc_frames, 0, 0, 1000),
    S("command_execute_bit", SF_U8, cmd_exec, 0, 0, 1),
    S("life_counter_fault_frame", SF_UNSIGNED, lc_fault_frame, 0, 1, MAX_FRAME_NO),
    S("position_fault_offset", SF_U64, pos_fault_offset, 0, 0, U64_MAX_D),
    S("position_fault_frame", SF_UNSIGNED, pos_fault_frame, 0, 1, MAX_FRAME_NO),
    END,
};

const sf_field sf_ssi[] = {
    I("bits", SF_UNSIGNED, bits, 0, 1, 64),
    I("position", SF_U64, pos0, 0, 0, U64_MAX_D),
    I("speed_cps", SF_DOUBLE, speed_cps, 1, -MAX_SPEED, MAX_SPEED),
    I("output_delay_ns", SF_PS, out_delay_ps, 0, 0, MAX_EDGE_NS),
    I("monoflop_ns", SF_PS, monoflop_ps, 0, 0, MAX_FRAME_NS),
    END,
};

const sf_field sf_top[] = {
    F("seed", SF_U64, scenario, seed, 0, 0, U64_MAX_D),
    END,
};

const sf_field *sf_find(const sf_field *t, const char *name) {
    for (; t->name; t++) {
        if (!strcmp(t->name, name)) {
            return t;
        }
    }
    return NULL;
}

int sf_whole(sf_kind k) {
    return k != SF_DOUBLE && k != SF_PS;
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
    case SF_U64:
        *(uint64_t *)p = u;
        break;
    case SF_I64:
        *(int64_t *)p = (int64_t)v;
        break;
    }
}

/* The stored value in JSON units (SF_U64: always in range, reported as 0). */
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
    case SF_U64:
        break;
    }
    return 0;
}

int sf_check_all(const sf_field *t, const void *obj, const char *prefix, char *err, size_t errlen) {
    for (; t->name; t++) {
        char what[128]; /* sf_check writes at most 110 bytes */
        if (sf_check(t, load(t, obj), what, sizeof what)) {
            snprintf(err, errlen, "%s%s: %s", prefix, t->name, what);
            return -1;
        }
    }
    return 0;
}
