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

/* A whole number 0..hi outside the tables (a register value, an index). */
static int get_whole(ctx *c, const cJSON *item, const char *field, double hi, unsigned *out) {
    const sf_field f = {.name = field, .kind = SF_UNSIGNED, .hi = hi};
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

/* "expected \"a\", \"b\" or \"c\"" for a list of names. */
static void expected_names(const char *const *names, size_t n, char *buf, size_t len) {
    size_t at = (size_t)snprintf(buf, len, "expected");
    for (size_t i = 0; i < n && at < len; i++) {
        const char *sep = i == 0 ? " " : i + 1 == n ? " or " : ", ";
        at += (size_t)snprintf(buf + at, len - at, "%s\"%s\"", sep, names[i]);
    }
}

/* ---- register files ---- */

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

static int parse_registers(ctx *c, const cJSON *obj, const char *field, regfile *r) {
    if (expect_object(c, obj, field)) {
        return -1;
    }
    const cJSON *it;
    cJSON_ArrayForEach(it, obj) {
        unsigned bank = 0;
        uint8_t addr = 0;
        unsigned v;
        if (parse_addr(c, it->string, field, &bank, &addr)) {
            return -1;
        }
        size_t saved = strlen(c->path);
        push(c, "%s", field); /* a bad value is named by its address */
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

/* ---- a table's object ---- */

static int parse_object(ctx *c, const cJSON *json, const sf_table *t, void *obj);

static int parse_choice(ctx *c, const cJSON *item, const sf_field *f, void *obj) {
    size_t n = 0;
    while (f->names[n]) {
        n++;
    }
    for (size_t i = 0; cJSON_IsString(item) && i < n; i++) {
        if (!strcmp(item->valuestring, f->names[i])) {
            char *p = (char *)obj + f->offset;
            if (f->size == sizeof(bool)) {
                *(bool *)p = i != 0;
            } else {
                *(int *)p = (int)i;
            }
            return 0;
        }
    }
    char what[160];
    expected_names(f->names, n, what, sizeof what);
    return fail(c, f->name, "%s", f->expect ? f->expect : what);
}

/* Each element of a JSON array of objects, with the path "name[i]". */
typedef int (*element_fn)(ctx *c, const cJSON *elem, const sf_field *f, void *obj, unsigned i);

static int each_object(ctx *c, const cJSON *arr, const sf_field *f, void *obj, element_fn fn) {
    size_t saved = strlen(c->path);
    for (int i = 0; i < cJSON_GetArraySize(arr); i++) {
        const cJSON *e = cJSON_GetArrayItem(arr, i);
        push(c, "%s[%d]", f->name, i);
        if (!cJSON_IsObject(e)) {
            return fail(c, NULL, "expected an object");
        }
        if (fn(c, e, f, obj, (unsigned)i)) {
            return -1;
        }
        pop(c, saved);
    }
    return 0;
}

static int array_element(ctx *c, const cJSON *elem, const sf_field *f, void *obj, unsigned i) {
    void *e = (char *)obj + f->offset + i * f->elem_size;
    if (f->sub->init) {
        f->sub->init(e);
    }
    return parse_object(c, elem, f->sub, e);
}

static int indexed_element(ctx *c, const cJSON *elem, const sf_field *f, void *obj, unsigned i) {
    (void)i;
    struct sf_indexed x = {0};
    if (parse_object(c, elem, f->sub, &x)) {
        return -1;
    }
    ((double *)((char *)obj + f->offset))[x.index] = x.value;
    return 0;
}

/* An array of whole numbers 0..hi, each setting its bool. */
static int parse_set(ctx *c, const cJSON *it, const sf_field *f, void *obj) {
    if (!cJSON_IsArray(it)) {
        return fail(c, f->name, "expected an array of slave indices (0..%.0f)", f->hi);
    }
    bool *set = (bool *)((char *)obj + f->offset);
    const cJSON *e;
    int i = 0;
    cJSON_ArrayForEach(e, it) {
        unsigned v = 0;
        char name[32];
        snprintf(name, sizeof name, "%s[%d]", f->name, i++);
        if (get_whole(c, e, name, f->hi, &v)) {
            return -1;
        }
        set[v] = true;
    }
    return 0;
}

static int parse_value(ctx *c, const cJSON *it, const sf_field *f, void *obj) {
    char *p = (char *)obj + f->offset;
    size_t saved = strlen(c->path);
    int r = 0;
    switch (f->kind) {
    case SF_BOOL:
    case SF_NOT:
        if (!(r = get_bool(c, it, f->name, (bool *)p)) && f->kind == SF_NOT) {
            *(bool *)p = !*(bool *)p;
        }
        return r;
    case SF_CHOICE:
        return parse_choice(c, it, f, obj);
    case SF_OBJECT:
        if (expect_object(c, it, f->name)) {
            return -1;
        }
        push(c, "%s", f->name);
        r = parse_object(c, it, f->sub, p);
        if (!r && f->offset2) {
            r = parse_object(c, it, f->sub, (char *)obj + f->offset2);
        }
        break;
    case SF_ARRAY: {
        int n = cJSON_GetArraySize(it);
        if (!cJSON_IsArray(it) || n < f->lo || n > f->hi) {
            return fail(c, f->name, "%s", f->expect);
        }
        *(unsigned *)((char *)obj + f->count_offset) = (unsigned)n;
        return each_object(c, it, f, obj, array_element);
    }
    case SF_SET:
        return parse_set(c, it, f, obj);
    case SF_INDEXED:
        if (!cJSON_IsArray(it)) {
            return fail(c, f->name, "%s", f->expect);
        }
        return each_object(c, it, f, obj, indexed_element);
    case SF_REGS:
        return parse_registers(c, it, f->name, (regfile *)p);
    case SF_REGFLAGS:
        return parse_flags(c, it, f->name, (regfile *)p, (uint8_t)f->hi);
    case SF_REGBANKS: {
        unsigned n;
        if (get_whole(c, it, f->name, f->hi, &n)) {
            return -1;
        }
        ((regfile *)p)->nbanks = n ? n : 1;
        return 0;
    }
    default:
        return parse_field(c, it, f, obj);
    }
    if (!r) {
        pop(c, saved);
    }
    return r;
}

/* The members of a JSON object by table t into obj: a register file's bank
 * count first (its registers may then fill any bank, whatever the order),
 * then each member in the document's order; every required field given. */
static int parse_object(ctx *c, const cJSON *json, const sf_table *t, void *obj) {
    for (const sf_field *f = t->fields; f->name; f++) {
        const cJSON *it =
            f->kind == SF_REGBANKS ? cJSON_GetObjectItemCaseSensitive(json, f->name) : NULL;
        if (it && parse_value(c, it, f, obj)) {
            return -1;
        }
    }
    bool given[64] = {false};
    const cJSON *it;
    cJSON_ArrayForEach(it, json) {
        const sf_field *f = sf_find(t, it->string);
        if (!f) {
            return fail(c, it->string, "unknown field");
        }
        given[f - t->fields] = true;
        if (f->kind != SF_REGBANKS && parse_value(c, it, f, obj)) {
            return -1;
        }
    }
    for (const sf_field *f = t->fields; f->name; f++) {
        if (f->required && !given[f - t->fields]) {
            return fail(c, f->name, "%s", t->missing);
        }
    }
    return 0;
}

/* ---- top level ---- */

/* "protocol": the model, named; a model's configuration in ext starts
 * from its defaults. */
static int parse_protocol(ctx *c, const cJSON *it, scenario *s) {
    const slave_model *m = cJSON_IsString(it) ? slave_model_find(it->valuestring) : NULL;
    if (m) {
        scenario_set_model(s, m);
        return 0;
    }
    const char *names[16];
    size_t n = 0;
    while (n < 16 && (names[n] = slave_model_at(n) ? slave_model_at(n)->name : NULL)) {
        n++;
    }
    char what[256];
    expected_names(names, n, what, sizeof what);
    return fail(c, "protocol", "%s", what);
}

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
    const cJSON *proto = cJSON_GetObjectItemCaseSensitive(root, "protocol");
    if (proto && parse_protocol(c, proto, s)) {
        return -1;
    }
    const cJSON *it;
    cJSON_ArrayForEach(it, root) {
        const char *k = it->string;
        const slave_model *m = slave_model_find(k);
        const sf_field *f = sf_find(&sf_scenario, k);
        int r = 0;
        c->path[0] = '\0';
        if (!strcmp(k, "profile") || !strcmp(k, "protocol")) {
            continue;
        } else if (m) {
            /* a model's configuration object */
            if (m->cfg_offset == offsetof(scenario, ext) && m != s->model) {
                r = fail(c, k,
                         "not the scenario's protocol (\"%s\"): its configuration has no place",
                         s->model->name);
            } else if (!(r = expect_object(c, it, k))) {
                push(c, "%s", k);
                r = parse_object(c, it, m->cfg, (char *)s + m->cfg_offset);
            }
        } else if (f) {
            r = parse_value(c, it, f, s);
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
