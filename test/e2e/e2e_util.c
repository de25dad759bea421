/* e2e_util.c - see e2e_util.h. */
#include "e2e_util.h"

#include "biss/biss_shm.h"
#include "read_file.h"

#include <check.h>
#include <stdlib.h>
#include <string.h>

#if !defined(FIRMWARE_IMAGE) || !defined(FIRMWARE_IMAGE_PRU1)
#error "FIRMWARE_IMAGE and FIRMWARE_IMAGE_PRU1 must name the built firmware images"
#endif

const char *e2e_firmware_image(unsigned pru) {
    return pru ? FIRMWARE_IMAGE_PRU1 : FIRMWARE_IMAGE;
}

/* The built firmware of the bench's PRU into its IRAM, and the PRU started. */
void e2e_start_firmware(struct e2e_run *r) {
    char *image;
    size_t n;
    const char *path = e2e_firmware_image(bench_config(r->b)->pru_index);
    ck_assert_msg(read_file(path, 1u << 16, &image, &n) == READ_FILE_OK, "cannot read %s", path);
    ck_assert_uint_gt(n, 0);
    r->image_words = (uint32_t)(n / 4);
    ck_assert_int_eq(bench_fw_start(r->b, image, n), 0);
    free(image);
}

struct bench *e2e_bench(struct e2e_run *r, const char *profile, double cable_m,
                        const struct pru_params *params) {
    scenario sc;
    ck_assert_int_eq(profile_by_name(profile, &sc), 0);
    scenario_set_cable(&sc, cable_m);
    return e2e_bench_scenario(r, &sc, params);
}

/* E2E_STRICT (a rule list, as pru-run --strict) and E2E_CONTEND (K,S[,...],
 * as pru-run --contend) put every run of a suite under the emulator's
 * strict mode (stop on the first violation) or data-RAM contention, unless
 * the test chose its own (issue 10 item 10: the whole end-to-end suite runs
 * in both). The strict window is fixed when the core is made, before a test
 * picks its rate: E2E_STRICT_WINDOW, default 10 cycles, so the clocked code
 * of every run at 10 MHz (most of the suite) is judged; test_e2e_strict
 * covers the other rates with the window set to each. */
static void env_params(struct pru_params *p) {
    const char *rules = getenv("E2E_STRICT");
    if (rules && *rules && !p->strict) {
        const char *bad = NULL;
        ck_assert_msg(pru_strict_parse(rules, &p->strict, &bad) == 0,
                      "E2E_STRICT: unknown rule at \"%s\"", bad ? bad : "");
        const char *w = getenv("E2E_STRICT_WINDOW");
        p->strict_window = w && *w ? (unsigned)strtoul(w, NULL, 0) : 10;
        ck_assert_msg(p->strict_window > 0, "E2E_STRICT_WINDOW: a positive number of cycles");
    }
    const char *contend = getenv("E2E_CONTEND");
    if (contend && *contend && !p->contend_period) {
        char err[160];
        ck_assert_msg(pru_contend_parse(contend, p, err, sizeof err) == 0, "E2E_CONTEND: %s", err);
    }
}

struct bench *e2e_bench_scenario(struct e2e_run *r, const scenario *sc,
                                 const struct pru_params *params) {
    struct bench_config cfg;
    bench_config_default(&cfg);
    if (params) {
        cfg.pru = *params;
    }
    env_params(&cfg.pru);
    cfg.link = *sc;
    char err[256];
    r->b = bench_new(&cfg, err, sizeof(err));
    ck_assert_msg(r->b != NULL, "%s", err);
    e2e_start_firmware(r);
    fw_check_attach(&r->fc, r->b);
    return r->b;
}

uint32_t e2e_cfg_seq(struct bench *b) {
    struct biss_proto_io io = bench_fw_io(b);
    struct biss_shm_config blk;
    ck_assert_int_eq(biss_proto_config_get(&io, &blk), 0);
    return blk.seq;
}

void e2e_run_publications(struct e2e_run *r, uint64_t n, int64_t max_ps) {
    uint64_t want = r->fc.publications + n;
    int64_t end = pru_time_ps(bench_core(r->b)) + max_ps;
    while (r->fc.publications < want && pru_time_ps(bench_core(r->b)) < end) {
        ck_assert_int_eq(bench_run_until(r->b, pru_time_ps(bench_core(r->b)) + 20 * SIM_PS_PER_US),
                         PRU_STOP_LIMIT);
    }
}

void e2e_configure(struct e2e_run *r, unsigned half) {
    ck_assert_int_eq(fw_check_configure(&r->fc, half), 0);
    uint32_t seq = e2e_cfg_seq(r->b);
    int64_t end = pru_time_ps(bench_core(r->b)) + 10 * SIM_PS_PER_MS;
    while (bench_fw_status(r->b).cfg_ack != seq && pru_time_ps(bench_core(r->b)) < end) {
        ck_assert_int_eq(bench_run_until(r->b, pru_time_ps(bench_core(r->b)) + 5 * SIM_PS_PER_US),
                         PRU_STOP_LIMIT);
    }
    ck_assert_uint_eq(bench_fw_status(r->b).cfg_ack, seq);
}

uint64_t e2e_run_frames(struct e2e_run *r, unsigned half, unsigned proc_limit, uint64_t frames) {
    r->fc.cfg.trigger = BISS_TRIGGER_FREERUN;
    r->fc.cfg.iep_period_ns = 0;
    r->fc.cfg.proc_limit = proc_limit;
    ck_assert_int_eq(fw_check_configure(&r->fc, half), 0);
    /* start-up: training, then the first valid frame */
    int64_t end = pru_time_ps(bench_core(r->b)) + 20 * SIM_PS_PER_MS;
    while (r->fc.frames == 0 && pru_time_ps(bench_core(r->b)) < end) {
        ck_assert_int_eq(bench_run_until(r->b, pru_time_ps(bench_core(r->b)) + 50 * SIM_PS_PER_US),
                         PRU_STOP_LIMIT);
    }
    ck_assert_msg(r->fc.frames > 0, "no valid frame within 20 ms (state %u, error %u)",
                  bench_fw_status(r->b).state, bench_fw_status(r->b).cfg_error);
    fw_check_restart(&r->fc, frames);
    bench_reset_stats(r->b);
    bench_set_frame_limit(r->b, bench_current_frame(r->b) + frames + 1);
    /* every frame well under a millisecond at the slowest rate tested */
    end = pru_time_ps(bench_core(r->b)) + (int64_t)frames * SIM_PS_PER_MS;
    while (r->fc.frames < frames && pru_time_ps(bench_core(r->b)) < end) {
        ck_assert_int_eq(bench_run_until(r->b, pru_time_ps(bench_core(r->b)) + SIM_PS_PER_MS),
                         PRU_STOP_LIMIT);
    }
    return r->fc.frames;
}

uint64_t e2e_frames(uint64_t def) {
    const char *e = getenv("E2E_FRAMES");
    return e ? strtoull(e, NULL, 10) : def;
}

void e2e_free(struct e2e_run *r) {
    bench_free(r->b);
    r->b = NULL;
}
