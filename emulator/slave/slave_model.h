/* slave_model.h - an encoder model behind the link: one table of
 * operations per protocol, so that the link, the scenario reader and the
 * bench reach every model the same way.
 *
 * A model is one file that fills a struct slave_model (its configuration's
 * fields and relations, its life cycle, its answer to MA edges, its frame
 * records and what they mean to a master) and one row in the table of
 * models (slave_models.c); a model kept outside that table (a test's)
 * joins it at run time with slave_model_register(). The scenario names
 * its model (JSON "protocol": the model's name) and holds its
 * configuration: the JSON object of the same name, read and checked by the
 * model's tables (scenario_fields.h).
 *
 * The models here: BiSS-C (biss_model.c, the chain of biss_slave.h) and
 * SSI (ssi_model.c, ssi_slave.h). */
#ifndef SLAVE_MODEL_H
#define SLAVE_MODEL_H

#include "biss_slave.h"
#include "event_queue.h"
#include "scenario_fields.h"
#include "sim_time.h"
#include "slave_status.h"
#include "ssi_slave.h"
#include "waveform.h"

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

/* The room the link keeps for a model's state (state_size at most its
 * size): the table's models' states, in place. */
typedef union {
    slave_status status;
    biss_slave biss;
    ssi_slave ssi;
} slave_state_room;

/* Words (slaves) a frame of any model carries at most. */
#define SLAVE_MAX_WORDS BISS_MAX_SLAVES

/* One slave's word as it goes over the wire, as a master must be set up to
 * read it (the bench turns it into the master's configuration): the
 * position MSB first, fill zeros, nE, nW, a life counter, then a CRC over
 * all of them; or an SSI word (position only, from the first rising edge:
 * no ACK, start bit or CDS). */
typedef struct {
    unsigned pos_bits, fill_bits, lc_bits;
    bool has_err, has_warn;
    uint32_t crc_poly, crc_start; /* crc_poly with its top term; 0: no CRC */
    bool ssi, gray;               /* an SSI word; Gray-coded */
    bool ew_active;               /* the model drives nE or nW active (error, warning) */
} slave_word;

/* One frame in every model's terms. */
typedef struct {
    uint64_t frame;     /* the model's number, from 0 */
    sim_ps start_ps;    /* its first MA edge at the slave */
    sim_ps end_ps;      /* its end (timeout), 0 while open */
    sim_ps latch_ps;    /* the position's instant, 0 none */
    sim_ps last_bit_ps; /* the rise that put its last bit on SL, 0 none */
    sim_ps data_ps;     /* the rise of its first data bit (BiSS-C: the start bit), 0 none */
    unsigned nwords;
    struct {
        uint64_t position; /* binary */
        uint64_t code;     /* the position as sent (Gray when the word is) */
        int nE, nW;        /* as sent: 1 = no error / warning; -1 absent */
        uint32_t lc, crc;  /* life counter; CRC as sent (inverted) */
    } word[SLAVE_MAX_WORDS];
} slave_frame;

/* A named span of SL at the slave, for the scope picture. */
typedef struct {
    sim_ps t0, t1;
    char text[16];
} slave_label;

/* Labels a frame has at most. */
#define SLAVE_LABELS_MAX 700

typedef struct slave_model {
    /* The scenario's "protocol", and the key of its configuration object. */
    const char *name;
    const char *title; /* for people: "BiSS-C", "SSI" */

    /* ---- configuration ---- */
    size_t cfg_offset;   /* where in struct scenario it lives */
    size_t cfg_size;     /* its size */
    const sf_table *cfg; /* its fields, ranges and relations */
    void (*cfg_default)(void *cfg);
    /* A BiSS-C chain (frames with ACK, start and CDS, slaves with IDs and
     * control communication): its configuration. NULL: not BiSS-C. */
    const biss_chain_cfg *(*chain)(const void *cfg);

    /* ---- the model at work ---- */
    size_t state_size; /* its state, starting with a slave_status (slave_state_room at most) */
    /* cfg has passed the model's checks; the model starts idle (SL high,
     * MA assumed high) at eq_now(q) and sends its SL edges to out. */
    void (*init)(void *m, const void *cfg, event_queue *q, sim_edge_sink out);
    /* Every MA edge as it arrives at the slave, in time order. */
    void (*ma_edge)(void *m, sim_ps t, int level);
    /* Frame n's record, record_size bytes: closed and still kept, or the
     * open one (n == frames while in a frame); NULL otherwise. */
    size_t record_size;
    const void *(*record)(const void *m, uint64_t n);
    /* A record in every model's terms: f's words past nwords are left as
     * they were. */
    void (*frame)(const void *cfg, const void *rec, slave_frame *f);
    /* A record's end (frame's end_ps) alone: the bench asks for it on
     * every frame's first MA fall, where frame() would cost a frame. */
    sim_ps (*end)(const void *rec);

    /* ---- what a master needs to know of a configuration ---- */
    sim_ps (*out_delay)(const void *cfg); /* MA edge at the slave to SL edge */
    /* How long MA must rest after a frame's last clock (period_ps apart)
     * for the frame to end: the timeout, the monoflop time. */
    sim_ps (*timeout)(const void *cfg, sim_ps period_ps);
    /* Rising edges a whole frame takes (its bits, its ACK, busy time at
     * this period), before the round trip. */
    unsigned (*clocks)(const void *cfg, sim_ps period_ps);
    /* Each slave's word (w has SLAVE_MAX_WORDS); returns how many. */
    unsigned (*words)(const void *cfg, slave_word *w);
    /* The names of a frame's bits on SL at the slave: from its record and
     * MA at the slave (rising edges clock the bits). Returns how many. */
    size_t (*labels)(const void *cfg, const void *rec, waveform *ma_slave, slave_label *out,
                     size_t max);
    /* The note of the word a master read from a non-BiSS-C slave, for the
     * scope picture ("as sent (binary or Gray)"). */
    const char *word_note;
} slave_model;

/* For a model's labels: the rising MA edges at the slave from `from` to
 * `to` (at most max), each plus delay, into t: the times at which SL takes
 * each next bit. Returns how many. */
size_t slave_bit_starts(waveform *ma_slave, sim_ps from, sim_ps to, sim_ps delay, sim_ps *t,
                        size_t max);

extern const slave_model slave_model_biss;
extern const slave_model slave_model_ssi;

/* The models: the table's, then those registered, in order; NULL past
 * the last. */
const slave_model *slave_model_at(size_t i);
/* The model called name, or NULL. */
const slave_model *slave_model_find(const char *name);
/* Adds a model outside the table (a test's), whose configuration lives in
 * the scenario's ext (cfg_offset offsetof(scenario, ext), cfg_size at most
 * SCENARIO_EXT_BYTES) and whose state fits the link's room for it
 * (slave_state_room). Returns 0, or -1 (table full, name taken, or its
 * configuration or state does not fit). */
int slave_model_register(const slave_model *m);

#endif
