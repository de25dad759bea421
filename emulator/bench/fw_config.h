/*
 * fw_config.h - configures the BiSS-C master firmware running on the
 * bench for the bench's own slave chain, through the shared-memory block
 * of include/biss/biss_shm.h, as a host would.
 */
#ifndef FW_CONFIG_H
#define FW_CONFIG_H

#include "bench.h"

struct fw_settings {
    unsigned half;       /* MA half period in PRU cycles (f = 100 MHz / half) */
    unsigned trigger;    /* BISS_TRIG_* */
    uint32_t iep_period; /* IEP counts, for BISS_TRIG_IEP */
    unsigned proc_limit; /* longest processing time accepted, MA clocks */
};

/* Writes the configuration for the bench's BiSS chain or SSI encoder (its
 * round trip from the model) and increments CFG_SEQ. Returns 0. */
int fw_config_write(struct bench *b, const struct fw_settings *s);

/* Why the firmware refuses the MA half period `half` (BISS_CFGERR_HALF:
 * out of BISS_MIN_HALF..BISS_MAX_HALF, or no exact 8x shift clock), or
 * NULL when it takes it. */
const char *fw_config_half_problem(unsigned half);

/* "BISS_CFGERR_HALF: ..." for a configuration-error code the firmware
 * reports in BISS_ST_CFG_ERROR (include/biss/biss_shm.h). */
const char *fw_config_error_text(uint32_t code);

#endif
