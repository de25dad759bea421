/* e2e_util.h - the BiSS-C master firmware in the emulator against the
 * encoder models, for the end-to-end suites. */
#ifndef E2E_UTIL_H
#define E2E_UTIL_H

#include "bench.h"
#include "fw_check.h"
#include "bench_fw.h"

#include <stdint.h>

struct e2e_run {
    struct bench *b;
    struct fw_check fc;
    uint32_t image_words;
};

/* Bench for the profile and cable, with the pru params given (NULL:
 * defaults), the firmware loaded and started; not yet configured. */
struct bench *e2e_bench(struct e2e_run *r, const char *profile, double cable_m,
                        const struct pru_params *params);

/* The same for any scenario (a profile changed by the test). */
struct bench *e2e_bench_scenario(struct e2e_run *r, const scenario *sc,
                                 const struct pru_params *params);

/* The built image for PRU pru (0: biss_master.bin, 1: biss_master_pru1.bin). */
const char *e2e_firmware_image(unsigned pru);
/* Loads the built firmware of r->b's PRU into its IRAM and starts it. */
void e2e_start_firmware(struct e2e_run *r);

/* Configures free-run at half period `half`, waits for the training and the
 * first valid frame, then checks `frames` frames. Returns the number of
 * valid frames checked (fewer if time ran out). */
uint64_t e2e_run_frames(struct e2e_run *r, unsigned half, unsigned proc_limit, uint64_t frames);

/* Writes r->fc.cfg (the chain's layout; the caller sets its trigger, IEP
 * period and limit) at half period `half` (fw_check_configure: 0 for
 * cfg.freq_hz's) and runs until the firmware has taken it (its
 * ST_CFG_ACK), at most 10 ms of simulated time. */
void e2e_configure(struct e2e_run *r, unsigned half);

/* Simulated time until the firmware publishes `n` more frames of any kind,
 * at most max_ps. */
void e2e_run_publications(struct e2e_run *r, uint64_t n, int64_t max_ps);

/* CFG_SEQ as the firmware's data RAM holds it. */
uint32_t e2e_cfg_seq(struct bench *b);

/* Frames per cell: E2E_FRAMES from the environment, else def. */
uint64_t e2e_frames(uint64_t def);

void e2e_free(struct e2e_run *r);

#endif
