/*
 * hal_biss.c - a LinuxCNC HAL component reading the BiSS-C master on a PRU
 * through libbiss, once per servo period, without blocking.
 *
 *   loadrt hal_biss target=am335x pru=0          (a board: attach to the
 *                                                 master the service runs)
 *   loadrt hal_biss target=emu scenario=FILE      (the desk: the emulator)
 *   addf hal-biss.0.read servo-thread
 *
 * On a board the component attaches to the master that biss-master@pruN
 * started with /etc/biss/pruN.conf (docs/hardware.md), so the slave layout
 * is that file's, one source for the service and the machine; attaching
 * changes nothing the firmware does. With target=emu it starts the
 * firmware on the emulated PRU against the profile or scenario given,
 * with the encoder's own layout, and each servo period lets that much
 * emulated time pass first (whole milliseconds, carried over): the
 * emulated encoder moves with the servo thread, not with the wall clock.
 *
 * Pins (N the slave, nearest the master 0): see README.md. A frame that is
 * not valid (no slave, CRC error, processing error, misframed) keeps the
 * last good position on the pins and clears `valid`.
 */
#include "hal.h"
#include "rtapi.h"
#include "rtapi_app.h"

#include <libbiss-emu.h>
#include <math.h>

static char *target = "emu";
RTAPI_MP_STRING(target, "emu, am335x, am437x-icss0 or am437x-icss1");
static int pru = 0;
RTAPI_MP_INT(pru, "the PRU (0 or 1) of the PRU-ICSS");
static char *profile = NULL;
RTAPI_MP_STRING(profile, "target=emu: the encoder profile (default tidep0022-test-encoder)");
static char *scenario = NULL;
RTAPI_MP_STRING(scenario, "target=emu: a JSON scenario file (wins over profile)");
static char *firmware = NULL;
RTAPI_MP_STRING(firmware, "target=emu: the firmware image (default: libbiss's, /lib/firmware)");
static int freq = 0;
RTAPI_MP_INT(freq, "target=emu: the MA rate in Hz (0: libbiss's default)");

struct slave_pins {
    hal_u32_t *raw;        /* the position field, low 32 bits */
    hal_float_t *position; /* scaled, unwrapped: (turns * 2^bits + raw) / scale */
    hal_bit_t *valid;      /* this frame's position is good */
    hal_bit_t *error;      /* nE active */
    hal_bit_t *warning;    /* nW active */
    hal_u32_t *crc_errors; /* frames with this slave's CRC wrong */
    hal_u32_t *faults;     /* other frames not valid: no slave, processing, misframed */
    hal_float_t scale;     /* counts per machine unit (param) */
    hal_u32_t turn_bits;   /* param: the position's bits for a single-turn encoder, whose
                              turns the component counts (0: none counted) */
    hal_s32_t *turns;      /* the turns counted */
    rtapi_u64 last;        /* the last good raw position */
    bool have_last;
};

struct master {
    biss_t *h;
    bool emu;
    long carry_ns;           /* emulated time owed (target=emu) */
    hal_u32_t *frame;        /* the firmware's frame number of the sample on the pins */
    bool have_frame;         /* a sample is on the pins (frame numbers wrap: 0 is one) */
    hal_u32_t *age;          /* servo periods since the frame number last changed */
    hal_bit_t *running;      /* the firmware runs and publishes */
    hal_s32_t *last_error;   /* the last libbiss error of a read (0: none) */
    hal_s32_t *link_eye;     /* the frame's eye opening, eighths of a bit (-1: none measured) */
    hal_bit_t *link_warning; /* marginal frames reached the warning (proto/biss_link.c) */
    unsigned nslaves;
    struct slave_pins s[BISS_API_MAX_SLAVES];
};

static int comp_id;
static struct master *m;

/* Counts a single-turn encoder's turns: a step of more than half a turn
 * is a wrap (no shaft turns half a revolution in one frame). */
static void unwrap(struct slave_pins *p, rtapi_u64 pos) {
    if (p->turn_bits == 0 || p->turn_bits > 63) {
        return;
    }
    rtapi_u64 range = (rtapi_u64)1 << p->turn_bits;
    if (p->have_last) {
        if (p->last > pos && p->last - pos > range / 2) {
            (*p->turns)++;
        } else if (pos > p->last && pos - p->last > range / 2) {
            (*p->turns)--;
        }
    }
}

static void publish(struct master *c, const struct biss_sample *s) {
    for (unsigned i = 0; i < c->nslaves && i < s->nslaves; i++) {
        struct slave_pins *p = &c->s[i];
        const struct biss_slave_result *r = &s->slave[i];
        bool good = s->valid && !s->training && r->crc_ok;
        *p->valid = good;
        *p->error = good && r->error;
        *p->warning = good && r->warning;
        if (!r->crc_ok && !s->no_slave) {
            (*p->crc_errors)++;
        } else if (!good && !s->training) {
            (*p->faults)++;
        }
        if (!good) {
            continue;
        }
        unwrap(p, r->position);
        p->last = r->position;
        p->have_last = true;
        *p->raw = (rtapi_u32)r->position;
        double counts = (double)r->position;
        if (p->turn_bits > 0 && p->turn_bits < 64) {
            counts += ldexp((double)*p->turns, (int)p->turn_bits);
        }
        *p->position = counts / (p->scale != 0.0 ? p->scale : 1.0);
    }
}

/* The servo thread's function: the newest sample, if a new one came. */
static void read_biss(void *arg, long period) {
    struct master *c = arg;
    if (c->emu) {
        c->carry_ns += period;
        if (c->carry_ns >= 1000000) {
            unsigned ms = (unsigned)(c->carry_ns / 1000000);
            c->carry_ns -= (long)ms * 1000000;
            int rc = biss_run_ms(c->h, ms);
            if (rc != BISS_OK) {
                *c->last_error = rc;
            }
        }
    }
    struct biss_sample s;
    int rc = biss_read_sample(c->h, &s);
    *c->running = rc == BISS_OK || rc == BISS_E_NO_SAMPLE;
    if (rc != BISS_OK) {
        if (rc != BISS_E_NO_SAMPLE) {
            *c->last_error = rc;
        }
        (*c->age)++;
        return;
    }
    if (c->have_frame && s.frame == *c->frame) {
        (*c->age)++;
        return;
    }
    *c->frame = s.frame;
    c->have_frame = true;
    *c->age = 0;
    *c->link_eye = s.link_eye;
    *c->link_warning = s.link_warning;
    publish(c, &s);
}

static int open_master(struct master *c) {
    struct biss_open_params p;
    biss_open_params_default(&p);
    if (biss_target_from_name(target, &p.target) != BISS_OK) {
        rtapi_print_msg(RTAPI_MSG_ERR, "hal_biss: target=%s: %s\n", target,
                        biss_strerror(BISS_E_TARGET));
        return -EINVAL;
    }
    char err[256] = "";
    p.errbuf = err;
    p.errbuf_len = sizeof err;
    p.pru = (unsigned)pru;
    c->emu = p.target == BISS_TARGET_EMU;
    p.attach = !c->emu;
    p.profile = profile;
    p.scenario_file = scenario;
    p.firmware = c->emu ? firmware : NULL;
    int rc = biss_emu_open(&p, &c->h);
    if (rc != BISS_OK) {
        rtapi_print_msg(RTAPI_MSG_ERR, "hal_biss: open %s (pru %d): %s%s%s\n", target, pru,
                        biss_strerror(rc), err[0] ? ": " : "", err);
        return -ENODEV;
    }
    struct biss_config cfg;
    biss_config_default(&cfg);
    if (c->emu) {
        rc = biss_config_from_emu(c->h, &cfg);
        if (rc == BISS_OK && freq > 0) {
            cfg.freq_hz = (uint32_t)freq;
        }
        if (rc == BISS_OK) {
            rc = biss_configure(c->h, &cfg);
        }
        if (rc == BISS_OK) {
            rc = biss_start(c->h);
        }
    } else {
        rc = biss_get_config(c->h, &cfg);
    }
    if (rc != BISS_OK) {
        rtapi_print_msg(RTAPI_MSG_ERR, "hal_biss: %s master: %s\n",
                        c->emu ? "starting the" : "reading the running", biss_strerror(rc));
        biss_close(c->h);
        return -ENODEV;
    }
    c->nslaves = cfg.nslaves;
    return 0;
}

static int make_pins(struct master *c, const char *n) {
    int r = 0;
    r |= hal_pin_u32_newf(HAL_OUT, &c->frame, comp_id, "%s.frame", n);
    r |= hal_pin_u32_newf(HAL_OUT, &c->age, comp_id, "%s.frame-age", n);
    r |= hal_pin_bit_newf(HAL_OUT, &c->running, comp_id, "%s.running", n);
    r |= hal_pin_s32_newf(HAL_OUT, &c->last_error, comp_id, "%s.last-error", n);
    r |= hal_pin_s32_newf(HAL_OUT, &c->link_eye, comp_id, "%s.link-eye", n);
    r |= hal_pin_bit_newf(HAL_OUT, &c->link_warning, comp_id, "%s.link-warning", n);
    for (unsigned i = 0; i < c->nslaves && r == 0; i++) {
        struct slave_pins *p = &c->s[i];
        r |= hal_pin_u32_newf(HAL_OUT, &p->raw, comp_id, "%s.slave.%u.raw", n, i);
        r |= hal_pin_float_newf(HAL_OUT, &p->position, comp_id, "%s.slave.%u.position", n, i);
        r |= hal_pin_bit_newf(HAL_OUT, &p->valid, comp_id, "%s.slave.%u.valid", n, i);
        r |= hal_pin_bit_newf(HAL_OUT, &p->error, comp_id, "%s.slave.%u.error", n, i);
        r |= hal_pin_bit_newf(HAL_OUT, &p->warning, comp_id, "%s.slave.%u.warning", n, i);
        r |= hal_pin_u32_newf(HAL_OUT, &p->crc_errors, comp_id, "%s.slave.%u.crc-errors", n, i);
        r |= hal_pin_u32_newf(HAL_OUT, &p->faults, comp_id, "%s.slave.%u.faults", n, i);
        r |= hal_pin_s32_newf(HAL_OUT, &p->turns, comp_id, "%s.slave.%u.turns", n, i);
        r |= hal_param_float_newf(HAL_RW, &p->scale, comp_id, "%s.slave.%u.scale", n, i);
        r |= hal_param_u32_newf(HAL_RW, &p->turn_bits, comp_id, "%s.slave.%u.turn-bits", n, i);
        p->scale = 1.0;
    }
    return r;
}

int rtapi_app_main(void) {
    comp_id = hal_init("hal_biss");
    if (comp_id < 0) {
        return comp_id;
    }
    m = hal_malloc(sizeof *m);
    if (m == NULL) {
        hal_exit(comp_id);
        return -ENOMEM;
    }
    *m = (struct master){0};
    int rc = open_master(m);
    if (rc == 0 && make_pins(m, "hal-biss.0") != 0) {
        rc = -EINVAL;
    }
    if (rc == 0) {
        rc = hal_export_funct("hal-biss.0.read", read_biss, m, 1, 0, comp_id);
    }
    if (rc != 0) {
        if (m->h != NULL) {
            biss_close(m->h);
            m->h = NULL;
        }
        hal_exit(comp_id);
        return rc;
    }
    rtapi_print_msg(RTAPI_MSG_INFO, "hal_biss: %s pru %d, %u slave(s)\n", target, pru, m->nslaves);
    hal_ready(comp_id);
    return 0;
}

void rtapi_app_exit(void) {
    if (m != NULL && m->h != NULL) {
        biss_close(m->h); /* attached: the master runs on; emu: it stops */
        m->h = NULL;
    }
    hal_exit(comp_id);
}
