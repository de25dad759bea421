/* A BiSS slave's register space as the control frame sees it: 7-bit
 * addresses, 0x00-0x3F banked (the bank chosen by the byte at 0x40),
 * 0x40-0x7F direct. Each address can be read-only (writes refused) or
 * write-protected (writes refused while protection is on). */
#ifndef REGFILE_H
#define REGFILE_H

#include <stdbool.h>
#include <stdint.h>

#define REGFILE_MAX_BANKS 72 /* the POSITAL kit has 68 */
#define REGFILE_BANK_SEL  0x40

enum { REG_RO = 1, REG_WP = 2 };

typedef struct {
    uint8_t direct[64];                  /* 0x40..0x7F */
    uint8_t bank[REGFILE_MAX_BANKS][64]; /* 0x00..0x3F per bank */
    uint8_t flags[128];                  /* REG_RO / REG_WP by address */
    unsigned nbanks;                     /* banks that exist, 1..MAX */
    bool protect;                        /* REG_WP addresses refuse writes */
} regfile;

void regfile_init(regfile *r, unsigned nbanks);

/* Byte at a 7-bit address in the current bank; 0 for a missing bank. */
uint8_t regfile_read(const regfile *r, uint8_t addr);

/* Writes a byte as a control frame would. Returns true if it was stored. */
bool regfile_write(regfile *r, uint8_t addr, uint8_t value);

/* Sets a byte regardless of access rights (profiles, tests). bank is only
 * used for 0x00-0x3F. */
void regfile_poke(regfile *r, unsigned bank, uint8_t addr, uint8_t value);

#endif
