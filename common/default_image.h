/* default_image.h - the firmware image a program takes when none is named
 * (libbiss for bissctl and applications, biss-sim): the build tree's for a
 * program inside the build tree, else the one installed in the firmware
 * directory as seen from the program's bin directory (a DESTDIR tree or a
 * moved one), else the configured firmware directory's (CMakeLists.txt:
 * BISS_FIRMWARE_DIR, /lib/firmware, where the kernel looks). */
#ifndef DEFAULT_IMAGE_H
#define DEFAULT_IMAGE_H

#include <stddef.h>

struct default_image {
    const char *build_dir;    /* the build tree */
    const char *build_image;  /* the image in it */
    const char *bin_to_image; /* from the bin directory, "../../../lib/firmware/x.bin" */
    const char *installed;    /* absolute, "/lib/firmware/x.bin" */
};

/* For the program at exe (an absolute path). buf holds the candidate
 * beside the program; the result is buf or one of d's strings. */
const char *default_image_for(const char *exe, const struct default_image *d, char *buf,
                              size_t len);
/* The same for this program (/proc/self/exe; d->installed when unknown). */
const char *default_image(const struct default_image *d, char *buf, size_t len);

#endif
