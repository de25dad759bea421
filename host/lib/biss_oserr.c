/* biss_oserr.c - open errors with their detail. */
#include "biss_oserr.h"

#include <errno.h>
#include <stdarg.h>
#include <stdio.h>

int biss_err(struct biss_errbuf *e, int code, const char *fmt, ...) {
    if (e && e->buf && e->len) {
        va_list ap;
        va_start(ap, fmt);
        vsnprintf(e->buf, e->len, fmt, ap);
        va_end(ap);
    }
    return code;
}

const char *biss_devmem_hint(int err) {
    switch (err) {
    case EACCES:
    case EPERM:
        return "run as root (CAP_SYS_RAWIO); a kernel with CONFIG_IO_STRICT_DEVMEM refuses "
               "memory a driver claimed: boot with iomem=relaxed";
    case ENOENT:
        return "no such file: /dev/mem needs CONFIG_DEVMEM, --devmem a file standing in for it";
    case EINVAL:
    case ENXIO:
        return "the address is outside what the file or the kernel maps";
    default:
        return "see the errno";
    }
}
