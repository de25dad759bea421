/* backend_linux.c - the PRU-ICSS of an AM335x/AM437x through mmap of
 * /dev/mem (or any file standing in for it, mapped at the same offset). */
#include "biss_priv.h"

#include <fcntl.h>
#include <stdlib.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

struct soc_info {
    off_t base;          /* physical address of the PRU-ICSS */
    uint32_t iram_bytes; /* PRU0 instruction RAM */
};

/* AM335x TRM ch. 4; AM437x TRM ch. 30 (ICSS1 is the big one). */
static int soc_of(enum biss_target t, struct soc_info *s) {
    switch (t) {
    case BISS_TARGET_AM335X:
        *s = (struct soc_info){0x4A300000, 8 * 1024};
        return BISS_OK;
    case BISS_TARGET_AM437X_ICSS1:
        *s = (struct soc_info){0x54400000, 12 * 1024};
        return BISS_OK;
    case BISS_TARGET_AM437X_ICSS0:
        *s = (struct soc_info){0x54440000, 4 * 1024};
        return BISS_OK;
    case BISS_TARGET_EMU:
        break;
    }
    return BISS_E_TARGET;
}

struct lnx {
    volatile uint8_t *map;
    int fd;
};

static int in_window(uint32_t off, size_t n) {
    return off <= ICSS_WINDOW && n <= ICSS_WINDOW - off;
}

static int aligned(uint32_t off, size_t n) {
    return off % 4 == 0 && n % 4 == 0;
}

/* Peripheral memory: 32-bit accesses for whole words (what the PRU RAMs
 * and registers expect), bytes otherwise; volatile so none is merged,
 * split or dropped. */
static int lnx_read(void *ctx, uint32_t off, void *buf, size_t n) {
    struct lnx *l = ctx;
    if (!in_window(off, n)) {
        return BISS_E_IO;
    }
    if (aligned(off, n)) {
        const volatile uint32_t *src = (const volatile uint32_t *)(l->map + off);
        uint32_t *dst = buf;
        for (size_t i = 0; i < n / 4; i++) {
            dst[i] = src[i];
        }
    } else {
        uint8_t *dst = buf;
        for (size_t i = 0; i < n; i++) {
            dst[i] = l->map[off + i];
        }
    }
    return BISS_OK;
}

static int lnx_write(void *ctx, uint32_t off, const void *buf, size_t n) {
    struct lnx *l = ctx;
    if (!in_window(off, n)) {
        return BISS_E_IO;
    }
    if (aligned(off, n)) {
        volatile uint32_t *dst = (volatile uint32_t *)(l->map + off);
        const uint32_t *src = buf;
        for (size_t i = 0; i < n / 4; i++) {
            dst[i] = src[i];
        }
    } else {
        const uint8_t *src = buf;
        for (size_t i = 0; i < n; i++) {
            l->map[off + i] = src[i];
        }
    }
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

static void lnx_close(void *ctx) {
    struct lnx *l = ctx;
    munmap((void *)l->map, ICSS_WINDOW);
    close(l->fd);
    free(l);
}

static const struct biss_backend_ops lnx_ops = {
    .read = lnx_read,
    .write = lnx_write,
    .advance = lnx_advance,
    .now_us = lnx_now_us,
    .close = lnx_close,
    .poll_us = 50,
    .advance_sleeps = 1,
};

int biss_linux_backend_open(const struct biss_open_params *p, struct biss_backend *be) {
    struct soc_info soc;
    int rc = soc_of(p->target, &soc);
    if (rc) {
        return rc;
    }
    struct lnx *l = calloc(1, sizeof *l);
    if (!l) {
        return BISS_E_NOMEM;
    }
    const char *path = p->devmem && *p->devmem ? p->devmem : "/dev/mem";
    /* O_SYNC: uncached mapping of /dev/mem, as device memory must be */
    l->fd = open(path, O_RDWR | O_SYNC | O_CLOEXEC);
    if (l->fd < 0) {
        free(l);
        return BISS_E_DEVMEM;
    }
    /* a plain file too short for the window would fault on first access */
    struct stat st;
    if (fstat(l->fd, &st) != 0 ||
        (S_ISREG(st.st_mode) && st.st_size < soc.base + (off_t)ICSS_WINDOW)) {
        close(l->fd);
        free(l);
        return BISS_E_DEVMEM;
    }
    void *m = mmap(NULL, ICSS_WINDOW, PROT_READ | PROT_WRITE, MAP_SHARED, l->fd, soc.base);
    if (m == MAP_FAILED) {
        close(l->fd);
        free(l);
        return BISS_E_DEVMEM;
    }
    l->map = m;
    *be = (struct biss_backend){.ops = &lnx_ops, .ctx = l, .iram_bytes = soc.iram_bytes};
    return BISS_OK;
}
