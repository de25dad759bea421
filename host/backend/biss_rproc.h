/* biss_rproc.h - a PRU's remoteproc instance through sysfs
 * (/sys/class/remoteproc/remoteprocN: name since Linux 5.4, device,
 * firmware, state), under any sysfs root so tests can use a fake tree. */
#ifndef BISS_RPROC_H
#define BISS_RPROC_H

#include "biss_oserr.h"

#include <limits.h>
#include <stddef.h>

/* The instance of the PRU whose IRAM is at iram: the one whose name, or
 * without a name attribute (before Linux 5.4) whose device link, is
 * "<iram>.pru" or "<iram>.pru<N>" (pru_rproc names it after its platform
 * device: "4a334000.pru"; TI's 4.14 tree "4a334000.pru0"). Its directory
 * into dir. 0, or BISS_E_RPROC with what to check in e (the PRU-ICSS at
 * icss_base: overlay loaded, pruss bound, pru_rproc). */
int biss_rproc_find(const char *sysfs, unsigned long icss_base, unsigned long iram,
                    char dir[PATH_MAX], struct biss_errbuf *e);
/* What sysfs says about a PRU-ICSS without PRU instances, as "; ..."
 * clauses for an error message: no overlay listed under
 * firmware/devicetree/base/chosen/overlays, no pruss driver bound (a pin
 * conflict), or pru_rproc missing. */
void biss_rproc_diagnose(const char *sysfs, unsigned long icss_base, char *buf, size_t n);
/* One attribute's first line, without the newline. 0 or BISS_E_RPROC. */
int biss_rproc_get(const char *dir, const char *attr, char *buf, size_t n, struct biss_errbuf *e);
/* Writes value to an attribute. 0, or BISS_E_RPROC_BUSY (EBUSY) /
 * BISS_E_RPROC with the errno in e. */
int biss_rproc_set(const char *dir, const char *attr, const char *value, struct biss_errbuf *e);

#endif
