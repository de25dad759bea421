/* bissctl_conf.c - bissctl --config FILE: a master's settings as
 * "key = value" lines, the keys being bissctl's long options without the
 * dashes (target, pru, loader, freq, slave, trigger, check-life, ...), so
 * a file and a command line say the same things the same way. A key may
 * repeat where the option may (slave, check-*). "#" starts a comment (at
 * the start of a line, or after a blank); blank lines are skipped. Each
 * error names FILE:LINE. Not JSON: the board's bissctl is built without
 * cJSON, and one option per line is what a systemd unit's admin edits. */
#include "bissctl.h"

#include <errno.h>
#include <stdio.h>
#include <string.h>

/* The file's text: the options point into it until the process ends. */
static char text[64 * 1024];

static char *trim(char *s) {
    while (*s == ' ' || *s == '\t') {
        s++;
    }
    char *end = s + strlen(s);
    while (end > s && (end[-1] == ' ' || end[-1] == '\t' || end[-1] == '\r')) {
        *--end = '\0';
    }
    return s;
}

/* A comment: "#" at the start or after a blank ("a#b" stays a value). */
static void drop_comment(char *line) {
    for (char *p = line; *p; p++) {
        if (*p == '#' && (p == line || p[-1] == ' ' || p[-1] == '\t')) {
            *p = '\0';
            return;
        }
    }
}

int bissctl_conf_read(const char *path, struct bissctl_opts *o) {
    FILE *f = fopen(path, "r");
    if (!f) {
        int err = errno;
        fprintf(stderr, "bissctl: --config %s: %s (errno %d)\n", path, strerror(err), err);
        return BISSCTL_FAIL;
    }
    size_t n = fread(text, 1, sizeof text, f);
    int err = ferror(f) ? errno : 0;
    fclose(f);
    if (err) {
        fprintf(stderr, "bissctl: --config %s: %s (errno %d)\n", path, strerror(err), err);
        return BISSCTL_FAIL;
    }
    if (n == sizeof text) {
        return bissctl_usage_error("--config %s: more than %zu bytes", path, sizeof text - 1);
    }
    text[n] = '\0';
    if (memchr(text, '\0', n)) {
        return bissctl_usage_error("--config %s: not a text file (a NUL byte)", path);
    }
    unsigned lineno = 0;
    for (char *save = NULL, *line = text; line; line = save) {
        save = strchr(line, '\n');
        if (save) {
            *save++ = '\0';
        }
        lineno++;
        drop_comment(line);
        char *key = trim(line);
        if (!*key) {
            continue;
        }
        char *value = strchr(key, '=');
        if (value) {
            *value++ = '\0';
            value = trim(value);
            key = trim(key);
        }
        char at[1100];
        snprintf(at, sizeof at, "%.1000s:%u", path, lineno);
        int rc = bissctl_set_option(key, value, at, o);
        if (rc) {
            return rc;
        }
    }
    return BISSCTL_OK;
}
