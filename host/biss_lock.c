/* biss_lock.c - per-PRU advisory locks. */
#include "biss_lock.h"

#include "libbiss.h"

#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/file.h>
#include <unistd.h>

static const char *lock_dir(const char *dir) {
    if (dir && *dir) {
        return dir;
    }
    const char *env = getenv("BISS_LOCK_DIR");
    if (env && *env) {
        return env;
    }
    return access("/run/lock", W_OK) == 0 ? "/run/lock" : "/tmp";
}

/* The pid the holder wrote, or 0. */
static long holder(int fd) {
    char buf[32] = {0};
    ssize_t n = pread(fd, buf, sizeof buf - 1, 0);
    return n > 0 ? strtol(buf, NULL, 10) : 0;
}

static void write_pid(int fd) {
    char buf[32];
    int n = snprintf(buf, sizeof buf, "%ld\n", (long)getpid());
    if (ftruncate(fd, 0) == 0 && pwrite(fd, buf, (size_t)n, 0) != n) {
        /* only the refusal message of another process loses its pid */
    }
}

static int busy(int fd, const char *what, struct biss_errbuf *e) {
    long pid = holder(fd);
    if (pid > 0) {
        return biss_err(e, BISS_E_BUSY, "%s is held by pid %ld", what, pid);
    }
    return biss_err(e, BISS_E_BUSY, "%s is held by another process", what);
}

int biss_lock_take(const char *dir, const char *key, bool shared, int *fd, struct biss_errbuf *e) {
    char path[PATH_MAX];
    if (snprintf(path, sizeof path, "%s/%s", lock_dir(dir), key) >= (int)sizeof path) {
        return biss_err(e, BISS_E_DEVMEM, "lock file path too long: %s/%s", lock_dir(dir), key);
    }
    int f = open(path, O_RDWR | O_CREAT | O_CLOEXEC, 0666);
    if (f < 0) {
        int err = errno;
        return biss_err(e, BISS_E_DEVMEM,
                        "lock file %s: %s (errno %d): set BISS_LOCK_DIR to a "
                        "writable directory",
                        path, strerror(err), err);
    }
    if (flock(f, (shared ? LOCK_SH : LOCK_EX) | LOCK_NB) != 0) {
        int rc = errno == EWOULDBLOCK ? busy(f, path, e)
                                      : biss_err(e, BISS_E_DEVMEM, "flock %s: %s (errno %d)", path,
                                                 strerror(errno), errno);
        close(f);
        return rc;
    }
    write_pid(f);
    *fd = f;
    return BISS_OK;
}

int biss_lock_upgrade(int fd, struct biss_errbuf *e) {
    if (flock(fd, LOCK_EX | LOCK_NB) == 0) {
        write_pid(fd);
        return BISS_OK;
    }
    /* flock converts by dropping the lock first: take the shared one back */
    int rc = busy(fd, "the PRU's lock", e);
    if (flock(fd, LOCK_SH | LOCK_NB) != 0) {
        /* a writer slipped in between: this handle goes on unlocked */
    }
    return rc;
}
