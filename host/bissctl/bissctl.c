/* bissctl - the libbiss command line: the same subcommands on the
 * emulator and on a real PRU-ICSS. */
#include "bissctl.h"
#include "libbiss-emu.h"

#include <stdio.h>
#include <string.h>

struct command {
    const char *name;
    int (*run)(biss_t *h, const struct bissctl_opts *o);
    bool configure; /* needs the configuration applied first */
};

static const struct command table[] = {
    {"info", bissctl_info, true},
    {"read", bissctl_read, true},
    {"stats", bissctl_stats, true},
    {"run", bissctl_run, true},
    {"trigger", bissctl_trigger, true},
    {"start", bissctl_start, true},
    {"stop", bissctl_stop, false},
    {"reg-read", bissctl_reg_read, true},
    {"reg-write", bissctl_reg_write, true},
    {"command", bissctl_command, true},
    {"probe", bissctl_probe, false}, /* configures its own capture layout */
    {"record", bissctl_record, true},
    {"rates", NULL, false},   /* needs no target: bissctl_rates */
    {"encoder", NULL, false}, /* its own handle: bissctl_encoder */
};

static const struct command *find(const char *name) {
    for (size_t i = 0; i < sizeof table / sizeof table[0]; i++) {
        if (strcmp(name, table[i].name) == 0) {
            return &table[i];
        }
    }
    return NULL;
}

/* Attached to a running firmware, only explicit options reconfigure it;
 * otherwise the command line (or the emulator profile's layout) does. */
static int apply_config(biss_t *h, struct bissctl_opts *o) {
    if (o->no_configure || (o->open.attach && !o->config_given)) {
        return BISSCTL_OK;
    }
    if (!o->slaves_given) {
        uint32_t ssi_delay = o->cfg.ssi_delay_ns; /* --ssi-delay-ns wins over the bench's */
        int rc = biss_config_from_emu(h, &o->cfg);
        if (ssi_delay) {
            o->cfg.ssi_delay_ns = ssi_delay;
        }
        if (rc == BISS_E_NOT_EMU) {
            return bissctl_usage_error("a real target needs --slave or --ssi (the slave layout)");
        }
        if (rc) {
            return bissctl_fail("slave layout", rc);
        }
        rc = biss_safety_merge(&o->cfg, &o->checks);
        if (rc) {
            return bissctl_fail("safety checks", rc);
        }
    }
    int rc = biss_configure(h, &o->cfg);
    return rc ? bissctl_fail("configure", rc) : BISSCTL_OK;
}

/* Commands that only look: on hardware they use a firmware already running
 * rather than reloading it (stop, too: it halts what runs). */
static bool read_only(const char *command) {
    return strcmp(command, "info") == 0 || strcmp(command, "stats") == 0 ||
           strcmp(command, "read") == 0 || strcmp(command, "record") == 0;
}

static int open_failed(struct bissctl_opts *o, int rc) {
    if (o->errbuf[0]) {
        fprintf(stderr, "bissctl: open: %s: %s\n", biss_strerror(rc), o->errbuf);
        return BISSCTL_FAIL;
    }
    return bissctl_fail("open", rc);
}

/* A firmware already running on hardware serves the read-only commands as
 * it is, unless a configuration is given; otherwise it is loaded. */
static int open_target(struct bissctl_opts *o, const struct command *cmd, biss_t **h) {
    bool hw = o->open.target != BISS_TARGET_EMU;
    bool layout = o->slaves_given || o->no_configure;
    bool stop = strcmp(cmd->name, "stop") == 0;
    if (hw && stop) {
        o->open.attach = true;
    }
    if (hw && !o->open.attach && read_only(cmd->name) && !o->config_given) {
        struct biss_open_params p = o->open;
        p.attach = true;
        int rc = biss_emu_open(&p, h);
        struct biss_status st;
        if (rc == BISS_OK && biss_get_status(*h, &st) == BISS_OK && st.firmware_running &&
            st.pru_enabled) {
            o->open.attach = true;
            return BISSCTL_OK;
        }
        if (rc == BISS_OK) {
            biss_close(*h);
        } else if (rc != BISS_E_NOT_RUNNING && rc != BISS_E_FW_ID) {
            return open_failed(o, rc); /* busy, another firmware, no access ... */
        }
        o->errbuf[0] = '\0';
    }
    if (hw && cmd->configure && !o->open.attach && !layout) {
        return bissctl_usage_error(
            "a real target needs --slave or --ssi (the slave layout)%s",
            read_only(cmd->name) ? ", or a firmware already running to attach to" : "");
    }
    int rc = biss_emu_open(&o->open, h);
    if (rc == BISS_E_NOT_RUNNING && hw && stop) {
        /* stopping a stopped master: done (a unit's ExecStop, a second stop) */
        printf("stopped: nothing was running (%s)\n", o->errbuf);
        *h = NULL;
        return BISSCTL_OK;
    }
    return rc ? open_failed(o, rc) : BISSCTL_OK;
}

/* --target not given: the emulator's own options mean the emulator, else
 * the board bissctl runs on (bissctl_target.c). */
static void default_target(struct bissctl_opts *o) {
    if (o->target_given) {
        return;
    }
    bool emu_options = (o->open.profile && *o->open.profile) ||
                       (o->open.scenario_file && *o->open.scenario_file) || o->open.cable_m >= 0 ||
                       o->open.set_seed;
    o->open.target = emu_options ? BISS_TARGET_EMU : bissctl_default_target(o->open.sysfs_root);
}

int main(int argc, char **argv) {
    if (argc == 2 && strcmp(argv[1], "--version") == 0) { /* the project's (CMakeLists.txt) */
        printf("%s %s\n", "bissctl", BISS_VERSION);
        return 0;
    }
    struct bissctl_opts o;
    int rc = bissctl_parse(argc, argv, &o);
    if (rc) {
        return rc;
    }
    if (o.help) {
        bissctl_usage(o.command);
        return BISSCTL_OK;
    }
    const struct command *cmd = find(o.command);
    if (!cmd->run && strcmp(cmd->name, "encoder") == 0) {
        default_target(&o);
        return bissctl_encoder(&o);
    }
    if (!cmd->run) {
        return bissctl_rates(&o);
    }
    default_target(&o);
    /* catch a bad command line before touching the target */
    rc = bissctl_check_args(&o);
    if (rc) {
        return rc;
    }
    if (cmd->configure && !o.no_configure && (o.config_given || !o.open.attach)) {
        rc = bissctl_line_before(&o); /* the rate against what is known of the line */
        if (rc) {
            return rc;
        }
    }
    if (cmd->configure && o.slaves_given && !o.no_configure) {
        int bad = biss_config_check(&o.cfg);
        if (bad) {
            char what[1100];
            snprintf(what, sizeof what, "configuration%s%.1000s", o.config_file ? " in " : "",
                     o.config_file ? o.config_file : "");
            return bissctl_fail(what, bad);
        }
    }
    biss_t *h;
    rc = open_target(&o, cmd, &h);
    if (rc || !h) {
        return rc;
    }
    if (*biss_image_unchecked(h)) { /* the running image is whatever it is: say so */
        fprintf(stderr,
                "bissctl: cannot check the running image: %s; install the firmware "
                "(docs/hardware.md) or name its image with --firmware\n",
                biss_image_unchecked(h));
    }
    if (biss_target(h) == BISS_TARGET_EMU && !o.json) {
        /* read --json says it in the object (bissctl_json.c) */
        printf("%s\n", bissctl_emulated_note);
    }
    rc = cmd->configure ? apply_config(h, &o) : BISSCTL_OK;
    if (rc == BISSCTL_OK && o.link_warn &&
        biss_set_link_warning(h, o.link_window, o.link_warn) != BISS_OK) {
        rc = bissctl_fail("link warning", BISS_E_INVAL);
    }
    if (rc == BISSCTL_OK) {
        rc = cmd->run(h, &o);
    }
    biss_close(h);
    return rc;
}
