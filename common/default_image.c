/* default_image.c - the firmware image a program takes by default. */
#include "default_image.h"

#include <limits.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

const char *default_image_for(const char *exe, const struct default_image *d, char *buf,
                              size_t len) {
    size_t b = strlen(d->build_dir);
    if (strncmp(exe, d->build_dir, b) == 0 && exe[b] == '/') {
        return d->build_image;
    }
    /* each leading "../" of the relative path takes one directory off the
     * program's: <root>/usr/local/bin/x and "../../../lib/firmware/y"
     * give <root>/lib/firmware/y */
    char dir[PATH_MAX];
    if (snprintf(dir, sizeof dir, "%s", exe) >= (int)sizeof dir) {
        return d->installed;
    }
    const char *rel = d->bin_to_image;
    char *slash = strrchr(dir, '/');
    while (slash && strncmp(rel, "../", 3) == 0) {
        *slash = '\0';
        slash = strrchr(dir, '/');
        rel += 3;
    }
    if (slash) {
        *slash = '\0';
        if (snprintf(buf, len, "%s/%s", dir, rel) < (int)len && access(buf, R_OK) == 0) {
            return buf;
        }
    }
    return d->installed;
}

const char *default_image(const struct default_image *d, char *buf, size_t len) {
    char exe[PATH_MAX];
    ssize_t n = readlink("/proc/self/exe", exe, sizeof exe - 1);
    if (n <= 0) {
        return d->installed;
    }
    exe[n] = '\0';
    return default_image_for(exe, d, buf, len);
}
