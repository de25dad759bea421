/* bissctl.h - the bissctl command line: options, and the subcommands that
 * run on an open handle. */
#ifndef BISSCTL_H
#define BISSCTL_H

#include "libbiss.h"

#include "biss_proto.h" /* the safety checks' command-line spellings, the rate rule */

#include <stdbool.h>

struct bissctl_opts {
    struct biss_open_params open;
    struct biss_config cfg;
    bool slaves_given;       /* --slave: layout from the command line, not the profile */
    bool slaves_from_file;   /* ... from --config's file (the command line's replace it) */
    bool config_given;       /* any configuration option on the command line */
    bool target_given;       /* --target (on the command line or in the file) */
    const char *config_file; /* --config FILE */
    bool no_configure;       /* --no-configure: use what the firmware runs */
    bool dump;               /* reg-read --dump: a hex dump */
    bool ida_test;           /* command --ida-test: withhold the command unless IDA = IDS */
    bool json;               /* read --json: one JSON object */
    bool force;              /* command --force: send a command that changes how an encoder works */
    unsigned time_limit_ms;  /* probe --time-limit (0: the library's default) */
    const char *command;
    unsigned count;      /* read -n */
    unsigned run_ms;     /* run --ms */
    unsigned record_ms;  /* record --seconds, in ms */
    unsigned poll_us;    /* record --poll-ms, in us */
    const char *format;  /* record --format: "csv", "npy", or NULL (by the extension) */
    unsigned timeout_ms; /* per sample */
    unsigned id;         /* reg-read/reg-write: control-frame ID */
    char **args;         /* words after the command */
    int nargs;
    bool help;
    bool attach_given;         /* --attach on the command line */
    bool pru_given;            /* --pru on the command line (or in the file) */
    uint32_t slave_timeout_ns; /* --slave-timeout-ns: the slaves' shortest timeout, 0 unknown */
    double round_trip_ns;      /* --round-trip-ns (rates): a measured round trip, < 0 none */
    uint32_t link_warn, link_window; /* --link-warn K[,N] (0: libbiss's defaults) */
    struct biss_config checks;       /* --check-life, --check-pair: only their fields, added to
                                        the layout (command line or profile) when it is known */
    char errbuf[2048];               /* open's detail */
};

/* Exit codes */
#define BISSCTL_OK    0
#define BISSCTL_FAIL  1 /* the library reported an error */
#define BISSCTL_USAGE 2 /* bad command line */

/* A usage error, the tools' one form (README "Conventions"): "bissctl:
 * MESSAGE" and "Try 'bissctl [COMMAND] --help' for more information." on
 * stderr; returns BISSCTL_USAGE. */
__attribute__((format(printf, 1, 2))) int bissctl_usage_error(const char *fmt, ...);
/* Parses argv; on a usage error prints it to stderr and returns
 * BISSCTL_USAGE, else BISSCTL_OK. */
int bissctl_parse(int argc, char **argv, struct bissctl_opts *o);
void bissctl_usage(const char *command);
/* One option of a --config file, key as the long option without the dashes;
 * at ("FILE:LINE") prefixes an error. BISSCTL_OK or BISSCTL_USAGE (reported). */
int bissctl_set_option(const char *key, const char *value, const char *at, struct bissctl_opts *o);
/* --config FILE (bissctl_conf.c): its options into o. BISSCTL_OK, or
 * BISSCTL_USAGE / BISSCTL_FAIL (reported, with FILE:LINE). */
int bissctl_conf_read(const char *path, struct bissctl_opts *o);
/* The target when --target is not given (bissctl_target.c): the SoC the
 * device tree under sysfs_root (NULL: /sys) names in its root compatible;
 * BISS_TARGET_EMU when it names none of ours or there is none. */
enum biss_target bissctl_default_target(const char *sysfs_root);
/* A number 0..max (decimal, 0x hex); 0 or -1. */
int bissctl_parse_byte(const char *s, unsigned max, uint8_t *v);

/* Subcommands: each returns an exit code and reports its own errors. */
int bissctl_info(biss_t *h, const struct bissctl_opts *o);
int bissctl_read(biss_t *h, const struct bissctl_opts *o);
int bissctl_stats(biss_t *h, const struct bissctl_opts *o);
int bissctl_run(biss_t *h, const struct bissctl_opts *o);
int bissctl_trigger(biss_t *h, const struct bissctl_opts *o);
int bissctl_start(biss_t *h, const struct bissctl_opts *o);
int bissctl_stop(biss_t *h, const struct bissctl_opts *o);
int bissctl_reg_read(biss_t *h, const struct bissctl_opts *o);
int bissctl_reg_write(biss_t *h, const struct bissctl_opts *o);
int bissctl_command(biss_t *h, const struct bissctl_opts *o);
int bissctl_probe(biss_t *h, const struct bissctl_opts *o);  /* bissctl_probe.c */
int bissctl_record(biss_t *h, const struct bissctl_opts *o); /* bissctl_record.c */
/* encoder start|status|stop (bissctl_encoder.c): opens its own handle. */
int bissctl_encoder(struct bissctl_opts *o);

/* read --json (bissctl_json.c): one frame of the "frames" array (after the
 * opening, which the first prints), then the end with the safety counts. */
void bissctl_json_frame(const struct biss_sample *s, const struct biss_config *c, bool first);
/* A frame's state in a word: valid, crc-error, training, no-slave, proc-error, ack-jump,
 * off-grid, misframed or invalid (read's lines and read --json's "state"). */
const char *bissctl_frame_state(const struct biss_sample *s);
void bissctl_json_end(biss_t *h);

/* The rate against the line (bissctl_line.c, proto's rules and words):
 * before configuring, what the command line says of it (a refusal is
 * BISSCTL_FAIL, reported; a warning is printed); each frame read noted;
 * after the frames, what they measured (a warning, or why no slave
 * answered, on stderr); the rates command, which needs no target. */
int bissctl_line_before(const struct bissctl_opts *o);
void bissctl_line_note(const struct biss_sample *s);
void bissctl_line_report(biss_t *h, const struct bissctl_opts *o);
int bissctl_rates(const struct bissctl_opts *o);
/* The first line of every output on the emulator target (bissctl_cmds.c). */
extern const char bissctl_emulated_note[];

/* "bissctl: <what>: <strerror>" on stderr; returns BISSCTL_FAIL. */
int bissctl_fail(const char *what, int err);
/* The command's own arguments, checked before anything is opened:
 * BISSCTL_OK or BISSCTL_USAGE (reported). */
int bissctl_check_args(const struct bissctl_opts *o);

#endif
