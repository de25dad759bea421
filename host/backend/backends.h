/* backends.h - the backends' openers that one backend hands another's
 * targets to (biss_open_with, host/lib/biss_priv.h): libbiss-emu's
 * biss_emu_open takes the Linux targets too. */
#ifndef BACKENDS_H
#define BACKENDS_H

#include "biss_priv.h"

/* A PRU-ICSS of an AM335x/AM437x through /dev/mem or remoteproc
 * (backend_linux.c). */
int biss_linux_backend_open(const struct biss_open_params *p, struct biss_backend *be);

#endif
