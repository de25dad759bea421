/* libbiss end to end on the emulator backend: the real firmware image on
 * the emulated PRU, a cable, and the TIDEP0022 test encoder model. What the
 * library reports is checked against what the slave model sent. */
#include "libbiss-emu.h"

#include "bench.h"

#include "check_run.h"

#include <check.h>
#include <math.h>
#include <pthread.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#define PROFILE "tidep0022-test-encoder"

static biss_t *open_emu(double cable_m) {
    struct biss_open_params p;
    biss_open_params_default(&p);
    p.target = BISS_TARGET_EMU;
    p.profile = PROFILE;
    p.cable_m = cable_m;
    p.set_seed = true;
    p.seed = 7;
    biss_t *h;
    int rc = biss_emu_open(&p, &h);
    ck_assert_msg(rc == BISS_OK, "open: %s", biss_strerror(rc));
    ck_assert_ptr_nonnull(biss_emu_bench(h));
    return h;
}

static void configure(biss_t *h, uint32_t freq, enum biss_trigger t, uint32_t iep_ns) {
    struct biss_config c;
    biss_config_default(&c);
    c.freq_hz = freq;
    c.trigger = t;
    c.iep_period_ns = iep_ns;
    ck_assert_int_eq(biss_config_from_emu(h, &c), BISS_OK);
    int rc = biss_configure(h, &c);
    ck_assert_msg(rc == BISS_OK, "configure: %s", biss_strerror(rc));
}

/* How a published frame is matched with what the slave model sent: the
 * firmware numbers every frame it clocks from 1 (the training frame after
 * a configuration included) and the slave model records every frame it
 * sees from 0, so frame F is the slave's record F - 1. That count is
 * checked by time, independently: the frame's IEP timestamp (PRU cycles
 * since the firmware started its IEP, a few cycles after time 0) comes
 * before the record's start (MA falling at the slave) by less than 2 us,
 * while frames are more than 20 us apart. In IEP mode the count restarts
 * at every period from a phase set at configuration time, so only the
 * count is used there (frames 100 us apart, the position moves 5 counts
 * per frame: a miscount shows as a wrong position). */
/* A record that starts less than 2 us after the frame's timestamp. */
static void assert_starts_after(const struct biss_sample *s, sim_ps start_ps) {
    sim_ps ts = (sim_ps)s->timestamp * PRU_PS_PER_CYCLE;
    sim_ps lead = start_ps - ts;
    ck_assert_msg(lead >= 0 && lead < 2 * SIM_PS_PER_US,
                  "frame %u at %lld ps, record starts at %lld ps", s->frame, (long long)ts,
                  (long long)start_ps);
}

static const biss_frame_record *sent_for(biss_t *h, const struct biss_sample *s) {
    link_model *l = bench_link(biss_emu_bench(h));
    ck_assert_uint_ge(s->frame, 1);
    const biss_frame_record *rec = biss_slave_record(link_biss(l), s->frame - 1);
    ck_assert_msg(rec != NULL, "no slave record for frame %u (%llu recorded)", s->frame,
                  (unsigned long long)link_frames(l));
    struct biss_config c;
    ck_assert_int_eq(biss_get_config(h, &c), BISS_OK);
    if (c.trigger == BISS_TRIGGER_IEP || c.trigger == BISS_TRIGGER_IEP_FOLLOW) {
        return rec;
    }
    assert_starts_after(s, rec->start_ps);
    return rec;
}

static void assert_matches_slave(biss_t *h, const struct biss_sample *s) {
    ck_assert_msg(s->valid && !s->crc_error, "frame %u flags 0x%x", s->frame, s->flags);
    ck_assert_uint_eq(s->nslaves, 1);
    const biss_frame_record *rec = sent_for(h, s);
    ck_assert(rec->complete);
    const struct biss_slave_result *r = &s->slave[0];
    ck_assert(r->crc_ok);
    ck_assert_msg(r->position == rec->s[0].position, "frame %u: position %llu, sent %llu", s->frame,
                  (unsigned long long)r->position, (unsigned long long)rec->s[0].position);
    /* the model says 1 for "no error" (the line level); libbiss says
     * whether the error is active */
    ck_assert_int_eq(r->error, rec->s[0].nE == 0);
    ck_assert_int_eq(r->warning, rec->s[0].nW == 0);
}

/* The model's round trip (lines + slave output delay), in bit/8 units:
 * the header's conversion takes the PRU input synchronizer out. */
static double expected_bit8(biss_t *h, unsigned half) {
    return bench_round_trip_ps(biss_emu_bench(h)) / (half / 4.0 * PRU_PS_PER_CYCLE);
}

/* Reads n frames after the training frame in free-run; all must be data
 * frames whose positions are what the slave sent. */
static void free_run(double cable_m, uint32_t freq, unsigned n, double delay_tol) {
    biss_t *h = open_emu(cable_m);
    configure(h, freq, BISS_TRIGGER_FREERUN, 0);
    struct biss_sample *s = calloc(n, sizeof *s);
    ck_assert_ptr_nonnull(s);
    struct biss_sample first;
    ck_assert_int_eq(biss_wait_sample(h, 0, 5, &first), BISS_OK);
    ck_assert_msg(first.training, "the first frame at a new rate trains");
    uint32_t after = first.frame;
    for (unsigned i = 0; i < n; i++) {
        ck_assert_int_eq(biss_wait_sample(h, after, 5, &s[i]), BISS_OK);
        ck_assert_uint_eq(s[i].frame, after + 1); /* polling misses none */
        after = s[i].frame;
    }
    /* the slave closes a frame's record at its timeout, after the master
     * has published it: let the last ones close */
    ck_assert_int_eq(biss_run_ms(h, 1), BISS_OK);
    unsigned half;
    ck_assert_int_eq(biss_rate_half(freq, &half), BISS_OK);
    double want = expected_bit8(h, half);
    for (unsigned i = 0; i < n; i++) {
        assert_matches_slave(h, &s[i]);
        ck_assert_uint_eq(s[i].delay.half, half);
        ck_assert_msg(fabs(s[i].delay.bit8 - want) <= delay_tol + 4.0 / half,
                      "frame %u: delay %.2f, model %.2f", s[i].frame, s[i].delay.bit8, want);
        ck_assert_msg(fabs(s[i].delay.raw_bit8 - want) <= delay_tol + 4.0 / half,
                      "frame %u: raw delay %.2f, model %.2f", s[i].frame, s[i].delay.raw_bit8,
                      want);
    }
    /* positions move: the encoder turns (50000 counts/s) */
    ck_assert_uint_ne(s[0].slave[0].position, s[n - 1].slave[0].position);
    struct biss_stats st;
    ck_assert_int_eq(biss_get_stats(h, &st), BISS_OK);
    ck_assert_uint_eq(st.crc_errors, 0);
    ck_assert_uint_eq(st.no_slave, 0);
    ck_assert_uint_eq(st.proc_errors, 0);
    ck_assert_uint_eq(st.training, 1);
    ck_assert_uint_ge(st.frames, n + 1);
    struct biss_line_delay d;
    ck_assert_int_eq(biss_line_delay(h, &d), BISS_OK);
    ck_assert(fabs(d.bit8 - want) <= delay_tol + 4.0 / half);
    free(s);
    biss_close(h);
}

START_TEST(test_free_run_10mhz_50_frames) {
    free_run(2.0, 10000000, 50, 1.0);
}
END_TEST

/* A long cable: the answer comes more than a bit period late at 10 MHz. */
START_TEST(test_free_run_10mhz_long_cable) {
    free_run(40.0, 10000000, 20, 1.0);
}
END_TEST

/* Lower rates: every frame right, and the line delay within a bit/8. */
START_TEST(test_free_run_rates) {
    static const uint32_t rates[] = {5000000, 4000000, 2000000, 1000000, 500000};
    free_run(10.0, rates[_i], 20, 1.0);
}
END_TEST

/* The header's claim, one bit/8 and one PRU cycle, at every rate and cable
 * (also the raw, unaveraged reading of every frame). Its own CTest entry: 18 runs. */
START_TEST(test_free_run_delay_claim) {
    static const uint32_t rates[] = {10000000, 5000000, 4000000, 2000000, 1000000, 500000};
    static const double cables[] = {2.0, 10.0, 40.0};
    free_run(cables[_i % 3], rates[_i / 3], 20, 1.0);
}
END_TEST

START_TEST(test_host_trigger) {
    biss_t *h = open_emu(2.0);
    link_model *l = bench_link(biss_emu_bench(h));
    configure(h, 10000000, BISS_TRIGGER_HOST, 0);
    /* untriggered, the firmware only measures the line once (a training
     * frame cut short after the ACK): no data frame */
    ck_assert_int_eq(biss_run_ms(h, 2), BISS_OK);
    struct biss_sample s;
    ck_assert_int_eq(biss_read_sample(h, &s), BISS_OK);
    ck_assert(s.training);
    ck_assert_uint_eq(s.frame, 1);
    ck_assert_uint_eq(link_frames(l), 1);
    uint32_t after = s.frame;
    for (int i = 0; i < 3; i++) {
        ck_assert_int_eq(biss_wait_sample(h, after, 2, &s), BISS_E_TIMEOUT);
        ck_assert_int_eq(biss_trigger(h), BISS_OK);
        ck_assert_int_eq(biss_wait_sample(h, after, 1, &s), BISS_OK);
        ck_assert_uint_eq(s.frame, after + 1);
        ck_assert_int_eq(biss_run_ms(h, 1), BISS_OK); /* the record closes */
        assert_matches_slave(h, &s);
        after = s.frame;
    }
    ck_assert_uint_eq(link_frames(l), 4);
    /* triggers faster than frames (a frame takes some 25 us): each one
     * taken is one frame, each one refused while the last was pending
     * asks for none */
    struct biss_stats before, after_run;
    ck_assert_int_eq(biss_get_stats(h, &before), BISS_OK);
    unsigned taken = 0, pending = 0;
    for (int i = 0; i < 100; i++) {
        int rc = biss_trigger(h);
        ck_assert_msg(rc == BISS_OK || rc == BISS_E_TRIGGER_PENDING, "%s", biss_strerror(rc));
        taken += rc == BISS_OK;
        pending += rc == BISS_E_TRIGGER_PENDING;
        ck_assert_int_eq(biss_run_us(h, 5), BISS_OK);
    }
    ck_assert_int_eq(biss_run_ms(h, 1), BISS_OK);
    ck_assert_int_eq(biss_get_stats(h, &after_run), BISS_OK);
    ck_assert_uint_gt(pending, 0);
    ck_assert_uint_eq(after_run.frames - before.frames, taken);
    biss_close(h);
}
END_TEST

/* IEP trigger: one frame per 100 us period, each at the same phase of it
 * (the IEP count restarts at CMP0, so the timestamps of all frames are
 * equal to within the cycle the firmware's poll may add). */
START_TEST(test_iep_trigger) {
    biss_t *h = open_emu(2.0);
    configure(h, 10000000, BISS_TRIGGER_IEP, 100000);
    struct biss_sample s;
    ck_assert_int_eq(biss_wait_sample(h, 0, 1, &s), BISS_OK);
    ck_assert(s.training);
    uint32_t first = s.frame, after = s.frame;
    uint32_t ts_min = UINT32_MAX, ts_max = 0;
    for (int i = 0; i < 20; i++) {
        ck_assert_int_eq(biss_wait_sample(h, after, 1, &s), BISS_OK);
        after = s.frame;
        ck_assert(s.valid);
        ts_min = s.timestamp < ts_min ? s.timestamp : ts_min;
        ts_max = s.timestamp > ts_max ? s.timestamp : ts_max;
    }
    /* 20 frames took 20 periods */
    sim_ps now = pru_time_ps(bench_core(biss_emu_bench(h)));
    ck_assert_msg(now > 20 * 100 * SIM_PS_PER_US && now < 22 * 100 * SIM_PS_PER_US,
                  "20 frames after %lld ps", (long long)now);
    ck_assert_uint_eq(after - first, 20);
    ck_assert_msg(ts_max - ts_min <= 2, "frame starts spread over %u cycles", ts_max - ts_min);
    ck_assert_int_eq(biss_run_ms(h, 1), BISS_OK);
    assert_matches_slave(h, &s);
    biss_close(h);
}
END_TEST

/* Two handles on the two PRUs of one emulated PRU-ICSS, two encoders of
 * different layouts: PRU0 owns the IEP, PRU1 follows it; every frame of
 * each is its own encoder's, and the frames of both start on the same IEP
 * count (their timestamps are equal). */
START_TEST(test_two_prus_one_iep) {
    static const char *const profile[2] = {PROFILE, "posital-kit-layout-biss-c"};
    struct biss_open_params p[2];
    for (unsigned i = 0; i < 2; i++) {
        biss_open_params_default(&p[i]);
        p[i].target = BISS_TARGET_EMU;
        p[i].profile = profile[i];
        p[i].cable_m = 5.0 + 20.0 * i;
    }
    biss_t *h[2];
    int rc = biss_emu_open_pair(p, h);
    ck_assert_msg(rc == BISS_OK, "open pair: %s", biss_strerror(rc));
    ck_assert_ptr_ne(biss_emu_bench(h[0]), biss_emu_bench(h[1]));
    configure(h[0], 10000000, BISS_TRIGGER_IEP, 50000);
    /* one channel owns the IEP: PRU1 may only follow */
    struct biss_config c;
    biss_config_default(&c);
    c.freq_hz = 5000000;
    c.trigger = BISS_TRIGGER_IEP;
    c.iep_period_ns = 50000;
    ck_assert_int_eq(biss_config_from_emu(h[1], &c), BISS_OK);
    ck_assert_int_eq(biss_configure(h[1], &c), BISS_E_IEP_OWNED);
    configure(h[1], 5000000, BISS_TRIGGER_IEP_FOLLOW, 0);
    struct biss_sample s[2];
    uint32_t after[2] = {0, 0};
    for (unsigned i = 0; i < 2; i++) { /* past the training frames */
        ck_assert_int_eq(biss_wait_sample(h[i], 0, 2, &s[i]), BISS_OK);
        ck_assert_int_eq(biss_wait_sample(h[i], s[i].frame, 2, &s[i]), BISS_OK);
        after[i] = s[i].frame;
    }
    struct biss_sample got[2][20];
    for (int k = 0; k < 20; k++) {
        for (unsigned i = 0; i < 2; i++) {
            ck_assert_int_eq(biss_wait_sample(h[i], after[i], 1, &got[i][k]), BISS_OK);
            ck_assert_uint_eq(got[i][k].frame, after[i] + 1); /* none missed */
            after[i] = got[i][k].frame;
        }
        ck_assert_uint_eq(got[0][k].timestamp, got[1][k].timestamp);
    }
    /* the slaves close their frames when their timeouts end */
    ck_assert_int_eq(biss_run_ms(h[0], 1), BISS_OK);
    for (int k = 0; k < 20; k++) {
        for (unsigned i = 0; i < 2; i++) {
            assert_matches_slave(h[i], &got[i][k]);
        }
    }
    biss_close(h[0]); /* the PRU-ICSS goes with the last handle */
    ck_assert_int_eq(biss_wait_sample(h[1], after[1], 1, &s[1]), BISS_OK);
    biss_close(h[1]);
    p[1].target = BISS_TARGET_AM335X;
    ck_assert_int_eq(biss_emu_open_pair(p, h), BISS_E_TARGET);
    ck_assert_ptr_null(h[0]);
}
END_TEST

/* Both channels of a pair asking for the IEP at once, from two threads,
 * round after round: one owns it, the other is refused (the check and the
 * write decided under the IEP's lock; apart, both got through). */
struct iep_claim {
    biss_t *h;
    int rc;
};

static void *claim_iep(void *arg) {
    struct iep_claim *k = arg;
    struct biss_config c;
    biss_config_default(&c);
    c.freq_hz = 10000000;
    c.trigger = BISS_TRIGGER_IEP;
    c.iep_period_ns = 50000;
    ck_assert_int_eq(biss_config_from_emu(k->h, &c), BISS_OK);
    k->rc = biss_configure(k->h, &c);
    return NULL;
}

START_TEST(test_iep_owned_once) {
    struct biss_open_params p[2];
    for (unsigned i = 0; i < 2; i++) {
        biss_open_params_default(&p[i]);
        p[i].target = BISS_TARGET_EMU;
    }
    biss_t *h[2];
    ck_assert_int_eq(biss_emu_open_pair(p, h), BISS_OK);
    for (int round = 0; round < 40; round++) {
        for (unsigned i = 0; i < 2; i++) {
            configure(h[i], 10000000, BISS_TRIGGER_FREERUN, 0); /* the IEP let go */
        }
        struct iep_claim k[2] = {{.h = h[0]}, {.h = h[1]}};
        pthread_t t[2];
        for (unsigned i = 0; i < 2; i++) {
            ck_assert_int_eq(pthread_create(&t[i], NULL, claim_iep, &k[i]), 0);
        }
        for (unsigned i = 0; i < 2; i++) {
            pthread_join(t[i], NULL);
        }
        ck_assert_msg((k[0].rc == BISS_OK && k[1].rc == BISS_E_IEP_OWNED) ||
                          (k[1].rc == BISS_OK && k[0].rc == BISS_E_IEP_OWNED),
                      "round %d: PRU0 %s, PRU1 %s", round, biss_strerror(k[0].rc),
                      biss_strerror(k[1].rc));
    }
    biss_close(h[0]);
    biss_close(h[1]);
}
END_TEST

START_TEST(test_stop_start) {
    biss_t *h = open_emu(2.0);
    configure(h, 10000000, BISS_TRIGGER_FREERUN, 0);
    struct biss_sample s;
    ck_assert_int_eq(biss_wait_sample(h, 3, 2, &s), BISS_OK);
    ck_assert_int_eq(biss_stop(h), BISS_OK);
    struct biss_status st;
    ck_assert_int_eq(biss_get_status(h, &st), BISS_OK);
    ck_assert(!st.pru_enabled);
    ck_assert_int_eq(biss_wait_sample(h, s.frame + 1, 2, &s), BISS_E_TIMEOUT);
    /* a restart runs the firmware from the top with the same configuration */
    ck_assert_int_eq(biss_start(h), BISS_OK);
    ck_assert_int_eq(biss_get_status(h, &st), BISS_OK);
    ck_assert(st.pru_enabled && st.firmware_running);
    ck_assert_uint_eq(st.state, BISS_FW_RUNNING);
    ck_assert_uint_eq(st.cfg_ack, st.cfg_seq);
    ck_assert_int_eq(biss_wait_sample(h, 1, 2, &s), BISS_OK);
    ck_assert(s.valid && s.slave[0].crc_ok);
    biss_close(h);
}
END_TEST

/* A restart (biss_start) halts the firmware wherever it is, possibly
 * inside a frame: its slave is then inside that frame too, waiting with SL
 * high for more clocks, and would take the new firmware's first frame for
 * the rest of it (an ACK a period early, the data misread). libbiss lets
 * the slave's longest timeout pass after the halt. The halt is swept
 * through the training frame that follows the configuration (every 0.25 us
 * over its first 4 us at 5 MHz): the frames after the new training are
 * all valid, with their CRC right. */
START_TEST(test_restart_inside_a_frame) {
    for (int k = 0; k < 16; k++) {
        biss_t *h = open_emu(10.0);
        configure(h, 5000000, BISS_TRIGGER_FREERUN, 0);
        struct bench *b = biss_emu_bench(h);
        bench_run_until(b, pru_time_ps(bench_core(b)) + (sim_ps)k * SIM_PS_PER_US / 4);
        ck_assert_int_eq(biss_start(h), BISS_OK);
        struct biss_sample s;
        ck_assert_int_eq(biss_wait_sample(h, 1, 2, &s), BISS_OK); /* the training */
        uint32_t first = s.frame;
        for (uint32_t f = first; f < first + 4; f = s.frame) {
            ck_assert_int_eq(biss_wait_sample(h, f, 2, &s), BISS_OK);
            ck_assert_msg(s.valid && s.slave[0].crc_ok && !s.ack_jump,
                          "halted %.2f us after the configuration: frame %u flags 0x%x", k / 4.0,
                          s.frame, s.flags);
        }
        biss_close(h);
    }
}
END_TEST

/* An SSI encoder (binary, and Gray in a scenario file): configured from
 * the bench with its line round trip, every word the encoder sent comes
 * back, and the Gray code is decoded to the position. The firmware counts
 * frames from 1 (no training frame: the delay is given), the model its
 * records from 0; the timestamp checks the pairing as for BiSS. */
static void ssi_run(const char *scenario_file, bool gray) {
    struct biss_open_params p;
    biss_open_params_default(&p);
    p.profile = "ssi";
    p.scenario_file = scenario_file;
    biss_t *h;
    int rc = biss_emu_open(&p, &h);
    ck_assert_msg(rc == BISS_OK, "open: %s", biss_strerror(rc));
    struct biss_config c;
    biss_config_default(&c);
    c.freq_hz = 2000000;
    ck_assert_int_eq(biss_config_from_emu(h, &c), BISS_OK);
    ck_assert(c.slave[0].ssi);
    ck_assert_int_eq(c.slave[0].gray, gray);
    ck_assert_uint_gt(c.ssi_delay_ns, 0);
    rc = biss_configure(h, &c);
    ck_assert_msg(rc == BISS_OK, "configure: %s", biss_strerror(rc));
    struct biss_sample s[20];
    uint32_t after = 0;
    for (unsigned i = 0; i < 20; i++) {
        ck_assert_int_eq(biss_wait_sample(h, after, 5, &s[i]), BISS_OK);
        after = s[i].frame;
    }
    ck_assert_int_eq(biss_run_ms(h, 1), BISS_OK);
    const ssi_slave *m = link_ssi(bench_link(biss_emu_bench(h)));
    for (unsigned i = 0; i < 20; i++) {
        ck_assert_msg(s[i].valid && !s[i].training, "frame %u flags 0x%x", s[i].frame, s[i].flags);
        const ssi_frame_record *rec = ssi_slave_record(m, s[i].frame - 1);
        ck_assert_ptr_nonnull(rec);
        assert_starts_after(&s[i], rec->start_ps);
        ck_assert_uint_eq(s[i].slave[0].data, rec->code);
        ck_assert_msg(s[i].slave[0].position == rec->position, "frame %u: %llu, sent %llu",
                      s[i].frame, (unsigned long long)s[i].slave[0].position,
                      (unsigned long long)rec->position);
    }
    ck_assert_uint_ne(s[0].slave[0].position, s[19].slave[0].position);
    /* no control communication: refused by name (it was run, and failed as
     * "no slave took the control frame") */
    uint8_t b[4], ida;
    ck_assert_int_eq(biss_reg_read(h, 0, 0x78, b, 4), BISS_E_SSI_NO_CONTROL);
    ck_assert_int_eq(biss_command(h, 0x01, 0, false, &ida), BISS_E_SSI_NO_CONTROL);
    biss_cd_job *j = (biss_cd_job *)1;
    ck_assert_int_eq(biss_reg_write_start(h, 0, 0x60, b, 1, &j), BISS_E_SSI_NO_CONTROL);
    ck_assert_ptr_null(j);
    static const uint8_t ops[1] = {0};
    ck_assert_int_eq(biss_cd_run(h, ops, 1, 0, 5, b), BISS_E_SSI_NO_CONTROL);
    biss_close(h);
}

/* A new slave layout: frames published under the previous one are no
 * sample of it (they hold another slave count), so reading waits for the
 * first frame made with the new layout instead of failing. */
START_TEST(test_reconfigure_other_layout) {
    biss_t *h = open_emu(2.0);
    struct biss_config c;
    biss_config_default(&c);
    c.freq_hz = 10000000;
    ck_assert_int_eq(biss_config_from_emu(h, &c), BISS_OK);
    struct biss_config wide = c; /* the same wire read as 3 slaves of 8 bits, no CRC */
    wide.nslaves = 3;
    for (unsigned i = 0; i < 3; i++) {
        wide.slave[i] = (struct biss_slave_config){.data_bits = 8};
    }
    ck_assert_int_eq(biss_configure(h, &wide), BISS_OK);
    struct biss_sample s;
    ck_assert_int_eq(biss_wait_sample(h, 0, 100, &s), BISS_OK);
    ck_assert_uint_eq(s.nslaves, 3);
    ck_assert_int_eq(biss_configure(h, &c), BISS_OK);
    int rc = biss_read_sample(h, &s);
    ck_assert_msg(rc == BISS_E_NO_SAMPLE || (rc == BISS_OK && s.nslaves == 1), "read: %s",
                  biss_strerror(rc));
    ck_assert_int_eq(biss_wait_sample(h, 0, 100, &s), BISS_OK);
    ck_assert_uint_eq(s.nslaves, 1);
    biss_close(h);
}
END_TEST

START_TEST(test_ssi_binary) {
    ssi_run(NULL, false);
}
END_TEST

START_TEST(test_ssi_gray) {
    char path[] = "/tmp/biss_ssi_gray_XXXXXX";
    int fd = mkstemp(path);
    ck_assert_int_ge(fd, 0);
    static const char json[] = "{\"profile\": \"ssi\", \"ssi\": {\"gray\": true}}\n";
    ck_assert_int_eq(write(fd, json, sizeof json - 1), (ssize_t)(sizeof json - 1));
    close(fd);
    ssi_run(path, true);
    unlink(path);
}
END_TEST

/* What the library refuses before the firmware sees it, and the
 * firmware's own refusal of an SSI slave in a chain. */
START_TEST(test_ssi_config_errors) {
    struct biss_config c;
    biss_config_default(&c);
    c.nslaves = 1;
    c.slave[0] = (struct biss_slave_config){.data_bits = 13, .ssi = true};
    ck_assert_int_eq(biss_config_check(&c), BISS_OK);
    c.ssi_delay_ns = 65536;
    ck_assert_int_eq(biss_config_check(&c), BISS_E_SSI);
    c.ssi_delay_ns = 100;
    c.slave[0].crc_bits = 6;
    c.slave[0].crc_poly = 0x43;
    ck_assert_int_eq(biss_config_check(&c), BISS_E_SSI);
    c.slave[0].crc_bits = 0;
    c.slave[0].crc_poly = 0;
    c.nslaves = 2;
    c.slave[1] = (struct biss_slave_config){.data_bits = 13};
    ck_assert_int_eq(biss_config_check(&c), BISS_E_SSI);
    c.nslaves = 1;
    c.slave[0].ssi = false;
    c.slave[0].gray = true; /* Gray without SSI means nothing here */
    ck_assert_int_eq(biss_config_check(&c), BISS_E_SSI);
    ck_assert_str_eq(biss_strerror(BISS_E_FW_SSI), "firmware refused the configuration: SSI");
}
END_TEST

START_TEST(test_emu_open_errors) {
    struct biss_open_params p;
    biss_open_params_default(&p);
    biss_t *h;
    p.profile = "no-such-encoder";
    ck_assert_int_eq(biss_emu_open(&p, &h), BISS_E_PROFILE);
    ck_assert_ptr_null(h);
    p.profile = NULL;
    p.scenario_file = "/nonexistent.json";
    ck_assert_int_eq(biss_emu_open(&p, &h), BISS_E_SCENARIO);
    p.scenario_file = NULL;
    p.firmware = "/nonexistent.bin";
    ck_assert_int_eq(biss_emu_open(&p, &h), BISS_E_FIRMWARE_IO);
    /* the other PRU's image, from its words, either way */
    char why_pru[200];
    p.errbuf = why_pru;
    p.errbuf_len = sizeof why_pru;
    p.firmware = BISS_BUILD_FIRMWARE_PRU1;
    ck_assert_int_eq(biss_emu_open(&p, &h), BISS_E_FW_PRU);
    ck_assert_ptr_nonnull(strstr(why_pru, "assembled for PRU1, not PRU0"));
    p.firmware = BISS_BUILD_FIRMWARE;
    p.pru = 1;
    ck_assert_int_eq(biss_emu_open(&p, &h), BISS_E_FW_PRU);
    ck_assert_ptr_nonnull(strstr(why_pru, "assembled for PRU0, not PRU1"));
    p.pru = 0;
    p.errbuf = NULL;
    /* the environment names the image when the params do not */
    p.firmware = NULL;
    setenv("BISS_FIRMWARE", "/nonexistent-env.bin", 1);
    ck_assert_int_eq(biss_emu_open(&p, &h), BISS_E_FIRMWARE_IO);
    unsetenv("BISS_FIRMWARE");
    /* libbiss alone has no emulator: a refusal that says where it is */
    char why[160];
    p.errbuf = why;
    p.errbuf_len = sizeof why;
    ck_assert_int_eq(biss_open(&p, &h), BISS_E_TARGET);
    ck_assert_ptr_null(h);
    ck_assert_ptr_nonnull(strstr(why, "libbiss-emu"));
    p.errbuf = NULL;
    ck_assert_int_eq(biss_emu_open(&p, &h), BISS_OK);
    ck_assert_int_eq(biss_target(h), BISS_TARGET_EMU);
    /* not configured yet: nothing to trigger, nothing published */
    struct biss_sample s;
    ck_assert_int_eq(biss_trigger(h), BISS_E_NOT_CONFIGURED);
    ck_assert_int_eq(biss_read_sample(h, &s), BISS_E_NO_SAMPLE);
    biss_close(h);
}
END_TEST

int main(int argc, char **argv) {
    Suite *s = suite_create("host_emu");
    TCase *tc = tcase_create("emulator");
    if (argc > 1 && strcmp(argv[1], "--delay-claim") == 0) {
        tcase_set_timeout(tc, 120);
        tcase_add_loop_test(tc, test_free_run_delay_claim, 0, 18);
        suite_add_tcase(s, tc);
        return check_run(s);
    }
    tcase_set_timeout(tc, 120);
    tcase_add_test(tc, test_free_run_10mhz_50_frames);
    tcase_add_test(tc, test_free_run_10mhz_long_cable);
    tcase_add_loop_test(tc, test_free_run_rates, 0, 5);
    tcase_add_test(tc, test_host_trigger);
    tcase_add_test(tc, test_iep_trigger);
    tcase_add_test(tc, test_stop_start);
    tcase_add_test(tc, test_restart_inside_a_frame);
    tcase_add_test(tc, test_emu_open_errors);
    tcase_add_test(tc, test_two_prus_one_iep);
    tcase_add_test(tc, test_iep_owned_once);
    tcase_add_test(tc, test_reconfigure_other_layout);
    tcase_add_test(tc, test_ssi_binary);
    tcase_add_test(tc, test_ssi_gray);
    tcase_add_test(tc, test_ssi_config_errors);
    suite_add_tcase(s, tc);
    return check_run(s);
}
