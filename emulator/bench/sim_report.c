/* sim_report.c - biss-sim's JSON, text and SVG output (see sim_report.h). */
#include "sim_report.h"

#include "biss/biss_shm.h"
#include "frame_labels.h"
#include "svg_scope.h"

#include <cjson/cJSON.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char *stop_name(enum pru_stop why) {
    switch (why) {
    case PRU_STOP_LIMIT:
        return "done";
    case PRU_STOP_HALT:
        return "halted";
    case PRU_STOP_FAULT:
        return "fault";
    case PRU_STOP_DISABLED:
        return "disabled";
    case PRU_STOP_STEP:
        return "step";
    }
    return "?";
}

/* The averaged round trip as proto converts it (biss_delay_decode). */
static struct biss_line_delay line_delay(unsigned raw, unsigned avg, unsigned half) {
    struct biss_line_delay d;
    biss_delay_decode((uint16_t)raw, (uint16_t)avg, half, &d);
    return d;
}

const char *sim_safety_problem(int rc) {
    switch (rc) {
    case BISS_E_SAFETY_LIFE:
        return "a life-counter check names a slave outside the chain or one without that many "
               "life-counter bits (BISS_E_SAFETY_LIFE)";
    case BISS_E_SAFETY_EW:
        return "the nE/nW check (a slave that never sets them) names a slave outside the chain "
               "or one that sends no nE/nW (BISS_E_SAFETY_EW)";
    case BISS_E_SAFETY_SPEED:
        return "the speed check names a slave outside the chain, or the trigger gives it no "
               "time to judge by (BISS_E_SAFETY_SPEED)";
    case BISS_E_SAFETY_CRC:
        return "the two channels of a pair have the same CRC polynomial and start value; BiSS "
               "Safety tells them apart by it (BISS_E_SAFETY_CRC)";
    default:
        return "a pair names a slave outside the chain or a slave twice, more than 4 pairs, or a "
               "shifted position over 64 bits (BISS_E_SAFETY_PAIR)";
    }
}

double sim_fw_line_delay_ns(const struct fw_check *fw) {
    return line_delay(fw->delay_raw, fw->delay_avg, fw->half).ns;
}

/* The last closed frame, per slave: what went over the wire (and, with the
 * firmware, what the master read). */
static cJSON *slaves_json(const struct sim_result *r) {
    link_model *l = bench_link(r->b);
    cJSON *arr = cJSON_CreateArray();
    uint64_t n = link_frames(l);
    const void *rec = n ? link_record(l, n - 1) : NULL;
    if (!rec) {
        return arr;
    }
    slave_frame f;
    l->model->frame(link_model_cfg(l), rec, &f);
    const biss_chain_cfg *c = scenario_chain(&l->sc);
    for (unsigned i = 0; i < f.nwords; i++) {
        cJSON *s = cJSON_CreateObject();
        if (!c) { /* a word without a BiSS-C slave's ID, status bits or CRC */
            cJSON_AddNumberToObject(s, "position", (double)f.word[i].position);
            cJSON_AddItemToArray(arr, s);
            continue;
        }
        cJSON_AddNumberToObject(s, "id", c->s[i].id);
        cJSON_AddNumberToObject(s, "position", (double)f.word[i].position);
        cJSON_AddNumberToObject(s, "nE", f.word[i].nE);
        cJSON_AddNumberToObject(s, "nW", f.word[i].nW);
        cJSON_AddNumberToObject(s, "crc", f.word[i].crc);
        if (r->fw) {
            cJSON_AddNumberToObject(s, "master_data", (double)r->fw->data[i]);
            cJSON_AddBoolToObject(s, "master_crc_ok", r->fw->status[i] & BISS_RS_CRC_OK);
        }
        cJSON_AddItemToArray(arr, s);
    }
    return arr;
}

static void add_min_mean_max(cJSON *o, const char *key, double lo, double mean, double hi) {
    cJSON *m = cJSON_AddObjectToObject(o, key);
    cJSON_AddNumberToObject(m, "min", lo);
    cJSON_AddNumberToObject(m, "mean", mean);
    cJSON_AddNumberToObject(m, "max", hi);
}

static void add_counter(cJSON *j, const char *key, const struct fw_check *fw, uint64_t v) {
    if (fw) {
        cJSON_AddNumberToObject(j, key, (double)v);
    } else {
        cJSON_AddNullToObject(j, key); /* an image that is not the firmware decodes nothing */
    }
}

double sim_frame_minimum_ps(struct bench *b, const struct fw_check *fw) {
    const biss_chain_cfg *c = &bench_link(b)->sc.biss;
    double period = 2.0 * fw->half * PRU_PS_PER_CYCLE;
    unsigned bits = 0;
    for (unsigned i = 0; i < c->n; i++) {
        bits += biss_slave_cfg_bits(&c->s[i]);
    }
    /* clocks: two to the ACK, the busy ones, start, CDS, the bits, and the
     * one on which the slave starts its timeout */
    unsigned clocks = 2 + fw->proc_clocks_max + 2 + bits + 1;
    double timeout = (double)biss_chain_timeout_ps(c, (sim_ps)period);
    /* the last rising edge comes half a period before the clocks' end; the
     * slave's timeout runs from it; its end travels back over the line */
    return (clocks - 0.5) * period + timeout + bench_round_trip_ps(b);
}

/* A span in PRU cycles, each value less `less_ps`; null when empty. */
static void add_span(cJSON *o, const char *key, const struct bench_span *s, double less_ps) {
    if (s->n == 0) {
        cJSON_AddNullToObject(o, key);
        return;
    }
    add_min_mean_max(o, key, ((double)s->min_ps - less_ps) / PRU_PS_PER_CYCLE,
                     ((double)s->sum_ps / (double)s->n - less_ps) / PRU_PS_PER_CYCLE,
                     ((double)s->max_ps - less_ps) / PRU_PS_PER_CYCLE);
}

/* The publication of valid frames after their last bit at the master pin
 * and after the position's latch (INSTRUMENTS.md), H the frames' half
 * period. */
static void add_publication(cJSON *f, const struct fw_check *fw) {
    double h_ps = (double)fw->half * PRU_PS_PER_CYCLE;
    cJSON *p = cJSON_AddObjectToObject(f, "publication_latency_cycles");
    add_span(p, "after_last_bit_start", &fw->latency, 0);
    add_span(p, "beyond_half_bit", &fw->latency, h_ps);
    add_span(p, "after_last_bit_end", &fw->latency, 2 * h_ps);
    add_span(f, "position_age_cycles", &fw->age, 0);
}

/* What the master's MA pin shows at each frame's first fall (bench_stats,
 * INSTRUMENTS.md); null before the bench knew H. */
static void add_frame_marks(cJSON *j, const struct bench_stats *st, unsigned half,
                            unsigned trigger) {
    if (st->ma_high.n == 0) {
        cJSON_AddNullToObject(j, "frame_starts");
        return;
    }
    double h_ps = (double)half * PRU_PS_PER_CYCLE;
    cJSON *o = cJSON_AddObjectToObject(j, "frame_starts");
    cJSON_AddNumberToObject(o, "frames", (double)st->ma_high.n);
    add_span(o, "ma_high_before_first_fall_cycles", &st->ma_high, 0);
    cJSON_AddNumberToObject(o, "ma_high_min_of_half", (double)st->ma_high.min_ps / h_ps);
    cJSON_AddNumberToObject(o, "ma_high_shorter_than_half", (double)st->ma_high_short);
    bool free_run = trigger == BISS_TRIG_FREERUN;
    if (free_run) {
        add_span(o, "restart_overhead_cycles", &st->restart, 0);
        add_span(o, "restart_over_idle_filter_cycles", &st->restart, h_ps);
    } else {
        cJSON_AddNullToObject(o, "restart_overhead_cycles"); /* a trigger starts the frames */
        cJSON_AddNullToObject(o, "restart_over_idle_filter_cycles");
    }
    if (st->iep_phase.n == 0) {
        cJSON_AddNullToObject(o, "iep");
        return;
    }
    cJSON *i = cJSON_AddObjectToObject(o, "iep");
    cJSON_AddNumberToObject(i, "period_cycles", st->iep_period);
    add_span(i, "trigger_to_first_fall_cycles", &st->iep_phase, 0);
    cJSON_AddNumberToObject(i, "frames", (double)st->iep_phase.n);
    cJSON_AddNumberToObject(i, "periods", (double)st->iep_periods);
    cJSON_AddNumberToObject(i, "skipped_periods", (double)st->iep_skipped);
    cJSON_AddNumberToObject(i, "crowded_periods", (double)st->iep_crowded);
    const struct iep_track *k = &st->iep_track;
    cJSON_AddNumberToObject(i, "judged_frames", (double)k->judged);
    cJSON_AddNumberToObject(i, "late_flagged", (double)k->late);
    cJSON_AddNumberToObject(i, "unflagged_off_count", (double)k->unflagged_off);
    cJSON_AddNumberToObject(i, "unflagged_skipped_periods", (double)k->unflagged_skips);
}

/* The wrong frames published as valid, by class (wrong_frame.h), and the
 * first few described. */
static void add_wrong(cJSON *j, const struct fw_check *fw) {
    cJSON *o = cJSON_AddObjectToObject(j, "wrong_frames");
    cJSON_AddNumberToObject(o, "valid_on_the_wire", (double)fw->wrong_by_class[WRONG_ON_WIRE]);
    cJSON_AddNumberToObject(o, "off_grid", (double)fw->wrong_by_class[WRONG_OFF_GRID]);
    cJSON_AddNumberToObject(o, "between_samples", (double)fw->wrong_by_class[WRONG_BETWEEN]);
    cJSON_AddNumberToObject(o, "other", (double)fw->wrong_by_class[WRONG_OTHER]);
    cJSON *a = cJSON_AddArrayToObject(o, "first");
    for (unsigned k = 0; k < fw->nwrong; k++) {
        char line[512];
        wrong_frame_describe(&fw->wrong[k], line, sizeof line);
        cJSON_AddItemToArray(a, cJSON_CreateString(line));
    }
}

static void print_wrong(const struct fw_check *fw) {
    if (!fw->mismatches) {
        return;
    }
    printf("wrong but valid      %llu valid on the wire, %llu off-grid, %llu between samples, "
           "%llu other\n",
           (unsigned long long)fw->wrong_by_class[WRONG_ON_WIRE],
           (unsigned long long)fw->wrong_by_class[WRONG_OFF_GRID],
           (unsigned long long)fw->wrong_by_class[WRONG_BETWEEN],
           (unsigned long long)fw->wrong_by_class[WRONG_OTHER]);
    for (unsigned k = 0; k < fw->nwrong; k++) {
        char line[512];
        wrong_frame_describe(&fw->wrong[k], line, sizeof line);
        printf("  %s\n", line);
    }
}

/* The link's eye and warning over every publication (proto/biss_link.c). */
static void add_link(cJSON *j, const struct biss_link_state *l) {
    const struct biss_link_stats *k = &l->stats;
    cJSON *o = cJSON_AddObjectToObject(j, "link");
    cJSON_AddNumberToObject(o, "frames", k->frames);
    cJSON *eye = cJSON_AddArrayToObject(o, "eye_histogram");
    for (unsigned i = 0; i <= BISS_LINK_EYE_MAX; i++) {
        cJSON_AddItemToArray(eye, cJSON_CreateNumber(k->eye[i]));
    }
    cJSON_AddNumberToObject(o, "eye_min", k->frames ? k->eye_min : BISS_LINK_EYE_MAX);
    cJSON_AddNumberToObject(o, "eye_mean", biss_link_eye_mean(k));
    cJSON_AddNumberToObject(o, "marginal_frames", k->marginal);
    cJSON_AddNumberToObject(o, "off_grid_frames", k->off_grid);
    cJSON_AddNumberToObject(o, "warning_frames", k->warnings);
    cJSON_AddNumberToObject(o, "warn", l->warn);
    cJSON_AddNumberToObject(o, "window", l->window);
}

static void add_firmware(cJSON *j, struct bench *b, const struct fw_check *fw) {
    cJSON *f = cJSON_AddObjectToObject(j, "firmware");
    cJSON_AddNumberToObject(f, "publications", (double)fw->publications);
    cJSON_AddNumberToObject(f, "no_slave", (double)fw->no_slave);
    cJSON_AddNumberToObject(f, "processing_errors", (double)fw->proc_errors);
    cJSON_AddNumberToObject(f, "ack_jumps", (double)fw->ack_jumps);
    cJSON_AddNumberToObject(f, "ack_jumps_good_lost", (double)fw->ack_jump_good);
    cJSON_AddNumberToObject(f, "off_grid", (double)fw->off_grid);
    cJSON_AddNumberToObject(f, "off_grid_good_lost", (double)fw->off_grid_good);
    add_link(j, &fw->link);
    cJSON_AddNumberToObject(f, "training_frames", (double)fw->training);
    if (fw->delay_frames) {
        cJSON_AddNumberToObject(f, "line_delay_ns", sim_fw_line_delay_ns(fw));
    } else {
        cJSON_AddNullToObject(f, "line_delay_ns"); /* nothing measured */
    }
    cJSON_AddNumberToObject(f, "delay_bit8_raw", fw->delay_raw);
    cJSON_AddNumberToObject(f, "delay_bit8_avg", fw->delay_avg);
    cJSON_AddNumberToObject(f, "sample_point", fw->sample_point);
    cJSON_AddNumberToObject(f, "lag_periods", fw->lag);
    cJSON_AddNumberToObject(f, "delay_frame", fw->delay_frame); /* the frame of those four */
    cJSON_AddNumberToObject(f, "processing_clocks_max", fw->proc_clocks_max);
    cJSON_AddNumberToObject(f, "last_flags", fw->last_flags);
    const struct bench_stats *st = bench_stats(b);
    double minimum = sim_frame_minimum_ps(b, fw);
    double mean = st->periods ? st->period_sum_ps / (double)st->periods : 0;
    cJSON_AddNumberToObject(f, "frame_minimum_ns", minimum / 1000.0);
    cJSON_AddNumberToObject(f, "master_overhead_cycles", (mean - minimum) / PRU_PS_PER_CYCLE);
    add_publication(f, fw);
}

/* The host's safety checks over every publication, when any is set. */
static bool any_safety(const struct fw_check *fw) {
    bool any = fw->cfg.npairs > 0;
    for (unsigned i = 0; i < fw->cfg.nslaves; i++) {
        any = any || fw->cfg.slave[i].life_check || fw->cfg.slave[i].ew_static ||
              fw->cfg.slave[i].max_speed;
    }
    return any;
}

static void add_safety(cJSON *j, const struct fw_check *fw) {
    const struct biss_safety_stats *st = &fw->safety.stats;
    cJSON *o = cJSON_AddObjectToObject(j, "safety");
    cJSON_AddNumberToObject(o, "frames_flagged", (double)fw->safety_faults);
    cJSON_AddNumberToObject(o, "first_flagged_frame", fw->safety_first_fault);
    cJSON *lc = cJSON_AddArrayToObject(o, "life_counter");
    for (unsigned i = 0; i < fw->cfg.nslaves; i++) {
        if (fw->cfg.slave[i].life_check) {
            cJSON *s = cJSON_CreateObject();
            cJSON_AddNumberToObject(s, "slave", i);
            cJSON_AddNumberToObject(s, "checked", st->lc_checked[i]);
            cJSON_AddNumberToObject(s, "frozen", st->lc_frozen[i]);
            cJSON_AddNumberToObject(s, "skipped", st->lc_skipped[i]);
            cJSON_AddItemToArray(lc, s);
        }
    }
    cJSON *ew = cJSON_AddArrayToObject(o, "ew_static");
    for (unsigned i = 0; i < fw->cfg.nslaves; i++) {
        if (fw->cfg.slave[i].ew_static) {
            cJSON *s = cJSON_CreateObject();
            cJSON_AddNumberToObject(s, "slave", i);
            cJSON_AddNumberToObject(s, "checked", st->ew_checked[i]);
            cJSON_AddNumberToObject(s, "misframed", st->ew_set[i]);
            cJSON_AddItemToArray(ew, s);
        }
    }
    cJSON *speed = cJSON_AddArrayToObject(o, "max_speed");
    for (unsigned i = 0; i < fw->cfg.nslaves; i++) {
        if (fw->cfg.slave[i].max_speed) {
            cJSON *s = cJSON_CreateObject();
            cJSON_AddNumberToObject(s, "slave", i);
            cJSON_AddNumberToObject(s, "counts_per_s", fw->cfg.slave[i].max_speed);
            cJSON_AddNumberToObject(s, "checked", st->pos_checked[i]);
            cJSON_AddNumberToObject(s, "jumped", st->pos_jumped[i]);
            cJSON_AddNumberToObject(s, "resync", st->pos_resync[i]);
            cJSON_AddItemToArray(speed, s);
        }
    }
    /* frames, not slaves: a frame with two slaves flagged counts once */
    cJSON_AddNumberToObject(o, "misframed_frames", (double)fw->misframed);
    cJSON_AddNumberToObject(o, "misframed_good_lost", (double)fw->misframed_good);
    cJSON *pairs = cJSON_AddArrayToObject(o, "pairs");
    for (unsigned k = 0; k < fw->cfg.npairs; k++) {
        cJSON *p = cJSON_CreateObject();
        cJSON_AddNumberToObject(p, "a", fw->cfg.pair[k].a);
        cJSON_AddNumberToObject(p, "b", fw->cfg.pair[k].b);
        cJSON_AddNumberToObject(p, "checked", st->pair_checked[k]);
        cJSON_AddNumberToObject(p, "disagree", st->pair_disagree[k]);
        cJSON_AddNumberToObject(p, "last_diff", (double)st->pair_last_diff[k]);
        cJSON_AddItemToArray(pairs, p);
    }
}

static void print_safety(const struct fw_check *fw) {
    const struct biss_safety_stats *st = &fw->safety.stats;
    for (unsigned i = 0; i < fw->cfg.nslaves; i++) {
        if (fw->cfg.slave[i].life_check) {
            printf("life counter %u       %u frames checked, %u frozen, %u skipped\n", i,
                   st->lc_checked[i], st->lc_frozen[i], st->lc_skipped[i]);
        }
    }
    for (unsigned i = 0; i < fw->cfg.nslaves; i++) {
        if (fw->cfg.slave[i].ew_static) {
            printf("nE/nW %u              %u frames checked, %u misframed (nE or nW active)\n", i,
                   st->ew_checked[i], st->ew_set[i]);
        }
    }
    for (unsigned i = 0; i < fw->cfg.nslaves; i++) {
        if (fw->cfg.slave[i].max_speed) {
            printf("speed %u              %u positions checked, %u beyond %g counts/s, %u "
                   "resyncs\n",
                   i, st->pos_checked[i], st->pos_jumped[i], fw->cfg.slave[i].max_speed,
                   st->pos_resync[i]);
        }
    }
    if (fw->misframed) {
        printf("misframed            %llu frames refused (nE/nW of a slave that never sets "
               "them, or a position beyond reach), %llu of them good\n",
               (unsigned long long)fw->misframed, (unsigned long long)fw->misframed_good);
    }
    for (unsigned k = 0; k < fw->cfg.npairs; k++) {
        printf("pair %u (slaves %u, %u) %u frames checked, %u disagree, last difference %lld\n", k,
               fw->cfg.pair[k].a, fw->cfg.pair[k].b, st->pair_checked[k], st->pair_disagree[k],
               (long long)st->pair_last_diff[k]);
    }
    if (fw->safety_faults) {
        printf("safety               %llu frames flagged, the first frame %u\n",
               (unsigned long long)fw->safety_faults, fw->safety_first_fault);
    }
}

static void add_control(cJSON *j, const struct fw_cd *cd) {
    cJSON *c = cJSON_AddObjectToObject(j, "control");
    const biss_cd_result *res = &cd->result;
    cJSON_AddStringToObject(c, "result", biss_cd_strerror(cd->err));
    cJSON_AddNumberToObject(c, "frames", (double)cd->frames);
    cJSON_AddNumberToObject(c, "good_bytes", res->good_bytes);
    cJSON *bytes = cJSON_AddArrayToObject(c, "bytes");
    for (unsigned i = 0; i < res->good_bytes; i++) {
        cJSON_AddItemToArray(bytes, cJSON_CreateNumber(res->byte[i].data));
    }
    if (cd->prog->kind == BISS_CD_COMMAND) {
        cJSON_AddNumberToObject(c, "ida", res->ida);
    }
}

cJSON *sim_json(const struct sim_result *r) {
    struct bench *b = r->b;
    const struct bench_stats *st = bench_stats(b);
    const struct fw_check *fw = r->fw;
    cJSON *j = cJSON_CreateObject();
    cJSON_AddStringToObject(j, "profile", bench_link(b)->sc.profile);
    cJSON_AddNumberToObject(j, "freq_hz", r->freq_hz);
    cJSON_AddNumberToObject(j, "cable_m", bench_link(b)->sc.ma_line.length_m);
    cJSON_AddStringToObject(j, "stop", stop_name(r->why));
    cJSON_AddNumberToObject(j, "frames", (double)(fw ? fw->frames : st->frames));
    add_counter(j, "crc_errors", fw, fw ? fw->crc_errors : 0);
    add_counter(j, "position_mismatches", fw, fw ? fw->mismatches : 0);
    if (fw) {
        add_wrong(j, fw);
    }
    cJSON_AddNumberToObject(j, "line_delay_ns", bench_round_trip_ps(b) / 1000.0);
    double mean = st->periods ? st->period_sum_ps / (double)st->periods : 0;
    add_min_mean_max(j, "frame_period_ns", (double)st->period_min_ps / 1000.0, mean / 1000.0,
                     (double)st->period_max_ps / 1000.0);
    cJSON *h = cJSON_AddObjectToObject(j, "ma_half_period_cycles");
    cJSON_AddNumberToObject(h, "min", (double)st->half_min_ps / PRU_PS_PER_CYCLE);
    cJSON_AddNumberToObject(h, "max", (double)st->half_max_ps / PRU_PS_PER_CYCLE);
    cJSON_AddNumberToObject(j, "pru_cycles", (double)pru_cycles(bench_core(b)));
    cJSON_AddNumberToObject(j, "host_seconds", r->host_seconds);
    /* loop iterations the core skipped rather than ran (same results) */
    cJSON_AddNumberToObject(j, "skipped_iterations", (double)pru_ff_skipped(bench_core(b)));
    cJSON_AddItemToObject(j, "slaves", slaves_json(r));
    if (fw) {
        add_firmware(j, b, fw);
    }
    if (fw && any_safety(fw)) {
        add_safety(j, fw);
    }
    if (r->cd) {
        add_control(j, r->cd);
    }
    add_frame_marks(j, st, r->half, r->trigger);
    return j;
}

void sim_print_json_object(cJSON *j) {
    char *text = cJSON_Print(j);
    printf("%s\n", text);
    free(text);
    cJSON_Delete(j);
}

/* Cycles of a span as "lo .. hi cycles (mean m)", each value less less_ps. */
static void print_span(const struct bench_span *s, double less_ps) {
    printf("%.1f .. %.1f cycles (mean %.1f)", ((double)s->min_ps - less_ps) / PRU_PS_PER_CYCLE,
           ((double)s->max_ps - less_ps) / PRU_PS_PER_CYCLE,
           ((double)s->sum_ps / (double)s->n - less_ps) / PRU_PS_PER_CYCLE);
}

/* The frame starts at the master's MA pin (add_frame_marks' text). */
static void print_frame_marks(const struct bench_stats *st, unsigned half, unsigned trigger) {
    if (st->ma_high.n == 0) {
        return;
    }
    double h_ps = (double)half * PRU_PS_PER_CYCLE;
    printf("MA high, frame start ");
    print_span(&st->ma_high, 0);
    printf(" before the first fall; %llu of %llu frames shorter than H = %u\n",
           (unsigned long long)st->ma_high_short, (unsigned long long)st->ma_high.n, half);
    if (trigger == BISS_TRIG_FREERUN && st->restart.n) {
        printf("restart              SL high at the master -> first MA fall ");
        print_span(&st->restart, 0);
        printf(", idle filter H + ");
        print_span(&st->restart, h_ps);
        printf("\n");
    }
    if (st->iep_phase.n) {
        printf("IEP                  period %u cycles: its start -> first MA fall ",
               st->iep_period);
        print_span(&st->iep_phase, 0);
        printf("; %llu frames in %llu periods, %llu without a frame, %llu with two or more\n",
               (unsigned long long)st->iep_phase.n, (unsigned long long)st->iep_periods,
               (unsigned long long)st->iep_skipped, (unsigned long long)st->iep_crowded);
        const struct iep_track *k = &st->iep_track;
        printf("IEP flags            %llu frames judged: %llu flagged late, %llu unflagged off "
               "their time, %llu periods skipped next to no flag\n",
               (unsigned long long)k->judged, (unsigned long long)k->late,
               (unsigned long long)k->unflagged_off, (unsigned long long)k->unflagged_skips);
    }
}

/* The publications' latency and the positions' age (add_publication's text). */
static void print_publication(const struct fw_check *fw) {
    if (fw->latency.n == 0) {
        return;
    }
    double h_ps = (double)fw->half * PRU_PS_PER_CYCLE;
    printf("publication          last bit at the master's SL pin -> ST_SEQ store: ");
    print_span(&fw->latency, 0);
    printf(" after it starts, H + ");
    print_span(&fw->latency, h_ps);
    printf("\n");
    printf("position age         its latch at the slave (BiSS-C: the first MA rise, SSI: the "
           "first fall) -> publication: ");
    print_span(&fw->age, 0);
    printf("\n");
}

void sim_print_json(const struct sim_result *r) {
    sim_print_json_object(sim_json(r));
}

/* Without the firmware: what the encoder(s) sent in the last closed frame. */
static void print_sent(const struct sim_result *r) {
    link_model *l = bench_link(r->b);
    uint64_t n = link_frames(l);
    const void *rec = n ? link_record(l, n - 1) : NULL;
    if (!rec) {
        return;
    }
    slave_frame f;
    l->model->frame(link_model_cfg(l), rec, &f);
    bool biss_c = scenario_chain(&l->sc) != NULL;
    for (unsigned i = 0; i < f.nwords; i++) {
        unsigned long long p = f.word[i].position;
        if (!biss_c && f.nwords == 1) {
            printf("encoder sent         position %llu\n", p);
        } else if (!biss_c) {
            printf("slave %u sent         position %llu (0x%llx)\n", i, p, p);
        } else {
            printf("slave %u sent         position %llu (0x%llx) nE=%d nW=%d crc=0x%x\n", i, p, p,
                   f.word[i].nE, f.word[i].nW, f.word[i].crc);
        }
    }
}

/* With the firmware: what the master read in the last frame it published. */
static void print_read(const struct sim_result *r) {
    const struct fw_check *fw = r->fw;
    const biss_chain_cfg *c = &bench_link(r->b)->sc.biss;
    if (fw->frames == 0) {
        printf("slaves               no valid frame read\n");
    }
    for (unsigned i = 0; fw->frames && i < c->n && i < 8; i++) {
        uint64_t pos;
        int nE, nW;
        struct biss_proto_word w = bench_fw_word(&c->s[i]);
        biss_proto_word_split(&w, fw->data[i], &pos, &nE, &nW);
        printf("slave %u              position %llu (0x%llx), error %s, warning %s, CRC %s "
               "(encoder sent %llu)\n",
               i, (unsigned long long)pos, (unsigned long long)pos, nE ? "no" : "YES",
               nW ? "no" : "YES", (fw->status[i] & BISS_RS_CRC_OK) ? "ok" : "WRONG",
               (unsigned long long)fw->sent[i]);
    }
    static const char *const names[] = {"valid",           "CRC error", "no slave",
                                        "processing time", "training",  "average ready"};
    if (fw->publications == 0) {
        printf("flags                none: the firmware published nothing\n");
        return;
    }
    printf("flags                0x%02x:", fw->last_flags);
    for (unsigned b = 0; b < sizeof(names) / sizeof(names[0]); b++) {
        if (fw->last_flags & (1u << b)) {
            printf(" %s", names[b]);
        }
    }
    printf("\n");
}

/* A register dump: address, hex bytes, 16 to a line. */
static void print_control(const struct fw_cd *cd) {
    const biss_cd_result *res = &cd->result;
    printf("control frame        %s in %llu frames, %u bytes right\n", biss_cd_strerror(cd->err),
           (unsigned long long)cd->frames, res->good_bytes);
    if (cd->prog->kind == BISS_CD_COMMAND) {
        printf("IDA                  0x%02x\n", res->ida);
        return;
    }
    for (unsigned i = 0; i < res->good_bytes; i++) {
        if (i % 16 == 0) {
            printf("%s  0x%02x:", i ? "\n" : "", (cd->prog->addr + i) & 0x7f);
        }
        printf(" %02x", res->byte[i].data);
    }
    if (res->good_bytes) {
        printf("\n");
    }
}

void sim_print_replay(const struct sim_result *r, const char *tape, bool same, bool json) {
    struct pru_core *c = bench_core(r->b);
    double cycles = (double)pru_cycles(c), insns = (double)pru_instructions(c);
    if (json) {
        cJSON *j = cJSON_CreateObject();
        cJSON_AddStringToObject(j, "sl_replay", tape);
        cJSON_AddBoolToObject(j, "same_run", same);
        cJSON_AddStringToObject(j, "stop", stop_name(r->why));
        cJSON_AddNumberToObject(j, "frames", (double)r->fw->frames);
        cJSON_AddNumberToObject(j, "crc_errors", (double)r->fw->crc_errors);
        cJSON_AddNumberToObject(j, "pru_cycles", cycles);
        cJSON_AddNumberToObject(j, "pru_instructions", insns);
        cJSON_AddNumberToObject(j, "host_seconds", r->host_seconds);
        sim_print_json_object(j);
        return;
    }
    printf("SL replayed from %s: %s\n", tape,
           same ? "the recorded run, instruction for instruction" : "NOT the recorded run");
    printf("frames:        %llu valid, %llu with a CRC error\n", (unsigned long long)r->fw->frames,
           (unsigned long long)r->fw->crc_errors);
    printf("PRU:           %.0f cycles, %.0f instructions\n", cycles, insns);
    printf("host:          %.3f s, %.2fx real time, no cable or encoder model\n", r->host_seconds,
           r->host_seconds > 0 ? cycles * PRU_PS_PER_CYCLE / SIM_PS_PER_S / r->host_seconds : 0.0);
}

void sim_print_text(const struct sim_result *r) {
    struct bench *b = r->b;
    const struct bench_stats *st = bench_stats(b);
    const struct fw_check *fw = r->fw;
    link_model *l = bench_link(b);
    printf("profile %s, %.3g MHz, %.1f m cable: %llu frames (%s)\n", l->sc.profile,
           r->freq_hz / 1e6, l->sc.ma_line.length_m,
           (unsigned long long)(fw ? fw->frames : st->frames), stop_name(r->why));
    if (fw) {
        printf("checked              %llu CRC errors, %llu position mismatches, %llu no-slave, "
               "%llu processing-time errors, %llu refused for an ACK jump, %llu for an edge "
               "off the bit grid\n",
               (unsigned long long)fw->crc_errors, (unsigned long long)fw->mismatches,
               (unsigned long long)fw->no_slave, (unsigned long long)fw->proc_errors,
               (unsigned long long)fw->ack_jumps, (unsigned long long)fw->off_grid);
        print_wrong(fw);
        const struct biss_link_stats *k = &fw->link.stats;
        if (k->frames) {
            printf("link                 eye %.2f/8 bit on average, at least %u/8 (frames by eye "
                   "0..4/8: %u %u %u %u %u); %u marginal, warning on %u frames (%u in %u)\n",
                   biss_link_eye_mean(k), k->eye_min, k->eye[0], k->eye[1], k->eye[2], k->eye[3],
                   k->eye[4], k->marginal, k->warnings, fw->link.warn, fw->link.window);
        }
        if (fw->delay_frames) {
            /* one frame's figures, the last one's: the firmware measures to 1/8 bit and
             * averages 4 frames, so a run's first frames may differ from its last by a step */
            printf("line delay           %.1f ns measured by the firmware in frame %u, the last "
                   "(%.1f ns in the model), sample point %u/8, lag %u periods\n"
                   "                     (lag: a bit is read that many MA periods after the "
                   "clock that made it, at the sample point; pru_fw/README.md)\n",
                   sim_fw_line_delay_ns(fw), fw->delay_frame, bench_round_trip_ps(b) / 1000.0,
                   fw->sample_point, fw->lag);
        } else {
            printf("line delay           not measured: the firmware published no frame with an "
                   "ACK (%.1f ns in the model)\n",
                   bench_round_trip_ps(b) / 1000.0);
        }
    } else {
        printf("round trip (model)   %.1f ns\n", bench_round_trip_ps(b) / 1000.0);
    }
    printf("MA half period       %lld .. %lld cycles\n",
           (long long)(st->half_min_ps / PRU_PS_PER_CYCLE),
           (long long)(st->half_max_ps / PRU_PS_PER_CYCLE));
    if (st->periods) {
        printf("frame period         %.1f .. %.1f ns (mean %.1f)\n", st->period_min_ps / 1000.0,
               st->period_max_ps / 1000.0, st->period_sum_ps / (double)st->periods / 1000.0);
    }
    printf("PRU cycles           %lld in %.3f s host time\n", (long long)pru_cycles(bench_core(b)),
           r->host_seconds);
    print_frame_marks(st, r->half, r->trigger);
    if (fw) {
        print_publication(fw);
        print_read(r);
        if (any_safety(fw)) {
            print_safety(fw);
        }
    } else {
        print_sent(r);
    }
    if (r->cd) {
        print_control(r->cd);
    }
}

/* Rising edges of w after t0 up to t1, at most max. */
static size_t rises(waveform *w, sim_ps t0, sim_ps t1, sim_ps *out, size_t max) {
    size_t n = 0;
    for (sim_ps t = waveform_next_after(w, t0); t <= t1 && n < max; t = waveform_next_after(w, t)) {
        if (waveform_level_at(w, t) == 1) {
            out[n++] = t;
        }
    }
    return n;
}

/* The firmware's side of the picture: where it sampled each bit at the
 * master's SL and the line delay it measured, from what it published for
 * this frame. A bit goes out on SL at the slave on the MA rise that clocks
 * it; the firmware places that bit's edge at the master one measured round
 * trip after the rise at the master pin (the 4-frame average it samples
 * by, converted by proto) and samples half a bit (H cycles) later, to 1/8
 * bit (its published sample point). */
struct svg_fw {
    sim_ps marks[FRAME_LABELS_MAX];
    size_t nmarks;
    struct svg_arrow arrow;
    int has_arrow;
};

static void firmware_marks(const struct sim_result *r, const struct svg_label *labels, size_t n,
                           waveform *pins[4], sim_ps t0, sim_ps t1, sim_ps slave_start,
                           struct svg_fw *out) {
    const struct fw_frame *f = &r->fw->watched;
    link_model *l = bench_link(r->b);
    double rt_cycles = line_delay(f->delay_raw, f->delay_avg, f->half).cycles;
    sim_ps rt = (sim_ps)(rt_cycles * PRU_PS_PER_CYCLE);
    sim_ps half = (sim_ps)f->half * PRU_PS_PER_CYCLE;
    sim_ps out_delay = l->model->out_delay(link_model_cfg(l));
    static sim_ps rm[FRAME_LABELS_MAX], rs[FRAME_LABELS_MAX];
    size_t nm = rises(pins[0], t0, t1, rm, FRAME_LABELS_MAX);
    size_t ns = rises(pins[2], slave_start, t1, rs, FRAME_LABELS_MAX);
    out->nmarks = 0;
    /* the MA rise of each named bit, by its place among the frame's rises */
    for (size_t i = 0; i < n; i++) {
        const char *txt = labels[i].text;
        if (!strcmp(txt, "ACK") || !strcmp(txt, "timeout")) {
            continue;
        }
        for (size_t j = 0; j < ns && j < nm; j++) {
            if (rs[j] + out_delay == labels[i].t0) {
                out->marks[out->nmarks++] = rm[j] + rt + half;
                break;
            }
        }
    }
    /* the line delay: a BiSS-C ACK answers the second rise */
    out->has_arrow = scenario_chain(&l->sc) && nm >= 2;
    if (out->has_arrow) {
        out->arrow.trace = 1;
        out->arrow.t0 = rm[1];
        out->arrow.t1 = rm[1] + rt;
        snprintf(out->arrow.text, sizeof(out->arrow.text), "line delay %.1f ns (firmware)",
                 rt_cycles * 5.0);
    }
}

/* What the firmware read in the frame, one line per slave, and its flags. */
static size_t firmware_notes(const struct sim_result *r, char (*notes)[160], size_t max) {
    const struct fw_frame *f = &r->fw->watched;
    const biss_chain_cfg *c = &bench_link(r->b)->sc.biss;
    size_t n = 0;
    snprintf(notes[n++], 160,
             "firmware: frame %u, flags 0x%02x, line delay %.1f ns, sample point %u/8, lag %u, "
             "eye %d/8, timestamp %.3f us (IEP %u)",
             f->frame, f->flags, line_delay(f->delay_raw, f->delay_avg, f->half).ns,
             f->sample_point, f->lag, biss_link_eye(&f->sample), f->timestamp * 5e-3, f->timestamp);
    if (!(f->flags & BISS_RF_VALID)) {
        snprintf(notes[n++], 160, "  no data in this frame (%s)",
                 (f->flags & BISS_RF_TRAINING)   ? "training frame"
                 : (f->flags & BISS_RF_OFF_GRID) ? "an SL edge off the bit grid"
                                                 : "not valid");
        return n;
    }
    const slave_model *m = bench_link(r->b)->model;
    if (!m->chain) {
        snprintf(notes[n++], 160, "  encoder word read: %llu (0x%llx), %s",
                 (unsigned long long)f->data[0], (unsigned long long)f->data[0],
                 m->word_note ? m->word_note : "as sent");
        return n;
    }
    for (unsigned i = 0; i < c->n && i < f->nslaves && n < max; i++) {
        uint64_t pos;
        int nE, nW;
        struct biss_proto_word w = bench_fw_word(&c->s[i]);
        biss_proto_word_split(&w, f->data[i], &pos, &nE, &nW);
        snprintf(notes[n++], 160, "  slave %u read: position %llu (0x%llx), nE %d, nW %d, CRC %s",
                 i, (unsigned long long)pos, (unsigned long long)pos, nE, nW,
                 (f->status[i] & BISS_RS_CRC_OK) ? "ok" : "WRONG");
    }
    return n;
}

int sim_write_svg(const struct sim_result *r, const char *path, uint64_t k, char *err,
                  size_t errlen) {
    waveform *pins[4];
    sim_ps t0, t1;
    const void *rec = bench_capture_record(r->b);
    if (bench_capture_get(r->b, pins, &t0, &t1) != 0 || !rec) {
        snprintf(err, errlen, "--svg: frame %llu was not captured whole (run more frames?)",
                 (unsigned long long)k);
        return -1;
    }
    static struct svg_label labels[FRAME_LABELS_MAX];
    link_model *l = bench_link(r->b);
    size_t n = frame_labels(l, rec, pins[2], labels, FRAME_LABELS_MAX);
    static const char *const names[4] = {"MA master", "SL master", "MA slave", "SL slave"};
    struct svg_trace tr[4];
    for (int i = 0; i < 4; i++) {
        tr[i] = (struct svg_trace){
            names[i], pins[i], i == 3 ? labels : NULL, i == 3 ? n : 0, NULL, 0, 0, 0};
    }
    char title[200];
    snprintf(title, sizeof(title), "%s, %.3g MHz, %.1f m: frame %llu (frame 1 is the first)",
             l->sc.profile, r->freq_hz / 1e6, l->sc.ma_line.length_m, (unsigned long long)k);
    struct svg_view v = {title, tr, 4, NULL, 0, NULL, NULL, NULL, 0, t0, t1};
    static struct svg_fw fw;
    char notes[1 + BISS_MAX_SLAVES][160];
    if (r->fw && r->fw->watched.seen) {
        slave_frame sf;
        l->model->frame(link_model_cfg(l), rec, &sf);
        sim_ps slave_start = sf.start_ps;
        firmware_marks(r, labels, n, pins, t0, t1, slave_start, &fw);
        tr[1].marks = fw.marks;
        tr[1].nmarks = fw.nmarks;
        v.mark_legend = "where the firmware samples each bit at the master: MA rise + its "
                        "measured line delay + half a bit";
        unsigned h = r->fw->watched.half;
        if (h >= BISS_GRID_MIN_HALF) { /* the bit-grid check's window: a sample is H/4 cycles */
            tr[1].before = (sim_ps)BISS_GRID_OLDER * h * PRU_PS_PER_CYCLE / 4;
            tr[1].after = (sim_ps)BISS_GRID_NEWER * h * PRU_PS_PER_CYCLE / 4;
            v.band_legend = "the bit-grid check: SL must hold still there (an edge in it: "
                            "off-grid, the frame not valid)";
        }
        v.arrows = fw.has_arrow ? &fw.arrow : NULL;
        v.narrows = fw.has_arrow ? 1 : 0;
        v.notes = notes;
        v.nnotes = firmware_notes(r, notes, 1 + BISS_MAX_SLAVES);
    }
    char why[PATH_MAX + 128];
    if (svg_scope_write(path, &v, why, sizeof why) != 0) {
        snprintf(err, errlen, "cannot write the SVG: %s", why);
        return -1;
    }
    return 0;
}
