/*
 * End-to-end: the firmware's behaviour beyond the matrix — across the
 * emulator's uncertain timing parameters, with bad configurations written
 * raw, processing time at and over the limit, a disconnected and
 * reconnected slave, the three triggers and a rate change at run time.
 */
#include "e2e_util.h"

#include "biss/biss_shm.h"

#include "check_run.h"

#include <check.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>

static uint64_t frames_per_case(void) {
    uint64_t n = e2e_frames(10000) / 20;
    return n < 50 ? 50 : n;
}

/* ---- uncertain parameters: shift-clock phase and divider pattern, input
 * synchronizer and output delay (emulator/core/TIMING.md) ---- */
START_TEST(test_uncertain_parameters) {
    static const int64_t phases[] = {0, 1250, 2500, 3750, 9000};
    static const int64_t gpi[] = {0, 5000, 10000, 15000};
    static const unsigned halves[] = {10, 50};
    struct pru_params p;
    pru_params_default(&p);
    p.shift_phase_ps = phases[_i % 5];
    p.gpi_delay_ps = gpi[(_i / 5) % 4];
    p.shift_frac = (_i / 20) % 2 ? PRU_FRAC_CYCLE : PRU_FRAC_EXACT;
    p.gpo_delay_ps = (_i / 40) % 2 ? 2500 : 0;
    unsigned half = halves[(_i / 80) % 2];
    struct e2e_run r;
    struct bench *b = e2e_bench(&r, _i % 2 ? "hengstler-ad38" : "tidep0022-test-encoder", 10, &p);
    uint64_t n = frames_per_case() / 4;
    ck_assert_uint_eq(e2e_run_frames(&r, half, 1000, n), n);
    ck_assert_uint_eq(r.fc.crc_errors, 0);
    ck_assert_uint_eq(r.fc.mismatches, 0);
    ck_assert_int_eq(bench_stats(b)->half_min_ps, (int64_t)half * PRU_PS_PER_CYCLE);
    ck_assert_int_eq(bench_stats(b)->half_max_ps, (int64_t)half * PRU_PS_PER_CYCLE);
    e2e_free(&r);
}
END_TEST

/* ---- the raw line delay at 4 MHz: 6.25 cycles per sample, so the frame
 * start takes 25 phases against the shift clock. The ACK edge lies at the
 * same time in every frame, so the raw ACK position of every frame is one
 * of two neighbours, whatever the phase: also when the edge falls just
 * before a window's oldest sample and the one-period ACK (shortened by the
 * line's rise/fall skew) ends before its newest, which then reads the start
 * bit ---- */
START_TEST(test_raw_delay_every_shift_phase) {
    struct pru_params p;
    pru_params_default(&p);
    p.shift_phase_ps = (int64_t)_i * 1250;
    struct e2e_run r;
    e2e_bench(&r, "tidep0022-test-encoder", 2, &p);
    ck_assert_uint_eq(e2e_run_frames(&r, 25, 1000, 10), 10);
    ck_assert_uint_eq(r.fc.mismatches, 0);
    ck_assert_msg(r.fc.delay_raw_max - r.fc.delay_raw_min <= 1,
                  "shift phase %d ps: raw ACK positions %u..%u", _i * 1250, r.fc.delay_raw_min,
                  r.fc.delay_raw_max);
    e2e_free(&r);
}
END_TEST

/* ---- data words of every awkward width: 1, 31, 32, 33, 63 and 64 bits,
 * with and without nE/nW, the position starting just below its top so the
 * high bits move. Every word as sent, CRC right, nE/nW as sent. ---- */
static const struct {
    unsigned pos_bits;
    bool ew;
} widths[] = {{1, false},  {29, true}, {30, true}, {32, false}, {31, true},
              {33, false}, {61, true}, {62, true}, {63, false}, {64, false}};

START_TEST(test_data_word_widths) {
    scenario sc;
    ck_assert_int_eq(profile_by_name("generic", &sc), 0);
    scenario_set_cable(&sc, 10.0);
    biss_slave_cfg *c = &sc.biss.s[0];
    c->pos_bits = widths[_i].pos_bits;
    c->has_err = c->has_warn = widths[_i].ew;
    c->warning = widths[_i].ew; /* nW active: a 0 among the ones */
    uint64_t top = c->pos_bits >= 64 ? ~0ull : (1ull << c->pos_bits) - 1u;
    c->pos0 = top - 20; /* wraps through all ones to zero during the run */
    c->speed_cps = 1e6;
    struct e2e_run r;
    e2e_bench_scenario(&r, &sc, NULL);
    ck_assert_uint_eq(e2e_run_frames(&r, 20, 1000, 100), 100);
    ck_assert_msg(r.fc.mismatches == 0 && r.fc.crc_errors == 0,
                  "%u position bits%s: %llu mismatches, %llu CRC errors", c->pos_bits,
                  widths[_i].ew ? " + nE/nW" : "", (unsigned long long)r.fc.mismatches,
                  (unsigned long long)r.fc.crc_errors);
    ck_assert_uint_eq(r.fc.unmatched, 0);
    if (widths[_i].ew) { /* nE high (no error), nW low (warning) in the last frame */
        ck_assert(r.fc.status[0] & BISS_RS_NE);
        ck_assert(!(r.fc.status[0] & BISS_RS_NW));
    }
    e2e_free(&r);
}
END_TEST

/* ---- configurations the host library would refuse, written raw (one
 * field of proto's encoded block broken) ---- */
struct bad_cfg {
    size_t off, bytes; /* a field of struct biss_shm_config */
    uint32_t value;
    uint32_t want_error;
};

#define CFG_FIELD(f) offsetof(struct biss_shm_config, f), sizeof(((struct biss_shm_config *)0)->f)
static const struct bad_cfg bad[] = {
    {CFG_FIELD(nslaves), 0, BISS_CFGERR_NSLAVES},
    {CFG_FIELD(nslaves), 9, BISS_CFGERR_NSLAVES},
    {CFG_FIELD(half), 9, BISS_CFGERR_HALF},    /* above 10 MHz */
    {CFG_FIELD(half), 11, BISS_CFGERR_HALF},   /* 9.09 MHz: no exact 8x clock */
    {CFG_FIELD(half), 1000, BISS_CFGERR_HALF}, /* 100 kHz: 1000 = 8 x 125 */
    {CFG_FIELD(half), 1025, BISS_CFGERR_HALF},
    {CFG_FIELD(trigger), 4, BISS_CFGERR_TRIGGER},
    {CFG_FIELD(slave[0].data_bits), 0, BISS_CFGERR_DATA_BITS},
    {CFG_FIELD(slave[0].data_bits), 65, BISS_CFGERR_DATA_BITS},
    {CFG_FIELD(slave[0].crc_bits), 17, BISS_CFGERR_CRC_BITS},
    {CFG_FIELD(slave[0].ew_shift), 13, BISS_CFGERR_EW}, /* nE past bit 13 */
};

START_TEST(test_bad_config_is_flagged) {
    struct e2e_run r;
    struct bench *b = e2e_bench(&r, "tidep0022-test-encoder", 2, NULL);
    /* first a good one, running */
    ck_assert_uint_eq(e2e_run_frames(&r, 10, 1000, 20), 20);
    uint32_t seq = e2e_cfg_seq(b);
    /* the good block again, with one field broken */
    struct biss_config c;
    bench_fw_config(b, &c);
    c.freq_hz = 10000000;
    c.trigger = BISS_TRIGGER_FREERUN;
    c.proc_limit = 1000;
    struct biss_shm_config blk;
    bench_fw_block(&c, 0, &blk);
    memcpy((uint8_t *)&blk + bad[_i].off, &bad[_i].value, bad[_i].bytes); /* little-endian */
    ck_assert_int_eq(bench_fw_put_block(b, &blk), 0);
    uint64_t pubs = r.fc.publications;
    ck_assert_int_eq(bench_run_until(b, pru_time_ps(bench_core(b)) + 2 * SIM_PS_PER_MS),
                     PRU_STOP_LIMIT); /* no fault, no halt: it goes on */
    struct biss_shm_status st = bench_fw_status(b);
    ck_assert_uint_eq(st.cfg_ack, seq + 1);
    ck_assert_uint_eq(st.cfg_error, bad[_i].want_error);
    ck_assert_uint_eq(st.state, BISS_STATE_CFG_ERROR);
    ck_assert_uint_le(r.fc.publications, pubs + 1); /* no frames on a refused config */
    /* and a good configuration brings it back */
    uint64_t frames = r.fc.frames;
    fw_check_restart(&r.fc, UINT64_MAX);
    ck_assert_uint_eq(e2e_run_frames(&r, 20, 1000, 20), 20);
    ck_assert_uint_eq(bench_fw_status(b).cfg_error, BISS_CFGERR_NONE);
    ck_assert_uint_eq(r.fc.mismatches, 0);
    (void)frames;
    e2e_free(&r);
}
END_TEST

/* ---- processing time: the AD38 chain is busy 2.4 us, 24 clocks at
 * 10 MHz (23 after the ACK's own): a limit of 23 passes, 22 aborts ---- */
START_TEST(test_processing_time_limit) {
    struct e2e_run r;
    struct bench *b = e2e_bench(&r, "hengstler-ad38", 2, NULL);
    ck_assert_uint_eq(e2e_run_frames(&r, 10, 23, 100), 100);
    ck_assert_uint_eq(r.fc.proc_clocks_max, 23);
    ck_assert_uint_eq(r.fc.proc_errors, 0);
    ck_assert_uint_eq(r.fc.mismatches, 0);
    r.fc.cfg.freq_hz = 10000000;
    r.fc.cfg.trigger = BISS_TRIGGER_FREERUN;
    r.fc.cfg.proc_limit = 22;
    e2e_configure(&r, 0);
    fw_check_restart(&r.fc, UINT64_MAX);
    e2e_run_publications(&r, 20, 20 * SIM_PS_PER_MS);
    ck_assert_uint_ge(r.fc.proc_errors, 19); /* all but the training */
    ck_assert_uint_eq(r.fc.frames, 0);
    ck_assert_uint_ge(bench_fw_status(b).proc_errors, 19);
    e2e_free(&r);
}
END_TEST

/* ---- processing time at the firmware's 16-bit busy count: a slave busy
 * for 65534 clocks (BISS_MAX_PROC_LIMIT) passes at that limit and aborts
 * one below it; one busy longer than the count holds (70000 clocks) aborts
 * at the API's longest limit, every frame, none published valid (a count
 * that wrapped to 0 would have taken the start bit at 70000 - 65536 and
 * published 4464 clocks as a valid frame) ---- */
static void busy_run(struct e2e_run *r, unsigned busy_clocks, unsigned limit, uint64_t n) {
    scenario sc;
    ck_assert_int_eq(profile_by_name("tidep0022-test-encoder", &sc), 0);
    sc.biss.busy_clocks = busy_clocks;
    e2e_bench_scenario(r, &sc, NULL);
    r->fc.cfg.trigger = BISS_TRIGGER_FREERUN;
    r->fc.cfg.proc_limit = limit;
    e2e_configure(r, 10);
    /* the training frames, then n publications of 6.6 ms (65536 clocks) or so */
    e2e_run_publications(r, 6, 60 * SIM_PS_PER_MS);
    fw_check_restart(&r->fc, UINT64_MAX);
    e2e_run_publications(r, n, (int64_t)n * 10 * SIM_PS_PER_MS);
}

START_TEST(test_processing_time_16_bit_limit) {
    struct e2e_run r;
    busy_run(&r, BISS_MAX_PROC_LIMIT, BISS_MAX_PROC_LIMIT, 2);
    ck_assert_uint_eq(r.fc.frames, 2);
    ck_assert_uint_eq(r.fc.proc_clocks_max, BISS_MAX_PROC_LIMIT);
    ck_assert_uint_eq(r.fc.proc_errors, 0);
    ck_assert_uint_eq(r.fc.mismatches, 0);
    e2e_free(&r);
    busy_run(&r, BISS_MAX_PROC_LIMIT, BISS_MAX_PROC_LIMIT - 1, 2);
    ck_assert_uint_eq(r.fc.frames, 0);
    ck_assert_uint_ge(r.fc.proc_errors, 2);
    e2e_free(&r);
}
END_TEST

START_TEST(test_busy_past_the_count) {
    struct biss_config c;
    biss_config_default(&c);
    c.nslaves = 1;
    c.slave[0].data_bits = 1;
    /* the longest limit the API accepts */
    c.proc_limit = 0xffff;
    while (biss_config_check(&c) == BISS_E_PROC_LIMIT) {
        c.proc_limit--;
    }
    ck_assert_int_eq(biss_config_check(&c), BISS_OK);
    struct e2e_run r;
    busy_run(&r, 70000, c.proc_limit, 2);
    ck_assert_uint_eq(r.fc.frames, 0);
    ck_assert_uint_ge(r.fc.proc_errors, 2);
    ck_assert_uint_eq(r.fc.mismatches, 0);
    e2e_free(&r);
}
END_TEST

/* ---- a slave that goes away (SL stuck low, or open: reads high) and
 * comes back: reported as no slave, retried, never halted ---- */
START_TEST(test_disconnect_and_reconnect) {
    static const line_fault faults[] = {LINE_STUCK_LOW, LINE_STUCK_HIGH, LINE_OPEN};
    struct e2e_run r;
    struct bench *b = e2e_bench(&r, "tidep0022-test-encoder", 10, NULL);
    ck_assert_uint_eq(e2e_run_frames(&r, 10, 1000, 50), 50);
    link_model *l = bench_link(b);
    sim_ps t = pru_time_ps(bench_core(b));
    line_dir_set_fault(_i == 2 ? &l->ma_line : &l->sl_line, t, faults[_i]);
    fw_check_restart(&r.fc, UINT64_MAX);
    ck_assert_int_eq(bench_run_until(b, t + 5 * SIM_PS_PER_MS), PRU_STOP_LIMIT);
    ck_assert_uint_gt(r.fc.no_slave, 0);
    ck_assert_uint_eq(r.fc.mismatches, 0);
    ck_assert_uint_eq(bench_fw_status(b).state, BISS_STATE_RUNNING);
    /* reconnected: valid frames again */
    line_dir_set_fault(_i == 2 ? &l->ma_line : &l->sl_line, t + 5 * SIM_PS_PER_MS, LINE_OK);
    uint64_t before = r.fc.frames;
    ck_assert_int_eq(bench_run_until(b, t + 10 * SIM_PS_PER_MS), PRU_STOP_LIMIT);
    ck_assert_uint_gt(r.fc.frames, before + 50);
    ck_assert_uint_eq(r.fc.mismatches, 0);
    e2e_free(&r);
}
END_TEST

/* ---- triggers: host (one frame per CMD_TRIGGER), IEP (exact period) ---- */
START_TEST(test_host_trigger) {
    struct e2e_run r;
    struct bench *b = e2e_bench(&r, "tidep0022-test-encoder", 2, NULL);
    struct biss_config c;
    bench_fw_config(b, &c);
    c.freq_hz = 10000000;
    c.trigger = BISS_TRIGGER_HOST;
    c.proc_limit = 1000;
    ck_assert_int_eq(bench_fw_configure(b, &c, 0), 0);
    ck_assert_int_eq(bench_run_until(b, 2 * SIM_PS_PER_MS), PRU_STOP_LIMIT);
    ck_assert_uint_eq(r.fc.training, 1);
    ck_assert_uint_eq(r.fc.frames, 0); /* nothing without a trigger */
    for (unsigned i = 1; i <= 5; i++) {
        struct biss_proto_io io = bench_fw_io(b);
        uint32_t pending = 1;
        ck_assert_int_eq(biss_proto_trigger(&io), 0);
        ck_assert_int_eq(bench_run_until(b, pru_time_ps(bench_core(b)) + SIM_PS_PER_MS),
                         PRU_STOP_LIMIT);
        ck_assert_uint_eq(r.fc.frames, i);
        ck_assert_int_eq(biss_proto_trigger_get(&io, &pending), 0);
        ck_assert_uint_eq(pending, 0); /* cleared */
    }
    ck_assert_uint_eq(r.fc.mismatches, 0);
    e2e_free(&r);
}
END_TEST

/* IEP-triggered frames at half period `half`, every `period` counts: after
 * the training and three frames, the next `n` frames start exactly one IEP
 * period (CMP0 + 1 counts, see TIMING.md) apart, every one right. */
static void iep_period_exact(const char *profile, unsigned half, uint32_t period, uint64_t n,
                             const struct pru_params *p) {
    struct e2e_run r;
    struct bench *b = e2e_bench(&r, profile, 2, p);
    struct biss_config c;
    bench_fw_config(b, &c);
    c.trigger = BISS_TRIGGER_IEP;
    c.iep_period_ns = period * 5u; /* 5 ns IEP counts */
    c.proc_limit = 1000;
    int64_t period_ps = (int64_t)period * PRU_PS_PER_CYCLE;
    ck_assert_int_eq(bench_fw_configure(b, &c, half), 0);
    e2e_run_publications(&r, 3, 10 * SIM_PS_PER_MS);
    bench_reset_stats(b);
    fw_check_restart(&r.fc, UINT64_MAX);
    e2e_run_publications(&r, n, (int64_t)(n + 5) * period_ps);
    const struct bench_stats *st = bench_stats(b);
    ck_assert_uint_ge(st->periods, n - 2);
    ck_assert_msg(st->period_min_ps == st->period_max_ps,
                  "%s H=%u: frame periods %lld..%lld ps, want all the same", profile, half,
                  (long long)st->period_min_ps, (long long)st->period_max_ps);
    ck_assert_int_ge(st->period_min_ps, period_ps);
    ck_assert_int_le(st->period_min_ps, period_ps + PRU_PS_PER_CYCLE);
    ck_assert_uint_eq(r.fc.mismatches, 0);
    ck_assert_uint_eq(r.fc.crc_errors, 0);
    e2e_free(&r);
}

START_TEST(test_iep_trigger_period) {
    iep_period_exact("hengstler-ad38", 10, 10000, 40, NULL);
}
END_TEST

/* The same under data-RAM contention: the loads before a frame stall, but
 * none lies between the IEP alignment and period 0, so frames still start
 * on the same count. A BiSS-C and an SSI profile, 10 MHz and 1 MHz. */
static const char *const iep_contend_specs[] = {"4,3", "2,8,random:7"};
static const char *const iep_contend_profiles[] = {"hengstler-ad38", "ssi"};
static const unsigned iep_contend_halves[] = {10, 100};

START_TEST(test_iep_trigger_contended) {
    const char *spec = iep_contend_specs[_i % 2];
    const char *profile = iep_contend_profiles[(_i / 2) % 2];
    unsigned half = iep_contend_halves[_i / 4];
    struct pru_params p;
    pru_params_default(&p);
    char err[200];
    ck_assert_int_eq(pru_contend_parse(spec, &p, err, sizeof err), 0);
    iep_period_exact(profile, half, 1000 * half, 20, &p);
}
END_TEST

/* IEP periods the firmware cannot keep are flagged, never skipped in
 * silence (issue 23): a frame that did not start on its period's count, or
 * that ran into the next period, carries BISS_RF_IEP_LATE. Every frame is
 * traced from its first MA edge (the slave's frame number) to its
 * publication; then every frame published without the flag started on the
 * same count of its period as every other such frame (its timestamp the
 * same too), and every period in which no frame started lies next to a
 * flagged frame (the one before ran into it, or the one after came late).
 * At a period the firmware keeps, no frame is flagged and none skipped. */
#define IEP_TRACED 120

struct iep_start {
    uint64_t frame; /* the slave's number */
    int64_t t;      /* its first MA edge at the master pin (ps) */
    int64_t period; /* the IEP period it began in: its first cycle */
    int64_t phase;  /* cycles from there to the edge's */
};
struct iep_pub {
    uint64_t frame;
    uint32_t flags, stamp;
};
struct iep_trace {
    struct iep_start start[IEP_TRACED + 8];
    struct iep_pub pub[IEP_TRACED];
    unsigned ns, np;
};

static void iep_trace(struct e2e_run *r, unsigned nslaves, struct iep_trace *tr) {
    struct bench *b = r->b;
    struct biss_proto_io io = bench_fw_io(b);
    uint64_t seen = r->fc.publications;
    int64_t end = pru_time_ps(bench_core(b)) + 200 * SIM_PS_PER_MS;
    tr->ns = tr->np = 0;
    while (tr->np < IEP_TRACED && pru_time_ps(bench_core(b)) < end) {
        /* a step far shorter than a publication to the next frame's start */
        ck_assert_int_eq(bench_run_until(b, pru_time_ps(bench_core(b)) + 100 * SIM_PS_PER_NS),
                         PRU_STOP_LIMIT);
        if (r->fc.publications != seen) {
            seen = r->fc.publications;
            struct biss_shm_result res;
            ck_assert_int_eq(biss_proto_result_get(&io, nslaves, &res), 0);
            if (tr->ns > 0)
                tr->pub[tr->np++] =
                    (struct iep_pub){bench_current_frame(b), res.flags, res.timestamp};
        }
        int64_t t = bench_frame_start_ps(b);
        if (t >= 0 && (tr->ns == 0 || tr->start[tr->ns - 1].t != t) && tr->ns < IEP_TRACED + 8) {
            /* its period as the bench places it (frame_marks.c): the IEP now */
            struct pru_iep_view v;
            pru_iep_view(bench_core(b), pru_cycles(bench_core(b)), &v);
            int64_t len = (int64_t)v.cmp0 + 1, ref = v.cycle - v.count;
            int64_t edge = (t - bench_config(b)->pru.gpo_delay_ps) / PRU_PS_PER_CYCLE;
            int64_t phase = ((edge - ref) % len + len) % len;
            tr->start[tr->ns++] =
                (struct iep_start){bench_current_frame(b), t, edge - phase, phase};
        }
    }
    ck_assert_uint_eq(tr->np, IEP_TRACED);
}

static int iep_pub_of(const struct iep_trace *tr, uint64_t frame) {
    for (unsigned i = 0; i < tr->np; i++)
        if (tr->pub[i].frame == frame)
            return (int)i;
    return -1;
}

/* The frames of `profile` at half period `half`, every `period` counts:
 * returns how many were flagged. */
static unsigned iep_flagged(const char *profile, unsigned half, uint32_t period) {
    struct e2e_run r;
    struct bench *b = e2e_bench(&r, profile, 2, NULL);
    r.fc.cfg.trigger = BISS_TRIGGER_IEP;
    r.fc.cfg.iep_period_ns = period * 5u; /* 5 ns IEP counts */
    r.fc.cfg.proc_limit = 1000;
    ck_assert_int_eq(fw_check_configure(&r.fc, half), 0);
    e2e_run_publications(&r, 20, 20 * SIM_PS_PER_MS); /* training, the first periods */
    fw_check_restart(&r.fc, UINT64_MAX);
    static struct iep_trace tr;
    iep_trace(&r, bench_link(b)->sc.biss.n, &tr);
    int ref = -1; /* a frame on its count */
    unsigned flagged = 0;
    for (unsigned k = 0; k + 1 < tr.ns; k++) {
        int a = iep_pub_of(&tr, tr.start[k].frame), c = iep_pub_of(&tr, tr.start[k + 1].frame);
        if (a < 0 || c < 0)
            continue;
        int late_a = (tr.pub[a].flags & BISS_RF_IEP_LATE) != 0;
        int late_c = (tr.pub[c].flags & BISS_RF_IEP_LATE) != 0;
        ck_assert_msg(tr.pub[a].flags & BISS_RF_VALID, "%s: frame %u flags %#x", profile, k,
                      tr.pub[a].flags);
        if (!late_a) {
            if (ref < 0)
                ref = (int)k;
            ck_assert_msg(tr.start[k].phase == tr.start[ref].phase,
                          "%s, period %u: frame %u unflagged, %lld cycles into its period, "
                          "frame %d %lld",
                          profile, period, k, (long long)tr.start[k].phase, ref,
                          (long long)tr.start[ref].phase);
            ck_assert_uint_eq(tr.pub[a].stamp, tr.pub[iep_pub_of(&tr, tr.start[ref].frame)].stamp);
        }
        flagged += late_a;
        int64_t gap = (tr.start[k + 1].period - tr.start[k].period) / (int64_t)period;
        ck_assert_msg(gap >= 1, "%s, period %u: frames %u and %u in one period", profile, period, k,
                      k + 1);
        if (gap > 1) /* periods without a frame start */
            ck_assert_msg(late_a || late_c,
                          "%s, period %u: %lld period(s) skipped after frame "
                          "%u, neither frame flagged",
                          profile, period, (long long)(gap - 1), k);
    }
    ck_assert_uint_eq(r.fc.mismatches, 0);
    ck_assert_uint_eq(r.fc.bad_results, 0);
    e2e_free(&r);
    return flagged;
}

/* AD38 (its 650 ns timeout ends before the firmware is done: the shortest
 * period the firmware keeps is 2863 counts at 10 MHz, some 3200 when the
 * host's reads stall the loads between frames, E2E_CONTEND 4,3) and the
 * TIDEP0022 encoder (its timeout is the longer: 4548). */
START_TEST(test_iep_overrun_flagged) {
    ck_assert_uint_gt(iep_flagged("hengstler-ad38", 10, 2000), IEP_TRACED / 2);
    ck_assert_uint_gt(iep_flagged("hengstler-ad38", 10, 2800), 0);
    ck_assert_uint_gt(iep_flagged("tidep0022-test-encoder", 10, 4000), 0);
    ck_assert_uint_eq(iep_flagged("hengstler-ad38", 10, 3500), 0);
    ck_assert_uint_eq(iep_flagged("tidep0022-test-encoder", 10, 5000), 0);
}
END_TEST

/* ---- rate change between frames: a new configuration, a training frame,
 * then every frame right at the new rate ---- */
START_TEST(test_rate_change) {
    static const unsigned halves[] = {10, 50, 20, 100, 10};
    struct e2e_run r;
    struct bench *b = e2e_bench(&r, "posital-kit-layout-biss-c", 10, NULL);
    for (size_t i = 0; i < sizeof(halves) / sizeof(halves[0]); i++) {
        fw_check_restart(&r.fc, UINT64_MAX);
        ck_assert_uint_eq(e2e_run_frames(&r, halves[i], 1000, 100), 100);
        ck_assert_uint_eq(r.fc.mismatches, 0);
        ck_assert_uint_eq(r.fc.crc_errors, 0);
        ck_assert_uint_eq(r.fc.half, halves[i]);
        ck_assert_int_eq(bench_stats(b)->half_max_ps, (int64_t)halves[i] * PRU_PS_PER_CYCLE);
    }
    e2e_free(&r);
}
END_TEST

int main(void) {
    Suite *s = suite_create("e2e_fw");
    TCase *tc = tcase_create("fw");
    tcase_set_timeout(tc, 600);
    tcase_add_loop_test(tc, test_uncertain_parameters, 0, 160);
    tcase_add_loop_test(tc, test_raw_delay_every_shift_phase, 0, 25);
    tcase_add_loop_test(tc, test_data_word_widths, 0, (int)(sizeof(widths) / sizeof(widths[0])));
    tcase_add_loop_test(tc, test_bad_config_is_flagged, 0, (int)(sizeof(bad) / sizeof(bad[0])));
    tcase_add_test(tc, test_processing_time_limit);
    tcase_add_test(tc, test_processing_time_16_bit_limit);
    tcase_add_test(tc, test_busy_past_the_count);
    tcase_add_loop_test(tc, test_disconnect_and_reconnect, 0, 3);
    tcase_add_test(tc, test_host_trigger);
    tcase_add_test(tc, test_iep_trigger_period);
    tcase_add_loop_test(tc, test_iep_trigger_contended, 0, 8);
    tcase_add_test(tc, test_iep_overrun_flagged);
    tcase_add_test(tc, test_rate_change);
    suite_add_tcase(s, tc);
    return check_run(s);
}
