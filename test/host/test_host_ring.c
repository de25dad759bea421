/* Every frame through libbiss's ring reader on the emulator (the real
 * firmware image, the default encoder at 10 MHz): a host that polls every
 * millisecond of PRU time loses none of 10^6 frames, each the position
 * the encoder model sent in it; one that polls too rarely loses exactly
 * the frames the ring could not keep, counted. The model's side comes
 * from a store watch on the firmware's ST_BUF, the store that makes a slot
 * the newest (the reader may take it before ST_SEQ's, one instruction
 * later, when the emulator stops between them): at each publication, the
 * record of the frame the slave model just sent, kept by the slot's
 * publication number; the reader never sees it. */
#include "libbiss-emu.h"

#include "bench.h"
#include "bench_fw.h"
#include "biss/biss_shm_struct.h"

#include "check_run.h"

#include <check.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#define FREQ 10000000u
#define KEEP 4096u /* publications remembered: many polls' worth */

/* What the encoder model sent, by publication number. */
struct model_log {
    struct bench *b;
    uint32_t published; /* the last publication number seen */
    uint32_t seq[KEEP];
    uint64_t position[KEEP];
    bool recorded[KEEP]; /* the model held the frame's record (a frame it answered) */
};

static void on_publish(void *ctx, uint32_t addr) {
    struct model_log *m = ctx;
    (void)addr;
    struct biss_proto_io io = bench_fw_io(m->b);
    struct biss_shm_result r0;
    if (biss_proto_result_get(&io, 0, &r0) != BISS_OK) {
        return; /* the start-up clearing the status words: no slot */
    }
    uint32_t seq = r0.frame; /* the slot's publication number */
    ck_assert_uint_eq(seq, m->published + 1);
    m->published = seq;
    link_model *l = bench_link(m->b);
    uint64_t n = bench_current_frame(m->b);
    const void *r = n == UINT64_MAX ? NULL : link_record(l, n);
    slave_frame f;
    if (r) {
        l->model->frame(link_model_cfg(l), r, &f);
    }
    m->seq[seq % KEEP] = seq;
    m->recorded[seq % KEEP] = r != NULL;
    m->position[seq % KEEP] = r ? f.word[0].position : 0;
}

static biss_t *open_logged_as(struct model_log *m, enum biss_trigger trigger) {
    struct biss_open_params p;
    biss_open_params_default(&p);
    p.target = BISS_TARGET_EMU;
    biss_t *h;
    ck_assert_int_eq(biss_emu_open(&p, &h), BISS_OK);
    memset(m, 0, sizeof *m);
    m->b = biss_emu_bench(h);
    pru_set_store_watch(bench_core(m->b), BISS_ST_BUF, on_publish, m);
    struct biss_config c;
    biss_config_default(&c);
    c.freq_hz = FREQ;
    c.trigger = trigger;
    ck_assert_int_eq(biss_config_from_emu(h, &c), BISS_OK);
    ck_assert_int_eq(biss_configure(h, &c), BISS_OK);
    unsigned cap;
    ck_assert_int_eq(biss_ring_capacity(h, &cap), BISS_OK);
    ck_assert_uint_eq(cap, BISS_RING_SLOTS(c.nslaves) - 1);
    ck_assert_uint_eq(cap, 59); /* one slave: 48-byte slots from 0x480 to 0xFE0 */
    return h;
}

static biss_t *open_logged(struct model_log *m) {
    return open_logged_as(m, BISS_TRIGGER_FREERUN);
}

/* One frame read against the model's record of its publication. */
static void check_frame(const struct model_log *m, const struct biss_sample *s) {
    ck_assert_uint_eq(m->seq[s->seq % KEEP], s->seq);
    ck_assert_uint_eq(s->frame, s->seq);
    if (s->training) {
        return; /* the first frame after the configuration: two clocks, no data */
    }
    ck_assert_msg(s->valid, "frame %u not valid (flags 0x%x)", s->seq, s->flags);
    ck_assert(m->recorded[s->seq % KEEP]);
    ck_assert_msg(s->slave[0].position == m->position[s->seq % KEEP],
                  "frame %u: position %llu read, the model sent %llu", s->seq,
                  (unsigned long long)s->slave[0].position,
                  (unsigned long long)m->position[s->seq % KEEP]);
}

/* A host polling every ms of PRU time: every frame of 10^6, in order, each
 * the model's; none lost. At 10 MHz a frame takes 22.6 us: 44 a poll,
 * the ring keeps 59. */
START_TEST(test_every_frame_of_a_million) {
    static struct model_log m;
    biss_t *h = open_logged(&m);
    static struct biss_sample buf[256];
    uint32_t next = 0; /* the seq expected next, 0 before the first */
    uint64_t frames = 0, lost_total = 0;
    unsigned most = 0;
    struct timespec t0, t1;
    clock_gettime(CLOCK_MONOTONIC, &t0);
    while (frames < 1000000) {
        ck_assert_int_eq(biss_run_ms(h, 1), BISS_OK);
        unsigned n;
        uint32_t lost;
        ck_assert_int_eq(biss_ring_read(h, buf, 256, &n, &lost), BISS_OK);
        lost_total += lost;
        ck_assert_uint_lt(n, 256);
        most = n > most ? n : most;
        for (unsigned i = 0; i < n; i++) {
            if (next) {
                ck_assert_uint_eq(buf[i].seq, next);
            }
            check_frame(&m, &buf[i]);
            next = buf[i].seq + 1;
        }
        frames += n;
        /* caught up: the newest read is the newest published */
        ck_assert_uint_eq(next - 1, m.published);
    }
    clock_gettime(CLOCK_MONOTONIC, &t1);
    ck_assert_uint_eq(lost_total, 0);
    ck_assert_uint_le(most, 45);
    ck_assert_uint_ge(most, 44);
    printf("ring: %llu frames, 0 lost, at most %u a poll, in %.1f s\n", (unsigned long long)frames,
           most, (double)(t1.tv_sec - t0.tv_sec) + (t1.tv_nsec - t0.tv_nsec) / 1e9);
    biss_close(h);
}
END_TEST

/* A host polling every 2 ms (some 88 frames, the ring keeps 59): each read
 * returns the newest 59 exactly, in order and each the model's, and counts
 * every frame before them since the last read as lost. */
START_TEST(test_overrun_counted_exactly) {
    static struct model_log m;
    biss_t *h = open_logged(&m);
    static struct biss_sample buf[256];
    uint32_t cursor = m.published; /* the configuration's: the record starts after it */
    uint64_t lost_total = 0;
    for (int poll = 0; poll < 50; poll++) {
        ck_assert_int_eq(biss_run_ms(h, 2), BISS_OK);
        unsigned n;
        uint32_t lost;
        ck_assert_int_eq(biss_ring_read(h, buf, 256, &n, &lost), BISS_OK);
        uint32_t pending = m.published - cursor;
        ck_assert_uint_gt(pending, 59);
        ck_assert_uint_eq(n, 59);
        ck_assert_uint_eq(lost, pending - 59);
        for (unsigned i = 0; i < n; i++) {
            ck_assert_uint_eq(buf[i].seq, m.published - 58 + i);
            check_frame(&m, &buf[i]);
        }
        lost_total += lost;
        cursor = m.published;
    }
    ck_assert_uint_gt(lost_total, 50 * 25);
    /* polled in time again: nothing lost from here on */
    ck_assert_int_eq(biss_run_ms(h, 1), BISS_OK);
    unsigned n;
    uint32_t lost;
    ck_assert_int_eq(biss_ring_read(h, buf, 256, &n, &lost), BISS_OK);
    ck_assert_uint_eq(lost, 0);
    ck_assert_uint_eq(n, m.published - cursor);
    biss_close(h);
}
END_TEST

/* A reader that takes fewer than are waiting gets the rest next time, none
 * lost while the ring still holds them; a reconfiguration counts the old
 * layout's unread frames as lost and starts at the new one's. */
START_TEST(test_partial_reads_and_reconfiguration) {
    static struct model_log m;
    biss_t *h = open_logged(&m);
    struct biss_sample buf[64];
    ck_assert_int_eq(biss_run_ms(h, 1), BISS_OK);
    unsigned n, got = 0;
    uint32_t lost;
    for (;;) {
        ck_assert_int_eq(biss_ring_read(h, buf, 5, &n, &lost), BISS_OK);
        ck_assert_uint_eq(lost, 0);
        for (unsigned i = 0; i < n; i++) {
            ck_assert_uint_eq(buf[i].seq, got + 1 + i); /* from the first publication */
            check_frame(&m, &buf[i]);
        }
        got += n;
        if (n < 5) {
            break;
        }
    }
    ck_assert_uint_eq(got, m.published);
    ck_assert_int_eq(biss_run_ms(h, 1), BISS_OK);
    struct biss_config c;
    ck_assert_int_eq(biss_get_config(h, &c), BISS_OK);
    c.freq_hz = 5000000;
    ck_assert_int_eq(biss_configure(h, &c), BISS_OK);
    uint32_t at_cfg = m.published; /* what the configuration saw published */
    ck_assert_int_eq(biss_run_ms(h, 1), BISS_OK);
    ck_assert_int_eq(biss_ring_read(h, buf, 64, &n, &lost), BISS_OK);
    ck_assert_uint_eq(lost, at_cfg - got); /* the old layout's, unread */
    ck_assert_uint_gt(n, 1);
    ck_assert_uint_eq(n, m.published - at_cfg);
    ck_assert_uint_eq(buf[0].seq, at_cfg + 1);
    ck_assert(buf[0].training); /* the new rate's first frame */
    ck_assert_uint_eq(buf[1].delay.half, 20);
    for (unsigned i = 1; i < n; i++) {
        ck_assert_uint_eq(buf[i].seq, at_cfg + 1 + i);
        check_frame(&m, &buf[i]);
    }
    biss_close(h);
}
END_TEST

/* One host-triggered frame, published. */
static void one_frame(biss_t *h, const struct model_log *m) {
    uint32_t before = m->published;
    ck_assert_int_eq(biss_trigger(h), BISS_OK);
    ck_assert_int_eq(biss_run_us(h, 30), BISS_OK); /* 22.6 us a frame */
    ck_assert_uint_eq(m->published, before + 1);
}

/* A reader lagging exactly capacity - 1, capacity and capacity + 1 frames
 * (58, 59, 60 of one slave; host trigger: the frames run when asked), with
 * its first unread frame in each of the ring's 60 slots in turn, so that
 * the ring's wrap falls at every place in the span read, and at none: it
 * gets the newest min(lag, 59), in order, each the model's, and exactly
 * the rest counted lost. Between two lags one or two frames more, read at
 * once, move the first unread slot on (lag + 1 or + 2 frames: coprime to
 * 60, so 60 turns visit every slot). A configuration starts the ring
 * afresh at its first slot (biss_shm.h), with the training frame: frame s
 * lies in slot (s - training) modulo 60. */
START_TEST(test_lag_around_the_capacity) {
    static struct model_log m;
    biss_t *h = open_logged_as(&m, BISS_TRIGGER_HOST);
    static struct biss_sample buf[256];
    unsigned n;
    uint32_t lost;
    ck_assert_int_eq(biss_run_ms(h, 1), BISS_OK);
    ck_assert_int_eq(biss_ring_read(h, buf, 256, &n, &lost), BISS_OK);
    ck_assert_uint_eq(n, 1);
    ck_assert(buf[0].training);
    const uint32_t training = buf[0].seq;
    static const unsigned lag[] = {58, 59, 60};
    for (unsigned k = 0; k < 3; k++) {
        uint64_t first_slots = 0;
        for (unsigned turn = 0; turn < 60; turn++) {
            first_slots |= 1ull << (m.published + 1 - training) % 60;
            for (unsigned i = 0; i < lag[k]; i++) {
                one_frame(h, &m);
            }
            ck_assert_int_eq(biss_ring_read(h, buf, 256, &n, &lost), BISS_OK);
            unsigned want = lag[k] < 59 ? lag[k] : 59;
            ck_assert_msg(n == want && lost == lag[k] - want, "%u behind from slot %u: %u, %u lost",
                          lag[k], __builtin_ctzll(first_slots), n, lost);
            for (unsigned i = 0; i < n; i++) {
                ck_assert_uint_eq(buf[i].seq, m.published - (n - 1) + i);
                check_frame(&m, &buf[i]);
            }
            unsigned more = (lag[k] + 1) % 60 ? 1 : 2;
            for (unsigned i = 0; i < more; i++) {
                one_frame(h, &m);
            }
            ck_assert_int_eq(biss_ring_read(h, buf, 256, &n, &lost), BISS_OK);
            ck_assert_uint_eq(n, more);
            ck_assert_uint_eq(lost, 0);
        }
        ck_assert_msg(first_slots == (1ull << 60) - 1, "%u behind: slots 0x%llx", lag[k],
                      (unsigned long long)first_slots);
    }
    biss_close(h);
}
END_TEST

/* This handle restarting the firmware (biss_stop, biss_start): the old
 * run's frames the reader had not taken are counted lost, and it reads
 * the new run from its first publication on (the training frame), each
 * the model's; none lost after. */
START_TEST(test_restart_reads_the_new_run) {
    static struct model_log m;
    biss_t *h = open_logged(&m);
    static struct biss_sample buf[256];
    unsigned n;
    uint32_t lost;
    ck_assert_int_eq(biss_run_ms(h, 1), BISS_OK);
    ck_assert_int_eq(biss_ring_read(h, buf, 256, &n, &lost), BISS_OK);
    uint32_t read = buf[n - 1].seq;
    ck_assert_int_eq(biss_run_us(h, 500), BISS_OK); /* 22 frames, unread */
    ck_assert_int_eq(biss_stop(h), BISS_OK);
    uint32_t unread = m.published - read;
    ck_assert_uint_ge(unread, 20);
    m.published = 0; /* the new run counts from 1 */
    ck_assert_int_eq(biss_start(h), BISS_OK);
    ck_assert_int_eq(biss_run_ms(h, 1), BISS_OK);
    ck_assert_int_eq(biss_ring_read(h, buf, 256, &n, &lost), BISS_OK);
    ck_assert_uint_eq(lost, unread);
    ck_assert_uint_eq(n, m.published);
    ck_assert(buf[0].training);
    for (unsigned i = 0; i < n; i++) {
        ck_assert_uint_eq(buf[i].seq, 1 + i);
        check_frame(&m, &buf[i]);
    }
    read = buf[n - 1].seq;
    ck_assert_int_eq(biss_run_ms(h, 1), BISS_OK);
    ck_assert_int_eq(biss_ring_read(h, buf, 256, &n, &lost), BISS_OK);
    ck_assert_uint_eq(lost, 0);
    ck_assert_uint_gt(n, 40);
    ck_assert_uint_eq(buf[0].seq, read + 1);
    biss_close(h);
}
END_TEST

int main(void) {
    Suite *s = suite_create("host_ring");
    TCase *tc = tcase_create("ring");
    tcase_set_timeout(tc, 600);
    tcase_add_test(tc, test_every_frame_of_a_million);
    tcase_add_test(tc, test_overrun_counted_exactly);
    tcase_add_test(tc, test_partial_reads_and_reconfiguration);
    tcase_add_test(tc, test_lag_around_the_capacity);
    tcase_add_test(tc, test_restart_reads_the_new_run);
    suite_add_tcase(s, tc);
    return check_run(s);
}
