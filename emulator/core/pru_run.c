/*
 * pru-run - run a raw PRU IRAM image on one emulated PRU from PC 0 until HALT.
 *
 * Exit status (README "Conventions"): 0 halted, 1 an unreadable or unfit
 * file, 2 bad usage, 3 fault, 124 no HALT within --max-cycles.
 */
#include "pru_core.h"
#include "read_file.h"

#include <ctype.h>
#include <errno.h>
#include <getopt.h>
#include <inttypes.h>
#include <stdarg.h>
#include <stdlib.h>
#include <stdio.h>
#include <string.h>

#define EXIT_USAGE         2
#define EXIT_NOHALT        124 /* as timeout(1): the limit ran out first */
#define EXIT_FAULT         3
#define DEFAULT_MAX_CYCLES 2000000000LL

struct opts {
    const char *image, *data;
    enum pru_soc soc;
    int64_t max_cycles;
    uint32_t inputs;
    int dump_regs, trace;
    struct pru_params params;
};

static void usage(FILE *f) {
    fprintf(f,
            "usage: pru-run [options] IMAGE.bin\n"
            "Runs a raw little-endian PRU IRAM image on one emulated PRU (PRU0) from\n"
            "PC 0 until HALT.\n"
            "\n"
            "  --max-cycles N   stop after N cycles (default %lld); exit 124 if not halted\n"
            "  --soc NAME       am335x (default), am437x-icss0, am437x-icss1\n"
            "  --data FILE      initial contents of PRU0 data RAM (from address 0)\n"
            "  --inputs VALUE   constant GPI input levels R31[29:0] (default 0)\n"
            "  --dump-regs      print r0..r31, pc, cycles, instructions after the run\n"
            "  --trace          print every executed instruction to stderr\n"
            "  --strict[=RULES] stop with a fault report on a construct of uncertain silicon\n"
            "                   behaviour (docs/silicon-assumptions.md): RULES is a comma\n"
            "                   list of loop1, loop0, loopfield, mvi, dram, spad (default: all)\n"
            "  --strict-scope S clocked (default: between two R30 changes at most\n"
            "                   --strict-window cycles apart) or all (every instruction)\n"
            "  --strict-window N  cycles (default %u)\n"
            "  --strict-log     record every violation and run on; list them at the end\n"
            "                   (exit 3 if there was one)\n"
            "  --contend K,S[,periodic[:PHASE]|random[:SEED]]\n"
            "                   a host reads the data RAM every K cycles; a PRU load/store\n"
            "                   meeting one stalls S cycles (emulator/core/TIMING.md)\n"
            "  --no-fast-path P run without the fast path P (the same results, only\n"
            "                   slower): ff (all), ff-counted, ff-r31-bits, ff-loop-delay,\n"
            "                   ff-count-loop (emulator/core/TIMING.md \"Fast-forward\"),\n"
            "                   fast-loop (the threaded loop: every instruction the general way),\n"
            "                   leaf-call (delay calls replayed from a memo),\n"
            "                   straight-run (runs of register-only instructions without\n"
            "                   the checks between them)\n"
            "  --help           this text\n"
            "\n"
            "exit status: 0 halted, 1 an unreadable or unfit file, 2 bad usage, 3 fault,\n"
            "124 no HALT within the cycle limit\n",
            (long long)DEFAULT_MAX_CYCLES, PRU_STRICT_DEFAULT_WINDOW);
}

/* A whole number, decimal or with a C prefix (0x...), 0..2^64-1: no sign,
 * no spaces, nothing after it. */
static int parse_u64(const char *s, uint64_t *out) {
    char *end;
    errno = 0;
    if (!s || !isdigit((unsigned char)*s))
        return -1;
    unsigned long long v = strtoull(s, &end, 0);
    if (errno || *end)
        return -1;
    *out = v;
    return 0;
}

/* A usage error in the tools' one form (README "Conventions"); returns -1. */
__attribute__((format(printf, 1, 2))) static int bad(const char *fmt, ...) {
    va_list ap;
    va_start(ap, fmt);
    fprintf(stderr, "pru-run: ");
    vfprintf(stderr, fmt, ap);
    va_end(ap);
    fprintf(stderr, "\nTry 'pru-run --help' for more information.\n");
    return -1;
}

enum {
    OPT_DUMP_REGS = 256,
    OPT_TRACE,
    OPT_STRICT,
    OPT_STRICT_SCOPE,
    OPT_STRICT_WINDOW,
    OPT_STRICT_LOG,
    OPT_CONTEND,
    OPT_NO_FAST_PATH,
    OPT_MAX_CYCLES,
    OPT_SOC,
    OPT_DATA,
    OPT_INPUTS,
};

static const struct option long_opts[] = {
    {"help", no_argument, NULL, 'h'},
    {"dump-regs", no_argument, NULL, OPT_DUMP_REGS},
    {"trace", no_argument, NULL, OPT_TRACE},
    {"strict", optional_argument, NULL, OPT_STRICT},
    {"strict-scope", required_argument, NULL, OPT_STRICT_SCOPE},
    {"strict-window", required_argument, NULL, OPT_STRICT_WINDOW},
    {"strict-log", no_argument, NULL, OPT_STRICT_LOG},
    {"contend", required_argument, NULL, OPT_CONTEND},
    {"no-fast-path", required_argument, NULL, OPT_NO_FAST_PATH},
    {"max-cycles", required_argument, NULL, OPT_MAX_CYCLES},
    {"soc", required_argument, NULL, OPT_SOC},
    {"data", required_argument, NULL, OPT_DATA},
    {"inputs", required_argument, NULL, OPT_INPUTS},
    {NULL, 0, NULL, 0},
};

/* One option and its value (getopt_long's); 0 or -1 (message printed). */
static int take_opt(int c, const char *val, struct opts *o) {
    uint64_t u;
    switch (c) {
    case 'h':
        usage(stdout);
        exit(0);
    case OPT_DUMP_REGS:
        o->dump_regs = 1;
        return 0;
    case OPT_TRACE:
        o->trace = 1;
        return 0;
    case OPT_STRICT: {
        const char *bad_rule;
        if (pru_strict_parse(val, &o->params.strict, &bad_rule))
            return bad("--strict '%s': expected loop1, loop0, loopfield, mvi, dram or spad",
                       bad_rule);
        return 0;
    }
    case OPT_STRICT_SCOPE:
        if (strcmp(val, "clocked") && strcmp(val, "all"))
            return bad("--strict-scope '%s': expected clocked or all", val);
        o->params.strict_everywhere = strcmp(val, "all") == 0;
        return 0;
    case OPT_STRICT_WINDOW:
        if (parse_u64(val, &u) || u == 0 || u > 0xffffffu)
            return bad("--strict-window '%s': expected cycles, 1..16777215", val);
        o->params.strict_window = (unsigned)u;
        return 0;
    case OPT_STRICT_LOG:
        o->params.strict_log = 1;
        return 0;
    case OPT_CONTEND: {
        char err[200];
        if (pru_contend_parse(val, &o->params, err, sizeof err))
            return bad("--contend %s", err);
        return 0;
    }
    case OPT_NO_FAST_PATH:
        if (pru_params_fast_path_off(&o->params, val))
            return bad("--no-fast-path '%s': expected ff, ff-counted, ff-r31-bits, "
                       "ff-loop-delay, ff-count-loop, fast-loop, leaf-call or straight-run",
                       val);
        return 0;
    case OPT_MAX_CYCLES:
        if (parse_u64(val, &u) || u == 0)
            return bad("--max-cycles '%s': expected cycles, 1..2^64-1", val);
        /* the core caps a limit at PRU_MAX_CYCLE (about 52 days) anyway */
        o->max_cycles = u > (uint64_t)INT64_MAX ? INT64_MAX : (int64_t)u;
        return 0;
    case OPT_SOC:
        if (pru_soc_from_name(val, &o->soc))
            return bad("--soc '%s': expected am335x, am437x-icss0 or am437x-icss1", val);
        return 0;
    case OPT_DATA:
        o->data = val;
        return 0;
    case OPT_INPUTS:
        if (parse_u64(val, &u) || u > 0x3fffffffu)
            return bad("--inputs '%s': expected 0..0x3fffffff", val);
        o->inputs = (uint32_t)u;
        return 0;
    }
    return -1;
}

/* getopt_long's options (--opt VALUE, --opt=VALUE, unambiguous
 * abbreviations); every usage error names the option it is about. */
static int parse_args(int argc, char **argv, struct opts *o) {
    *o = (struct opts){.soc = PRU_SOC_AM335X, .max_cycles = DEFAULT_MAX_CYCLES};
    pru_params_default(&o->params);
    opterr = 0;
    optind = 1;
    int c;
    while ((c = getopt_long(argc, argv, ":h", long_opts, NULL)) != -1) {
        const char *opt = argv[optind - 1];
        if (c == '?') {
            return bad(optopt >= OPT_DUMP_REGS ? "option '%s' takes no value"
                       : optopt                ? "unknown option '%s'"
                                : "unknown option '%s' (or an ambiguous abbreviation)",
                       opt);
        }
        if (c == ':')
            return bad("option '%s' needs a value", opt);
        if (take_opt(c, optarg, o))
            return -1;
    }
    for (int i = optind; i < argc; i++) {
        if (o->image)
            return bad("unexpected argument '%s' (one IMAGE.bin)", argv[i]);
        o->image = argv[i];
    }
    if (!o->image)
        return bad("no IMAGE.bin given");
    if (!o->params.strict && (o->params.strict_log || o->params.strict_everywhere))
        return bad("--strict-log and --strict-scope need --strict");
    return 0;
}

/* Read a whole input file (image or data, shorter than 32 MB); returns 0 or
 * -1 (message printed). */
static int read_input(const char *opt, const char *path, uint8_t **buf, size_t *len) {
    char *b;
    read_file_err e = read_file(path, 32u << 20, &b, len);
    const char *why = e == READ_FILE_TOO_BIG ? "larger than 32 MB"
                      : e == READ_FILE_NOMEM ? "out of memory"
                                             : strerror(errno);
    if (e && opt) {
        fprintf(stderr, "pru-run: %s %s: cannot %s: %s\n", opt, path,
                e == READ_FILE_OPEN ? "open" : "read", why);
        return -1;
    }
    if (e) {
        fprintf(stderr, "pru-run: cannot %s %s: %s\n", e == READ_FILE_OPEN ? "open" : "read", path,
                why);
        return -1;
    }
    *buf = (uint8_t *)b;
    return 0;
}

static int load(struct pru_core *c, const struct opts *o) {
    uint8_t *buf;
    size_t len;
    if (read_input(NULL, o->image, &buf, &len))
        return -1;
    int rc = 0;
    if (len == 0) {
        fprintf(stderr, "pru-run: %s: empty image (no instruction to run)\n", o->image);
        rc = -1;
    } else if (len % 4 != 0) {
        fprintf(stderr, "pru-run: %s: size %zu is not a multiple of 4\n", o->image, len);
        rc = -1;
    } else if (pru_load_image(c, buf, len) != 0) {
        fprintf(stderr, "pru-run: %s: %zu bytes do not fit the %u-byte IRAM of %s\n", o->image, len,
                pru_iram_bytes(c), pru_soc_name(o->soc));
        rc = -1;
    }
    free(buf);
    if (rc || !o->data)
        return rc;
    if (read_input("--data", o->data, &buf, &len))
        return -1;
    if (len > pru_dram_bytes(c) ||
        pru_host_write(c, pru_soc_base(o->soc) + PRU_OFS_DRAM0, buf, len) != 0) {
        fprintf(stderr, "pru-run: --data %s: %zu bytes do not fit the %u-byte data RAM\n", o->data,
                len, pru_dram_bytes(c));
        rc = -1;
    }
    free(buf);
    return rc;
}

static void dump_regs(struct pru_core *c) {
    for (unsigned i = 0; i < 32; i++)
        printf("r%u=0x%08" PRIx32 "\n", i, pru_reg(c, i));
    printf("pc=0x%04" PRIx32 "\n", pru_pc(c));
    printf("cycles=%lld\n", (long long)pru_cycles(c));
    printf("instructions=%llu\n", (unsigned long long)pru_instructions(c));
}

/* The strict-mode log, one line per (pc, rule); returns how many. */
static size_t print_strict_log(struct pru_core *c) {
    const struct pru_strict_hit *h;
    uint64_t lost;
    size_t n = pru_strict_hits(c, &h, &lost);
    for (size_t i = 0; i < n; i++)
        fprintf(stderr, "strict: %s at pc=0x%04x first cycle=%lld, %llu times (word=0x%08x)\n",
                pru_strict_rule_name(h[i].rule), h[i].pc, (long long)h[i].first_cycle,
                (unsigned long long)h[i].count, h[i].word);
    if (lost)
        fprintf(stderr, "strict: %llu more not listed\n", (unsigned long long)lost);
    return n + (size_t)lost;
}

int main(int argc, char **argv) {
    if (argc == 2 && strcmp(argv[1], "--version") == 0) { /* the project's (CMakeLists.txt) */
        printf("%s %s\n", "pru-run", BISS_VERSION);
        return 0;
    }
    struct opts o;
    if (parse_args(argc, argv, &o))
        return EXIT_USAGE;
    struct pru_core *c = pru_core_new(o.soc, &o.params);
    if (!c) {
        fprintf(stderr, "pru-run: out of memory\n");
        return 1;
    }
    if (load(c, &o)) {
        pru_core_free(c);
        return 1;
    }
    pru_set_inputs(c, o.inputs);
    if (o.trace)
        pru_set_trace(c, stderr);
    pru_start(c);
    enum pru_stop st = pru_run(c, o.max_cycles);
    int rc = 0;
    if (st == PRU_STOP_FAULT) {
        pru_print_fault(c, stderr);
        rc = EXIT_FAULT;
    } else if (st != PRU_STOP_HALT) {
        fprintf(stderr, "pru-run: no HALT within %lld cycles (pc=0x%04x)\n",
                (long long)o.max_cycles, pru_pc(c));
        rc = EXIT_NOHALT;
    }
    if (o.params.strict_log && print_strict_log(c) && rc == 0)
        rc = EXIT_FAULT;
    if (o.params.contend_period) {
        uint64_t n, stall;
        pru_contend_stats(c, &n, &stall);
        fprintf(stderr, "contention: %llu accesses stalled, %llu cycles\n", (unsigned long long)n,
                (unsigned long long)stall);
    }
    if (o.dump_regs)
        dump_regs(c);
    pru_core_free(c);
    return rc;
}
