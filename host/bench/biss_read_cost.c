/*
 * biss-read-cost - what one read of the newest sample costs the host
 * (biss_read_sample), on the two paths a program meets:
 *
 *  - the Linux backend, attached, over the PRU-ICSS mapped from a memory
 *    file: the path of a board (/dev/mem or remoteproc), whose data-RAM
 *    reads here are RAM reads. On silicon each 32-bit read of PRU data RAM
 *    also crosses the L3/L4 interconnect, which this machine cannot show.
 *  - the emulator backend (libbiss-emu), whose reads are calls into the
 *    emulated PRU-ICSS.
 *
 * The memory file is a snapshot of the emulated PRU-ICSS after the real
 * firmware ran (its data RAM with a published frame, IRAM, CONTROL), at the
 * AM335x's addresses, with CM_PER_PRU_ICSS_CLKCTRL saying "powered": the
 * attached handle checks the image, the configuration and the result as it
 * does on a board, and reads the frame the emulator published.
 *
 * A third path shows what the read costs where the PRU-ICSS is mapped (a
 * board's /dev/mem; the Linux backend reads a regular file with pread, so
 * the file cannot show it): the same snapshot in this process's memory
 * behind a backend that reads with backend_linux.c's mapped copy
 * (mmio.h: volatile 32-bit loads), counting the words each read takes.
 *
 * The ring read (biss_ring_read: every frame since the last call) is timed
 * on the same three paths with frames published between the calls: on the
 * emulator by the firmware itself (biss_run_ms of 1 ms, the servo loop's
 * poll), on the snapshot by a stand-in of the firmware's PUBLISH
 * (publish() below) that renumbers the newest slot into the next one, as
 * many frames as the emulator published in 1 ms.
 *
 * usage: biss-read-cost [--calls N] [--dir DIR] [--json]
 */
#include "bench.h"
#include "biss_priv.h"
#include "libbiss-emu.h"
#include "mmio.h"
#include "pru_core.h"
#include "pruss/pruss_map.h"

#include <errno.h>
#include <fcntl.h>
#include <getopt.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#define CM_PER_PRU_ICSS_CLKCTRL 0x44E000E8u /* AM335x TRM 8.1.12.1 */

static double now_ns(void) {
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec * 1e9 + (double)t.tv_nsec;
}

/* ns per biss_read_sample over calls calls; s the last sample. */
static int time_reads(biss_t *h, unsigned long calls, struct biss_sample *s, double *ns) {
    double t0 = now_ns();
    for (unsigned long i = 0; i < calls; i++) {
        int rc = biss_read_sample(h, s);
        if (rc != BISS_OK) {
            return rc;
        }
    }
    *ns = (now_ns() - t0) / (double)calls;
    return BISS_OK;
}

/* ---- the ring read ------------------------------------------------------ */
/* The firmware's PUBLISH (pru_fw/results.p) on a data-RAM image: the slot
 * ST_RING_NEXT names gets the newest slot's words under the next
 * publication number, then ST_BUF, ST_SEQ (and ST_FRAMES), then
 * ST_RING_NEXT moves on one stride, back to BISS_RING0 past ST_RING_LAST. */
static void publish(uint8_t *dram) {
    uint32_t seq, buf, next;
    uint16_t stride, last;
    memcpy(&seq, dram + BISS_ST_SEQ, 4);
    memcpy(&buf, dram + BISS_ST_BUF, 4);
    memcpy(&next, dram + BISS_ST_RING_NEXT, 4);
    memcpy(&stride, dram + BISS_ST_RING_STRIDE, 2);
    memcpy(&last, dram + BISS_ST_RING_LAST, 2);
    seq++;
    memmove(dram + next, dram + buf, stride);
    memcpy(dram + next + BISS_R_FRAME, &seq, 4);
    memcpy(dram + BISS_ST_BUF, &next, 4);
    memcpy(dram + BISS_ST_SEQ, &seq, 4);
    memcpy(dram + BISS_ST_FRAMES, &seq, 4);
    next += stride;
    if (next > last) {
        next = BISS_RING0;
    }
    memcpy(dram + BISS_ST_RING_NEXT, &next, 4);
}

/* What happens between two timed ring reads: the poll period's frames. */
struct between {
    int (*run)(struct between *b);
    biss_t *emu;          /* the emulator: 1 ms of it */
    uint8_t *dram;        /* the stand-ins: publish() per frame on this image, */
    int fd;               /* then written to the memory file (fd >= 0) */
    unsigned per;         /* frames a poll */
    unsigned long *words; /* the mapped path's count of 32-bit reads, or NULL */
};

static int between_emu(struct between *b) {
    return biss_run_ms(b->emu, 1);
}

static int between_publish(struct between *b) {
    for (unsigned i = 0; i < b->per; i++) {
        publish(b->dram);
    }
    if (b->fd >= 0 &&
        pwrite(b->fd, b->dram, PRUSS_AM335X_DRAM0_BYTES,
               (off_t)PRUSS_AM335X_BASE + PRUSS_OFS_DRAM0) != (ssize_t)PRUSS_AM335X_DRAM0_BYTES) {
        return BISS_E_IO;
    }
    return BISS_OK;
}

struct ring_cost {
    double ns_call;     /* per biss_ring_read */
    double frames_call; /* frames it returned */
    unsigned long lost; /* frames lost over the run (0: the reader kept up) */
    double words_call;  /* the mapped path: 32-bit reads of the PRU-ICSS a call */
};

/* calls timed ring reads, b->run between them (not timed); the first read
 * (the frames before) is not timed either. */
static int time_ring(biss_t *h, unsigned long calls, struct between *b, struct ring_cost *c) {
    struct biss_sample out[BISS_RING_SLOTS(1)];
    unsigned n;
    uint32_t lost;
    int rc = biss_ring_read(h, out, BISS_RING_SLOTS(1), &n, &lost);
    double ns = 0;
    unsigned long frames = 0;
    c->lost = 0;
    if (b->words) {
        *b->words = 0; /* the timed calls' */
    }
    for (unsigned long i = 0; rc == BISS_OK && i < calls; i++) {
        rc = b->run(b);
        if (rc != BISS_OK) {
            break;
        }
        double t0 = now_ns();
        rc = biss_ring_read(h, out, BISS_RING_SLOTS(1), &n, &lost);
        ns += now_ns() - t0;
        frames += n;
        c->lost += lost;
    }
    c->ns_call = ns / (double)calls;
    c->frames_call = (double)frames / (double)calls;
    c->words_call = b->words ? (double)*b->words / (double)calls : 0;
    return rc;
}

/* The regions of the PRU-ICSS a handle on PRU0 reads, copied from the
 * emulated core (SoC addresses: the AM335x's) into the file; IRAM, which
 * the host cannot read while the PRU runs (as on the SoC), from the image
 * the emulator loaded. */
static int snapshot(struct pru_core *core, const char *image, int fd) {
    static const struct {
        uint32_t ofs, bytes;
    } regions[] = {
        {PRUSS_OFS_DRAM0, PRUSS_AM335X_DRAM0_BYTES},
        {PRUSS_OFS_DRAM1, PRUSS_AM335X_DRAM0_BYTES},
        {PRUSS_OFS_SHARED, PRUSS_AM335X_SHARED_BYTES},
        {PRUSS_OFS_CTRL0, 0x30},
    };
    static uint8_t buf[PRUSS_AM335X_SHARED_BYTES];
    for (size_t i = 0; i < sizeof regions / sizeof regions[0]; i++) {
        uint32_t n = regions[i].bytes;
        if (pru_host_read(core, PRUSS_AM335X_BASE + regions[i].ofs, buf, n) != 0) {
            fprintf(stderr, "biss-read-cost: the emulated PRU-ICSS at 0x%05x: no read\n",
                    regions[i].ofs);
            return -1;
        }
        if (pwrite(fd, buf, n, (off_t)PRUSS_AM335X_BASE + regions[i].ofs) != (ssize_t)n) {
            return -1;
        }
    }
    int in = open(image, O_RDONLY);
    ssize_t got = in < 0 ? -1 : read(in, buf, PRUSS_AM335X_IRAM0_BYTES);
    if (in >= 0) {
        close(in);
    }
    if (got <= 0 ||
        pwrite(fd, buf, (size_t)got, (off_t)PRUSS_AM335X_BASE + PRUSS_OFS_IRAM0) != got) {
        fprintf(stderr, "biss-read-cost: the image %s: no read\n", image);
        return -1;
    }
    uint32_t powered = 0x2; /* MODULEMODE enabled, IDLEST functional */
    if (pwrite(fd, &powered, 4, CM_PER_PRU_ICSS_CLKCTRL) != 4) {
        return -1;
    }
    return ftruncate(fd, (off_t)PRUSS_AM335X_BASE + PRUSS_AM335X_WINDOW);
}

/* ---- the mapped stand-in: the snapshot in memory ------------------------ */
struct mapped {
    uint8_t *icss; /* PRUSS_AM335X_WINDOW bytes */
    unsigned long words;
};

static int mapped_read(void *ctx, uint32_t off, void *buf, size_t n) {
    struct mapped *m = ctx;
    if (off > PRUSS_AM335X_WINDOW || n > PRUSS_AM335X_WINDOW - off) {
        return BISS_E_IO;
    }
    mmio_read(buf, m->icss, off, n); /* backend_linux.c's mapped path */
    m->words += mmio_words(off, n) ? n / 4 : n;
    return BISS_OK;
}

static int mapped_write(void *ctx, uint32_t off, const void *buf, size_t n) {
    struct mapped *m = ctx;
    if (off > PRUSS_AM335X_WINDOW || n > PRUSS_AM335X_WINDOW - off) {
        return BISS_E_IO;
    }
    mmio_write(m->icss, off, buf, n);
    return BISS_OK;
}

static int mapped_advance(void *ctx, unsigned us) {
    (void)ctx;
    struct timespec t = {.tv_sec = us / 1000000, .tv_nsec = (long)(us % 1000000) * 1000};
    nanosleep(&t, NULL);
    return BISS_OK;
}

static uint64_t mapped_now_us(void *ctx) {
    (void)ctx;
    return (uint64_t)(now_ns() / 1000.0);
}

static void mapped_close(void *ctx) {
    (void)ctx; /* main() owns the memory */
}

static const struct biss_backend_ops mapped_ops = {
    .read = mapped_read,
    .write = mapped_write,
    .advance = mapped_advance,
    .now_us = mapped_now_us,
    .close = mapped_close,
    .poll_us = 100,
    .advance_sleeps = 1,
};

static struct mapped the_map;

static int mapped_open(const struct biss_open_params *p, struct biss_backend *be) {
    (void)p;
    be->ops = &mapped_ops;
    be->ctx = &the_map;
    be->iram_bytes = PRUSS_AM335X_IRAM0_BYTES;
    be->pru = 0;
    return BISS_OK;
}

static void usage(FILE *f) {
    fprintf(f, "usage: biss-read-cost [--calls N] [--dir DIR] [--json]\n"
               "The cost of one biss_read_sample, and of one biss_ring_read after each 1 ms:\n"
               "attached to a snapshot of the emulated PRU-ICSS in a memory file (a board's\n"
               "path), mapped, and on the emulator.\n"
               "  --calls N   reads timed on each path (default 1000000; ring reads N/1000,\n"
               "              at least 10)\n"
               "  --dir DIR   where the memory file goes (default /dev/shm, else /tmp)\n"
               "  --json      one JSON object instead of the table\n"
               "  --help, --version\n");
}

int main(int argc, char **argv) {
    unsigned long calls = 1000000;
    const char *dir = access("/dev/shm", W_OK) == 0 ? "/dev/shm" : "/tmp";
    int json = 0;
    static const struct option opts[] = {
        {"calls", required_argument, NULL, 'n'}, {"dir", required_argument, NULL, 'd'},
        {"json", no_argument, NULL, 'j'},        {"help", no_argument, NULL, 'h'},
        {"version", no_argument, NULL, 'V'},     {NULL, 0, NULL, 0}};
    for (int o; (o = getopt_long(argc, argv, "", opts, NULL)) != -1;) {
        char *end;
        switch (o) {
        case 'n':
            errno = 0;
            calls = strtoul(optarg, &end, 10);
            if (errno || *end || calls == 0) {
                fprintf(stderr, "biss-read-cost: --calls %s: not a count\n", optarg);
                return 2;
            }
            break;
        case 'd':
            dir = optarg;
            break;
        case 'j':
            json = 1;
            break;
        case 'h':
            usage(stdout);
            return 0;
        case 'V':
            printf("biss-read-cost %s\n", BISS_VERSION);
            return 0;
        default:
            usage(stderr);
            return 2;
        }
    }
    if (optind != argc) {
        usage(stderr);
        return 2;
    }

    struct biss_open_params p;
    biss_open_params_default(&p);
    char err[512] = "";
    p.errbuf = err;
    p.errbuf_len = sizeof err;
    biss_t *emu;
    struct biss_config c;
    biss_config_default(&c);
    int rc = biss_emu_open(&p, &emu);
    if (rc == BISS_OK && (rc = biss_config_from_emu(emu, &c)) == BISS_OK &&
        (rc = biss_configure(emu, &c)) == BISS_OK && (rc = biss_start(emu)) == BISS_OK) {
        rc = biss_run_ms(emu, 5);
    }
    if (rc != BISS_OK) {
        fprintf(stderr, "biss-read-cost: the emulator: %s%s%s\n", biss_strerror(rc),
                err[0] ? ": " : "", err);
        return 1;
    }
    struct biss_sample se, sl;
    double ns_emu, ns_linux;
    rc = time_reads(emu, calls, &se, &ns_emu);
    /* the ring: the firmware publishes between the reads, 1 ms at a time */
    unsigned long ring_calls = calls / 1000 < 10 ? 10 : calls / 1000;
    struct ring_cost ring_emu, ring_file = {0}, ring_map = {0};
    struct between b = {.run = between_emu, .emu = emu, .fd = -1};
    if (rc == BISS_OK) {
        rc = time_ring(emu, ring_calls, &b, &ring_emu);
    }
    if (rc == BISS_OK) {
        rc = biss_read_sample(emu, &se); /* the frame the snapshot holds */
    }
    if (rc != BISS_OK) {
        fprintf(stderr, "biss-read-cost: reading the emulator: %s\n", biss_strerror(rc));
        return 1;
    }
    /* the stand-ins publish as many frames a poll as the firmware did */
    b = (struct between){
        .run = between_publish, .fd = -1, .per = (unsigned)(ring_emu.frames_call + 0.5)};

    char path[4096];
    snprintf(path, sizeof path, "%s/biss-read-cost-XXXXXX", dir);
    int fd = mkstemp(path);
    if (fd < 0) {
        fprintf(stderr, "biss-read-cost: %s: %s (errno %d)\n", path, strerror(errno), errno);
        return 1;
    }
    rc = snapshot(bench_core(biss_emu_bench(emu)), biss_firmware_path(emu), fd);
    close(fd);
    /* the same snapshot, copied into memory (the mapped path) before the
     * file's ring timing publishes into the file */
    double ns_map = 0;
    double words = 0;
    struct biss_sample sm;
    if (rc == 0) {
        the_map.icss = malloc(PRUSS_AM335X_WINDOW);
        int in = open(path, O_RDONLY);
        if (!the_map.icss || in < 0 ||
            pread(in, the_map.icss, PRUSS_AM335X_WINDOW, (off_t)PRUSS_AM335X_BASE) !=
                (ssize_t)PRUSS_AM335X_WINDOW) {
            fprintf(stderr, "biss-read-cost: %s: no copy in memory\n", path);
            rc = 1;
        }
        if (in >= 0) {
            close(in);
        }
    }
    biss_t *board = NULL;
    if (rc == 0) {
        struct biss_open_params pb;
        biss_open_params_default(&pb);
        pb.target = BISS_TARGET_AM335X;
        pb.loader = BISS_LOADER_DEVMEM;
        pb.devmem = path;
        pb.attach = true;
        pb.firmware = biss_firmware_path(emu);
        pb.errbuf = err;
        pb.errbuf_len = sizeof err;
        rc = biss_open(&pb, &board);
        if (rc == BISS_OK) {
            rc = time_reads(board, calls, &sl, &ns_linux);
        }
        static uint8_t dram[PRUSS_AM335X_DRAM0_BYTES];
        b.dram = dram;
        b.fd = rc == BISS_OK ? open(path, O_RDWR) : -1;
        if (b.fd >= 0 && pread(b.fd, dram, sizeof dram,
                               (off_t)PRUSS_AM335X_BASE + PRUSS_OFS_DRAM0) == sizeof dram) {
            rc = time_ring(board, ring_calls, &b, &ring_file);
        } else if (rc == BISS_OK) {
            rc = BISS_E_IO;
        }
        if (b.fd >= 0) {
            close(b.fd);
        }
        b.fd = -1;
        if (rc != BISS_OK) {
            fprintf(stderr, "biss-read-cost: attached to %s: %s%s%s\n", path, biss_strerror(rc),
                    err[0] ? ": " : "", err);
        }
    } else {
        fprintf(stderr, "biss-read-cost: %s: %s\n", path, strerror(errno));
        rc = 1;
    }
    biss_close(board);
    if (rc == BISS_OK) {
        struct biss_open_params pm;
        biss_open_params_default(&pm);
        pm.target = BISS_TARGET_AM335X;
        pm.attach = true;
        pm.firmware = biss_firmware_path(emu);
        pm.errbuf = err;
        pm.errbuf_len = sizeof err;
        const struct biss_backends mapped_backends = {.linux_open = mapped_open};
        biss_t *hm;
        rc = biss_open_with(&pm, &mapped_backends, &hm);
        if (rc == BISS_OK) {
            the_map.words = 0;
            rc = time_reads(hm, calls, &sm, &ns_map);
            words = (double)the_map.words / (double)calls;
            b.dram = the_map.icss + PRUSS_OFS_DRAM0;
            b.words = &the_map.words;
            if (rc == BISS_OK) {
                rc = time_ring(hm, ring_calls, &b, &ring_map);
            }
            biss_close(hm);
        }
        if (rc != BISS_OK) {
            fprintf(stderr, "biss-read-cost: attached to the mapped copy: %s%s%s\n",
                    biss_strerror(rc), err[0] ? ": " : "", err);
        }
    }
    free(the_map.icss);
    biss_close(emu);
    unlink(path);
    if (rc != BISS_OK) {
        return 1;
    }
    if (sl.frame != se.frame || sl.slave[0].position != se.slave[0].position ||
        sm.frame != se.frame || sm.slave[0].position != se.slave[0].position) {
        fprintf(stderr,
                "biss-read-cost: the attached handle read frame %u position %llu, the "
                "emulator frame %u position %llu\n",
                sl.frame, (unsigned long long)sl.slave[0].position, se.frame,
                (unsigned long long)se.slave[0].position);
        return 1;
    }
    /* the reader keeps up with a 1 ms poll on every path, and the stand-ins'
     * polls return exactly the frames published */
    if (ring_emu.lost || ring_file.lost || ring_map.lost || b.per == 0 ||
        ring_file.frames_call != (double)b.per || ring_map.frames_call != (double)b.per) {
        fprintf(stderr,
                "biss-read-cost: the ring read lost frames or returned others than published "
                "(emulator %.1f a call, %lu lost; file %.1f, %lu lost; mapped %.1f, %lu lost; "
                "%u published a call)\n",
                ring_emu.frames_call, ring_emu.lost, ring_file.frames_call, ring_file.lost,
                ring_map.frames_call, ring_map.lost, b.per);
        return 1;
    }
    if (json) {
        printf("{\"calls\": %lu, \"mapped_ns\": %.1f, \"mapped_words\": %.1f, "
               "\"file_pread_ns\": %.1f, \"emulator_ns\": %.1f, \"frame\": %u, "
               "\"ring_calls\": %lu, \"ring_frames_per_call\": %.1f, "
               "\"ring_mapped_ns\": %.1f, \"ring_file_pread_ns\": %.1f, "
               "\"ring_emulator_ns\": %.1f, \"ring_mapped_words\": %.1f}\n",
               calls, ns_map, words, ns_linux, ns_emu, sl.frame, ring_calls, ring_emu.frames_call,
               ring_map.ns_call, ring_file.ns_call, ring_emu.ns_call, ring_map.words_call);
    } else {
        printf("biss_read_sample, %lu calls each (frame %u, %u slave(s)):\n", calls, sl.frame,
               sl.nslaves);
        printf("  mapped PRU-ICSS (a board's /dev/mem)  %8.1f ns/call, %.1f 32-bit reads of "
               "it a call\n",
               ns_map, words);
        printf("  Linux backend on a file (pread)       %8.1f ns/call\n", ns_linux);
        printf("  emulator backend                      %8.1f ns/call\n", ns_emu);
        printf("biss_ring_read after each 1 ms, %lu calls each (%.1f frames a call):\n", ring_calls,
               ring_emu.frames_call);
        printf("  mapped PRU-ICSS (a board's /dev/mem)  %8.1f ns/call, %6.1f ns/frame, %.1f "
               "32-bit reads of it a call\n",
               ring_map.ns_call, ring_map.ns_call / ring_emu.frames_call, ring_map.words_call);
        printf("  Linux backend on a file (pread)       %8.1f ns/call, %6.1f ns/frame\n",
               ring_file.ns_call, ring_file.ns_call / ring_emu.frames_call);
        printf("  emulator backend                      %8.1f ns/call, %6.1f ns/frame\n",
               ring_emu.ns_call, ring_emu.ns_call / ring_emu.frames_call);
    }
    return 0;
}
