/* bissctl_cmds.c - bissctl's subcommands on an open, configured handle. */
#include "bissctl.h"

#include "biss_cd.h"

#include <stdbool.h>
#include <stdio.h>
#include <string.h>

const char bissctl_emulated_note[] =
    "emulated: target emu, no board (the PRU, the cable and the encoder are models; "
    "--target am335x or am437x for hardware)";

int bissctl_fail(const char *what, int err) {
    fprintf(stderr, "bissctl: %s: %s\n", what, biss_strerror(err));
    return BISSCTL_FAIL;
}

/* The same, naming what data RAM held when the library refused it. */
static int fail_h(biss_t *h, const char *what, int err) {
    if (err != BISS_E_SHM_RESULT) {
        return bissctl_fail(what, err);
    }
    fprintf(stderr, "bissctl: %s: %s: %s\n", what, biss_strerror(err), biss_shm_problem(h));
    return BISSCTL_FAIL;
}

static void print_delay(const struct biss_line_delay *d) {
    printf("delay_bit8=%.1f delay_cycles=%.1f delay_ns=%.1f", d->bit8, d->cycles, d->ns);
}

/* nE/nW and the CRC verdict, or "none" where the layout (c, when known)
 * has no such field: a slave without CRC (or an SSI encoder) is not "ok". */
static void print_slave(unsigned i, const struct biss_slave_result *r,
                        const struct biss_slave_config *c) {
    bool ew = !c || c->has_ew;
    bool crc = !c || c->crc_bits;
    printf(" s%u.pos=%llu s%u.data=0x%llx s%u.nE=%s s%u.nW=%s s%u.crc=%s", i,
           (unsigned long long)r->position, i, (unsigned long long)r->data, i,
           !ew        ? "none"
           : r->error ? "error"
                      : "ok",
           i,
           !ew          ? "none"
           : r->warning ? "warning"
                        : "ok",
           i,
           !crc        ? "none"
           : r->crc_ok ? "ok"
                       : "bad");
}

/* The safety verdicts of a frame: each checked slave's life counter,
 * each pair ("-": not judged in this frame: the first read, a bad CRC). */
static void print_safety(const struct biss_sample *s, const struct biss_config *c) {
    for (unsigned i = 0; i < s->nslaves && i < c->nslaves; i++) {
        uint32_t f = s->slave[i].safety;
        if (c->slave[i].life_check) {
            printf(" s%u.life=%s", i,
                   !(f & BISS_SAFE_LC_CHECKED) ? "-"
                   : f & BISS_SAFE_LC_FROZEN   ? "frozen"
                   : f & BISS_SAFE_LC_SKIP     ? "skip"
                                               : "ok");
        }
    }
    for (unsigned i = 0; i < s->nslaves && i < c->nslaves; i++) {
        uint32_t f = s->slave[i].safety;
        if (c->slave[i].max_speed) {
            printf(" s%u.speed=%s", i,
                   f & BISS_SAFE_POS_UNTIMED      ? "untimed"
                   : !(f & BISS_SAFE_POS_CHECKED) ? "-"
                   : f & BISS_SAFE_POS_JUMP       ? "jump"
                                                  : "ok");
        }
    }
    for (unsigned k = 0; k < c->npairs; k++) {
        uint32_t f = s->slave[c->pair[k].a].safety & s->slave[c->pair[k].b].safety;
        printf(" pair%u=%s", k,
               !(f & BISS_SAFE_PAIR_CHECKED) ? "-"
               : f & BISS_SAFE_DISAGREE      ? "disagree"
                                             : "ok");
    }
}

static void print_sample(const struct biss_sample *s, const struct biss_config *c) {
    printf("frame=%u flags=0x%02x %s", s->frame, s->flags, bissctl_frame_state(s));
    if (s->flags & BISS_RF_IEP_LATE) { /* off its IEP period's count (BISS_RF_IEP_LATE) */
        printf(" iep-late");
    }
    if (s->valid) {
        for (unsigned i = 0; i < s->nslaves; i++) {
            print_slave(i, &s->slave[i], c && i < c->nslaves ? &c->slave[i] : NULL);
        }
        if (c) {
            print_safety(s, c);
        }
    }
    if (s->valid || s->training) {
        printf(" ");
        print_delay(&s->delay);
    }
    if (s->valid) { /* the sample point (1/8 bit) and lag a data frame was read with */
        printf(" sample_point=%u lag=%u", s->sample_point, s->lag_periods);
    }
    if (s->link_eye >= 0) { /* the nearest edge seen from a sample point (proto/biss_link.c) */
        printf(" eye=%d/8%s", s->link_eye, s->link_warning ? " link-warning" : "");
    }
    /* IEP counts of one PRU cycle, 5 ns (the firmware sets increment 1) */
    printf(" timestamp=%u (IEP counts of 5 ns: %.3f us)\n", s->timestamp, s->timestamp * 5e-3);
}

static void print_stats(const struct biss_stats *st) {
    printf("frames=%u crc_errors=%u no_slave=%u proc_errors=%u training=%u off_grid=%u\n",
           st->frames, st->crc_errors, st->no_slave, st->proc_errors, st->training, st->off_grid);
}

/* The link's eye over the frames this run read (proto/biss_link.c). */
static void print_link_stats(biss_t *h) {
    struct biss_link_stats k;
    if (biss_get_link_stats(h, &k) != BISS_OK || k.frames == 0) {
        return;
    }
    printf("link: frames=%u eye_mean=%.2f/8 eye_min=%u/8 marginal=%u off_grid=%u warned=%u\n",
           k.frames, biss_link_eye_mean(&k), k.eye_min, k.marginal, k.off_grid, k.warnings);
}

/* The safety checks' counts over the frames this run read, for the
 * checks configured (nothing without any). */
static void print_safety_stats(biss_t *h) {
    struct biss_config c;
    struct biss_safety_stats st;
    if (biss_get_config(h, &c) != BISS_OK || biss_get_safety_stats(h, &st) != BISS_OK) {
        return;
    }
    bool any = false;
    for (unsigned i = 0; i < c.nslaves; i++) {
        if (c.slave[i].life_check) {
            printf("%ss%u.life_checked=%u s%u.life_frozen=%u s%u.life_skipped=%u",
                   any ? " " : "safety: ", i, st.lc_checked[i], i, st.lc_frozen[i], i,
                   st.lc_skipped[i]);
            any = true;
        }
    }
    for (unsigned i = 0; i < c.nslaves; i++) {
        if (c.slave[i].ew_static) {
            printf("%ss%u.ew_checked=%u s%u.misframed=%u", any ? " " : "safety: ", i,
                   st.ew_checked[i], i, st.ew_set[i]);
            any = true;
        }
    }
    for (unsigned i = 0; i < c.nslaves; i++) {
        if (c.slave[i].max_speed) {
            printf("%ss%u.pos_checked=%u s%u.pos_jumped=%u s%u.pos_resync=%u s%u.pos_untimed=%u",
                   any ? " " : "safety: ", i, st.pos_checked[i], i, st.pos_jumped[i], i,
                   st.pos_resync[i], i, st.pos_untimed[i]);
            any = true;
        }
    }
    for (unsigned k = 0; k < c.npairs; k++) {
        printf("%spair%u.checked=%u pair%u.disagree=%u pair%u.last_diff=%lld",
               any ? " " : "safety: ", k, st.pair_checked[k], k, st.pair_disagree[k], k,
               (long long)st.pair_last_diff[k]);
        any = true;
    }
    if (any) {
        printf("\n");
    }
}

/* An emulated master is born with the command and has run no frame yet:
 * info and stats let it run first (--ms, as run), so their counts are
 * those of a master that ran, and say so. On hardware they count what the
 * running master did. */
static int emu_run_first(biss_t *h, const struct bissctl_opts *o, const char *what) {
    if (biss_target(h) != BISS_TARGET_EMU) {
        return BISSCTL_OK;
    }
    int rc = biss_run_ms(h, o->run_ms);
    if (rc) {
        return bissctl_fail(what, rc);
    }
    printf("emulated: counts after %u ms of simulated time (a new emulated master each "
           "command; --ms MS for longer)\n",
           o->run_ms);
    return BISSCTL_OK;
}

static int print_counts(biss_t *h) {
    struct biss_stats st;
    int rc = biss_get_stats(h, &st);
    if (rc) {
        return fail_h(h, "stats", rc);
    }
    print_stats(&st);
    return BISSCTL_OK;
}

int bissctl_stats(biss_t *h, const struct bissctl_opts *o) {
    int rc = emu_run_first(h, o, "stats");
    return rc ? rc : print_counts(h);
}

int bissctl_info(biss_t *h, const struct bissctl_opts *o) {
    struct biss_status st;
    int rc = emu_run_first(h, o, "info");
    if (rc) {
        return rc;
    }
    rc = biss_get_status(h, &st);
    if (rc) {
        return fail_h(h, "info", rc);
    }
    printf("target=%s firmware=%s%s\n", biss_target_name(biss_target(h)),
           *biss_firmware_path(h) ? biss_firmware_path(h) : "(not known here)",
           biss_attached(h) ? " (attached)" : "");
    printf("shm_version=%u image_crc=0x%08x\n", st.shm_version, st.image_crc);
    printf("pru=%s firmware_running=%s state=%s\n", st.pru_enabled ? "enabled" : "halted",
           st.firmware_running ? "yes" : "no", biss_fw_state_name(st.state));
    printf("cfg_seq=%u cfg_ack=%u cfg_error=%u publications=%u\n", st.cfg_seq, st.cfg_ack,
           st.cfg_error, st.seq);
    struct biss_config c;
    if (biss_get_config(h, &c) == BISS_OK) {
        printf("freq_hz=%u slaves=%u trigger=%s proc_limit=%u\n", c.freq_hz, c.nslaves,
               biss_trigger_name(c.trigger), c.proc_limit);
    }
    return print_counts(h);
}

/* In host-trigger mode a frame comes only when asked for. The firmware
 * measures the line with a training frame of its own after a
 * configuration; that one is not the answer to the trigger. */
static int next_sample(biss_t *h, const struct bissctl_opts *o, uint32_t after,
                       struct biss_sample *s) {
    struct biss_config c;
    if (biss_get_config(h, &c) != BISS_OK || c.trigger != BISS_TRIGGER_HOST) {
        return biss_wait_sample(h, after, o->timeout_ms, s);
    }
    int rc = biss_trigger(h);
    if (rc == BISS_E_TRIGGER_PENDING) {
        rc = BISS_OK; /* the last one's frame is still to come (an untriggered one answered it) */
    }
    while (rc == BISS_OK) {
        rc = biss_wait_sample(h, after, o->timeout_ms, s);
        if (rc == BISS_OK && !s->training) {
            break;
        }
        after = s->frame;
    }
    return rc;
}

int bissctl_read(biss_t *h, const struct bissctl_opts *o) {
    struct biss_sample s;
    /* start after what is already published: every line is a new frame */
    uint32_t after = 0;
    struct biss_config c;
    bool layout = biss_get_config(h, &c) == BISS_OK;
    if (biss_read_sample(h, &s) == BISS_OK) {
        after = s.frame;
    }
    if (o->json) { /* on the emulator: says so here, in place of the text note */
        enum biss_target t = biss_target(h);
        printf("{\n  \"target\": \"%s\",\n  \"emulated\": %s,\n  \"frames\": [",
               biss_target_name(t), t == BISS_TARGET_EMU ? "true" : "false");
    }
    for (unsigned i = 0; i < o->count; i++) {
        int rc = next_sample(h, o, after, &s);
        if (rc) {
            if (o->json) {
                printf("\n  ]\n}\n"); /* what was read stays valid JSON */
            }
            return fail_h(h, "read", rc);
        }
        if (o->json) {
            bissctl_json_frame(&s, layout ? &c : NULL, i == 0);
        } else {
            print_sample(&s, layout ? &c : NULL);
        }
        bissctl_line_note(&s);
        after = s.frame;
    }
    bissctl_line_report(h, o);
    if (o->json) {
        bissctl_json_end(h);
    } else {
        print_safety_stats(h);
        print_link_stats(h);
    }
    return BISSCTL_OK;
}

int bissctl_trigger(biss_t *h, const struct bissctl_opts *o) {
    struct bissctl_opts one = *o;
    one.count = 1;
    struct biss_config c;
    if (biss_get_config(h, &c) != BISS_OK || c.trigger != BISS_TRIGGER_HOST) {
        return bissctl_fail("trigger", BISS_E_NOT_HOST_TRIG);
    }
    return bissctl_read(h, &one);
}

int bissctl_run(biss_t *h, const struct bissctl_opts *o) {
    int rc = biss_run_ms(h, o->run_ms);
    if (rc) {
        return bissctl_fail("run", rc);
    }
    rc = print_counts(h);
    struct biss_line_delay d;
    if (rc == BISSCTL_OK && biss_line_delay(h, &d) == BISS_OK) {
        print_delay(&d);
        printf("\n");
    }
    /* the latest frame tells what the line measured, or that no slave answered */
    struct biss_sample s;
    if (rc == BISSCTL_OK && biss_read_sample(h, &s) == BISS_OK) {
        if (biss_line_delay(h, &d) == BISS_OK) {
            s.delay = d;
            s.training = !s.valid;
            s.no_slave = false;
        }
        bissctl_line_note(&s);
        bissctl_line_report(h, o);
    }
    return rc;
}

/* Opening loaded and started the master and the configuration went in
 * (only an attached handle restarts it here); it is left running for
 * others to attach to: on hardware it outlives bissctl, the emulated one
 * ends with it. */
int bissctl_start(biss_t *h, const struct bissctl_opts *o) {
    int rc = biss_attached(h) ? biss_start(h) : BISS_OK;
    if (!rc) {
        rc = biss_leave_running(h);
    }
    struct biss_config c;
    if (!rc) {
        rc = biss_get_config(h, &c);
    }
    if (rc) {
        return bissctl_fail("start", rc);
    }
    /* the configuration just went in: its first frame is the training,
     * and what it measured is checked (a warning, or why no slave
     * answered, on stderr) */
    struct biss_sample s;
    if (biss_wait_sample(h, 0, o->timeout_ms, &s) == BISS_OK) {
        bissctl_line_note(&s);
        bissctl_line_report(h, o);
    }
    bool emu = biss_target(h) == BISS_TARGET_EMU;
    printf("started: target=%s pru=%u firmware=%s freq_hz=%u slaves=%u trigger=%s\n",
           biss_target_name(biss_target(h)), o->open.pru,
           *biss_firmware_path(h) ? biss_firmware_path(h) : "(not known here)", c.freq_hz,
           c.nslaves, biss_trigger_name(c.trigger));
    printf("%s\n", emu ? "the emulated master ends with this bissctl"
                       : "it keeps running after bissctl exits: read, info and stats attach "
                         "to it; bissctl stop stops it");
    return BISSCTL_OK;
}

int bissctl_stop(biss_t *h, const struct bissctl_opts *o) {
    int rc = biss_stop(h);
    if (rc) {
        return bissctl_fail("stop", rc);
    }
    printf("stopped: target=%s pru=%u\n", biss_target_name(biss_target(h)), o->open.pru);
    return BISSCTL_OK;
}

static int parse_addr(const struct bissctl_opts *o, uint8_t *addr) {
    if (o->nargs < 1 || bissctl_parse_byte(o->args[0], 0x7f, addr)) {
        return bissctl_usage_error("%s needs a register address 0x00..0x7f", o->command);
    }
    return BISSCTL_OK;
}

/* 16 registers a line from addr (wrapping after 0x7F as the slave does),
 * printable bytes as ASCII after them. */
static void print_dump(uint8_t addr, const uint8_t *buf, unsigned n) {
    for (unsigned line = 0; line < n; line += 16) {
        unsigned k = n - line < 16 ? n - line : 16;
        printf("0x%02x:", (addr + line) & 0x7f);
        for (unsigned i = 0; i < 16; i++) {
            printf(i < k ? " %02x" : "   ", buf[line + i < n ? line + i : 0]);
        }
        printf("  ");
        for (unsigned i = 0; i < k; i++) {
            uint8_t c = buf[line + i];
            putchar(c >= 0x20 && c < 0x7f ? c : '.');
        }
        printf("\n");
    }
}

int bissctl_reg_read(biss_t *h, const struct bissctl_opts *o) {
    uint8_t addr, buf[BISS_REG_MAX_SEQ];
    int rc = parse_addr(o, &addr);
    if (rc) {
        return rc;
    }
    if (o->nargs > 1) {
        return bissctl_usage_error("reg-read takes one address (-n N for more registers)");
    }
    rc = biss_reg_read(h, o->id, addr, buf, o->count);
    if (rc) {
        return bissctl_fail("reg-read", rc);
    }
    if (o->dump) {
        print_dump(addr, buf, o->count);
        return BISSCTL_OK;
    }
    for (unsigned i = 0; i < o->count; i++) {
        printf("id=%u addr=0x%02x value=0x%02x\n", o->id, (addr + i) & 0x7f, buf[i]);
    }
    return BISSCTL_OK;
}

int bissctl_reg_write(biss_t *h, const struct bissctl_opts *o) {
    uint8_t addr, buf[BISS_REG_MAX_SEQ];
    int rc = parse_addr(o, &addr);
    if (rc) {
        return rc;
    }
    unsigned n = (unsigned)o->nargs - 1;
    if (n < 1 || n > BISS_REG_MAX_SEQ) {
        return bissctl_usage_error("reg-write needs 1..64 bytes after the address");
    }
    for (unsigned i = 0; i < n; i++) {
        if (bissctl_parse_byte(o->args[1 + i], 0xff, &buf[i])) {
            return bissctl_usage_error("reg-write: '%s' is not a byte", o->args[1 + i]);
        }
    }
    rc = biss_reg_write(h, o->id, addr, buf, n);
    return rc ? bissctl_fail("reg-write", rc) : BISSCTL_OK;
}

/* The slaves a command goes to, in words. */
/* "every slave (broadcast)", "ID 1", "IDs 0, 2" */
static const char *targets_text(uint8_t ids, char *buf, size_t size) {
    if (!ids) {
        return "every slave (broadcast)";
    }
    size_t at = (size_t)snprintf(buf, size, "ID%s", (ids & (ids - 1)) ? "s" : "");
    for (unsigned i = 0, n = 0; i < 8 && at < size; i++) {
        if (ids >> i & 1u) {
            at += (size_t)snprintf(buf + at, size - at, "%s %u", n++ ? "," : "", i);
        }
    }
    return buf;
}

static void print_targets(uint8_t ids, FILE *f) {
    char buf[48];
    fputs(targets_text(ids, buf, sizeof buf), f);
}

/* A command that changes how an encoder works goes out with --force only
 * (a usage error: the command's help lists what each command does). */
static int check_command(const struct bissctl_opts *o, uint8_t ids, uint8_t cmd) {
    const biss_cd_cmd_info *c = biss_cd_cmd_effect(ids, cmd);
    if (c->changes_encoder && !o->force) {
        char buf[48];
        return bissctl_usage_error(
            "command 0x%02x %u to %s %s: that changes how an encoder works; --force sends it", ids,
            cmd, targets_text(ids, buf, sizeof buf), c->effect);
    }
    return BISSCTL_OK;
}

int bissctl_command(biss_t *h, const struct bissctl_opts *o) {
    uint8_t ids, cmd, ida = 0;
    if (o->nargs != 2 || bissctl_parse_byte(o->args[0], 0xff, &ids) ||
        bissctl_parse_byte(o->args[1], 3, &cmd)) {
        return bissctl_usage_error("command needs an ID mask 0..0xff and a command 0..3");
    }
    int rc = check_command(o, ids, cmd);
    if (rc) {
        return rc;
    }
    printf("command %u to ", cmd);
    print_targets(ids, stdout);
    printf(": %s\n", biss_cd_cmd_effect(ids, cmd)->effect);
    rc = biss_command(h, ids, cmd, o->ida_test, &ida);
    if (!rc || rc == BISS_E_CD_IDA || rc == BISS_E_CD_WITHHELD) {
        printf("ids=0x%02x cmd=%u ida=0x%02x\n", ids, cmd, ida); /* which IDs answered */
    }
    return rc ? bissctl_fail("command", rc) : BISSCTL_OK;
}

int bissctl_check_args(const struct bissctl_opts *o) {
    uint8_t addr, b;
    if (strcmp(o->command, "reg-read") == 0) {
        int rc = parse_addr(o, &addr);
        if (!rc && o->nargs > 1) {
            rc = bissctl_usage_error("reg-read takes one address (-n N for more registers)");
        }
        if (!rc && o->count > BISS_REG_MAX_SEQ) {
            rc = bissctl_usage_error("reg-read reads at most %d registers", BISS_REG_MAX_SEQ);
        }
        return rc;
    }
    if (strcmp(o->command, "reg-write") == 0) {
        int rc = parse_addr(o, &addr);
        if (rc) {
            return rc;
        }
        if (o->nargs < 2 || o->nargs - 1 > BISS_REG_MAX_SEQ) {
            return bissctl_usage_error("reg-write needs 1..64 bytes after the address");
        }
        for (int i = 1; i < o->nargs; i++) {
            if (bissctl_parse_byte(o->args[i], 0xff, &b)) {
                return bissctl_usage_error("reg-write: '%s' is not a byte", o->args[i]);
            }
        }
        return BISSCTL_OK;
    }
    if (strcmp(o->command, "record") == 0 && o->nargs != 1) {
        return bissctl_usage_error("record needs one FILE (.csv or .npy)");
    }
    if (strcmp(o->command, "command") == 0) {
        uint8_t cmd;
        if (o->nargs != 2 || bissctl_parse_byte(o->args[0], 0xff, &b) ||
            bissctl_parse_byte(o->args[1], 3, &cmd)) {
            return bissctl_usage_error("command needs an ID mask 0..0xff and a command 0..3");
        }
        return check_command(o, b, cmd);
    }
    return BISSCTL_OK;
}
