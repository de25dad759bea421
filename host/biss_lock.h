/* biss_lock.h - the advisory lock (flock) that keeps two processes off one
 * PRU: exclusive to load, configure, start or stop, shared to attach and
 * read. The holder's pid is written into the lock file so a refusal can
 * name it. */
#ifndef BISS_LOCK_H
#define BISS_LOCK_H

#include "biss_oserr.h"

#include <stdbool.h>

/* The lock file for key (a file name) in dir (NULL: $BISS_LOCK_DIR, else
 * /run/lock when writable, else /tmp). 0 and *fd, or BISS_E_BUSY (the
 * holder's pid in e) / BISS_E_DEVMEM (the lock file cannot be made). */
int biss_lock_take(const char *dir, const char *key, bool shared, int *fd, struct biss_errbuf *e);
/* Shared to exclusive, without waiting; on refusal the shared lock is
 * taken again. 0 or BISS_E_BUSY. */
int biss_lock_upgrade(int fd, struct biss_errbuf *e);

#endif
