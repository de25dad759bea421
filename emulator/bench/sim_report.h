/*
 * sim_report.h - what biss-sim prints: one JSON object (--json) or a short
 * text summary, and the SVG scope view of one frame.
 */
#ifndef SIM_REPORT_H
#define SIM_REPORT_H

#include "bench.h"
#include "fw_cd.h"
#include "fw_check.h"

#include <cjson/cJSON.h>

struct sim_result {
    struct bench *b;
    const struct fw_check *fw; /* NULL: the image is not the BiSS master firmware */
    enum pru_stop why;
    double freq_hz; /* the MA rate as asked for (--freq) */
    unsigned half;  /* ... and its half period, PRU cycles (proto's rate rule) */
    double host_seconds;
    const struct fw_cd *cd; /* a control frame that ran, or NULL */
    unsigned trigger;       /* BISS_TRIG_*: free-run frames have a restart to measure */
};

void sim_print_json(const struct sim_result *r);
/* The object sim_print_json prints (the caller owns it), and printing one
 * (which frees it). */
cJSON *sim_json(const struct sim_result *r);
void sim_print_json_object(cJSON *j);
void sim_print_text(const struct sim_result *r);
/* A run of biss-sim --sl-replay (the firmware's): whether it was the run
 * on the tape, what the PRU did, and the host's time; JSON or text. */
void sim_print_replay(const struct sim_result *r, const char *tape, bool same, bool json);

/* The SVG of the captured frame, numbered k as biss-sim and bissctl count
 * frames (1 = the first frame, the training frame of a BiSS-C run): the
 * pins, the bit names, and with the firmware what it published for the
 * frame: its sample points, its measured line delay and the values it
 * read. Returns 0 or -1 (message in err). */
int sim_write_svg(const struct sim_result *r, const char *path, uint64_t k, char *err,
                  size_t errlen);

/* What a refusal of biss_safety_config_check means (rc nonzero). */
const char *sim_safety_problem(int rc);

/* The firmware's line delay in ns from its averaged ACK position
 * (proto's biss_delay_decode of the published DELAY_AVG). */
double sim_fw_line_delay_ns(const struct fw_check *fw);

/* The shortest frame period the encoders and the line allow for what the
 * firmware configured: its clocks (with the busy ones seen), the slave's
 * timeout and the round trip, in ps. */
double sim_frame_minimum_ps(struct bench *b, const struct fw_check *fw);

#endif
