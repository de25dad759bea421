/* mmio.h - copies to and from peripheral memory (a mapped PRU-ICSS):
 * 32-bit accesses for whole words (what the PRU RAMs and registers
 * expect), bytes otherwise; volatile so none is merged, split or dropped.
 * backend_linux.c's mapped path, and biss-read-cost's stand-in for it. */
#ifndef BISS_MMIO_H
#define BISS_MMIO_H

#include <stddef.h>
#include <stdint.h>

/* Whole 32-bit words: at a word offset (the map is page aligned), n a
 * multiple of 4. */
static inline int mmio_words(uint32_t off, size_t n) {
    return off % 4 == 0 && n % 4 == 0;
}

static inline void mmio_read(void *buf, const volatile uint8_t *map, uint32_t off, size_t n) {
    if (mmio_words(off, n)) {
        const volatile uint32_t *src = (const volatile uint32_t *)(map + off);
        uint32_t *dst = buf;
        for (size_t i = 0; i < n / 4; i++) {
            dst[i] = src[i];
        }
    } else {
        uint8_t *dst = buf;
        for (size_t i = 0; i < n; i++) {
            dst[i] = map[off + i];
        }
    }
}

static inline void mmio_write(volatile uint8_t *map, uint32_t off, const void *buf, size_t n) {
    if (mmio_words(off, n)) {
        volatile uint32_t *dst = (volatile uint32_t *)(map + off);
        const uint32_t *src = buf;
        for (size_t i = 0; i < n / 4; i++) {
            dst[i] = src[i];
        }
    } else {
        const uint8_t *src = buf;
        for (size_t i = 0; i < n; i++) {
            map[off + i] = src[i];
        }
    }
}

#endif
