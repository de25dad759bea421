/* biss_image_id.c - CRC-32 and the image identification block. */
#include "biss_image_id.h"

#include <string.h>

uint32_t biss_crc32(const void *data, size_t n) {
    const uint8_t *p = data;
    uint32_t crc = 0xffffffffu;
    for (size_t i = 0; i < n; i++) {
        crc ^= p[i];
        for (int b = 0; b < 8; b++) {
            crc = (crc >> 1) ^ (0xedb88320u & (0u - (crc & 1u)));
        }
    }
    return ~crc;
}

void biss_image_id(const void *image, size_t n, struct biss_shm_id *id) {
    *id = (struct biss_shm_id){
        .magic = BISS_ID_MAGIC,
        .shm_version = BISS_SHM_VERSION,
        .image_crc = biss_crc32(image, n),
        .image_bytes = (uint32_t)n,
    };
}

void biss_rsc_table(uint8_t out[BISS_RSC_TABLE_BYTES]) {
    memset(out, 0, BISS_RSC_TABLE_BYTES);
    out[0] = 1; /* ver = 1 (little-endian u32); num = 0; reserved[2] = 0 */
}
