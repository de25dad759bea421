#include "scenario_json.h"

#include "biss/biss_rules.h"
#include "read_file.h"
#include "scenario_fields.h"

#include <cJSON.h>
#include <ctype.h>
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

/* A string holding a whole number, decimal or with a C prefix ("0x43",
 * "18446744073709551615"): its exact value. No sign, no spaces. */
static int whole_string(const char *text, uint64_t *out) {
    if (!isdigit((unsigned char)text[0])) {
        return -1;
    }
    char *end;
    errno = 0;
    unsigned long long v = strtoull(text, &end, 0);
    if (errno || *end) {
        return -1;
    }
    *out = v;
    return 0;
}

/* One numeric field of a table (scenario_fields.h): a JSON number, or a
 * string with a whole number; checked against the field's range, then
 * stored. A whole number from 2^53 up is exact only as a string: a JSON
 * number there has already lost digits in the parser's double. */
static int parse_field(ctx *c, const cJSON *item, const sf_field *f, void *obj) {
    double v;
    uint64_t u = 0;
    int exact = 0;
    if (cJSON_IsNumber(item)) {
        v = item->valuedouble;
    } else if (cJSON_IsString(item) && whole_string(item->valuestring, &u) == 0) {
        v = (double)u;
        exact = 1;
    } else {
        return fail(c, f->name, "expected a number (or a string like \"0x43\")");
    }
    char what[96];
    if (f->kind != SF_U64 || !exact) {
        if (sf_check(f, v, what, sizeof what)) {
            return fail(c, f->name, "%s", what);
        }
    }
    if (f->kind == SF_U64 && !exact) {
        if (v >= 9007199254740992.0) {
            sf_format(v, what, sizeof what);
            return fail(c, f->name,
                        "a JSON number is exact only below 2^53 (this one reads as %s): "
                        "give it as a string, \"18446744073709551615\" or \"0xffffffffffffffff\"",
                        what);
        }
        u = (uint64_t)v;
    }
    sf_store(f, obj, v, u);
    return 0;
}

/* If the key of item is a numeric field of table t, parses it into obj
 * (*r: 0 or -1) and returns 1; else returns 0. */
static int number_field(ctx *c, const sf_field *t, const cJSON *item, void *obj, int *r) {
    const sf_field *f = sf_find(t, item->string);
    if (!f) {
        return 0;
    }
    *r = parse_field(c, item, f, obj);
    return 1;
}

/* A whole number 0..hi outside the tables (bank count, register value). */
static int get_whole(ctx *c, const cJSON *item, const char *field, double hi, unsigned *out) {
    const sf_field f = {field, SF_UNSIGNED, 0, 0, 0, hi};
    return parse_field(c, item, &f, out);
}

static int get_bool(ctx *c, const cJSON *item, const char *field, bool *out) {
    if (!cJSON_IsBool(item)) {
        return fail(c, field, "expected true or false");
    }
    *out = cJSON_IsTrue(item);
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
        int r;
        if (number_field(c, sf_line, it, p, &r)) {
        } else if (!strcmp(it->string, "fault")) {
            r = parse_fault(c, it, &p->fault);
        } else {
            r = fail(c, it->string, "unknown field");
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
        unsigned v;
        if (parse_addr(c, it->string, "registers", &bank, &addr)) {
            return -1;
        }
        size_t saved = strlen(c->path);
        push(c, "registers"); /* a bad value is named by its address */
        if (get_whole(c, it, it->string, 255, &v)) {
            return -1;
        }
        pop(c, saved);
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

static int parse_lc_fault(ctx *c, const cJSON *item, biss_lc_fault *f) {
    static const char *names[] = {"none", "frozen", "skip"};
    if (cJSON_IsString(item)) {
        for (int i = 0; i < 3; i++) {
            if (strcmp(item->valuestring, names[i]) == 0) {
                *f = (biss_lc_fault)i;
                return 0;
            }
        }
    }
    return fail(c, "life_counter_fault", "expected \"none\", \"frozen\" or \"skip\"");
}

/* Which CDS slots carry the ID lock IDL0..7 (host/CD.md, "IDL"). */
static int parse_idl_slot(ctx *c, const cJSON *it, bool *at_cts) {
    if (cJSON_IsString(it) && (!strcmp(it->valuestring, "s") || !strcmp(it->valuestring, "cts"))) {
        *at_cts = !strcmp(it->valuestring, "cts");
        return 0;
    }
    return fail(c, "id_lock_slot", "expected \"s\" (IDL0 answers S) or \"cts\" (it answers CTS)");
}

static int parse_slave(ctx *c, const cJSON *obj, biss_slave_cfg *s) {
    /* the bank count first, so "registers" may fill any bank whatever the
     * order of the fields */
    const cJSON *banks = cJSON_GetObjectItemCaseSensitive(obj, "banks");
    if (banks) {
        unsigned n;
        if (get_whole(c, banks, "banks", REGFILE_MAX_BANKS, &n)) {
            return -1;
        }
        s->regs.nbanks = n ? n : 1;
    }
    const cJSON *it;
    cJSON_ArrayForEach(it, obj) {
        const char *k = it->string;
        int r = 0;
        if (number_field(c, sf_slave, it, s, &r)) {
        } else if (!strcmp(k, "error_bit")) {
            r = get_bool(c, it, k, &s->has_err);
        } else if (!strcmp(k, "warning_bit")) {
            r = get_bool(c, it, k, &s->has_warn);
        } else if (!strcmp(k, "error")) {
            r = get_bool(c, it, k, &s->error);
        } else if (!strcmp(k, "warning")) {
            r = get_bool(c, it, k, &s->warning);
        } else if (!strcmp(k, "control")) {
            bool on = true;
            r = get_bool(c, it, k, &on);
            s->no_control = !on;
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
        } else if (!strcmp(k, "life_counter_fault")) {
            r = parse_lc_fault(c, it, &s->lc_fault);
        } else if (!strcmp(k, "id_lock_slot")) {
            r = parse_idl_slot(c, it, &s->idl_at_cts);
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
        } else if (number_field(c, sf_timeout, it, b, &r)) {
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
        int r = 0;
        if (number_field(c, sf_chain, it, b, &r)) {
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
        int r;
        if (number_field(c, sf_ssi, it, s, &r)) {
        } else if (!strcmp(it->string, "gray")) {
            r = get_bool(c, it, it->string, &s->gray);
        } else {
            r = fail(c, it->string, "unknown field");
        }
        if (r) {
            return -1;
        }
    }
    return 0;
}

/* ---- the master's safety checks ---- */

static const sf_field sf_pair[] = {
    {"a", SF_UNSIGNED, 0, 0, 0, BISS_MAX_SLAVES - 1},
    {"b", SF_UNSIGNED, 0, 0, 0, BISS_MAX_SLAVES - 1},
    {"shift_a", SF_UNSIGNED, 0, 0, 0, 63},
    {"shift_b", SF_UNSIGNED, 0, 0, 0, 63},
    {"tolerance", SF_U64, 0, 0, 0, 18446744073709551615.0},
};

static int parse_pair(ctx *c, const cJSON *obj, scenario_checks *k, unsigned i) {
    k->pair[i].distinct_crc = true;
    void *where[] = {&k->pair[i].a, &k->pair[i].b, &k->pair[i].shift_a, &k->pair[i].shift_b,
                     &k->pair[i].tolerance};
    bool has_a = false, has_b = false;
    const cJSON *it;
    cJSON_ArrayForEach(it, obj) {
        const char *n = it->string;
        int r = -1;
        size_t f = 0;
        while (f < 5 && strcmp(sf_pair[f].name, n)) {
            f++;
        }
        if (f < 5) {
            r = parse_field(c, it, &sf_pair[f], where[f]);
            has_a |= f == 0;
            has_b |= f == 1;
        } else if (!strcmp(n, "distinct_crc")) {
            r = get_bool(c, it, n, &k->pair[i].distinct_crc);
        } else {
            r = fail(c, n, "unknown field");
        }
        if (r) {
            return -1;
        }
    }
    return has_a && has_b ? 0 : fail(c, has_a ? "b" : "a", "missing (the pair's two slaves)");
}

static const sf_field sf_speed[] = {
    {"slave", SF_UNSIGNED, 0, 0, 0, BISS_MAX_SLAVES - 1},
    {"counts_per_s", SF_DOUBLE, 0, 1, BISS_MAX_SPEED_MIN_CPS, BISS_MAX_SPEED_MAX_CPS},
};

/* One {"slave": S, "counts_per_s": V} of max_speed. */
static int parse_speed(ctx *c, const cJSON *obj, scenario_checks *k) {
    unsigned slave = 0;
    double cps = 0;
    void *where[] = {&slave, &cps};
    bool has[2] = {false, false};
    const cJSON *it;
    cJSON_ArrayForEach(it, obj) {
        size_t f = 0;
        while (f < 2 && strcmp(sf_speed[f].name, it->string)) {
            f++;
        }
        if (f == 2) {
            return fail(c, it->string, "unknown field");
        }
        if (parse_field(c, it, &sf_speed[f], where[f])) {
            return -1;
        }
        has[f] = true;
    }
    if (!has[0] || !has[1]) {
        return fail(c, has[0] ? "counts_per_s" : "slave",
                    "missing (the slave and its top speed in counts per second)");
    }
    k->max_speed[slave] = cps;
    return 0;
}

/* An array of slave indices (0..7) into a per-slave set. */
static int slave_set(ctx *c, const cJSON *it, const char *n, bool *set) {
    if (!cJSON_IsArray(it)) {
        return fail(c, n, "expected an array of slave indices (0..7)");
    }
    const cJSON *e;
    int i = 0;
    cJSON_ArrayForEach(e, it) {
        unsigned v = 0;
        char name[32];
        snprintf(name, sizeof name, "%s[%d]", n, i++);
        if (get_whole(c, e, name, BISS_MAX_SLAVES - 1, &v)) {
            return -1;
        }
        set[v] = true;
    }
    return 0;
}

static int parse_checks(ctx *c, const cJSON *obj, scenario_checks *k) {
    const cJSON *it;
    cJSON_ArrayForEach(it, obj) {
        const char *n = it->string;
        size_t saved = strlen(c->path);
        int r = 0;
        if (!strcmp(n, "life_counter")) {
            r = slave_set(c, it, n, k->life);
        } else if (!strcmp(n, "ew_static")) {
            r = slave_set(c, it, n, k->ew_static);
        } else if (!strcmp(n, "max_speed")) {
            if (!cJSON_IsArray(it)) {
                r = fail(c, n, "expected an array of {\"slave\", \"counts_per_s\"} objects");
            }
            for (int i = 0; !r && i < cJSON_GetArraySize(it); i++) {
                const cJSON *so = cJSON_GetArrayItem(it, i);
                push(c, "max_speed[%d]", i);
                r = cJSON_IsObject(so) ? parse_speed(c, so, k)
                                       : fail(c, NULL, "expected an object");
                if (!r) {
                    pop(c, saved);
                }
            }
        } else if (!strcmp(n, "pairs")) {
            int cnt = cJSON_GetArraySize(it);
            if (!cJSON_IsArray(it) || cnt > SCENARIO_MAX_PAIRS) {
                r = fail(c, n, "expected an array of at most 4 pair objects");
            } else {
                k->npairs = (unsigned)cnt;
                for (int i = 0; i < cnt && !r; i++) {
                    const cJSON *po = cJSON_GetArrayItem(it, i);
                    push(c, "pairs[%d]", i);
                    r = cJSON_IsObject(po) ? parse_pair(c, po, k, (unsigned)i)
                                           : fail(c, NULL, "expected an object");
                    if (!r) {
                        pop(c, saved);
                    }
                }
            }
        } else {
            r = fail(c, n, "unknown field");
        }
        if (r) {
            return -1;
        }
        pop(c, saved);
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
        c->path[0] = '\0';
        if (!strcmp(k, "profile")) {
            continue;
        } else if (number_field(c, sf_top, it, s, &r)) {
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
        } else if (!strcmp(k, "checks")) {
            if (!(r = expect_object(c, it, k))) {
                push(c, "checks");
                r = parse_checks(c, it, &s->checks);
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

/* A key given twice in one object would let the last one win unseen. */
struct key_at {
    const char *name;
    size_t at; /* its place among the object's members */
};

static int by_name_then_place(const void *a, const void *b) {
    const struct key_at *x = a, *y = b;
    int d = strcmp(x->name, y->name);
    return d ? d : (x->at > y->at) - (x->at < y->at);
}

/* The place of the first member whose key an earlier member has, SIZE_MAX
 * none, or -1 out of memory: sorted, so n log n (a scan of every pair
 * took 24 s over 60 000 keys). */
static int first_repeat(const cJSON *obj, size_t *first) {
    size_t n = 0;
    const cJSON *it;
    cJSON_ArrayForEach(it, obj) {
        n++;
    }
    *first = SIZE_MAX;
    if (n < 2) {
        return 0;
    }
    struct key_at *k = malloc(n * sizeof *k);
    if (!k) {
        return -1;
    }
    size_t i = 0;
    cJSON_ArrayForEach(it, obj) {
        k[i] = (struct key_at){it->string, i};
        i++;
    }
    qsort(k, n, sizeof *k, by_name_then_place);
    for (i = 1; i < n; i++) {
        if (!strcmp(k[i - 1].name, k[i].name) && k[i].at < *first) {
            *first = k[i].at;
        }
    }
    free(k);
    return 0;
}

/* Finds the first such key anywhere in the document, in document order. */
static int duplicate_key(ctx *c, const cJSON *item) {
    size_t saved = strlen(c->path);
    size_t repeat = SIZE_MAX;
    if (cJSON_IsObject(item) && first_repeat(item, &repeat)) {
        return fail(c, NULL, "out of memory");
    }
    const cJSON *it;
    size_t i = 0;
    cJSON_ArrayForEach(it, item) {
        if (cJSON_IsObject(item)) {
            if (i == repeat) {
                return fail(c, it->string, "given twice");
            }
            push(c, "%s", it->string);
        } else {
            size_t n = strlen(c->path);
            snprintf(c->path + n, sizeof c->path - n, "[%zu]", i);
        }
        i++;
        if (duplicate_key(c, it)) {
            return -1;
        }
        pop(c, saved);
    }
    return 0;
}

int scenario_from_json(const char *text, scenario *s, char *err, size_t errlen) {
    ctx c = {.path = "", .err = err, .errlen = errlen};
    const char *end = NULL;
    cJSON *root = cJSON_ParseWithOpts(text, &end, 0);
    if (!root) {
        const char *at = cJSON_GetErrorPtr();
        long off = at && at >= text ? (long)(at - text) : -1;
        snprintf(err, errlen, "not valid JSON (near byte %ld)", off);
        return -1;
    }
    while (end && isspace((unsigned char)*end)) {
        end++;
    }
    int r;
    if (end && *end) {
        r = fail(&c, NULL, "text after the JSON object (at byte %ld)", (long)(end - text));
    } else if (!cJSON_IsObject(root)) {
        r = fail(&c, NULL, "the scenario must be a JSON object");
    } else {
        r = duplicate_key(&c, root);
        c.path[0] = '\0';
        if (r == 0) {
            r = parse_top(&c, root, s);
        }
    }
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
    case READ_FILE_TOO_BIG:
        snprintf(err, errlen, "%s: too large", path);
        return -1;
    default:
        snprintf(err, errlen, "%s: %s", path, strerror(errno));
        return -1;
    }
    if (strlen(buf) != len) {
        snprintf(err, errlen, "%s: a NUL byte at byte %zu (not a text file)", path, strlen(buf));
        free(buf);
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
