#include "biss_crc.h"

/* The index of the top set bit; every frame bit's CRC step asks for it. */
unsigned biss_crc_width(uint32_t poly) {
    return poly > 1 ? 31u - (unsigned)__builtin_clz(poly) : 0u;
}

uint32_t biss_crc_bit(uint32_t crc, uint32_t poly, int bit) {
    unsigned w = biss_crc_width(poly);
    if (w == 0) {
        return 0;
    }
    uint32_t mask = (w >= 32) ? 0xffffffffu : ((1u << w) - 1u);
    uint32_t feedback = ((crc >> (w - 1)) & 1u) ^ (bit ? 1u : 0u);
    crc = (crc << 1) & mask;
    if (feedback) {
        crc ^= poly & mask;
    }
    return crc;
}

uint32_t biss_crc_bits(uint32_t poly, uint32_t start, uint64_t value, unsigned nbits) {
    uint32_t crc = start;
    for (unsigned i = nbits; i > 0; i--) {
        crc = biss_crc_bit(crc, poly, (int)((value >> (i - 1)) & 1u));
    }
    return crc;
}
