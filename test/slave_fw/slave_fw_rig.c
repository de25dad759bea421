/* slave_fw_rig.c - see slave_fw_rig.h. */
#include "slave_fw_rig.h"

#include "read_file.h"

#include <check.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define PS_CYC SIM_PS_PER_PRU_CYCLE

/* ---- the firmware's pins ---------------------------------------------- */

static uint32_t pins_in(void *ctx, int64_t t) {
    struct rig *r = ctx;
    return (uint32_t)waveform_level_at(&r->ma, t) << RIG_MA_BIT;
}

static int64_t pins_next(void *ctx, int64_t t) {
    struct rig *r = ctx;
    return waveform_next_after(&r->ma, t);
}

static void pins_out(void *ctx, int64_t t, uint32_t r30) {
    struct rig *r = ctx;
    waveform_append(&r->sl, t, (int)(r30 & 1u));
}

void rig_open(struct rig *r, const biss_chain_cfg *chain, const struct pru_params *params) {
    memset(r, 0, sizeof *r);
    r->icss = pru_icss_new(PRU_SOC_AM335X, params);
    ck_assert_ptr_nonnull(r->icss);
    r->core = pru_icss_core(r->icss, 1);
    waveform_init(&r->ma, 1);
    waveform_init(&r->sl, 0); /* R30 is 0 out of reset */
    waveform_init(&r->sl_m, 1);
    r->frames = calloc(RIG_MAX_FRAMES, sizeof *r->frames);
    ck_assert_ptr_nonnull(r->frames);
    r->cursor = 20 * SIM_PS_PER_US;
    struct pru_pins pins = {.ctx = r,
                            .inputs_at = pins_in,
                            .next_input_change = pins_next,
                            .outputs_changed = pins_out};
    pru_set_pins(r->core, &pins);
    char *img;
    size_t len;
    ck_assert_int_eq(read_file(SLAVE_IMAGE_PRU1, 16384, &img, &len), READ_FILE_OK);
    ck_assert_int_eq(pru_load_image(r->core, img, len), 0);
    free(img);
    r->trace = getenv("RIG_TRACE") ? fopen(getenv("RIG_TRACE"), "a") : NULL;
    if (r->trace) {
        fprintf(r->trace, "# rig: %u slaves\n", chain->n);
    }
    pru_set_trace(r->core, r->trace);
    pru_start(r->core);
    slave_fw_ram_init(&r->ram, r->core, PRU_SOC_AM335X, 1);
    r->io = slave_fw_io(&r->ram);
    /* start-up, then the configuration (within 10 us of simulated time) */
    ck_assert_int_ne(pru_icss_run_until_time(r->icss, 2 * SIM_PS_PER_US), PRU_STOP_FAULT);
    r->chain = *chain;
    char err[256];
    ck_assert_msg(slave_fw_load(&r->io, chain, err, sizeof err) == 0, "%s", err);
    ck_assert_int_ne(pru_icss_run_until_time(r->icss, 15 * SIM_PS_PER_US), PRU_STOP_FAULT);
    struct biss_slv_status st = rig_status(r);
    ck_assert_uint_eq(st.magic, BISS_SLV_MAGIC);
    ck_assert_uint_eq(st.pru, 1);
    ck_assert_uint_eq(st.ma_bit, RIG_MA_BIT);
    ck_assert_msg(st.cfg_error == 0, "configuration refused: %s",
                  biss_encoder_cfg_error_text(st.cfg_error));
    ck_assert_uint_eq(st.cfg_ack, 1);
    /* the model */
    eq_init(&r->q);
    r->model = malloc(sizeof *r->model);
    ck_assert_ptr_nonnull(r->model);
    biss_slave_init(r->model, chain, &r->q, waveform_sink(&r->sl_m));
}

void rig_close(struct rig *r) {
    pru_icss_free(r->icss);
    if (r->trace) {
        fclose(r->trace);
    }
    waveform_free(&r->ma);
    waveform_free(&r->sl);
    waveform_free(&r->sl_m);
    free(r->frames);
    free(r->model);
    eq_free(&r->q);
}

struct rig_frame *rig_add(struct rig *r, unsigned half, unsigned clocks, int cdm, sim_ps gap) {
    ck_assert_uint_lt(r->nframes, RIG_MAX_FRAMES);
    struct rig_frame *f = &r->frames[r->nframes++];
    memset(f, 0, sizeof *f);
    f->half = half;
    f->clocks = clocks;
    f->cdm = cdm;
    f->gap = gap;
    sim_ps h = (sim_ps)half * PS_CYC, t = r->cursor + r->phase;
    f->t0 = t;
    waveform_append(&r->ma, t, 0);
    sim_ps last = t;
    for (unsigned k = 1; k <= clocks; k++) {
        last = t + (sim_ps)(2 * k - 1) * h;
        if (k <= 160) {
            f->rise[k - 1] = last;
        }
        waveform_append(&r->ma, last, 1);
        if (k < clocks) {
            waveform_append(&r->ma, last + h, 0);
        } else if (cdm) {
            waveform_append(&r->ma, last + (r->cdm_fall ? r->cdm_fall : h), 0);
        }
    }
    waveform_append(&r->ma, last + gap, 1);
    /* the next frame after MA has been high for a while */
    r->cursor = last - r->phase + gap + 4 * h + 2 * SIM_PS_PER_US;
    return f;
}

void rig_add_n(struct rig *r, unsigned n, unsigned half, unsigned clocks, const int *cdm,
               sim_ps gap) {
    for (unsigned i = 0; i < n; i++) {
        rig_add(r, half, clocks, cdm ? cdm[i] : 0, gap);
    }
}

void rig_run_fw_until(struct rig *r, sim_ps t) {
    enum pru_stop why = pru_icss_run_until_time(r->icss, t);
    if (why == PRU_STOP_FAULT) {
        pru_print_fault(r->core, stderr);
    }
    ck_assert_int_eq(why, PRU_STOP_LIMIT);
}

void rig_run(struct rig *r) {
    for (unsigned k = 0; k < r->nframes; k++) {
        rig_run_fw_until(r, r->frames[k].t0 - 1);
        ck_assert_int_eq(biss_proto_encoder_rec(&r->io, &r->frames[k].rec), 0);
    }
    rig_run_fw_until(r, r->cursor);
    /* the model, on the same edges */
    for (size_t i = 0; i < r->ma.len; i++) {
        eq_run_until(&r->q, r->ma.edges[i].t);
        biss_slave_ma_edge(r->model, r->ma.edges[i].t, r->ma.edges[i].level);
    }
    eq_run_until(&r->q, r->cursor);
}

int rig_sl_fw(struct rig *r, sim_ps t) {
    return waveform_level_at(&r->sl, t);
}

int rig_sl_model(struct rig *r, sim_ps t) {
    return waveform_level_at(&r->sl_m, t);
}

unsigned rig_compare(struct rig *r, char *what, size_t len) {
    unsigned diffs = 0;
    what[0] = 0;
    for (unsigned k = 0; k < r->nframes; k++) {
        const struct rig_frame *f = &r->frames[k];
        sim_ps h = (sim_ps)f->half * PS_CYC;
        unsigned n = f->clocks < 160 ? f->clocks : 160;
        for (unsigned j = 1; j <= n; j++) {
            /* the bit rise j - 1 put out, just before rise j (after the last
             * rise: a period after it) */
            sim_ps t = j < n ? f->rise[j] - 1 : f->rise[n - 1] + 2 * h - 1;
            if (j == 1) {
                t = f->t0 - 1; /* idle before the frame: SL high */
            }
            int a = rig_sl_fw(r, t), b = rig_sl_model(r, t);
            if (a != b && diffs++ == 0) {
                snprintf(what, len, "frame %u, before rise %u (t = %lld ps): firmware %d, model %d",
                         k, j, (long long)t, a, b);
            }
        }
    }
    return diffs;
}

const biss_frame_record *rig_model_record(struct rig *r, unsigned k) {
    return biss_slave_record(r->model, k);
}

struct biss_slv_status rig_status(struct rig *r) {
    struct biss_slv_status st;
    ck_assert_int_eq(biss_proto_encoder_status(&r->io, &st), 0);
    return st;
}

void rig_latency(struct rig *r, sim_ps *min, sim_ps *max, unsigned *n) {
    *min = *max = 0;
    *n = 0;
    for (size_t i = 0; i + 1 < r->ma.len; i++) {
        if (!r->ma.edges[i].level) {
            continue;
        }
        sim_ps t = r->ma.edges[i].t, next = r->ma.edges[i + 1].t;
        if (next - t > 1024 * PS_CYC) {
            continue; /* the frame's last rise: SL's next change is the timeout's */
        }
        sim_ps c = waveform_next_after(&r->sl, t);
        if (c == SIM_NEVER || c >= next) {
            continue;
        }
        sim_ps d = c - t;
        if (*n == 0 || d < *min) {
            *min = d;
        }
        if (*n == 0 || d > *max) {
            *max = d;
        }
        (*n)++;
    }
}
