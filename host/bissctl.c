/* bissctl - the libbiss command line: the same subcommands on the
 * emulator and on a real PRU-ICSS. */
#include "bissctl.h"

#include <stdio.h>
#include <string.h>

struct command {
    const char *name;
    int (*run)(biss_t *h, const struct bissctl_opts *o);
    bool configure; /* needs the configuration applied first */
};

static const struct command table[] = {
    {"info", bissctl_info, true},           {"read", bissctl_read, true},
    {"stats", bissctl_stats, true},         {"run", bissctl_run, true},
    {"trigger", bissctl_trigger, true},     {"start", bissctl_start, true},
    {"stop", bissctl_stop, false},          {"reg-read", bissctl_reg_read, true},
    {"reg-write", bissctl_reg_write, true}, {"command", bissctl_command, true},
    {"probe", bissctl_probe, false}, /* configures its own capture layout */
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
            fprintf(stderr, "bissctl: a real target needs --slave or --ssi (the slave layout)\n");
            return BISSCTL_USAGE;
        }
        if (rc) {
            return bissctl_fail("slave layout", rc);
        }
    }
    int rc = biss_configure(h, &o->cfg);
    return rc ? bissctl_fail("configure", rc) : BISSCTL_OK;
}

int main(int argc, char **argv) {
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
    /* catch a bad configuration before touching the target */
    if (cmd->configure && o.slaves_given && !o.no_configure) {
        int bad = biss_config_check(&o.cfg);
        if (bad) {
            return bissctl_fail("configuration", bad);
        }
    }
    biss_t *h;
    rc = biss_open(&o.open, &h);
    if (rc) {
        return bissctl_fail("open", rc);
    }
    rc = cmd->configure ? apply_config(h, &o) : BISSCTL_OK;
    if (rc == BISSCTL_OK) {
        rc = cmd->run(h, &o);
    }
    biss_close(h);
    return rc;
}
