#include "scenario_json.h"

#include "read_file.h"

#include <cJSON.h>
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Where we are in the document, for error messages, and the error itself. */
typedef struct {
    char path[128];
    char *err;
    size_t errlen;
} ctx;

static int fail(ctx *c, const char *field, const char *fmt, ...) {
    char what[160];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(what, sizeof what, fmt, ap);
    va_end(ap);
    char where[200];
    snprintf(where, sizeof where, "%s%s%s", c->path, c->path[0] && field ? "." : "",
             field ? field : "");
    if (where[0]) {
        snprintf(c->err, c->errlen, "%s: %s", where, what);
    } else {
        snprintf(c->err, c->errlen, "%s", what);
    }
    return -1;
}

/* Numbers may be JSON numbers or strings such as "0x43". */
static int get_number(ctx *c, const cJSON *item, const char *field, double *out) {
    if (cJSON_IsNumber(item)) {
        *out = item->valuedouble;
        return 0;
    }
    if (cJSON_IsString(item)) {
        char *end;
        errno = 0;
        unsigned long long v = strtoull(item->valuestring, &end, 0);
        if (errno == 0 && end != item->valuestring && *end == '\0') {
            *out = (double)v;
            return 0;
        }
    }
    return fail(c, field, "expected a number (or a string like \"0x43\")");
}

static int get_uint(ctx *c, const cJSON *item, const char *field, double max, uint64_t *out) {
    double v = 0;
    if (cJSON_IsString(item)) { /* keep all 64 bits of hex strings */
        char *end;
        errno = 0;
        unsigned long long u = strtoull(item->valuestring, &end, 0);
        if (errno == 0 && end != item->valuestring && *end == '\0' && (double)u <= max) {
            *out = u;
            return 0;
        }
    }
    if (get_number(c, item, field, &v)) {
        return -1;
    }
    if (v < 0 || v > max || v != floor(v)) {
        return fail(c, field, "expected a whole number from 0 to %.0f", max);
    }
    *out = (uint64_t)v;
    return 0;
}

static int get_bool(ctx *c, const cJSON *item, const char *field, bool *out) {
    if (!cJSON_IsBool(item)) {
        return fail(c, field, "expected true or false");
    }
    *out = cJSON_IsTrue(item);
    return 0;
}

/* A time in ns (fractions allowed) stored as ps. */
static int get_ns(ctx *c, const cJSON *item, const char *field, sim_ps *out) {
    double v = 0;
    if (get_number(c, item, field, &v)) {
        return -1;
    }
    if (v < 0 || v > 9e9) {
        return fail(c, field, "expected a time in ns from 0 to 9e9");
    }
    *out = (sim_ps)llround(v * 1000.0);
    return 0;
}

static int get_nonneg(ctx *c, const cJSON *item, const char *field, double *out) {
    if (get_number(c, item, field, out)) {
        return -1;
    }
    if (*out < 0) {
        return fail(c, field, "must be >= 0");
    }
    return 0;
}

static int expect_object(ctx *c, const cJSON *item, const char *field) {
    return cJSON_IsObject(item) ? 0 : fail(c, field, "expected an object");
}

static void push(ctx *c, const char *fmt, ...) {
    size_t n = strlen(c->path);
    if (n && n < sizeof c->path - 1) {
        c->path[n++] = '.';
    }
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(c->path + n, sizeof c->path - n, fmt, ap);
    va_end(ap);
}

static void pop(ctx *c, size_t saved) {
    c->path[saved] = '\0';
}

/* ---- line ---- */

static int parse_fault(ctx *c, const cJSON *item, line_fault *f) {
    static const char *names[] = {"none", "stuck_low", "stuck_high", "open"};
    if (cJSON_IsString(item)) {
        for (int i = 0; i < 4; i++) {
            if (strcmp(item->valuestring, names[i]) == 0) {
                *f = (line_fault)i;
                return 0;
            }
        }
    }
    return fail(c, "fault", "expected \"none\", \"stuck_low\", \"stuck_high\" or \"open\"");
}

static int parse_line(ctx *c, const cJSON *obj, line_params *p) {
    const cJSON *it;
    cJSON_ArrayForEach(it, obj) {
        const char *k = it->string;
        int r;
        if (!strcmp(k, "length_m")) {
            r = get_nonneg(c, it, k, &p->length_m);
        } else if (!strcmp(k, "ns_per_m")) {
            double v = 0;
            r = get_nonneg(c, it, k, &v);
            p->ps_per_m = v * 1000.0;
        } else if (!strcmp(k, "driver_delay_ns")) {
            r = get_ns(c, it, k, &p->driver_delay_ps);
        } else if (!strcmp(k, "receiver_delay_ns")) {
            r = get_ns(c, it, k, &p->receiver_delay_ps);
        } else if (!strcmp(k, "rise_extra_ns")) {
            r = get_ns(c, it, k, &p->rise_extra_ps);
        } else if (!strcmp(k, "fall_extra_ns")) {
            r = get_ns(c, it, k, &p->fall_extra_ps);
        } else if (!strcmp(k, "tau0_ns")) {
            double v = 0;
            r = get_nonneg(c, it, k, &v);
            p->tau0_ps = v * 1000.0;
        } else if (!strcmp(k, "tau_per_m2_ps")) {
            r = get_nonneg(c, it, k, &p->tau_per_m2_ps);
        } else if (!strcmp(k, "jitter_rms_ps")) {
            r = get_nonneg(c, it, k, &p->jitter_rms_ps);
        } else if (!strcmp(k, "glitch_rate_hz")) {
            r = get_nonneg(c, it, k, &p->glitch_rate_hz);
        } else if (!strcmp(k, "glitch_width_ns")) {
            r = get_ns(c, it, k, &p->glitch_width_ps);
        } else if (!strcmp(k, "fault")) {
            r = parse_fault(c, it, &p->fault);
        } else if (!strcmp(k, "fault_at_ns")) {
            r = get_ns(c, it, k, &p->fault_at_ps);
        } else if (!strcmp(k, "fault_until_ns")) {
            r = get_ns(c, it, k, &p->fault_until_ps);
        } else {
            r = fail(c, k, "unknown field");
        }
        if (r) {
            return -1;
        }
    }
    return 0;
}

/* ---- BiSS slaves ---- */

static int parse_addr(ctx *c, const char *text, const char *field, unsigned *bank, uint8_t *addr) {
    /* "0x44" or "bank2:0x10" */
    char *end;
    *bank = 0;
    if (!strncmp(text, "bank", 4)) {
        *bank = (unsigned)strtoul(text + 4, &end, 0);
        if (*end != ':' || *bank >= REGFILE_MAX_BANKS) {
            return fail(c, field, "address \"%s\": expected \"0x44\" or \"bankN:0x10\"", text);
        }
        text = end + 1;
    }
    unsigned long a = strtoul(text, &end, 0);
    if (end == text || *end || a > 0x7f || (*bank && a >= 0x40)) {
        return fail(c, field, "address \"%s\": expected 0x00..0x7F (banked: 0x00..0x3F)", text);
    }
    *addr = (uint8_t)a;
    return 0;
}

static int parse_registers(ctx *c, const cJSON *obj, regfile *r) {
    if (expect_object(c, obj, "registers")) {
        return -1;
    }
    const cJSON *it;
    cJSON_ArrayForEach(it, obj) {
        unsigned bank = 0;
        uint8_t addr = 0;
        uint64_t v;
        if (parse_addr(c, it->string, "registers", &bank, &addr) ||
            get_uint(c, it, "registers", 255, &v)) {
            return -1;
        }
        regfile_poke(r, bank, addr, (uint8_t)v);
    }
    return 0;
}

static int parse_flags(ctx *c, const cJSON *arr, const char *field, regfile *r, uint8_t flag) {
    if (!cJSON_IsArray(arr)) {
        return fail(c, field, "expected an array of addresses");
    }
    const cJSON *it;
    cJSON_ArrayForEach(it, arr) {
        unsigned bank = 0;
        uint8_t addr = 0;
        if (!cJSON_IsString(it)) {
            return fail(c, field, "expected address strings like \"0x44\"");
        }
        if (parse_addr(c, it->valuestring, field, &bank, &addr)) {
            return -1;
        }
        r->flags[addr] |= flag;
    }
    return 0;
}

static int parse_slave(ctx *c, const cJSON *obj, biss_slave_cfg *s) {
    /* the bank count first, so "registers" may fill any bank whatever the
     * order of the fields */
    const cJSON *banks = cJSON_GetObjectItemCaseSensitive(obj, "banks");
    if (banks) {
        uint64_t u;
        if (get_uint(c, banks, "banks", REGFILE_MAX_BANKS, &u)) {
            return -1;
        }
        s->regs.nbanks = u ? (unsigned)u : 1;
    }
    const cJSON *it;
    cJSON_ArrayForEach(it, obj) {
        const char *k = it->string;
        uint64_t u = 0;
        int r = 0;
        if (!strcmp(k, "id")) {
            r = get_uint(c, it, k, 7, &u);
            s->id = (uint8_t)u;
        } else if (!strcmp(k, "position_bits")) {
            r = get_uint(c, it, k, 64, &u);
            s->pos_bits = (unsigned)u;
        } else if (!strcmp(k, "fill_bits")) {
            r = get_uint(c, it, k, 64, &u);
            s->fill_bits = (unsigned)u;
        } else if (!strcmp(k, "error_bit")) {
            r = get_bool(c, it, k, &s->has_err);
        } else if (!strcmp(k, "warning_bit")) {
            r = get_bool(c, it, k, &s->has_warn);
        } else if (!strcmp(k, "life_counter_bits")) {
            r = get_uint(c, it, k, 32, &u);
            s->lc_bits = (unsigned)u;
        } else if (!strcmp(k, "crc_poly")) {
            r = get_uint(c, it, k, 0x1ffff, &u);
            s->crc_poly = (uint32_t)u;
        } else if (!strcmp(k, "crc_start")) {
            r = get_uint(c, it, k, 0xffff, &u);
            s->crc_start = (uint32_t)u;
        } else if (!strcmp(k, "position")) {
            r = get_uint(c, it, k, 18446744073709551615.0, &s->pos0);
        } else if (!strcmp(k, "speed_cps")) {
            r = get_number(c, it, k, &s->speed_cps);
        } else if (!strcmp(k, "error")) {
            r = get_bool(c, it, k, &s->error);
        } else if (!strcmp(k, "warning")) {
            r = get_bool(c, it, k, &s->warning);
        } else if (!strcmp(k, "register_processing_frames")) {
            r = get_uint(c, it, k, 1000, &u);
            s->reg_proc_frames = (unsigned)u;
        } else if (!strcmp(k, "banks")) {
            continue; /* done above */
        } else if (!strcmp(k, "registers")) {
            r = parse_registers(c, it, &s->regs);
        } else if (!strcmp(k, "read_only")) {
            r = parse_flags(c, it, k, &s->regs, REG_RO);
        } else if (!strcmp(k, "write_protected")) {
            r = parse_flags(c, it, k, &s->regs, REG_WP);
        } else if (!strcmp(k, "protect")) {
            r = get_bool(c, it, k, &s->regs.protect);
        } else {
            r = fail(c, k, "unknown field");
        }
        if (r) {
            return -1;
        }
    }
    return 0;
}

static int parse_timeout(ctx *c, const cJSON *obj, biss_chain_cfg *b) {
    const cJSON *it;
    cJSON_ArrayForEach(it, obj) {
        const char *k = it->string;
        int r;
        if (!strcmp(k, "mode")) {
            if (cJSON_IsString(it) && !strcmp(it->valuestring, "fixed")) {
                b->timeout_mode = BISS_TIMEOUT_FIXED;
                r = 0;
            } else if (cJSON_IsString(it) && !strcmp(it->valuestring, "adaptive")) {
                b->timeout_mode = BISS_TIMEOUT_ADAPTIVE;
                r = 0;
            } else {
                r = fail(c, k, "expected \"fixed\" or \"adaptive\"");
            }
        } else if (!strcmp(k, "ns")) {
            r = get_ns(c, it, k, &b->timeout_ps);
        } else if (!strcmp(k, "factor")) {
            r = get_nonneg(c, it, k, &b->adaptive_factor);
        } else if (!strcmp(k, "min_ns")) {
            r = get_ns(c, it, k, &b->adaptive_min_ps);
        } else if (!strcmp(k, "max_ns")) {
            r = get_ns(c, it, k, &b->adaptive_max_ps);
        } else {
            r = fail(c, k, "unknown field");
        }
        if (r) {
            return -1;
        }
    }
    return 0;
}

static int parse_biss(ctx *c, const cJSON *obj, biss_chain_cfg *b) {
    const cJSON *it;
    cJSON_ArrayForEach(it, obj) {
        const char *k = it->string;
        size_t saved = strlen(c->path);
        uint64_t u = 0;
        int r = 0;
        if (!strcmp(k, "output_delay_ns")) {
            r = get_ns(c, it, k, &b->out_delay_ps);
        } else if (!strcmp(k, "busy_ns")) {
            r = get_ns(c, it, k, &b->busy_ps);
        } else if (!strcmp(k, "busy_clocks")) {
            r = get_uint(c, it, k, 10000, &u);
            b->busy_clocks = (unsigned)u;
        } else if (!strcmp(k, "timeout")) {
            if (!(r = expect_object(c, it, k))) {
                push(c, "timeout");
                r = parse_timeout(c, it, b);
            }
        } else if (!strcmp(k, "slaves")) {
            int n = cJSON_GetArraySize(it);
            if (!cJSON_IsArray(it) || n < 1 || n > BISS_MAX_SLAVES) {
                r = fail(c, k, "expected an array of 1 to 8 slave objects");
            } else {
                b->n = (unsigned)n;
                for (int i = 0; i < n && !r; i++) {
                    const cJSON *so = cJSON_GetArrayItem(it, i);
                    push(c, "slaves[%d]", i);
                    r = cJSON_IsObject(so) ? parse_slave(c, so, &b->s[i])
                                           : fail(c, NULL, "expected an object");
                    if (!r) {
                        pop(c, saved);
                    }
                }
            }
        } else {
            r = fail(c, k, "unknown field");
        }
        if (r) {
            return -1;
        }
        pop(c, saved);
    }
    return 0;
}

static int parse_ssi(ctx *c, const cJSON *obj, ssi_cfg *s) {
    const cJSON *it;
    cJSON_ArrayForEach(it, obj) {
        const char *k = it->string;
        uint64_t u = 0;
        int r;
        if (!strcmp(k, "bits")) {
            r = get_uint(c, it, k, 64, &u);
            s->bits = (unsigned)u;
        } else if (!strcmp(k, "gray")) {
            r = get_bool(c, it, k, &s->gray);
        } else if (!strcmp(k, "position")) {
            r = get_uint(c, it, k, 18446744073709551615.0, &s->pos0);
        } else if (!strcmp(k, "speed_cps")) {
            r = get_number(c, it, k, &s->speed_cps);
        } else if (!strcmp(k, "output_delay_ns")) {
            r = get_ns(c, it, k, &s->out_delay_ps);
        } else if (!strcmp(k, "monoflop_ns")) {
            r = get_ns(c, it, k, &s->monoflop_ps);
        } else {
            r = fail(c, k, "unknown field");
        }
        if (r) {
            return -1;
        }
    }
    return 0;
}

/* ---- top level ---- */

static int parse_top(ctx *c, const cJSON *root, scenario *s) {
    const cJSON *prof = cJSON_GetObjectItemCaseSensitive(root, "profile");
    const char *name = "generic";
    if (prof) {
        if (!cJSON_IsString(prof)) {
            return fail(c, "profile", "expected a profile name string");
        }
        name = prof->valuestring;
    }
    if (profile_by_name(name, s)) {
        return fail(c, "profile", "unknown profile \"%s\"", name);
    }
    const cJSON *it;
    cJSON_ArrayForEach(it, root) {
        const char *k = it->string;
        int r = 0;
        uint64_t u;
        c->path[0] = '\0';
        if (!strcmp(k, "profile")) {
            continue;
        } else if (!strcmp(k, "seed")) {
            r = get_uint(c, it, k, 18446744073709551615.0, &u);
            s->seed = u;
        } else if (!strcmp(k, "protocol")) {
            if (cJSON_IsString(it) && !strcmp(it->valuestring, "biss")) {
                s->protocol = SCENARIO_BISS;
            } else if (cJSON_IsString(it) && !strcmp(it->valuestring, "ssi")) {
                s->protocol = SCENARIO_SSI;
            } else {
                r = fail(c, k, "expected \"biss\" or \"ssi\"");
            }
        } else if (!strcmp(k, "line") || !strcmp(k, "ma_line") || !strcmp(k, "sl_line")) {
            if (!(r = expect_object(c, it, k))) {
                push(c, "%s", k);
                if (k[0] != 's') {
                    r = parse_line(c, it, &s->ma_line);
                }
                if (!r && k[0] != 'm') {
                    r = parse_line(c, it, &s->sl_line);
                }
            }
        } else if (!strcmp(k, "biss")) {
            if (!(r = expect_object(c, it, k))) {
                push(c, "biss");
                r = parse_biss(c, it, &s->biss);
            }
        } else if (!strcmp(k, "ssi")) {
            if (!(r = expect_object(c, it, k))) {
                push(c, "ssi");
                r = parse_ssi(c, it, &s->ssi);
            }
        } else {
            r = fail(c, k, "unknown field");
        }
        if (r) {
            return -1;
        }
    }
    return 0;
}

int scenario_from_json(const char *text, scenario *s, char *err, size_t errlen) {
    ctx c = {.path = "", .err = err, .errlen = errlen};
    cJSON *root = cJSON_Parse(text);
    if (!root) {
        const char *at = cJSON_GetErrorPtr();
        long off = at && at >= text ? (long)(at - text) : -1;
        snprintf(err, errlen, "not valid JSON (near byte %ld)", off);
        return -1;
    }
    int r = cJSON_IsObject(root) ? parse_top(&c, root, s)
                                 : fail(&c, NULL, "the scenario must be a JSON object");
    cJSON_Delete(root);
    if (r == 0) {
        r = scenario_check(s, err, errlen);
    }
    return r;
}

int scenario_load_file(const char *path, scenario *s, char *err, size_t errlen) {
    char *buf;
    size_t len;
    switch (read_file(path, SIZE_MAX, &buf, &len)) {
    case READ_FILE_OK:
        break;
    case READ_FILE_OPEN:
        snprintf(err, errlen, "%s: %s", path, strerror(errno));
        return -1;
    case READ_FILE_NOMEM:
        snprintf(err, errlen, "%s: out of memory", path);
        return -1;
    default:
        snprintf(err, errlen, "%s: read error", path);
        return -1;
    }
    char inner[256];
    int r = scenario_from_json(buf, s, inner, sizeof inner);
    free(buf);
    if (r) {
        snprintf(err, errlen, "%s: %s", path, inner);
    }
    return r;
}
