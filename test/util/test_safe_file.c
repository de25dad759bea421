/* safe_file: an output written whole or not at all, without following or
 * replacing what is not a regular file (safe_file.h). */
#define _XOPEN_SOURCE 700 /* mknod (XSI) */
#include "safe_file.h"

#include "check_run.h"

#include <check.h>
#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <sys/un.h>
#include <sys/wait.h>
#include <unistd.h>

static char dir[64];
static char err[PATH_MAX + 200];

static void setup(void) {
    snprintf(dir, sizeof dir, "/tmp/safe-file-XXXXXX");
    ck_assert_ptr_nonnull(mkdtemp(dir));
}

static void teardown(void) {
    char cmd[128];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
    ck_assert_int_eq(system(cmd), 0);
}

static const char *in_dir(const char *name) {
    static char p[4][PATH_MAX];
    static int k;
    k = (k + 1) % 4;
    snprintf(p[k], sizeof p[k], "%s/%s", dir, name);
    return p[k];
}

static char *slurp(const char *path) {
    static char buf[256];
    FILE *f = fopen(path, "r");
    ck_assert_ptr_nonnull(f);
    size_t n = fread(buf, 1, sizeof buf - 1, f);
    buf[n] = 0;
    fclose(f);
    return buf;
}

/* The directory holds exactly n entries (no temporary file left). */
static void entries(int n) {
    char cmd[128];
    snprintf(cmd, sizeof cmd, "test $(ls -A '%s' | wc -l) -eq %d", dir, n);
    ck_assert_msg(system(cmd) == 0, "%d entries expected in %s", n, dir);
}

START_TEST(new_and_replaced) {
    const char *out = in_dir("out.txt");
    ck_assert_int_eq(safe_file_write(out, "one\n", 4, err, sizeof err), 0);
    ck_assert_str_eq(slurp(out), "one\n");
    struct stat st;
    ck_assert_int_eq(stat(out, &st), 0);
    mode_t m = umask(0);
    umask(m);
    ck_assert_uint_eq(st.st_mode & 0777, 0666 & ~m); /* as fopen would make it */
    /* replaced whole, its mode kept */
    ck_assert_int_eq(chmod(out, 0640), 0);
    ck_assert_int_eq(safe_file_write(out, "two\n", 4, err, sizeof err), 0);
    ck_assert_str_eq(slurp(out), "two\n");
    ck_assert_int_eq(stat(out, &st), 0);
    ck_assert_uint_eq(st.st_mode & 0777, 0640);
    entries(1);
}
END_TEST

/* Dropped halfway: the old content stays, nothing else is left. */
START_TEST(abort_leaves_the_old) {
    const char *out = in_dir("out.txt");
    ck_assert_int_eq(safe_file_write(out, "old\n", 4, err, sizeof err), 0);
    struct safe_file s;
    ck_assert_int_eq(safe_file_open(&s, out, err, sizeof err), 0);
    fputs("half", s.f);
    safe_file_abort(&s);
    ck_assert_str_eq(slurp(out), "old\n");
    entries(1);
}
END_TEST

/* The name out.tmp (what pru-elf once used) planted as a link to a victim
 * is neither followed nor touched: the temporary name is mkstemp's. */
START_TEST(no_predictable_name) {
    const char *out = in_dir("out.elf"), *victim = in_dir("victim");
    ck_assert_int_eq(safe_file_write(victim, "keep\n", 5, err, sizeof err), 0);
    ck_assert_int_eq(symlink(victim, in_dir("out.elf.tmp")), 0);
    ck_assert_int_eq(safe_file_write(out, "elf\n", 4, err, sizeof err), 0);
    ck_assert_str_eq(slurp(victim), "keep\n");
    ck_assert_str_eq(slurp(out), "elf\n");
    entries(3);
}
END_TEST

/* A link to a regular file: that file replaced, the link kept. */
START_TEST(link_to_a_file) {
    const char *real = in_dir("real.vcd"), *link = in_dir("link.vcd");
    ck_assert_int_eq(safe_file_write(real, "a\n", 2, err, sizeof err), 0);
    ck_assert_int_eq(symlink(real, link), 0);
    ck_assert_int_eq(safe_file_write(link, "b\n", 2, err, sizeof err), 0);
    struct stat st;
    ck_assert_int_eq(lstat(link, &st), 0);
    ck_assert(S_ISLNK(st.st_mode));
    ck_assert_str_eq(slurp(real), "b\n");
    entries(2);
}
END_TEST

/* A FIFO is written in place and stays a FIFO (a reader on the other
 * end); so would /dev/null. */
START_TEST(fifo_in_place) {
    const char *fifo = in_dir("pipe");
    ck_assert_int_eq(mkfifo(fifo, 0600), 0);
    pid_t pid = fork();
    ck_assert_int_ge(pid, 0);
    if (pid == 0) {
        char buf[16] = {0};
        int fd = open(fifo, O_RDONLY);
        ssize_t n = fd >= 0 ? read(fd, buf, sizeof buf - 1) : -1;
        _exit(n == 6 && strcmp(buf, "piped\n") == 0 ? 0 : 1);
    }
    ck_assert_int_eq(safe_file_write(fifo, "piped\n", 6, err, sizeof err), 0);
    int status;
    ck_assert_int_eq(waitpid(pid, &status, 0), pid);
    ck_assert(WIFEXITED(status) && WEXITSTATUS(status) == 0);
    struct stat st;
    ck_assert_int_eq(lstat(fifo, &st), 0);
    ck_assert(S_ISFIFO(st.st_mode));
    entries(1);
}
END_TEST

/* Not written over: a directory, a socket, a link to nothing; each
 * refused by name, and left as it was. */
START_TEST(refused) {
    const char *sub = in_dir("sub"), *sock = in_dir("sock"), *dangling = in_dir("dangling");
    ck_assert_int_eq(mkdir(sub, 0700), 0);
    ck_assert_int_eq(safe_file_write(sub, "x", 1, err, sizeof err), -1);
    ck_assert_msg(strstr(err, "not a regular file") && strstr(err, sub), "%s", err);
    int fd = socket(AF_UNIX, SOCK_STREAM, 0);
    ck_assert_int_ge(fd, 0);
    struct sockaddr_un a = {.sun_family = AF_UNIX};
    snprintf(a.sun_path, sizeof a.sun_path, "%s", sock);
    ck_assert_int_eq(bind(fd, (struct sockaddr *)&a, sizeof a), 0);
    ck_assert_int_eq(safe_file_write(sock, "x", 1, err, sizeof err), -1);
    ck_assert_msg(strstr(err, "not a regular file"), "%s", err);
    struct stat st;
    ck_assert_int_eq(lstat(sock, &st), 0);
    ck_assert(S_ISSOCK(st.st_mode));
    close(fd);
    ck_assert_int_eq(symlink(in_dir("nowhere/x"), dangling), 0);
    ck_assert_int_eq(safe_file_write(dangling, "x", 1, err, sizeof err), -1);
    ck_assert_msg(strstr(err, "symbolic link"), "%s", err);
    ck_assert_int_eq(safe_file_write(in_dir("nowhere/x"), "x", 1, err, sizeof err), -1);
    ck_assert_msg(strstr(err, "No such file"), "%s", err);
    entries(3);
}
END_TEST

/* A full device (1:7, /dev/full) is written in place: the write fails
 * with its error, and the node stays the device. As root the node is a
 * private one in the test's directory (root may rename over /dev/full);
 * otherwise /dev/full itself, which no one else may replace. */
START_TEST(full_device) {
    const char *full = "/dev/full";
    if (geteuid() == 0) {
        full = in_dir("full");
        ck_assert_int_eq(mknod(full, S_IFCHR | 0666, makedev(1, 7)), 0);
    }
    struct stat before, after;
    ck_assert_int_eq(stat(full, &before), 0);
    ck_assert_int_eq(safe_file_write(full, "x", 1, err, sizeof err), -1);
    ck_assert_msg(strstr(err, full) && strstr(err, strerror(ENOSPC)), "%s", err);
    ck_assert_int_eq(lstat(full, &after), 0);
    ck_assert(S_ISCHR(after.st_mode) && after.st_rdev == before.st_rdev);
}
END_TEST

int main(void) {
    Suite *s = suite_create("safe_file");
    TCase *tc = tcase_create("safe_file");
    tcase_add_checked_fixture(tc, setup, teardown);
    tcase_add_test(tc, new_and_replaced);
    tcase_add_test(tc, abort_leaves_the_old);
    tcase_add_test(tc, no_predictable_name);
    tcase_add_test(tc, link_to_a_file);
    tcase_add_test(tc, fifo_in_place);
    tcase_add_test(tc, refused);
    tcase_add_test(tc, full_device);
    suite_add_tcase(s, tc);
    return check_run(s);
}
