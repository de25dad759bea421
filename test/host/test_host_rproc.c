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
    char tmp[600];
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
    char path[512];
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

/* Where the kernel puts the PRU-ICSS's devices, and which attributes an
 * instance has, per kernel. The device directories follow the driver
 * core: a class device lives under its parent (.../4a334000.pru/remoteproc/
 * remoteprocN), /sys/class/remoteproc/remoteprocN is a symlink to it, and
 * it has a "device" link to its parent (drivers/base/core.c,
 * device_add_class_symlinks); platform devices are named
 * "<translated address>.<node name>" (drivers/of/platform.c,
 * of_device_make_bus_id), from BeagleBoard's trees: v5.10.x-ti/v6.1.x-ti
 * am33xx-l4.dtsi (pruss@0 and pru@34000 under target-module@300000, rev
 * register 0x4a326000) and v4.19.x-ti am33xx.dtsi (pruss-soc-bus@4a326004,
 * pruss@4a300000, pru@4a334000). The "name" attribute exists since Linux
 * 5.4 (Documentation/ABI/testing/sysfs-class-remoteproc): 4.19 has only
 * firmware and state. The pruss driver's directory holds a link per bound
 * device. */
struct layout {
    const char *label;
    const char *pruss; /* the PRU-ICSS's device directory under sys/devices */
    bool has_name;     /* the instance's "name" attribute */
};
static const struct layout linux_510 = {
    "5.10",
    "platform/ocp/4a000000.interconnect/4a000000.interconnect:segment@0/"
    "4a326000.target-module/4a300000.pruss",
    true};
static const struct layout linux_419 = {
    "4.19", "platform/ocp/4a326004.pruss-soc-bus/4a300000.pruss", false};
static const struct layout *layout = &linux_510;

static void symlink_to(const char *target, const char *at) {
    ck_assert_msg(symlink(target, at) == 0, "symlink %s -> %s", at, target);
}

/* the tree: remoteproc0 another processor (the wakeup M3, under its own
 * parent), remoteproc1 PRU0 (offline, firmware named something else),
 * remoteproc2 PRU1; the chosen/overlays entry of a BiSS overlay */
static void make_tree(void) {
    snprintf(root, sizeof root, "/tmp/biss_rproc_XXXXXX");
    ck_assert_ptr_nonnull(mkdtemp(root));
    const char *procs[][3] = {
        {"remoteproc0", "platform/ocp/44d00000.wkup_m3", "44d00000.m3\n"},
        {"remoteproc1", NULL, "4a334000.pru\n"},
        {"remoteproc2", NULL, "4a338000.pru\n"},
    };
    mkdirs(root, "sys/class/remoteproc");
    for (int i = 0; i < 3; i++) {
        char parent[256], rel[320], path[400];
        if (procs[i][1]) {
            snprintf(parent, sizeof parent, "%s", procs[i][1]);
        } else {
            /* "4a334000.pru" from the name, without the newline */
            snprintf(parent, sizeof parent, "%s/%.*s", layout->pruss,
                     (int)strcspn(procs[i][2], "\n"), procs[i][2]);
        }
        snprintf(rel, sizeof rel, "sys/devices/%s/remoteproc/%s", parent, procs[i][0]);
        mkdirs(root, rel);
        if (layout->has_name) {
            snprintf(path, sizeof path, "%s/%s/name", root, rel);
            put_file(path, procs[i][2]);
        }
        snprintf(path, sizeof path, "%s/%s/state", root, rel);
        put_file(path, "offline\n");
        snprintf(path, sizeof path, "%s/%s/firmware", root, rel);
        put_file(path, "am335x-pru-fw-old\n");
        /* device -> ../../../4a334000.pru; the class entry -> the instance */
        const char *leaf = strrchr(parent, '/');
        char target[400], cls[400];
        snprintf(target, sizeof target, "../../../%s", leaf ? leaf + 1 : parent);
        snprintf(path, sizeof path, "%s/%s/device", root, rel);
        symlink_to(target, path);
        snprintf(target, sizeof target, "../../devices/%s/remoteproc/%s", parent, procs[i][0]);
        snprintf(cls, sizeof cls, "%s/sys/class/remoteproc/%s", root, procs[i][0]);
        symlink_to(target, cls);
    }
    /* the pruss driver bound to the PRU-ICSS */
    mkdirs(root, "sys/bus/platform/drivers/pruss");
    char path[400], target[320];
    snprintf(path, sizeof path, "%s/sys/bus/platform/drivers/pruss/4a300000.pruss", root);
    snprintf(target, sizeof target, "../../../../devices/%s", layout->pruss);
    symlink_to(target, path);
    mkdirs(root, "sys/firmware/devicetree/base/chosen/overlays");
    snprintf(path, sizeof path, "%s/sys/firmware/devicetree/base/chosen/overlays/BB-BISS-PRU0-00A0",
             root);
    put_file(path, "BiSS-C master");
    snprintf(rp, sizeof rp, "%s/sys/class/remoteproc/remoteproc1", root);
    snprintf(fwdir, sizeof fwdir, "%s/lib/firmware", root);
    mkdirs(root, "lib/firmware");
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

static char err[2048];

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

/* biss_leave_running: what the handle started outlives it, and a later
 * handle attaches to it and stops it. */
START_TEST(test_leave_running) {
    make_tree();
    struct kernel k = {0};
    pthread_t t;
    ck_assert_int_eq(pthread_create(&t, NULL, kernel_thread, &k), 0);
    struct biss_open_params p = params();
    biss_t *h;
    ck_assert_int_eq(biss_open(&p, &h), BISS_OK);
    ck_assert_int_eq(biss_leave_running(h), BISS_OK);
    ck_assert_int_eq(biss_start(h), BISS_OK); /* a restart does not undo it */
    wait_state("running\n");
    biss_close(h);
    nanosleep(&(struct timespec){.tv_nsec = 20000000}, NULL);
    char buf[64];
    attr("state", buf, sizeof buf);
    ck_assert_str_eq(buf, "running\n");
    ck_assert_int_eq(atomic_load(&k.starts), 2);
    p.attach = true;
    ck_assert_int_eq(biss_open(&p, &h), BISS_OK);
    ck_assert_int_eq(biss_stop(h), BISS_OK);
    wait_state("offline\n");
    biss_close(h);
    ck_assert_int_eq(biss_leave_running(NULL), BISS_E_INVAL);
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
    /* the instance missing (PRU1's IRAM address is not PRU0's): what to
     * check, from what sysfs shows: pruss bound, so pru_rproc */
    set_attr("name", "4a338000.pru\n");
    ck_assert_int_eq(biss_open(&p, &h), BISS_E_RPROC);
    ck_assert_msg(strstr(err, "no remoteproc instance of 4a334000.pru") &&
                      strstr(err, "4a300000.pruss) but has no PRU instance") &&
                      strstr(err, "modprobe pru_rproc") && !strstr(err, "overlay"),
                  "%s", err);
    /* ... and the overlay not listed */
    char cmd[300];
    snprintf(cmd, sizeof cmd, "rm %s/sys/firmware/devicetree/base/chosen/overlays/*", root);
    ck_assert_int_eq(system(cmd), 0);
    ck_assert_int_eq(biss_open(&p, &h), BISS_E_RPROC);
    ck_assert_msg(strstr(err, "no *-BISS-* overlay under") && strstr(err, "uboot_overlay_addr4"),
                  "%s", err);
    snprintf(cmd, sizeof cmd, "rm -r %s/sys/firmware/devicetree/base/chosen/overlays", root);
    ck_assert_int_eq(system(cmd), 0);
    ck_assert_int_eq(biss_open(&p, &h), BISS_E_RPROC);
    ck_assert_msg(strstr(err, "U-Boot applied no overlay"), "%s", err);
    /* the PRU-ICSS did not probe (a pin conflict) and its clock is off:
     * not touched, and the message says where to look */
    p.sysfs_root = "/nonexistent";
    ck_assert_int_eq(biss_open(&p, &h), BISS_E_NOT_POWERED); /* checked first */
    ck_assert_msg(strstr(err, "no pruss driver bound to 4a300000.pruss") &&
                      strstr(err, "already requested") && strstr(err, "bus error"),
                  "%s", err);
    /* no remoteproc at all */
    p = params();
    snprintf(cmd, sizeof cmd, "rm -rf %s/sys/class", root);
    ck_assert_int_eq(system(cmd), 0);
    ck_assert_int_eq(biss_open(&p, &h), BISS_E_RPROC);
    ck_assert_msg(strstr(err, "class/remoteproc: No such file or directory (errno 2)"), "%s", err);
    remove_tree();
}
END_TEST

/* 4.19-ti: no "name" attribute; each instance found through its device
 * link, PRU0's and PRU1's, and started with its own firmware name. */
START_TEST(test_419_without_name) {
    layout = &linux_419;
    make_tree();
    char path[300];
    snprintf(path, sizeof path, "%s/name", rp);
    ck_assert_int_ne(access(path, F_OK), 0); /* as on 4.19 */
    struct kernel k = {0};
    pthread_t t;
    ck_assert_int_eq(pthread_create(&t, NULL, kernel_thread, &k), 0);
    struct biss_open_params p = params();
    biss_t *h;
    ck_assert_msg(biss_open(&p, &h) == BISS_OK, "%s", err);
    char buf[64];
    attr("firmware", buf, sizeof buf);
    ck_assert_str_eq(buf, "biss_master.elf");
    ck_assert_int_eq(atomic_load(&k.starts), 1);
    biss_close(h);
    wait_state("offline\n");
    atomic_store(&k.stop, 1);
    pthread_join(t, NULL);
    remove_tree();
    /* PRU1, the same way */
    struct kernel k1 = {0};
    pru1_begin(&k1, &t, -1);
    p = params();
    p.pru = 1;
    ck_assert_msg(biss_open(&p, &h) == BISS_OK, "%s", err);
    attr("firmware", buf, sizeof buf);
    ck_assert_str_eq(buf, "biss_master_pru1.elf");
    biss_close(h);
    wait_state("offline\n");
    pru1_end(&k1, t);
    layout = &linux_510;
}
END_TEST

/* 4.19-ti without PRU0's instance: the others' device links (the wakeup
 * M3, PRU1) are not taken for it. */
START_TEST(test_419_missing) {
    layout = &linux_419;
    make_tree();
    char cmd[300];
    snprintf(cmd, sizeof cmd, "rm %s/sys/class/remoteproc/remoteproc1", root);
    ck_assert_int_eq(system(cmd), 0);
    struct biss_open_params p = params();
    biss_t *h;
    ck_assert_int_eq(biss_open(&p, &h), BISS_E_RPROC);
    ck_assert_msg(strstr(err, "no remoteproc instance of 4a334000.pru") &&
                      strstr(err, "modprobe pru_rproc"),
                  "%s", err);
    remove_tree();
    layout = &linux_510;
}
END_TEST

int main(void) {
    Suite *s = suite_create("host_rproc");
    TCase *tc = tcase_create("fake-sysfs");
    tcase_set_timeout(tc, 60);
    tcase_add_test(tc, test_start_stop_firmware_name);
    tcase_add_test(tc, test_attach_leaves_it_running);
    tcase_add_test(tc, test_leave_running);
    tcase_add_test(tc, test_pru1_instance);
    tcase_add_test(tc, test_pru1_wrong_image);
    tcase_add_test(tc, test_refusals);
    tcase_add_test(tc, test_419_without_name);
    tcase_add_test(tc, test_419_missing);
    suite_add_tcase(s, tc);
    return check_run(s);
}
