/* libbiss's remoteproc loader against a stand-in sysfs tree (remoteprocN
 * directories with name/state/firmware files, the pruss driver's device)
 * and a sparse file standing in for /dev/mem. A "kernel" thread plays
 * pru_rproc: on "start" it loads the identification block the ELF carries
 * and the firmware sets its magic; on "stop" the instance goes offline. */
#include "libbiss.h"

#include "biss/biss_shm_struct.h"
#include "biss_image_id.h"
#include "check_run.h"

#include <check.h>
#include <fcntl.h>
#include <pthread.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#define AM335X_BASE 0x4A300000L
#define CTRL0       0x22000L
#define IRAM0       0x34000L

static char root[64], devmem[128], image[128], rp[128], fwdir[128];
static off_t kdram;   /* the data RAM of the PRU the stand-in kernel runs (PRU1: + 0x2000) */
static int kpru = -1; /* the PRU its firmware says it was built for (-1: kdram's) */
static const uint8_t image_bytes[16] = {1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16};

/* Whole at once (a rename), as sysfs attributes read: never half written. */
static void put_file(const char *path, const char *text) {
    char tmp[300];
    snprintf(tmp, sizeof tmp, "%s.%lx", path, (unsigned long)pthread_self());
    FILE *f = fopen(tmp, "w");
    ck_assert_ptr_nonnull(f);
    fputs(text, f);
    fclose(f);
    ck_assert_int_eq(rename(tmp, path), 0);
}

static void get_file(const char *path, char *buf, size_t n) {
    FILE *f = fopen(path, "r");
    ck_assert_ptr_nonnull(f);
    size_t got = fread(buf, 1, n - 1, f);
    buf[got] = '\0';
    fclose(f);
}

static void attr(const char *name, char *buf, size_t n) {
    char path[256];
    snprintf(path, sizeof path, "%s/%s", rp, name);
    get_file(path, buf, n);
}

static void set_attr(const char *name, const char *text) {
    char path[256];
    snprintf(path, sizeof path, "%s/%s", rp, name);
    put_file(path, text);
}

/* The stand-in kernel answers within a poll or two: wait for it. */
static void wait_state(const char *want) {
    char buf[64] = "";
    for (int i = 0; i < 2000; i++) {
        attr("state", buf, sizeof buf);
        if (strcmp(buf, want) == 0) {
            return;
        }
        nanosleep(&(struct timespec){.tv_nsec = 1000000}, NULL);
    }
    ck_abort_msg("state '%s', not '%s'", buf, want);
}

static void mkdirs(const char *base, const char *rel) {
    char path[256];
    snprintf(path, sizeof path, "%s/%s", base, rel);
    for (char *s = path + strlen(base) + 1; (s = strchr(s, '/')); s++) {
        *s = '\0';
        mkdir(path, 0755);
        *s = '/';
    }
    mkdir(path, 0755);
}

static void mem_write(off_t at, const void *buf, size_t n) {
    int fd = open(devmem, O_WRONLY);
    ck_assert_int_ge(fd, 0);
    ck_assert_int_eq(pwrite(fd, buf, n, at), (ssize_t)n);
    close(fd);
}

static uint32_t mem32(off_t at) {
    uint32_t v = 0;
    int fd = open(devmem, O_RDONLY);
    ck_assert_int_ge(fd, 0);
    ck_assert_int_eq(pread(fd, &v, 4, at), 4);
    close(fd);
    return v;
}

/* the tree: remoteproc0 another processor, remoteproc1 PRU0 (offline,
 * firmware named something else), remoteproc2 PRU1 */
static void make_tree(void) {
    snprintf(root, sizeof root, "/tmp/biss_rproc_XXXXXX");
    ck_assert_ptr_nonnull(mkdtemp(root));
    const char *procs[][2] = {{"remoteproc0", "44d00000.m3\n"},
                              {"remoteproc1", "4a334000.pru\n"},
                              {"remoteproc2", "4a338000.pru\n"}};
    for (int i = 0; i < 3; i++) {
        char rel[128], path[256];
        snprintf(rel, sizeof rel, "sys/class/remoteproc/%s", procs[i][0]);
        mkdirs(root, rel);
        snprintf(path, sizeof path, "%s/%s/name", root, rel);
        put_file(path, procs[i][1]);
        snprintf(path, sizeof path, "%s/%s/state", root, rel);
        put_file(path, "offline\n");
        snprintf(path, sizeof path, "%s/%s/firmware", root, rel);
        put_file(path, "am335x-pru-fw-old\n");
    }
    mkdirs(root, "sys/bus/platform/drivers/pruss/4a300000.pruss");
    snprintf(rp, sizeof rp, "%s/sys/class/remoteproc/remoteproc1", root);
    snprintf(fwdir, sizeof fwdir, "%s/lib/firmware", root);
    mkdirs(root, "lib/firmware");
    char path[256];
    snprintf(path, sizeof path, "%s/biss_master.elf", fwdir);
    put_file(path, "an ELF");
    snprintf(devmem, sizeof devmem, "%s/mem", root);
    int fd = open(devmem, O_RDWR | O_CREAT, 0600);
    ck_assert_int_ge(fd, 0);
    ck_assert_int_eq(ftruncate(fd, AM335X_BASE + 0x80000), 0);
    close(fd);
    snprintf(image, sizeof image, "%s/biss_master.bin", root);
    fd = open(image, O_WRONLY | O_CREAT, 0600);
    ck_assert_int_eq(write(fd, image_bytes, sizeof image_bytes), (ssize_t)sizeof image_bytes);
    close(fd);
    /* sentinels: the remoteproc loader must touch neither CONTROL nor IRAM */
    uint32_t s = 0x5a5a5a5a;
    mem_write(AM335X_BASE + CTRL0, &s, 4);
    mem_write(AM335X_BASE + IRAM0, &s, 4);
}

static void remove_tree(void) {
    char cmd[128];
    snprintf(cmd, sizeof cmd, "rm -rf %s", root);
    ck_assert_int_eq(system(cmd), 0);
}

/* ---- the stand-in kernel ------------------------------------------------ */
struct kernel {
    atomic_int stop;
    atomic_int starts;
};

static void *kernel_thread(void *arg) {
    struct kernel *k = arg;
    while (!atomic_load(&k->stop)) {
        char state[64];
        attr("state", state, sizeof state);
        if (strcmp(state, "start") == 0) {
            /* pru_rproc loads the ELF's data segment: the id block */
            struct biss_shm_id id;
            biss_image_id(image_bytes, sizeof image_bytes, &id);
            mem_write(AM335X_BASE + kdram + BISS_ID, &id, sizeof id);
            atomic_fetch_add(&k->starts, 1);
            set_attr("state", "running\n");
            /* the firmware's start-up, last: the PRU it was built for
             * (kpru, else the one whose data RAM it is) and the magic */
            uint32_t st[2] = {kpru >= 0 ? (uint32_t)kpru : kdram != 0, BISS_MAGIC};
            mem_write(AM335X_BASE + kdram + BISS_ST_PRU, st, sizeof st);
        } else if (strcmp(state, "stop") == 0) {
            uint32_t zero = 0;
            mem_write(AM335X_BASE + kdram + BISS_ST_MAGIC, &zero, 4);
            set_attr("state", "offline\n");
        }
        nanosleep(&(struct timespec){.tv_nsec = 100000}, NULL);
    }
    return NULL;
}

static char err[512];

static struct biss_open_params params(void) {
    struct biss_open_params p;
    biss_open_params_default(&p);
    p.target = BISS_TARGET_AM335X;
    p.loader = BISS_LOADER_REMOTEPROC;
    p.devmem = devmem;
    p.firmware = image;
    p.timeout_ms = 2000;
    static char sys[96];
    snprintf(sys, sizeof sys, "%s/sys", root);
    p.sysfs_root = sys;
    p.firmware_dir = fwdir;
    p.lock_dir = root;
    p.errbuf = err;
    p.errbuf_len = sizeof err;
    return p;
}

START_TEST(test_start_stop_firmware_name) {
    make_tree();
    struct kernel k = {0};
    pthread_t t;
    ck_assert_int_eq(pthread_create(&t, NULL, kernel_thread, &k), 0);
    struct biss_open_params p = params();
    biss_t *h;
    ck_assert_int_eq(biss_open(&p, &h), BISS_OK);
    char buf[64];
    attr("firmware", buf, sizeof buf);
    /* the ELF's own name, not the kernel's am335x-pru0-fw (maybe another's) */
    ck_assert_str_eq(buf, "biss_master.elf");
    attr("state", buf, sizeof buf);
    ck_assert_str_eq(buf, "running\n");
    ck_assert_int_eq(atomic_load(&k.starts), 1);
    struct biss_status st;
    ck_assert_int_eq(biss_get_status(h, &st), BISS_OK);
    ck_assert(st.firmware_running && st.pru_enabled);
    ck_assert_uint_eq(st.shm_version, BISS_SHM_VERSION);
    ck_assert_uint_eq(st.image_crc, biss_crc32(image_bytes, sizeof image_bytes));
    /* stop and start go through sysfs */
    ck_assert_int_eq(biss_stop(h), BISS_OK);
    wait_state("offline\n");
    ck_assert_int_eq(biss_get_status(h, &st), BISS_OK);
    ck_assert(!st.pru_enabled);
    ck_assert_int_eq(biss_start(h), BISS_OK);
    wait_state("running\n");
    ck_assert_int_eq(atomic_load(&k.starts), 2);
    biss_close(h);
    wait_state("offline\n"); /* this handle started it: close stopped it */
    /* CONTROL and IRAM were never written: only data RAM is mapped */
    ck_assert_uint_eq(mem32(AM335X_BASE + CTRL0), 0x5a5a5a5a);
    ck_assert_uint_eq(mem32(AM335X_BASE + IRAM0), 0x5a5a5a5a);
    atomic_store(&k.stop, 1);
    pthread_join(t, NULL);
    remove_tree();
}
END_TEST

START_TEST(test_attach_leaves_it_running) {
    make_tree();
    struct kernel k = {0};
    pthread_t t;
    ck_assert_int_eq(pthread_create(&t, NULL, kernel_thread, &k), 0);
    struct biss_open_params p = params();
    biss_t *h;
    p.attach = true;
    ck_assert_int_eq(biss_open(&p, &h), BISS_E_NOT_RUNNING); /* offline: nothing there */
    ck_assert_msg(strstr(err, "remoteproc1/state is 'offline'"), "%s", err);
    p.attach = false;
    ck_assert_int_eq(biss_open(&p, &h), BISS_OK);
    biss_t *h2;
    p.attach = true;
    ck_assert_int_eq(biss_open(&p, &h2), BISS_E_BUSY); /* the loader holds it */
    biss_close(h);
    wait_state("offline\n");
    set_attr("state", "start"); /* someone else's start of our firmware */
    wait_state("running\n");
    ck_assert_int_eq(biss_open(&p, &h2), BISS_OK);
    ck_assert(biss_attached(h2));
    biss_close(h2);
    nanosleep(&(struct timespec){.tv_nsec = 20000000}, NULL);
    char buf[64];
    attr("state", buf, sizeof buf);
    ck_assert_str_eq(buf, "running\n");
    atomic_store(&k.stop, 1);
    pthread_join(t, NULL);
    remove_tree();
}
END_TEST

/* PRU1's remoteproc instance (named after its IRAM, 4a338000) with its
 * firmware name in place, and the stand-in kernel running it: the kernel's
 * PRU1 image says it was built for built_for (-1: PRU1). */
static void pru1_begin(struct kernel *k, pthread_t *t, int built_for) {
    make_tree();
    snprintf(rp, sizeof rp, "%s/sys/class/remoteproc/remoteproc2", root);
    kdram = 0x2000;
    kpru = built_for;
    char path[256];
    snprintf(path, sizeof path, "%s/biss_master_pru1.elf", fwdir);
    put_file(path, "an ELF");
    ck_assert_int_eq(pthread_create(t, NULL, kernel_thread, k), 0);
}

static void pru1_end(struct kernel *k, pthread_t t) {
    atomic_store(&k->stop, 1);
    pthread_join(t, NULL);
    kdram = 0;
    kpru = -1;
    remove_tree();
}

/* --pru 1: PRU1's instance (named after its IRAM, 4a338000) and firmware
 * name, its data RAM; PRU0's instance left alone. */
START_TEST(test_pru1_instance) {
    struct kernel k = {0};
    pthread_t t;
    pru1_begin(&k, &t, -1);
    struct biss_open_params p = params();
    p.pru = 1;
    biss_t *h;
    ck_assert_msg(biss_open(&p, &h) == BISS_OK, "%s", err);
    char buf[64];
    attr("firmware", buf, sizeof buf);
    ck_assert_str_eq(buf, "biss_master_pru1.elf");
    ck_assert_int_eq(atomic_load(&k.starts), 1);
    struct biss_status st;
    ck_assert_int_eq(biss_get_status(h, &st), BISS_OK);
    ck_assert(st.firmware_running);
    biss_close(h);
    wait_state("offline\n");
    char path[256];
    snprintf(path, sizeof path, "%s/sys/class/remoteproc/remoteproc1/firmware", root);
    get_file(path, buf, sizeof buf);
    ck_assert_str_eq(buf, "am335x-pru-fw-old\n"); /* PRU0's instance untouched */
    ck_assert_uint_eq(mem32(AM335X_BASE + CTRL0), 0x5a5a5a5a);
    pru1_end(&k, t);
}
END_TEST

/* PRU1 running an image built for PRU0 (the name linked to PRU0's ELF):
 * refused once its start-up says so (BISS_ST_PRU), with the image to use. */
START_TEST(test_pru1_wrong_image) {
    struct kernel k = {0};
    pthread_t t;
    pru1_begin(&k, &t, 0);
    struct biss_open_params p = params();
    p.pru = 1;
    biss_t *h;
    ck_assert_int_eq(biss_open(&p, &h), BISS_E_FW_PRU);
    ck_assert_msg(strstr(err, "PRU1 runs an image assembled for PRU0") &&
                      strstr(err, "biss_master_pru1"),
                  "%s", err);
    pru1_end(&k, t);
}
END_TEST

START_TEST(test_refusals) {
    make_tree();
    struct biss_open_params p = params();
    biss_t *h;
    /* busy: another firmware runs there; left as it is */
    set_attr("state", "running\n");
    set_attr("firmware", "am335x-pru0-other-fw\n");
    ck_assert_int_eq(biss_open(&p, &h), BISS_E_RPROC_BUSY);
    ck_assert_msg(strstr(err, "am335x-pru0-other-fw") && strstr(err, "echo stop"), "%s", err);
    char buf[64];
    attr("state", buf, sizeof buf);
    ck_assert_str_eq(buf, "running\n");
    attr("firmware", buf, sizeof buf);
    ck_assert_str_eq(buf, "am335x-pru0-other-fw\n");
    set_attr("state", "crashed\n");
    ck_assert_int_eq(biss_open(&p, &h), BISS_E_RPROC_BUSY);
    set_attr("state", "offline\n");
    /* the firmware is not installed under the name */
    p.rproc_firmware = "biss-not-installed.elf";
    ck_assert_int_eq(biss_open(&p, &h), BISS_E_FIRMWARE_IO);
    ck_assert_msg(strstr(err, "lib/firmware/biss-not-installed.elf: No such file"), "%s", err);
    p.rproc_firmware = NULL;
    /* the instance missing: PRU1's IRAM address is not PRU0's */
    set_attr("name", "4a338000.pru\n");
    ck_assert_int_eq(biss_open(&p, &h), BISS_E_RPROC);
    ck_assert_msg(strstr(err, "no instance named 4a334000.pru*") && strstr(err, "modprobe"), "%s",
                  err);
    /* no remoteproc at all */
    p.sysfs_root = "/nonexistent";
    ck_assert_int_eq(biss_open(&p, &h), BISS_E_NOT_POWERED); /* checked first */
    p = params();
    char cmd[160];
    snprintf(cmd, sizeof cmd, "rm -rf %s/sys/class", root);
    ck_assert_int_eq(system(cmd), 0);
    ck_assert_int_eq(biss_open(&p, &h), BISS_E_RPROC);
    ck_assert_msg(strstr(err, "class/remoteproc: No such file or directory (errno 2)"), "%s", err);
    remove_tree();
}
END_TEST

int main(void) {
    Suite *s = suite_create("host_rproc");
    TCase *tc = tcase_create("fake-sysfs");
    tcase_set_timeout(tc, 60);
    tcase_add_test(tc, test_start_stop_firmware_name);
    tcase_add_test(tc, test_attach_leaves_it_running);
    tcase_add_test(tc, test_pru1_instance);
    tcase_add_test(tc, test_pru1_wrong_image);
    tcase_add_test(tc, test_refusals);
    suite_add_tcase(s, tc);
    return check_run(s);
}
