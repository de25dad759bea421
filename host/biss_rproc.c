/* biss_rproc.c - remoteproc's sysfs attributes. */
#include "biss_rproc.h"

#include "libbiss.h"

#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

int biss_rproc_get(const char *dir, const char *attr, char *buf, size_t n, struct biss_errbuf *e) {
    char path[PATH_MAX + 32];
    snprintf(path, sizeof path, "%s/%s", dir, attr);
    int fd = open(path, O_RDONLY | O_CLOEXEC);
    if (fd < 0) {
        int err = errno;
        return biss_err(e, BISS_E_RPROC, "%s: %s (errno %d)", path, strerror(err), err);
    }
    ssize_t got = read(fd, buf, n - 1);
    int err = errno;
    close(fd);
    if (got < 0) {
        return biss_err(e, BISS_E_RPROC, "%s: %s (errno %d)", path, strerror(err), err);
    }
    buf[got] = '\0';
    buf[strcspn(buf, "\n")] = '\0';
    return BISS_OK;
}

int biss_rproc_set(const char *dir, const char *attr, const char *value, struct biss_errbuf *e) {
    char path[PATH_MAX + 32];
    snprintf(path, sizeof path, "%s/%s", dir, attr);
    /* O_TRUNC: a no-op on sysfs, and what a stand-in file needs */
    int fd = open(path, O_WRONLY | O_TRUNC | O_CLOEXEC);
    size_t n = strlen(value);
    ssize_t put = fd < 0 ? -1 : write(fd, value, n);
    int err = errno;
    if (fd >= 0 && close(fd) != 0 && put == (ssize_t)n) {
        put = -1;
        err = errno;
    }
    if (put == (ssize_t)n) {
        return BISS_OK;
    }
    if (err == EBUSY) {
        return biss_err(e, BISS_E_RPROC_BUSY,
                        "writing '%s' to %s: %s (errno %d): the PRU is in "
                        "use (another firmware or driver)",
                        value, path, strerror(err), err);
    }
    return biss_err(e, BISS_E_RPROC, "writing '%s' to %s: %s (errno %d)%s", value, path,
                    strerror(err), err,
                    err == EACCES || err == EPERM ? ": run as root"
                    : err == ENOENT || err == EINVAL
                        ? ": is the firmware installed in /lib/firmware (docs/hardware.md)?"
                        : "");
}

int biss_rproc_find(const char *sysfs, unsigned long iram, char dir[PATH_MAX],
                    struct biss_errbuf *e) {
    char cls[3840], want[32];
    if (snprintf(cls, sizeof cls, "%s/class/remoteproc", sysfs) >= (int)sizeof cls) {
        return biss_err(e, BISS_E_RPROC, "sysfs root too long: %s", sysfs);
    }
    snprintf(want, sizeof want, "%lx.pru", iram);
    DIR *d = opendir(cls);
    if (!d) {
        int err = errno;
        return biss_err(e, BISS_E_RPROC,
                        "%s: %s (errno %d): no remoteproc here; load pru_rproc "
                        "(modprobe pru_rproc) with the PRU-ICSS enabled in the device tree, or "
                        "use --loader devmem",
                        cls, strerror(err), err);
    }
    int rc = BISS_E_RPROC;
    for (struct dirent *de; (de = readdir(d));) {
        if (strncmp(de->d_name, "remoteproc", 10) != 0) {
            continue;
        }
        char name[64];
        if (snprintf(dir, PATH_MAX, "%.3800s/%.250s", cls, de->d_name) >= PATH_MAX) {
            continue;
        }
        if (biss_rproc_get(dir, "name", name, sizeof name, NULL) == BISS_OK &&
            strncmp(name, want, strlen(want)) == 0) {
            rc = BISS_OK;
            break;
        }
    }
    closedir(d);
    if (rc) {
        return biss_err(e, rc,
                        "no instance named %s* under %s: load pru_rproc (modprobe "
                        "pru_rproc) with this PRU-ICSS enabled in the device tree, or use "
                        "--loader devmem",
                        want, cls);
    }
    return BISS_OK;
}
