/* bissctl_probe.c - `bissctl probe`: the layout of an unknown encoder from
 * the wire, its identification registers, and the options to read it. */
#include "biss_probe.h"
#include "bissctl.h"
#include "safe_file.h"

#include <errno.h>
#include <limits.h>
#include <stdio.h>
#include <string.h>

#define DEFAULT_FRAMES 1024

static void print_slave(unsigned i, const struct biss_probe_slave *s, unsigned frames) {
    printf("  slave %u: data %u bits, CRC %u bits poly 0x%X start 0x%X; fits %u/%u frames, %u "
           "distinct words, %u independent differences",
           i, s->data_bits, s->crc_bits, s->crc_poly, s->crc_start, s->support, frames, s->distinct,
           s->rank);
    if (s->crc_stuck) {
        printf(", %u CRC bits never change", s->crc_stuck);
    }
    if (s->has_ew) {
        printf("; nE/nW above bit %u (1 in %u%% of frames)", s->ew_shift, s->ew_ones_pct);
    } else {
        printf("; no nE/nW (the two bits were 1 in %u%% of frames)", s->ew_ones_pct);
    }
    if (s->lc_bits) {
        printf("; %u-bit life counter%s", s->lc_bits,
               s->lc_open ? " (or wider: it never wrapped)" : "");
    }
    printf("\n");
}

/* The layout as options: every field found. nE/nW's bit (the position is
 * above them), or "-" and the position's width above a counter without
 * them; a counter is checked (--check-life), which also names it. */
static void print_slave_opts(const struct biss_probe_layout *l) {
    printf("options:");
    for (unsigned i = 0; i < l->nslaves; i++) {
        const struct biss_probe_slave *s = &l->slave[i];
        printf(" --slave %u,%u,0x%X,0x%X", s->data_bits, s->crc_bits, s->crc_poly, s->crc_start);
        if (s->has_ew) {
            printf(",%u", s->ew_shift);
        } else if (s->lc_bits) {
            printf(",-,%u", s->data_bits - s->lc_bits);
        }
    }
    for (unsigned i = 0; i < l->nslaves; i++) {
        if (l->slave[i].lc_bits) {
            printf(" --check-life %u,%u", i, l->slave[i].lc_bits);
        }
    }
    printf("\n");
}

static void print_bytes(const char *name, int rc, const uint8_t *b, unsigned n) {
    printf(" %s", name);
    if (rc) {
        printf(" (%s)", biss_strerror(rc));
        return;
    }
    for (unsigned i = 0; i < n; i++) {
        printf(" %02X", b[i]);
    }
}

static void print_regs(const struct biss_probe_regs *r) {
    printf("registers ID %u:", r->id);
    if (r->rc_device == BISS_E_CD_NO_ECHO) {
        printf(" no answer (%s)\n", biss_strerror(r->rc_device));
        return;
    }
    print_bytes("device 0x78..0x7D", r->rc_device, r->device, sizeof r->device);
    print_bytes("manufacturer 0x7E..0x7F", r->rc_manufacturer, r->manufacturer,
                sizeof r->manufacturer);
    if (r->rc_manufacturer == BISS_OK) {
        printf(" \"%c%c\"",
               r->manufacturer[0] >= 0x20 && r->manufacturer[0] < 0x7f ? r->manufacturer[0] : '.',
               r->manufacturer[1] >= 0x20 && r->manufacturer[1] < 0x7f ? r->manufacturer[1] : '.');
    }
    print_bytes("profile 0x41..0x43", r->rc_profile, r->profile, sizeof r->profile);
    print_bytes("serial 0x44..0x47", r->rc_serial, r->serial, sizeof r->serial);
    printf("\n");
}

/* The layout the registers describe and what the wire says to it. */
static void print_reg_layout(const struct biss_probe_report *r) {
    const struct biss_probe_reg_layout *rl = &r->reg_layout;
    if (r->reg_verdict == BISS_PROBE_REG_NONE) {
        return;
    }
    if (r->reg_verdict == BISS_PROBE_REG_INVALID) {
        printf("register layout: %s\n", r->reg_why);
        return;
    }
    printf("register layout (ID %u, %s): 0x78..0x7D = %02X %02X %02X %02X %02X %02X:", rl->id,
           rl->format, rl->raw[0], rl->raw[1], rl->raw[2], rl->raw[3], rl->raw[4], rl->raw[5]);
    for (unsigned i = 0; i < rl->nchannels; i++) {
        const struct biss_probe_reg_channel *c = &rl->ch[i];
        printf("%s slave %u %s %u + nE/nW = %u data bits, CRC %u", i ? ";" : "", i, c->what,
               c->value_bits, c->data_bits, c->crc_bits);
    }
    printf(" (MT %u, ST %u); life counter %u bits\n", rl->mt_bits, rl->st_bits, rl->lc_bits);
    printf("registers vs wire: %s: %s\n", biss_probe_reg_verdict_name(r->reg_verdict), r->reg_why);
}

static int write_scenario(const char *path, const char *json) {
    char err[PATH_MAX + 128];
    if (safe_file_write(path, json, strlen(json), err, sizeof err) != 0) {
        fprintf(stderr, "bissctl: %s\n", err);
        return BISSCTL_FAIL;
    }
    printf("scenario written to %s (biss-sim --scenario %s)\n", path, path);
    return BISSCTL_OK;
}

/* An SSI encoder's options and scenario (the ssi profile with its word). */
static int print_ssi(const struct bissctl_opts *o, const struct biss_probe_ssi *s) {
    printf("options: --ssi %u%s --ssi-delay-ns %u\n", s->bits, s->gray ? ",gray" : "", s->delay_ns);
    char json[160];
    snprintf(json, sizeof json,
             "{\n  \"profile\": \"ssi\",\n  \"ssi\": { \"bits\": %u, \"gray\": %s }\n}\n", s->bits,
             s->gray ? "true" : "false");
    if (o->nargs > 0) {
        return write_scenario(o->args[0], json);
    }
    printf("scenario:\n%s", json);
    return BISSCTL_OK;
}

/* A long search's progress, on stderr (stdout stays the result). */
static void progress(void *ctx, const struct biss_probe_progress *p) {
    (void)ctx;
    fprintf(stderr,
            "bissctl: probe: searching, %u of %u bit offsets tried, %.0f%% of the work limit, "
            "%.0f of %.0f s\n",
            p->offsets_searched, p->end_bit, 100.0 * (double)p->work / (double)p->work_limit,
            p->elapsed_ms / 1000.0, p->time_limit_ms / 1000.0);
}

/* What the analysis cost, and what stopped it if anything did. */
static void print_cost(const struct biss_probe_report *r, unsigned limit_ms) {
    const struct biss_probe_result *w = &r->wire;
    printf("analysis: %.2f s, %.3g steps", w->elapsed_ms / 1000.0, (double)w->work);
    if (w->ran_out == BISS_PROBE_RAN_OUT_WORK) {
        printf(" (stopped at the work limit, %.3g steps)", (double)BISS_PROBE_WORK_LIMIT);
    } else if (w->ran_out == BISS_PROBE_RAN_OUT_TIME) {
        printf(" (stopped at the time limit, %.3g s)", limit_ms / 1000.0);
    }
    if (r->capture_cut) {
        printf("; the time limit (%.3g s) ended the capture", limit_ms / 1000.0);
    }
    printf("\n");
}

int bissctl_probe(biss_t *h, const struct bissctl_opts *o) {
    if (o->nargs > 1) {
        return bissctl_usage_error("probe takes one FILE.json, not '%s'", o->args[1]);
    }
    struct biss_probe_params p = {
        .freq_hz = o->cfg.freq_hz,
        .frames = o->count > 1 ? o->count : DEFAULT_FRAMES,
        .read_regs = true,
        .ssi_delay_ns = o->cfg.ssi_delay_ns,
        .limits = {.time_limit_ms = o->time_limit_ms, .progress = progress},
    };
    static struct biss_probe_report r;
    int rc = biss_probe(h, &p, &r);
    if (rc) {
        return bissctl_fail("probe", rc);
    }
    const struct biss_probe_result *w = &r.wire;
    printf("captured %u frames (%u without ACK, %u invalid), analysed %u; frame length %u bits "
           "after the CDS\n",
           w->frames + r.no_slave + r.invalid, r.no_slave, r.invalid, w->frames, w->end_bit);
    printf("line delay %.0f ns, processing time up to %u MA clocks\n", r.delay_ns, r.busy_max);
    print_cost(&r, o->time_limit_ms ? o->time_limit_ms : BISS_PROBE_TIME_LIMIT_MS);
    printf("verdict: %s: %s\n", biss_probe_verdict_name(w->verdict), w->reason);
    if (w->verdict != BISS_PROBE_NONE && w->nkept && w->dropped) {
        printf("set aside as noise: %u of %u frames (the CRCs of candidate 1 fail them); nE/nW "
               "and life counters judged on the other %u\n",
               w->dropped, w->frames, w->frames - w->dropped);
    }
    /* the best, or with an ambiguous verdict the first three */
    unsigned show = w->verdict == BISS_PROBE_AMBIGUOUS ? 3u : 1u;
    show = show < w->nkept ? show : w->nkept;
    for (unsigned k = 0; k < show && w->verdict != BISS_PROBE_NONE; k++) {
        const struct biss_probe_layout *l = &w->layout[k];
        printf("candidate %u: %u slave%s, %u CRC bits, fits %u/%u frames%s\n", k + 1, l->nslaves,
               l->nslaves == 1 ? "" : "s", l->crc_total, l->support, w->frames,
               l->weak ? " (a slave's data hardly changed)" : "");
        for (unsigned i = 0; i < l->nslaves; i++) {
            print_slave(i, &l->slave[i], w->frames);
        }
    }
    if (w->verdict == BISS_PROBE_AMBIGUOUS && w->nlayouts > show) {
        printf("(%u more candidates)\n", w->nlayouts - show);
    }
    for (unsigned i = 0; i < r.nregs; i++) {
        print_regs(&r.regs[i]);
    }
    print_reg_layout(&r);
    for (unsigned i = 0; i < r.nnotes; i++) {
        printf("note: %s\n", r.notes[i]);
    }
    if (r.ssi.tried) {
        printf("SSI capture (64 bits at %u ns round trip, %u words): %s\n", r.ssi.delay_ns,
               r.ssi.frames, r.ssi.verdict);
    }
    if (r.ssi.decided) {
        return print_ssi(o, &r.ssi);
    }
    if (w->verdict == BISS_PROBE_NONE || !w->nkept) {
        return BISSCTL_FAIL;
    }
    print_slave_opts(&w->layout[0]);
    static char json[4096];
    if (biss_probe_to_json(&w->layout[0], json, sizeof json)) {
        return bissctl_fail("scenario", BISS_E_INVAL);
    }
    if (o->nargs > 0) {
        rc = write_scenario(o->args[0], json);
    } else {
        printf("scenario:\n%s", json);
    }
    /* ambiguous is an answer, but not one to configure blindly */
    return rc ? rc : w->verdict == BISS_PROBE_AMBIGUOUS ? BISSCTL_FAIL : BISSCTL_OK;
}
