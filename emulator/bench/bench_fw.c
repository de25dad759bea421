/* bench_fw.c - the bench as the firmware's host (bench_fw.h). */
#include "bench_fw.h"

#include <string.h>

static int io_read(void *ctx, uint32_t off, void *buf, size_t n) {
    struct bench *b = ctx;
    uint32_t at = pru_soc_base(bench_config(b)->soc) + ICSS_DRAM(bench_config(b)->pru_index) + off;
    return pru_host_read(bench_core(b), at, buf, n) ? BISS_E_IO : BISS_OK;
}

static int io_write(void *ctx, uint32_t off, const void *buf, size_t n) {
    struct bench *b = ctx;
    uint32_t at = pru_soc_base(bench_config(b)->soc) + ICSS_DRAM(bench_config(b)->pru_index) + off;
    return pru_host_write(bench_core(b), at, buf, n) ? BISS_E_IO : BISS_OK;
}

struct biss_proto_io bench_fw_io(struct bench *b) {
    return (struct biss_proto_io){.read = io_read, .write = io_write, .ctx = b};
}

int bench_fw_start(struct bench *b, const void *image, size_t bytes) {
    struct pru_core *c = bench_core(b);
    if (pru_load_image(c, image, bytes) != 0) {
        return -1;
    }
    pru_start(c);
    return 0;
}

struct biss_proto_word bench_fw_word(const biss_slave_cfg *s) {
    return (struct biss_proto_word){.pos_bits = s->pos_bits,
                                    .fill_bits = s->fill_bits,
                                    .lc_bits = s->lc_bits,
                                    .has_err = s->has_err,
                                    .has_warn = s->has_warn};
}

struct biss_proto_word bench_fw_slave_word(const slave_word *w) {
    return (struct biss_proto_word){.pos_bits = w->pos_bits,
                                    .fill_bits = w->fill_bits,
                                    .lc_bits = w->lc_bits,
                                    .has_err = w->has_err,
                                    .has_warn = w->has_warn};
}

void bench_fw_layout(const struct bench *b, struct biss_config *c) {
    const scenario *sc = &bench_link((struct bench *)b)->sc;
    slave_word w[SLAVE_MAX_WORDS];
    c->nslaves = sc->model->words(scenario_model_cfg(sc), w);
    for (unsigned i = 0; i < c->nslaves && i < BISS_API_MAX_SLAVES; i++) {
        if (w[i].ssi) {
            /* its line delay from the model: an SSI slave gives no ACK to measure it by */
            c->slave[i] = (struct biss_slave_config){
                .data_bits = w[i].pos_bits, .ssi = true, .gray = w[i].gray};
            c->ssi_delay_ns = bench_ssi_delay_ns(b);
            continue;
        }
        struct biss_proto_word pw = bench_fw_slave_word(&w[i]);
        biss_proto_slave_layout(&pw, w[i].crc_poly, w[i].crc_start, &c->slave[i]);
        /* the scenario's safety checks (the host's, not the models') */
        c->slave[i].life_check = sc->checks.life[i];
        c->slave[i].life_bits = sc->checks.life[i] ? w[i].lc_bits : 0;
        c->slave[i].ew_static = sc->checks.ew_static[i];
        c->slave[i].max_speed = sc->checks.max_speed[i];
    }
    c->npairs = sc->checks.npairs;
    for (unsigned k = 0; k < sc->checks.npairs && k < BISS_API_MAX_PAIRS; k++) {
        c->pair[k] = (struct biss_pair_check){.a = sc->checks.pair[k].a,
                                              .b = sc->checks.pair[k].b,
                                              .shift_a = sc->checks.pair[k].shift_a,
                                              .shift_b = sc->checks.pair[k].shift_b,
                                              .tolerance = sc->checks.pair[k].tolerance,
                                              .distinct_crc = sc->checks.pair[k].distinct_crc};
    }
}

void bench_fw_config(const struct bench *b, struct biss_config *c) {
    biss_config_default(c);
    bench_fw_layout(b, c);
}

void bench_fw_block(const struct biss_config *c, unsigned half, struct biss_shm_config *blk) {
    if (half) {
        biss_config_encode_half(c, half, blk);
    } else {
        biss_config_encode(c, blk);
    }
}

int bench_fw_put_block(struct bench *b, const struct biss_shm_config *blk) {
    struct biss_proto_io io = bench_fw_io(b);
    struct biss_shm_config cur;
    int rc = biss_proto_config_get(&io, &cur);
    return rc ? rc : biss_proto_config_put(&io, blk, cur.seq + 1);
}

int bench_fw_configure(struct bench *b, const struct biss_config *c, unsigned half) {
    struct biss_shm_config blk;
    bench_fw_block(c, half, &blk);
    /* the frame marks follow the rate the firmware will clock */
    bench_set_ma_half(b, biss_proto_half_check(blk.half) == BISS_OK ? blk.half : 0);
    return bench_fw_put_block(b, &blk);
}

struct biss_shm_status bench_fw_status(struct bench *b) {
    struct biss_proto_io io = bench_fw_io(b);
    struct biss_shm_status st;
    if (biss_proto_status_get(&io, &st)) {
        memset(&st, 0, sizeof st);
    }
    return st;
}
