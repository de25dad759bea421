/* biss_rproc.h - a PRU's remoteproc instance through sysfs
 * (/sys/class/remoteproc/remoteprocN: name, firmware, state), under any
 * sysfs root so tests can use a fake tree. */
#ifndef BISS_RPROC_H
#define BISS_RPROC_H

#include "biss_oserr.h"

#include <limits.h>
#include <stddef.h>

/* The instance whose name is "<iram>.pru..." (pru_rproc names it after
 * its IRAM's physical address, "4a334000.pru" or "4a334000.pru0"): its
 * directory into dir. 0 or BISS_E_RPROC. */
int biss_rproc_find(const char *sysfs, unsigned long iram, char dir[PATH_MAX],
                    struct biss_errbuf *e);
/* One attribute's first line, without the newline. 0 or BISS_E_RPROC. */
int biss_rproc_get(const char *dir, const char *attr, char *buf, size_t n, struct biss_errbuf *e);
/* Writes value to an attribute. 0, or BISS_E_RPROC_BUSY (EBUSY) /
 * BISS_E_RPROC with the errno in e. */
int biss_rproc_set(const char *dir, const char *attr, const char *value, struct biss_errbuf *e);

#endif
