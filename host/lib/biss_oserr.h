/* biss_oserr.h - open errors with their detail: the path, the errno and a
 * hint, into the caller's buffer (struct biss_open_params errbuf). */
#ifndef BISS_OSERR_H
#define BISS_OSERR_H

#include <stddef.h>

struct biss_errbuf {
    char *buf;
    size_t len;
};

/* Formats into e (when it has a buffer) and returns code. */
int biss_err(struct biss_errbuf *e, int code, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));

/* The hint for an errno met opening or mapping physical memory. */
const char *biss_devmem_hint(int err);

#endif
