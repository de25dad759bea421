/* libbiss protocol code against a scripted firmware (fake_backend.c): the
 * seqlock reader while frames are published under it, waiting, and the
 * configuration handshake with the firmware's verdict. */
#include "fake_backend.h"

#include "biss/biss_shm.h"

#include "check_run.h"

#include <check.h>
#include <pthread.h>
#include <stdlib.h>

/* A sample is whole when every word came from the one frame it names, and
 * its seq is that frame's publication number, also when the slot ST_BUF
 * names is the one being published (whole, with ST_SEQ not yet bumped). */
static void assert_consistent(const struct biss_sample *s) {
    uint32_t k = s->frame;
    ck_assert_uint_eq(s->seq, k);
    ck_assert_uint_eq(s->timestamp, k);
    ck_assert_uint_eq(s->proc_clocks, k & 0xffffu);
    ck_assert_uint_eq(s->delay.raw, 8 + k % 4096);
    ck_assert_uint_eq(s->delay.avg, 8 + (k >> 12) % 4096);
    ck_assert_uint_eq(s->sample_point, k & 7);
    ck_assert_uint_eq(s->lag_periods, k >> 3 & 0xff);
    ck_assert(s->valid);
    ck_assert_uint_eq(s->nslaves, BISS_MAX_SLAVES);
    for (unsigned i = 0; i < s->nslaves; i++) {
        ck_assert_uint_eq(s->slave[i].data, (uint64_t)k << 32 | k);
        ck_assert_uint_eq(s->slave[i].crc_reg, k);
        ck_assert_uint_eq(s->slave[i].status, k & 7);
    }
}

/* The fake stores 0..12 words before each host access: a publication
 * (42 stores) lands in the middle of most reads of the 40-word buffer. */
START_TEST(test_reader_never_sees_a_torn_frame) {
    struct fake *f;
    biss_t *h = fake_handle(&f);
    f->publishing = true;
    f->max_steps = 12;
    struct biss_sample s;
    uint32_t last = 0;
    unsigned samples = 0;
    while (samples < 3000) {
        int rc = biss_read_sample(h, &s);
        if (rc == BISS_E_NO_SAMPLE) {
            continue;
        }
        ck_assert_int_eq(rc, BISS_OK);
        assert_consistent(&s);
        ck_assert_uint_ge(s.frame, last);
        last = s.frame;
        samples++;
    }
    /* the reads really did race the publications */
    ck_assert_uint_gt(f->frame, 1000);
    ck_assert_uint_gt(f->accesses, 4ul * samples);
    biss_close(h);
}
END_TEST

/* The ring reader while the firmware publishes under it: before each of
 * its reads the fake stores 0..60 words (a publication is 42), and every
 * 50th call the host was away for 1 ms (1000 stores: 23 publications;
 * the ring keeps 17 of eight slaves). Every frame returned is whole, each
 * seq once and in order; the frames not returned are exactly the ones
 * counted lost, and some were. */
START_TEST(test_ring_reader_counts_what_it_misses) {
    struct fake *f;
    biss_t *h = fake_handle(&f);
    f->publishing = true;
    f->max_steps = 60;
    f->steps_per_us = 1;
    struct biss_sample buf[32];
    uint32_t done = 0; /* the last seq returned or counted lost */
    uint64_t got = 0, lost_total = 0;
    for (int call = 0; call < 20000; call++) {
        if (call % 50 == 49) {
            ck_assert_int_eq(biss_run_ms(h, 1), BISS_OK);
        }
        unsigned n;
        uint32_t lost;
        int rc = biss_ring_read(h, buf, 32, &n, &lost);
        ck_assert_msg(rc == BISS_OK, "call %d: %s: %s", call, biss_strerror(rc),
                      biss_shm_problem(h));
        uint32_t gaps = 0;
        for (unsigned i = 0; i < n; i++) {
            assert_consistent(&buf[i]);
            ck_assert_uint_eq(buf[i].seq, buf[i].frame);
            if (call > 0) { /* (the first call starts at the newest) */
                ck_assert_uint_gt(buf[i].seq, done);
                gaps += buf[i].seq - done - 1;
            }
            done = buf[i].seq;
        }
        /* every frame not returned is counted: the gaps, then any after */
        ck_assert_uint_ge(lost, gaps);
        done += lost - gaps;
        got += n;
        lost_total += lost;
    }
    ck_assert_uint_gt(got, 10000);
    ck_assert_uint_gt(lost_total, 0);
    /* the reader's place is the one counted here: the next is done + 1 */
    f->max_steps = 0;
    unsigned n;
    uint32_t lost;
    ck_assert_int_eq(biss_ring_read(h, buf, 32, &n, &lost), BISS_OK);
    ck_assert_uint_eq(done + n + lost, fake_dram32(f, BISS_ST_SEQ));
    biss_close(h);
}
END_TEST

/* The firmware begins refilling a slot while the reader copies it: frame
 * 18 published, the reader 17 behind (all the ring keeps), and while it
 * copies, frame 19 is published and frame 20's timestamp stored in the
 * oldest copied slot (frame 2's), as BUF_STAMP does first; its frame
 * number still says 2. ST_SEQ read after the copy shows it: frame 2 is
 * counted lost, frames 3..18 come whole. Without the stores, all 17. */
static bool refill_armed;

static void refill_during_copy(struct fake *f, uint32_t off, size_t n) {
    if (!refill_armed || off < BISS_RING0 || n <= BISS_R_SLAVE0) {
        return; /* not the copy */
    }
    refill_armed = false;
    fake_steps(f, FAKE_RESULT_WORDS + 2); /* frame 19, whole */
    uint32_t slot2 = BISS_RING0 + 1 * BISS_RING_STRIDE(BISS_MAX_SLAVES);
    fake_set_dram32(f, slot2 + BISS_R_TIMESTAMP, 20);
}

static void ring_behind_by_17(biss_t **h, struct fake **f) {
    *h = fake_handle(f);
    (*f)->publishing = true;
    fake_steps(*f, FAKE_RESULT_WORDS + 2); /* frame 1 */
    struct biss_sample buf[32];
    unsigned n;
    uint32_t lost;
    ck_assert_int_eq(biss_ring_read(*h, buf, 32, &n, &lost), BISS_OK);
    ck_assert_uint_eq(n, 1);                      /* the newest, where a reader starts */
    fake_steps(*f, 17 * (FAKE_RESULT_WORDS + 2)); /* frames 2..18 */
    ck_assert_uint_eq(FAKE_SLOTS - 1, 17);
}

START_TEST(test_ring_copy_being_refilled_is_lost) {
    struct fake *f;
    biss_t *h;
    struct biss_sample buf[32];
    unsigned n;
    uint32_t lost;
    ring_behind_by_17(&h, &f);
    ck_assert_int_eq(biss_ring_read(h, buf, 32, &n, &lost), BISS_OK);
    ck_assert_uint_eq(n, 17);
    ck_assert_uint_eq(lost, 0);
    ck_assert_uint_eq(buf[0].seq, 2);
    biss_close(h);

    ring_behind_by_17(&h, &f);
    f->before_read = refill_during_copy;
    refill_armed = true;
    ck_assert_int_eq(biss_ring_read(h, buf, 32, &n, &lost), BISS_OK);
    ck_assert(!refill_armed); /* the stores came during the copy */
    ck_assert_uint_eq(lost, 1);
    ck_assert_uint_eq(n, 16);
    for (unsigned i = 0; i < n; i++) {
        ck_assert_uint_eq(buf[i].seq, 3 + i);
        assert_consistent(&buf[i]);
    }
    /* next: frame 19 */
    ck_assert_int_eq(biss_ring_read(h, buf, 32, &n, &lost), BISS_OK);
    ck_assert_uint_eq(n, 1);
    ck_assert_uint_eq(lost, 0);
    ck_assert_uint_eq(buf[0].seq, 19);
    biss_close(h);
}
END_TEST

/* The fake publishing frames from..to (publication numbers, none 0). */
static void publish_span(struct fake *f, uint32_t from, uint32_t to) {
    f->frame = from;
    fake_steps(f, (to - from + 1) * (FAKE_RESULT_WORDS + 2));
    ck_assert_uint_eq(fake_dram32(f, BISS_ST_SEQ), to);
}

/* A handle over a fake whose ring reader's last call took publication
 * 1000 (frames 990..1000 published). */
static biss_t *reader_at_1000(struct fake **f) {
    biss_t *h = fake_handle(f);
    (*f)->publishing = true;
    publish_span(*f, 990, 1000);
    struct biss_sample buf[32];
    unsigned n;
    uint32_t lost;
    ck_assert_int_eq(biss_ring_read(h, buf, 32, &n, &lost), BISS_OK);
    ck_assert_uint_eq(n, 1);
    ck_assert_uint_eq(buf[0].seq, 1000); /* the newest, where a reader starts */
    return h;
}

/* buf holds n frames: the `want` publications up to newest, in order,
 * each whole. */
static void assert_newest(const struct biss_sample *buf, unsigned n, unsigned want,
                          uint32_t newest) {
    ck_assert_uint_eq(n, want);
    for (unsigned i = 0; i < n; i++) {
        ck_assert_uint_eq(buf[i].seq, newest - (want - 1) + i);
        assert_consistent(&buf[i]);
    }
}

/* A reader that fell behind by `lag` publications with no configuration
 * between: the newest 17 come, in order, and exactly the rest are counted
 * lost, for any lag up to 2^32 - 1 (modulo 2^32: 2^31 and more behind is
 * behind, not a counter that went back), and around the ring's 17. */
START_TEST(test_ring_reader_far_behind) {
    static const uint32_t lag[] = {16, 17, 18, 0x7fffffffu, 0x80000000u, 0x80000001u, 0xffffffffu};
    for (unsigned k = 0; k < sizeof lag / sizeof lag[0]; k++) {
        struct fake *f;
        biss_t *h = reader_at_1000(&f);
        uint32_t newest = 1000 + lag[k];
        publish_span(f, lag[k] < 20 ? 1001 : newest - 19, newest);
        struct biss_sample buf[32];
        unsigned n;
        uint32_t lost;
        ck_assert_int_eq(biss_ring_read(h, buf, 32, &n, &lost), BISS_OK);
        unsigned want = lag[k] < 17 ? lag[k] : 17;
        ck_assert_msg(lost == lag[k] - want, "%u behind: %u lost", lag[k], lost);
        assert_newest(buf, n, want, newest);
        biss_close(h);
    }
}
END_TEST

/* The firmware restarted (by another process: its publications count
 * from 1 again, and the data RAM keeps the old run's slots). A restarted
 * firmware publishes nothing before a configuration, so the counter went
 * back where it reads as behind (2^31 or more on since the last call) and
 * ST_CFG_ACK changed: the reader starts again from the new run's first
 * publication, however long it was away: 5 of them all come, of 40 the
 * newest 17 (23 lost); none yet (the start-up's ST_CFG_ACK), nothing, then
 * from the first. */
START_TEST(test_ring_reader_after_a_restart) {
    static const uint32_t run[] = {5, 40, 0};
    for (unsigned k = 0; k < 3; k++) {
        struct fake *f;
        biss_t *h = reader_at_1000(&f);
        if (run[k]) {
            publish_span(f, 1, run[k]);
            fake_set_dram32(f, BISS_ST_CFG_ACK, 7);
        } else {
            fake_set_dram32(f, BISS_ST_SEQ, 0); /* the start-up's */
            fake_set_dram32(f, BISS_ST_BUF, 0);
            fake_set_dram32(f, BISS_ST_CFG_ACK, 0xfffffffeu);
        }
        f->now_us += 3600000000u;
        struct biss_sample buf[32];
        unsigned n;
        uint32_t lost;
        ck_assert_int_eq(biss_ring_read(h, buf, 32, &n, &lost), BISS_OK);
        unsigned want = run[k] < 17 ? run[k] : 17;
        ck_assert_msg(lost == run[k] - want, "%u published since the restart: %u lost", run[k],
                      lost);
        assert_newest(buf, n, want, run[k]);
        if (!run[k]) {
            publish_span(f, 1, 3);
            fake_set_dram32(f, BISS_ST_CFG_ACK, 7);
            ck_assert_int_eq(biss_ring_read(h, buf, 32, &n, &lost), BISS_OK);
            ck_assert_uint_eq(lost, 0);
            assert_newest(buf, n, 3, 3);
        }
        biss_close(h);
    }
}
END_TEST

/* What the counter and ST_CFG_ACK cannot tell: a restart whose
 * configuration took the number of the one before, not looked at in
 * between (the firmware restarted by something else, configured by a
 * handle new to it), reads as far behind: the frames that come are still
 * exactly the new run's (the old run's slots are not theirs: counted
 * lost), the lost count is that distance. And a reader 2^31 or more
 * behind across another handle's configuration reads as after a restart:
 * from publication 1. */
START_TEST(test_ring_restart_neither_tells) {
    struct fake *f;
    biss_t *h = reader_at_1000(&f);
    publish_span(f, 1, 5);
    struct biss_sample buf[32];
    unsigned n;
    uint32_t lost;
    ck_assert_int_eq(biss_ring_read(h, buf, 32, &n, &lost), BISS_OK);
    assert_newest(buf, n, 5, 5);
    ck_assert_uint_eq(lost, 5u - 1000u - 5u);
    biss_close(h);

    h = reader_at_1000(&f);
    uint32_t newest = 1000 + 0x80000000u;
    publish_span(f, newest - 19, newest);
    fake_set_dram32(f, BISS_ST_CFG_ACK, 7);
    ck_assert_int_eq(biss_ring_read(h, buf, 32, &n, &lost), BISS_OK);
    ck_assert_uint_eq(lost, newest - 17); /* from publication 1 */
    assert_newest(buf, n, 17, newest);
    biss_close(h);
}
END_TEST

/* The firmware stands between its stores of ST_BUF and ST_SEQ (the
 * emulator's PRU stops anywhere, and stands still while the host reads):
 * the slot ST_BUF names is whole and is the newest frame, for the ring
 * reader and the newest-sample read alike, with its own number; once
 * ST_SEQ follows, the ring reader does not return it again. */
START_TEST(test_between_st_buf_and_st_seq) {
    struct fake *f;
    biss_t *h = fake_handle(&f);
    f->publishing = true;
    fake_steps(f, 3 * (FAKE_RESULT_WORDS + 2)); /* frames 1..3 */
    struct biss_sample buf[32], s;
    unsigned n;
    uint32_t lost;
    ck_assert_int_eq(biss_ring_read(h, buf, 32, &n, &lost), BISS_OK);
    ck_assert_uint_eq(n, 1);              /* frame 3, where a reader starts */
    fake_steps(f, FAKE_RESULT_WORDS + 1); /* frame 4's words and ST_BUF */
    ck_assert_uint_eq(fake_dram32(f, BISS_ST_SEQ), 3);
    ck_assert_int_eq(biss_ring_read(h, buf, 32, &n, &lost), BISS_OK);
    ck_assert_uint_eq(n, 1);
    ck_assert_uint_eq(lost, 0);
    ck_assert_uint_eq(buf[0].seq, 4);
    assert_consistent(&buf[0]);
    ck_assert_int_eq(biss_read_sample(h, &s), BISS_OK);
    ck_assert_uint_eq(s.seq, 4);
    assert_consistent(&s);
    fake_steps(f, 1); /* ST_SEQ = 4 */
    ck_assert_int_eq(biss_ring_read(h, buf, 32, &n, &lost), BISS_OK);
    ck_assert_uint_eq(n, 0);
    ck_assert_uint_eq(lost, 0);
    fake_steps(f, FAKE_RESULT_WORDS + 2); /* frame 5 */
    ck_assert_int_eq(biss_ring_read(h, buf, 32, &n, &lost), BISS_OK);
    ck_assert_uint_eq(n, 1);
    ck_assert_uint_eq(buf[0].seq, 5);
    biss_close(h);
}
END_TEST

/* A whole publication (42 stores) before every access: ST_SEQ differs
 * at each re-read, so no read can complete. */
START_TEST(test_reader_gives_up) {
    struct fake *f;
    biss_t *h = fake_handle(&f);
    f->publishing = true;
    f->fixed_steps = true;
    f->max_steps = FAKE_RESULT_WORDS + 2;
    struct biss_sample s;
    ck_assert_int_eq(biss_read_sample(h, &s), BISS_E_RETRY);
    biss_close(h);
}
END_TEST

START_TEST(test_nothing_published) {
    struct fake *f;
    biss_t *h = fake_handle(&f);
    struct biss_sample s;
    ck_assert_int_eq(biss_read_sample(h, &s), BISS_E_NO_SAMPLE);
    ck_assert_int_eq(biss_wait_sample(h, 0, 0, &s), BISS_E_TIMEOUT);
    struct biss_line_delay d;
    ck_assert_int_eq(biss_line_delay(h, &d), BISS_E_NO_SAMPLE);
    ck_assert_int_eq(biss_read_sample(NULL, &s), BISS_E_INVAL);
    ck_assert_int_eq(biss_read_sample(h, NULL), BISS_E_INVAL);
    biss_close(h);
}
END_TEST

/* Publications only as (fake) time passes: 42 stores per frame at 4 per
 * microsecond is one frame every 10.5 us. */
START_TEST(test_wait_sample) {
    struct fake *f;
    biss_t *h = fake_handle(&f);
    f->publishing = true;
    f->steps_per_us = 4;
    struct biss_sample s;
    ck_assert_int_eq(biss_wait_sample(h, 0, 1, &s), BISS_OK);
    ck_assert_uint_eq(s.frame, 1);
    uint64_t t0 = f->now_us;
    ck_assert_int_eq(biss_wait_sample(h, 5, 1, &s), BISS_OK);
    ck_assert_uint_eq(s.frame, 6);
    assert_consistent(&s);
    /* it returned as soon as frame 6 was out, not at the timeout */
    ck_assert_uint_lt(f->now_us - t0, 1000);
    /* nothing newer comes: the timeout, in backend time */
    f->publishing = false;
    t0 = f->now_us;
    ck_assert_int_eq(biss_wait_sample(h, s.frame, 3, &s), BISS_E_TIMEOUT);
    ck_assert_uint_eq(f->now_us - t0, 3000);
    /* frame numbers wrap: 0xfffffff0 is "before" 6 */
    ck_assert_int_eq(biss_wait_sample(h, 0xfffffff0u, 0, &s), BISS_OK);
    biss_close(h);
}
END_TEST

static struct biss_config one_slave(enum biss_trigger t) {
    struct biss_config c;
    biss_config_default(&c);
    c.freq_hz = 10000000;
    c.nslaves = 1;
    c.trigger = t;
    c.slave[0] = (struct biss_slave_config){
        .data_bits = 14, .crc_bits = 6, .crc_poly = 0x43, .has_ew = true};
    return c;
}

START_TEST(test_configure_handshake) {
    struct fake *f;
    biss_t *h = fake_handle(&f);
    struct biss_config c = one_slave(BISS_TRIGGER_FREERUN);
    /* no firmware at all */
    ck_assert_int_eq(biss_configure(h, &c), BISS_E_NOT_RUNNING);
    ck_assert_uint_eq(fake_dram32(f, BISS_CFG_SEQ), 1);
    /* running but deaf */
    fake_set_dram32(f, BISS_ST_MAGIC, BISS_MAGIC);
    ck_assert_int_eq(biss_configure(h, &c), BISS_E_TIMEOUT);
    ck_assert_uint_eq(fake_dram32(f, BISS_CFG_SEQ), 2);
    /* answering */
    f->acks = true;
    ck_assert_int_eq(biss_configure(h, &c), BISS_OK);
    ck_assert_uint_eq(fake_dram32(f, BISS_CFG_SEQ), 3);
    ck_assert_uint_eq(fake_dram32(f, BISS_ST_CFG_ACK), 3);
    ck_assert_uint_eq(fake_dram32(f, BISS_CFG_HALF) & 0xffff, 10);
    struct biss_config back;
    ck_assert_int_eq(biss_get_config(h, &back), BISS_OK);
    ck_assert_uint_eq(back.freq_hz, 10000000);
    /* the firmware refuses: its reason comes back */
    f->cfg_error = BISS_CFGERR_HALF;
    ck_assert_int_eq(biss_configure(h, &c), BISS_E_FW_HALF);
    ck_assert_int_eq(biss_get_config(h, &back), BISS_E_NOT_CONFIGURED);
    f->cfg_error = BISS_CFGERR_IEP_PERIOD;
    ck_assert_int_eq(biss_configure(h, &c), BISS_E_FW_IEP_PERIOD);
    /* host-side checks never reach the firmware */
    uint32_t seq = fake_dram32(f, BISS_CFG_SEQ);
    c.freq_hz = 3000000;
    ck_assert_int_eq(biss_configure(h, &c), BISS_E_RATE_INEXACT);
    ck_assert_uint_eq(fake_dram32(f, BISS_CFG_SEQ), seq);
    biss_close(h);
}
END_TEST

/* CFG_SEQ never takes 0 ("none written") or 0xffffffff (the firmware's
 * initial ack): either would be taken as already acknowledged. */
START_TEST(test_seq_skips_reserved_values) {
    struct fake *f;
    biss_t *h = fake_handle(&f);
    f->acks = true;
    fake_set_dram32(f, BISS_ST_MAGIC, BISS_MAGIC);
    struct biss_config c = one_slave(BISS_TRIGGER_FREERUN);
    h->cfg_seq = 0xfffffffeu;
    ck_assert_int_eq(biss_configure(h, &c), BISS_OK);
    ck_assert_uint_eq(fake_dram32(f, BISS_CFG_SEQ), 1);
    biss_close(h);
}
END_TEST

START_TEST(test_trigger_modes) {
    struct fake *f;
    biss_t *h = fake_handle(&f);
    f->acks = true;
    fake_set_dram32(f, BISS_ST_MAGIC, BISS_MAGIC);
    ck_assert_int_eq(biss_trigger(h), BISS_E_NOT_CONFIGURED);
    struct biss_config c = one_slave(BISS_TRIGGER_FREERUN);
    ck_assert_int_eq(biss_configure(h, &c), BISS_OK);
    ck_assert_int_eq(biss_trigger(h), BISS_E_NOT_HOST_TRIG);
    ck_assert_uint_eq(fake_dram32(f, BISS_CMD_TRIGGER), 0);
    c = one_slave(BISS_TRIGGER_HOST);
    ck_assert_int_eq(biss_configure(h, &c), BISS_OK);
    ck_assert_int_eq(biss_trigger(h), BISS_OK);
    ck_assert_uint_eq(fake_dram32(f, BISS_CMD_TRIGGER), 1);
    /* not yet taken: asked for again, that frame would come once */
    ck_assert_int_eq(biss_trigger(h), BISS_E_TRIGGER_PENDING);
    fake_set_dram32(f, BISS_CMD_TRIGGER, 0); /* the firmware starts the frame */
    ck_assert_int_eq(biss_trigger(h), BISS_OK);
    ck_assert_uint_eq(fake_dram32(f, BISS_CMD_TRIGGER), 1);
    biss_close(h);
}
END_TEST

struct reader {
    biss_t *h;
    int bad;
    int last_rc;
};

static void *read_many(void *arg) {
    struct reader *r = arg;
    for (int i = 0; i < 2000; i++) {
        struct biss_sample s;
        int rc = biss_read_sample(r->h, &s);
        if (rc == BISS_OK) {
            r->bad += (s.seq != s.frame && s.seq + 1 != s.frame) || s.timestamp != s.frame ||
                      s.slave[7].data != ((uint64_t)s.frame << 32 | s.frame);
        } else if (rc != BISS_E_NO_SAMPLE) {
            r->bad++;
            r->last_rc = rc;
        }
    }
    return NULL;
}

/* One handle, several threads: the handle's lock keeps the fake (which is
 * not thread safe at all) and the reads whole. */
START_TEST(test_threads_share_a_handle) {
    struct fake *f;
    biss_t *h = fake_handle(&f);
    f->publishing = true;
    f->max_steps = 6;
    pthread_t t[4];
    struct reader r[4];
    for (int i = 0; i < 4; i++) {
        r[i] = (struct reader){.h = h};
        ck_assert_int_eq(pthread_create(&t[i], NULL, read_many, &r[i]), 0);
    }
    for (int i = 0; i < 4; i++) {
        pthread_join(t[i], NULL);
        ck_assert_msg(r[i].bad == 0, "%d bad reads, last %s", r[i].bad,
                      biss_strerror(r[i].last_rc));
    }
    biss_close(h);
}
END_TEST

int main(void) {
    Suite *s = suite_create("host_seqlock");
    TCase *tc = tcase_create("protocol");
    tcase_add_test(tc, test_reader_never_sees_a_torn_frame);
    tcase_add_test(tc, test_reader_gives_up);
    tcase_add_test(tc, test_ring_reader_counts_what_it_misses);
    tcase_add_test(tc, test_ring_copy_being_refilled_is_lost);
    tcase_add_test(tc, test_ring_reader_far_behind);
    tcase_add_test(tc, test_ring_reader_after_a_restart);
    tcase_add_test(tc, test_ring_restart_neither_tells);
    tcase_add_test(tc, test_between_st_buf_and_st_seq);
    tcase_add_test(tc, test_nothing_published);
    tcase_add_test(tc, test_wait_sample);
    tcase_add_test(tc, test_configure_handshake);
    tcase_add_test(tc, test_seq_skips_reserved_values);
    tcase_add_test(tc, test_trigger_modes);
    tcase_add_test(tc, test_threads_share_a_handle);
    suite_add_tcase(s, tc);
    return check_run(s);
}
