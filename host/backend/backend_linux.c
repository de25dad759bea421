/* backend_linux.c - a PRU-ICSS of an AM335x/AM437x through mmap of
 * /dev/mem (or any file standing in for it, mapped at the same offset).
 * Two loaders: devmem (the whole PRU-ICSS mapped; libbiss writes IRAM and
 * CONTROL itself) and remoteproc (the kernel's pru_rproc loads and starts
 * the ELF through sysfs; only PRU0's data RAM is mapped). Both check that
 * the PRU-ICSS is powered before touching it (an access to an unclocked
 * module is a bus error, not an error code) and take the per-PRU lock.
 * The memory is /dev/mem itself (mapped: it cannot shrink) or a regular
 * file standing in for it, which is read and written with pread/pwrite: a
 * mapping of it would be a bus error (SIGBUS) wherever another process
 * truncated it, and an error code is what a reader must get. Other
 * devices (/dev/zero, ...) are no memory of a PRU-ICSS and are refused. */
#include "biss_priv.h"

#include "backends.h"
#include "biss_lock.h"
#include "biss_oserr.h"
#include "biss_rproc.h"
#include "mmio.h"

#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <time.h>
#include <unistd.h>

/* docs/pru-facts.md §5.4 and the map in proto/biss_soc.h. */
static int soc_of(enum biss_target t, struct biss_soc_icss *s) {
    static const struct biss_soc_icss am335x = BISS_SOC_AM335X;
    static const struct biss_soc_icss icss1 = BISS_SOC_AM437X_ICSS1;
    static const struct biss_soc_icss icss0 = BISS_SOC_AM437X_ICSS0;
    switch (t) {
    case BISS_TARGET_AM335X:
        *s = am335x;
        return BISS_OK;
    case BISS_TARGET_AM437X_ICSS1:
        *s = icss1;
        return BISS_OK;
    case BISS_TARGET_AM437X_ICSS0:
        *s = icss0;
        return BISS_OK;
    case BISS_TARGET_EMU:
        break;
    }
    return BISS_E_TARGET;
}

struct lnx {
    volatile uint8_t *map; /* /dev/mem mapped; NULL for a file (pread/pwrite) */
    size_t map_len;
    off_t base; /* the PRU-ICSS's address in the file */
    int fd;
    off_t pru_lock; /* the PRU's lock: its data RAM's address (biss_lock.h) */
    off_t iep_lock; /* the IEP's: its address */
    char path[PATH_MAX];
    char what[64]; /* "PRU0 of the PRU-ICSS at 0x4a300000" */
    bool shared;   /* the lock is shared (attached) */
    bool rproc;    /* remoteproc loader */
    bool started;  /* this handle started the instance: close stops it */
    bool keep;     /* ... unless it is to keep running (biss_leave_running) */
    char dir[PATH_MAX];
    char fw_name[256];
};

static int in_window(const struct lnx *l, uint32_t off, size_t n) {
    return off <= l->map_len && n <= l->map_len - off;
}

/* A file standing in for /dev/mem: all of it, or an I/O error (a file
 * truncated under us reads short). */
static int file_io(struct lnx *l, uint32_t off, void *buf, size_t n, bool write) {
    off_t at = l->base + (off_t)off;
    ssize_t done = write ? pwrite(l->fd, buf, n, at) : pread(l->fd, buf, n, at);
    return done == (ssize_t)n ? BISS_OK : BISS_E_IO;
}

static int lnx_read(void *ctx, uint32_t off, void *buf, size_t n) {
    struct lnx *l = ctx;
    if (!in_window(l, off, n)) {
        return BISS_E_IO;
    }
    if (!l->map) {
        return file_io(l, off, buf, n, false);
    }
    mmio_read(buf, l->map, off, n);
    return BISS_OK;
}

static int lnx_write(void *ctx, uint32_t off, const void *buf, size_t n) {
    struct lnx *l = ctx;
    if (!in_window(l, off, n)) {
        return BISS_E_IO;
    }
    if (!l->map) {
        return file_io(l, off, (void *)buf, n, true);
    }
    mmio_write(l->map, off, buf, n);
    return BISS_OK;
}

static int lnx_advance(void *ctx, unsigned us) {
    (void)ctx;
    struct timespec ts = {.tv_sec = us / 1000000u, .tv_nsec = (long)(us % 1000000u) * 1000L};
    nanosleep(&ts, NULL);
    return BISS_OK;
}

static uint64_t lnx_now_us(void *ctx) {
    (void)ctx;
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (uint64_t)ts.tv_sec * 1000000u + (uint64_t)ts.tv_nsec / 1000u;
}

static int lnx_exclusive(void *ctx) {
    struct lnx *l = ctx;
    if (!l->shared) {
        return BISS_OK;
    }
    /* in place: refused, the shared lock stays */
    int rc = biss_lock_take(l->fd, l->pru_lock, false, l->path, l->what, NULL);
    if (!rc) {
        l->shared = false;
    }
    return rc;
}

/* The IEP's lock, for the exchange that decides who owns it (biss_priv.h). */
static int lnx_iep_lock(void *ctx, bool take, unsigned timeout_ms) {
    struct lnx *l = ctx;
    if (!take) {
        biss_lock_drop(l->fd, l->iep_lock);
        return BISS_OK;
    }
    return biss_lock_wait(l->fd, l->iep_lock, l->path, "the PRU-ICSS's IEP", timeout_ms, NULL);
}

/* ---- remoteproc: the kernel loads, starts and stops ------------------- */
static int rproc_state(struct lnx *l, char *state, size_t n) {
    return biss_rproc_get(l->dir, "state", state, n, NULL);
}

/* Writing "stop" returns once the kernel has stopped the core (state reads
 * "offline" at once on silicon), but the instance is polled until it says
 * so: a "firmware" or "start" written before would be refused or lost
 * (the kernel answers EBUSY while running). At most RPROC_STOP_MS. */
#define RPROC_STOP_MS 2000
static int rproc_await_offline(struct lnx *l) {
    char state[32];
    for (int ms = 0;; ms++) {
        int rc = rproc_state(l, state, sizeof state);
        if (rc || strcmp(state, "offline") == 0) {
            return rc;
        }
        if (ms == RPROC_STOP_MS) {
            return BISS_E_TIMEOUT;
        }
        nanosleep(&(struct timespec){.tv_nsec = 1000000}, NULL);
    }
}

static int rproc_halt(void *ctx) {
    struct lnx *l = ctx;
    char state[32];
    int rc = rproc_state(l, state, sizeof state);
    if (!rc && strcmp(state, "offline") != 0) {
        rc = biss_rproc_set(l->dir, "state", "stop", NULL);
        if (!rc) {
            rc = rproc_await_offline(l);
        }
    }
    if (!rc) {
        l->started = false;
    }
    return rc;
}

static int rproc_start(void *ctx) {
    struct lnx *l = ctx;
    int rc = biss_rproc_set(l->dir, "firmware", l->fw_name, NULL);
    if (!rc) {
        rc = biss_rproc_set(l->dir, "state", "start", NULL);
    }
    if (!rc) {
        l->started = true;
    }
    return rc;
}

static int rproc_enabled(void *ctx, bool *on) {
    struct lnx *l = ctx;
    char state[32];
    int rc = rproc_state(l, state, sizeof state);
    *on = !rc && strcmp(state, "running") == 0;
    return rc;
}

static void rproc_leave_running(void *ctx) {
    struct lnx *l = ctx;
    l->keep = true;
}

static void lnx_close(void *ctx) {
    struct lnx *l = ctx;
    if (l->started && !l->keep) {
        biss_rproc_set(l->dir, "state", "stop", NULL);
    }
    if (l->map) {
        munmap((void *)l->map, l->map_len);
    }
    if (l->fd >= 0) {
        close(l->fd); /* releases the locks */
    }
    free(l);
}

static const struct biss_backend_ops devmem_ops = {
    .read = lnx_read,
    .write = lnx_write,
    .advance = lnx_advance,
    .now_us = lnx_now_us,
    .close = lnx_close,
    .exclusive = lnx_exclusive,
    .iep_lock = lnx_iep_lock,
    .poll_us = 50,
    .advance_sleeps = 1,
};

static const struct biss_backend_ops rproc_ops = {
    .read = lnx_read,
    .write = lnx_write,
    .advance = lnx_advance,
    .now_us = lnx_now_us,
    .close = lnx_close,
    .exclusive = lnx_exclusive,
    .iep_lock = lnx_iep_lock,
    .pru_halt = rproc_halt,
    .pru_start = rproc_start,
    .pru_enabled = rproc_enabled,
    .leave_running = rproc_leave_running,
    .poll_us = 50,
    .advance_sleeps = 1,
};

/* ---- opening ------------------------------------------------------------ */
static const char *sysfs_root(const struct biss_open_params *p) {
    return p->sysfs_root && *p->sysfs_root ? p->sysfs_root : "/sys";
}

/* A regular file standing in for memory must reach end, or an access past
 * its end would be a SIGBUS. */
static int file_covers(const struct stat *st, off_t end) {
    return !S_ISREG(st->st_mode) || st->st_size >= end;
}

static int clock_on(const struct biss_soc_icss *s, uint32_t v, const char *path, const char *sysfs,
                    struct biss_errbuf *e);

/* The pruss driver bound (it keeps the module powered), or else the PRCM
 * clock control says the module is enabled and functional (MODULEMODE = 2,
 * IDLEST = 0; AM335x TRM 8.1.12.1, CM_PER_PRU_ICSS_CLKCTRL). */
static int check_powered(const struct biss_soc_icss *s, const char *sysfs, int fd,
                         const struct stat *st, const char *path, struct biss_errbuf *e) {
    char drv[PATH_MAX];
    snprintf(drv, sizeof drv, "%s/bus/platform/drivers/pruss/%lx.pruss", sysfs,
             (unsigned long)s->base);
    if (access(drv, F_OK) == 0) {
        return BISS_OK;
    }
    long page = sysconf(_SC_PAGESIZE);
    off_t at = s->clkctrl & ~(off_t)(page - 1);
    uint32_t v;
    if (S_ISREG(st->st_mode)) {
        if (pread(fd, &v, 4, (off_t)s->clkctrl) != 4) {
            return biss_err(e, BISS_E_NOT_POWERED,
                            "%s ends before CM_PER_PRU_ICSS_CLKCTRL (0x%lx) "
                            "and %s does not exist: cannot tell that the PRU-ICSS is powered",
                            path, (unsigned long)s->clkctrl, drv);
        }
        return clock_on(s, v, path, sysfs, e);
    }
    void *m = mmap(NULL, (size_t)page, PROT_READ, MAP_SHARED, fd, at);
    if (m == MAP_FAILED) {
        int err = errno;
        return biss_err(e, BISS_E_NOT_POWERED,
                        "%s: mapping CM_PER_PRU_ICSS_CLKCTRL (0x%lx): %s "
                        "(errno %d): %s; or bind the pruss driver (%s)",
                        path, (unsigned long)s->clkctrl, strerror(err), err, biss_devmem_hint(err),
                        drv);
    }
    v = *(volatile uint32_t *)((volatile uint8_t *)m + (s->clkctrl - at));
    munmap(m, (size_t)page);
    return clock_on(s, v, path, sysfs, e);
}

/* CM_PER_PRU_ICSS_CLKCTRL = v: enabled and functional, or why not. */
static int clock_on(const struct biss_soc_icss *s, uint32_t v, const char *path, const char *sysfs,
                    struct biss_errbuf *e) {
    unsigned mode = v & 3u, idlest = (v >> 16) & 3u;
    if (mode == 2 && idlest == 0) {
        return BISS_OK;
    }
    char hint[1200];
    biss_rproc_diagnose(sysfs, (unsigned long)s->base, hint, sizeof hint);
    return biss_err(e, BISS_E_NOT_POWERED,
                    "%s: CM_PER_PRU_ICSS_CLKCTRL (0x%lx) = 0x%08x "
                    "(MODULEMODE %u, IDLEST %u: not enabled), so touching the PRU-ICSS would be a "
                    "bus error%s",
                    path, (unsigned long)s->clkctrl, v, mode, idlest, hint);
}

/* Remoteproc: the instance, not running someone else's firmware. */
static int rproc_prepare(struct lnx *l, const struct biss_soc_icss *s,
                         const struct biss_open_params *p, struct biss_errbuf *e) {
    /* pru_rproc names an instance after its PRU's IRAM */
    int rc = biss_rproc_find(sysfs_root(p), (unsigned long)s->base,
                             s->iram_phys + ICSS_IRAM(p->pru) - ICSS_IRAM0, l->dir, e);
    if (rc) {
        return rc;
    }
    /* The ELF by its own name (pru_fw/CMakeLists.txt installs it in
     * /lib/firmware), not by the name the kernel's device tree gives the
     * PRU (s->fw_name), which may be another firmware's. */
    const char *own = p->pru ? "biss_master_pru1.elf" : "biss_master.elf";
    snprintf(l->fw_name, sizeof l->fw_name, "%s",
             p->rproc_firmware && *p->rproc_firmware ? p->rproc_firmware : own);
    char state[32], fw[256];
    rc = biss_rproc_get(l->dir, "state", state, sizeof state, e);
    if (!rc) {
        rc = biss_rproc_get(l->dir, "firmware", fw, sizeof fw, e);
    }
    if (rc) {
        return rc;
    }
    bool running = strcmp(state, "running") == 0;
    if (p->attach) {
        return running ? BISS_OK
                       : biss_err(e, BISS_E_NOT_RUNNING, "%s/state is '%s': nothing to attach to",
                                  l->dir, state);
    }
    if (running && strcmp(fw, l->fw_name) != 0) {
        return biss_err(e, BISS_E_RPROC_BUSY,
                        "%s runs firmware '%s', not '%s': stop it first "
                        "(echo stop > %s/state) if it is yours to stop",
                        l->dir, fw, l->fw_name, l->dir);
    }
    if (strcmp(state, "offline") != 0 && !running) {
        return biss_err(e, BISS_E_RPROC_BUSY, "%s/state is '%s'", l->dir, state);
    }
    const char *fwdir = p->firmware_dir && *p->firmware_dir ? p->firmware_dir : "/lib/firmware";
    char fwpath[PATH_MAX];
    snprintf(fwpath, sizeof fwpath, "%s/%s", fwdir, l->fw_name);
    if (access(fwpath, R_OK) != 0) {
        int err = errno;
        return biss_err(e, BISS_E_FIRMWARE_IO,
                        "%s: %s (errno %d): install the firmware (the "
                        "pru-biss-firmware package, or cmake --install; docs/hardware.md)",
                        fwpath, strerror(err), err);
    }
    return BISS_OK;
}

static int open_mem(struct lnx *l, const struct biss_soc_icss *s, const struct biss_open_params *p,
                    struct biss_errbuf *e) {
    const char *path = p->devmem && *p->devmem ? p->devmem : "/dev/mem";
    /* O_SYNC: uncached mapping of /dev/mem, as device memory must be */
    l->fd = open(path, O_RDWR | O_SYNC | O_CLOEXEC);
    if (l->fd < 0) {
        int err = errno;
        return biss_err(e, BISS_E_DEVMEM, "%s: %s (errno %d): %s", path, strerror(err), err,
                        biss_devmem_hint(err));
    }
    struct stat st;
    if (fstat(l->fd, &st) != 0) {
        int err = errno;
        return biss_err(e, BISS_E_DEVMEM, "%s: %s (errno %d)", path, strerror(err), err);
    }
    /* /dev/mem is character device 1:1 (Linux's devices.txt); a regular
     * file may stand in for it */
    bool mem = S_ISCHR(st.st_mode) && major(st.st_rdev) == 1 && minor(st.st_rdev) == 1;
    if (!mem && !S_ISREG(st.st_mode)) {
        return biss_err(e, BISS_E_DEVMEM,
                        "%s is not /dev/mem (character device 1:1) nor a regular file standing in "
                        "for it: no PRU-ICSS memory there",
                        path);
    }
    /* one lock per PRU, on the memory file itself at the PRU's data RAM
     * (for PRU0 the PRU-ICSS base): every process that can reach the PRU
     * agrees on it (biss_lock.h); and one at the IEP */
    snprintf(l->path, sizeof l->path, "%s", path);
    snprintf(l->what, sizeof l->what, "PRU%u of the PRU-ICSS at 0x%lx", p->pru,
             (unsigned long)s->base);
    l->pru_lock = (off_t)(s->base + ICSS_DRAM(p->pru));
    l->iep_lock = (off_t)(s->base + PRUSS_OFS_IEP);
    l->shared = p->attach;
    int rc = biss_lock_take(l->fd, l->pru_lock, l->shared, path, l->what, e);
    if (!rc) {
        rc = check_powered(s, sysfs_root(p), l->fd, &st, path, e);
    }
    if (!rc && l->rproc) {
        rc = rproc_prepare(l, s, p, e);
    }
    if (rc) {
        return rc;
    }
    /* remoteproc: both data RAMs (the other PRU's says who owns the IEP);
     * devmem: everything */
    l->map_len = l->rproc ? ICSS_DRAM(1) + s->dram_bytes : s->window;
    if (!file_covers(&st, s->base + (off_t)l->map_len)) {
        return biss_err(e, BISS_E_DEVMEM,
                        "%s: %lld bytes, ends before the PRU-ICSS window "
                        "0x%lx..0x%lx",
                        path, (long long)st.st_size, (unsigned long)s->base,
                        (unsigned long)(s->base + (off_t)l->map_len));
    }
    l->base = (off_t)s->base;
    if (!mem) {
        return BISS_OK; /* pread/pwrite */
    }
    void *m = mmap(NULL, l->map_len, PROT_READ | PROT_WRITE, MAP_SHARED, l->fd, s->base);
    if (m == MAP_FAILED) {
        int err = errno;
        return biss_err(e, BISS_E_DEVMEM, "%s: mapping 0x%lx+0x%zx: %s (errno %d): %s", path,
                        (unsigned long)s->base, l->map_len, strerror(err), err,
                        biss_devmem_hint(err));
    }
    l->map = m;
    return BISS_OK;
}

int biss_linux_backend_open(const struct biss_open_params *p, struct biss_backend *be) {
    struct biss_soc_icss soc;
    int rc = soc_of(p->target, &soc);
    if (rc) {
        return rc;
    }
    if (p->loader != BISS_LOADER_DEVMEM && p->loader != BISS_LOADER_REMOTEPROC) {
        return BISS_E_INVAL;
    }
    struct lnx *l = calloc(1, sizeof *l);
    if (!l) {
        return BISS_E_NOMEM;
    }
    l->fd = -1;
    l->rproc = p->loader == BISS_LOADER_REMOTEPROC;
    struct biss_errbuf e = {p->errbuf, p->errbuf_len};
    rc = open_mem(l, &soc, p, &e);
    if (rc) {
        lnx_close(l);
        return rc;
    }
    *be = (struct biss_backend){.ops = l->rproc ? &rproc_ops : &devmem_ops,
                                .ctx = l,
                                .iram_bytes = soc.iram_bytes,
                                .pru = p->pru};
    return BISS_OK;
}

/* libbiss alone: the Linux targets (the emulator's is libbiss-emu's). */
int biss_open(const struct biss_open_params *p, biss_t **out) {
    static const struct biss_backends linux_only = {.linux_open = biss_linux_backend_open};
    return biss_open_with(p, &linux_only, out);
}

int biss_encoder_open(const struct biss_open_params *p, biss_encoder_t **out) {
    return biss_encoder_open_with(p, biss_linux_backend_open, out);
}
