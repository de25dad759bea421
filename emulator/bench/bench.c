/* bench.c - the PRU core wired to the link, and what the bench measures
 * on the way (see bench.h). */
#include "bench.h"

#include "frame_marks.h"
#include "pruss.h"
#include "vcd.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* MA edges in flight between the master pin and the slave. A cable of any
 * length the models allow holds far fewer. */
#define MA_RING 4096

/* VCD wires: the four pins (by link_pin), then the frame wire */
static const char *const pin_names[4] = {"MA_master", "SL_master", "MA_slave", "SL_slave"};
#define VCD_FRAME_WIRE 4

enum capture_state { CAP_OFF, CAP_ARMED, CAP_ON, CAP_DONE };

/* The fields of the per-edge work first, the configuration (40 KB) and
 * ma_times (32 KB) last, so those share cache lines and pages. */
struct bench {
    struct pru_core *core;
    unsigned ma_bit; /* cfg.ma_bit, here with the rest */
    /* a core of a PRU-ICSS (NULL: a core alone), owned by this bench or
     * by its peer, the bench on the other PRU (NULL: none) */
    struct pru_icss *icss;
    bool owns_icss;
    struct bench *peer;
    /* bench_new_loop: PRU1 is the slave end, MA on its R31 bit enc_ma_bit,
     * SL on its R30 bit 0 (NULL: a slave model) */
    struct pru_core *encoder;
    unsigned enc_ma_bit;

    uint64_t prev_frame; /* frame number + 1 of the previous in-frame edge, 0 none */
    int64_t prev_t;
    int64_t frame_start_t;
    bool have_frame_start;
    int64_t pending_half;   /* a half period ending in a falling edge, 0 none */
    uint64_t current_frame; /* slave frame number of the last frame started, or UINT64_MAX */

    struct vcd_writer vcd;
    bool vcd_on;
    sim_ps vcd_ma_lag;     /* the longest an MA edge takes to the slave, with margin */
    bool vcd_frame_open;   /* the frame wire is high */
    uint64_t vcd_frame;    /* the slave's number of that frame */
    sim_ps vcd_frame_last; /* master time of its last MA edge so far */
    sim_ps vcd_frame_half; /* and the time from the edge before it, 0 none */

    enum capture_state cap_state;
    uint64_t cap_frame;
    waveform cap[4];
    sim_ps cap_t0, cap_last; /* first and last MA edge of the frame, at the master */
    sim_ps cap_end;          /* when the frame was over on every pin */
    void *cap_record;        /* the frame's record, kept (the model's ring moves on), or NULL */

    struct frame_marks marks; /* each frame's first MA fall at the master pin (marks_scan) */
    uint64_t frame_limit;     /* frames from this number on are not measured */
    sim_ps forgot_at;         /* when pin history was last dropped */
    struct bench_stats st;
    bool ahead_overrun;          /* bench_ahead_overrun() */
    struct sl_tape_writer *tape; /* SL at the master recorded (bench_tape_record), or NULL */

    link_model link; /* its per-edge state first */
    /* master-side MA edge times by edge number modulo MA_RING, so an edge
     * the slave takes as part of a frame is timed where the PRU drove it */
    int64_t ma_times[MA_RING];
    struct bench_config cfg;
};

void bench_config_default(struct bench_config *c) {
    memset(c, 0, sizeof(*c));
    c->soc = PRU_SOC_AM335X;
    pru_params_default(&c->pru);
    c->ma_bit = 1;
    profile_by_name("generic", &c->link);
}

/* ---- frame bookkeeping -------------------------------------------------- */

static uint64_t slave_frames(const struct bench *b) {
    return link_frames(&b->link);
}

static void min_max(int64_t v, uint64_t n, int64_t *lo, int64_t *hi) {
    if (n == 0 || v < *lo) {
        *lo = v;
    }
    if (n == 0 || v > *hi) {
        *hi = v;
    }
}

static void count_half_period(struct bench_stats *st, int64_t h) {
    min_max(h, st->half_periods, &st->half_min_ps, &st->half_max_ps);
    st->half_periods++;
}

/* The half period up to an edge at t of a frame under way (the last edge
 * at prev_t): counted at a rise, with the one before it that a fall left
 * pending; a fall's waits in *pending for the next rise. */
static inline void count_continuing(struct bench_stats *st, int64_t *pending, int64_t prev_t,
                                    int64_t t, int level) {
    if (*pending > 0) {
        count_half_period(st, *pending);
    }
    *pending = 0;
    if (level) {
        count_half_period(st, t - prev_t);
    } else {
        *pending = t - prev_t;
    }
}

/* An MA edge the slave took as part of frame `frame`, timed at the master.
 * A half period that ends in a falling edge counts once the next rising
 * edge comes in the same frame: a frame's last falling edge is the CDM
 * (MA low through the timeout), not a clock. */
static void account_edge(struct bench *b, uint64_t frame, int64_t t, int level) {
    struct bench_stats *st = &b->st;
    if (b->prev_frame == frame + 1) {
        count_continuing(st, &b->pending_half, b->prev_t, t, level);
    } else {
        b->pending_half = 0;
        st->frames_started++;
        if (b->have_frame_start) {
            int64_t p = t - b->frame_start_t;
            min_max(p, st->periods, &st->period_min_ps, &st->period_max_ps);
            st->period_sum_ps += (double)p;
            st->periods++;
        }
        b->frame_start_t = t;
        b->have_frame_start = true;
        if (b->cap_state == CAP_ON && frame == b->cap_frame) {
            b->cap_t0 = t;
        }
    }
    if (b->cap_state == CAP_ON && frame == b->cap_frame) {
        b->cap_last = t;
    }
    b->prev_frame = frame + 1;
    b->prev_t = t;
}

static void vcd_frame_edge(struct bench *b, uint64_t frame, sim_ps t_master);

/* Whether the ring still holds the master's time of the idx-th edge to
 * reach the slave: idx < ma_edges_master && ma_edges_master - idx <=
 * MA_RING, in one unsigned compare (idx >= ma_edges_master wraps to a
 * large value). */
static inline bool ring_holds(const struct bench *b, uint64_t idx) {
    return b->st.ma_edges_master - idx - 1 < MA_RING;
}

/* In line in both of on_pin()'s paths: the one without the VCD (vcd
 * false) then makes no call and saves no registers. */
static inline __attribute__((always_inline)) void
ma_edge_measured(struct bench *b, int level, bool active, uint64_t frame, bool vcd) {
    uint64_t idx = b->st.ma_edges_slave++;
    bool timed = ring_holds(b, idx);
    if (active) {
        b->current_frame = frame;
    }
    if (vcd && timed && active) {
        vcd_frame_edge(b, frame, b->ma_times[idx % MA_RING]);
    }
    if (timed && active && frame < b->frame_limit) {
        account_edge(b, frame, b->ma_times[idx % MA_RING], level);
    } else {
        b->prev_frame = 0;
    }
}

static inline __attribute__((always_inline)) void ma_reached_slave(struct bench *b, int level,
                                                                   bool vcd) {
    /* the open frame's number, when active */
    ma_edge_measured(b, level, link_in_frame(&b->link), slave_frames(b), vcd);
}

/* Whether account_edge() would take the next edge to reach the slave, of
 * the open frame `frame`, as one more edge of a frame under way: the
 * frame measured, the edge timed, no capture in it. */
static bool continues_frame(const struct bench *b, uint64_t frame) {
    return frame < b->frame_limit && b->prev_frame == frame + 1 &&
           ring_holds(b, b->st.ma_edges_slave) && b->cap_state != CAP_ON;
}

/* The MA edges taken ahead that the link counted (link_batch_ahead()),
 * measured as each would have been when it reached the slave: inside the
 * frame they were counted in, their levels alternating. Before anything
 * looks at the measurements or the link tells of another pin. */
static __attribute__((noinline)) void take_ahead(struct bench *b) {
    uint64_t frame;
    int level;
    uint64_t n = link_take_ahead(&b->link, &frame, &level);
    /* ma_edge_measured() for each, until they continue a frame measured
     * under the limit (then so do the rest: the ring holds later edges
     * longer, the limit and the capture stay) */
    for (; n && !continues_frame(b, frame); n--, level ^= 1) {
        ma_edge_measured(b, level, true, frame, false);
    }
    if (!n) {
        return;
    }
    /* then account_edge()'s half periods of a frame under way, in a loop */
    struct bench_stats *st = &b->st;
    uint64_t idx = st->ma_edges_slave;
    int64_t prev_t = b->prev_t, pending = b->pending_half;
    st->ma_edges_slave += n;
    b->current_frame = frame; /* as it is already: set with prev_frame */
    for (; n; n--, level ^= 1, idx++) {
        int64_t t = b->ma_times[idx % MA_RING];
        count_continuing(st, &pending, prev_t, t, level);
        prev_t = t;
    }
    b->prev_t = prev_t;
    b->pending_half = pending;
}

static inline void ahead_taken(struct bench *b) {
    if (b->link.batch_n) {
        take_ahead(b);
    }
}

/* ---- the VCD's frame wire ---------------------------------------------- */

/* High from a frame's first MA edge at the master pin (the same time
 * stamp) to one half period after its last (where the next clock edge
 * would have come), so a decoder that takes it as a chip select sees every
 * clock edge of the frame inside it. Which edges belong to a frame is
 * known when they reach the slave (and which was the last when the slave
 * closes the frame), so the writer holds back what comes after the edges
 * in flight and after the open frame's last edge (vcd.h). */
static void vcd_frame_close(struct bench *b) {
    vcd_change(&b->vcd, b->vcd_frame_last + b->vcd_frame_half, VCD_FRAME_WIRE, 0);
    b->vcd_frame_open = false;
}

static void vcd_frame_edge(struct bench *b, uint64_t frame, sim_ps t_master) {
    if (b->vcd_frame_open && b->vcd_frame != frame) {
        vcd_frame_close(b);
    }
    if (!b->vcd_frame_open) {
        vcd_change(&b->vcd, t_master, VCD_FRAME_WIRE, 1);
        b->vcd_frame_open = true;
        b->vcd_frame = frame;
        b->vcd_frame_half = 0;
    } else {
        b->vcd_frame_half = t_master - b->vcd_frame_last;
    }
    b->vcd_frame_last = t_master;
}

/* Closes the frame wire once the slave closed the frame, and writes what
 * can no longer be preceded by a frame wire change. */
static void vcd_frame_update(struct bench *b, sim_ps now) {
    if (b->vcd_frame_open && link_frames(&b->link) > b->vcd_frame) {
        vcd_frame_close(b);
    }
    sim_ps hold = now - b->vcd_ma_lag;
    if (b->vcd_frame_open && b->vcd_frame_last < hold) {
        hold = b->vcd_frame_last;
    }
    vcd_flush_before(&b->vcd, hold);
}

/* ---- scope capture ------------------------------------------------------ */

/* Time after which frame cap_frame is over on every pin, -1 if unknown:
 * its close at the slave plus one round trip and a margin. */
static sim_ps capture_end(const struct bench *b) {
    sim_ps end = link_frame_end(&b->link, b->cap_frame);
    return end < 0 ? -1 : end + (sim_ps)bench_round_trip_ps(b) + 200 * SIM_PS_PER_NS;
}

/* Copies the captured frame's record, which capture_end found. */
static void capture_keep_record(struct bench *b) {
    size_t n = b->link.model->record_size;
    b->cap_record = malloc(n);
    if (b->cap_record) {
        memcpy(b->cap_record, link_record(&b->link, b->cap_frame), n);
    }
}

/* on_pin has work for every pin while the VCD is written or a capture is
 * armed or running, otherwise for MA at the slave only (the measurements):
 * the link calls it for those. */
static void observe_pins_update(struct bench *b) {
    bool all = b->vcd_on || b->cap_state == CAP_ARMED || b->cap_state == CAP_ON;
    link_observe_pins(&b->link, all ? 0xfu : 1u << LINK_MA_SLAVE);
}

/* Capturing runs from the close of frame k-1 until frame k is over. */
static void capture_update(struct bench *b, sim_ps t) {
    if (b->cap_state == CAP_ARMED && slave_frames(b) == b->cap_frame) {
        for (int i = 0; i < 4; i++) {
            waveform_init(&b->cap[i], waveform_level_at(link_pin_record(&b->link, (link_pin)i), t));
        }
        b->cap_state = CAP_ON;
        observe_pins_update(b);
    } else if (b->cap_state == CAP_ON && slave_frames(b) > b->cap_frame) {
        sim_ps end = capture_end(b);
        if (end >= 0 && t > end) {
            capture_keep_record(b);
            b->cap_end = end;
            b->cap_state = CAP_DONE;
            observe_pins_update(b);
        }
    }
}

static void capture_free(struct bench *b) {
    if (b->cap_state >= CAP_ON) {
        for (int i = 0; i < 4; i++) {
            waveform_free(&b->cap[i]);
        }
    }
    free(b->cap_record);
    b->cap_record = NULL;
    b->cap_state = CAP_OFF;
    observe_pins_update(b);
}

/* ---- pins --------------------------------------------------------------- */

/* on_pin() with the VCD or a capture under way (any pin). */
static __attribute__((noinline)) void on_pin_watched(struct bench *b, link_pin pin, sim_ps t,
                                                     int level) {
    if (b->vcd_on) {
        vcd_change(&b->vcd, t, (int)pin, level);
    }
    if (pin == LINK_MA_SLAVE) {
        ma_reached_slave(b, level, b->vcd_on);
    }
    if (b->vcd_on) {
        vcd_frame_update(b, t);
    }
    if (b->cap_state != CAP_OFF) {
        capture_update(b, t);
        if (b->cap_state == CAP_ON) {
            waveform_append(&b->cap[pin], t, level);
        }
    }
}

/* Without the VCD and a capture the link calls this for MA at the slave
 * only (observe_pins_update), and the measurements are all there is to
 * do: that path is kept free of the calls the others make, so it needs no
 * saved registers. */
static void on_pin(void *ctx, link_pin pin, sim_ps t, int level) {
    struct bench *b = ctx;
    ahead_taken(b);
    if (!b->vcd_on && b->cap_state == CAP_OFF && pin == LINK_MA_SLAVE) {
        ma_reached_slave(b, level, false);
        return;
    }
    on_pin_watched(b, pin, t, level);
}

static uint32_t pins_inputs_at(void *ctx, int64_t t) {
    struct bench *b = ctx;
    /* SL on R31 bit 0; the other inputs are not connected and read 0 */
    return (uint32_t)link_sl(&b->link, t);
}

/* The next SL change after t: one already recorded (the link may have run
 * ahead of t: an MA edge makes it catch up with the core), or whatever the
 * pending events may bring. */
static int64_t pins_next_change(void *ctx, int64_t t) {
    struct bench *b = ctx;
    sim_ps recorded = waveform_next_after(&b->link.sl_master, t);
    sim_ps pending = link_next_sl_change(&b->link);
    return recorded < pending ? recorded : pending;
}

static uint32_t pins_inputs_run(void *ctx, int64_t t, int64_t *next) {
    struct bench *b = ctx;
    return (uint32_t)link_sl_run(&b->link, t, next);
}

static void pins_outputs(void *ctx, int64_t t, uint32_t r30) {
    struct bench *b = ctx;
    int level = (int)((r30 >> b->ma_bit) & 1u);
    if (level == waveform_last_level(&b->link.ma_master)) {
        return;
    }
    b->ma_times[b->st.ma_edges_master % MA_RING] = t;
    b->st.ma_edges_master++;
    link_ma(&b->link, t, level);
}

/* PRU1 as the slave end (bench_new_loop): MA at the slave pin on its R31
 * bit enc_ma_bit, its R30 bit 0 the SL pin. */
static uint32_t enc_inputs_at(void *ctx, int64_t t) {
    struct bench *b = ctx;
    sim_ps next;
    return (uint32_t)link_ma_at_slave(&b->link, t, &next) << b->enc_ma_bit;
}

static int64_t enc_next_change(void *ctx, int64_t t) {
    struct bench *b = ctx;
    sim_ps next;
    link_ma_at_slave(&b->link, t, &next);
    return next;
}

static uint32_t enc_inputs_run(void *ctx, int64_t t, int64_t *next) {
    struct bench *b = ctx;
    return (uint32_t)link_ma_at_slave(&b->link, t, next) << b->enc_ma_bit;
}

static void enc_outputs(void *ctx, int64_t t, uint32_t r30) {
    struct bench *b = ctx;
    link_sl_at_slave(&b->link, t, (int)(r30 & 1u));
}

/* ---- life cycle --------------------------------------------------------- */

/* A bench on core (a core alone when icss is NULL); it owns what it is
 * given unless a peer does. */
static struct bench *bench_on(const struct bench_config *cfg, struct pru_core *core,
                              struct pru_icss *icss, char *err, size_t errlen) {
    if (cfg->ma_bit > 15) {
        snprintf(err, errlen, "ma_bit %u: MA must be an R30 output pin, 0..15", cfg->ma_bit);
        return NULL;
    }
    struct bench *b = calloc(1, sizeof(*b));
    if (!b) {
        snprintf(err, errlen, "out of memory");
        return NULL;
    }
    b->cfg = *cfg;
    b->ma_bit = cfg->ma_bit;
    b->cfg.pru_index = pru_core_index(core);
    b->core = core;
    b->icss = icss;
    b->frame_limit = UINT64_MAX;
    b->current_frame = UINT64_MAX;
    frame_marks_init(&b->marks);
    if (link_init(&b->link, &cfg->link, err, errlen) != 0) {
        free(b);
        return NULL;
    }
    link_set_observer(&b->link, on_pin, b);
    /* MA at both ends and SL at the slave are only ever asked for their
     * level at the queue's time (where a capture or the VCD starts, on_pin
     * at an edge's time or eq_now()): their last level, so they keep no
     * edges (link_keep_history); SL at the master is read back in time */
    link_keep_history(&b->link, 1u << LINK_SL_MASTER);
    observe_pins_update(b);
    link_set_sl_reach(&b->link, !cfg->no_sl_reach);
    link_set_line_settled(&b->link, !cfg->no_line_settled);
    link_set_slave_quick(&b->link, !cfg->no_slave_quick);
    link_set_ma_ahead(&b->link, cfg->ma_ahead && !icss, PRU_PS_PER_CYCLE);
    /* their measurements in batches (take_ahead), half the ring at most */
    link_batch_ahead(&b->link, cfg->no_ahead_batch ? 0 : MA_RING / 2);
    struct pru_pins pins = {.ctx = b,
                            .inputs_at = pins_inputs_at,
                            .next_input_change = pins_next_change,
                            .outputs_changed = pins_outputs,
                            .inputs_run = pins_inputs_run};
    pru_set_pins(b->core, &pins);
    return b;
}

struct bench *bench_new(const struct bench_config *cfg, char *err, size_t errlen) {
    if (cfg->pru_index > 1) {
        snprintf(err, errlen, "pru %u: a PRU-ICSS has PRU 0 and PRU 1", cfg->pru_index);
        return NULL;
    }
    struct pru_icss *icss = NULL;
    struct pru_core *core;
    if (cfg->pru_index == 1) {
        icss = pru_icss_new(cfg->soc, &cfg->pru);
        core = icss ? pru_icss_core(icss, 1) : NULL;
    } else {
        core = pru_core_new(cfg->soc, &cfg->pru);
    }
    if (!core) {
        snprintf(err, errlen, "out of memory");
        return NULL;
    }
    struct bench *b = bench_on(cfg, core, icss, err, errlen);
    if (!b) {
        if (icss) {
            pru_icss_free(icss);
        } else {
            pru_core_free(core);
        }
        return NULL;
    }
    b->owns_icss = icss != NULL;
    return b;
}

int bench_new_pair(const struct bench_config cfg[2], struct bench *b[2], char *err, size_t errlen) {
    b[0] = b[1] = NULL;
    struct pru_icss *icss = pru_icss_new(cfg[0].soc, &cfg[0].pru);
    if (!icss) {
        snprintf(err, errlen, "out of memory");
        return -1;
    }
    struct bench_config c1 = cfg[1];
    c1.soc = cfg[0].soc;
    c1.pru = cfg[0].pru; /* the PRU-ICSS's parameters */
    b[0] = bench_on(&cfg[0], pru_icss_core(icss, 0), icss, err, errlen);
    b[1] = b[0] ? bench_on(&c1, pru_icss_core(icss, 1), icss, err, errlen) : NULL;
    if (!b[1]) {
        bench_free(b[0]);
        pru_icss_free(icss);
        b[0] = NULL;
        return -1;
    }
    b[0]->owns_icss = true;
    b[0]->peer = b[1];
    b[1]->peer = b[0];
    return 0;
}

struct bench *bench_new_loop(const struct bench_config *cfg, char *err, size_t errlen) {
    if (cfg->link.model != &slave_model_biss) {
        snprintf(err, errlen,
                 "the encoder firmware is a BiSS-C slave: not a scenario of another protocol");
        return NULL;
    }
    struct pru_icss *icss = pru_icss_new(cfg->soc, &cfg->pru);
    if (!icss) {
        snprintf(err, errlen, "out of memory");
        return NULL;
    }
    struct bench *b = bench_on(cfg, pru_icss_core(icss, 0), icss, err, errlen);
    if (!b) {
        pru_icss_free(icss);
        return NULL;
    }
    b->owns_icss = true;
    b->encoder = pru_icss_core(icss, 1);
    pru_icss_lockstep(icss); /* PRU0's MA is PRU1's input */
    b->enc_ma_bit = 1;
    link_set_external_slave(&b->link, 1);
    struct pru_pins pins = {.ctx = b,
                            .inputs_at = enc_inputs_at,
                            .next_input_change = enc_next_change,
                            .outputs_changed = enc_outputs,
                            .inputs_run = enc_inputs_run};
    pru_set_pins(b->encoder, &pins);
    return b;
}

struct pru_core *bench_encoder_core(struct bench *b) {
    return b->encoder;
}

int bench_set_encoder_ma_bit(struct bench *b, unsigned bit) {
    if (!b->encoder || bit > 29) {
        return -1;
    }
    b->enc_ma_bit = bit;
    return 0;
}

void bench_free(struct bench *b) {
    if (!b) {
        return;
    }
    capture_free(b);
    bench_close_vcd(b);
    if (b->tape && b->tape->f) {
        fclose(b->tape->f); /* not finished: the tape has no end, and is refused */
    }
    free(b->tape);
    if (b->peer) {
        b->peer->peer = NULL;
    }
    if (b->owns_icss) {
        pru_icss_free(b->icss);
    } else if (!b->icss) {
        pru_core_free(b->core);
    }
    link_free(&b->link);
    free(b);
}

int bench_open_vcd(struct bench *b, const char *path, int64_t unit_ps) {
    bench_close_vcd(b);
    if (!vcd_unit_valid(unit_ps)) {
        snprintf(b->vcd.err, sizeof b->vcd.err, "%s: timescale %lld ps: not 1, 10, 100 or 1000",
                 path, (long long)unit_ps);
        errno = EINVAL;
        return -1;
    }
    if (vcd_open(&b->vcd, path, unit_ps) != 0) {
        return -1;
    }
    for (int i = 0; i < 4; i++) {
        vcd_add_wire(&b->vcd, pin_names[i]);
    }
    vcd_add_wire(&b->vcd, "frame");
    const line_params *ma = &b->link.sc.ma_line;
    b->vcd_ma_lag = (sim_ps)(line_nominal_delay_ps(ma) + 10 * ma->jitter_rms_ps) + SIM_PS_PER_US;
    b->vcd_frame_open = false;
    ahead_taken(b);
    b->vcd_on = true;
    observe_pins_update(b);
    sim_ps now = eq_now(&b->link.q);
    for (int i = 0; i < 4; i++) {
        vcd_change(&b->vcd, now, i, waveform_level_at(link_pin_record(&b->link, (link_pin)i), now));
    }
    vcd_change(&b->vcd, now, VCD_FRAME_WIRE, 0);
    return 0;
}

const char *bench_vcd_error(const struct bench *b) {
    return vcd_error(&b->vcd);
}

int bench_close_vcd(struct bench *b) {
    if (!b->vcd_on) {
        return 0;
    }
    b->vcd_on = false;
    observe_pins_update(b);
    return vcd_close(&b->vcd, eq_now(&b->link.q));
}

struct pru_core *bench_core(struct bench *b) {
    return b->core;
}

link_model *bench_link(struct bench *b) {
    return &b->link;
}

int bench_start_image(struct bench *b, const void *image, size_t bytes) {
    if (pru_load_image(b->core, image, bytes) != 0) {
        return -1;
    }
    pru_start(b->core);
    return 0;
}

/* The link catches up with the core and drops old pin history. */
static void bench_caught_up(struct bench *b);

/* The frame marks of the MA edges driven since the last look (the ring
 * holds MA_RING of them: bench_caught_up looks after every run step once
 * an eighth of them has come). */
static void marks_scan(struct bench *b) {
    struct frame_marks_edges e = {b->ma_times, MA_RING, b->st.ma_edges_master};
    frame_marks_scan(&b->marks, &b->st, &e, &b->link, b->core, b->cfg.pru.gpo_delay_ps,
                     b->frame_limit);
}

enum pru_stop bench_run_until(struct bench *b, int64_t t_ps) {
    if (b->icss) { /* both PRUs together; each bench's link follows its core */
        enum pru_stop why = pru_icss_run_until_time(b->icss, t_ps);
        bench_caught_up(b);
        if (b->peer) {
            bench_caught_up(b->peer);
        }
        return why;
    }
    link_set_ahead_until(&b->link, t_ps); /* the host looks at the link between runs */
    enum pru_stop why = pru_run_until_time(b->core, t_ps);
    bench_caught_up(b);
    return why;
}

bool bench_ahead_overrun(const struct bench *b) {
    return b->ahead_overrun;
}

static void bench_caught_up(struct bench *b) {
    /* the link catches up with the core (a halted core leaves it behind) */
    int64_t now = pru_time_ps(b->core);
    link_sl(&b->link, now);
    ahead_taken(b);
    b->ahead_overrun = b->ahead_overrun || link_ahead_beyond(&b->link, now);
    if (b->vcd_on) {
        vcd_frame_update(b, now);
    }
    if (b->tape) { /* before its history is dropped */
        sl_tape_append(b->tape, &b->link.sl_master);
    }
    /* SL at the master older than a millisecond is never looked at again;
     * it is dropped every 16 ms: each drop moves the millisecond that is
     * kept, so dropping every millisecond cost 2 % of the run */
    bool forget = now - b->forgot_at > 16 * SIM_PS_PER_MS;
    /* the frame marks in batches, an eighth of the edge ring (the slave's
     * 256 records hold every frame of it), and before SL's history is
     * dropped: restarts look back at it */
    if (forget || b->st.ma_edges_master - b->marks.next >= MA_RING / 8) {
        marks_scan(b);
    }
    if (forget) {
        unsigned kept = 1u << LINK_SL_MASTER | (b->encoder ? 1u << LINK_MA_SLAVE : 0);
        link_forget_pins_before(&b->link, kept, now - SIM_PS_PER_MS);
        b->forgot_at = now;
    }
    /* MA at both ends and SL at the slave keep no history (bench_on) */
}

int bench_tape_record(struct bench *b, const char *path, char *err, size_t errlen) {
    if (b->peer || b->encoder) {
        snprintf(err, errlen, "%s: SL on tape is a slave model's to one PRU", path);
        return -1;
    }
    b->tape = malloc(sizeof *b->tape);
    if (!b->tape) {
        snprintf(err, errlen, "%s: out of memory", path);
        return -1;
    }
    if (sl_tape_create(b->tape, path, b->link.sl_master.initial, err, errlen) != 0) {
        free(b->tape);
        b->tape = NULL;
        return -1;
    }
    return 0;
}

int bench_tape_finish(struct bench *b, char *err, size_t errlen) {
    bench_caught_up(b); /* the last edges */
    return sl_tape_finish(b->tape, b->core, pru_soc_base(b->cfg.soc), err, errlen);
}

void bench_tape_play(struct bench *b, struct sl_tape *t) {
    struct pru_pins pins = sl_tape_pins(t);
    pru_set_pins(b->core, &pins);
}

bool bench_tape_same(struct bench *b, const struct sl_tape *t) {
    return sl_tape_same(t, b->core, pru_soc_base(b->cfg.soc));
}

enum pru_stop bench_run_frames(struct bench *b, uint64_t frames, int64_t max_ps,
                               void (*progress)(void *ctx, uint64_t done, uint64_t total),
                               void *ctx) {
    const int64_t step = 100 * SIM_PS_PER_US;
    int64_t end = pru_time_ps(b->core) + max_ps;
    /* a step may close a frame or two more; they are not measured */
    bench_set_frame_limit(b, frames);
    enum pru_stop why = PRU_STOP_LIMIT;
    while (slave_frames(b) < frames && pru_time_ps(b->core) < end) {
        int64_t next = pru_time_ps(b->core) + step;
        why = bench_run_until(b, next < end ? next : end);
        if (why != PRU_STOP_LIMIT) {
            break;
        }
        if (progress) {
            progress(ctx, slave_frames(b), frames);
        }
    }
    /* all frames done: whatever else the last step met is past the run */
    return slave_frames(b) >= frames ? PRU_STOP_LIMIT : why;
}

const struct bench_stats *bench_stats(struct bench *b) {
    ahead_taken(b);
    marks_scan(b);
    uint64_t n = slave_frames(b);
    b->st.frames = n < b->frame_limit ? n : b->frame_limit;
    return &b->st;
}

void bench_iep_published(struct bench *b, uint64_t frame, uint32_t flags) {
    iep_track_flags(&b->st.iep_track, frame, flags);
}

void bench_set_ma_half(struct bench *b, unsigned half) {
    marks_scan(b); /* the edges so far at the H they were clocked at */
    b->marks.half_ps = (int64_t)half * PRU_PS_PER_CYCLE;
}

void bench_set_frame_limit(struct bench *b, uint64_t frames) {
    ahead_taken(b); /* measured under the limit they were taken under */
    b->frame_limit = frames;
}

void bench_reset_stats(struct bench *b) {
    ahead_taken(b);
    marks_scan(b); /* what came before the reset is not measured after it */
    uint64_t edges_master = b->st.ma_edges_master, edges_slave = b->st.ma_edges_slave;
    memset(&b->st, 0, sizeof(b->st));
    b->st.ma_edges_master = edges_master; /* they index the edge ring */
    b->st.ma_edges_slave = edges_slave;
    /* a frame under way goes on being measured, but its start was before
     * the reset: the first period is measured from the next frame's start */
    b->have_frame_start = false;
    b->pending_half = 0;
}

uint64_t bench_current_frame(struct bench *b) {
    ahead_taken(b);
    return b->current_frame;
}

int64_t bench_frame_start_ps(struct bench *b) {
    ahead_taken(b);
    return b->have_frame_start ? b->frame_start_t : -1;
}

const struct bench_config *bench_config(const struct bench *b) {
    return &b->cfg;
}

double bench_round_trip_ps(const struct bench *b) {
    const scenario *sc = &b->link.sc;
    sim_ps out = sc->model->out_delay(scenario_model_cfg(sc));
    return line_nominal_delay_ps(&sc->ma_line) + (double)out + line_nominal_delay_ps(&sc->sl_line);
}

uint32_t bench_ssi_delay_ns(const struct bench *b) {
    return (uint32_t)(bench_round_trip_ps(b) / 1000.0 + 0.5);
}

void bench_capture_frame(struct bench *b, uint64_t k) {
    ahead_taken(b);
    capture_free(b);
    b->cap_state = CAP_ARMED;
    b->cap_frame = k;
    b->cap_t0 = -1;
    observe_pins_update(b);
    capture_update(b, eq_now(&b->link.q));
}

int bench_capture_get(struct bench *b, waveform *pins[4], sim_ps *t0, sim_ps *t1) {
    capture_update(b, eq_now(&b->link.q));
    sim_ps end = b->cap_end;
    if (b->cap_state != CAP_DONE || b->cap_t0 < 0 || end <= b->cap_t0) {
        return -1;
    }
    /* The clocked part of the frame and SL's answer to its last clock; a
     * long timeout is cut short so the bits stay readable. */
    sim_ps rt = (sim_ps)bench_round_trip_ps(b);
    sim_ps clocked = b->cap_last + 2 * rt + (b->cap_last - b->cap_t0) / 4;
    *t1 = end < clocked ? end : clocked;
    *t0 = b->cap_t0 - (*t1 - b->cap_t0) / 20;
    for (int i = 0; i < 4; i++) {
        pins[i] = &b->cap[i];
    }
    return 0;
}

const void *bench_capture_record(const struct bench *b) {
    return b->cap_state == CAP_DONE ? b->cap_record : NULL;
}
