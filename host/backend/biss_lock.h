/* biss_lock.h - the advisory locks that keep two processes off one PRU and
 * off the PRU-ICSS's one IEP: open-file-description byte-range locks
 * (fcntl F_OFD_SETLK) on the memory file itself (/dev/mem, or the file
 * standing in for it), at the address of what they guard. Every process
 * that reaches a PRU-ICSS opens that file, so every process agrees on the
 * lock whatever its environment or directory; the kernel drops a lock with
 * its holder. A refusal names the holder (its pid and command, from the
 * kernel's lock lines in /proc/PID/fdinfo: an OFD lock's pid is shown
 * nowhere else). */
#ifndef BISS_LOCK_H
#define BISS_LOCK_H

#include "biss_oserr.h"

#include <stdbool.h>
#include <sys/types.h>

/* The lock on byte `at` of the memory file open as fd (path names it in
 * messages, what says what it guards): shared or exclusive, without
 * waiting. 0, or BISS_E_BUSY (the holder named in e) / BISS_E_DEVMEM (the
 * file takes no lock). Taking it again on the same fd changes its kind in
 * place (shared to exclusive only when no one else shares it; the shared
 * lock stays when refused). */
int biss_lock_take(int fd, off_t at, bool shared, const char *path, const char *what,
                   struct biss_errbuf *e);
/* The same, retried for up to timeout_ms (a lock held only for a short
 * exchange, the IEP's). */
int biss_lock_wait(int fd, off_t at, const char *path, const char *what, unsigned timeout_ms,
                   struct biss_errbuf *e);
/* Lets go of the lock on byte `at`. */
void biss_lock_drop(int fd, off_t at);

#endif
