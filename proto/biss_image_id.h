/* biss_image_id.h - the identification block an image carries into data
 * RAM (include/biss/biss_shm.h, BISS_ID): the firmware ELF writer builds
 * it, the host's loader writes it, and an attaching host checks it. */
#ifndef BISS_IMAGE_ID_H
#define BISS_IMAGE_ID_H

#include "biss/biss_shm_struct.h"

#include <stddef.h>
#include <stdint.h>

/* CRC-32 as zlib and ELF tools compute it (IEEE 802.3, reflected, poly
 * 0xEDB88320, start and final xor 0xFFFFFFFF). */
uint32_t biss_crc32(const void *data, size_t n);

/* The block for an image of n bytes. */
void biss_image_id(const void *image, size_t n, struct biss_shm_id *id);

/* The remoteproc resource table the loader expects: version 1, no
 * entries, two reserved words (struct resource_table, Linux
 * include/linux/remoteproc.h). */
#define BISS_RSC_TABLE_BYTES 16
void biss_rsc_table(uint8_t out[BISS_RSC_TABLE_BYTES]);

#endif
