/* safe_file.c - output files written safely (safe_file.h). */
#define _XOPEN_SOURCE 700 /* realpath (XSI) */
#include "safe_file.h"

#include <errno.h>
#include <fcntl.h>
#include <stdarg.h>
#include <stdbool.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

__attribute__((format(printf, 3, 4))) static int fail(char *err, size_t errlen, const char *fmt,
                                                      ...) {
    if (err && errlen) {
        va_list ap;
        va_start(ap, fmt);
        vsnprintf(err, errlen, fmt, ap);
        va_end(ap);
    }
    return -1;
}

/* The process's umask (it has no getter: set and set back). */
static mode_t current_umask(void) {
    mode_t m = umask(022);
    umask(m);
    return m;
}

/* In place: a character device or a FIFO, opened as it is. */
static int open_in_place(struct safe_file *s, char *err, size_t errlen) {
    int fd = open(s->path, O_WRONLY | O_NOCTTY | O_CLOEXEC);
    if (fd < 0) {
        int e = errno;
        return fail(err, errlen, "%s: %s", s->path, strerror(e));
    }
    s->f = fdopen(fd, "wb");
    if (!s->f) {
        int e = errno;
        close(fd);
        return fail(err, errlen, "%s: %s", s->path, strerror(e));
    }
    s->tmp[0] = '\0';
    return 0;
}

/* Staged: a temporary file beside s->path, mode `mode`. */
static int open_staged(struct safe_file *s, mode_t mode, char *err, size_t errlen) {
    if (snprintf(s->tmp, sizeof s->tmp, "%s.XXXXXX", s->path) >= (int)sizeof s->tmp) {
        return fail(err, errlen, "%s: path too long", s->path);
    }
    int fd = mkstemp(s->tmp);
    if (fd < 0) {
        int e = errno;
        return fail(err, errlen, "%s: cannot create a file beside it: %s", s->path, strerror(e));
    }
    if (fchmod(fd, mode & 07777) != 0 || !(s->f = fdopen(fd, "wb"))) {
        int e = errno;
        close(fd);
        unlink(s->tmp);
        return fail(err, errlen, "%s: %s", s->tmp, strerror(e));
    }
    return 0;
}

int safe_file_open(struct safe_file *s, const char *path, char *err, size_t errlen) {
    memset(s, 0, sizeof *s);
    if (!path || !*path) {
        return fail(err, errlen, "no output file named");
    }
    if (snprintf(s->path, sizeof s->path, "%s", path) >= (int)sizeof s->path) {
        return fail(err, errlen, "%s: path too long", path);
    }
    struct stat st;
    if (lstat(path, &st) != 0) {
        if (errno != ENOENT) {
            int e = errno;
            return fail(err, errlen, "%s: %s", path, strerror(e));
        }
        return open_staged(s, 0666 & ~current_umask(), err, errlen); /* a new file */
    }
    if (S_ISLNK(st.st_mode)) {
        /* what the link names decides; a regular file is replaced there */
        char target[PATH_MAX];
        if (!realpath(path, target) || stat(target, &st) != 0) {
            int e = errno;
            return fail(err, errlen, "%s: a symbolic link to nothing that can be written (%s)",
                        path, strerror(e));
        }
        snprintf(s->path, sizeof s->path, "%s", target);
    }
    if (S_ISREG(st.st_mode)) {
        return open_staged(s, st.st_mode, err, errlen);
    }
    if (S_ISCHR(st.st_mode) || S_ISFIFO(st.st_mode)) {
        return open_in_place(s, err, errlen);
    }
    return fail(err, errlen,
                "%s: not a regular file, a character device or a FIFO: not written over", path);
}

void safe_file_abort(struct safe_file *s) {
    if (s->f) {
        fclose(s->f);
        s->f = NULL;
    }
    if (s->tmp[0]) {
        unlink(s->tmp);
        s->tmp[0] = '\0';
    }
}

int safe_file_close(struct safe_file *s, char *err, size_t errlen) {
    if (!s->f) {
        return fail(err, errlen, "%s: not open", s->path);
    }
    int bad = fflush(s->f) != 0 || ferror(s->f);
    int e = bad ? errno : 0;
    /* staged: on the disk before it takes the name */
    if (!bad && s->tmp[0] && fsync(fileno(s->f)) != 0) {
        bad = 1;
        e = errno;
    }
    if (fclose(s->f) != 0 && !bad) {
        bad = 1;
        e = errno;
    }
    s->f = NULL;
    if (bad) {
        safe_file_abort(s);
        return fail(err, errlen, "%s: %s", s->path, e ? strerror(e) : "write error");
    }
    if (s->tmp[0] && rename(s->tmp, s->path) != 0) {
        e = errno;
        safe_file_abort(s);
        return fail(err, errlen, "%s: %s", s->path, strerror(e));
    }
    s->tmp[0] = '\0';
    return 0;
}

int safe_file_write(const char *path, const void *data, size_t n, char *err, size_t errlen) {
    struct safe_file s;
    if (safe_file_open(&s, path, err, errlen) != 0) {
        return -1;
    }
    if (n && fwrite(data, 1, n, s.f) != n) {
        int e = errno;
        safe_file_abort(&s);
        return fail(err, errlen, "%s: %s", s.path, strerror(e));
    }
    return safe_file_close(&s, err, errlen);
}
