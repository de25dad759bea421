/* backend_emu.c - libbiss-emu: the in-process backend, the bench's
 * emulated PRU-ICSS, reached through the same global addresses as on the
 * SoC. Time is simulated and moves only in advance(). */
#include "biss_priv.h"
#include "libbiss-emu.h"

#include "backends.h"

#include "bench.h"
#include "bench_fw.h"
#include "scenario_json.h"

#include <pthread.h>
#include <stdbool.h>
#include <stdlib.h>

#define EMU_DEFAULT_PROFILE "tidep0022-test-encoder"

/* A bench pair behind two handles (biss_emu_open_pair), freed with the
 * second handle closed. */
struct emu_pair {
    struct bench *bench[2];
    unsigned refs;
    pthread_mutex_t lock; /* the two handles' locks do not order their runs */
    pthread_mutex_t iep;  /* the PRU-ICSS's IEP (biss_backend_ops.iep_lock) */
};

struct emu {
    struct bench *bench;
    uint32_t base;         /* global address of the PRU-ICSS */
    struct emu_pair *pair; /* NULL: the bench is this handle's own */
};

/* A pair's handles each hold only their own lock: the pair's orders
 * their use of the shared PRU-ICSS. */
static void pair_lock(struct emu *e) {
    if (e->pair) {
        pthread_mutex_lock(&e->pair->lock);
    }
}

static void pair_unlock(struct emu *e) {
    if (e->pair) {
        pthread_mutex_unlock(&e->pair->lock);
    }
}

static int emu_read(void *ctx, uint32_t off, void *buf, size_t n) {
    struct emu *e = ctx;
    pair_lock(e);
    int rc = pru_host_read(bench_core(e->bench), e->base + off, buf, n);
    pair_unlock(e);
    return rc ? BISS_E_IO : BISS_OK;
}

static int emu_write(void *ctx, uint32_t off, const void *buf, size_t n) {
    struct emu *e = ctx;
    pair_lock(e);
    int rc = pru_host_write(bench_core(e->bench), e->base + off, buf, n);
    pair_unlock(e);
    return rc ? BISS_E_IO : BISS_OK;
}

static int emu_advance(void *ctx, unsigned us) {
    struct emu *e = ctx;
    pair_lock(e);
    int64_t until = pru_time_ps(bench_core(e->bench)) + (int64_t)us * SIM_PS_PER_US;
    enum pru_stop why = bench_run_until(e->bench, until);
    /* a stopped PRU (DISABLED) lets time pass; a fault is final, and so is
     * a HALT of this handle's own PRU (not of the other of a pair) */
    bool halted = why == PRU_STOP_HALT && pru_halted(bench_core(e->bench));
    pair_unlock(e);
    return why == PRU_STOP_FAULT || halted ? BISS_E_PRU_FAULT : BISS_OK;
}

static uint64_t emu_now_us(void *ctx) {
    struct emu *e = ctx;
    pair_lock(e);
    uint64_t us = (uint64_t)(pru_time_ps(bench_core(e->bench)) / SIM_PS_PER_US);
    pair_unlock(e);
    return us;
}

static void emu_close(void *ctx) {
    struct emu *e = ctx;
    struct emu_pair *pr = e->pair;
    if (!pr) {
        bench_free(e->bench);
    } else {
        pthread_mutex_lock(&pr->lock);
        bool last = --pr->refs == 0;
        pthread_mutex_unlock(&pr->lock);
        if (last) {
            bench_free(pr->bench[1]); /* PRU0's bench owns the PRU-ICSS */
            bench_free(pr->bench[0]);
            pthread_mutex_destroy(&pr->iep);
            pthread_mutex_destroy(&pr->lock);
            free(pr);
        }
    }
    free(e);
}

/* The pair's IEP: the two handles' configurations decide who owns it one
 * at a time (a handle of its own has no other channel). */
static int emu_iep_lock(void *ctx, bool take, unsigned timeout_ms) {
    struct emu *e = ctx;
    (void)timeout_ms; /* held for one configuration, which ends */
    if (e->pair && take) {
        pthread_mutex_lock(&e->pair->iep);
    } else if (e->pair) {
        pthread_mutex_unlock(&e->pair->iep);
    }
    return BISS_OK;
}

static const struct biss_backend_ops emu_ops = {
    .read = emu_read,
    .write = emu_write,
    .advance = emu_advance,
    .now_us = emu_now_us,
    .close = emu_close,
    .iep_lock = emu_iep_lock,
    .poll_us = 1, /* a 10 MHz frame is ~20 us: publications are seen within 1 us */
    .advance_sleeps = 0,
};

static int build_scenario(const struct biss_open_params *p, scenario *sc) {
    char err[256];
    if (p->scenario_file && *p->scenario_file) {
        if (scenario_load_file(p->scenario_file, sc, err, sizeof err) != 0) {
            return BISS_E_SCENARIO;
        }
    } else if (profile_by_name(p->profile && *p->profile ? p->profile : EMU_DEFAULT_PROFILE, sc) !=
               0) {
        return BISS_E_PROFILE;
    }
    if (p->cable_m >= 0) {
        scenario_set_cable(sc, p->cable_m);
    }
    if (p->set_seed) {
        sc->seed = p->seed;
    }
    return scenario_check(sc, err, sizeof err) == 0 ? BISS_OK : BISS_E_SCENARIO;
}

static int emu_backend_open(const struct biss_open_params *p, struct biss_backend *be) {
    struct bench_config cfg;
    bench_config_default(&cfg);
    cfg.pru_index = p->pru; /* the bench's line on that PRU of the PRU-ICSS */
    int rc = build_scenario(p, &cfg.link);
    if (rc) {
        return rc;
    }
    struct emu *e = calloc(1, sizeof *e);
    if (!e) {
        return BISS_E_NOMEM;
    }
    char err[256];
    e->bench = bench_new(&cfg, err, sizeof err);
    if (!e->bench) {
        free(e);
        return BISS_E_EMU;
    }
    e->base = pru_soc_base(cfg.soc);
    *be = (struct biss_backend){
        .ops = &emu_ops,
        .ctx = e,
        .iram_bytes = pru_iram_bytes(bench_core(e->bench)),
        .pru = p->pru,
        .bench = e->bench,
    };
    return BISS_OK;
}

int biss_emu_open(const struct biss_open_params *p, biss_t **out) {
    static const struct biss_backends both = {.linux_open = biss_linux_backend_open,
                                              .emu = emu_backend_open};
    return biss_open_with(p, &both, out);
}

/* The params biss_open_with hands to the backend, with the pair and the
 * PRU behind them (p first: the backend gets a pointer to it). */
struct pair_open {
    struct biss_open_params p;
    struct emu_pair *pair;
};

static int pair_backend_open(const struct biss_open_params *p, struct biss_backend *be) {
    const struct pair_open *po = (const struct pair_open *)p;
    struct emu *e = calloc(1, sizeof *e);
    if (!e) {
        return BISS_E_NOMEM;
    }
    struct bench *b = po->pair->bench[p->pru];
    e->bench = b;
    e->pair = po->pair;
    e->base = pru_soc_base(bench_config(b)->soc);
    po->pair->refs++;
    *be = (struct biss_backend){
        .ops = &emu_ops,
        .ctx = e,
        .iram_bytes = pru_iram_bytes(bench_core(b)),
        .pru = p->pru,
        .bench = b,
    };
    return BISS_OK;
}

int biss_emu_open_pair(const struct biss_open_params p[2], biss_t *h[2]) {
    if (!p || !h) {
        return BISS_E_INVAL;
    }
    h[0] = h[1] = NULL;
    struct bench_config cfg[2];
    for (unsigned i = 0; i < 2; i++) {
        if (p[i].target != BISS_TARGET_EMU) {
            return BISS_E_TARGET;
        }
        bench_config_default(&cfg[i]);
        int rc = build_scenario(&p[i], &cfg[i].link);
        if (rc) {
            return rc;
        }
    }
    struct emu_pair *pr = calloc(1, sizeof *pr);
    if (!pr) {
        return BISS_E_NOMEM;
    }
    char err[256];
    if (bench_new_pair(cfg, pr->bench, err, sizeof err) != 0) {
        free(pr);
        return BISS_E_EMU;
    }
    pthread_mutex_init(&pr->lock, NULL);
    pthread_mutex_init(&pr->iep, NULL);
    pr->refs = 1; /* this call's, until both handles hold theirs */
    static const struct biss_backends pair = {.emu = pair_backend_open}; /* both "emu" */
    int rc = BISS_OK;
    for (unsigned i = 0; i < 2 && !rc; i++) {
        struct pair_open po = {.p = p[i], .pair = pr};
        po.p.pru = i;
        rc = biss_open_with(&po.p, &pair, &h[i]);
    }
    if (rc) {
        biss_close(h[0]); /* a failed open closed its own backend already */
        h[0] = h[1] = NULL;
    }
    pthread_mutex_lock(&pr->lock);
    bool last = --pr->refs == 0;
    pthread_mutex_unlock(&pr->lock);
    if (last) {
        bench_free(pr->bench[1]);
        bench_free(pr->bench[0]);
        pthread_mutex_destroy(&pr->iep);
        pthread_mutex_destroy(&pr->lock);
        free(pr);
    }
    return rc;
}

struct bench *biss_emu_bench(biss_t *h) {
    return h ? h->be.bench : NULL;
}

int biss_config_from_emu(biss_t *h, struct biss_config *c) {
    if (!h || !c) {
        return BISS_E_INVAL;
    }
    if (!h->be.bench) {
        return BISS_E_NOT_EMU;
    }
    pthread_mutex_lock(&h->lock);
    /* the chain's layout by proto's rule; the SSI round trip the bench's
     * line gives, as a user would measure it */
    bench_fw_layout(h->be.bench, c);
    int rc = BISS_OK;
    pthread_mutex_unlock(&h->lock);
    return rc;
}
