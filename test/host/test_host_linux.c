/* libbiss's Linux backend against a sparse file standing in for /dev/mem:
 * the image lands in PRU0 IRAM at the SoC's PRU-ICSS base + 0x34000,
 * CONTROL is written, the configuration bytes are where biss_shm.h says;
 * with a "virtual firmware" thread on the same file the whole protocol
 * runs as on a board. */
#define _GNU_SOURCE /* F_OFD_SETLK */
#include "libbiss-emu.h"

#include "biss/biss_shm_struct.h"
#include "biss/biss_slave_shm.h"

#include "biss_oserr.h"
#include "check_run.h"

#include <check.h>
#include <errno.h>
#include <fcntl.h>
#include <pthread.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <signal.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#define AM335X_BASE 0x4A300000L
#define ICSS1_BASE  0x54400000L
#define ICSS0_BASE  0x54440000L
#define WINDOW      0x80000L
#define CTRL0       0x22000L
#define IRAM0       0x34000L

#define AM335X_CLKCTRL 0x44E000E8L /* CM_PER_PRU_ICSS_CLKCTRL */
#define AM437X_CLKCTRL 0x44DF8B20L

static char devmem[256], image[256];

static void file_write32(off_t at, uint32_t v);

/* A sparse file standing in for /dev/mem, with the PRU-ICSS clock on
 * (MODULEMODE enabled, IDLEST functional) as the pruss driver leaves it. */
static void make_devmem(off_t size) {
    snprintf(devmem, sizeof devmem, "/tmp/biss_devmem_XXXXXX");
    int fd = mkstemp(devmem);
    ck_assert_int_ge(fd, 0);
    ck_assert_int_eq(ftruncate(fd, size), 0); /* sparse: costs no disk */
    close(fd);
    if (size > AM335X_CLKCTRL) {
        file_write32(AM335X_CLKCTRL, 0x2);
        file_write32(AM437X_CLKCTRL, 0x2);
    }
}

/* An image of n bytes whose word i is 0x1000 + i. */
static void make_image(size_t n) {
    snprintf(image, sizeof image, "/tmp/biss_image_XXXXXX");
    int fd = mkstemp(image);
    ck_assert_int_ge(fd, 0);
    for (uint32_t i = 0; i < n / 4; i++) {
        uint32_t w = 0x1000 + i;
        ck_assert_int_eq(write(fd, &w, 4), 4);
    }
    if (n % 4) {
        ck_assert_int_eq(write(fd, "xyz", n % 4), (ssize_t)(n % 4));
    }
    close(fd);
}

static void cleanup(void) {
    unlink(devmem);
    unlink(image);
}

static void file_read(off_t at, void *buf, size_t n) {
    int fd = open(devmem, O_RDONLY);
    ck_assert_int_ge(fd, 0);
    ck_assert_int_eq(pread(fd, buf, n, at), (ssize_t)n);
    close(fd);
}

static uint32_t file32(off_t at) {
    uint32_t v;
    file_read(at, &v, 4);
    return v;
}

static void file_write32(off_t at, uint32_t v) {
    int fd = open(devmem, O_WRONLY);
    ck_assert_int_ge(fd, 0);
    ck_assert_int_eq(pwrite(fd, &v, 4, at), 4);
    close(fd);
}

static struct biss_open_params params(enum biss_target t) {
    struct biss_open_params p;
    biss_open_params_default(&p);
    p.target = t;
    p.loader = BISS_LOADER_DEVMEM;
    p.devmem = devmem;
    p.firmware = image;
    p.timeout_ms = 20;
    p.sysfs_root = "/nonexistent-sysfs"; /* the clock word decides */
    p.lock_dir = "/tmp";
    return p;
}

static struct biss_config one_slave(void) {
    struct biss_config c;
    biss_config_default(&c);
    c.freq_hz = 5000000;
    c.nslaves = 1;
    c.proc_limit = 250;
    c.slave[0] = (struct biss_slave_config){
        .data_bits = 14, .crc_bits = 6, .crc_poly = 0x43, .has_ew = true, .ew_shift = 0};
    return c;
}

START_TEST(test_image_lands_in_iram) {
    make_devmem(AM335X_BASE + WINDOW);
    make_image(1000);
    /* leftovers of an earlier run in IRAM and data RAM */
    file_write32(AM335X_BASE + IRAM0 + 4000, 0xdeadbeef);
    file_write32(AM335X_BASE + BISS_ST_MAGIC, BISS_MAGIC);
    file_write32(AM335X_BASE + BISS_ST_CFG_ACK, 1);
    file_write32(AM335X_BASE + BISS_ST_CD_SEQ, 1);
    file_write32(AM335X_BASE + BISS_CD_RESP, 0xffffffff);
    struct biss_open_params p = params(BISS_TARGET_AM335X);
    biss_t *h;
    ck_assert_int_eq(biss_open(&p, &h), BISS_OK);
    for (uint32_t i = 0; i < 250; i++) {
        ck_assert_uint_eq(file32(AM335X_BASE + IRAM0 + 4 * i), 0x1000 + i);
    }
    /* the rest of the 8 KB IRAM is cleared, nothing written past it */
    ck_assert_uint_eq(file32(AM335X_BASE + IRAM0 + 1000), 0);
    ck_assert_uint_eq(file32(AM335X_BASE + IRAM0 + 4000), 0);
    ck_assert_uint_eq(file32(AM335X_BASE + IRAM0 + 8188), 0);
    /* status cleared: a stale magic or ack cannot fool the handshake */
    ck_assert_uint_eq(file32(AM335X_BASE + BISS_ST_MAGIC), 0);
    ck_assert_uint_eq(file32(AM335X_BASE + BISS_ST_CFG_ACK), 0);
    ck_assert_uint_eq(file32(AM335X_BASE + BISS_ST_CD_SEQ), 0);
    ck_assert_uint_eq(file32(AM335X_BASE + BISS_CD_RESP), 0);
    /* CONTROL: ENABLE with SOFT_RST_N low (reset to PC 0 and run) */
    ck_assert_uint_eq(file32(AM335X_BASE + CTRL0), 0x2);
    ck_assert_str_eq(biss_firmware_path(h), image);
    ck_assert_int_eq(biss_stop(h), BISS_OK);
    ck_assert_uint_eq(file32(AM335X_BASE + CTRL0), 0x1);
    biss_close(h);
    cleanup();
}
END_TEST

/* --pru 1: PRU1's IRAM, CONTROL and data RAM; PRU0's left alone, so a
 * second handle can drive it. */
START_TEST(test_pru1_offsets) {
    const off_t dram1 = AM335X_BASE + 0x2000, ctrl1 = AM335X_BASE + 0x24000,
                iram1 = AM335X_BASE + 0x38000;
    make_devmem(AM335X_BASE + WINDOW);
    make_image(1000);
    file_write32(AM335X_BASE + BISS_ST_MAGIC, BISS_MAGIC); /* PRU0's: kept */
    file_write32(dram1 + BISS_ST_MAGIC, BISS_MAGIC);       /* PRU1's: cleared */
    struct biss_open_params p = params(BISS_TARGET_AM335X);
    p.pru = 1;
    biss_t *h;
    ck_assert_int_eq(biss_open(&p, &h), BISS_OK);
    for (uint32_t i = 0; i < 250; i++) {
        ck_assert_uint_eq(file32(iram1 + 4 * i), 0x1000 + i);
    }
    ck_assert_uint_eq(file32(AM335X_BASE + IRAM0), 0);
    ck_assert_uint_eq(file32(ctrl1), 0x2);
    ck_assert_uint_eq(file32(AM335X_BASE + CTRL0), 0);
    ck_assert_uint_eq(file32(dram1 + BISS_ST_MAGIC), 0);
    ck_assert_uint_eq(file32(AM335X_BASE + BISS_ST_MAGIC), BISS_MAGIC);
    /* PRU0 at the same time: its own lock */
    struct biss_open_params p0 = params(BISS_TARGET_AM335X);
    biss_t *h0;
    ck_assert_int_eq(biss_open(&p0, &h0), BISS_OK);
    ck_assert_uint_eq(file32(AM335X_BASE + CTRL0), 0x2);
    ck_assert_int_eq(biss_stop(h), BISS_OK);
    ck_assert_uint_eq(file32(ctrl1), 0x1);
    ck_assert_uint_eq(file32(AM335X_BASE + CTRL0), 0x2);
    biss_close(h0);
    biss_close(h);
    p.pru = 2;
    ck_assert_int_eq(biss_open(&p, &h), BISS_E_INVAL);
    cleanup();
}
END_TEST

START_TEST(test_config_bytes_in_data_ram) {
    make_devmem(AM335X_BASE + WINDOW);
    make_image(64);
    struct biss_open_params p = params(BISS_TARGET_AM335X);
    biss_t *h;
    ck_assert_int_eq(biss_open(&p, &h), BISS_OK);
    struct biss_config c = one_slave();
    /* no firmware runs on a file: the block is written, nobody answers */
    ck_assert_int_eq(biss_configure(h, &c), BISS_E_NOT_RUNNING);
    uint8_t b[BISS_CFG_END];
    file_read(AM335X_BASE, b, sizeof b);
    ck_assert_uint_eq(b[BISS_CFG_SEQ], 1);
    ck_assert_uint_eq(b[BISS_CFG_HALF] | b[BISS_CFG_HALF + 1] << 8, 20);
    ck_assert_uint_eq(b[BISS_CFG_NSLAVES], 1);
    ck_assert_uint_eq(b[BISS_CFG_TRIGGER], BISS_TRIG_FREERUN);
    ck_assert_uint_eq(b[BISS_CFG_PROC_LIMIT] | b[BISS_CFG_PROC_LIMIT + 1] << 8, 251); /* + 1 */
    ck_assert_uint_eq(b[BISS_CFG_SLAVE0 + BISS_CFG_S_DATA_BITS], 14);
    ck_assert_uint_eq(b[BISS_CFG_SLAVE0 + BISS_CFG_S_CRC_BITS], 6);
    ck_assert_uint_eq(b[BISS_CFG_SLAVE0 + BISS_CFG_S_EW_SHIFT], 0);
    ck_assert_uint_eq(b[BISS_CFG_SLAVE0 + BISS_CFG_S_FLAGS], BISS_SF_EW);
    ck_assert_uint_eq(b[BISS_CFG_SLAVE0 + BISS_CFG_S_CRC_POLY], 0x03);
    biss_close(h);
    cleanup();
}
END_TEST

/* ---- a virtual firmware on the same file ------------------------------- */
struct vfw {
    volatile uint32_t *dram;
    unsigned pru;          /* the PRU it says it runs on (ST_PRU) */
    unsigned ack_delay_us; /* how long it takes to apply a configuration */
    atomic_int stop;
    atomic_int publish; /* frames still to publish */
};

static void *virtual_firmware(void *arg) {
    struct vfw *v = arg;
    volatile uint32_t *d = v->dram;
    d[BISS_ST_CFG_ACK / 4] = 0xffffffffu;
    d[BISS_ST_PRU / 4] = v->pru;
    d[BISS_ST_MAGIC / 4] = BISS_MAGIC;
    uint32_t seq = 0;
    while (!atomic_load(&v->stop)) {
        uint32_t cfg = d[BISS_CFG_SEQ / 4];
        if (cfg != 0 && cfg != d[BISS_ST_CFG_ACK / 4]) {
            nanosleep(&(struct timespec){.tv_nsec = 1000L * v->ack_delay_us}, NULL);
            d[BISS_ST_CFG_ERROR / 4] = BISS_CFGERR_NONE;
            d[BISS_ST_STATE / 4] = BISS_STATE_RUNNING;
            d[BISS_ST_CFG_ACK / 4] = cfg;
        }
        if (atomic_load(&v->publish) > 0) {
            seq++;
            /* the ring's slots of one slave, from the first (biss_shm.h) */
            uint32_t buf = BISS_RING0 + (seq - 1) % BISS_RING_SLOTS(1) * BISS_RING_STRIDE(1);
            volatile uint32_t *r = d + buf / 4;
            r[BISS_R_FRAME / 4] = seq;
            r[BISS_R_FLAGS / 4] = BISS_RF_VALID;
            r[BISS_R_PROC_CLOCKS / 4] = 1u << 24; /* one slave */
            r[BISS_R_DELAY_RAW / 4] = 28u << 16 | 27u;
            r[BISS_R_SAMPLE_POINT / 4] = 20u << 16;                            /* H */
            r[(BISS_R_SLAVE0 + BISS_R_S_DATA_LO) / 4] = 0x123u << 2 | 1u << 1; /* nE ok */
            r[(BISS_R_SLAVE0 + BISS_R_S_STATUS) / 4] = BISS_RS_CRC_OK | BISS_RS_NE;
            atomic_thread_fence(memory_order_seq_cst);
            d[BISS_ST_BUF / 4] = buf;
            d[BISS_ST_SEQ / 4] = seq;
            d[BISS_ST_FRAMES / 4] = seq;
            atomic_fetch_sub(&v->publish, 1);
        }
        nanosleep(&(struct timespec){.tv_nsec = 20000}, NULL);
    }
    return NULL;
}

struct configurer {
    biss_t *h;
    int failures;
};

static void *configure_often(void *arg) {
    struct configurer *c = arg;
    struct biss_config cfg = one_slave();
    for (int i = 0; i < 5; i++) {
        c->failures += biss_configure(c->h, &cfg) != BISS_OK;
    }
    return NULL;
}

START_TEST(test_virtual_board) {
    make_devmem(AM335X_BASE + WINDOW);
    make_image(64);
    struct biss_open_params p = params(BISS_TARGET_AM335X);
    p.timeout_ms = 2000;
    biss_t *h;
    ck_assert_int_eq(biss_open(&p, &h), BISS_OK);
    int fd = open(devmem, O_RDWR);
    ck_assert_int_ge(fd, 0);
    void *m = mmap(NULL, WINDOW, PROT_READ | PROT_WRITE, MAP_SHARED, fd, AM335X_BASE);
    ck_assert_ptr_ne(m, MAP_FAILED);
    struct vfw v = {.dram = m};
    pthread_t t;
    ck_assert_int_eq(pthread_create(&t, NULL, virtual_firmware, &v), 0);

    struct biss_config c = one_slave();
    ck_assert_int_eq(biss_configure(h, &c), BISS_OK);
    struct biss_sample s;
    ck_assert_int_eq(biss_wait_sample(h, 0, 0, &s), BISS_E_TIMEOUT);
    uint32_t after = 0;
    for (int i = 0; i < 3; i++) {
        atomic_store(&v.publish, 1);
        ck_assert_int_eq(biss_wait_sample(h, after, 2000, &s), BISS_OK);
        ck_assert_uint_gt(s.frame, after);
        ck_assert(s.valid);
        ck_assert_uint_eq(s.slave[0].position, 0x123);
        ck_assert(!s.slave[0].error && s.slave[0].warning);
        ck_assert(s.slave[0].crc_ok);
        /* DELAY_AVG 28 at H = 20, converted as biss_shm.h says */
        ck_assert_double_eq_tol(s.delay.cycles,
                                (28 - BISS_DELAY_ZERO) * 5.0 - BISS_DELAY_ADJ_CYCLES, 1e-9);
        after = s.frame;
    }
    struct biss_stats st;
    ck_assert_int_eq(biss_get_stats(h, &st), BISS_OK);
    ck_assert_uint_eq(st.frames, 3);
    struct biss_status status;
    ck_assert_int_eq(biss_get_status(h, &status), BISS_OK);
    ck_assert(status.firmware_running && status.pru_enabled);
    ck_assert_uint_eq(status.cfg_ack, 1);

    /* two threads configuring at once: each waits for its own ack while
     * the other's sleeps let it in, and no exchange spoils the other */
    struct configurer cf[2] = {{.h = h}, {.h = h}};
    pthread_t ct[2];
    for (int i = 0; i < 2; i++) {
        ck_assert_int_eq(pthread_create(&ct[i], NULL, configure_often, &cf[i]), 0);
    }
    for (int i = 0; i < 2; i++) {
        pthread_join(ct[i], NULL);
        ck_assert_int_eq(cf[i].failures, 0);
    }
    ck_assert_int_eq(biss_get_status(h, &status), BISS_OK);
    ck_assert_uint_eq(status.cfg_ack, 11);

    /* a second handle is refused while the first holds the PRU, and the
     * refusal names the holder */
    char err[256];
    struct biss_open_params pa = params(BISS_TARGET_AM335X);
    pa.attach = true;
    pa.errbuf = err;
    pa.errbuf_len = sizeof err;
    biss_t *h2;
    ck_assert_int_eq(biss_open(&pa, &h2), BISS_E_BUSY);
    char pid[32];
    snprintf(pid, sizeof pid, "pid %ld", (long)getpid());
    ck_assert_msg(strstr(err, pid) && strstr(err, "(test_host_linux)") && strstr(err, devmem) &&
                      strstr(err, "PRU0 of the PRU-ICSS at 0x4a300000"),
                  "%s", err);
    struct biss_open_params pl = params(BISS_TARGET_AM335X);
    ck_assert_int_eq(biss_open(&pl, &h2), BISS_E_BUSY);
    /* whatever lock directory another process was given (it names none:
     * the lock is on the memory file) */
    pl.lock_dir = "/nonexistent-other-lock-dir";
    setenv("BISS_LOCK_DIR", "/nonexistent-env-lock-dir", 1);
    ck_assert_int_eq(biss_open(&pl, &h2), BISS_E_BUSY);
    unsetenv("BISS_LOCK_DIR");
    biss_close(h); /* the devmem loader leaves the PRU running */

    /* attach: no reload, the running configuration, the image checked */
    ck_assert_int_eq(biss_open(&pa, &h2), BISS_OK);
    ck_assert(biss_attached(h2));
    struct biss_config back;
    ck_assert_int_eq(biss_get_config(h2, &back), BISS_OK);
    ck_assert_uint_eq(back.freq_hz, 5000000);
    ck_assert_uint_eq(back.slave[0].crc_poly, 0x43);
    ck_assert_int_eq(biss_read_sample(h2, &s), BISS_OK);
    ck_assert_uint_eq(s.slave[0].position, 0x123);
    ck_assert_int_eq(biss_get_status(h2, &status), BISS_OK);
    ck_assert_uint_eq(status.shm_version, BISS_SHM_VERSION);
    ck_assert_uint_ne(status.image_crc, 0);
    /* readers share the PRU; changing it takes it alone */
    biss_t *h3;
    ck_assert_int_eq(biss_open(&pa, &h3), BISS_OK);
    ck_assert_int_eq(biss_configure(h2, &c), BISS_E_BUSY);
    ck_assert_int_eq(biss_stop(h3), BISS_E_BUSY);
    biss_close(h3);
    ck_assert_int_eq(biss_configure(h2, &c), BISS_OK); /* alone now */
    biss_close(h2);

    /* another image than the one expected */
    struct biss_open_params po = pa;
    char other[] = "/tmp/biss_other_XXXXXX";
    int ofd = mkstemp(other);
    ck_assert_int_ge(ofd, 0);
    ck_assert_int_eq(write(ofd, "\1\2\3\4", 4), 4);
    close(ofd);
    po.firmware = other;
    ck_assert_int_eq(biss_open(&po, &h2), BISS_E_FW_IMAGE);
    ck_assert_msg(strstr(err, "CRC-32") && strstr(err, other), "%s", err);
    unlink(other);
    po.firmware = "/nonexistent.bin"; /* given: must be readable */
    ck_assert_int_eq(biss_open(&po, &h2), BISS_E_FIRMWARE_IO);

    /* junk in data RAM, as another firmware or a stray write leaves it */
    struct {
        uint32_t off, val;
        int rc;
        const char *text;
    } junk[] = {
        {BISS_CFG_NSLAVES & ~3u, 0x000a0014, BISS_E_SHM_CONFIG, "bad slave count"},
        {BISS_CFG_SLAVE0, 200, BISS_E_SHM_CONFIG, "bad slave data bits"},
        {BISS_CFG_HALF & ~3u, 1, BISS_E_SHM_CONFIG, "bad MA half period"},
        {BISS_ID + 4, BISS_SHM_VERSION + 1, BISS_E_SHM_VERSION, "BISS_SHM_VERSION"},
        {BISS_ID, 0x12345678, BISS_E_FW_ID, "0x12345678"},
    };
    for (size_t i = 0; i < sizeof junk / sizeof junk[0]; i++) {
        uint32_t keep = file32(AM335X_BASE + junk[i].off);
        file_write32(AM335X_BASE + junk[i].off, junk[i].val);
        ck_assert_int_eq(biss_open(&pa, &h2), junk[i].rc);
        ck_assert_msg(strstr(err, junk[i].text), "%zu: %s", i, err);
        file_write32(AM335X_BASE + junk[i].off, keep);
    }
    ck_assert_int_eq(biss_open(&pa, &h2), BISS_OK);
    /* a published result no firmware with this configuration writes */
    uint32_t buf = file32(AM335X_BASE + BISS_ST_BUF);
    off_t res = AM335X_BASE + buf;
    uint32_t word = file32(res + (BISS_R_NSLAVES & ~3u));
    file_write32(res + (BISS_R_NSLAVES & ~3u), (word & 0x00ffffffu) | 200u << 24);
    ck_assert_int_eq(biss_read_sample(h2, &s), BISS_E_SHM_RESULT);
    ck_assert_str_eq(biss_shm_problem(h2), "slave count: not the configuration's");
    file_write32(res + (BISS_R_NSLAVES & ~3u), word);
    ck_assert_int_eq(biss_read_sample(h2, &s), BISS_OK);
    /* fields the firmware never writes so, each refused by name: VALID
     * with ACK_JUMP, all flags, half periods 0 and 0xffff, sample point
     * 255, lag 255 at 5 MHz (the firmware waits 204 periods at most) */
    uint32_t sp = file32(res + BISS_R_SAMPLE_POINT); /* point, lag, half */
    struct {
        off_t at;
        uint32_t val;
        const char *field;
    } bad[] = {
        {res + BISS_R_FLAGS, BISS_RF_VALID | BISS_RF_ACK_JUMP, "result flags"},
        {res + BISS_R_FLAGS, 0xffffffffu, "result flags"},
        {res + BISS_R_SAMPLE_POINT, sp & 0x0000ffffu, "MA half period"},
        {res + BISS_R_SAMPLE_POINT, sp | 0xffff0000u, "MA half period"},
        {res + BISS_R_SAMPLE_POINT, (sp & ~0xffu) | 0xffu, "sample point"},
        {res + BISS_R_SAMPLE_POINT, (sp & ~0xff00u) | 0xff00u, "lag"},
    };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        uint32_t keep = file32(bad[i].at);
        file_write32(bad[i].at, bad[i].val);
        ck_assert_int_eq(biss_read_sample(h2, &s), BISS_E_SHM_RESULT);
        ck_assert_msg(strstr(biss_shm_problem(h2), bad[i].field), "%zu: %s", i,
                      biss_shm_problem(h2));
        file_write32(bad[i].at, keep);
    }
    ck_assert_int_eq(biss_read_sample(h2, &s), BISS_OK);
    file_write32(AM335X_BASE + BISS_ST_STATE, 9);
    ck_assert_int_eq(biss_get_status(h2, &status), BISS_E_SHM_RESULT);
    ck_assert_ptr_nonnull(strstr(biss_shm_problem(h2), "ST_STATE"));
    ck_assert_int_eq(biss_get_stats(h2, &st), BISS_E_SHM_RESULT);
    file_write32(AM335X_BASE + BISS_ST_STATE, BISS_STATE_RUNNING);
    file_write32(AM335X_BASE + BISS_ST_BUF, 7);
    ck_assert_int_eq(biss_read_sample(h2, &s), BISS_E_SHM_RESULT);
    biss_close(h2);

    atomic_store(&v.stop, 1);
    pthread_join(t, NULL);
    munmap(m, WINDOW);
    close(fd);
    cleanup();
}
END_TEST

/* AM437x: ICSS1 (12 KB IRAM) and ICSS0 (4 KB) at their own bases. */
/* The encoder firmware's handle (libbiss "the encoder firmware") on the
 * same stand-in board: PRU1's IRAM and CONTROL, a virtual encoder that
 * comes up when its PRU is enabled (magic, PRU, MA bit) and acks each
 * configuration, refusing a chain of 3 (as if the chain were bad) with
 * CFGERR_ID; the bytes of the configuration, the live nE/nW, the table and
 * the register files land where biss_slave_shm.h says. */
struct venc {
    volatile uint32_t *dram;
    volatile uint32_t *control;
    atomic_int stop;
};

static void *virtual_encoder(void *arg) {
    struct venc *v = arg;
    volatile uint32_t *d = v->dram;
    bool up = false;
    while (!atomic_load(&v->stop)) {
        if (!up && (*v->control & 2u)) { /* ENABLE: its start-up */
            d[BISS_SLV_ST_CFG_ACK / 4] = 0xffffffffu;
            d[BISS_SLV_ST_PRU / 4] = 1;
            ((volatile uint8_t *)d)[BISS_SLV_ST_MA_BIT] = 1;
            d[BISS_SLV_ST_MAGIC / 4] = BISS_SLV_MAGIC;
            up = true;
        }
        uint32_t cfg = d[BISS_SLV_CFG_SEQ / 4];
        if (up && cfg != 0 && cfg != d[BISS_SLV_ST_CFG_ACK / 4]) {
            uint8_t n = ((volatile uint8_t *)d)[BISS_SLV_CFG_NSLAVES];
            d[BISS_SLV_ST_CFG_ERROR / 4] = n == 3 ? BISS_SLV_CFGERR_ID : BISS_SLV_CFGERR_NONE;
            d[BISS_SLV_ST_FRAMES / 4] = 7;
            d[BISS_SLV_ST_CFG_ACK / 4] = cfg;
        }
        nanosleep(&(struct timespec){.tv_nsec = 100000}, NULL);
    }
    return NULL;
}

START_TEST(test_encoder_virtual_board) {
    make_devmem(AM335X_BASE + WINDOW);
    make_image(64);
    int fd = open(devmem, O_RDWR);
    ck_assert_int_ge(fd, 0);
    uint8_t *m = mmap(NULL, WINDOW, PROT_READ | PROT_WRITE, MAP_SHARED, fd, AM335X_BASE);
    ck_assert_ptr_ne(m, MAP_FAILED);
    struct venc v = {.dram = (volatile uint32_t *)(m + 0x2000),
                     .control = (volatile uint32_t *)(m + 0x24000)};
    pthread_t t;
    ck_assert_int_eq(pthread_create(&t, NULL, virtual_encoder, &v), 0);

    struct biss_open_params p = params(BISS_TARGET_AM335X);
    p.pru = 1;
    p.timeout_ms = 2000;
    biss_encoder_t *e;
    ck_assert_int_eq(biss_encoder_open(&p, &e), BISS_OK);
    /* the image in PRU1's IRAM (0x38000), word i = 0x1000 + i */
    uint32_t w;
    memcpy(&w, m + 0x38000 + 4 * 5, 4);
    ck_assert_uint_eq(w, 0x1005);

    struct biss_encoder_config c;
    biss_encoder_config_default(&c);
    c.nslaves = 2;
    c.slave[1] = c.slave[0];
    c.slave[1].id = 1;
    c.slave[1].pos_bits = 36;
    c.slave[1].banks = 2;
    c.slave[1].bank0 = 3;
    c.slave[1].position = 0x123456789ull;
    c.slave[1].step = -5;
    ck_assert_int_eq(biss_encoder_configure(e, &c), BISS_OK);
    ck_assert_uint_eq(m[0x2000 + BISS_SLV_CFG_NSLAVES], 2);
    ck_assert_uint_eq(m[0x2000 + BISS_SLV_CFG_SLAVE0 + BISS_SLV_CFG_SLAVE_SIZE], 36);
    ck_assert_int_eq(biss_encoder_set_ew(e, 1, true, false), BISS_OK);
    ck_assert_uint_eq(m[0x2000 + BISS_SLV_LIVE_EW + 1], BISS_SLV_EW_ERROR);
    const uint64_t tab[2] = {0xabc, 0xdef};
    ck_assert_int_eq(biss_encoder_table(e, 126, tab, 2), BISS_OK);
    ck_assert_int_eq(biss_encoder_table(e, 127, tab, 2), BISS_E_INVAL);
    uint64_t got;
    memcpy(&got, m + 0x2000 + BISS_SLV_TABLE + 127 * 8, 8);
    ck_assert_uint_eq(got, 0xdef);
    /* a direct register (read-only), and byte 0x10 of slave 1's bank 1 =
     * pool bank 3 + 1 */
    ck_assert_int_eq(biss_encoder_reg_set(e, 1, 0, 0x7e, 0x5a, true, false), BISS_OK);
    ck_assert_int_eq(biss_encoder_reg_set(e, 1, 1, 0x10, 0xc3, false, true), BISS_OK);
    ck_assert_int_eq(biss_encoder_reg_set(e, 1, 2, 0x10, 0xc3, false, false), BISS_E_INVAL);
    uint32_t regs = 0x2000 + BISS_SLV_REGS + BISS_SLV_REGS_SIZE;
    ck_assert_uint_eq(m[regs + 0x7e - 0x40], 0x5a);
    ck_assert_uint_eq(m[regs + BISS_SLV_R_RO + 0x7e / 8] >> (0x7e % 8) & 1u, 1);
    ck_assert_uint_eq(m[regs + BISS_SLV_R_WP + 0x10 / 8] >> (0x10 % 8) & 1u, 1);
    ck_assert_uint_eq(m[0x2000 + BISS_SLV_POOL + 4 * BISS_SLV_BANK_SIZE + 0x10], 0xc3);
    uint8_t b;
    ck_assert_int_eq(biss_encoder_reg_get(e, 1, 1, 0x10, &b), BISS_OK);
    ck_assert_uint_eq(b, 0xc3);
    struct biss_encoder_status st;
    ck_assert_int_eq(biss_encoder_get_status(e, &st), BISS_OK);
    ck_assert_uint_eq(st.pru, 1);
    ck_assert_uint_eq(st.ma_bit, 1);
    ck_assert_uint_eq(st.frames, 7);
    ck_assert_int_eq(st.cdm, 0);
    /* a refusal comes back as the firmware's */
    c.nslaves = 3;
    c.slave[2] = c.slave[0];
    c.slave[2].id = 2;
    ck_assert_int_eq(biss_encoder_configure(e, &c), BISS_E_ENC_REFUSED);
    ck_assert_int_eq(biss_encoder_stop(e), BISS_OK);
    uint32_t control;
    memcpy(&control, m + 0x24000, 4);
    ck_assert_uint_eq(control & 2u, 0);
    biss_encoder_close(e);
    /* the emulator target: not there (biss-sim --encoder) */
    p.target = BISS_TARGET_EMU;
    ck_assert_int_eq(biss_encoder_open(&p, &e), BISS_E_TARGET);
    atomic_store(&v.stop, 1);
    pthread_join(t, NULL);
    munmap(m, WINDOW);
    close(fd);
    cleanup();
}
END_TEST

START_TEST(test_am437x_bases_and_iram_sizes) {
    make_devmem(ICSS0_BASE + WINDOW);
    make_image(12 * 1024);
    biss_t *h;
    struct biss_open_params p = params(BISS_TARGET_AM437X_ICSS1);
    ck_assert_int_eq(biss_open(&p, &h), BISS_OK);
    ck_assert_uint_eq(file32(ICSS1_BASE + IRAM0 + 12 * 1024 - 4), 0x1000 + 3071);
    ck_assert_uint_eq(file32(ICSS1_BASE + CTRL0), 0x2);
    biss_close(h);
    p = params(BISS_TARGET_AM437X_ICSS0);
    ck_assert_int_eq(biss_open(&p, &h), BISS_E_FIRMWARE_SIZE);
    ck_assert_ptr_null(h);
    unlink(image);
    make_image(4 * 1024);
    ck_assert_int_eq(biss_open(&p, &h), BISS_OK);
    ck_assert_uint_eq(file32(ICSS0_BASE + IRAM0), 0x1000);
    ck_assert_uint_eq(file32(ICSS0_BASE + CTRL0), 0x2);
    biss_close(h);
    /* AM335x's image (8 KB max) is too big at 12 KB */
    cleanup();
    make_devmem(AM335X_BASE + WINDOW);
    make_image(8 * 1024 + 4);
    p = params(BISS_TARGET_AM335X);
    ck_assert_int_eq(biss_open(&p, &h), BISS_E_FIRMWARE_SIZE);
    cleanup();
}
END_TEST

/* Two channels of one PRU-ICSS asking for the IEP at the same time, each
 * from its own thread, with a virtual firmware on each PRU that takes a
 * while to apply a configuration (as a board's does between frames): in
 * every round one owns the IEP and the other is refused. With the owner
 * read apart from the write, both got through. */
struct claimer {
    biss_t *h;
    atomic_int *start;
    int rc;
};

static void *claim_iep(void *arg) {
    struct claimer *k = arg;
    struct biss_config c = one_slave();
    c.trigger = BISS_TRIGGER_IEP;
    c.iep_period_ns = 100000;
    while (!atomic_load(k->start)) {
    }
    k->rc = biss_configure(k->h, &c);
    return NULL;
}

START_TEST(test_iep_owned_once) {
    make_devmem(AM335X_BASE + WINDOW);
    make_image(64);
    biss_t *h[2];
    for (unsigned i = 0; i < 2; i++) {
        struct biss_open_params p = params(BISS_TARGET_AM335X);
        p.pru = i;
        p.timeout_ms = 2000;
        ck_assert_int_eq(biss_open(&p, &h[i]), BISS_OK);
    }
    int fd = open(devmem, O_RDWR);
    ck_assert_int_ge(fd, 0);
    uint8_t *m = mmap(NULL, WINDOW, PROT_READ | PROT_WRITE, MAP_SHARED, fd, AM335X_BASE);
    ck_assert_ptr_ne(m, MAP_FAILED);
    /* a configuration applied at the next frame boundary, 300 us on */
    struct vfw v[2] = {{.dram = (volatile uint32_t *)m, .ack_delay_us = 300},
                       {.dram = (volatile uint32_t *)(m + 0x2000), .pru = 1, .ack_delay_us = 300}};
    pthread_t t[2];
    for (unsigned i = 0; i < 2; i++) {
        ck_assert_int_eq(pthread_create(&t[i], NULL, virtual_firmware, &v[i]), 0);
    }
    for (int round = 0; round < 20; round++) {
        struct biss_config free_run = one_slave();
        for (unsigned i = 0; i < 2; i++) {
            ck_assert_int_eq(biss_configure(h[i], &free_run), BISS_OK); /* the IEP let go */
        }
        atomic_int start = 0;
        struct claimer k[2] = {{.h = h[0], .start = &start}, {.h = h[1], .start = &start}};
        pthread_t c[2];
        for (unsigned i = 0; i < 2; i++) {
            ck_assert_int_eq(pthread_create(&c[i], NULL, claim_iep, &k[i]), 0);
        }
        atomic_store(&start, 1);
        for (unsigned i = 0; i < 2; i++) {
            pthread_join(c[i], NULL);
        }
        ck_assert_msg((k[0].rc == BISS_OK && k[1].rc == BISS_E_IEP_OWNED) ||
                          (k[1].rc == BISS_OK && k[0].rc == BISS_E_IEP_OWNED),
                      "round %d: PRU0 %s, PRU1 %s", round, biss_strerror(k[0].rc),
                      biss_strerror(k[1].rc));
    }
    for (unsigned i = 0; i < 2; i++) {
        atomic_store(&v[i].stop, 1);
        pthread_join(t[i], NULL);
        biss_close(h[i]);
    }
    munmap(m, WINDOW);
    close(fd);
    cleanup();
}
END_TEST

/* The IEP's lock is on the memory file too: while another process holds
 * it (deciding who owns the IEP), a configuration waits its timeout, then
 * is refused; once it is let go, the configuration goes on. */
START_TEST(test_iep_lock_across_processes) {
    make_devmem(AM335X_BASE + WINDOW);
    make_image(64);
    struct biss_open_params p = params(BISS_TARGET_AM335X);
    char err[512];
    p.errbuf = err;
    p.errbuf_len = sizeof err;
    biss_t *h;
    ck_assert_int_eq(biss_open(&p, &h), BISS_OK);
    int go[2];
    ck_assert_int_eq(pipe(go), 0);
    pid_t child = fork();
    ck_assert_int_ge(child, 0);
    if (child == 0) {
        int fd = open(devmem, O_RDWR);
        struct flock fl = {
            .l_type = F_WRLCK, .l_whence = SEEK_SET, .l_start = AM335X_BASE + 0x2E000, .l_len = 1};
        char c = fcntl(fd, F_OFD_SETLK, &fl) == 0 ? 'y' : 'n';
        /* the child only writes: a read here could take its own answer
         * before the parent does, and the parent would wait forever */
        if (write(go[1], &c, 1) != 1) {
            _exit(1);
        }
        pause();
        _exit(0);
    }
    char c;
    ck_assert_int_eq(read(go[0], &c, 1), 1);
    ck_assert_int_eq(c, 'y');
    struct biss_config cfg = one_slave();
    ck_assert_int_eq(biss_configure(h, &cfg), BISS_E_BUSY);
    kill(child, SIGKILL);
    waitpid(child, NULL, 0);
    /* let go: the configuration goes on (and finds no firmware here) */
    ck_assert_int_eq(biss_configure(h, &cfg), BISS_E_NOT_RUNNING);
    biss_close(h);
    close(go[0]);
    close(go[1]);
    cleanup();
}
END_TEST

/* A file standing in for /dev/mem truncated under a reader: every access
 * an I/O error, no bus error (a mapping of the file would raise SIGBUS
 * past its new end); and a device that is no memory (/dev/zero, whose
 * shared mapping ends at its own length) is refused when opened. */
START_TEST(test_memory_gone_under_a_reader) {
    make_devmem(AM335X_BASE + WINDOW);
    make_image(64);
    struct biss_open_params p = params(BISS_TARGET_AM335X);
    biss_t *h;
    ck_assert_int_eq(biss_open(&p, &h), BISS_OK);
    ck_assert_int_eq(truncate(devmem, AM335X_BASE), 0);
    struct biss_sample s;
    struct biss_status st;
    struct biss_stats stats;
    ck_assert_int_eq(biss_read_sample(h, &s), BISS_E_IO);
    ck_assert_int_eq(biss_get_status(h, &st), BISS_E_IO);
    ck_assert_int_eq(biss_get_stats(h, &stats), BISS_E_IO);
    struct biss_config c = one_slave();
    ck_assert_int_eq(biss_configure(h, &c), BISS_E_IO);
    biss_close(h);
    char err[256];
    p.errbuf = err;
    p.errbuf_len = sizeof err;
    p.devmem = "/dev/zero";
    ck_assert_int_eq(biss_open(&p, &h), BISS_E_DEVMEM);
    ck_assert_msg(strstr(err, "/dev/zero is not /dev/mem"), "%s", err);
    p.devmem = "/tmp"; /* a directory */
    ck_assert_int_eq(biss_open(&p, &h), BISS_E_DEVMEM);
    cleanup();
}
END_TEST

START_TEST(test_open_errors) {
    make_devmem(AM335X_BASE + WINDOW);
    biss_t *h;
    char err[2048];
    struct biss_open_params p = params(BISS_TARGET_AM335X);
    p.errbuf = err;
    p.errbuf_len = sizeof err;
    make_image(0);
    ck_assert_int_eq(biss_open(&p, &h), BISS_E_FIRMWARE_SIZE);
    unlink(image);
    make_image(10);
    ck_assert_int_eq(biss_open(&p, &h), BISS_E_FIRMWARE_SIZE);
    ck_assert_msg(strstr(err, "10 bytes, not whole 32-bit words"), "%s", err);
    p.firmware = "/nonexistent/biss.bin";
    ck_assert_int_eq(biss_open(&p, &h), BISS_E_FIRMWARE_IO);
    ck_assert_msg(strstr(err, "/nonexistent/biss.bin: No such file or directory (errno 2)"), "%s",
                  err);
    p.firmware = image;
    unlink(image);
    make_image(64);
    /* every memory error names the path, the errno and a hint */
    p.devmem = "/nonexistent/mem";
    ck_assert_int_eq(biss_open(&p, &h), BISS_E_DEVMEM);
    ck_assert_msg(strstr(err, "/nonexistent/mem: No such file or directory (errno 2)"), "%s", err);
    ck_assert_msg(strstr(err, "CONFIG_DEVMEM"), "%s", err);
    /* the hint for a refusal (this suite may run as root, which no file
     * refuses): root, and strict /dev/mem */
    ck_assert_ptr_nonnull(strstr(biss_devmem_hint(EACCES), "run as root"));
    ck_assert_ptr_nonnull(strstr(biss_devmem_hint(EPERM), "iomem=relaxed"));
    p.devmem = devmem;
    /* the PRU-ICSS clock off and no pruss driver bound: refused before any
     * access to it, which would be a bus error on silicon */
    file_write32(AM335X_CLKCTRL, 0x00030000);
    file_write32(AM335X_BASE + CTRL0, 0x5a5a5a5a);
    ck_assert_int_eq(biss_open(&p, &h), BISS_E_NOT_POWERED);
    ck_assert_msg(strstr(err, "CM_PER_PRU_ICSS_CLKCTRL (0x44e000e8) = 0x00030000") &&
                      strstr(err, "/nonexistent-sysfs/bus/platform/drivers/pruss/4a300000.pruss") &&
                      strstr(err, "already requested"),
                  "%s", err);
    ck_assert_uint_eq(file32(AM335X_BASE + CTRL0), 0x5a5a5a5a); /* untouched */
    /* the pruss driver bound (a stand-in sysfs tree) is enough */
    char sys[] = "/tmp/biss_sys_XXXXXX";
    ck_assert_ptr_nonnull(mkdtemp(sys));
    char path[256];
    const char *parts[] = {"/bus", "/bus/platform", "/bus/platform/drivers",
                           "/bus/platform/drivers/pruss",
                           "/bus/platform/drivers/pruss/4a300000.pruss"};
    for (size_t i = 0; i < 5; i++) {
        snprintf(path, sizeof path, "%s%s", sys, parts[i]);
        ck_assert_int_eq(mkdir(path, 0755), 0);
    }
    p.sysfs_root = sys;
    ck_assert_int_eq(biss_open(&p, &h), BISS_OK);
    biss_close(h);
    for (size_t i = 5; i-- > 0;) {
        snprintf(path, sizeof path, "%s%s", sys, parts[i]);
        rmdir(path);
    }
    rmdir(sys);
    p.sysfs_root = "/nonexistent-sysfs";
    file_write32(AM335X_CLKCTRL, 0x2);
    cleanup();
    /* a file that ends before the PRU-ICSS window */
    make_devmem(AM335X_BASE + 0x1000);
    make_image(64);
    p.devmem = devmem;
    ck_assert_int_eq(biss_open(&p, &h), BISS_E_DEVMEM);
    ck_assert_msg(strstr(err, "ends before the PRU-ICSS window 0x4a300000..0x4a380000"), "%s", err);
    /* and one that ends before the clock control */
    cleanup();
    make_devmem(0x1000);
    make_image(64);
    ck_assert_int_eq(biss_open(&p, &h), BISS_E_NOT_POWERED);
    ck_assert_msg(strstr(err, "ends before CM_PER_PRU_ICSS_CLKCTRL"), "%s", err);
    p.target = (enum biss_target)42;
    ck_assert_int_eq(biss_open(&p, &h), BISS_E_TARGET);
    ck_assert_int_eq(biss_open(NULL, &h), BISS_E_INVAL);
    ck_assert_int_eq(biss_open(&p, NULL), BISS_E_INVAL);
    ck_assert_ptr_null(biss_emu_bench(NULL));
    cleanup();
}
END_TEST

int main(void) {
    Suite *s = suite_create("host_linux");
    TCase *tc = tcase_create("devmem-file");
    tcase_set_timeout(tc, 60);
    tcase_add_test(tc, test_image_lands_in_iram);
    tcase_add_test(tc, test_config_bytes_in_data_ram);
    tcase_add_test(tc, test_pru1_offsets);
    tcase_add_test(tc, test_virtual_board);
    tcase_add_test(tc, test_encoder_virtual_board);
    tcase_add_test(tc, test_am437x_bases_and_iram_sizes);
    tcase_add_test(tc, test_open_errors);
    tcase_add_test(tc, test_memory_gone_under_a_reader);
    tcase_add_test(tc, test_iep_lock_across_processes);
    tcase_add_test(tc, test_iep_owned_once);
    suite_add_tcase(s, tc);
    return check_run(s);
}
