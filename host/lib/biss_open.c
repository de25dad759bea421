/* biss_open.c - handles: building the backend, loading the firmware image,
 * closing. */
#include "biss_priv.h"

#include "biss/biss_shm_struct.h"
#include "biss_image_id.h"
#include "biss_oserr.h"
#include "default_image.h"
#include "read_file.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <limits.h>
#include <string.h>
#include <unistd.h>

/* Where the image is when nothing names it (host/CMakeLists.txt sets all
 * of them): the build tree's, the installed one relative to an installed
 * program's bin directory, and the one in the configured firmware
 * directory; each for PRU0 and for PRU1 (one image per PRU:
 * pru_fw/README.md). */
#ifndef BISS_BUILD_DIR
#define BISS_BUILD_DIR           "/nonexistent"
#define BISS_BUILD_FIRMWARE      "biss_master.bin"
#define BISS_BUILD_FIRMWARE_PRU1 "biss_master_pru1.bin"
#endif
#ifndef BISS_BIN_TO_FIRMWARE
#define BISS_BIN_TO_FIRMWARE      "../../lib/firmware/biss_master.bin"
#define BISS_BIN_TO_FIRMWARE_PRU1 "../../lib/firmware/biss_master_pru1.bin"
#endif
#ifndef BISS_INSTALLED_FIRMWARE
#define BISS_INSTALLED_FIRMWARE      "/lib/firmware/biss_master.bin"
#define BISS_INSTALLED_FIRMWARE_PRU1 "/lib/firmware/biss_master_pru1.bin"
#endif
#define DEFAULT_TIMEOUT_MS 100

void biss_open_params_default(struct biss_open_params *p) {
    if (!p) {
        return;
    }
    *p = (struct biss_open_params){
        .target = BISS_TARGET_EMU,
        .cable_m = -1.0,
    };
}

/* With no image named: default_image.h's choice for the PRU. */
static const char *default_firmware(unsigned pru, char *buf, size_t len) {
    const struct default_image d[2] = {
        {BISS_BUILD_DIR, BISS_BUILD_FIRMWARE, BISS_BIN_TO_FIRMWARE, BISS_INSTALLED_FIRMWARE},
        {BISS_BUILD_DIR, BISS_BUILD_FIRMWARE_PRU1, BISS_BIN_TO_FIRMWARE_PRU1,
         BISS_INSTALLED_FIRMWARE_PRU1},
    };
    return default_image(&d[pru ? 1 : 0], buf, len);
}

/* The params win, then $BISS_FIRMWARE, then default_firmware(). */
static const char *firmware_path(const struct biss_open_params *p, char *buf, size_t len) {
    if (p->firmware && *p->firmware) {
        return p->firmware;
    }
    const char *env = getenv("BISS_FIRMWARE");
    if (env && *env) {
        return env;
    }
    return default_firmware(p->pru, buf, len);
}

/* An IRAM image from path into h (h->image, h->firmware): whole 32-bit
 * words, no more than the PRU's IRAM; with master set, also a master image
 * assembled for h's PRU (one image per PRU, pru_fw/README.md: the other
 * PRU's, started, points its private area at the shared block and says
 * nothing). The encoder's images (biss_enc.c) take it with master false. */
int biss_read_image(biss_t *h, const char *path, bool master, struct biss_errbuf *e) {
    char *buf;
    size_t n;
    switch (read_file(path, h->be.iram_bytes + 1u, &buf, &n)) {
    case READ_FILE_OK:
        break;
    case READ_FILE_TOO_BIG:
        return biss_err(e, BISS_E_FIRMWARE_SIZE, "%s: more than the %u bytes of this PRU's IRAM",
                        path, (unsigned)h->be.iram_bytes);
    case READ_FILE_NOMEM:
        return BISS_E_NOMEM;
    default: {
        int err = errno;
        return biss_err(e, BISS_E_FIRMWARE_IO, "%s: %s (errno %d)", path, strerror(err), err);
    }
    }
    if (n == 0 || n % 4 != 0) {
        free(buf);
        return biss_err(e, BISS_E_FIRMWARE_SIZE, "%s: %zu bytes, not whole 32-bit words", path, n);
    }
    int built = master ? biss_image_pru(buf, n) : -1;
    if (built >= 0 && (unsigned)built != h->be.pru) {
        free(buf);
        return biss_err(e, BISS_E_FW_PRU, "%s was assembled for PRU%d, not PRU%u: load %s", path,
                        built, h->be.pru, h->be.pru ? "biss_master_pru1.bin" : "biss_master.bin");
    }
    h->image = (uint8_t *)buf;
    h->image_bytes = n;
    snprintf(h->firmware, sizeof h->firmware, "%s", path);
    return BISS_OK;
}

int biss_handle_new(enum biss_target t, const struct biss_backend *be, unsigned timeout_ms,
                    biss_t **out) {
    biss_t *h = calloc(1, sizeof *h);
    if (!h) {
        be->ops->close(be->ctx);
        return BISS_E_NOMEM;
    }
    biss_link_init(&h->link, 0, 0);
    if (pthread_mutex_init(&h->lock, NULL) != 0) {
        be->ops->close(be->ctx);
        free(h);
        return BISS_E_NOMEM;
    }
    if (pthread_mutex_init(&h->op_lock, NULL) != 0) {
        pthread_mutex_destroy(&h->lock);
        be->ops->close(be->ctx);
        free(h);
        return BISS_E_NOMEM;
    }
    h->target = t;
    h->be = *be;
    h->timeout_ms = timeout_ms ? timeout_ms : DEFAULT_TIMEOUT_MS;
    *out = h;
    return BISS_OK;
}

static int open_backend(const struct biss_open_params *p, const struct biss_backends *b,
                        struct biss_backend *be, struct biss_errbuf *e) {
    switch (p->target) {
    case BISS_TARGET_EMU:
        if (!b->emu) {
            return biss_err(e, BISS_E_TARGET,
                            "the emulator target is in libbiss-emu (biss_emu_open), "
                            "not in libbiss");
        }
        return b->emu(p, be);
    case BISS_TARGET_AM335X:
    case BISS_TARGET_AM437X_ICSS0:
    case BISS_TARGET_AM437X_ICSS1:
        return b->linux_open ? b->linux_open(p, be) : BISS_E_TARGET;
    }
    return BISS_E_TARGET;
}

/* Attached: the configuration in force is the block in data RAM, read as
 * untrusted input (another process, or another firmware, wrote it). */
static int adopt_running_config(biss_t *h, struct biss_errbuf *e) {
    struct biss_proto_io io = biss_io(h);
    struct biss_shm_config blk;
    struct biss_shm_status st;
    int rc = biss_proto_config_get(&io, &blk);
    if (!rc) {
        rc = biss_proto_status_get(&io, &st);
    }
    if (rc) {
        return rc;
    }
    uint32_t ack = st.cfg_ack, err = st.cfg_error;
    h->cfg_seq = blk.seq;
    if (blk.seq == 0 || ack != blk.seq || err != BISS_CFGERR_NONE) {
        return BISS_OK; /* not configured (yet, or refused): nothing to adopt */
    }
    const char *field;
    rc = biss_config_decode(&blk, &h->cfg, &field);
    if (rc == BISS_E_SHM_CONFIG) {
        return biss_err(e, rc, "data RAM configuration block (CFG_SEQ %u, acked): bad %s", blk.seq,
                        field);
    }
    h->configured = rc == BISS_OK;
    return BISS_OK;
}

/* The image identification block (biss_shm.h BISS_ID): this project's
 * firmware, built with this library's BISS_SHM_VERSION, and the image the
 * host expects when it has one. */
static int check_identity(biss_t *h, struct biss_errbuf *e) {
    struct biss_proto_io io = biss_io(h);
    struct biss_shm_id id;
    int rc = biss_proto_id_get(&io, &id);
    if (rc) {
        return rc;
    }
    if (id.magic != BISS_ID_MAGIC) {
        return biss_err(e, BISS_E_FW_ID,
                        "data RAM 0x%03x holds 0x%08x, not the identification "
                        "block (0x%08x): not biss_master, or a build older than the block",
                        BISS_ID, id.magic, BISS_ID_MAGIC);
    }
    if (id.shm_version != BISS_SHM_VERSION) {
        return biss_err(e, BISS_E_SHM_VERSION,
                        "the firmware was built with BISS_SHM_VERSION %u, "
                        "this library with %u: rebuild one of them",
                        id.shm_version, BISS_SHM_VERSION);
    }
    if (h->image) {
        struct biss_shm_id want;
        biss_image_id(h->image, h->image_bytes, &want);
        if (want.image_crc != id.image_crc || want.image_bytes != id.image_bytes) {
            return biss_err(e, BISS_E_FW_IMAGE,
                            "the running image has CRC-32 0x%08x (%u bytes), "
                            "%s has 0x%08x (%u bytes)",
                            id.image_crc, id.image_bytes, h->firmware, want.image_crc,
                            want.image_bytes);
        }
    }
    return BISS_OK;
}

static int magic_seen(biss_t *h, void *arg) {
    (void)arg;
    struct biss_proto_io io = biss_io(h);
    struct biss_shm_status st;
    int rc = biss_proto_status_get(&io, &st);
    return rc ? rc : st.magic == BISS_MAGIC;
}

/* The image the host expects: loaded by the devmem loader; for the
 * others (attach, remoteproc, which loads its ELF itself) only compared,
 * and the default image may be absent on a board: then the handle says
 * why it could not compare (biss_image_unchecked). */
static int expected_image(biss_t *h, const struct biss_open_params *p, bool loads,
                          struct biss_errbuf *e) {
    char buf[PATH_MAX + 64];
    const char *path = firmware_path(p, buf, sizeof buf);
    const char *env = getenv("BISS_FIRMWARE");
    bool given = (p->firmware && *p->firmware) || (env && *env);
    struct biss_errbuf why = {h->unchecked, sizeof h->unchecked};
    int rc = biss_read_image(h, path, true, (loads || given) ? e : &why);
    return rc && !loads && !given ? BISS_OK : rc;
}

static int open_linux(biss_t *h, const struct biss_open_params *p, struct biss_errbuf *e) {
    bool rproc = p->loader == BISS_LOADER_REMOTEPROC;
    int rc = expected_image(h, p, !p->attach && !rproc, e);
    if (rc) {
        return rc;
    }
    if (p->attach) {
        h->attached = true;
        rc = check_identity(h, e);
        if (!rc) {
            rc = biss_pru_image_check(h, e);
        }
        return rc ? rc : adopt_running_config(h, e);
    }
    rc = biss_pru_load_and_start(h);
    if (rc || !rproc) {
        return rc;
    }
    pthread_mutex_lock(&h->lock); /* the wait drops it while it sleeps */
    rc = biss_wait_for(h, h->timeout_ms, magic_seen, NULL);
    pthread_mutex_unlock(&h->lock);
    if (rc == BISS_E_TIMEOUT) {
        return biss_err(e, BISS_E_NOT_RUNNING,
                        "remoteproc started the firmware but no magic "
                        "appeared in data RAM within %u ms: is the installed firmware "
                        "biss_master.elf?",
                        h->timeout_ms);
    }
    if (!rc) {
        rc = check_identity(h, e);
    }
    return rc ? rc : biss_pru_image_check(h, e);
}

int biss_open_params_check(const struct biss_open_params *p, struct biss_errbuf *e) {
    if (!p) {
        return BISS_E_INVAL;
    }
    if (p->errbuf && p->errbuf_len) {
        p->errbuf[0] = '\0';
    }
    *e = (struct biss_errbuf){p->errbuf, p->errbuf_len};
    if (p->pru > 1) {
        return biss_err(e, BISS_E_INVAL, "pru %u: a PRU-ICSS has PRU 0 and PRU 1", p->pru);
    }
    return BISS_OK;
}

int biss_open_with(const struct biss_open_params *p, const struct biss_backends *b, biss_t **out) {
    if (!out) {
        return BISS_E_INVAL;
    }
    *out = NULL;
    struct biss_errbuf e;
    int rc = b ? biss_open_params_check(p, &e) : BISS_E_INVAL;
    if (rc) {
        return rc;
    }
    struct biss_backend be;
    rc = open_backend(p, b, &be, &e);
    if (rc) {
        return rc;
    }
    biss_t *h;
    rc = biss_handle_new(p->target, &be, p->timeout_ms, &h);
    if (rc) {
        return rc;
    }
    if (p->target == BISS_TARGET_EMU) {
        char buf[PATH_MAX + 64];
        rc = biss_read_image(h, firmware_path(p, buf, sizeof buf), true, &e);
        if (!rc) {
            rc = biss_pru_load_and_start(h);
        }
    } else {
        rc = open_linux(h, p, &e);
    }
    if (rc) {
        biss_close(h);
        return rc;
    }
    *out = h;
    return BISS_OK;
}

void biss_op_begin(biss_t *h) {
    pthread_mutex_lock(&h->op_lock);
    pthread_mutex_lock(&h->lock);
}

void biss_op_end(biss_t *h) {
    pthread_mutex_unlock(&h->lock);
    pthread_mutex_unlock(&h->op_lock);
}

int biss_leave_running(biss_t *h) {
    if (!h) {
        return BISS_E_INVAL;
    }
    pthread_mutex_lock(&h->lock);
    if (h->be.ops->leave_running) {
        h->be.ops->leave_running(h->be.ctx);
    }
    pthread_mutex_unlock(&h->lock);
    return BISS_OK;
}

void biss_close(biss_t *h) {
    if (!h) {
        return;
    }
    h->be.ops->close(h->be.ctx);
    pthread_mutex_destroy(&h->op_lock);
    pthread_mutex_destroy(&h->lock);
    free(h->image);
    free(h);
}

enum biss_target biss_target(const biss_t *h) {
    return h ? h->target : BISS_TARGET_EMU;
}

bool biss_attached(const biss_t *h) {
    return h && h->attached;
}

const char *biss_firmware_path(const biss_t *h) {
    return h ? h->firmware : "";
}

const char *biss_image_unchecked(const biss_t *h) {
    return h ? h->unchecked : "";
}
