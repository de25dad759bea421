/* biss_lock.c - the PRU's and the IEP's locks (biss_lock.h). */
#define _GNU_SOURCE /* F_OFD_SETLK (Linux 3.15) */
#include "biss_lock.h"

#include "libbiss.h"

#include <ctype.h>
#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <time.h>
#include <unistd.h>

static int set_lock(int fd, off_t at, short type) {
    struct flock fl = {.l_type = type, .l_whence = SEEK_SET, .l_start = at, .l_len = 1};
    return fcntl(fd, F_OFD_SETLK, &fl);
}

/* Whether an fdinfo file of another process shows an OFD lock on byte
 * `at` of the file (dev, ino): the kernel's line is "lock:\t1: OFDLCK
 * ADVISORY  WRITE -1 MAJ:MIN:INO START END" (fs/locks.c, lock_get_status). */
static bool holds(const char *fdinfo, dev_t dev, ino_t ino, off_t at) {
    FILE *f = fopen(fdinfo, "r");
    if (!f) {
        return false;
    }
    char line[256];
    bool found = false;
    while (!found && fgets(line, sizeof line, f)) {
        unsigned maj, min;
        unsigned long long inode;
        long long start;
        char *p = strstr(line, "OFDLCK");
        if (strncmp(line, "lock:", 5) != 0 || !p) {
            continue;
        }
        /* OFDLCK ADVISORY WRITE -1 MAJ:MIN:INO START END (END "EOF": to the end) */
        long long end = -1;
        int n =
            sscanf(p, "OFDLCK %*s %*s %*s %x:%x:%llu %lld %lld", &maj, &min, &inode, &start, &end);
        found = n >= 4 && maj == major(dev) && min == minor(dev) &&
                inode == (unsigned long long)ino && start <= (long long)at &&
                (n == 4 || end >= (long long)at);
    }
    fclose(f);
    return found;
}

/* The pid of a process holding an OFD lock on byte `at` of fd's file, and
 * its command name; 0 when none can be seen (another user's process, or
 * no /proc). Only on a refusal: it reads every process's fdinfo. */
static long find_holder(int fd, off_t at, char *comm, size_t n) {
    struct stat st;
    DIR *proc = fstat(fd, &st) == 0 ? opendir("/proc") : NULL;
    if (!proc) {
        return 0;
    }
    long pid = 0;
    struct dirent *d;
    while (!pid && (d = readdir(proc))) {
        if (!isdigit((unsigned char)d->d_name[0])) {
            continue;
        }
        char dir[320];
        snprintf(dir, sizeof dir, "/proc/%.255s/fdinfo", d->d_name);
        DIR *fds = opendir(dir);
        struct dirent *e;
        while (fds && !pid && (e = readdir(fds))) {
            char info[600];
            snprintf(info, sizeof info, "%s/%.255s", dir, e->d_name);
            if (isdigit((unsigned char)e->d_name[0]) && holds(info, st.st_dev, st.st_ino, at)) {
                pid = strtol(d->d_name, NULL, 10);
            }
        }
        if (fds) {
            closedir(fds);
        }
    }
    closedir(proc);
    comm[0] = '\0';
    char path[64];
    snprintf(path, sizeof path, "/proc/%ld/comm", pid);
    FILE *f = pid ? fopen(path, "r") : NULL;
    if (f) {
        if (fgets(comm, (int)n, f)) {
            comm[strcspn(comm, "\n")] = '\0';
        }
        fclose(f);
    }
    return pid;
}

static int busy(int fd, off_t at, const char *path, const char *what, struct biss_errbuf *e) {
    char comm[64];
    long pid = find_holder(fd, at, comm, sizeof comm);
    if (pid > 0) {
        return biss_err(e, BISS_E_BUSY, "%s is held by pid %ld (%s): the lock on %s at 0x%llx",
                        what, pid, comm[0] ? comm : "?", path, (unsigned long long)at);
    }
    return biss_err(e, BISS_E_BUSY,
                    "%s is held by another process (not visible here: another user's?): the "
                    "lock on %s at 0x%llx",
                    what, path, (unsigned long long)at);
}

int biss_lock_take(int fd, off_t at, bool shared, const char *path, const char *what,
                   struct biss_errbuf *e) {
    if (set_lock(fd, at, shared ? F_RDLCK : F_WRLCK) == 0) {
        return BISS_OK;
    }
    int err = errno;
    if (err == EAGAIN || err == EACCES) {
        return busy(fd, at, path, what, e);
    }
    return biss_err(e, BISS_E_DEVMEM, "%s: lock at 0x%llx: %s (errno %d)", path,
                    (unsigned long long)at, strerror(err), err);
}

int biss_lock_wait(int fd, off_t at, const char *path, const char *what, unsigned timeout_ms,
                   struct biss_errbuf *e) {
    for (unsigned waited = 0;; waited++) {
        if (set_lock(fd, at, F_WRLCK) == 0) {
            return BISS_OK;
        }
        if ((errno != EAGAIN && errno != EACCES) || waited >= timeout_ms) {
            return biss_lock_take(fd, at, false, path, what, e); /* the reason, named */
        }
        nanosleep(&(struct timespec){.tv_nsec = 1000000}, NULL);
    }
}

void biss_lock_drop(int fd, off_t at) {
    set_lock(fd, at, F_UNLCK);
}
