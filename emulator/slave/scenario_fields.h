/* The fields of a scenario: JSON name, where the value lives, its kind,
 * and for numbers their unit and range (the ranges are listed in
 * MODELS.md, "Ranges"); objects and arrays nest tables.
 *
 * One table per JSON object is the whole path from JSON to a checked
 * configuration: the JSON reader (scenario_json.c) walks it to read each
 * value, checking each number as it is read so the message names its JSON
 * path and the value as written; sf_check_object walks the same table over
 * a configuration (from a profile, a file, or built in code), each range
 * again and then each table's relations among its fields (its check).
 * So a range is written once, in its table, and a relation once, in its
 * table's check; a model's tables are its own (slave_model.h). The ranges
 * keep every run finite and every conversion defined: a time in ns fits
 * sim_ps, a speed times the longest simulated time fits int64, no delay is
 * so long that one frame takes hours. */
#ifndef SCENARIO_FIELDS_H
#define SCENARIO_FIELDS_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

typedef enum {
    SF_DOUBLE,   /* double: stored = JSON value x scale */
    SF_PS,       /* sim_ps from a JSON time in ns (fractions allowed, 1 ps resolution) */
    SF_UNSIGNED, /* unsigned, whole */
    SF_U8,       /* uint8_t, whole */
    SF_U32,      /* uint32_t, whole */
    SF_I64,      /* int64_t, whole (within what a double holds exactly: lo, hi) */
    SF_U64,      /* uint64_t, whole, any value (0 .. 2^64 - 1) */
    SF_BOOL,     /* bool from true / false */
    SF_NOT,      /* bool from true / false, stored inverted */
    SF_CHOICE,   /* a string, one of names[]: its index, into an int (enum) or a bool (size) */
    SF_OBJECT,   /* an object: the table sub over the struct at offset (and at offset2) */
    SF_ARRAY,    /* lo..hi objects, each the table sub over elements elem_size apart
                    from offset; their number (unsigned) at count_offset */
    SF_SET,      /* an array of whole numbers 0..hi: bool[v] at offset set for each */
    SF_REGS,     /* regfile: {"0x44": value, "bank2:0x10": value, ...} */
    SF_REGFLAGS, /* regfile: ["0x44", ...], flags |= (uint8_t)hi at each */
    SF_REGBANKS, /* regfile: its bank count 0..hi (0: 1), read before the registers */
    SF_INDEXED,  /* an array of objects, each an index and a value (the table sub over
                    struct sf_indexed): double[index] at offset = value */
} sf_kind;

typedef struct sf_table sf_table;

/* An SF_INDEXED element as read. */
struct sf_indexed {
    unsigned index;
    double value;
};

typedef struct {
    const char *name; /* JSON key; NULL ends a table */
    sf_kind kind;
    size_t offset;            /* in the struct the table describes */
    double scale;             /* SF_DOUBLE: stored value per JSON unit */
    double lo, hi;            /* numbers: range in JSON units, both ends included; SF_ARRAY:
                                 the element count; SF_SET, SF_REGBANKS: hi the largest */
    size_t size;              /* SF_CHOICE: sizeof the member (an enum or a bool) */
    const char *const *names; /* SF_CHOICE: the strings, NULL-ended */
    const char *expect;       /* the message for a value of the wrong kind, if not the usual */
    const sf_table *sub;      /* SF_OBJECT, SF_ARRAY */
    size_t offset2;           /* SF_OBJECT: also stored there (0: nowhere else) */
    size_t elem_size;         /* SF_ARRAY */
    size_t count_offset;      /* SF_ARRAY */
    bool required;            /* must be given (in an array's element objects) */
    bool unchecked;           /* read from JSON only: its values are checked where they land */
} sf_field;

/* A JSON object: its fields, and what relates them (run by
 * sf_check_object once every field is in range). */
struct sf_table {
    const sf_field *fields;
    /* Relations among the fields: 0, or -1 with a message that starts with
     * the field it names ("position_bits: ..."), the path to the object
     * not included. NULL: none. */
    int (*check)(const void *obj, char *err, size_t errlen);
    /* Sets an array element's defaults before it is read. NULL: none. */
    void (*init)(void *obj);
    /* For a missing required field ("missing (the pair's two slaves)"). */
    const char *missing;
};

/* line_params ("line", "ma_line", "sl_line") */
extern const sf_table sf_line;
/* scenario_checks ("checks") */
extern const sf_table sf_checks;
/* scenario: the top level ("profile", "protocol" and the models' objects
 * are read beside it: scenario_json.c, slave_model.h) */
extern const sf_table sf_scenario;

/* The field called name in table t, or NULL. */
const sf_field *sf_find(const sf_table *t, const char *name);

/* Whether kind k is a number, and whether it holds whole numbers. */
bool sf_number(sf_kind k);
bool sf_whole(sf_kind k);

/* Checks a number in JSON units: finite, in range, whole where the kind
 * needs it. Returns 0, or -1 with "9000000000 out of range 0..1000000"
 * (no field name) in err. */
int sf_check(const sf_field *f, double v, char *err, size_t errlen);

/* Stores a checked number (JSON units) into the struct at obj. SF_U64
 * fields take their exact value from u (v is ignored). */
void sf_store(const sf_field *f, void *obj, double v, uint64_t u);

/* Checks every field of table t in the struct at obj (numbers in range,
 * choices among their names, nested objects and arrays the same way),
 * then t's relations; a message starts with prefix and the path of the
 * field ("ma_line.length_m: ...", "biss.slaves[1].id: ..."). */
int sf_check_object(const sf_table *t, const void *obj, const char *prefix, char *err,
                    size_t errlen);

/* A number as the messages print it: whole numbers in full, others %g. */
void sf_format(double v, char *buf, size_t len);

/* The ranges' limits the tables share. The longest delays: 10 us for
 * anything a transceiver or a slave output adds, 1 ms for a slave's busy
 * and timeout times (the longest the firmware waits, BISS_MAX_HALF
 * clocks, is 10 ms at 97.7 kHz): each frame then ends within milliseconds
 * of simulated time. */
#define SF_MAX_EDGE_NS  1e4
#define SF_MAX_FRAME_NS 1e6
/* Counts per second: times the longest simulated time (PRU_MAX_CYCLE,
 * 2.3e6 s) this stays below 2^63. */
#define SF_MAX_SPEED 1e12
#define SF_U64_MAX   18446744073709551615.0
/* Frame numbers as biss-sim counts them (1 = the first), in an unsigned. */
#define SF_MAX_FRAME_NO 4294967295.0
/* Counts a frame: every whole number a JSON number holds exactly. */
#define SF_MAX_STEP 9007199254740991.0

/* Field initialisers for the tables: F for a number (JSON unit `scale`,
 * range lo..hi), and the others by kind. */
#define SF_FIELD(nm, knd, type, member, sc, l, h)                                                  \
    { .name = nm, .kind = knd, .offset = offsetof(type, member), .scale = sc, .lo = l, .hi = h }
#define SF_FLAG(nm, knd, type, member)                                                             \
    { .name = nm, .kind = knd, .offset = offsetof(type, member) }
#define SF_CHOOSE(nm, type, member, nms)                                                           \
    {                                                                                              \
        .name = nm, .kind = SF_CHOICE, .offset = offsetof(type, member),                           \
        .size = sizeof(((type *)0)->member), .names = nms                                          \
    }
#define SF_END                                                                                     \
    { .name = NULL }

#endif
