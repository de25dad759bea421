/* bissctl_record.c - record: every frame from the firmware's result ring
 * (biss_ring_read) into a CSV file or a NumPy .npy file. */
#include "bissctl.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

/* Frames taken from the library per call (more wait for the next). */
#define BATCH 1024

/* One file being written: its format and the columns' slave count. */
struct rec_file {
    FILE *f;
    const char *path;
    bool npy;
    unsigned nslaves;
    uint64_t rows;
};

/* ---- NumPy .npy, format version 1.0 (numpy.lib.format): the magic
 * "\x93NUMPY", 1, 0, the header's length (u16, little-endian), the header
 * (a Python dict literal: descr, fortran_order, shape; padded with spaces
 * and a newline to a multiple of 64 bytes with what precedes it), then the
 * rows, packed, little-endian, in the order descr lists the fields. ---- */
#define NPY_PREFIX 10
#define NPY_ALIGN  64

/* The columns of a row, as the CSV header and npy's descr name them, and
 * their npy types. */
static const struct {
    const char *name, *type;
} frame_fields[] = {{"seq", "<u4"},   {"timestamp", "<u4"}, {"flags", "<u4"},
                    {"valid", "|u1"}, {"link_eye", "|i1"},  {"link_warning", "|u1"}};
static const struct {
    const char *name, *type;
} slave_fields[] = {
    {"position", "<u8"}, {"data", "<u8"}, {"error", "|u1"}, {"warning", "|u1"}, {"crc_ok", "|u1"}};

/* The header dict for rows rows, padded to the length that the most rows
 * (20 digits) would need, so that the first and the last agree. */
static int npy_header(const struct rec_file *r, uint64_t rows, char *out, size_t cap) {
    char descr[2048];
    size_t n = 0;
    for (size_t i = 0; i < sizeof frame_fields / sizeof frame_fields[0]; i++) {
        n += (size_t)snprintf(descr + n, sizeof descr - n, "('%s', '%s'), ", frame_fields[i].name,
                              frame_fields[i].type);
    }
    for (unsigned s = 0; s < r->nslaves; s++) {
        for (size_t i = 0; i < sizeof slave_fields / sizeof slave_fields[0]; i++) {
            n += (size_t)snprintf(descr + n, sizeof descr - n, "('s%u_%s', '%s'), ", s,
                                  slave_fields[i].name, slave_fields[i].type);
        }
    }
    const char *fmt = "{'descr': [%s], 'fortran_order': False, 'shape': (%llu,), }";
    int most = snprintf(NULL, 0, fmt, descr, 18446744073709551615ull);
    int len = snprintf(out, cap, fmt, descr, (unsigned long long)rows);
    size_t total = ((size_t)NPY_PREFIX + (size_t)most + 1 + NPY_ALIGN - 1) / NPY_ALIGN * NPY_ALIGN;
    size_t hlen = total - NPY_PREFIX;
    if (len < 0 || hlen + 1 > cap) {
        return -1;
    }
    memset(out + len, ' ', hlen - (size_t)len - 1);
    out[hlen - 1] = '\n';
    return (int)hlen;
}

static int npy_write_header(struct rec_file *r) {
    char h[4096];
    int hlen = npy_header(r, r->rows, h, sizeof h);
    if (hlen < 0) {
        errno = EINVAL;
        return -1;
    }
    unsigned char pre[NPY_PREFIX] = {
        0x93, 'N', 'U', 'M', 'P', 'Y', 1, 0, (unsigned char)hlen, (unsigned char)(hlen >> 8)};
    if (fseek(r->f, 0, SEEK_SET) || fwrite(pre, 1, sizeof pre, r->f) != sizeof pre ||
        fwrite(h, 1, (size_t)hlen, r->f) != (size_t)hlen) {
        return -1;
    }
    return fseek(r->f, 0, SEEK_END);
}

static size_t put_le(unsigned char *p, uint64_t v, unsigned bytes) {
    for (unsigned i = 0; i < bytes; i++) {
        p[i] = (unsigned char)(v >> (8 * i));
    }
    return bytes;
}

static int npy_row(struct rec_file *r, const struct biss_sample *s) {
    unsigned char row[15 + BISS_API_MAX_SLAVES * 19];
    size_t n = 0;
    n += put_le(row + n, s->seq, 4);
    n += put_le(row + n, s->timestamp, 4);
    n += put_le(row + n, s->flags, 4);
    n += put_le(row + n, s->valid, 1);
    n += put_le(row + n, (uint8_t)(int8_t)s->link_eye, 1); /* -1: not measured */
    n += put_le(row + n, s->link_warning, 1);
    for (unsigned i = 0; i < r->nslaves; i++) {
        const struct biss_slave_result *sl = &s->slave[i];
        n += put_le(row + n, sl->position, 8);
        n += put_le(row + n, sl->data, 8);
        n += put_le(row + n, sl->error, 1);
        n += put_le(row + n, sl->warning, 1);
        n += put_le(row + n, sl->crc_ok, 1);
    }
    return fwrite(row, 1, n, r->f) == n ? 0 : -1;
}

/* ---- CSV: a header line, then one line a frame ---- */
static int csv_header(struct rec_file *r) {
    for (size_t i = 0; i < sizeof frame_fields / sizeof frame_fields[0]; i++) {
        fprintf(r->f, "%s%s", i ? "," : "", frame_fields[i].name);
    }
    for (unsigned s = 0; s < r->nslaves; s++) {
        for (size_t i = 0; i < sizeof slave_fields / sizeof slave_fields[0]; i++) {
            fprintf(r->f, ",s%u_%s", s, slave_fields[i].name);
        }
    }
    return fprintf(r->f, "\n") < 0 ? -1 : 0;
}

static int csv_row(struct rec_file *r, const struct biss_sample *s) {
    fprintf(r->f, "%u,%u,0x%x,%d,%d,%d", s->seq, s->timestamp, s->flags, s->valid, s->link_eye,
            s->link_warning);
    for (unsigned i = 0; i < r->nslaves; i++) {
        const struct biss_slave_result *sl = &s->slave[i];
        fprintf(r->f, ",%llu,0x%llx,%d,%d,%d", (unsigned long long)sl->position,
                (unsigned long long)sl->data, sl->error, sl->warning, sl->crc_ok);
    }
    return fprintf(r->f, "\n") < 0 ? -1 : 0;
}

static bool ends_with(const char *s, const char *tail) {
    size_t n = strlen(s), t = strlen(tail);
    return n >= t && strcmp(s + n - t, tail) == 0;
}

static int file_failed(const struct rec_file *r) {
    fprintf(stderr, "bissctl: record: %s: %s\n", r->path, strerror(errno ? errno : EIO));
    return BISSCTL_FAIL;
}

/* What the record has seen so far. */
struct rec_count {
    uint64_t frames, lost;
    uint32_t first_seq, last_seq;
};

/* Everything published since the last call, into the file: the library's
 * code (0 or BISS_E_*), *file_err set on a write that failed. */
static int drain(biss_t *h, struct rec_file *r, struct biss_sample *buf, struct rec_count *c,
                 bool *file_err) {
    for (;;) {
        unsigned n = 0;
        uint32_t lost = 0;
        int rc = biss_ring_read(h, buf, BATCH, &n, &lost);
        c->lost += lost;
        if (rc) {
            return rc;
        }
        for (unsigned i = 0; i < n; i++) {
            if (c->frames == 0) {
                c->first_seq = buf[i].seq - (uint32_t)c->lost; /* lost ones came before it */
            }
            errno = 0;
            if ((r->npy ? npy_row(r, &buf[i]) : csv_row(r, &buf[i])) != 0) {
                *file_err = true;
                return BISS_OK;
            }
            c->frames++;
            r->rows++;
            c->last_seq = buf[i].seq;
        }
        if (n < BATCH) {
            return BISS_OK;
        }
    }
}

static double now_s(void) {
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + t.tv_nsec / 1e9;
}

int bissctl_record(biss_t *h, const struct bissctl_opts *o) {
    struct biss_config c;
    int rc = biss_get_config(h, &c);
    unsigned capacity = 0;
    if (!rc) {
        rc = biss_ring_capacity(h, &capacity);
    }
    if (rc) {
        return bissctl_fail("record", rc);
    }
    struct rec_file r = {.path = o->args[0], .nslaves = c.nslaves};
    r.npy = o->format ? strcmp(o->format, "npy") == 0 : ends_with(r.path, ".npy");
    struct biss_sample *buf = malloc(BATCH * sizeof *buf);
    r.f = buf ? fopen(r.path, "wb") : NULL;
    if (!r.f) {
        int err = buf ? errno : ENOMEM;
        free(buf);
        errno = err;
        return file_failed(&r);
    }
    errno = 0;
    bool ferr = (r.npy ? npy_write_header(&r) : csv_header(&r)) != 0;
    struct rec_count cnt = {0};
    double start = now_s(), shown = start;
    bool emu = biss_target(h) == BISS_TARGET_EMU;
    rc = BISS_OK;
    const uint64_t record_us = (uint64_t)o->record_ms * 1000u;
    for (uint64_t us = 0; !ferr && !rc && us < record_us;) {
        unsigned step = o->poll_us < record_us - us ? o->poll_us : (unsigned)(record_us - us);
        rc = biss_run_us(h, step); /* the poll period (emu: simulated) */
        us += step;
        if (!rc) {
            rc = drain(h, &r, buf, &cnt, &ferr);
        }
        double t = now_s();
        if (t - shown >= 1.0) {
            shown = t;
            fprintf(stderr, "record: %.1f of %.1f s%s, %llu frames, %llu lost\n", us / 1e6,
                    o->record_ms / 1000.0, emu ? " (simulated)" : "",
                    (unsigned long long)cnt.frames, (unsigned long long)cnt.lost);
        }
    }
    free(buf);
    if (!ferr && r.npy) {
        ferr = npy_write_header(&r) != 0; /* now with the row count */
    }
    if (fclose(r.f) && !ferr) {
        ferr = true;
    }
    if (ferr) {
        return file_failed(&r);
    }
    if (rc) {
        return bissctl_fail("record", rc);
    }
    printf("recorded=%llu lost=%llu first_seq=%u last_seq=%u seconds=%.3f ring_frames=%u "
           "poll_ms=%g format=%s file=%s\n",
           (unsigned long long)cnt.frames, (unsigned long long)cnt.lost, cnt.first_seq,
           cnt.last_seq, o->record_ms / 1000.0, capacity, o->poll_us / 1000.0,
           r.npy ? "npy" : "csv", r.path);
    if (cnt.lost) {
        fprintf(stderr,
                "bissctl: record: %llu frames lost: the ring holds %u frames; read it more "
                "often (--poll-ms) or at a lower rate\n",
                (unsigned long long)cnt.lost, capacity);
        return BISSCTL_FAIL;
    }
    return BISSCTL_OK;
}
