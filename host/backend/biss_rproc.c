/* biss_rproc.c - remoteproc's sysfs attributes. */
#include "biss_rproc.h"

#include "libbiss.h"

#include <ctype.h>
#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>
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

/* "<iram>.pru" or "<iram>.pru<N>": the PRU's platform device, named by
 * of_device_make_bus_id() after its translated "iram" address and node name
 * (pru@4a334000 on TI's 4.19 tree, pru@34000 under a 0x4a300000 range on
 * 5.10 and newer; TI's 4.14 tree called the nodes pru0@, pru1@). */
static bool is_pru_device(const char *name, const char *want) {
    size_t n = strlen(want);
    return strncmp(name, want, n) == 0 && (name[n] == '\0' || isdigit((unsigned char)name[n]));
}

/* The last component of the link at dir/link, or "" when it is none. */
static void link_base(const char *dir, const char *link, char *out, size_t n) {
    char path[PATH_MAX + 32], target[PATH_MAX];
    snprintf(path, sizeof path, "%s/%s", dir, link);
    ssize_t len = readlink(path, target, sizeof target - 1);
    out[0] = '\0';
    if (len > 0) {
        target[len] = '\0';
        const char *slash = strrchr(target, '/');
        const char *base = slash ? slash + 1 : target;
        size_t k = strnlen(base, n - 1);
        memcpy(out, base, k);
        out[k] = '\0';
    }
}

/* The instance's PRU, however the kernel shows it: the "name" attribute
 * (pru_rproc names the instance after its platform device; the attribute
 * exists since Linux 5.4, Documentation/ABI/testing/sysfs-class-remoteproc),
 * else the "device" link every class device has to its parent
 * (drivers/base/core.c, device_add_class_symlinks), which on 4.19 is the
 * only way. */
static bool is_instance(const char *dir, const char *want) {
    char name[256];
    if (biss_rproc_get(dir, "name", name, sizeof name, NULL) == BISS_OK) {
        return is_pru_device(name, want);
    }
    link_base(dir, "device", name, sizeof name);
    return is_pru_device(name, want);
}

static bool exists(const char *path) {
    struct stat st;
    return stat(path, &st) == 0;
}

/* A BiSS overlay's entry under chosen/overlays (the boards/ overlays add
 * one, as BeagleBoard's do). */
static bool biss_overlay_listed(const char *dir) {
    DIR *d = opendir(dir);
    bool found = false;
    for (struct dirent *de; d && !found && (de = readdir(d));) {
        found = strstr(de->d_name, "-BISS-") != NULL;
    }
    if (d) {
        closedir(d);
    }
    return found;
}

void biss_rproc_diagnose(const char *sysfs, unsigned long icss_base, char *buf, size_t n) {
    char path[PATH_MAX];
    size_t used = 0;
    buf[0] = '\0';
    snprintf(path, sizeof path, "%s/firmware/devicetree/base/chosen/overlays", sysfs);
    if (!exists(path)) {
        used +=
            (size_t)snprintf(buf + used, n - used,
                             "; %s is missing: U-Boot applied no overlay (enable_uboot_overlays=1 "
                             "and uboot_overlay_addr4 in /boot/uEnv.txt, docs/hardware.md §3)",
                             path);
    } else if (!biss_overlay_listed(path)) {
        used += (size_t)snprintf(buf + used, n - used,
                                 "; no *-BISS-* overlay under %s: uboot_overlay_addr4 in "
                                 "/boot/uEnv.txt names a missing file? (docs/hardware.md §3)",
                                 path);
    }
    if (used >= n) {
        return;
    }
    snprintf(path, sizeof path, "%s/bus/platform/drivers/pruss/%lx.pruss", sysfs, icss_base);
    if (!exists(path)) {
        snprintf(buf + used, n - used,
                 "; no pruss driver bound to %lx.pruss (%s): the PRU-ICSS did not probe; "
                 "look in dmesg for \"already requested\" (another node holds a pad: pin helper, "
                 "HDMI, McASP; docs/hardware.md §5) and for pruss errors",
                 icss_base, path);
    } else {
        snprintf(buf + used, n - used,
                 "; the PRU-ICSS is bound (%s) but has no PRU instance: load pru_rproc "
                 "(modprobe pru_rproc; dmesg | grep -i pru)",
                 path);
    }
}

int biss_rproc_find(const char *sysfs, unsigned long icss_base, unsigned long iram,
                    char dir[PATH_MAX], struct biss_errbuf *e) {
    char cls[3840], want[32], hint[1200];
    if (snprintf(cls, sizeof cls, "%s/class/remoteproc", sysfs) >= (int)sizeof cls) {
        return biss_err(e, BISS_E_RPROC, "sysfs root too long: %s", sysfs);
    }
    snprintf(want, sizeof want, "%lx.pru", iram);
    DIR *d = opendir(cls);
    if (!d) {
        int err = errno;
        biss_rproc_diagnose(sysfs, icss_base, hint, sizeof hint);
        return biss_err(e, BISS_E_RPROC,
                        "%s: %s (errno %d): no remoteproc class in this kernel, so no "
                        "instance of %s%s; or use --loader devmem",
                        cls, strerror(err), err, want, hint);
    }
    int rc = BISS_E_RPROC;
    for (struct dirent *de; (de = readdir(d));) {
        if (strncmp(de->d_name, "remoteproc", 10) != 0) {
            continue;
        }
        if (snprintf(dir, PATH_MAX, "%.3800s/%.250s", cls, de->d_name) >= PATH_MAX) {
            continue;
        }
        if (is_instance(dir, want)) {
            rc = BISS_OK;
            break;
        }
    }
    closedir(d);
    if (rc) {
        biss_rproc_diagnose(sysfs, icss_base, hint, sizeof hint);
        return biss_err(e, rc,
                        "no remoteproc instance of %s (its name, or its device link) under "
                        "%s%s; or use --loader devmem",
                        want, cls, hint);
    }
    return BISS_OK;
}
