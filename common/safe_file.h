/* safe_file.h - output files written safely, the same way by every tool
 * that writes one (pruasm, pru-elf, biss-sim's VCD and SVG, bissctl's
 * scenario).
 *
 * A regular file (or a new name) is written whole or not at all: into a
 * temporary file made with mkstemp in the same directory (an unpredictable
 * name, created, never followed), with the mode the file has (a new one
 * 0666 less the umask), then renamed over it; a symbolic link to a regular
 * file replaces the file it names and stays a link. A character device or
 * a FIFO (/dev/null, /dev/stdout, a pipe) is written in place, never
 * replaced. Anything else (a directory, a socket, a block device, a link
 * to nothing) is refused. */
#ifndef SAFE_FILE_H
#define SAFE_FILE_H

#include <limits.h>
#include <stddef.h>
#include <stdio.h>

struct safe_file {
    FILE *f;
    char path[PATH_MAX]; /* the file written (a link resolved) */
    char tmp[PATH_MAX];  /* the temporary file, "" when written in place */
};

/* Opens path for writing: 0 and s->f, or -1 with a message naming path
 * and the reason in err (nothing created). */
int safe_file_open(struct safe_file *s, const char *path, char *err, size_t errlen);

/* Flushes and closes s->f and puts the file in place (renames the
 * temporary file over it): 0, or -1 with the message in err (the
 * temporary file removed, the target as it was). */
int safe_file_close(struct safe_file *s, char *err, size_t errlen);

/* Drops what was written: the temporary file removed, the target as it
 * was (in place: what was written stays written). */
void safe_file_abort(struct safe_file *s);

/* The n bytes of data as the whole of path: open, write, close. */
int safe_file_write(const char *path, const void *data, size_t n, char *err, size_t errlen);

#endif
