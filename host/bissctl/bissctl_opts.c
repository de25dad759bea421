/* bissctl_opts.c - bissctl's command line and help texts. */
#include "bissctl.h"

#include "biss_cd.h"

#include <errno.h>
#include <stdarg.h>
#include <getopt.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#ifndef BISS_FIRMWARE_DIR_TEXT /* host/CMakeLists.txt: the configured BISS_FIRMWARE_DIR */
#define BISS_FIRMWARE_DIR_TEXT "/lib/firmware"
#endif

static const char *const commands[] = {"info",  "read",  "stats",    "run",       "trigger",
                                       "start", "stop",  "reg-read", "reg-write", "command",
                                       "probe", "rates", "encoder",  "record"};

static const char common_help[] =
    "Target:\n"
    "  --target T         emu, am335x, am437x (= am437x-icss0), am437x-icss1; default:\n"
    "                     the board's SoC from the device tree's compatible (ti,am33xx:\n"
    "                     am335x; ti,am4372 or ti,am43: am437x-icss0), else emu, and\n"
    "                     then every output says \"emulated\"\n"
    "  --config FILE      options from FILE, key = value lines named as the long\n"
    "                     options (/etc/biss/pru0.conf; docs/hardware.md); the command\n"
    "                     line's win. Read-only commands still attach to a running master\n"
    "  --pru N            the PRU of that PRU-ICSS: 0 (default) or 1 (its own line)\n"
    "  --devmem PATH      file mapped at the PRU-ICSS base (default /dev/mem)\n"
    "  --attach           use the firmware already running (no load, no restart);\n"
    "                     info, stats, read, record and stop attach by default when\n"
    "                     one runs\n"
    "  --loader L         remoteproc (default: the kernel's pru_rproc loads the ELF) or\n"
    "                     devmem (IRAM and CONTROL written through /dev/mem)\n"
    "  --sysfs DIR        sysfs root (default /sys), also of the device tree\n"
    "                     (DIR/firmware/devicetree/base) the default target comes from\n"
    "  --firmware-dir DIR where remoteproc finds firmware (default /lib/firmware)\n"
    "  --rproc-firmware N firmware name for remoteproc (default biss_master.elf, PRU1\n"
    "                     biss_master_pru1.elf); a PRU in use by another process is\n"
    "                     refused, naming it (the lock is on the memory file)\n"
    "  --firmware FILE    IRAM image (default: $BISS_FIRMWARE, else the build's or the\n"
    "                     installed one for the PRU, in " BISS_FIRMWARE_DIR_TEXT ":\n"
    "                     biss_master.bin for PRU0, biss_master_pru1.bin for PRU1)\n"
    "  --timeout-ms MS    firmware answers and each sample (default 100; emu: simulated)\n"
    "Emulator:\n"
    "  --profile NAME     encoder profile (default tidep0022-test-encoder)\n"
    "  --scenario FILE    JSON scenario file (wins over --profile)\n"
    "  --cable-m M        cable length in metres\n"
    "  --seed S           random seed of the line models\n"
    "Configuration (the slave layout defaults to the emulator profile's):\n"
    "  --freq HZ          MA rate, 100 MHz / H (default 1000000)\n"
    "  --slave D,C,POLY,START[,EW[,POS]]\n"
    "                     one slave (repeat, nearest first): data bits, CRC bits,\n"
    "                     CRC polynomial with its top term (0x43), CRC start, nW bit\n"
    "                     (if the slave has nE/nW; - if not), position bits (at the\n"
    "                     top of the word; default all above nE/nW, or the whole word)\n"
    "  --ssi BITS[,gray]  an SSI encoder instead: its word length, Gray-coded or not\n"
    "  --ssi-delay-ns NS  SSI: the line's round trip (no ACK to measure it by)\n"
    "  --trigger MODE     host, iep, iep-follow, free (default free); iep-follow: the\n"
    "                     IEP period the other PRU's channel (--trigger iep) set up\n"
    "  --iep-period-ns NS frame period for --trigger iep\n"
    "  --proc-limit N     longest processing time accepted, MA clocks, 0..65534\n"
    "                     (default 1000)\n"
    "Line (checked against the rate: TIDEP0022 Table 5, iC-MB4's shortest timeout):\n"
    "  --cable-m M        (above) the cable's length, also on a board\n"
    "  --slave-timeout-ns NS\n"
    "                     the slaves' shortest timeout: refused below 55 % of the MA\n"
    "                     period (iC-MB4 I306)\n"
    "Safety checks (host side, on every frame read; host/README.md):\n"
    "  --check-life S[,BITS]\n"
    "                     slave S's life counter (the BITS at its data word's LSB,\n"
    "                     default its nW bit) must advance by the frames run\n"
    "  --check-pair A,B,TOL[,SHIFT_A,SHIFT_B]\n"
    "                     slaves A and B (two channels: their CRCs must differ) agree\n"
    "                     within TOL counts after shifting their positions left\n"
    "  --check-ew S       slave S never sets nE/nW: a frame where either reads active\n"
    "                     was read one bit off (misframed) and is not valid\n"
    "  --check-speed S,CPS\n"
    "                     slave S's position moves at most CPS counts a second: a\n"
    "                     frame beyond reach of the last one accepted is misframed\n"
    "  --link-warn K[,N]  the link warning (read, record) once K frames in a block\n"
    "                     of N read are marginal: an SL edge seen 2/8 bit or less\n"
    "                     from a sample point (default 1,10000; proto/biss_link.c)\n"
    "  --no-configure     leave the configuration as it is\n"
    "\n"
    "exit status: 0 done, 1 an error (the library's or the target's; a probe that\n"
    "cannot decide, a command withheld, a rate refused), 2 bad usage (also a\n"
    "command that needs --force)\n";

static const char *command_help(const char *command) {
    if (strcmp(command, "info") == 0) {
        return "bissctl [options] info [--ms MS]\n"
               "  Firmware state, configuration ack and error, counters. On the emulator\n"
               "  the master starts with the command: it runs MS ms first (default 100,\n"
               "  simulated), and the counters are of those.\n";
    }
    if (strcmp(command, "read") == 0) {
        return "bissctl [options] read [-n N] [--json]\n"
               "  Prints N published frames (default 1), one line each: frame (1 is the\n"
               "  first, a training frame after each configuration), flags,\n"
               "  per slave position, data, nE/nW, CRC (\"none\" where the layout has\n"
               "  none); line delay, sample point (where in a bit, in eighths, it is read),\n"
               "  lag (how many MA periods after the clock that made a bit it is read), the\n"
               "  eye (how near, in eighths of a bit, the nearest SL edge seen came to a\n"
               "  sample point: 4 on a clean line, 3 with the ACK's rounding, 2 or less a\n"
               "  marginal frame; off-grid: an edge within 2/8 before one or 1/8 after it,\n"
               "  refused below 10 MHz)\n"
               "  and link-warning (marginal frames: 1 in a block of 10000 frames read),\n"
               "  the IEP timestamp (counts of 5 ns) and the time it stands for; after\n"
               "  the last, the link's counts (link: eye mean and least, marginal frames).\n"
               "  In host-trigger mode each frame is triggered first. With safety checks\n"
               "  (--check-life, --check-pair, --check-ew, --check-speed) each frame's verdicts "
               "and, after\n"
               "  the last, their counts. --json: one JSON object, {\"frames\": [...], \"safety\": "
               "{...}}.\n";
    }
    if (strcmp(command, "record") == 0) {
        return "bissctl [options] record [--seconds S] [--poll-ms MS] [--format csv|npy] FILE\n"
               "  Records every frame for S seconds (default 1; emu: simulated) into FILE,\n"
               "  read from the firmware's result ring every MS ms (default 1, down to\n"
               "  0.01): CSV (a header line, then a line a frame) or NumPy's .npy (a\n"
               "  structured array, numpy.load(FILE)), by --format or else FILE's\n"
               "  extension (.npy; anything else CSV). Columns: seq (the publication\n"
               "  number: consecutive unless frames were lost), timestamp (IEP counts of\n"
               "  5 ns), flags, valid, link_eye (eighths of a bit, -1 not measured: read\n"
               "  --help), link_warning, and per slave sN_position, sN_data, sN_error,\n"
               "  sN_warning, sN_crc_ok. The ring keeps 59 frames of one slave, 17 of\n"
               "  eight: at 10 MHz 1.3 ms of the default encoder, 0.5 ms of the AD38's\n"
               "  three (poll it every 0.25 ms). Progress on stderr once a second; at the\n"
               "  end the frames recorded and lost. Frames the ring no longer held when\n"
               "  read are lost, counted and reported: exit status 1 if any were.\n";
    }
    if (strcmp(command, "stats") == 0) {
        return "bissctl [options] stats [--ms MS]\n"
               "  Frame, CRC error, no-slave, processing-time error and training counters.\n"
               "  On the emulator the master runs MS ms first (default 100, simulated).\n";
    }
    if (strcmp(command, "run") == 0) {
        return "bissctl [options] run [--ms MS]\n"
               "  Lets the master run for MS ms (default 100; emu: simulated), then prints\n"
               "  the counters and the line delay.\n";
    }
    if (strcmp(command, "trigger") == 0) {
        return "bissctl [options] trigger\n"
               "  Host-trigger mode: starts one frame and prints it.\n";
    }
    if (strcmp(command, "start") == 0) {
        return "bissctl [options] start\n"
               "  Loads and starts the firmware (restarting ours if it runs), applies the\n"
               "  configuration (options or --config FILE) and leaves the master running\n"
               "  after bissctl exits: read, info and stats then attach to it, as\n"
               "  applications do (libbiss, attach); bissctl stop stops it. What the\n"
               "  systemd unit biss-master@pru0 runs at boot. (The emulated master ends\n"
               "  with bissctl.)\n";
    }
    if (strcmp(command, "stop") == 0) {
        return "bissctl [options] stop\n"
               "  Stops the running master (halts its PRU); nothing running is no error.\n";
    }
    if (strcmp(command, "reg-read") == 0) {
        return "bissctl [options] reg-read [--id ID] ADDR [-n N] [--dump]\n"
               "  Reads N registers (default 1, at most 64) from ADDR (0x00..0x7F) of the\n"
               "  slave with control-frame ID (default 0), through CDM/CDS: one line per\n"
               "  register, or with --dump a hex dump (16 a line, with ASCII).\n";
    }
    if (strcmp(command, "command") == 0) {
        return "bissctl [options] command IDS CMD [--ida-test] [--force]\n"
               "  Sends BiSS command CMD (0..3) to the slaves in the ID mask IDS (bit i =\n"
               "  ID i; 0 = all, a broadcast without acknowledge); prints what it does and\n"
               "  the IDA answers. --ida-test: the firmware checks them before the execute\n"
               "  bit and withholds the command unless they equal IDS (exit status 1,\n"
               "  'withheld'). A command that changes how an encoder works (switches\n"
               "  something off, bypass, reserved, the maker's own) is refused (exit\n"
               "  status 2) unless --force is given. What each does:\n";
    }
    if (strcmp(command, "probe") == 0) {
        return "bissctl [options] probe [-n N] [--time-limit S] [FILE.json]\n"
               "  Finds an unknown encoder's layout: captures N raw frames (default 1024) in\n"
               "  a capture layout (8 x 64 bits, no CRC), finds where the data ends and\n"
               "  which data + CRC split (3..16 bits, any polynomial and start) fits the\n"
               "  frames, per slave of a chain; on the frames every CRC fits (the others\n"
               "  are set aside as noise, and counted) it finds life counters and nE/nW;\n"
               "  reads the identification registers (0x78..0x7F, 0x41..0x47). Prints the\n"
               "  candidates with a verdict, a --slave line and a scenario for biss-sim\n"
               "  (into FILE). The whole probe stops after S seconds (default 60; a\n"
               "  decimal fraction allowed), the search also after a fixed amount of work\n"
               "  (the same on every machine); a search stopped early is reported, never\n"
               "  unique. Progress goes to stderr about once a second on a long search.\n"
               "  Exit status 1 when it cannot decide or the result is ambiguous.\n";
    }
    if (strcmp(command, "rates") == 0) {
        return "bissctl [options] rates [--round-trip-ns NS]\n"
               "  The MA rates a line allows, from what is known of it: --cable-m, a\n"
               "  measured round trip (--round-trip-ns, as read prints delay_ns), the\n"
               "  slaves' --slave-timeout-ns. Prints TIDEP0022 Table 5 and rates_hz=, the\n"
               "  rates the firmware clocks exactly that the line allows, fastest first;\n"
               "  with --freq the verdict on that rate (exit status 1 if refused). Needs\n"
               "  no target.\n";
    }
    if (strcmp(command, "encoder") == 0) {
        return "bissctl [options] encoder start CHAIN | status | ew SLAVE [error] [warning] | "
               "stop\n"
               "  The encoder firmware (a BiSS-C slave chain, pru_slave/README.md) on a PRU\n"
               "  of the board, PRU1 unless --pru says otherwise: the other end of the\n"
               "  one-board loop (docs/hardware.md, \"One board, both ends\"). start loads\n"
               "  it (--firmware names another image; --loader as for the master), takes\n"
               "  the chain CHAIN, a scenario file (JSON, emulator/slave/MODELS.md) or a\n"
               "  profile name, with its register files, and leaves it running; a chain\n"
               "  that moves with time moves by counts per frame (at a 50 us frame: give\n"
               "  counts_per_frame in the scenario to choose). status prints what it did\n"
               "  (frames, control communication); ew sends slave SLAVE's nE and nW\n"
               "  active (error, warning) or inactive (not named) from the next frame;\n"
               "  stop halts its PRU. Not on the emulator, where biss-sim --encoder runs\n"
               "  the loop.\n";
    }
    if (strcmp(command, "reg-write") == 0) {
        return "bissctl [options] reg-write [--id ID] ADDR BYTE...\n"
               "  Writes the bytes to ADDR, ADDR+1, ... of the slave with control-frame\n"
               "  ID (default 0). A read-only register ignores it: read it back.\n";
    }
    return NULL;
}

/* The BiSS command table (proto/biss_cd_cmd.c) with its source. */
static void print_command_table(void) {
    for (int broadcast = 1; broadcast >= 0; broadcast--) {
        for (unsigned cmd = 0; cmd < 4; cmd++) {
            const biss_cd_cmd_info *c = biss_cd_cmd_effect(broadcast ? 0 : 1, cmd);
            printf("    %s %u (%u%u): %s%s\n",
                   broadcast ? "broadcast (IDS 0)" : "addressed        ", cmd, cmd >> 1, cmd & 1u,
                   c->effect, c->changes_encoder ? " [--force]" : "");
        }
    }
    printf("  Source: %s.\n", biss_cd_cmd_source);
}

void bissctl_usage(const char *command) {
    const char *h = command ? command_help(command) : NULL;
    if (h) {
        printf("%s", h);
        if (strcmp(command, "command") == 0) {
            print_command_table();
        }
        printf("\n%s", common_help);
        return;
    }
    printf("usage: bissctl [options] COMMAND [command options]\n"
           "BiSS-C master on a PRU (emulated or real) through libbiss.\n"
           "Commands: info, read [-n N], stats, run [--ms MS], trigger, start, stop,\n"
           "          reg-read ADDR [-n N], reg-write ADDR BYTE..., command IDS CMD [--force],\n"
           "          probe [-n N] [--time-limit S] [FILE.json], rates,\n"
           "          record [--seconds S] [--poll-ms MS] FILE.csv|FILE.npy,\n"
           "          encoder start CHAIN|status|ew SLAVE [error] [warning]|stop\n"
           "          (the encoder firmware, PRU1)\n"
           "          (also spelt reg read, reg write, cmd; bissctl COMMAND --help for each)\n\n%s",
           common_help);
}

/* "FILE:LINE" while a --config file is read: errors name the line */
static const char *error_at;
/* the command, once known: the help a usage error points to is its own */
static const char *help_command;

int bissctl_usage_error(const char *fmt, ...) {
    va_list ap;
    va_start(ap, fmt);
    fprintf(stderr, "bissctl: ");
    if (error_at) {
        fprintf(stderr, "%s: ", error_at);
    }
    vfprintf(stderr, fmt, ap);
    va_end(ap);
    fprintf(stderr, "\nTry 'bissctl%s%s --help' for more information.\n", help_command ? " " : "",
            help_command ? help_command : "");
    return BISSCTL_USAGE;
}

static int parse_ulong(const char *s, unsigned long long max, unsigned long long *v) {
    if (!s || !*s || *s == '-') {
        return -1;
    }
    char *end;
    errno = 0;
    unsigned long long x = strtoull(s, &end, 0);
    if (errno || *end || x > max) {
        return -1;
    }
    *v = x;
    return 0;
}

static int parse_u32(const char *s, uint32_t *v) {
    unsigned long long x;
    if (parse_ulong(s, 0xffffffffu, &x)) {
        return -1;
    }
    *v = (uint32_t)x;
    return 0;
}

static int parse_unsigned(const char *s, unsigned *v) {
    uint32_t x;
    if (parse_u32(s, &x)) {
        return -1;
    }
    *v = x;
    return 0;
}

int bissctl_parse_byte(const char *s, unsigned max, uint8_t *v) {
    unsigned long long x;
    if (parse_ulong(s, max, &x)) {
        return -1;
    }
    *v = (uint8_t)x;
    return 0;
}

/* D,C,POLY,START[,EW[,POS]]; EW "-": no nE/nW (a POS may follow) */
static int parse_slave(const char *arg, struct biss_slave_config *s) {
    char buf[128];
    if (snprintf(buf, sizeof buf, "%s", arg) >= (int)sizeof buf) {
        return -1;
    }
    uint32_t f[6];
    int n = 0;
    bool no_ew = false;
    for (char *save = NULL, *tok = strtok_r(buf, ",", &save); tok;
         tok = strtok_r(NULL, ",", &save)) {
        if (n == 4 && strcmp(tok, "-") == 0) {
            no_ew = true;
            f[n++] = 0;
            continue;
        }
        if (n == 6 || parse_u32(tok, &f[n])) {
            return -1;
        }
        n++;
    }
    if (n < 4 || (no_ew && n == 5)) {
        return -1;
    }
    *s = (struct biss_slave_config){
        .data_bits = f[0],
        .crc_bits = f[1],
        .crc_poly = f[2],
        .crc_start = f[3],
        .has_ew = n >= 5 && !no_ew,
        .ew_shift = n >= 5 ? f[4] : 0,
        .pos_bits = n >= 6 ? f[5] : 0,
    };
    return 0;
}

enum {
    OPT_TARGET = 256,
    OPT_DEVMEM,
    OPT_ATTACH,
    OPT_FIRMWARE,
    OPT_TIMEOUT,
    OPT_PROFILE,
    OPT_SCENARIO,
    OPT_CABLE,
    OPT_SEED,
    OPT_FREQ,
    OPT_SLAVE,
    OPT_SSI,
    OPT_SSI_DELAY,
    OPT_TRIGGER,
    OPT_IEP,
    OPT_PROC,
    OPT_CHECK_LIFE,
    OPT_CHECK_EW,
    OPT_CHECK_SPEED,
    OPT_LINK_WARN,
    OPT_CHECK_PAIR,
    OPT_NOCONF,
    OPT_MS,
    OPT_ID,
    OPT_DUMP,
    OPT_IDA_TEST,
    OPT_JSON,
    OPT_LOADER,
    OPT_SYSFS,
    OPT_FWDIR,
    OPT_RPROC_FW,
    OPT_PRU,
    OPT_SLAVE_TIMEOUT,
    OPT_ROUND_TRIP,
    OPT_CONFIG,
    OPT_FORCE,
    OPT_TIME_LIMIT,
    OPT_SECONDS,
    OPT_POLL_MS,
    OPT_FORMAT,
};

static const struct option long_opts[] = {
    {"target", required_argument, NULL, OPT_TARGET},
    {"devmem", required_argument, NULL, OPT_DEVMEM},
    {"attach", no_argument, NULL, OPT_ATTACH},
    {"firmware", required_argument, NULL, OPT_FIRMWARE},
    {"timeout-ms", required_argument, NULL, OPT_TIMEOUT},
    {"profile", required_argument, NULL, OPT_PROFILE},
    {"scenario", required_argument, NULL, OPT_SCENARIO},
    {"cable-m", required_argument, NULL, OPT_CABLE},
    {"seed", required_argument, NULL, OPT_SEED},
    {"freq", required_argument, NULL, OPT_FREQ},
    {"slave", required_argument, NULL, OPT_SLAVE},
    {"ssi", required_argument, NULL, OPT_SSI},
    {"ssi-delay-ns", required_argument, NULL, OPT_SSI_DELAY},
    {"trigger", required_argument, NULL, OPT_TRIGGER},
    {"iep-period-ns", required_argument, NULL, OPT_IEP},
    {"proc-limit", required_argument, NULL, OPT_PROC},
    {"check-life", required_argument, NULL, OPT_CHECK_LIFE},
    {"check-ew", required_argument, NULL, OPT_CHECK_EW},
    {"check-speed", required_argument, NULL, OPT_CHECK_SPEED},
    {"link-warn", required_argument, NULL, OPT_LINK_WARN},
    {"check-pair", required_argument, NULL, OPT_CHECK_PAIR},
    {"no-configure", no_argument, NULL, OPT_NOCONF},
    {"ms", required_argument, NULL, OPT_MS},
    {"id", required_argument, NULL, OPT_ID},
    {"dump", no_argument, NULL, OPT_DUMP},
    {"ida-test", no_argument, NULL, OPT_IDA_TEST},
    {"json", no_argument, NULL, OPT_JSON},
    {"loader", required_argument, NULL, OPT_LOADER},
    {"sysfs", required_argument, NULL, OPT_SYSFS},
    {"firmware-dir", required_argument, NULL, OPT_FWDIR},
    {"rproc-firmware", required_argument, NULL, OPT_RPROC_FW},
    {"pru", required_argument, NULL, OPT_PRU},
    {"slave-timeout-ns", required_argument, NULL, OPT_SLAVE_TIMEOUT},
    {"round-trip-ns", required_argument, NULL, OPT_ROUND_TRIP},
    {"config", required_argument, NULL, OPT_CONFIG},
    {"force", no_argument, NULL, OPT_FORCE},
    {"time-limit", required_argument, NULL, OPT_TIME_LIMIT},
    {"seconds", required_argument, NULL, OPT_SECONDS},
    {"poll-ms", required_argument, NULL, OPT_POLL_MS},
    {"format", required_argument, NULL, OPT_FORMAT},
    {"help", no_argument, NULL, 'h'},
    {NULL, 0, NULL, 0},
};

static int parse_cable(const char *arg, double *m) {
    char *end;
    errno = 0;
    double v = strtod(arg, &end);
    if (errno || *end || end == arg || !(v >= 0 && v <= 1000)) {
        return -1;
    }
    *m = v;
    return 0;
}

/* A round trip in ns, 0..1 ms. */
static int parse_cable_ns(const char *arg, double *ns) {
    char *end;
    errno = 0;
    double v = strtod(arg, &end);
    if (errno || *end || end == arg || !(v >= 0 && v <= 1e6)) {
        return -1;
    }
    *ns = v;
    return 0;
}

/* Seconds (a decimal fraction allowed) as ms, 1 ms .. a day. */
/* A decimal number in lo..hi, times scale, rounded: --seconds and
 * --time-limit to ms (0.001..86400 s), --poll-ms to us (0.01..60000 ms). */
static int parse_scaled(const char *arg, double lo, double hi, double scale, unsigned *out) {
    char *end;
    errno = 0;
    double v = strtod(arg, &end);
    if (errno || *end || end == arg || !(v >= lo && v <= hi)) {
        return -1;
    }
    *out = (unsigned)(v * scale + 0.5);
    return 0;
}

static int parse_seconds(const char *arg, unsigned *ms) {
    return parse_scaled(arg, 0.001, 86400, 1000.0, ms);
}

/* BITS[,gray] */
static int parse_ssi(const char *arg, struct biss_slave_config *s) {
    char buf[32];
    if (snprintf(buf, sizeof buf, "%s", arg) >= (int)sizeof buf) {
        return -1;
    }
    char *comma = strchr(buf, ',');
    bool gray = false;
    if (comma) {
        *comma = '\0';
        if (strcmp(comma + 1, "gray")) {
            return -1;
        }
        gray = true;
    }
    uint32_t bits;
    if (parse_u32(buf, &bits)) {
        return -1;
    }
    *s = (struct biss_slave_config){.data_bits = bits, .ssi = true, .gray = gray};
    return 0;
}

/* Target options */
static int take_target_opt(int c, const char *arg, struct bissctl_opts *o) {
    unsigned long long v;
    switch (c) {
    case OPT_TARGET:
        o->target_given = true;
        return biss_target_from_name(arg, &o->open.target)
                   ? bissctl_usage_error("unknown target '%s' (emu, am335x, am437x, am437x-icss0, "
                                         "am437x-icss1)",
                                         arg)
                   : 0;
    case OPT_DEVMEM:
        o->open.devmem = arg;
        return 0;
    case OPT_PRU:
        if (strcmp(arg, "0") != 0 && strcmp(arg, "1") != 0) {
            return bissctl_usage_error("--pru '%s': expected 0 or 1", arg);
        }
        o->open.pru = (unsigned)(arg[0] - '0');
        o->pru_given = true;
        return 0;
    case OPT_ATTACH:
        o->open.attach = true;
        o->attach_given = true;
        return 0;
    case OPT_LOADER:
        return biss_loader_from_name(arg, &o->open.loader)
                   ? bissctl_usage_error("--loader '%s': expected remoteproc or devmem", arg)
                   : 0;
    case OPT_SYSFS:
        o->open.sysfs_root = arg;
        return 0;
    case OPT_FWDIR:
        o->open.firmware_dir = arg;
        return 0;
    case OPT_RPROC_FW:
        o->open.rproc_firmware = arg;
        return 0;
    case OPT_FIRMWARE:
        o->open.firmware = arg;
        return 0;
    case OPT_TIMEOUT:
        if (parse_unsigned(arg, &o->timeout_ms) || o->timeout_ms == 0) {
            return bissctl_usage_error("--timeout-ms '%s': expected a positive number", arg);
        }
        o->open.timeout_ms = o->timeout_ms;
        return 0;
    case OPT_PROFILE:
        o->open.profile = arg;
        return 0;
    case OPT_SCENARIO:
        o->open.scenario_file = arg;
        return 0;
    case OPT_CABLE:
        return parse_cable(arg, &o->open.cable_m)
                   ? bissctl_usage_error("--cable-m '%s': expected metres, 0..1000", arg)
                   : 0;
    case OPT_SEED:
        if (parse_ulong(arg, ~0ull, &v)) {
            return bissctl_usage_error("--seed '%s': expected a number", arg);
        }
        o->open.seed = v;
        o->open.set_seed = true;
        return 0;
    }
    return 1; /* not a target option */
}

/* Configuration options */
static int take_config_opt(int c, const char *arg, struct bissctl_opts *o) {
    struct biss_config *cfg = &o->cfg;
    if (c < OPT_FREQ || c > OPT_CHECK_PAIR) {
        return 1; /* not a configuration option */
    }
    o->config_given = o->config_given || !error_at; /* the command line's, not a file's */
    switch (c) {
    case OPT_FREQ:
        return parse_u32(arg, &cfg->freq_hz) ? bissctl_usage_error("--freq '%s': expected Hz", arg)
                                             : 0;
    case OPT_SLAVE:
        if (!o->slaves_given || o->slaves_from_file) { /* the command line's replace a file's */
            cfg->nslaves = 0;
            o->slaves_given = true;
            o->slaves_from_file = false;
        }
        if (cfg->nslaves == BISS_API_MAX_SLAVES) {
            return bissctl_usage_error("--slave %s: at most 8 slaves", arg);
        }
        return parse_slave(arg, &cfg->slave[cfg->nslaves++])
                   ? bissctl_usage_error("--slave '%s': expected D,C,POLY,START[,EW[,POS]]", arg)
                   : 0;
    case OPT_SSI:
        if (o->slaves_from_file) {
            o->slaves_given = o->slaves_from_file = false;
        }
        if (o->slaves_given) {
            return bissctl_usage_error("--ssi %s: an SSI encoder is alone on its line (no --slave)",
                                       arg);
        }
        o->slaves_given = true;
        cfg->nslaves = 1;
        return parse_ssi(arg, &cfg->slave[0])
                   ? bissctl_usage_error("--ssi '%s': expected BITS[,gray]", arg)
                   : 0;
    case OPT_SSI_DELAY:
        return parse_u32(arg, &cfg->ssi_delay_ns)
                   ? bissctl_usage_error("--ssi-delay-ns '%s': expected ns", arg)
                   : 0;
    case OPT_TRIGGER:
        return biss_trigger_from_name(arg, &cfg->trigger)
                   ? bissctl_usage_error("--trigger '%s': expected host, iep or free", arg)
                   : 0;
    case OPT_IEP:
        return parse_u32(arg, &cfg->iep_period_ns)
                   ? bissctl_usage_error("--iep-period-ns '%s': expected ns", arg)
                   : 0;
    case OPT_PROC:
        return parse_u32(arg, &cfg->proc_limit)
                   ? bissctl_usage_error("--proc-limit '%s': expected MA clocks", arg)
                   : 0;
    case OPT_CHECK_LIFE:
        return biss_safety_parse_life(arg, &o->checks)
                   ? bissctl_usage_error(
                         "--check-life '%s': expected S[,BITS] (slave 0..7, 1..32 bits)", arg)
                   : 0;
    case OPT_CHECK_EW:
        return biss_safety_parse_ew(arg, &o->checks)
                   ? bissctl_usage_error("--check-ew '%s': expected S (slave 0..7)", arg)
                   : 0;
    case OPT_LINK_WARN:
        return biss_link_parse(arg, &o->link_warn, &o->link_window)
                   ? bissctl_usage_error("--link-warn '%s': expected K[,N] (K marginal frames "
                                         "in a block of N, both >= 1)",
                                         arg)
                   : 0;
    case OPT_CHECK_SPEED:
        return biss_safety_parse_speed(arg, &o->checks)
                   ? bissctl_usage_error(
                         "--check-speed '%s': expected S,CPS (slave 0..7, counts per "
                         "second 1e-9..1e18)",
                         arg)
                   : 0;
    case OPT_CHECK_PAIR:
        switch (biss_safety_parse_pair(arg, &o->checks)) {
        case BISS_OK:
            return 0;
        case BISS_E_SAFETY_PAIR:
            return bissctl_usage_error("--check-pair %s: at most 4 pairs", arg);
        default:
            return bissctl_usage_error(
                "--check-pair '%s': expected A,B,TOL[,SHIFT_A,SHIFT_B] (slaves "
                "0..7, shifts 0..63)",
                arg);
        }
    }
    return 1;
}

static int take_command_opt(int c, const char *arg, struct bissctl_opts *o) {
    switch (c) {
    case 'n':
        if (parse_unsigned(arg, &o->count) || o->count == 0) {
            return bissctl_usage_error("-n '%s': expected a positive count", arg);
        }
        return 0;
    case OPT_MS:
        return parse_unsigned(arg, &o->run_ms) ? bissctl_usage_error("--ms '%s': expected ms", arg)
                                               : 0;
    case OPT_ID:
        if (parse_unsigned(arg, &o->id) || o->id > 7) {
            return bissctl_usage_error("--id '%s': expected 0..7", arg);
        }
        return 0;
    case OPT_NOCONF:
        o->no_configure = true;
        return 0;
    case OPT_DUMP:
        o->dump = true;
        return 0;
    case OPT_IDA_TEST:
        o->ida_test = true;
        return 0;
    case OPT_JSON:
        o->json = true;
        return 0;
    case OPT_SLAVE_TIMEOUT:
        if (parse_u32(arg, &o->slave_timeout_ns) || o->slave_timeout_ns == 0) {
            return bissctl_usage_error("--slave-timeout-ns '%s': expected ns, above 0", arg);
        }
        return 0;
    case OPT_ROUND_TRIP:
        if (parse_cable_ns(arg, &o->round_trip_ns)) {
            return bissctl_usage_error("--round-trip-ns '%s': expected ns, 0..1000000", arg);
        }
        return 0;
    case OPT_FORCE:
        o->force = true;
        return 0;
    case OPT_TIME_LIMIT:
        return parse_seconds(arg, &o->time_limit_ms)
                   ? bissctl_usage_error("--time-limit '%s': expected seconds, 0.001..86400", arg)
                   : 0;
    case OPT_SECONDS:
        return parse_seconds(arg, &o->record_ms)
                   ? bissctl_usage_error("--seconds '%s': expected seconds, 0.001..86400", arg)
                   : 0;
    case OPT_POLL_MS:
        return parse_scaled(arg, 0.01, 60000, 1000.0, &o->poll_us)
                   ? bissctl_usage_error("--poll-ms '%s': expected ms, 0.01..60000", arg)
                   : 0;
    case OPT_FORMAT:
        if (strcmp(arg, "csv") && strcmp(arg, "npy")) {
            return bissctl_usage_error("--format '%s': expected csv or npy", arg);
        }
        o->format = arg;
        return 0;
    case 'h':
        o->help = true;
        return 0;
    }
    return 1;
}

static int known_command(const char *s) {
    for (size_t i = 0; i < sizeof commands / sizeof commands[0]; i++) {
        if (strcmp(s, commands[i]) == 0) {
            return 1;
        }
    }
    return 0;
}

static int take_opt(int c, const char *arg, struct bissctl_opts *o) {
    int rc = take_target_opt(c, arg, o);
    if (rc == 1) {
        rc = take_config_opt(c, arg, o);
    }
    if (rc == 1) {
        rc = take_command_opt(c, arg, o);
    }
    return rc;
}

/* What a configuration file may set: the target and the configuration,
 * not a command's own options, --attach or another --config. */
static bool file_option(int c) {
    return (c >= OPT_TARGET && c <= OPT_CHECK_PAIR && c != OPT_ATTACH) || c == OPT_LOADER ||
           c == OPT_SYSFS || c == OPT_FWDIR || c == OPT_RPROC_FW || c == OPT_PRU;
}

int bissctl_set_option(const char *key, const char *value, const char *at, struct bissctl_opts *o) {
    const struct option *opt = NULL;
    for (size_t i = 0; long_opts[i].name; i++) {
        if (strcmp(long_opts[i].name, key) == 0) {
            opt = &long_opts[i];
        }
    }
    error_at = at;
    int rc;
    if (!opt) {
        rc = bissctl_usage_error("unknown key '%s' (keys are bissctl's long options, without "
                                 "the dashes)",
                                 key);
    } else if (!file_option(opt->val)) {
        rc = bissctl_usage_error("'%s' is a command's option, not a configuration key", key);
    } else if (!value || !*value) {
        rc = bissctl_usage_error("'%s' needs a value (key = value)", key);
    } else {
        rc = take_opt(opt->val, value, o);
    }
    error_at = NULL;
    return rc;
}

/* The --config FILE on the command line, if any (the last one): read
 * before the other options, which then win over it. It looks at a copy of
 * argv: getopt_long permutes what it scans, and "info --freq" (a value
 * missing) would come back as "--freq info". */
static const char *config_file(int argc, char **argv) {
    const char *path = NULL;
    char **copy = malloc(((size_t)argc + 1) * sizeof *copy);
    if (!copy) {
        return NULL;
    }
    memcpy(copy, argv, ((size_t)argc + 1) * sizeof *copy);
    opterr = 0;
    optind = 0; /* glibc: a full restart of getopt */
    for (int c; (c = getopt_long(argc, copy, ":n:h", long_opts, NULL)) != -1;) {
        if (c == OPT_CONFIG) {
            path = optarg;
        }
    }
    free(copy);
    return path;
}

int bissctl_parse(int argc, char **argv, struct bissctl_opts *o) {
    memset(o, 0, sizeof *o);
    biss_open_params_default(&o->open);
    biss_config_default(&o->cfg);
    o->count = 1;
    o->run_ms = 100;
    o->record_ms = 1000;
    o->poll_us = 1000;
    o->timeout_ms = 100;
    o->round_trip_ns = -1;
    o->open.errbuf = o->errbuf;
    o->open.errbuf_len = sizeof o->errbuf;
    o->config_file = config_file(argc, argv);
    if (o->config_file) {
        int rc = bissctl_conf_read(o->config_file, o);
        if (rc) {
            return rc;
        }
        o->slaves_from_file = o->slaves_given;
    }
    opterr = 0;
    optind = 0;
    int c;
    while ((c = getopt_long(argc, argv, ":n:h", long_opts, NULL)) != -1) {
        if (c == '?') {
            return bissctl_usage_error("unknown option '%s'", argv[optind - 1]);
        }
        if (c == ':') {
            return bissctl_usage_error("option '%s' needs a value", argv[optind - 1]);
        }
        int rc = c == OPT_CONFIG ? 0 : take_opt(c, optarg, o); /* --config: read above */
        if (rc) {
            return rc;
        }
    }
    if (optind < argc) {
        o->command = argv[optind++];
        /* the spellings "reg read", "reg write" and "cmd" as well */
        if (strcmp(o->command, "reg") == 0 && optind < argc &&
            (strcmp(argv[optind], "read") == 0 || strcmp(argv[optind], "write") == 0)) {
            o->command = strcmp(argv[optind++], "read") == 0 ? "reg-read" : "reg-write";
        } else if (strcmp(o->command, "cmd") == 0) {
            o->command = "command";
        }
        if (!known_command(o->command)) {
            return bissctl_usage_error("unknown command '%s'", o->command);
        }
        help_command = o->command;
    }
    o->args = argv + optind;
    o->nargs = argc - optind;
    bool takes_args =
        o->command && (strncmp(o->command, "reg-", 4) == 0 || strcmp(o->command, "command") == 0 ||
                       strcmp(o->command, "probe") == 0 || strcmp(o->command, "encoder") == 0 ||
                       strcmp(o->command, "record") == 0);
    if (o->nargs > 0 && !takes_args) {
        return bissctl_usage_error("unexpected argument '%s'", argv[optind]);
    }
    if (!o->command && !o->help) {
        return bissctl_usage_error("%s", "no command given");
    }
    /* a layout from the command line takes the checks now (to be checked
     * with it); the profile's takes them when the emulator gives it */
    if (o->slaves_given && biss_safety_merge(&o->cfg, &o->checks)) {
        return bissctl_usage_error("%s", "at most 4 --check-pair in all");
    }
    return BISSCTL_OK;
}
