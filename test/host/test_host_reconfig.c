/* Reconfiguring a running master through libbiss on the emulator (the real
 * firmware image): rate jumps across the whole range, the trigger changed
 * both ways, the slave count of a chain from 8 to 1 and back, SSI and
 * BiSS-C on one line, many configurations back to back. After each the
 * firmware's ack and state, then every frame through the ring: numbered
 * without a gap and none lost after the first read (a configuration counts
 * the old layout's unread frames as lost: biss_ring_read), the training
 * frame first (BiSS-C) and no other, every other frame valid with the
 * positions the encoder model sent, every MA half period H of the new rate
 * and the MA high before every frame's first fall at least H (the bench's
 * frame marks, emulator/bench/INSTRUMENTS.md), the firmware's error
 * counters unmoved. */
#include "libbiss-emu.h"

#include "bench.h"
#include "bench_fw.h"
#include "biss/biss_shm.h"
#include "ssi_slave.h"

#include "check_run.h"

#include <check.h>
#include <stdio.h>

#ifndef SCENARIO_DIR
#error "SCENARIO_DIR must name test/scenarios"
#endif

#define FRAMES 30 /* data frames checked after each configuration */

static biss_t *open_emu(const char *profile, const char *scenario, struct biss_config *base) {
    struct biss_open_params p;
    biss_open_params_default(&p);
    p.target = BISS_TARGET_EMU;
    p.profile = profile;
    p.scenario_file = scenario;
    p.cable_m = 2.0;
    biss_t *h;
    int rc = biss_emu_open(&p, &h);
    ck_assert_msg(rc == BISS_OK, "open: %s", biss_strerror(rc));
    biss_config_default(base);
    base->freq_hz = 10000000;
    ck_assert_int_eq(biss_config_from_emu(h, base), BISS_OK);
    return h;
}

/* Every frame still in the ring, read and dropped. */
static void drain(biss_t *h) {
    struct biss_sample s[64];
    unsigned n;
    uint32_t lost;
    do {
        ck_assert_int_eq(biss_ring_read(h, s, 64, &n, &lost), BISS_OK);
    } while (n == 64);
}

/* Whether slave model records frame k - 1 (frames count from 1 at the
 * firmware, from 0 at the model) with the positions s holds. */
static void assert_sent(biss_t *h, const struct biss_sample *s, bool ssi) {
    link_model *l = bench_link(biss_emu_bench(h));
    if (ssi) {
        const ssi_frame_record *r = ssi_slave_record(link_ssi(l), s->frame - 1);
        ck_assert_msg(r != NULL, "no record of frame %u", s->frame);
        ck_assert_msg(r->position == s->slave[0].position, "frame %u: %llu, sent %llu", s->frame,
                      (unsigned long long)s->slave[0].position, (unsigned long long)r->position);
        return;
    }
    const biss_frame_record *r = biss_slave_record(link_biss(l), s->frame - 1);
    ck_assert_msg(r != NULL, "no record of frame %u", s->frame);
    for (unsigned i = 0; i < s->nslaves; i++) {
        ck_assert_msg(r->s[i].position == s->slave[i].position,
                      "frame %u slave %u: %llu, sent %llu", s->frame, i,
                      (unsigned long long)s->slave[i].position,
                      (unsigned long long)r->s[i].position);
    }
}

/* c configured (the ring drained first: one frame under way may still be
 * the old layout's, counted lost), then checked as the file comment says. */
static void reconfigure(biss_t *h, const struct biss_config *c) {
    struct bench *b = biss_emu_bench(h);
    struct biss_stats before;
    ck_assert_int_eq(biss_get_stats(h, &before), BISS_OK);
    drain(h);
    int rc = biss_configure(h, c);
    ck_assert_msg(rc == BISS_OK, "configure %u Hz, trigger %s, %u slaves: %s", c->freq_hz,
                  biss_trigger_name(c->trigger), c->nslaves, biss_strerror(rc));
    struct biss_status st;
    ck_assert_int_eq(biss_get_status(h, &st), BISS_OK);
    ck_assert_uint_eq(st.cfg_ack, st.cfg_seq);
    ck_assert_uint_eq(st.cfg_error, BISS_CFGERR_NONE);
    ck_assert_uint_eq(st.state, BISS_STATE_RUNNING);
    unsigned half;
    ck_assert_int_eq(biss_rate_half(c->freq_hz, &half), BISS_OK);
    /* from the ack on, every frame is the new configuration's */
    bench_set_ma_half(b, half);
    bench_reset_stats(b);

    bool ssi = c->slave[0].ssi, host = c->trigger == BISS_TRIGGER_HOST;
    /* a frame of 80 bits and a 20 us timeout, at the least */
    unsigned step_us = (unsigned)(80ull * 2 * half / 200) + 25;
    struct biss_sample s[64], pending[64];
    unsigned npending = 0, data = 0, training = 0;
    uint32_t last = 0;
    for (unsigned round = 0; data < FRAMES || npending; round++) {
        ck_assert_uint_lt(round, 200);
        if (host) {
            ck_assert_int_eq(biss_trigger(h), BISS_OK);
        }
        ck_assert_int_eq(biss_run_us(h, host ? step_us : 4 * step_us), BISS_OK);
        /* the frames read last time: the slave has closed their records now */
        for (unsigned i = 0; i < npending; i++) {
            assert_sent(h, &pending[i], ssi);
        }
        npending = 0;
        if (data >= FRAMES) {
            break;
        }
        unsigned n;
        uint32_t lost;
        ck_assert_int_eq(biss_ring_read(h, s, 64, &n, &lost), BISS_OK);
        ck_assert_uint_le(lost, round == 0 ? 1 : 0);
        for (unsigned i = 0; i < n; i++) {
            ck_assert_msg(last == 0 || s[i].seq == last + 1, "seq %u after %u", s[i].seq, last);
            last = s[i].seq;
            if (s[i].training) {
                ck_assert_msg(!ssi && data == 0 && training == 0, "training frame %u", s[i].frame);
                training++;
                continue;
            }
            ck_assert_msg(s[i].valid && !s[i].crc_error, "frame %u flags 0x%x", s[i].frame,
                          s[i].flags);
            ck_assert_uint_eq(s[i].nslaves, c->nslaves);
            ck_assert_uint_eq(s[i].delay.half, half);
            pending[npending++] = s[i];
            data++;
        }
    }
    ck_assert_uint_eq(training, ssi ? 0 : 1);
    const struct bench_stats *bs = bench_stats(b);
    ck_assert_uint_gt(bs->half_periods, 0);
    ck_assert_int_eq(bs->half_min_ps, half * PRU_PS_PER_CYCLE);
    ck_assert_int_eq(bs->half_max_ps, half * PRU_PS_PER_CYCLE);
    ck_assert_uint_ge(bs->ma_high.n, FRAMES);
    ck_assert_uint_eq(bs->ma_high_short, 0);
    struct biss_stats after;
    ck_assert_int_eq(biss_get_stats(h, &after), BISS_OK);
    ck_assert_uint_eq(after.crc_errors, before.crc_errors);
    ck_assert_uint_eq(after.no_slave, before.no_slave);
    ck_assert_uint_eq(after.proc_errors, before.proc_errors);
    ck_assert_uint_eq(after.off_grid, before.off_grid);
}

static void rate(biss_t *h, const struct biss_config *base, uint32_t freq, enum biss_trigger t) {
    struct biss_config c = *base;
    c.freq_hz = freq;
    c.trigger = t;
    c.iep_period_ns = t == BISS_TRIGGER_IEP ? (freq < 1000000 ? 2000000 : 100000) : 0;
    reconfigure(h, &c);
}

/* 10 MHz and 125 kHz (the slowest whole rate in Hz the firmware clocks:
 * H = 800) in turn, and rates between, odd ones among them. */
static const uint32_t rates[] = {10000000, 125000,  10000000, 4000000, 125000,
                                 781250,   3125000, 1000000,  5000000, 10000000};

START_TEST(test_rate_jumps) {
    static const char *const profiles[] = {"tidep0022-test-encoder", "hengstler-ad38", "ssi"};
    struct biss_config base;
    biss_t *h = open_emu(profiles[_i], NULL, &base);
    for (unsigned i = 0; i < sizeof rates / sizeof rates[0]; i++) {
        rate(h, &base, rates[i], BISS_TRIGGER_FREERUN);
    }
    biss_close(h);
}
END_TEST

/* The trigger changed every way, at both ends of the range. */
START_TEST(test_trigger_changes) {
    static const enum biss_trigger order[] = {BISS_TRIGGER_HOST, BISS_TRIGGER_FREERUN,
                                              BISS_TRIGGER_IEP,  BISS_TRIGGER_HOST,
                                              BISS_TRIGGER_IEP,  BISS_TRIGGER_FREERUN};
    struct biss_config base;
    biss_t *h = open_emu(_i < 2 ? "tidep0022-test-encoder" : "ssi", NULL, &base);
    for (unsigned i = 0; i < sizeof order / sizeof order[0]; i++) {
        rate(h, &base, _i % 2 ? 125000 : 10000000, order[i]);
    }
    biss_close(h);
}
END_TEST

/* An 8-slave chain read as its first k slaves (the master stops clocking
 * after their bits; the rest time out unread), k from 8 to 1 and back,
 * the ring's stride changing with it. */
START_TEST(test_chain_shape) {
    struct biss_config base;
    biss_t *h = open_emu(NULL, SCENARIO_DIR "/chain8-20us.json", &base);
    ck_assert_uint_eq(base.nslaves, 8);
    static const unsigned counts[] = {8, 1, 2, 5, 8, 3, 1, 8};
    for (unsigned i = 0; i < sizeof counts / sizeof counts[0]; i++) {
        struct biss_config c = base;
        c.nslaves = counts[i];
        c.freq_hz = i % 3 == 1 ? 125000 : 10000000;
        reconfigure(h, &c);
    }
    biss_close(h);
}
END_TEST

/* A 24-bit SSI encoder on base's line (the round trip given: an SSI word
 * has no ACK to measure it by). */
static struct biss_config ssi_on(const struct biss_config *base) {
    struct biss_config ssi = *base;
    ssi.nslaves = 1;
    ssi.slave[0] = (struct biss_slave_config){.data_bits = 24, .ssi = true};
    ssi.ssi_delay_ns = 100;
    return ssi;
}

/* SSI frames on a BiSS-C encoder's line and back: the BiSS-C frames after
 * them train again and read right (the SSI frames themselves read whatever
 * the line shows: an SSI word has no check). */
START_TEST(test_ssi_and_back) {
    struct biss_config base;
    biss_t *h = open_emu("tidep0022-test-encoder", NULL, &base);
    struct biss_config ssi = ssi_on(&base);
    for (unsigned i = 0; i < 3; i++) {
        ssi.freq_hz = i == 1 ? 125000 : 10000000;
        drain(h);
        ck_assert_int_eq(biss_configure(h, &ssi), BISS_OK);
        ck_assert_int_eq(biss_run_ms(h, 2), BISS_OK);
        rate(h, &base, i == 2 ? 125000 : 10000000, BISS_TRIGGER_FREERUN);
    }
    biss_close(h);
}
END_TEST

/* Configurations back to back with no time between (each waits only for
 * the firmware's ack, at the end of the frame under way), every rate and
 * trigger among them; then the last one's frames. */
START_TEST(test_back_to_back) {
    static const enum biss_trigger trig[] = {BISS_TRIGGER_FREERUN, BISS_TRIGGER_HOST,
                                             BISS_TRIGGER_IEP};
    struct biss_config base;
    biss_t *h = open_emu(_i ? "ssi" : "tidep0022-test-encoder", NULL, &base);
    for (unsigned i = 0; i < 40; i++) {
        struct biss_config c = base;
        c.freq_hz = rates[i % (sizeof rates / sizeof rates[0])];
        c.trigger = trig[(i / 3) % 3];
        c.iep_period_ns = c.trigger == BISS_TRIGGER_IEP ? 2000000 : 0;
        int rc = biss_configure(h, &c);
        ck_assert_msg(rc == BISS_OK, "configuration %u: %s", i, biss_strerror(rc));
    }
    rate(h, &base, 10000000, BISS_TRIGGER_FREERUN);
    rate(h, &base, 125000, BISS_TRIGGER_HOST);
    biss_close(h);
}
END_TEST

/* Frames after the IEP trigger was left: their timestamps (the IEP count
 * at each frame's first MA edge) run on, each after the one before, and
 * a speed check on them passes every frame (the encoder model moves
 * slowly). The IEP owner's compare 0 restarted the count every period; a
 * free-run or host configuration turns that off (pru_fw/config.p). */
static void assert_count_runs_free(biss_t *h, enum biss_trigger t) {
    drain(h);
    uint32_t last = 0;
    unsigned seen = 0;
    for (unsigned round = 0; round < 40 && seen < FRAMES; round++) {
        if (t == BISS_TRIGGER_HOST) {
            int rc = biss_trigger(h);
            ck_assert_msg(rc == BISS_OK || rc == BISS_E_TRIGGER_PENDING, "%s", biss_strerror(rc));
        }
        ck_assert_int_eq(biss_run_us(h, 100), BISS_OK);
        struct biss_sample s[64];
        unsigned n;
        uint32_t lost;
        ck_assert_int_eq(biss_ring_read(h, s, 64, &n, &lost), BISS_OK);
        for (unsigned i = 0; i < n; i++) {
            if (s[i].training) {
                continue;
            }
            ck_assert_msg(s[i].valid, "%s: frame %u flags 0x%x safety 0x%x", biss_trigger_name(t),
                          s[i].frame, s[i].flags, s[i].safety);
            ck_assert_msg(seen == 0 || (s[i].safety & BISS_SAFE_POS_CHECKED),
                          "%s: frame %u not compared", biss_trigger_name(t), s[i].frame);
            ck_assert_msg(seen == 0 || (int32_t)(s[i].timestamp - last) > 0,
                          "%s: frame %u at count %u, the one before at %u", biss_trigger_name(t),
                          s[i].frame, s[i].timestamp, last);
            last = s[i].timestamp;
            seen++;
        }
    }
    ck_assert_uint_ge(seen, FRAMES);
}

START_TEST(test_iep_left) {
    static const enum biss_trigger after[] = {BISS_TRIGGER_FREERUN, BISS_TRIGGER_HOST};
    struct biss_config base;
    biss_t *h = open_emu("tidep0022-test-encoder", NULL, &base);
    struct biss_config iep = base, next = base;
    iep.trigger = BISS_TRIGGER_IEP;
    iep.iep_period_ns = 40000;
    next.trigger = after[_i];
    next.slave[0].max_speed = 1e7;
    ck_assert_int_eq(biss_configure(h, &iep), BISS_OK);
    ck_assert_int_eq(biss_run_ms(h, 2), BISS_OK);
    ck_assert_int_eq(biss_configure(h, &next), BISS_OK);
    assert_count_runs_free(h, next.trigger);
    biss_close(h);
}
END_TEST

/* ... but not while the other PRU's channel owns the IEP: PRU1 configured
 * free-run or host after PRU0 took the IEP trigger leaves PRU0's period
 * as it was: every PRU0 frame on its count, one period after the last. */
START_TEST(test_iep_kept_for_the_other) {
    static const enum biss_trigger other[] = {BISS_TRIGGER_FREERUN, BISS_TRIGGER_HOST};
    struct biss_open_params p[2];
    for (unsigned i = 0; i < 2; i++) {
        biss_open_params_default(&p[i]);
        p[i].target = BISS_TARGET_EMU;
        p[i].profile = "tidep0022-test-encoder";
    }
    biss_t *h[2];
    int rc = biss_emu_open_pair(p, h);
    ck_assert_msg(rc == BISS_OK, "open pair: %s", biss_strerror(rc));
    struct biss_config c[2];
    for (unsigned i = 0; i < 2; i++) {
        biss_config_default(&c[i]);
        c[i].freq_hz = 10000000;
        ck_assert_int_eq(biss_config_from_emu(h[i], &c[i]), BISS_OK);
    }
    c[0].trigger = BISS_TRIGGER_IEP;
    c[0].iep_period_ns = 40000;
    c[1].trigger = other[_i];
    ck_assert_int_eq(biss_configure(h[0], &c[0]), BISS_OK);
    ck_assert_int_eq(biss_run_ms(h[0], 1), BISS_OK);
    ck_assert_int_eq(biss_configure(h[1], &c[1]), BISS_OK);
    drain(h[0]);
    ck_assert_int_eq(biss_run_ms(h[0], 2), BISS_OK);
    struct biss_sample s[64];
    unsigned n;
    uint32_t lost;
    ck_assert_int_eq(biss_ring_read(h[0], s, 64, &n, &lost), BISS_OK);
    ck_assert_uint_ge(n, 40);
    for (unsigned i = 0; i < n; i++) {
        ck_assert_msg(s[i].valid && !(s[i].flags & BISS_RF_IEP_LATE), "frame %u flags 0x%x",
                      s[i].frame, s[i].flags);
        ck_assert_msg(i == 0 || s[i].timestamp == s[i - 1].timestamp, "frame %u at count %u, %u",
                      s[i].frame, s[i].timestamp, s[i - 1].timestamp);
    }
    biss_close(h[1]);
    biss_close(h[0]);
}
END_TEST

/* A control program running (or waiting for its 14 CDM zeros) when an SSI
 * configuration is written: SSI frames carry no CDM or CDS, so it cannot
 * end as a register access; its verdict is BISS_E_SSI_NO_CONTROL (not the
 * CD error its CDS read on SSI frames would give), at once and from then
 * on. Nothing else is lost: the SSI frames come, every one; back on
 * BiSS-C a register read reads right. A program that ended before the
 * configuration keeps its verdict and bytes. Swept over the program's
 * life at 10 MHz (the zeros take 14 frames, 0.3 ms; the read about 1.5
 * ms). */
START_TEST(test_ssi_ends_a_running_program) {
    struct biss_config base;
    biss_t *h = open_emu("tidep0022-test-encoder", NULL, &base);
    struct biss_config ssi = ssi_on(&base);
    ck_assert_int_eq(biss_configure(h, &base), BISS_OK);
    ck_assert_int_eq(biss_run_ms(h, 1), BISS_OK);
    uint8_t want[2], got[2];
    ck_assert_int_eq(biss_reg_read(h, 0, 0x78, want, 2), BISS_OK);
    unsigned seen[2] = {0, 0}; /* running, ended */
    for (unsigned us = 0; us <= 3000; us += 250) {
        ck_assert_int_eq(biss_configure(h, &base), BISS_OK);
        ck_assert_int_eq(biss_run_ms(h, 1), BISS_OK);
        biss_cd_job *j;
        ck_assert_int_eq(biss_reg_read_start(h, 0, 0x78, 2, &j), BISS_OK);
        ck_assert_int_eq(biss_run_us(h, us), BISS_OK);
        struct biss_proto_io io = bench_fw_io(biss_emu_bench(h));
        uint32_t cmd;
        int running = biss_proto_cd_running(&io, &cmd);
        ck_assert_int_ge(running, 0);
        bool ended = !running; /* by the firmware, not polled yet */
        seen[ended]++;
        drain(h);
        ck_assert_int_eq(biss_configure(h, &ssi), BISS_OK);
        int rc = biss_cd_poll(h, j);
        ck_assert_msg(rc == (ended ? BISS_OK : BISS_E_SSI_NO_CONTROL),
                      "%u us into the program (%s): %s", us, ended ? "ended" : "running",
                      biss_strerror(rc));
        /* 2 ms of SSI frames (about 23 us each), every one read */
        uint32_t lost_total = 0, last = 0, frames = 0;
        for (unsigned k = 0; k < 20; k++) {
            ck_assert_int_eq(biss_run_us(h, 100), BISS_OK);
            struct biss_sample s[64];
            unsigned n;
            uint32_t lost;
            ck_assert_int_eq(biss_ring_read(h, s, 64, &n, &lost), BISS_OK);
            lost_total += lost;
            for (unsigned i = 0; i < n; i++) {
                ck_assert_msg(s[i].valid && s[i].nslaves == 1, "SSI frame %u", s[i].frame);
                ck_assert(last == 0 || s[i].seq == last + 1);
                last = s[i].seq;
            }
            frames += n;
        }
        ck_assert_uint_le(lost_total, 1); /* the BiSS-C frame under way at the ack */
        ck_assert_uint_ge(frames, 80);
        ck_assert_int_eq(biss_cd_poll(h, j), rc);
        ck_assert_int_eq(biss_cd_job_bytes(j, got), rc);
        if (ended) {
            ck_assert_mem_eq(got, want, 2);
        }
        biss_cd_job_free(j);
        ck_assert_int_eq(biss_configure(h, &base), BISS_OK);
        ck_assert_int_eq(biss_run_ms(h, 1), BISS_OK);
        rc = biss_reg_read(h, 0, 0x78, got, 2);
        ck_assert_msg(rc == BISS_OK, "back on BiSS-C: %s", biss_strerror(rc));
        ck_assert_mem_eq(got, want, 2);
    }
    ck_assert_uint_ge(seen[0], 5);
    ck_assert_uint_ge(seen[1], 5);
    biss_close(h);
}
END_TEST

int main(void) {
    Suite *s = suite_create("host_reconfig");
    TCase *tc = tcase_create("reconfig");
    tcase_set_timeout(tc, 120);
    tcase_add_loop_test(tc, test_rate_jumps, 0, 3);
    tcase_add_loop_test(tc, test_trigger_changes, 0, 4);
    tcase_add_test(tc, test_chain_shape);
    tcase_add_test(tc, test_ssi_and_back);
    tcase_add_test(tc, test_ssi_ends_a_running_program);
    tcase_add_loop_test(tc, test_back_to_back, 0, 2);
    tcase_add_loop_test(tc, test_iep_left, 0, 2);
    tcase_add_loop_test(tc, test_iep_kept_for_the_other, 0, 2);
    suite_add_tcase(s, tc);
    return check_run(s);
}
