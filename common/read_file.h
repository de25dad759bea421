/* read_file.h - a whole file into memory, for the tools that read their
 * inputs at once (assembler sources, PRU images, scenario files). */
#ifndef READ_FILE_H
#define READ_FILE_H

#include <stddef.h>

typedef enum {
    READ_FILE_OK = 0,
    READ_FILE_OPEN,    /* cannot be opened (errno says why) */
    READ_FILE_IO,      /* a read failed (errno says why) */
    READ_FILE_TOO_BIG, /* max bytes or more */
    READ_FILE_NOMEM,
} read_file_err;

/* Reads the file at path, which must be shorter than max bytes, into a new
 * buffer *buf (the caller frees it) of *len bytes and a terminating NUL
 * (not counted), so text can be used as a string. On error *buf is NULL. */
read_file_err read_file(const char *path, size_t max, char **buf, size_t *len);

#endif
