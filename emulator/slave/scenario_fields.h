/* The numeric fields of a scenario: JSON name, where the value lives, its
 * unit and its range (the ranges are listed in MODELS.md, "Ranges").
 *
 * One table per JSON object serves both the JSON parser (each value is
 * checked as it is read, the message naming its JSON path) and
 * scenario_check (a scenario from a profile or built in code), so a range
 * is written once. The ranges keep every run finite and every conversion
 * defined: a time in ns fits sim_ps, a speed times the longest simulated
 * time fits int64, no delay is so long that one frame takes hours. */
#ifndef SCENARIO_FIELDS_H
#define SCENARIO_FIELDS_H

#include <stddef.h>
#include <stdint.h>

typedef enum {
    SF_DOUBLE,   /* double: stored = JSON value x scale */
    SF_PS,       /* sim_ps from a JSON time in ns (fractions allowed, 1 ps resolution) */
    SF_UNSIGNED, /* unsigned, whole */
    SF_U8,       /* uint8_t, whole */
    SF_U32,      /* uint32_t, whole */
    SF_U64,      /* uint64_t, whole, any value (0 .. 2^64 - 1) */
    SF_I64,      /* int64_t, whole */
} sf_kind;

typedef struct {
    const char *name; /* JSON key; NULL ends a table */
    sf_kind kind;
    size_t offset; /* in the struct the table describes */
    double scale;  /* SF_DOUBLE: stored value per JSON unit */
    double lo, hi; /* range in JSON units, both ends included */
} sf_field;

/* line_params ("line", "ma_line", "sl_line") */
extern const sf_field sf_line[];
/* biss_chain_cfg: "biss" and its "timeout" object */
extern const sf_field sf_chain[];
extern const sf_field sf_timeout[];
/* biss_slave_cfg: "biss.slaves[i]" */
extern const sf_field sf_slave[];
/* ssi_cfg: "ssi" */
extern const sf_field sf_ssi[];
/* scenario: the top level */
extern const sf_field sf_top[];

/* The field called name in table t, or NULL. */
const sf_field *sf_find(const sf_field *t, const char *name);

/* Whether kind k holds whole numbers. */
int sf_whole(sf_kind k);

/* Checks a value in JSON units: finite, in range, whole where the kind
 * needs it. Returns 0, or -1 with "9000000000 out of range 0..1000000"
 * (no field name) in err. */
int sf_check(const sf_field *f, double v, char *err, size_t errlen);

/* Stores a checked value (JSON units) into the struct at obj. SF_U64
 * fields take their exact value from u (v is ignored). */
void sf_store(const sf_field *f, void *obj, double v, uint64_t u);

/* Checks every field of table t in the struct at obj; a message starts
 * with prefix and the field name ("ma_line.length_m: ..."). */
int sf_check_all(const sf_field *t, const void *obj, const char *prefix, char *err, size_t errlen);

/* A number as the messages print it: whole numbers in full, others %g. */
void sf_format(double v, char *buf, size_t len);

#endif
