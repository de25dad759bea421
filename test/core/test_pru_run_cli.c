/*
 * Check suite: the pru-run CLI contract - --dump-regs output, exit codes
 * (0 halted, 1 an unreadable file, 2 bad usage, 3 fault, 124 no HALT within
 * --max-cycles), --data, --soc, --help.
 */
#include "check_run.h"
#include "core_test_util.h"

#include <errno.h>
#include <stdio.h>
#include <string.h>
#include <stdlib.h>
#include <sys/wait.h>
#include <unistd.h>

static char dir[256], tool[512], outf[600], errf[600];

static void setup(void) {
    const char *bin = getenv("TEST_BIN_DIR");
    snprintf(tool, sizeof tool, "%s/emulator/core/pru-run", bin ? bin : ".");
    snprintf(dir, sizeof dir, "/tmp/pru-run-test-XXXXXX");
    ck_assert_ptr_nonnull(mkdtemp(dir));
    snprintf(outf, sizeof outf, "%s/out", dir);
    snprintf(errf, sizeof errf, "%s/err", dir);
}

static void teardown(void) {
    char cmd[600];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
    ck_assert_int_eq(system(cmd), 0);
}

static const char *write_file(const char *name, const void *data, size_t n) {
    static char path[600];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    FILE *f = fopen(path, "wb");
    ck_assert_ptr_nonnull(f);
    ck_assert_uint_eq(fwrite(data, 1, n, f), n);
    fclose(f);
    return path;
}

/* Run pru-run with args; returns its exit status. */
static int run(const char *args) {
    char cmd[2048];
    int len = snprintf(cmd, sizeof cmd, "'%s' %s >'%s' 2>'%s'", tool, args, outf, errf);
    ck_assert_int_lt(len, (int)sizeof cmd);
    int st = system(cmd);
    ck_assert(WIFEXITED(st));
    return WEXITSTATUS(st);
}

static char *slurp(const char *path) {
    static char buf[8192];
    FILE *f = fopen(path, "r");
    ck_assert_ptr_nonnull(f);
    size_t n = fread(buf, 1, sizeof buf - 1, f);
    buf[n] = 0;
    fclose(f);
    return buf;
}

START_TEST(halts_and_dumps_registers) {
    const uint32_t w[] = {ldi(R(1), 42), ldi(W2(5), 0xDEAD), halt()};
    const char *img = write_file("a.bin", w, sizeof w);
    char args[700];
    snprintf(args, sizeof args, "--dump-regs '%s'", img);
    ck_assert_int_eq(run(args), 0);
    const char *out = slurp(outf);
    ck_assert_ptr_nonnull(strstr(out, "r0=0x00000000\nr1=0x0000002a\n"));
    ck_assert_ptr_nonnull(strstr(out, "\nr5=0xdead0000\n"));
    ck_assert_ptr_nonnull(strstr(out, "\nr31=0x00000000\npc=0x0002\ncycles=3\ninstructions=3\n"));
    /* one line per register, in order */
    int lines = 0;
    for (const char *p = out; *p; p++)
        lines += *p == '\n';
    ck_assert_int_eq(lines, 35);
}
END_TEST

START_TEST(no_halt_exit_124) {
    const uint32_t w[] = {qba(0)};
    const char *img = write_file("loop.bin", w, sizeof w);
    char args[700];
    snprintf(args, sizeof args, "--max-cycles 1000 --dump-regs '%s'", img);
    ck_assert_int_eq(run(args), 124);
    ck_assert_ptr_nonnull(strstr(slurp(outf), "cycles=1000\ninstructions=1000\n"));
}
END_TEST

START_TEST(fault_exit_3) {
    const uint32_t w[] = {ldi(R(1), 1), 0x32000000u};
    const char *img = write_file("bad.bin", w, sizeof w);
    char args[700];
    snprintf(args, sizeof args, "'%s'", img);
    ck_assert_int_eq(run(args), 3);
    const char *err = slurp(errf);
    ck_assert_ptr_nonnull(strstr(err, "fault"));
    ck_assert_ptr_nonnull(strstr(err, "pc=0x0001"));
    ck_assert_ptr_nonnull(strstr(err, "cycle=1"));
}
END_TEST

/* --strict: the fault report names rule, PC, cycle and the instruction;
 * --strict-log lists every site; --contend stalls; bad values refused. */
START_TEST(strict_and_contend) {
    const uint32_t w[] = {ldi(R(2), 0), loopi(2, 3), alui(PRU_OP_ADD, R(1), R(1), 1),
                          burst(PRU_OP_SBBO, 4, 2, 0, 4), halt()};
    const char *img = write_file("s.bin", w, sizeof w);
    char args[800];
    snprintf(args, sizeof args, "--strict --strict-scope all '%s'", img);
    ck_assert_int_eq(run(args), 3);
    const char *err = slurp(errf);
    ck_assert_msg(strstr(err, "strict rule loop1") && strstr(err, "pc=0x0001 cycle=1: loop 3, 3"),
                  "%s", err);
    snprintf(args, sizeof args, "--strict=dram --strict-scope all '%s'", img);
    ck_assert_int_eq(run(args), 3);
    err = slurp(errf);
    ck_assert_msg(strstr(err, "strict rule dram") &&
                      strstr(err, "pc=0x0003 cycle=5: sbbo r1, r2, 0, 4"),
                  "%s", err);
    snprintf(args, sizeof args, "--strict --strict-scope all --strict-log '%s'", img);
    ck_assert_int_eq(run(args), 3);
    err = slurp(errf);
    ck_assert_msg(strstr(err, "strict: loop1 at pc=0x0001 first cycle=1, 1 times") &&
                      strstr(err, "strict: dram at pc=0x0003 first cycle=5, 1 times"),
                  "%s", err);
    /* clocked scope (the default): no R30 change, so nothing to report */
    snprintf(args, sizeof args, "--strict '%s'", img);
    ck_assert_int_eq(run(args), 0);
    /* the store at cycle 5 meets the host at 5 (K = 5, phase 0): 7 cycles more */
    snprintf(args, sizeof args, "--contend 5,7,periodic --dump-regs '%s'", img);
    ck_assert_int_eq(run(args), 0);
    ck_assert_ptr_nonnull(strstr(slurp(outf), "\ncycles=14\n"));
    ck_assert_ptr_nonnull(strstr(slurp(errf), "contention: 1 accesses stalled, 7 cycles"));
    snprintf(args, sizeof args, "--strict=loop2 '%s'", img);
    ck_assert_int_eq(run(args), 2);
    ck_assert_ptr_nonnull(strstr(slurp(errf), "pru-run: --strict 'loop2': expected loop1,"));
    snprintf(args, sizeof args, "--contend 5 '%s'", img);
    ck_assert_int_eq(run(args), 2);
    ck_assert_ptr_nonnull(strstr(slurp(errf), "pru-run: --contend '5' is not K,S"));
    snprintf(args, sizeof args, "--strict-log '%s'", img);
    ck_assert_int_eq(run(args), 2);
}
END_TEST

START_TEST(data_and_soc) {
    const uint32_t w[] = {burst(PRU_OP_LBCO, 4 * 2, 24, 4, 4), halt()};
    const uint32_t d[] = {0x11111111u, 0xCAFEF00Du};
    const char *img = write_file("d.bin", w, sizeof w);
    char imgp[600];
    snprintf(imgp, sizeof imgp, "%s", img);
    const char *dat = write_file("d.dat", d, sizeof d);
    char args[1400];
    snprintf(args, sizeof args, "--soc am437x-icss0 --data '%s' --dump-regs '%s'", dat, imgp);
    ck_assert_int_eq(run(args), 0);
    const char *out = slurp(outf);
    ck_assert_ptr_nonnull(strstr(out, "\nr2=0xcafef00d\n"));
    ck_assert_ptr_nonnull(strstr(out, "\ncycles=4\n"));
    /* an image too big for the 4 KB IRAM of ICSS0 */
    uint32_t *big = calloc(1025, 4);
    big[1024] = halt();
    const char *bigp = write_file("big.bin", big, 1025 * 4);
    snprintf(args, sizeof args, "--soc am437x-icss0 '%s'", bigp);
    ck_assert_int_ne(run(args), 0);
    snprintf(args, sizeof args, "--soc am335x '%s'", bigp);
    ck_assert_int_eq(run(args), 0);
    free(big);
}
END_TEST

/* Usage errors: exit 2, "pru-run: MESSAGE" and the way to the help, the
 * whole of stderr (README "Conventions"); files that cannot be used: exit 1. */
START_TEST(usage_errors) {
    static const struct {
        const char *args, *message;
    } usage[] = {
        {"", "no IMAGE.bin given"},
        {"--bogus x.bin", "unknown option '--bogus' (or an ambiguous abbreviation)"},
        {"--soc am999 x.bin", "--soc 'am999': expected am335x, am437x-icss0 or am437x-icss1"},
        {"--max-cycles abc x.bin", "--max-cycles 'abc': expected cycles, 1..2^64-1"},
        {"x.bin y.bin", "unexpected argument 'y.bin' (one IMAGE.bin)"},
        /* every usage error names its option: a value missing, one given
         * to an option that takes none */
        {"x.bin --max-cycles", "option '--max-cycles' needs a value"},
        {"--dump-regs=1 x.bin", "option '--dump-regs=1' takes no value"},
    };
    for (size_t i = 0; i < sizeof usage / sizeof usage[0]; i++) {
        char want[300];
        snprintf(want, sizeof want, "pru-run: %s\nTry 'pru-run --help' for more information.\n",
                 usage[i].message);
        ck_assert_msg(run(usage[i].args) == 2, "%s", usage[i].args);
        ck_assert_str_eq(slurp(errf), want);
        ck_assert_str_eq(slurp(outf), "");
    }
    ck_assert_int_eq(run("--help"), 0);
    ck_assert_ptr_nonnull(strstr(slurp(outf), "--max-cycles"));
    ck_assert_int_eq(run("/nonexistent/file.bin"), 1);
    ck_assert_str_eq(slurp(errf), "pru-run: cannot open /nonexistent/file.bin: No such file or "
                                  "directory\n");
    const uint8_t odd[3] = {1, 2, 3};
    char args[700];
    snprintf(args, sizeof args, "'%s'", write_file("odd.bin", odd, 3));
    ck_assert_int_eq(run(args), 1);
    const uint32_t w[] = {halt()};
    const char *img = write_file("h.bin", w, sizeof w);
    snprintf(args, sizeof args, "--data /nonexistent/d.bin '%s'", img);
    ck_assert_int_eq(run(args), 1);
    ck_assert_ptr_nonnull(strstr(slurp(errf), "--data /nonexistent/d.bin: cannot open"));
    /* --option=value as getopt_long takes it, and abbreviations */
    snprintf(args, sizeof args, "--max-cycles=1 --dump '%s'", img);
    ck_assert_int_eq(run(args), 0);
    ck_assert_ptr_nonnull(strstr(slurp(outf), "\ncycles=1\n"));
}
END_TEST

/* --no-fast-path: a countdown delay gives the same registers, cycles and
 * instructions without each fast path; an unknown name is refused. */
START_TEST(no_fast_path) {
    const uint32_t w[] = {ldi(R(1), 50000), alui(PRU_OP_SUB, R(1), R(1), 1),
                          alu(PRU_OP_AND, R(0), R(0), R(0)), qbi(PRU_OP_QBNE, -2, R(1), 0), halt()};
    const char *img = write_file("count.bin", w, sizeof w);
    char args[800], ref[8192];
    snprintf(args, sizeof args, "--dump-regs '%s'", img);
    ck_assert_int_eq(run(args), 0);
    snprintf(ref, sizeof ref, "%s", slurp(outf));
    ck_assert_ptr_nonnull(strstr(ref, "\ncycles=150002\ninstructions=150002\n"));
    const char *names[] = {
        "ff",        "ff-counted", "ff-r31-bits", "ff-loop-delay", "ff-count-loop",
        "fast-loop", "leaf-call",  "straight-run"};
    for (unsigned i = 0; i < sizeof names / sizeof names[0]; i++) {
        snprintf(args, sizeof args, "--no-fast-path %s --dump-regs '%s'", names[i], img);
        ck_assert_int_eq(run(args), 0);
        ck_assert_str_eq(slurp(outf), ref);
    }
    snprintf(args, sizeof args, "--no-fast-path ff-bogus '%s'", img);
    ck_assert_int_eq(run(args), 2);
    ck_assert_ptr_nonnull(strstr(slurp(errf), "--no-fast-path 'ff-bogus': expected ff,"));
}
END_TEST

/* Any count of 1 .. 2^64-1 cycles is a limit (the core caps it); anything
 * else is refused with the value named. */
START_TEST(max_cycles_range) {
    const uint32_t w[] = {ldi(R(1), 1), halt()};
    const char *img = write_file("m.bin", w, sizeof w);
    static const char *const good[] = {"1000", "0x7fffffffffffffff", "9223372036854775808",
                                       "18446744073709551615"};
    char args[800];
    for (size_t i = 0; i < sizeof good / sizeof good[0]; i++) {
        snprintf(args, sizeof args, "--max-cycles %s '%s'", good[i], img);
        ck_assert_msg(run(args) == 0, "--max-cycles %s: %s", good[i], slurp(errf));
    }
    static const char *const bad_values[] = {"0", "-1", "' 5'", "12x", "18446744073709551616",
                                             "''"};
    for (size_t i = 0; i < sizeof bad_values / sizeof bad_values[0]; i++) {
        snprintf(args, sizeof args, "--max-cycles %s '%s'", bad_values[i], img);
        ck_assert_int_eq(run(args), 2);
        const char *err = slurp(errf);
        ck_assert_msg(strstr(err, "': expected cycles, 1..2^64-1"), "%s", err);
    }
    /* the value is named in the message */
    snprintf(args, sizeof args, "--max-cycles 12x '%s'", img);
    ck_assert_int_eq(run(args), 2);
    ck_assert_ptr_nonnull(strstr(slurp(errf), "--max-cycles '12x': expected"));
    /* and the limit is still a limit */
    const uint32_t spin[] = {qba(0)};
    snprintf(args, sizeof args, "--max-cycles 0x10 '%s'", write_file("s.bin", spin, 4));
    ck_assert_int_eq(run(args), 124);
    ck_assert_ptr_nonnull(strstr(slurp(errf), "no HALT within 16 cycles"));
}
END_TEST

/* Unreadable images say why; an empty one is refused before it runs. */
START_TEST(bad_image_files) {
    char args[700];
    snprintf(args, sizeof args, "'%s'", dir);
    ck_assert_int_eq(run(args), 1);
    const char *err = slurp(errf);
    ck_assert_msg(strstr(err, "cannot read") && strstr(err, strerror(EISDIR)), "%s", err);
    snprintf(args, sizeof args, "'%s'", write_file("empty.bin", "", 0));
    ck_assert_int_eq(run(args), 1);
    err = slurp(errf);
    ck_assert_msg(strstr(err, "empty.bin: empty image"), "%s", err);
    const uint32_t w[] = {halt()};
    snprintf(args, sizeof args, "--data '%s' '%s'", dir, write_file("h.bin", w, sizeof w));
    ck_assert_int_eq(run(args), 1);
    ck_assert_ptr_nonnull(strstr(slurp(errf), strerror(EISDIR)));
}
END_TEST

START_TEST(trace_output) {
    const uint32_t w[] = {ldi(R(1), 42), halt()};
    const char *img = write_file("t.bin", w, sizeof w);
    char args[700];
    snprintf(args, sizeof args, "--trace '%s'", img);
    ck_assert_int_eq(run(args), 0);
    const char *err = slurp(errf);
    ck_assert_ptr_nonnull(strstr(err, "ldi r1, 0x2a"));
    ck_assert_ptr_nonnull(strstr(err, "r1=0x0000002a"));
    ck_assert_ptr_nonnull(strstr(err, "halt"));
}
END_TEST

Suite *cli_suite(void) {
    Suite *s = suite_create("pru_run_cli");
    TCase *t = tcase_create("cli");
    tcase_add_checked_fixture(t, setup, teardown);
    tcase_add_test(t, halts_and_dumps_registers);
    tcase_add_test(t, no_halt_exit_124);
    tcase_add_test(t, fault_exit_3);
    tcase_add_test(t, strict_and_contend);
    tcase_add_test(t, data_and_soc);
    tcase_add_test(t, usage_errors);
    tcase_add_test(t, trace_output);
    tcase_add_test(t, max_cycles_range);
    tcase_add_test(t, no_fast_path);
    tcase_add_test(t, bad_image_files);
    suite_add_tcase(s, t);
    return s;
}

int main(void) {
    return check_run(cli_suite());
}
