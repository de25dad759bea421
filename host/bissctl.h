/* bissctl.h - the bissctl command line: options, and the subcommands that
 * run on an open handle. */
#ifndef BISSCTL_H
#define BISSCTL_H

#include "libbiss.h"

#include "biss_proto.h" /* the safety checks' command-line spellings */

#include <stdbool.h>

struct bissctl_opts {
    struct biss_open_params open;
    struct biss_config cfg;
    bool slaves_given;      /* --slave: layout from the command line, not the profile */
    bool config_given;      /* any configuration option */
    bool no_configure;      /* --no-configure: use what the firmware runs */
    bool dump;              /* reg-read --dump: a hex dump */
    bool ida_test;          /* command --ida-test: withhold the command unless IDA = IDS */
    bool json;              /* read --json: one JSON object */
    bool force;             /* command --force: send a command that changes how an encoder works */
    unsigned time_limit_ms; /* probe --time-limit (0: the library's default) */
    const char *command;
    unsigned count;      /* read -n */
    unsigned run_ms;     /* run --ms */
    unsigned timeout_ms; /* per sample */
    unsigned id;         /* reg-read/reg-write: control-frame ID */
    char **args;         /* words after the command */
    int nargs;
    bool help;
    bool attach_given;         /* --attach on the command line */
    struct biss_config checks; /* --check-life, --check-pair: only their fields, added to
                                  the layout (command line or profile) when it is known */
    char errbuf[1024];         /* open's detail */
};

/* Exit codes */
#define BISSCTL_OK    0
#define BISSCTL_FAIL  1 /* the library reported an error */
#define BISSCTL_USAGE 2 /* bad command line */

/* Parses argv; on a usage error prints it to stderr and returns
 * BISSCTL_USAGE, else BISSCTL_OK. */
int bissctl_parse(int argc, char **argv, struct bissctl_opts *o);
void bissctl_usage(const char *command);
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
int bissctl_probe(biss_t *h, const struct bissctl_opts *o); /* bissctl_probe.c */

/* read --json (bissctl_json.c): one frame of the "frames" array (after the
 * opening, which the first prints), then the end with the safety counts. */
void bissctl_json_frame(const struct biss_sample *s, const struct biss_config *c, bool first);
void bissctl_json_end(biss_t *h);

/* "bissctl: <what>: <strerror>" on stderr; returns BISSCTL_FAIL. */
int bissctl_fail(const char *what, int err);
/* The command's own arguments, checked before anything is opened:
 * BISSCTL_OK or BISSCTL_USAGE (reported). */
int bissctl_check_args(const struct bissctl_opts *o);

#endif
