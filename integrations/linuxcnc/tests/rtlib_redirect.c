/*
 * rtlib_redirect.c - the test's stand-in for an installed component.
 * rtapi_app opens a module only from LinuxCNC's module folder
 * (<folder>/NAME.so, the folder built in); preloaded into it, this makes
 * its dlopen of <folder>/hal_biss.so open $BISS_HAL_MODULE instead, the
 * build tree's, so the test needs neither an install nor a mount (which a
 * chroot, as scripts/fresh-machine-check has, cannot make private). Every
 * other name goes to dlopen as it was.
 */
#define _GNU_SOURCE
#include <dlfcn.h>
#include <stdlib.h>
#include <string.h>

void *dlopen(const char *file, int mode) {
    void *(*real)(const char *, int);
    *(void **)&real = dlsym(RTLD_NEXT, "dlopen");
    const char *want = getenv("BISS_HAL_MODULE");
    const char *slash = file ? strrchr(file, '/') : NULL;
    if (want && slash && strcmp(slash + 1, "hal_biss.so") == 0) {
        file = want;
    }
    return real(file, mode);
}
