/* BiSS CRCs: any generator polynomial up to degree 16, a start value, bits
 * fed MSB first. The polynomial is written with its top term, as the
 * references do: 0x13 = x^4+x+1 (control frames), 0x43 = x^6+x+1,
 * 0x25 = x^5+x^2+1, 0x190D9 (16 bits). The result is the plain remainder;
 * a slave sends it inverted. */
#ifndef BISS_CRC_H
#define BISS_CRC_H

#include <stdint.h>

/* Degree of the polynomial (its CRC length), 0 for "no CRC". */
unsigned biss_crc_width(uint32_t poly);

/* Feeds one bit into a running CRC register. */
uint32_t biss_crc_bit(uint32_t crc, uint32_t poly, int bit);

/* CRC over the low nbits of value (up to 64), MSB first, from start. */
uint32_t biss_crc_bits(uint32_t poly, uint32_t start, uint64_t value, unsigned nbits);

#define BISS_CRC4_POLY 0x13u /* control frames */

#endif
