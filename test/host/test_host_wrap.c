/* The counters at their limits, through libbiss on the emulator (the real
 * firmware image, the default encoder at 10 MHz): what a host meets after
 * the master has run for hours or days. Rather than run that long, the
 * tests write a counter near its limit into the firmware's data RAM while
 * the firmware leaves it alone (before a configuration, or between two
 * host-triggered frames) and watch every reader across the wrap:
 *  - the publication counter ST_SEQ (and the frame numbers) passing 2^32:
 *    the frame published as 0 is a frame like any other (biss_shm.h: the
 *    firmware adds 1 to ST_SEQ, modulo 2^32);
 *  - 2^31 publications and more after a configuration: still its frames;
 *  - the control program counter CD_CMD passing 2^32;
 *  - the IEP count (the timestamps) passing 2^32 between two frames, and
 *    lying 2^31 or more counts on between two: the speed check's time. */
#include "libbiss-emu.h"

#include "bench.h"
#include "bench_fw.h"
#include "biss/biss_shm_struct.h"

#include "check_run.h"

#include <check.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

#define FREQ 10000000u

static void poke32(biss_t *h, uint32_t off, uint32_t v) {
    struct biss_proto_io io = bench_fw_io(biss_emu_bench(h));
    ck_assert_int_eq(io.write(io.ctx, off, &v, 4), BISS_OK);
}

static uint32_t peek32(biss_t *h, uint32_t off) {
    struct biss_proto_io io = bench_fw_io(biss_emu_bench(h));
    uint32_t v;
    ck_assert_int_eq(io.read(io.ctx, off, &v, 4), BISS_OK);
    return v;
}

static biss_t *open_emu(void) {
    struct biss_open_params p;
    biss_open_params_default(&p);
    p.target = BISS_TARGET_EMU;
    biss_t *h;
    ck_assert_int_eq(biss_emu_open(&p, &h), BISS_OK);
    ck_assert_int_eq(biss_run_us(h, 10), BISS_OK); /* its start-up clears the status words */
    ck_assert_uint_eq(peek32(h, BISS_ST_MAGIC), BISS_MAGIC);
    return h;
}

static void configure(biss_t *h, enum biss_trigger trig) {
    struct biss_config c;
    biss_config_default(&c);
    c.freq_hz = FREQ;
    c.trigger = trig;
    ck_assert_int_eq(biss_config_from_emu(h, &c), BISS_OK);
    ck_assert_int_eq(biss_configure(h, &c), BISS_OK);
}

/* The firmware's publication counter set to seq, as if it had published
 * that many frames (ST_FRAMES counts them alike). Only while it publishes
 * nothing: before a configuration, or between host-triggered frames. */
static void set_published(biss_t *h, uint32_t seq) {
    poke32(h, BISS_ST_SEQ, seq);
    poke32(h, BISS_ST_FRAMES, seq);
}

/* One host-triggered frame, read by biss_wait_sample: it is frame after + 1. */
static void trigger_one(biss_t *h, uint32_t after, struct biss_sample *s) {
    ck_assert_int_eq(biss_trigger(h), BISS_OK);
    int rc = biss_wait_sample(h, after, 5, s);
    ck_assert_msg(rc == BISS_OK, "frame after %u: %s", after, biss_strerror(rc));
    ck_assert_uint_eq(s->frame, after + 1);
    ck_assert_uint_eq(s->seq, after + 1);
    ck_assert_msg(s->valid, "frame %u not valid (flags 0x%x)", s->frame, s->flags);
}

/* Host trigger across 2^32: every frame, 0 included, read by
 * biss_wait_sample and biss_read_sample as it comes, then all of them by
 * the ring, in order, none lost. */
START_TEST(test_host_trigger_across_the_wrap) {
    biss_t *h = open_emu();
    set_published(h, 0xfffffffcu);
    configure(h, BISS_TRIGGER_HOST);
    ck_assert_int_eq(biss_run_ms(h, 1), BISS_OK); /* the training frame */
    struct biss_sample s;
    ck_assert_int_eq(biss_read_sample(h, &s), BISS_OK);
    ck_assert(s.training);
    ck_assert_uint_eq(s.frame, 0xfffffffdu);
    uint32_t after = s.frame;
    for (int i = 0; i < 5; i++) { /* ...fe, ...ff, 0, 1, 2 */
        trigger_one(h, after, &s);
        after = s.frame;
        ck_assert_int_eq(biss_run_us(h, 50), BISS_OK);
        struct biss_sample again;
        ck_assert_int_eq(biss_read_sample(h, &again), BISS_OK);
        ck_assert_uint_eq(again.frame, after);
        ck_assert_uint_eq(again.slave[0].position, s.slave[0].position);
        struct biss_status st; /* ST_SEQ 0 with ST_BUF a slot is a firmware's status */
        int rc = biss_get_status(h, &st);
        ck_assert_msg(rc == BISS_OK, "status at frame %u: %s (%s)", after, biss_strerror(rc),
                      biss_shm_problem(h));
        ck_assert_uint_eq(st.seq, after);
    }
    ck_assert_uint_eq(peek32(h, BISS_ST_SEQ), 2);
    struct biss_sample buf[16];
    unsigned n;
    uint32_t lost;
    ck_assert_int_eq(biss_ring_read(h, buf, 16, &n, &lost), BISS_OK);
    ck_assert_uint_eq(lost, 0);
    ck_assert_uint_eq(n, 6);
    for (unsigned i = 0; i < n; i++) {
        ck_assert_uint_eq(buf[i].frame, 0xfffffffdu + i);
        ck_assert(i == 0 ? buf[i].training : buf[i].valid);
    }
    biss_close(h);
}
END_TEST

/* Free-running across 2^32 (a frame every 22.6 us at 10 MHz): polled every
 * 5 us, so some polls find frame 0 the newest, the newest sample never
 * fails and is never older than the last; the ring reader gets every
 * frame in order, none lost. */
START_TEST(test_free_run_across_the_wrap) {
    biss_t *h = open_emu();
    set_published(h, 0xffffffffu - 100);
    configure(h, BISS_TRIGGER_FREERUN);
    uint32_t next = 0xffffffffu - 99, got = 0, newest = 0xffffffffu - 100;
    unsigned saw_zero = 0;
    struct biss_sample buf[64];
    ck_assert_int_eq(biss_run_us(h, 50), BISS_OK);
    while (got < 200) {
        ck_assert_int_eq(biss_run_us(h, 5), BISS_OK);
        struct biss_sample s;
        int rc = biss_read_sample(h, &s);
        ck_assert_msg(rc == BISS_OK, "newest after frame %u: %s", newest, biss_strerror(rc));
        ck_assert_int_ge((int32_t)(s.frame - newest), 0);
        newest = s.frame;
        saw_zero += s.frame == 0;
        unsigned n;
        uint32_t lost;
        ck_assert_int_eq(biss_ring_read(h, buf, 64, &n, &lost), BISS_OK);
        ck_assert_uint_eq(lost, 0);
        for (unsigned i = 0; i < n; i++) {
            ck_assert_uint_eq(buf[i].frame, next);
            ck_assert(buf[i].valid || (buf[i].training && got == 0));
            next++;
            got++;
        }
    }
    ck_assert_uint_ge(saw_zero, 2); /* 22.6 us: 4 or 5 polls */
    struct biss_stats st;
    ck_assert_int_eq(biss_get_stats(h, &st), BISS_OK);
    ck_assert_uint_eq(st.frames, peek32(h, BISS_ST_SEQ)); /* past the wrap: small */
    ck_assert_uint_lt(st.frames, 200);
    biss_close(h);
}
END_TEST

/* 2^31 publications and more after the configuration (12 hours at 50 kHz):
 * the newest sample and a wait for the next are this configuration's. */
START_TEST(test_half_the_counter_after_configuring) {
    biss_t *h = open_emu();
    configure(h, BISS_TRIGGER_HOST);
    ck_assert_int_eq(biss_run_ms(h, 1), BISS_OK);
    struct biss_sample s;
    ck_assert_int_eq(biss_read_sample(h, &s), BISS_OK);
    uint32_t cfg_pub = s.frame - 1; /* the training frame is the first */
    uint32_t far[] = {cfg_pub + 0x7ffffffeu, cfg_pub + 0x80000000u, cfg_pub + 0xfffffff0u};
    for (unsigned k = 0; k < sizeof far / sizeof far[0]; k++) {
        set_published(h, far[k]);
        trigger_one(h, far[k], &s);
        struct biss_sample again;
        int rc = biss_read_sample(h, &again);
        ck_assert_msg(rc == BISS_OK, "newest at %u after the configuration: %s",
                      far[k] + 1 - cfg_pub, biss_strerror(rc));
        ck_assert_uint_eq(again.frame, far[k] + 1);
    }
    biss_close(h);
}
END_TEST

/* The control program counter CD_CMD at 2^32 - 1 (the last program's,
 * echoed in ST_CD_SEQ): the next register reads run and end as any. The
 * firmware takes CD_CMD 0 for "no program" (pru_fw/cd.p, CdState.cmd). */
START_TEST(test_control_counter_across_the_wrap) {
    biss_t *h = open_emu();
    configure(h, BISS_TRIGGER_FREERUN);
    ck_assert_int_eq(biss_run_ms(h, 1), BISS_OK);
    poke32(h, BISS_CD_CMD, 0xfffffffeu);
    poke32(h, BISS_ST_CD_SEQ, 0xfffffffeu);
    for (int i = 0; i < 3; i++) { /* ...ff, then past 0 */
        uint8_t b[2];
        int rc = biss_reg_read(h, 0, 0x78, b, 2);
        ck_assert_msg(rc == BISS_OK, "read %d (CD_CMD 0x%x): %s", i, peek32(h, BISS_CD_CMD),
                      biss_strerror(rc));
        ck_assert_uint_eq(b[0], 0x46);
        ck_assert_uint_eq(b[1], 0x3a);
        ck_assert_uint_eq(peek32(h, BISS_ST_CD_SEQ), peek32(h, BISS_CD_CMD));
    }
    ck_assert_uint_ne(peek32(h, BISS_CD_CMD), 0);
    ck_assert_uint_lt(peek32(h, BISS_CD_CMD), 3);
    biss_close(h);
}
END_TEST

/* The IEP count (the timestamps) set to `count`, as 21.5 s of running
 * leave it once a wrap (COUNT, AM335x TRM 30.1.11.2.4: offset 0x0C). */
static void set_iep_count(biss_t *h, uint32_t count) {
    struct bench *b = biss_emu_bench(h);
    uint32_t at = pru_soc_base(bench_config(b)->soc) + PRU_OFS_IEP + 0x0c;
    ck_assert_int_eq(pru_host_write32(bench_core(b), at, count), 0);
}

/* The default encoder turning at 20000 counts/s, checked at 30000: its
 * positions are all within reach, whatever the IEP count. */
static biss_t *open_turning(char *path, size_t len) {
    snprintf(path, len, "/tmp/biss-wrap-%ld.json", (long)getpid());
    FILE *f = fopen(path, "w");
    ck_assert_ptr_nonnull(f);
    fputs("{\"biss\": {\"slaves\": [{\"speed_cps\": 20000}]}, "
          "\"checks\": {\"max_speed\": [{\"slave\": 0, \"counts_per_s\": 30000}]}}",
          f);
    fclose(f);
    struct biss_open_params p;
    biss_open_params_default(&p);
    p.target = BISS_TARGET_EMU;
    p.scenario_file = path;
    biss_t *h;
    int rc = biss_emu_open(&p, &h);
    ck_assert_msg(rc == BISS_OK, "open: %s", biss_strerror(rc));
    return h;
}

/* Free-running and host-triggered, the IEP count passing 2^32 between two
 * frames: the speed check's time between them is the modular difference,
 * every position within reach (none misframed), each one judged. */
START_TEST(test_timestamps_across_the_iep_wrap) {
    static const enum biss_trigger trig[] = {BISS_TRIGGER_FREERUN, BISS_TRIGGER_HOST};
    for (unsigned t = 0; t < 2; t++) {
        char path[64];
        biss_t *h = open_turning(path, sizeof path);
        struct biss_config c;
        biss_config_default(&c);
        c.freq_hz = FREQ;
        c.trigger = trig[t];
        ck_assert_int_eq(biss_config_from_emu(h, &c), BISS_OK);
        ck_assert_double_eq(c.slave[0].max_speed, 30000);
        /* 500 us before the wrap: the count runs on through the
         * configuration (free-run and host trigger leave it alone) */
        set_iep_count(h, 0xffffffffu - 100000);
        ck_assert_int_eq(biss_configure(h, &c), BISS_OK);
        struct biss_sample buf[64];
        unsigned judged = 0, wrapped = 0;
        uint32_t last_ts = 0;
        for (int poll = 0; poll < 150; poll++) {
            if (trig[t] == BISS_TRIGGER_HOST) {
                ck_assert_int_eq(biss_run_us(h, 20), BISS_OK); /* the frame before ended */
                ck_assert_int_eq(biss_trigger(h), BISS_OK);
            }
            ck_assert_int_eq(biss_run_us(h, 10), BISS_OK);
            unsigned n;
            uint32_t lost;
            ck_assert_int_eq(biss_ring_read(h, buf, 64, &n, &lost), BISS_OK);
            ck_assert_uint_eq(lost, 0);
            for (unsigned i = 0; i < n; i++) {
                ck_assert_msg(!buf[i].misframed, "frame %u (timestamp %u) misframed", buf[i].frame,
                              buf[i].timestamp);
                ck_assert(buf[i].valid || buf[i].training);
                judged += (buf[i].safety & BISS_SAFE_POS_CHECKED) != 0;
                wrapped += last_ts > 0xf0000000u && buf[i].timestamp < 0x10000000u;
                last_ts = buf[i].timestamp;
            }
        }
        ck_assert_uint_eq(wrapped, 1);
        ck_assert_uint_ge(judged, 60);
        struct biss_safety_stats st;
        ck_assert_int_eq(biss_get_safety_stats(h, &st), BISS_OK);
        ck_assert_uint_eq(st.pos_jumped[0], 0);
        biss_close(h);
        unlink(path);
    }
}
END_TEST

/* A host that triggers a frame every 10.7 s or more (as the IEP count
 * shows it: the count is moved on between two frames, the encoder turns
 * as ever): past half the counter the time since the last frame is not
 * known, so the speed check neither passes nor refuses such a frame; it
 * is valid and the reference for the next, which the check judges as
 * ever. (Before, every frame from the first such gap on was refused as
 * misframed: none valid for as long as the host polled so slowly.) */
START_TEST(test_slow_host_trigger_speed_check) {
    char path[64];
    biss_t *h = open_turning(path, sizeof path);
    struct biss_config c;
    biss_config_default(&c);
    c.freq_hz = FREQ;
    c.trigger = BISS_TRIGGER_HOST;
    ck_assert_int_eq(biss_config_from_emu(h, &c), BISS_OK);
    ck_assert_int_eq(biss_configure(h, &c), BISS_OK);
    ck_assert_int_eq(biss_run_ms(h, 1), BISS_OK); /* the training frame */
    struct biss_sample s;
    ck_assert_int_eq(biss_read_sample(h, &s), BISS_OK);
    uint32_t after = s.frame;
    trigger_one(h, after, &s); /* the first position: the reference */
    after = s.frame;
    /* 2^31 counts (10.74 s) and a little more after the frame before, as
     * the frame starts later than the count is set; 10.74 s, 16.1 s and
     * 21.47 s (a count that came round once more is the clock's to tell:
     * test_proto_safety, test_speed_clock_came_round) */
    static const uint32_t gap[] = {0x80000000u, 0x80000000u + 20000, 0xc0000000u, 0xfffff000u};
    for (unsigned k = 0; k < 4; k++) {
        ck_assert_int_eq(biss_run_us(h, 30), BISS_OK);
        set_iep_count(h, s.timestamp + gap[k]);
        trigger_one(h, after, &s);
        after = s.frame;
        ck_assert_msg(!s.misframed, "frame %u after a gap of 0x%x counts misframed", s.frame,
                      gap[k]);
        ck_assert_uint_eq(s.slave[0].safety, BISS_SAFE_POS_UNTIMED);
    }
    for (unsigned k = 0; k < 3; k++) { /* then 30 us apart: judged */
        ck_assert_int_eq(biss_run_us(h, 30), BISS_OK);
        trigger_one(h, after, &s);
        after = s.frame;
        ck_assert_uint_eq(s.slave[0].safety, BISS_SAFE_POS_CHECKED);
    }
    /* the ring reader, judging the same frames in its own order, alike */
    struct biss_sample buf[16];
    unsigned n;
    uint32_t lost;
    ck_assert_int_eq(biss_ring_read(h, buf, 16, &n, &lost), BISS_OK);
    ck_assert_uint_eq(n, 9);
    ck_assert_uint_eq(lost, 0);
    for (unsigned i = 1; i < n; i++) {
        ck_assert(buf[i].valid);
        uint32_t want = i == 1 ? 0 : i < 6 ? BISS_SAFE_POS_UNTIMED : BISS_SAFE_POS_CHECKED;
        ck_assert_msg(buf[i].slave[0].safety == want, "ring frame %u: 0x%x", buf[i].frame,
                      buf[i].slave[0].safety);
    }
    struct biss_safety_stats st;
    ck_assert_int_eq(biss_get_safety_stats(h, &st), BISS_OK);
    ck_assert_uint_eq(st.pos_untimed[0], 4);
    ck_assert_uint_eq(st.pos_checked[0], 3);
    ck_assert_uint_eq(st.pos_jumped[0] + st.pos_resync[0], 0);
    biss_close(h);
    unlink(path);
}
END_TEST

int main(void) {
    Suite *s = suite_create("host_wrap");
    TCase *tc = tcase_create("wrap");
    tcase_set_timeout(tc, 60);
    tcase_add_test(tc, test_host_trigger_across_the_wrap);
    tcase_add_test(tc, test_free_run_across_the_wrap);
    tcase_add_test(tc, test_half_the_counter_after_configuring);
    tcase_add_test(tc, test_control_counter_across_the_wrap);
    tcase_add_test(tc, test_timestamps_across_the_iep_wrap);
    tcase_add_test(tc, test_slow_host_trigger_speed_check);
    suite_add_tcase(s, tc);
    return check_run(s);
}
