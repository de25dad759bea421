/* bench.c - wiring of core, lines and slaves (see bench.h). */
#include "bench.h"

#include "vcd.h"
#include "waveform.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* MA edges in flight between the master pin and the slave. A cable of any
 * length the models allow holds far fewer. */
#define MA_RING 4096

enum { W_MA_MASTER, W_SL_MASTER, W_MA_SLAVE, W_SL_SLAVE, W_COUNT };
static const char *const wire_names[W_COUNT] = {"MA_master", "SL_master", "MA_slave",
                                                "SL_slave"};

struct bench {
    struct bench_config cfg;
    struct pru_core *core;
    event_queue q;
    line_dir ma_line, sl_line;
    biss_slave biss;
    ssi_slave ssi;
    sim_edge_sink slave_in;
    waveform sl_master;
    int ma_level; /* last level driven on MA */

    /* master-side MA edge times, indexed by edge number modulo MA_RING */
    int64_t ma_times[MA_RING];
    uint64_t in_frame_of_prev; /* frame number of the previous in-frame edge + 1, 0 none */
    int64_t prev_in_frame_t;
    int64_t frame_start_t;
    bool have_frame_start;

    struct vcd_writer vcd;
    bool vcd_on;
    struct bench_stats st;
};

void bench_config_default(struct bench_config *c)
{
    memset(c, 0, sizeof(*c));
    c->soc = PRU_SOC_AM335X;
    pru_params_default(&c->pru);
    c->ma_bit = 1;
    line_params_default(&c->ma_line);
    line_params_default(&c->sl_line);
    c->kind = BENCH_SLAVE_BISS;
    biss_chain_cfg_default(&c->chain);
    ssi_cfg_default(&c->ssi);
    c->seed = 1;
}

void bench_config_set_cable(struct bench_config *c, double length_m)
{
    c->ma_line.length_m = length_m;
    c->sl_line.length_m = length_m;
}

static void vcd_edge(struct bench *b, int wire, int64_t t, int level)
{
    if (b->vcd_on) {
        vcd_change(&b->vcd, t, wire, level);
    }
}

/* ---- slave side -------------------------------------------------------- */

static bool slave_in_frame(const struct bench *b, uint64_t *frame)
{
    if (b->cfg.kind == BENCH_SLAVE_BISS) {
        *frame = b->biss.frames;
        return b->biss.phase == BISS_ACTIVE;
    }
    *frame = b->ssi.frames;
    return b->ssi.active;
}

/* An in-frame MA edge, timed at the master pin: frame starts and half
 * periods are measured where the firmware drives them. */
static void account_edge(struct bench *b, uint64_t frame, int64_t t_master)
{
    struct bench_stats *st = &b->st;
    if (b->in_frame_of_prev != frame + 1) {
        st->frames_started++;
        if (b->have_frame_start) {
            int64_t p = t_master - b->frame_start_t;
            if (st->periods == 0 || p < st->period_min_ps) {
                st->period_min_ps = p;
            }
            if (st->periods == 0 || p > st->period_max_ps) {
                st->period_max_ps = p;
            }
            st->period_sum_ps += (double)p;
            st->periods++;
        }
        b->frame_start_t = t_master;
        b->have_frame_start = true;
    } else {
        int64_t h = t_master - b->prev_in_frame_t;
        if (st->half_periods == 0 || h < st->half_min_ps) {
            st->half_min_ps = h;
        }
        if (st->half_periods == 0 || h > st->half_max_ps) {
            st->half_max_ps = h;
        }
        st->half_periods++;
    }
    b->in_frame_of_prev = frame + 1;
    b->prev_in_frame_t = t_master;
}

static void ma_at_slave(void *ctx, sim_ps t, int level)
{
    struct bench *b = ctx;
    uint64_t idx = b->st.ma_edges_slave++;
    vcd_edge(b, W_MA_SLAVE, t, level);
    sim_edge_send(&b->slave_in, t, level);
    uint64_t frame;
    if (slave_in_frame(b, &frame) && idx < b->st.ma_edges_master &&
        b->st.ma_edges_master - idx <= MA_RING) {
        account_edge(b, frame, b->ma_times[idx % MA_RING]);
    } else {
        b->in_frame_of_prev = 0;
    }
}

static void sl_at_slave(void *ctx, sim_ps t, int level)
{
    struct bench *b = ctx;
    vcd_edge(b, W_SL_SLAVE, t, level);
    line_dir_input(&b->sl_line, t, level);
}

static void sl_at_master(void *ctx, sim_ps t, int level)
{
    struct bench *b = ctx;
    waveform_append(&b->sl_master, t, level);
    vcd_edge(b, W_SL_MASTER, t, level);
}

/* ---- PRU pins ---------------------------------------------------------- */

static uint32_t pins_inputs_at(void *ctx, int64_t t)
{
    struct bench *b = ctx;
    if (t > eq_now(&b->q)) {
        eq_run_until(&b->q, t);
    }
    /* SL on R31 bit 0; the other inputs are not connected and read 0 */
    return (uint32_t)waveform_level_at(&b->sl_master, t);
}

static int64_t pins_next_change(void *ctx, int64_t t)
{
    struct bench *b = ctx;
    (void)t;
    /* any pending event may move SL at the master */
    return eq_next_time(&b->q);
}

static void pins_outputs(void *ctx, int64_t t, uint32_t r30)
{
    struct bench *b = ctx;
    int level = (int)((r30 >> b->cfg.ma_bit) & 1u);
    if (level == b->ma_level) {
        return;
    }
    /* Everything before this edge happens first, so the VCD and the lines
     * see time in order; nothing before t depends on this edge. */
    if (t > eq_now(&b->q)) {
        eq_run_until(&b->q, t);
    }
    b->ma_level = level;
    b->ma_times[b->st.ma_edges_master % MA_RING] = t;
    b->st.ma_edges_master++;
    vcd_edge(b, W_MA_MASTER, t, level);
    line_dir_input(&b->ma_line, t, level);
}

/* ---- life cycle -------------------------------------------------------- */

static int check_config(const struct bench_config *c, char *err, size_t errlen)
{
    const char *why = NULL;
    if (c->ma_bit > 15) {
        why = "ma_bit must be an R30 output pin, 0..15";
    } else if (c->kind == BENCH_SLAVE_BISS) {
        why = biss_chain_cfg_check(&c->chain);
    } else {
        why = ssi_cfg_check(&c->ssi);
    }
    if (!why && (c->ma_line.length_m < 0 || c->sl_line.length_m < 0)) {
        why = "cable length must not be negative";
    }
    if (why) {
        snprintf(err, errlen, "%s", why);
        return -1;
    }
    return 0;
}

struct bench *bench_new(const struct bench_config *cfg, char *err, size_t errlen)
{
    if (check_config(cfg, err, errlen) != 0) {
        return NULL;
    }
    struct bench *b = calloc(1, sizeof(*b));
    if (!b) {
        snprintf(err, errlen, "out of memory");
        return NULL;
    }
    b->cfg = *cfg;
    b->core = pru_core_new(cfg->soc, &cfg->pru);
    if (!b->core) {
        free(b);
        snprintf(err, errlen, "out of memory");
        return NULL;
    }
    eq_init(&b->q);
    waveform_init(&b->sl_master, 1);
    b->ma_level = 1;

    /* Seeds of the two directions differ so their noise is independent. */
    line_dir_init(&b->ma_line, &cfg->ma_line, &b->q, cfg->seed * 2 + 1, 1,
                  (sim_edge_sink){ma_at_slave, b});
    line_dir_init(&b->sl_line, &cfg->sl_line, &b->q, cfg->seed * 2 + 2, 1,
                  (sim_edge_sink){sl_at_master, b});
    sim_edge_sink sl_out = {sl_at_slave, b};
    if (cfg->kind == BENCH_SLAVE_BISS) {
        biss_slave_init(&b->biss, &cfg->chain, &b->q, sl_out);
        b->slave_in = biss_slave_sink(&b->biss);
    } else {
        ssi_slave_init(&b->ssi, &cfg->ssi, &b->q, sl_out);
        b->slave_in = ssi_slave_sink(&b->ssi);
    }

    struct pru_pins pins = {b, pins_inputs_at, pins_next_change, pins_outputs};
    pru_set_pins(b->core, &pins);
    return b;
}

void bench_free(struct bench *b)
{
    if (!b) {
        return;
    }
    bench_close_vcd(b);
    pru_core_free(b->core);
    waveform_free(&b->sl_master);
    eq_free(&b->q);
    free(b);
}

int bench_open_vcd(struct bench *b, const char *path)
{
    bench_close_vcd(b);
    if (vcd_open(&b->vcd, path) != 0) {
        return -1;
    }
    for (int i = 0; i < W_COUNT; i++) {
        vcd_add_wire(&b->vcd, wire_names[i]);
    }
    b->vcd_on = true;
    int64_t now = eq_now(&b->q);
    vcd_change(&b->vcd, now, W_MA_MASTER, b->ma_level);
    vcd_change(&b->vcd, now, W_SL_MASTER, waveform_level_at(&b->sl_master, now));
    vcd_change(&b->vcd, now, W_MA_SLAVE, b->cfg.kind == BENCH_SLAVE_BISS ? b->biss.ma : b->ssi.ma);
    vcd_change(&b->vcd, now, W_SL_SLAVE, b->sl_line.in_level);
    return 0;
}

int bench_close_vcd(struct bench *b)
{
    if (!b->vcd_on) {
        return 0;
    }
    b->vcd_on = false;
    return vcd_close(&b->vcd, pru_time_ps(b->core));
}

struct pru_core *bench_core(struct bench *b)
{
    return b->core;
}

int bench_start_image(struct bench *b, const void *image, size_t bytes)
{
    if (pru_load_image(b->core, image, bytes) != 0) {
        return -1;
    }
    pru_start(b->core);
    return 0;
}

enum pru_stop bench_run_until(struct bench *b, int64_t t_ps)
{
    enum pru_stop why = pru_run_until_time(b->core, t_ps);
    /* the models catch up with the core (a halted core leaves them behind) */
    int64_t now = pru_time_ps(b->core);
    if (now > eq_now(&b->q)) {
        eq_run_until(&b->q, now);
    }
    /* SL history older than a millisecond is never looked at again */
    if (now > SIM_PS_PER_MS) {
        waveform_forget_before(&b->sl_master, now - SIM_PS_PER_MS);
    }
    return why;
}

static uint64_t slave_frames(const struct bench *b)
{
    return b->cfg.kind == BENCH_SLAVE_BISS ? b->biss.frames : b->ssi.frames;
}

enum pru_stop bench_run_frames(struct bench *b, uint64_t frames, int64_t max_ps,
                               void (*progress)(void *ctx, uint64_t done, uint64_t total),
                               void *ctx)
{
    const int64_t step = 100 * SIM_PS_PER_US;
    int64_t end = pru_time_ps(b->core) + max_ps;
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
    b->st.frames = slave_frames(b);
    return why;
}

const struct bench_stats *bench_stats(struct bench *b)
{
    b->st.frames = slave_frames(b);
    return &b->st;
}

const struct bench_config *bench_config(const struct bench *b)
{
    return &b->cfg;
}

biss_slave *bench_biss(struct bench *b)
{
    return b->cfg.kind == BENCH_SLAVE_BISS ? &b->biss : NULL;
}

ssi_slave *bench_ssi(struct bench *b)
{
    return b->cfg.kind == BENCH_SLAVE_SSI ? &b->ssi : NULL;
}

double bench_round_trip_ps(const struct bench *b)
{
    sim_ps out = b->cfg.kind == BENCH_SLAVE_BISS ? b->cfg.chain.out_delay_ps
                                                 : b->cfg.ssi.out_delay_ps;
    return line_nominal_delay_ps(&b->cfg.ma_line) + (double)out +
           line_nominal_delay_ps(&b->cfg.sl_line);
}

line_dir *bench_ma_line(struct bench *b)
{
    return &b->ma_line;
}

line_dir *bench_sl_line(struct bench *b)
{
    return &b->sl_line;
}
