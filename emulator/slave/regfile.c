#include "regfile.h"

#include <string.h>

void regfile_init(regfile *r, unsigned nbanks) {
    memset(r, 0, sizeof *r);
    if (nbanks < 1) {
        nbanks = 1;
    }
    r->nbanks = nbanks > REGFILE_MAX_BANKS ? REGFILE_MAX_BANKS : nbanks;
}

static uint8_t *cell(regfile *r, unsigned bank, uint8_t addr) {
    addr &= 0x7f;
    if (addr >= 0x40) {
        return &r->direct[addr - 0x40];
    }
    return bank < r->nbanks ? &r->bank[bank][addr] : NULL;
}

uint8_t regfile_read(const regfile *r, uint8_t addr) {
    addr &= 0x7f;
    if (addr >= 0x40) {
        return r->direct[addr - 0x40];
    }
    unsigned bank = r->direct[0];
    return bank < r->nbanks ? r->bank[bank][addr] : 0;
}

bool regfile_write(regfile *r, uint8_t addr, uint8_t value) {
    addr &= 0x7f;
    if ((r->flags[addr] & REG_RO) || ((r->flags[addr] & REG_WP) && r->protect)) {
        return false;
    }
    uint8_t *c = cell(r, r->direct[0], addr);
    if (!c) {
        return false;
    }
    *c = value;
    return true;
}

void regfile_poke(regfile *r, unsigned bank, uint8_t addr, uint8_t value) {
    uint8_t *c = cell(r, bank, addr);
    if (c) {
        *c = value;
    }
}
