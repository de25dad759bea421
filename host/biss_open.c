/* biss_open.c - handles: building the backend, loading the firmware image,
 * closing. */
#include "biss_priv.h"

#include "biss/biss_shm_struct.h"
#include "read_file.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#ifndef BISS_DEFAULT_FIRMWARE
#define BISS_DEFAULT_FIRMWARE "biss_master.bin"
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

/* The params win, then $BISS_FIRMWARE, then the build tree's image. */
static const char *firmware_path(const struct biss_open_params *p) {
    if (p->firmware && *p->firmware) {
        return p->firmware;
    }
    const char *env = getenv("BISS_FIRMWARE");
    if (env && *env) {
        return env;
    }
    return BISS_DEFAULT_FIRMWARE;
}

static int read_image(biss_t *h, const char *path) {
    char *buf;
    size_t n;
    switch (read_file(path, h->be.iram_bytes + 1u, &buf, &n)) {
    case READ_FILE_OK:
        break;
    case READ_FILE_TOO_BIG:
        return BISS_E_FIRMWARE_SIZE;
    case READ_FILE_NOMEM:
        return BISS_E_NOMEM;
    default:
        return BISS_E_FIRMWARE_IO;
    }
    if (n == 0 || n % 4 != 0) {
        free(buf);
        return BISS_E_FIRMWARE_SIZE;
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

static int open_backend(const struct biss_open_params *p, struct biss_backend *be) {
    switch (p->target) {
    case BISS_TARGET_EMU:
        return biss_emu_backend_open(p, be);
    case BISS_TARGET_AM335X:
    case BISS_TARGET_AM437X_ICSS0:
    case BISS_TARGET_AM437X_ICSS1:
        return biss_linux_backend_open(p, be);
    }
    return BISS_E_TARGET;
}

/* Attached: the configuration in force is the block in data RAM. */
static void adopt_running_config(biss_t *h) {
    struct biss_shm_config blk;
    uint32_t ack = 0, err = 1;
    if (biss_dram_read(h, 0, &blk, sizeof blk) || biss_dram_read32(h, BISS_ST_CFG_ACK, &ack) ||
        biss_dram_read32(h, BISS_ST_CFG_ERROR, &err)) {
        return;
    }
    h->cfg_seq = blk.seq;
    if (blk.seq != 0 && ack == blk.seq && err == BISS_CFGERR_NONE &&
        biss_config_decode(&blk, &h->cfg) == BISS_OK) {
        h->configured = true;
    }
}

int biss_open(const struct biss_open_params *p, biss_t **out) {
    if (!out) {
        return BISS_E_INVAL;
    }
    *out = NULL;
    if (!p) {
        return BISS_E_INVAL;
    }
    bool attach = p->attach && p->target != BISS_TARGET_EMU;
    struct biss_backend be;
    int rc = open_backend(p, &be);
    if (rc) {
        return rc;
    }
    biss_t *h;
    rc = biss_handle_new(p->target, &be, p->timeout_ms, &h);
    if (rc) {
        return rc;
    }
    if (attach) {
        adopt_running_config(h);
    } else {
        rc = read_image(h, firmware_path(p));
        if (!rc) {
            rc = biss_pru_load_and_start(h);
        }
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

const char *biss_firmware_path(const biss_t *h) {
    return h ? h->firmware : "";
}

struct bench *biss_emu_bench(biss_t *h) {
    return h ? h->be.bench : NULL;
}
