/* CRC4 and header bits of BiSS-C control frames. */
#include "biss_cd.h"

/* x^4 + x + 1 without its top term: what is fed back when a 1 falls out. */
#define CRC4_FEEDBACK 0x3u

uint8_t biss_cd_crc4(uint32_t bits, unsigned nbits) {
    unsigned crc = 0;
    for (unsigned i = nbits; i-- > 0;) {
        unsigned out = ((crc >> 3) ^ (bits >> i)) & 1u;
        crc = (crc << 1) & 0xfu;
        if (out) {
            crc ^= CRC4_FEEDBACK;
        }
    }
    return (uint8_t)crc;
}

uint8_t biss_cd_crc4_line(uint32_t bits, unsigned nbits) {
    return (uint8_t)(~biss_cd_crc4(bits, nbits) & 0xfu);
}

uint16_t biss_cd_reg_header(uint8_t id, uint8_t addr) {
    return (uint16_t)(1u << 10 | (id & 7u) << 7 | (addr & 0x7fu));
}

/* IDS goes out ID 0 first, so on the line (MSB first) the mask's bit 0
 * comes first: reverse it. */
static uint8_t reverse8(uint8_t v) {
    uint8_t r = 0;
    for (unsigned i = 0; i < 8; i++) {
        r = (uint8_t)(r << 1 | ((v >> i) & 1u));
    }
    return r;
}

uint16_t biss_cd_cmd_header(uint8_t ids, uint8_t cmd) {
    return (uint16_t)((unsigned)reverse8(ids) << 2 | (cmd & 3u));
}
