/* fake_backend.c - see fake_backend.h. */
#include "fake_backend.h"

#include "biss/biss_shm.h"

#include <check.h>
#include <stdlib.h>
#include <string.h>

uint32_t fake_dram32(const struct fake *f, uint32_t off) {
    uint32_t v;
    memcpy(&v, f->mem + ICSS_DRAM0 + off, 4);
    return v;
}

void fake_set_dram32(struct fake *f, uint32_t off, uint32_t v) {
    memcpy(f->mem + ICSS_DRAM0 + off, &v, 4);
}

/* Every word names its frame as far as the firmware's values allow (the
 * flags, slave count and half period are fixed; a line delay, sample
 * point, lag, CDM and status take some of its bits), so a torn read shows
 * as words of two frames; and every word is one the firmware can write. */
uint32_t fake_result_word(uint32_t k, unsigned i) {
    switch (i * 4) {
    case BISS_R_FLAGS:
        return BISS_RF_VALID;
    case BISS_R_PROC_CLOCKS:
        return (uint32_t)BISS_MAX_SLAVES << 24 | (k & 0xffffu);
    case BISS_R_DELAY_RAW:
        return (8u + (k >> 12) % 4096u) << 16 | (8u + k % 4096u);
    case BISS_R_SAMPLE_POINT:
        return 10u << 16 | (k >> 3 & 0xffu) << 8 | (k & 7u); /* H = 10, lag, point */
    case BISS_R_CDM:
        return k & 1u;
    }
    if (i * 4 >= BISS_R_SLAVE0 && (i * 4 - BISS_R_SLAVE0) % BISS_R_SLAVE_SIZE == BISS_R_S_STATUS) {
        return k & (BISS_RS_CRC_OK | BISS_RS_NE | BISS_RS_NW);
    }
    return k;
}

/* One store of the firmware: a result word, ST_BUF, or ST_SEQ. Frame k
 * fills the ring's slot (k - 1) % FAKE_SLOTS only after k - 1 published
 * the one before it (biss_shm.h). */
static void firmware_step(struct fake *f) {
    if (!f->publishing) {
        return;
    }
    uint32_t slot = BISS_RING0 + (f->frame - 1) % FAKE_SLOTS * BISS_RING_STRIDE(BISS_MAX_SLAVES);
    if (f->word < FAKE_RESULT_WORDS) {
        fake_set_dram32(f, slot + f->word * 4, fake_result_word(f->frame, f->word));
        f->word++;
    } else if (f->word == FAKE_RESULT_WORDS) {
        fake_set_dram32(f, BISS_ST_BUF, slot);
        f->word++;
    } else {
        fake_set_dram32(f, BISS_ST_SEQ, f->frame);
        f->frame++;
        f->word = 0;
    }
}

void fake_steps(struct fake *f, unsigned k) {
    for (unsigned i = 0; i < k; i++) {
        firmware_step(f);
    }
}

static void interleave(struct fake *f) {
    f->accesses++;
    if (f->max_steps == 0) {
        return;
    }
    f->rng = f->rng * 1103515245u + 12345u;
    unsigned n = f->fixed_steps ? f->max_steps : (f->rng >> 16) % (f->max_steps + 1);
    for (unsigned i = 0; i < n; i++) {
        firmware_step(f);
    }
}

static int fake_read(void *ctx, uint32_t off, void *buf, size_t n) {
    struct fake *f = ctx;
    ck_assert_uint_le(off + n, ICSS_WINDOW);
    interleave(f);
    if (f->before_read) {
        f->before_read(f, off - ICSS_DRAM0, n);
    }
    memcpy(buf, f->mem + off, n);
    return BISS_OK;
}

static int fake_write(void *ctx, uint32_t off, const void *buf, size_t n) {
    struct fake *f = ctx;
    ck_assert_uint_le(off + n, ICSS_WINDOW);
    interleave(f);
    memcpy(f->mem + off, buf, n);
    return BISS_OK;
}

static int fake_advance(void *ctx, unsigned us) {
    struct fake *f = ctx;
    f->now_us += us;
    if (f->acks && fake_dram32(f, BISS_CFG_SEQ) != fake_dram32(f, BISS_ST_CFG_ACK)) {
        fake_set_dram32(f, BISS_ST_CFG_ERROR, f->cfg_error);
        fake_set_dram32(f, BISS_ST_CFG_ACK, fake_dram32(f, BISS_CFG_SEQ));
    }
    if (f->cd_answers && fake_dram32(f, BISS_CD_CMD) != fake_dram32(f, BISS_ST_CD_SEQ)) {
        fake_set_dram32(f, BISS_ST_CD_STATUS, f->cd_status);
        fake_set_dram32(f, BISS_ST_CD_SEQ, fake_dram32(f, BISS_CD_CMD));
    }
    for (unsigned i = 0; i < us * f->steps_per_us; i++) {
        firmware_step(f);
    }
    return BISS_OK;
}

static uint64_t fake_now_us(void *ctx) {
    return ((struct fake *)ctx)->now_us;
}

static void fake_close(void *ctx) {
    struct fake *f = ctx;
    free(f->mem);
    free(f);
}

static const struct biss_backend_ops fake_ops = {
    .read = fake_read,
    .write = fake_write,
    .advance = fake_advance,
    .now_us = fake_now_us,
    .close = fake_close,
    .poll_us = 1,
    .advance_sleeps = 0,
};

biss_t *fake_handle(struct fake **out) {
    struct fake *f = calloc(1, sizeof *f);
    ck_assert_ptr_nonnull(f);
    f->mem = calloc(1, ICSS_WINDOW);
    ck_assert_ptr_nonnull(f->mem);
    f->frame = 1;
    f->rng = 1;
    fake_set_dram32(f, BISS_ST_CFG_ACK, 0xffffffffu);
    struct biss_backend be = {.ops = &fake_ops, .ctx = f, .iram_bytes = 8192};
    biss_t *h;
    ck_assert_int_eq(biss_handle_new(BISS_TARGET_EMU, &be, 10, &h), BISS_OK);
    *out = f;
    return h;
}
