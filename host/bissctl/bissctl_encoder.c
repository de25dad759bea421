/* bissctl_encoder.c - bissctl encoder start|status|ew|stop: the encoder
 * firmware (pru_slave/) on a PRU of the board, by default PRU1, the other
 * end of the one-board loop (docs/hardware.md, "One board, both ends"). */
#include "bissctl.h"

#include "biss/biss_slave_shm.h"
#include "scenario_json.h"
#include "slave_fw.h"

#include <stdio.h>
#include <string.h>

/* What a frame lasts for a chain that moves with time: its speed becomes
 * counts per frame at this (a scenario's counts_per_frame says it exactly). */
#define NOMINAL_FRAME_PS (50 * SIM_PS_PER_US)

static int chain_of(const char *what, biss_chain_cfg *c) {
    scenario sc;
    char err[512];
    if (strchr(what, '.') || strchr(what, '/')) {
        if (scenario_load_file(what, &sc, err, sizeof err) != 0) {
            fprintf(stderr, "bissctl: encoder: %s\n", err);
            return BISSCTL_USAGE;
        }
    } else if (profile_by_name(what, &sc) != 0) {
        fprintf(stderr, "bissctl: encoder: unknown profile '%s' (biss-sim --list-profiles)\n",
                what);
        return BISSCTL_USAGE;
    }
    if (sc.model != &slave_model_biss) {
        fprintf(stderr, "bissctl: encoder: %s is not a BiSS-C chain\n", what);
        return BISSCTL_USAGE;
    }
    *c = sc.biss;
    slave_fw_chain(c, NOMINAL_FRAME_PS, stderr);
    return BISSCTL_OK;
}

/* The chain's register files (its models' bytes and rights) into the
 * encoder, byte by byte. */
static int put_registers(biss_encoder_t *e, const biss_chain_cfg *c) {
    for (unsigned i = 0; i < c->n; i++) {
        const regfile *r = &c->s[i].regs;
        for (unsigned b = 0; b <= r->nbanks; b++) {
            unsigned from = b < r->nbanks ? 0x00 : 0x40, to = from + 0x40;
            for (unsigned a = from; a < to; a++) {
                uint8_t v = a >= 0x40 ? r->direct[a - 0x40] : r->bank[b][a];
                int rc = biss_encoder_reg_set(e, i, b < r->nbanks ? b : 0, (uint8_t)a, v,
                                              r->flags[a] & REG_RO, r->flags[a] & REG_WP);
                if (rc) {
                    return rc;
                }
            }
        }
    }
    return BISS_OK;
}

static int start(struct bissctl_opts *o, biss_encoder_t **e) {
    if (o->nargs < 2) {
        fprintf(stderr, "bissctl: encoder start needs the chain: a scenario file (JSON) or a "
                        "profile name\n");
        return BISSCTL_USAGE;
    }
    biss_chain_cfg chain;
    int rc = chain_of(o->args[1], &chain);
    if (rc) {
        return rc;
    }
    struct biss_encoder_config cfg;
    char err[512];
    if (slave_fw_config(&chain, &cfg, err, sizeof err) != 0) {
        fprintf(stderr, "bissctl: encoder: %s\n", err);
        return BISSCTL_USAGE;
    }
    rc = biss_encoder_open(&o->open, e);
    if (rc) {
        fprintf(stderr, "bissctl: encoder: open: %s%s%s\n", biss_strerror(rc),
                o->errbuf[0] ? ": " : "", o->errbuf);
        return BISSCTL_FAIL;
    }
    rc = biss_encoder_configure(*e, &cfg);
    if (!rc) {
        rc = put_registers(*e, &chain);
    }
    if (!rc) {
        rc = biss_encoder_leave_running(*e);
    }
    if (rc) {
        return bissctl_fail("encoder", rc);
    }
    struct biss_encoder_status st;
    rc = biss_encoder_get_status(*e, &st);
    if (rc) {
        return bissctl_fail("encoder status", rc);
    }
    printf("encoder running on PRU%u: %u slave%s, MA in on R31 bit %u, SL out on R30 bit 0\n",
           o->open.pru, cfg.nslaves, cfg.nslaves == 1 ? "" : "s", st.ma_bit);
    return BISSCTL_OK;
}

static int status(struct bissctl_opts *o, biss_encoder_t **e) {
    o->open.attach = true;
    int rc = biss_encoder_open(&o->open, e);
    if (rc) {
        fprintf(stderr, "bissctl: encoder: %s%s%s\n", biss_strerror(rc), o->errbuf[0] ? ": " : "",
                o->errbuf);
        return BISSCTL_FAIL;
    }
    struct biss_encoder_status st;
    rc = biss_encoder_get_status(*e, &st);
    if (rc) {
        return bissctl_fail("encoder status", rc);
    }
    printf("pru=%u ma_bit=%u cfg_seq=%u cfg_error=%u\n", st.pru, st.ma_bit, st.cfg_seq,
           st.cfg_error);
    printf("frames=%u latches=%u cd_frames=%u cdm=%d cds=%u ctrl_state=%u\n", st.frames, st.latches,
           st.cd_frames, st.cdm, st.cds, st.ctrl_state);
    printf("period_ns=%u timeout_ns=%u work_cycles=%u work_pad_cycles=%u cancels=%u "
           "header_crc_errors=%u\n",
           st.period_ns, st.timeout_ns, st.work_cycles, st.work_pad_cycles, st.cancels,
           st.header_crc_errors);
    for (unsigned i = 0; i < BISS_ENC_MAX_SLAVES; i++) {
        const struct biss_encoder_slave_status *s = &st.slave[i];
        if (s->reads || s->writes || s->refused || s->write_crc_errors || s->commands ||
            s->dropped) {
            printf("slave%u reads=%u writes=%u refused=%u write_crc_errors=%u commands=%u "
                   "dropped=%u last_cmd=%d last_addr=%d\n",
                   i, s->reads, s->writes, s->refused, s->write_crc_errors, s->commands, s->dropped,
                   s->last_cmd, s->last_addr);
        }
    }
    return BISSCTL_OK;
}

/* ew SLAVE [error] [warning]: the slave's nE / nW sent active from the
 * next frame, the one not named inactive (neither: both inactive). */
static int ew(struct bissctl_opts *o, biss_encoder_t **e) {
    uint8_t slave;
    if (o->nargs < 2 || bissctl_parse_byte(o->args[1], BISS_ENC_MAX_SLAVES - 1, &slave)) {
        fprintf(stderr,
                "bissctl: encoder ew needs a slave 0..%u, then error, warning, both or "
                "neither\n",
                BISS_ENC_MAX_SLAVES - 1);
        return BISSCTL_USAGE;
    }
    bool error = false, warning = false;
    for (int i = 2; i < o->nargs; i++) {
        if (strcmp(o->args[i], "error") == 0) {
            error = true;
        } else if (strcmp(o->args[i], "warning") == 0) {
            warning = true;
        } else {
            fprintf(stderr, "bissctl: encoder ew: '%s': expected error or warning\n", o->args[i]);
            return BISSCTL_USAGE;
        }
    }
    o->open.attach = true;
    int rc = biss_encoder_open(&o->open, e);
    if (rc) {
        fprintf(stderr, "bissctl: encoder: %s%s%s\n", biss_strerror(rc), o->errbuf[0] ? ": " : "",
                o->errbuf);
        return BISSCTL_FAIL;
    }
    rc = biss_encoder_set_ew(*e, slave, error, warning);
    if (rc) {
        return bissctl_fail("encoder ew", rc);
    }
    printf("slave %u: nE %s, nW %s\n", slave, error ? "active" : "inactive",
           warning ? "active" : "inactive");
    return BISSCTL_OK;
}

static int stop(struct bissctl_opts *o, biss_encoder_t **e) {
    o->open.attach = true;
    int rc = biss_encoder_open(&o->open, e);
    if (rc == BISS_E_NOT_RUNNING) {
        printf("stopped: no encoder was running\n");
        return BISSCTL_OK;
    }
    if (rc) {
        fprintf(stderr, "bissctl: encoder: %s%s%s\n", biss_strerror(rc), o->errbuf[0] ? ": " : "",
                o->errbuf);
        return BISSCTL_FAIL;
    }
    rc = biss_encoder_stop(*e);
    if (rc) {
        return bissctl_fail("encoder stop", rc);
    }
    printf("stopped: the encoder on PRU%u\n", o->open.pru);
    return BISSCTL_OK;
}

int bissctl_encoder(struct bissctl_opts *o) {
    if (!o->pru_given) {
        o->open.pru = 1; /* the loop's: the master keeps PRU0 */
    }
    o->open.errbuf = o->errbuf;
    o->open.errbuf_len = sizeof o->errbuf;
    const char *sub = o->nargs > 0 ? o->args[0] : "";
    biss_encoder_t *e = NULL;
    int rc;
    if (strcmp(sub, "start") == 0) {
        rc = start(o, &e);
    } else if (strcmp(sub, "status") == 0) {
        rc = status(o, &e);
    } else if (strcmp(sub, "ew") == 0) {
        rc = ew(o, &e);
    } else if (strcmp(sub, "stop") == 0) {
        rc = stop(o, &e);
    } else {
        fprintf(stderr,
                "bissctl: encoder: expected start CHAIN, status, ew SLAVE [error] [warning] "
                "or stop (bissctl encoder --help)\n");
        return BISSCTL_USAGE;
    }
    biss_encoder_close(e);
    return rc;
}
