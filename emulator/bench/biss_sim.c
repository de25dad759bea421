/*
 * biss-sim - runs the BiSS-C master firmware (or any PRU image) on the
 * emulated PRU against a simulated cable and encoder(s).
 *
 * By default it runs the firmware built in this tree, configures it for the
 * chosen encoder profile as a host would, and checks every frame it
 * publishes against what the encoder models sent. With --image it runs any
 * image as is: a raw IRAM image (.bin) or pasm-dialect source assembled in
 * process with the rate and frame parameters as -D defines (the bench's
 * clocking image test/bench/clock_frames.p takes them).
 */
#include "bench.h"
#include "biss/biss_shm.h"
#include "fw_cd.h"
#include "fw_check.h"
#include "pru_isa.h"
#include "safe_file.h"
#include "bench_fw.h"
#include "default_image.h"
#include "scenario_json.h"
#include "sim_image.h"
#include "sim_encoder.h"
#include "sim_pair.h"
#include "sim_report.h"

#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

/* The longest simulated run (~11.6 days): far inside the core's time range
 * (PRU_MAX_CYCLE), so run limits in ps never overflow. */
#define MAX_SIM_MS 1e9

#ifndef BISS_SIM_FIRMWARE /* emulator/bench/CMakeLists.txt sets them all */
#define BISS_BUILD_DIR           "/nonexistent"
#define BISS_SIM_FIRMWARE        "biss_master.bin"
#define BISS_SIM_FIRMWARE_PRU1   "biss_master_pru1.bin"
#define BISS_SIM_ENCODER_PRU1    "biss_encoder_pru1.bin"
#define BISS_BIN_TO_FIRMWARE_DIR "../../lib/firmware"
#define BISS_FIRMWARE_DIR        "/lib/firmware"
#endif

/* The firmware image of PRU pru when none is named: the build's for the
 * build's biss-sim, else the installed one (default_image.h). */
static const char *own_image(unsigned pru) {
    static char buf[2][PATH_MAX + 64];
    const struct default_image d[2] = {
        {BISS_BUILD_DIR, BISS_SIM_FIRMWARE, BISS_BIN_TO_FIRMWARE_DIR "/biss_master.bin",
         BISS_FIRMWARE_DIR "/biss_master.bin"},
        {BISS_BUILD_DIR, BISS_SIM_FIRMWARE_PRU1, BISS_BIN_TO_FIRMWARE_DIR "/biss_master_pru1.bin",
         BISS_FIRMWARE_DIR "/biss_master_pru1.bin"},
    };
    pru = pru ? 1 : 0;
    return default_image(&d[pru], buf[pru], sizeof buf[pru]);
}

/* The encoder firmware's PRU1 image (pru_slave/), likewise. */
static const char *own_encoder_image(void) {
    static char buf[PATH_MAX + 64];
    const struct default_image d = {BISS_BUILD_DIR, BISS_SIM_ENCODER_PRU1,
                                    BISS_BIN_TO_FIRMWARE_DIR "/biss_encoder_pru1.bin",
                                    BISS_FIRMWARE_DIR "/biss_encoder_pru1.bin"};
    return default_image(&d, buf, sizeof buf);
}

struct options {
    const char *profile;
    const char *scenario_file;
    double freq_hz;
    double cable_m; /* < 0: the profile's */
    uint64_t frames;
    uint64_t settle; /* valid frames run before the measured ones (after the first) */
    uint64_t seed;
    int seed_set;
    const char *image;         /* any image, run as is */
    const char *firmware;      /* the BiSS master firmware (default: this tree's) */
    const char *pru1_firmware; /* PRU1's, with a second encoder */
    int encoder;               /* the encoder firmware on PRU1 as the slave end */
    const char *encoder_image; /* ... this image (default: this tree's) */
    const char *soc;
    unsigned pru; /* the PRU of the PRU-ICSS that runs the image */
    /* a second encoder on PRU1's line (sim_pair.h), and the IEP period */
    const char *pru1_profile, *pru1_scenario;
    unsigned trigger; /* BISS_TRIG_FREERUN, _HOST or _IEP (one PRU) */
    int trigger_set;
    double iep_period_ns;
    const char *vcd;
    int64_t vcd_unit_ps;
    const char *trace; /* --trace: every instruction the PRU runs, to this file */
    /* SL at the master on tape (sl_tape.h): recorded to this file, or
     * played back from it (loaded by main into tape) */
    const char *sl_record, *sl_replay;
    struct sl_tape *tape;
    const char *svg;
    uint64_t svg_frame;
    int json;
    double max_ms;                   /* simulated time limit, 0: derived */
    uint32_t link_warn, link_window; /* --link-warn K[,N] (0: the defaults) */
    biss_cd_prog cd;                 /* a control frame to send, when cd_set */
    int cd_set;
    const char *cd_what; /* the option that asked for it */
    /* fast paths switched off (--no-fast-path): the core's in its
     * parameters (otherwise the defaults), the link's here */
    struct pru_params core;
    int no_sl_reach, no_line_settled, no_slave_quick, no_ma_ahead, no_ahead_batch;
    /* strict and contention modes (emulator/core/TIMING.md) */
    unsigned strict, strict_window;
    int strict_log;
    const char *contend;
    struct biss_config
        checks; /* --check-life, --check-pair, --check-ew, --check-speed (their fields only) */
};

/* The MA rate when --freq is not given: libbiss's and bissctl's, one
 * source (biss_config_default; why it is 1 MHz: README "Conventions"). */
static double default_freq_hz(void) {
    struct biss_config c;
    biss_config_default(&c);
    return c.freq_hz;
}

static void usage(FILE *f) {
    fprintf(f, "usage: biss-sim [options]\n"
               "Runs a PRU image on the emulated PRU against a cable and BiSS-C/SSI encoder "
               "models.\n\n"
               "  --profile NAME     encoder profile (default tidep0022-test-encoder);\n"
               "                     --list-profiles prints them\n"
               "  --scenario FILE    JSON scenario: a profile plus any model parameter\n");
    fprintf(f,
            "  --freq HZ          MA clock rate (default %.0f, as bissctl's); 100 MHz / HZ\n"
            "                     must be whole\n",
            default_freq_hz());
    fprintf(f, "  --cable-m M        cable length in metres, both directions (default: profile's)\n"
               "  --frames N         frames to run (default 100)\n"
               "  --settle-frames N  valid frames to run first, neither checked nor measured\n"
               "                     (default 0: from the first valid frame on; e.g. for IEP\n"
               "                     frames to reach their period after the start)\n"
               "  --seed S           random seed for noise and jitter (default: scenario's)\n"
               "  --firmware FILE    BiSS master firmware, .bin or .p (default: the PRU's\n"
               "                     image of this build, or the one installed in\n"
               "                     " BISS_FIRMWARE_DIR "); configured for the profile and\n"
               "                     checked frame by frame; a .p is assembled for the PRU\n"
               "                     (-D PRU_NUM)\n"
               "  --image FILE       any PRU image (.bin, or .p assembled with -D HALF, CLOCKS,\n"
               "                     GAP, FRAMES, MA_BIT), run as is: nothing is decoded\n"
               "  --soc NAME         am335x (default), am437x-icss0, am437x-icss1\n"
               "  --pru N            run it on PRU N of the PRU-ICSS: 0 (default) or 1 (PRU0\n"
               "                     idle; the line on PRU1's pins, GPCFG1, data RAM1)\n"
               "  --pru1-profile NAME, --pru1-scenario FILE\n"
               "                     a second encoder on its own line to PRU1: the firmware\n"
               "                     on both PRUs, PRU0's frames on the IEP, PRU1's following\n"
               "                     them; both checked, and their frame starts compared\n"
               "  --trigger MODE     free (default: the next frame once the slave's timeout\n"
               "                     is over), host (one frame per CMD_TRIGGER, which the\n"
               "                     bench writes again once the firmware has taken it) or\n"
               "                     iep (one frame per IEP period)\n"
               "  --iep-period-ns NS the IEP period, with --trigger iep or a second encoder\n"
               "                     (default: twice the longer frame, in whole us)\n"
               "  --encoder[=FILE]   the slave end is the encoder firmware (pru_slave/) on\n"
               "                     PRU1 of the same PRU-ICSS (default: this build's\n"
               "                     biss_encoder_pru1.bin, or the installed one), the\n"
               "                     scenario's chain loaded into it; the slave model runs\n"
               "                     beside it on the same MA: the master's frames are\n"
               "                     checked against the model's, and the firmware's SL\n"
               "                     against the model's at every rising MA edge (a chain\n"
               "                     that moves with time moves by counts per frame)\n"
               "  --pru1-firmware FILE\n"
               "                     with a second encoder: PRU1's image (default: this\n"
               "                     build's or the installed PRU1 image, or --firmware's\n"
               "                     .p for PRU1)\n"
               "  --vcd FILE         write MA/SL at master and slave and a frame wire (high\n"
               "                     while a frame is clocked) as VCD (scope bench)\n"
               "  --vcd-timescale U  1ps, 10ps, 100ps or 1ns (default); edges keep their order\n"
               "  --trace FILE       write every instruction the PRU runs: cycle, PC, the\n"
               "                     instruction, the registers it changed (pru-run's\n"
               "                     --trace; idle loops the fast-forward skips are noted)\n"
               "  --sl-record FILE   write SL at the master's pin as the run goes (a tape)\n"
               "  --sl-replay FILE   the run again without the cable and encoder models: the\n"
               "                     PRU reads SL from the tape --sl-record wrote, its MA\n"
               "                     goes nowhere; the same options as the recording give\n"
               "                     the same run (checked: instructions, cycles and the\n"
               "                     RAMs at the end); prints what the PRU did and the\n"
               "                     time it took: the core's cost without the models\n"
               "  --svg FILE         write a scope view of one frame as SVG\n"
               "  --svg-frame K      which frame the SVG shows (default 2); frames count from 1,\n"
               "                     as bissctl's: frame 1 is the first (BiSS-C: training)\n"
               "  --json             print the results as one JSON object\n"
               "  --check-life S[,BITS]        the host's safety check of slave S's life\n"
               "                               counter on every frame (as bissctl's)\n"
               "  --check-pair A,B,TOL[,SA,SB] slaves A and B agree within TOL counts after\n"
               "                               shifting left by SA, SB (their CRCs differ)\n"
               "  --check-ew S                 slave S never sets nE/nW: a frame where either\n"
               "                               reads active is misframed, not valid\n"
               "  --check-speed S,CPS          slave S's position moves at most CPS counts a\n"
               "                               second: a frame beyond reach is misframed\n"
               "  --link-warn K[,N]            the link warning after K marginal frames (an\n"
               "                               eye of 2/8 bit or less) in a block of N\n"
               "                               (default 1,10000; proto/biss_link.c)\n"
               "  --no-fast-path P   run without the emulator's fast path P (results are the\n"
               "                     same, only slower): ff (idle loops, and with it the\n"
               "                     next four), ff-counted (polls with a time-out counter),\n"
               "                     ff-r31-bits (horizons of the R31 bits a loop tests),\n"
               "                     ff-loop-delay (LOOP delays run at once),\n"
               "                     ff-count-loop (countdown delays run at once),\n"
               "                     fast-loop (the core's threaded execute loop: every\n"
               "                     instruction the general way), leaf-call (delay\n"
               "                     calls replayed from a memo), straight-run (runs of\n"
               "                     register-only instructions without the checks\n"
               "                     between them; the firmware's bit-loop pairs, its\n"
               "                     carry chain and its one-instruction delay call as\n"
               "                     one), sl-reach (the SL input\n"
               "                     stays until an event could reach the master's pin),\n"
               "                     line-settled (a cable edge after a settled level\n"
               "                     without the low-pass arithmetic), slave-quick (a\n"
               "                     BiSS-C chain's clock edges in one step), ma-ahead\n"
               "                     (those edges taken by the slave when the PRU drives\n"
               "                     them; a run that halts or faults before one arrives\n"
               "                     runs again without), ahead-batch (the bench's\n"
               "                     measurements of those edges in batches, not one by\n"
               "                     one), run-ahead (two PRUs: each runs ahead to its\n"
               "                     next cross-PRU event, not both cycle by cycle)\n"
               "  --max-ms T         stop after T ms of simulated time (default: ample)\n"
               "  --strict[=RULES]   stop with a fault report on a construct of uncertain\n"
               "                     silicon behaviour in clocked code (between two MA edges\n"
               "                     at most --strict-window cycles apart, default 1024):\n"
               "                     loop1, loop0, loopfield, mvi, dram, spad (default: all)\n"
               "  --strict-log       with --strict: record every violation, run on, list them\n"
               "  --contend K,S[,periodic[:PHASE]|random[:SEED]]\n"
               "                     the host reads the data RAM every K cycles; a PRU\n"
               "                     load/store meeting one stalls S cycles\n"
               "  --reg-read ID:ADDR[:N]       read N (1..64) registers of slave ID through\n"
               "                               control frames, while positions go on\n"
               "  --reg-write ID:ADDR:B[,B..]  write bytes (hex) to consecutive registers\n"
               "  --command IDS:CMD[:T]        BiSS command CMD (0..3) to the slaves in the\n"
               "                               hex ID mask IDS (0: all, broadcast); T = 1:\n"
               "                               IDA test (withheld unless IDA = IDS)\n"
               "  -h, --help         this text\n"
               "\n"
               "exit status: 0 every frame run and checked, 1 an error (a file, the line, the\n"
               "firmware), 2 bad usage, 3 a PRU fault or a strict-mode construct, 4 the\n"
               "control frame failed, 5 two PRUs: a frame or their starts wrong, 124 the\n"
               "frames did not complete in time (--max-ms)\n");
}

/* Exit status (README "Conventions"; the list in --help) */
#define EXIT_ERROR   1   /* a file, the line or the firmware refused the run */
#define EXIT_USAGE   2   /* the command line */
#define EXIT_FAULT   3   /* the PRU faulted, or strict mode found a construct */
#define EXIT_CD      4   /* the control frame failed */
#define EXIT_TIMEOUT 124 /* as timeout(1): the frames did not complete in time */

/* Prints "biss-sim: <message>" and returns EXIT_ERROR. */
__attribute__((format(printf, 1, 2))) static int die(const char *fmt, ...) {
    va_list ap;
    va_start(ap, fmt);
    fprintf(stderr, "biss-sim: ");
    vfprintf(stderr, fmt, ap);
    fprintf(stderr, "\n");
    va_end(ap);
    return EXIT_ERROR;
}

/* A usage error in the tools' one form: "biss-sim: <message>" and the way
 * to the help; returns EXIT_USAGE. */
__attribute__((format(printf, 1, 2))) static int usage_error(const char *fmt, ...) {
    va_list ap;
    va_start(ap, fmt);
    fprintf(stderr, "biss-sim: ");
    vfprintf(stderr, fmt, ap);
    fprintf(stderr, "\nTry 'biss-sim --help' for more information.\n");
    va_end(ap);
    return EXIT_USAGE;
}

static int parse_double(const char *s, double *out) {
    char *end;
    errno = 0;
    double v = strtod(s, &end);
    if (errno || end == s || *end || !isfinite(v)) {
        return -1;
    }
    *out = v;
    return 0;
}

static int parse_u64(const char *s, uint64_t *out) {
    char *end;
    errno = 0;
    unsigned long long v = strtoull(s, &end, 0);
    if (errno || end == s || *end || s[0] == '-') {
        return -1;
    }
    *out = v;
    return 0;
}

static void list_profiles(void) {
    for (size_t i = 0; profile_name_at(i); i++) {
        printf("%s\n", profile_name_at(i));
    }
}

/* Options that take a value. */
static const char *const valued[] = {
    "--profile",  "--scenario",    "--freq",      "--cable-m", "--frames",     "--seed",
    "--image",    "--soc",         "--vcd",       "--svg",     "--svg-frame",  "--max-ms",
    "--firmware", "--reg-read",    "--reg-write", "--command", "--check-life", "--check-pair",
    "--check-ew", "--check-speed", "--link-warn"};
/* ... and those of the waveform output and the fast paths */
static const char *const valued_out[] = {
    "--vcd-timescale", "--no-fast-path",  "--strict-window", "--trace",         "--contend",
    "--pru",           "--pru1-profile",  "--pru1-scenario", "--iep-period-ns", "--trigger",
    "--pru1-firmware", "--settle-frames", "--sl-record",     "--sl-replay"};

static int takes_value(const char *a) {
    for (size_t i = 0; i < sizeof(valued) / sizeof(valued[0]); i++) {
        if (!strcmp(a, valued[i])) {
            return 1;
        }
    }
    for (size_t i = 0; i < sizeof(valued_out) / sizeof(valued_out[0]); i++) {
        if (!strcmp(a, valued_out[i])) {
            return 1;
        }
    }
    return 0;
}

/* "a:b:c,d,..." into numbers (base 16 after the second field for writes). */
static int parse_fields(const char *v, unsigned *f, unsigned max, int hex_from) {
    unsigned n = 0;
    const char *p = v;
    while (n < max) {
        char *end;
        errno = 0;
        unsigned long x = strtoul(p, &end, (int)n >= hex_from ? 16 : 0);
        if (errno || end == p || x > 0xffff) {
            return -1;
        }
        f[n++] = (unsigned)x;
        if (*end == '\0') {
            return (int)n;
        }
        if (*end != ':' && *end != ',') {
            return -1;
        }
        p = end + 1;
    }
    return -1;
}

/* --reg-read, --reg-write, --command into a CDM program. */
static int set_control(struct options *o, const char *a, const char *v) {
    unsigned f[2 + BISS_CD_MAX_BYTES];
    int n;
    biss_cd_err e = BISS_CD_E_ARG;
    if (!strcmp(a, "--reg-read")) {
        n = parse_fields(v, f, 3, 99);
        if (n >= 2) {
            e = biss_cd_build_read(&o->cd, f[0], f[1], n == 3 ? f[2] : 1);
        }
    } else if (!strcmp(a, "--reg-write")) {
        n = parse_fields(v, f, 2 + BISS_CD_MAX_BYTES, 2);
        if (n >= 3) {
            uint8_t bytes[BISS_CD_MAX_BYTES];
            for (int i = 2; i < n; i++) {
                bytes[i - 2] = (uint8_t)f[i];
            }
            e = f[2] <= 0xff ? biss_cd_build_write(&o->cd, f[0], f[1], bytes, (unsigned)n - 2) : e;
        }
    } else {
        n = parse_fields(v, f, 3, 0);
        if (n >= 2 && f[0] <= 0xff && (n == 2 || f[2] <= 1)) {
            e = biss_cd_build_command(&o->cd, (uint8_t)f[0], f[1], n == 3 && f[2]);
        }
    }
    if (e != BISS_CD_OK) {
        return usage_error("%s '%s': %s", a, v, biss_cd_strerror(e));
    }
    o->cd_set = 1;
    o->cd_what = a;
    return 0;
}

/* One option with its value; returns 0 or EXIT_USAGE (message printed). */
static int set_option(struct options *o, const char *a, const char *v) {
    if (!strcmp(a, "--profile")) {
        o->profile = v;
    } else if (!strcmp(a, "--scenario")) {
        o->scenario_file = v;
    } else if (!strcmp(a, "--freq")) {
        if (parse_double(v, &o->freq_hz) || o->freq_hz <= 0) {
            return usage_error("--freq '%s': expected Hz, above 0", v);
        }
    } else if (!strcmp(a, "--cable-m")) {
        if (parse_double(v, &o->cable_m) || o->cable_m < 0 || o->cable_m > 1000) {
            return usage_error("--cable-m '%s': expected metres, 0..1000", v);
        }
    } else if (!strcmp(a, "--frames")) {
        if (parse_u64(v, &o->frames) || o->frames == 0) {
            return usage_error("--frames '%s': expected a positive count", v);
        }
    } else if (!strcmp(a, "--settle-frames")) {
        if (parse_u64(v, &o->settle)) {
            return usage_error("--settle-frames '%s': expected a count", v);
        }
    } else if (!strcmp(a, "--seed")) {
        if (parse_u64(v, &o->seed)) {
            return usage_error("--seed '%s': expected a number", v);
        }
        o->seed_set = 1;
    } else if (!strcmp(a, "--image")) {
        o->image = v;
    } else if (!strcmp(a, "--pru1-profile")) {
        o->pru1_profile = v;
    } else if (!strcmp(a, "--pru1-scenario")) {
        o->pru1_scenario = v;
    } else if (!strcmp(a, "--iep-period-ns")) {
        if (parse_double(v, &o->iep_period_ns) || o->iep_period_ns < 5 || o->iep_period_ns > 2e7 ||
            fmod(o->iep_period_ns, 5) != 0) {
            return usage_error("--iep-period-ns '%s': expected a multiple of 5 ns up to 20 ms", v);
        }
    } else if (!strcmp(a, "--trigger")) {
        static const struct {
            const char *name;
            unsigned mode;
        } modes[] = {{"free", BISS_TRIG_FREERUN}, {"host", BISS_TRIG_HOST}, {"iep", BISS_TRIG_IEP}};
        o->trigger_set = 0;
        for (unsigned t = 0; t < sizeof modes / sizeof modes[0]; t++) {
            if (!strcmp(v, modes[t].name)) {
                o->trigger = modes[t].mode;
                o->trigger_set = 1;
            }
        }
        if (!o->trigger_set) {
            return usage_error("--trigger '%s': expected free, host or iep", v);
        }
    } else if (!strcmp(a, "--pru")) {
        if (strcmp(v, "0") && strcmp(v, "1")) {
            return usage_error("--pru '%s': expected 0 or 1", v);
        }
        o->pru = (unsigned)(v[0] - '0');
    } else if (!strcmp(a, "--firmware")) {
        o->firmware = v;
    } else if (!strcmp(a, "--pru1-firmware")) {
        o->pru1_firmware = v;
    } else if (!strcmp(a, "--check-life")) {
        if (biss_safety_parse_life(v, &o->checks)) {
            return usage_error("--check-life '%s': expected S[,BITS] (slave 0..7, 1..32 bits)", v);
        }
    } else if (!strcmp(a, "--check-ew")) {
        if (biss_safety_parse_ew(v, &o->checks)) {
            return usage_error("--check-ew '%s': expected S (slave 0..7)", v);
        }
    } else if (!strcmp(a, "--check-speed")) {
        if (biss_safety_parse_speed(v, &o->checks)) {
            return usage_error(
                "--check-speed '%s': expected S,CPS (slave 0..7, counts per second 1e-9..1e18)", v);
        }
    } else if (!strcmp(a, "--check-pair")) {
        if (biss_safety_parse_pair(v, &o->checks)) {
            return usage_error("--check-pair '%s': expected A,B,TOL[,SHIFT_A,SHIFT_B] (slaves "
                               "0..7, shifts 0..63; at most 4 pairs)",
                               v);
        }
    } else if (!strcmp(a, "--reg-read") || !strcmp(a, "--reg-write") || !strcmp(a, "--command")) {
        return set_control(o, a, v);
    } else if (!strcmp(a, "--soc")) {
        o->soc = v;
    } else if (!strcmp(a, "--vcd")) {
        o->vcd = v;
    } else if (!strcmp(a, "--trace")) {
        o->trace = v;
    } else if (!strcmp(a, "--sl-record")) {
        o->sl_record = v;
    } else if (!strcmp(a, "--sl-replay")) {
        o->sl_replay = v;
    } else if (!strcmp(a, "--vcd-timescale")) {
        static const char *const units[] = {"1ps", "10ps", "100ps", "1ns"};
        static const int64_t ps[] = {1, 10, 100, 1000};
        o->vcd_unit_ps = 0;
        for (int i = 0; i < 4; i++) {
            o->vcd_unit_ps = strcmp(v, units[i]) ? o->vcd_unit_ps : ps[i];
        }
        if (!o->vcd_unit_ps) {
            return usage_error("--vcd-timescale '%s': expected 1ps, 10ps, 100ps or 1ns", v);
        }
    } else if (!strcmp(a, "--no-fast-path")) {
        if (!strcmp(v, "sl-reach")) {
            o->no_sl_reach = 1;
        } else if (!strcmp(v, "line-settled")) {
            o->no_line_settled = 1;
        } else if (!strcmp(v, "slave-quick")) {
            o->no_slave_quick = 1;
        } else if (!strcmp(v, "ma-ahead")) {
            o->no_ma_ahead = 1;
        } else if (!strcmp(v, "ahead-batch")) {
            o->no_ahead_batch = 1;
        } else if (pru_params_fast_path_off(&o->core, v) != 0) {
            return usage_error("--no-fast-path '%s': expected ff, ff-counted, ff-r31-bits, "
                               "ff-loop-delay, ff-count-loop, fast-loop, leaf-call, straight-run, "
                               "sl-reach, line-settled, slave-quick, ma-ahead, ahead-batch or "
                               "run-ahead",
                               v);
        }
    } else if (!strcmp(a, "--strict-window")) {
        char *end;
        errno = 0;
        unsigned long w = strtoul(v, &end, 10);
        if (errno || end == v || *end || w == 0 || w > 0xffffff) {
            return usage_error("--strict-window '%s': expected cycles, 1..16777215", v);
        }
        o->strict_window = (unsigned)w;
    } else if (!strcmp(a, "--contend")) {
        o->contend = v;
    } else if (!strcmp(a, "--svg")) {
        o->svg = v;
    } else if (!strcmp(a, "--svg-frame")) {
        if (parse_u64(v, &o->svg_frame) || o->svg_frame == 0) {
            return usage_error("--svg-frame '%s': expected a frame number (1 is the first)", v);
        }
    } else if (!strcmp(a, "--link-warn")) {
        if (biss_link_parse(v, &o->link_warn, &o->link_window) != BISS_OK) {
            return usage_error("--link-warn '%s': expected K[,N] (K marginal frames in a block "
                               "of N, both >= 1)",
                               v);
        }
    } else if (!strcmp(a, "--max-ms")) {
        if (parse_double(v, &o->max_ms) || o->max_ms <= 0 || o->max_ms > MAX_SIM_MS) {
            return usage_error("--max-ms '%s': expected ms, above 0 and at most %.0f", v,
                               MAX_SIM_MS);
        }
    }
    return 0;
}

/* Returns 0 to run, -1 to exit 0 (help printed), else EXIT_USAGE (message
 * printed). */
static int parse_args(int argc, char **argv, struct options *o) {
    *o = (struct options){.profile = "tidep0022-test-encoder",
                          .freq_hz = default_freq_hz(),
                          .cable_m = -1,
                          .frames = 100,
                          .soc = "am335x",
                          .trigger = BISS_TRIG_FREERUN,
                          .vcd_unit_ps = 1000,
                          .svg_frame = 2};
    pru_params_default(&o->core);
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        if (!strcmp(a, "-h") || !strcmp(a, "--help")) {
            usage(stdout);
            return -1;
        } else if (!strcmp(a, "--list-profiles")) {
            list_profiles();
            return -1;
        } else if (!strcmp(a, "--json")) {
            o->json = 1;
        } else if (!strcmp(a, "--strict") || !strncmp(a, "--strict=", 9)) {
            const char *bad;
            if (pru_strict_parse(a[8] ? a + 9 : NULL, &o->strict, &bad) != 0) {
                return usage_error(
                    "--strict '%s': expected loop1, loop0, loopfield, mvi, dram or spad", bad);
            }
        } else if (!strcmp(a, "--strict-log")) {
            o->strict_log = 1;
        } else if (!strcmp(a, "--encoder") || !strncmp(a, "--encoder=", 10)) {
            o->encoder = 1;
            o->encoder_image = a[9] ? a + 10 : NULL;
        } else if (!takes_value(a)) {
            return usage_error("unknown option '%s'", a);
        } else if (i + 1 >= argc) {
            return usage_error("option '%s' needs a value", a);
        } else if (set_option(o, a, argv[++i]) != 0) {
            return EXIT_USAGE;
        }
    }
    return 0;
}

static int build_config(const struct options *o, struct bench_config *cfg) {
    char err[256];
    bench_config_default(cfg);
    cfg->pru_index = o->pru;
    if (pru_soc_from_name(o->soc, &cfg->soc) != 0) {
        return usage_error("--soc '%s': expected am335x, am437x-icss0 or am437x-icss1", o->soc);
    }
    if (o->scenario_file) {
        if (scenario_load_file(o->scenario_file, &cfg->link, err, sizeof(err)) != 0) {
            return die("%s", err);
        }
    } else if (profile_by_name(o->profile, &cfg->link) != 0) {
        return usage_error("--profile '%s': expected a profile of --list-profiles", o->profile);
    }
    if (o->cable_m >= 0) {
        scenario_set_cable(&cfg->link, o->cable_m);
    }
    if (o->seed_set) {
        cfg->link.seed = o->seed;
    }
    cfg->pru = o->core; /* the defaults, fast paths off as asked */
    cfg->no_sl_reach = o->no_sl_reach;
    cfg->no_slave_quick = o->no_slave_quick;
    cfg->no_line_settled = o->no_line_settled;
    /* not where the run writes as it goes (the VCD, the trace) or captures:
     * a run that stops short of an edge taken ahead runs again (main) */
    cfg->ma_ahead = !o->no_ma_ahead && !o->vcd && !o->svg && !o->trace;
    cfg->no_ahead_batch = o->no_ahead_batch;
    cfg->pru.strict = o->strict;
    cfg->pru.strict_log = o->strict_log;
    if (o->strict_window) {
        cfg->pru.strict_window = o->strict_window;
    }
    if ((o->strict_log || o->strict_window) && !o->strict) {
        return usage_error("--strict-log and --strict-window need --strict");
    }
    if (o->contend && pru_contend_parse(o->contend, &cfg->pru, err, sizeof(err)) != 0) {
        return usage_error("--contend %s", err);
    }
    return 0;
}

/* What the scenario's line and slaves allow the rate (proto's rules,
 * libbiss.h "what a line allows"): its cable, the model's round trip, the
 * slaves' timeout at this rate (an SSI encoder's monoflop). */
static int line_verdict(const scenario *sc, unsigned half, struct biss_line_verdict *v) {
    sim_ps period = 2 * (sim_ps)half * PRU_PS_PER_CYCLE;
    sim_ps timeout = sc->model->timeout(scenario_model_cfg(sc), period);
    sim_ps out = sc->model->out_delay(scenario_model_cfg(sc));
    struct biss_line_facts f = {.cable_m = sc->ma_line.length_m,
                                .round_trip_ns =
                                    (line_nominal_delay_ps(&sc->ma_line) + (double)out +
                                     line_nominal_delay_ps(&sc->sl_line)) /
                                    1000.0,
                                .slave_timeout_ns = (uint32_t)((timeout + 999) / 1000)};
    return biss_proto_line_check(half, &f, v);
}

/* The rate against the line, up front: a warning beyond TIDEP0022 Table
 * 5, a refusal (1, message printed) for a timeout or a round trip no
 * frame can work with. `who` names the line in a two-PRU run. */
static int check_line(const scenario *sc, unsigned half, const char *who,
                      struct biss_line_verdict *v) {
    int rc = line_verdict(sc, half, v);
    if (rc != BISS_OK && rc != BISS_E_LINE_TIMEOUT && rc != BISS_E_LINE_DELAY) {
        memset(v, 0, sizeof *v); /* a rate beyond the firmware's (--image): no rule for it */
        return 0;
    }
    char text[512];
    biss_line_text(v, text, sizeof text);
    if (rc != BISS_OK) {
        return die("%s%s", who, text);
    }
    if (v->beyond_table) {
        fprintf(stderr, "biss-sim: warning: %s%s\n", who, text);
    }
    return 0;
}

/* The shortest MA half period the bench clocks a bare image at (--image:
 * clock_frames.p's loops); the firmware's own limits are proto's rule. */
#define SIM_IMAGE_MIN_HALF 5

static void progress(uint64_t done, uint64_t total) {
    fprintf(stderr, "\rbiss-sim: frame %llu/%llu", (unsigned long long)done,
            (unsigned long long)total);
    fflush(stderr);
}

static double now_seconds(void) {
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + (double)ts.tv_nsec * 1e-9;
}

/* The strict-mode log on stderr, one line per (pc, rule); returns how many. */
static size_t print_strict_log(struct pru_core *c) {
    const struct pru_strict_hit *h;
    uint64_t lost;
    size_t n = pru_strict_hits(c, &h, &lost);
    for (size_t i = 0; i < n; i++) {
        char dis[96];
        pru_disasm(h[i].word, h[i].pc, dis, sizeof dis);
        fprintf(stderr, "biss-sim: strict: %-9s pc=0x%04x first cycle %lld, %llu times: %s\n",
                pru_strict_rule_name(h[i].rule), h[i].pc, (long long)h[i].first_cycle,
                (unsigned long long)h[i].count, dis);
    }
    if (lost) {
        fprintf(stderr, "biss-sim: strict: %llu more not listed\n", (unsigned long long)lost);
    }
    return n + (size_t)lost;
}

/* What run_firmware runs. */
struct run_plan {
    uint64_t settle;          /* valid frames after the first before the measured ones */
    uint64_t frames;          /* valid frames checked and measured */
    int64_t max_ps;           /* simulated time at most */
    int show;                 /* progress on stderr */
    const biss_cd_prog *prog; /* a control program to run, or NULL */
    /* host-trigger mode: how often the bench (the host) looks whether its
     * last request was taken, to ask for the next frame; 0: not that mode */
    int64_t host_step_ps;
};

/* Asks for a frame (CMD_TRIGGER) unless one is still pending. */
static void trigger_again(struct bench *b) {
    struct biss_proto_io io = bench_fw_io(b);
    uint32_t pending = 1;
    if (biss_proto_trigger_get(&io, &pending) == 0 && !pending) {
        biss_proto_trigger(&io);
    }
}

/* Runs until the firmware has published p->frames valid frames after its
 * first one and p->settle more (whose training, start-up and settling the
 * statistics leave out); in host-trigger mode asking for each. */
static enum pru_stop run_firmware(struct bench *b, struct fw_check *fc, struct fw_cd *cd,
                                  const struct run_plan *p) {
    const int64_t step = p->host_step_ps ? p->host_step_ps : 100 * SIM_PS_PER_US;
    const uint64_t frames = p->frames;
    const biss_cd_prog *prog = p->prog;
    int64_t end = pru_time_ps(bench_core(b)) + p->max_ps;
    enum pru_stop why = PRU_STOP_LIMIT;
    int started = 0;
    while (pru_time_ps(bench_core(b)) < end) {
        if (!started && fc->frames > p->settle) {
            /* from here on, `frames` frames are checked and measured */
            started = 1;
            fw_check_restart(fc, frames);
            bench_reset_stats(b);
            bench_set_frame_limit(b, bench_current_frame(b) + frames + 1);
        }
        if (started && prog && !cd->b) {
            fw_cd_issue(cd, b, prog, 100); /* a late S may take 100 frames */
        }
        if (started && fc->frames >= frames && (!prog || fw_cd_poll(cd))) {
            break;
        }
        if (bench_fw_status(b).state == BISS_STATE_CFG_ERROR) {
            break;
        }
        if (p->host_step_ps) {
            trigger_again(b);
        }
        int64_t next = pru_time_ps(bench_core(b)) + step;
        why = bench_run_until(b, next < end ? next : end);
        if (why != PRU_STOP_LIMIT) {
            break;
        }
        if (p->show) {
            progress(fc->frames, frames);
        }
    }
    return why;
}

static bool is_bin(const char *path) {
    size_t n = strlen(path);
    return n >= 4 && !strcmp(path + n - 4, ".bin");
}

/* An image assembled for the other PRU (its words say so) is refused
 * before it runs: started, it would point its private area at the shared
 * block and say nothing (pru_fw/README.md, one image per PRU). */
static bool wrong_pru(const char *path, const struct pruasm_image *img, unsigned pru) {
    int built = biss_image_pru(img->words, img->nwords * 4);
    if (built < 0 || (unsigned)built == pru) {
        return false;
    }
    die("%s was assembled for PRU%d, not PRU%u (one image per PRU: %s)", path, built, pru,
        pru ? "biss_master_pru1.bin" : "biss_master.bin");
    return true;
}

/* The firmware source is assembled for the PRU it runs on (PRU_NUM). */
static void pru_num_define(unsigned pru, struct sim_defines *d) {
    snprintf(d->text[d->n++], sizeof d->text[0], "PRU_NUM=%u", pru);
}

/* A second encoder on PRU1 (sim_pair.h): the firmware on both PRUs. */
static int run_pair(const struct options *o, const struct bench_config *cfg, unsigned half) {
    if (o->image || o->vcd || o->svg || o->cd_set || o->pru || o->trigger_set || o->trace) {
        return usage_error("--pru1-profile/--pru1-scenario run the firmware on both PRUs, PRU0 "
                           "on the IEP and PRU1 following it: not with --image, --vcd, --svg, "
                           "--trace, --pru, --trigger or control frames");
    }
    struct sim_pair_run r = {.cfg = {*cfg, *cfg},
                             .half = half,
                             .iep_period = (uint32_t)(o->iep_period_ns / 5),
                             .frames = o->frames,
                             .settle = o->settle,
                             .checks = &o->checks,
                             .json = o->json};
    char err[512];
    if (o->pru1_scenario) {
        if (scenario_load_file(o->pru1_scenario, &r.cfg[1].link, err, sizeof(err)) != 0) {
            return die("%s", err);
        }
    } else if (profile_by_name(o->pru1_profile, &r.cfg[1].link) != 0) {
        return usage_error("--pru1-profile '%s': expected a profile of --list-profiles",
                           o->pru1_profile);
    }
    if (o->cable_m >= 0) {
        scenario_set_cable(&r.cfg[1].link, o->cable_m);
    }
    if (o->seed_set) {
        r.cfg[1].link.seed = o->seed + 1; /* a noise of its own */
    }
    struct biss_line_verdict line;
    if (check_line(&r.cfg[1].link, half, "PRU1's line: ", &line) != 0) {
        return EXIT_ERROR;
    }
    /* one image per PRU (pru_fw/README.md) */
    struct pruasm_image img[2];
    const char *path[2] = {o->firmware ? o->firmware : own_image(0),
                           o->pru1_firmware ? o->pru1_firmware : own_image(1)};
    if (!o->pru1_firmware && o->firmware && !is_bin(o->firmware)) {
        path[1] = o->firmware; /* the source, assembled for PRU1 */
    }
    for (unsigned i = 0; i < 2; i++) {
        struct sim_defines d = {.n = 0};
        pru_num_define(i, &d);
        if (sim_load_image(path[i], &d, &img[i], err, sizeof(err)) != 0) {
            if (i) {
                pruasm_image_free(&img[0]);
            }
            return die("%s", err);
        }
        if (wrong_pru(path[i], &img[i], i)) {
            for (unsigned k = 0; k <= i; k++) {
                pruasm_image_free(&img[k]);
            }
            return EXIT_ERROR;
        }
        r.image[i] = img[i].words;
        r.bytes[i] = img[i].nwords * 4;
    }
    r.max_ps = (int64_t)(o->max_ms * 1e9); /* 0: ample (sim_pair) */
    r.cap_ps = (int64_t)(MAX_SIM_MS * 1e9);
    int rc = sim_pair(&r);
    pruasm_image_free(&img[0]);
    pruasm_image_free(&img[1]);
    return rc;
}

/* A bench with the encoder firmware on PRU1 at the slave end (--encoder):
 * its chain first moved by counts per frame at this rate's frame. */
static struct bench *new_loop(struct bench_config *cfg, unsigned half, char *err, size_t errlen) {
    struct bench *b = bench_new_loop(cfg, err, errlen);
    if (!b) {
        return NULL;
    }
    biss_chain_cfg c = cfg->link.biss;
    slave_fw_chain(&c, sim_clock_frame_ps(b, half), stderr);
    if (memcmp(&c, &cfg->link.biss, sizeof c) == 0) {
        return b;
    }
    bench_free(b);
    cfg->link.biss = c;
    return bench_new_loop(cfg, err, errlen);
}

/* The encoder image loaded on PRU1 and the chain into it. */
static int start_encoder(const struct options *o, struct bench *b, const struct bench_config *cfg,
                         struct sim_encoder *e) {
    char err[512];
    struct sim_defines d = {.n = 0};
    pru_num_define(1, &d);
    snprintf(d.text[d.n++], sizeof d.text[0], "MA_IN_BIT=1");
    const char *path = o->encoder_image ? o->encoder_image : own_encoder_image();
    struct pruasm_image img;
    if (sim_load_image(path, &d, &img, err, sizeof err) != 0) {
        return die("--encoder: %s", err);
    }
    int rc = sim_encoder_start(e, b, img.words, img.nwords * 4, &cfg->link.biss, err, sizeof err);
    pruasm_image_free(&img);
    if (!rc && o->core.strict) {
        /* clocked by its input: strict's scope from MA's edges (MA_IN_BIT) */
        pru_strict_inputs(bench_encoder_core(b), 1u << 1);
    }
    return rc ? die("--encoder: %s (%s)", err, path) : 0;
}

/* The scenario's safety checks and the command line's, against the
 * chain's layout: a specific message for each bad one. */
static int safety_checks(const struct options *o, struct biss_config *c) {
    int rc = biss_safety_merge(c, &o->checks);
    if (!rc) {
        rc = biss_safety_config_check(c);
    }
    return rc ? die("safety checks: %s", sim_safety_problem(rc)) : 0;
}

/* run()'s answer when the fast path "ma-ahead" took an MA edge ahead that
 * the run, stopped short of it, would not have delivered: it wrote
 * nothing, and runs again without that fast path. */
#define RUN_AGAIN (-2)

static int run(const struct options *o) {
    struct bench_config cfg;
    int bad = build_config(o, &cfg);
    if (bad) {
        return bad;
    }
    unsigned half; /* the rate's H, once, by proto's rate rule */
    if (biss_proto_freq_half(o->freq_hz, &half) != BISS_OK || half < SIM_IMAGE_MIN_HALF ||
        half > BISS_MAX_HALF) {
        return usage_error("--freq '%.10g': expected 100 MHz / f a whole number of PRU cycles, "
                           "%d..%d",
                           o->freq_hz, SIM_IMAGE_MIN_HALF, BISS_MAX_HALF);
    }
    const char *why_not = o->image ? NULL : biss_proto_half_problem(half);
    if (why_not) {
        return usage_error("--freq '%.10g': the firmware cannot clock it: %s", o->freq_hz, why_not);
    }
    char err[512];
    struct biss_line_verdict line;
    if (check_line(&cfg.link, half, (o->pru1_profile || o->pru1_scenario) ? "PRU0's line: " : "",
                   &line) != 0) {
        return EXIT_ERROR;
    }
    if ((o->sl_record || o->sl_replay) &&
        (o->pru1_profile || o->pru1_scenario || o->encoder || o->image)) {
        return usage_error("--sl-record, --sl-replay: the firmware on one PRU, SL from the "
                           "encoder models (not --image, --encoder or a second encoder)");
    }
    if (o->sl_replay && (o->sl_record || o->vcd || o->svg || o->cd_set)) {
        return usage_error("--sl-replay runs no model: not with --sl-record, --vcd, --svg or "
                           "control frames");
    }
    if (o->pru1_profile || o->pru1_scenario) {
        if (o->encoder) {
            return die("--encoder runs on PRU1: not with a second encoder");
        }
        return run_pair(o, &cfg, half);
    }
    if (o->encoder && (o->image || o->pru)) {
        return die("--encoder is PRU1's: the master firmware on PRU0 (not --image, --pru 1)");
    }
    struct bench *b =
        o->encoder ? new_loop(&cfg, half, err, sizeof err) : bench_new(&cfg, err, sizeof(err));
    if (!b) {
        return die("%s", err);
    }
    if (o->sl_record && bench_tape_record(b, o->sl_record, err, sizeof err) != 0) {
        bench_free(b);
        return die("--sl-record: %s", err);
    }
    struct sim_encoder enc = {0};
    if (o->encoder && start_encoder(o, b, &cfg, &enc) != 0) {
        bench_free(b);
        return 1;
    }
    int fw_mode = o->image == NULL;
    struct sim_defines defs = {.n = 0};
    if (!fw_mode) {
        sim_clock_defines(b, half, o->frames, &defs);
        bench_set_ma_half(b, half);
        if (o->cd_set || o->trigger_set) {
            bench_free(b);
            return usage_error("%s needs the firmware (not --image)",
                               o->cd_set ? o->cd_what : "--trigger");
        }
    }
    if (o->iep_period_ns > 0 && o->trigger != BISS_TRIG_IEP) {
        bench_free(b);
        return usage_error("--iep-period-ns needs --trigger iep (or a second encoder)");
    }
    /* IEP: the period asked for, or twice the frame in whole microseconds */
    double frame_ps = sim_clock_frame_ps(b, half);
    uint32_t iep_period = o->iep_period_ns > 0
                              ? (uint32_t)(o->iep_period_ns / 5)
                              : (uint32_t)ceil(2 * frame_ps / SIM_PS_PER_US) * 200u;
    /* host trigger: the bench looks every two frames whether to ask again */
    int64_t host_step = (int64_t)fmax(2 * frame_ps, 10 * SIM_PS_PER_US);
    struct pruasm_image img;
    int rc = 0;
    struct safe_file trace = {.f = NULL};
    const char *own = own_image(o->pru); /* one per PRU */
    const char *path = fw_mode ? (o->firmware ? o->firmware : own) : o->image;
    if (fw_mode) {
        pru_num_define(o->pru, &defs);
    }
    if (sim_load_image(path, &defs, &img, err, sizeof(err)) != 0) {
        bench_free(b);
        return die("%s", err);
    }
    if (fw_mode && wrong_pru(path, &img, o->pru)) {
        pruasm_image_free(&img);
        bench_free(b);
        return EXIT_ERROR;
    }
    if ((fw_mode ? bench_fw_start(b, img.words, img.nwords * 4)
                 : bench_start_image(b, img.words, img.nwords * 4)) != 0) {
        rc = die("image of %zu words does not fit the IRAM of %s", img.nwords, o->soc);
    } else if (o->vcd && bench_open_vcd(b, o->vcd, o->vcd_unit_ps) != 0) {
        rc = die("cannot write the VCD: %s", bench_vcd_error(b));
    } else if (o->trace && safe_file_open(&trace, o->trace, err, sizeof err) != 0) {
        rc = die("--trace: %s", err);
    } else if (trace.f) {
        pru_set_trace(bench_core(b), trace.f);
    }
    struct fw_check fc;
    if (rc == 0 && fw_mode) {
        fw_check_attach(&fc, b);
        biss_link_init(&fc.link, o->link_window, o->link_warn);
        rc = safety_checks(o, &fc.cfg);
        fc.cfg.trigger = (enum biss_trigger)o->trigger;
        fc.cfg.iep_period_ns = o->trigger == BISS_TRIG_IEP ? iep_period * 5u : 0; /* 5 ns counts */
        fc.cfg.proc_limit = 1000;
        fw_check_configure(&fc, half); /* H as is: --freq need not be a whole number of Hz */
        if (o->cd_set && !scenario_chain(&cfg.link)) {
            rc = die("%s: an %s encoder has no control communication", o->cd_what,
                     cfg.link.model->title);
        }
    }
    if (rc != 0) {
        pruasm_image_free(&img);
        bench_free(b);
        return rc;
    }
    if (o->svg) { /* the slave numbers frames from 0 */
        bench_capture_frame(b, o->svg_frame - 1);
        if (fw_mode) {
            fw_check_watch(&fc, o->svg_frame - 1);
        }
    }
    /* ample time: every frame at its longest (or its IEP period, or the
     * host's look), twice, plus start-up; never beyond MAX_SIM_MS (the
     * message then says how many frames ran) */
    double per_frame = o->trigger == BISS_TRIG_IEP    ? fmax(frame_ps, iep_period * 5e3)
                       : o->trigger == BISS_TRIG_HOST ? fmax(frame_ps, (double)host_step)
                                                      : frame_ps;
    double limit_ps = o->max_ms > 0
                          ? o->max_ms * 1e9
                          : 2 * per_frame * ((double)(o->frames + o->settle) + 4) + SIM_PS_PER_MS;
    int tty = isatty(2);
    double t_start = now_seconds();
    struct fw_cd cd = {0};
    if (o->cd_set) {
        limit_ps += 2 * per_frame * (o->cd.len + 20);
    }
    int64_t max_ps = (int64_t)fmin(limit_ps, MAX_SIM_MS * 1e9);
    struct run_plan plan = {.settle = o->settle,
                            .frames = o->frames,
                            .max_ps = max_ps,
                            .show = tty,
                            .prog = o->cd_set ? &o->cd : NULL,
                            .host_step_ps = o->trigger == BISS_TRIG_HOST ? host_step : 0};
    if (o->tape) {
        bench_tape_play(b, o->tape);
    }
    enum pru_stop why = fw_mode ? run_firmware(b, &fc, &cd, &plan)
                                : bench_run_frames(b, o->frames, max_ps, NULL, NULL);
    if (bench_ahead_overrun(b)) { /* nothing written yet: again, exactly */
        pruasm_image_free(&img);
        bench_free(b);
        return RUN_AGAIN;
    }
    struct sim_result res = {.b = b,
                             .fw = fw_mode ? &fc : NULL,
                             .why = why,
                             .freq_hz = o->freq_hz,
                             .half = half,
                             .host_seconds = now_seconds() - t_start,
                             .cd = cd.done ? &cd : NULL,
                             .trigger = o->trigger};
    if (tty) {
        fprintf(stderr, "\r%40s\r", "");
    }
    if (why == PRU_STOP_FAULT) {
        pru_print_fault(bench_core(b), stderr);
        rc = EXIT_FAULT;
    }
    if (o->strict_log && print_strict_log(bench_core(b)) > 0 && rc == 0) {
        rc = EXIT_FAULT;
    }
    if (o->contend) {
        uint64_t n, stall;
        pru_contend_stats(bench_core(b), &n, &stall);
        fprintf(stderr, "biss-sim: contention: %llu PRU accesses stalled, %llu cycles\n",
                (unsigned long long)n, (unsigned long long)stall);
    }
    if (o->tape) { /* what the PRU did, not what the models did: none ran */
        bool same = bench_tape_same(b, o->tape);
        sim_print_replay(&res, o->sl_replay, same, o->json);
        if (!same && rc == 0) {
            rc = die("--sl-replay: not the run recorded on %s (its %llu instructions and "
                     "%lld cycles against %llu and %lld here, or other results): run it with "
                     "the options it was recorded with",
                     o->sl_replay, (unsigned long long)o->tape->insns, (long long)o->tape->cycles,
                     (unsigned long long)pru_instructions(bench_core(b)),
                     (long long)pru_cycles(bench_core(b)));
        }
        pruasm_image_free(&img);
        bench_free(b);
        return rc;
    }
    uint32_t built_for = o->pru;
    struct biss_proto_io io = bench_fw_io(b);
    if (fw_mode && bench_fw_status(b).magic == BISS_MAGIC &&
        biss_proto_fw_pru_get(&io, &built_for) == 0 && built_for != o->pru) {
        rc = die("%s was assembled for PRU%u, not PRU%u (one image per PRU: %s)", path, built_for,
                 o->pru, o->pru ? "biss_master_pru1.bin" : "biss_master.bin");
    } else if (fw_mode && bench_fw_status(b).state == BISS_STATE_CFG_ERROR) {
        uint32_t code = bench_fw_status(b).cfg_error;
        rc = die("the firmware refused the configuration (error %u, %s)", code,
                 biss_proto_cfg_error_text(code));
    }
    if (o->svg && sim_write_svg(&res, o->svg, o->svg_frame, err, sizeof(err)) != 0) {
        rc = die("%s", err);
    }
    if (bench_close_vcd(b) != 0) {
        rc = die("error writing the VCD: %s", bench_vcd_error(b));
    }
    if (trace.f) {
        pru_set_trace(bench_core(b), NULL);
        if (safe_file_close(&trace, err, sizeof err) != 0) {
            rc = die("--trace: %s", err);
        }
    }
    if (o->json) {
        cJSON *j = sim_json(&res);
        if (o->encoder && sim_encoder_report(&enc, j) && rc == 0) {
            rc = 5;
        }
        sim_print_json_object(j);
    } else {
        sim_print_text(&res);
        if (o->encoder && sim_encoder_report(&enc, NULL) && rc == 0) {
            rc = 5;
        }
        if (o->vcd) {
            printf("VCD written to %s\n", o->vcd);
        }
        if (o->svg) {
            printf("SVG scope view written to %s\n", o->svg);
        }
    }
    if (rc == 0 && o->cd_set && !cd.done) {
        rc = die("%s: the control frame did not end in time", o->cd_what);
    } else if (rc == 0 && o->cd_set && cd.err != BISS_CD_OK) {
        fprintf(stderr, "biss-sim: %s: %s\n", o->cd_what, biss_cd_strerror(cd.err));
        rc = EXIT_CD;
    }
    uint64_t done = fw_mode ? fc.frames : bench_stats(b)->frames;
    if (rc == 0 && fw_mode && fc.frames == 0 && fc.no_slave && line.beyond_table) {
        char text[512];
        biss_line_text(&line, text, sizeof text);
        fprintf(stderr, "biss-sim: no slave answered: %s\n", text);
    }
    if (rc == 0 && done < o->frames) {
        fprintf(stderr,
                "biss-sim: only %llu of %llu frames completed in %.6g ms of simulated time "
                "(%s)\n",
                (unsigned long long)done, (unsigned long long)o->frames, (double)max_ps / 1e9,
                o->max_ms > 0 ? "the --max-ms limit"
                              : "the limit for these frames; --max-ms sets it");
        rc = EXIT_TIMEOUT;
    }
    if (o->sl_record && bench_tape_finish(b, err, sizeof err) != 0) {
        rc = die("--sl-record: %s", err);
    }
    pruasm_image_free(&img);
    bench_free(b);
    return rc;
}

int main(int argc, char **argv) {
    if (argc == 2 && strcmp(argv[1], "--version") == 0) { /* the project's (CMakeLists.txt) */
        printf("%s %s\n", "biss-sim", BISS_VERSION);
        return 0;
    }
    struct options o;
    int rc = parse_args(argc, argv, &o);
    if (rc) {
        return rc < 0 ? 0 : rc;
    }
    struct sl_tape tape = {0};
    if (o.sl_replay) {
        char err[PATH_MAX + 128];
        if (sl_tape_load(&tape, o.sl_replay, err, sizeof err) != 0) {
            return die("--sl-replay: %s", err);
        }
        o.tape = &tape;
    }
    rc = run(&o);
    if (rc == RUN_AGAIN) {
        o.no_ma_ahead = 1;
        rc = run(&o);
    }
    sl_tape_free(&tape);
    return rc;
}
