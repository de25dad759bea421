/* biss_reg.c - register access of a BiSS-C slave as a control frame in CDM
 * bits, run by the firmware's CD program (biss_cd.c):
 *
 *   S=1, CTS=1, ID(3), ADR(7), inverted CRC4 of those 11 bits, R W S
 *   then per byte: WAIT for the slave's S (its register processing time),
 *   8 data bits (write: the byte; read: 0), 4 CRC bits (write: inverted
 *   CRC4 of the byte; read: 0), P=0, S (1: the next address follows)
 *
 * The slave echoes R and W, then answers each data bit (read: the
 * register, MSB first; write: the echo) and the inverted CRC4 of its
 * byte. All bits MSB first.
 *
 * A slave takes a new control frame only after 14 CDM = 0 following the
 * end of the last one. The program ends with those 14 zeros itself: the
 * firmware counts zeros sent inside a program towards its own 14-zero
 * rule and would start the next program too early. */
#include "biss_priv.h"

#include "biss/biss_shm.h"

#include <stdbool.h>
#include <string.h>

/* Frames a register may take to answer (late S) before the firmware gives up. */
#define REG_WAIT_LIMIT 64
/* CDM = 0 frames a slave needs between two control frames. */
#define REG_IDLE_ZEROS 14

struct reg_prog {
    uint8_t ops[BISS_CD_MAX_STEPS];
    unsigned n;
    unsigned rw_step;                     /* the R step; W follows */
    unsigned data_step[BISS_REG_MAX_SEQ]; /* each byte's first data step */
};

static void emit(struct reg_prog *p, unsigned op) {
    p->ops[p->n++] = (uint8_t)op;
}

static void emit_bits(struct reg_prog *p, uint32_t v, unsigned nbits) {
    for (unsigned i = nbits; i-- > 0;) {
        emit(p, (v >> i) & 1u);
    }
}

static void build(struct reg_prog *p, unsigned id, uint8_t addr, bool write, const uint8_t *data,
                  unsigned n) {
    p->n = 0;
    uint32_t header = 1u << 10 | (id & 7u) << 7 | (addr & 0x7fu); /* CTS = 1: registers */
    emit(p, 1);                                                   /* S: a control frame */
    emit_bits(p, header, 11);
    emit_bits(p, biss_crc4_sent(header, 11), 4);
    p->rw_step = p->n;
    emit(p, !write); /* R */
    emit(p, write);  /* W */
    emit(p, 1);      /* S */
    for (unsigned k = 0; k < n; k++) {
        emit(p, BISS_CD_OP_WAIT);
        p->data_step[k] = p->n;
        emit_bits(p, write ? data[k] : 0, 8);
        emit_bits(p, write ? biss_crc4_sent(data[k], 8) : 0, 4);
        emit(p, 0);         /* P */
        emit(p, k + 1 < n); /* S: sequential access goes on */
    }
    for (unsigned i = 0; i < REG_IDLE_ZEROS; i++) {
        emit(p, 0);
    }
    emit(p, BISS_CD_OP_END);
}

/* nbits answers from step on, MSB first. */
static uint32_t answer(const uint8_t *resp, unsigned step, unsigned nbits) {
    uint32_t v = 0;
    for (unsigned i = step; i < step + nbits; i++) {
        v = v << 1 | ((resp[i / 8] >> (i % 8)) & 1u);
    }
    return v;
}

static int check_answer(const struct reg_prog *p, const uint8_t *resp, bool write, uint8_t *data,
                        unsigned n) {
    if (answer(resp, p->rw_step, 2) != (write ? 1u : 2u)) {
        return BISS_E_CD_ANSWER; /* R and W not echoed */
    }
    for (unsigned k = 0; k < n; k++) {
        uint32_t value = answer(resp, p->data_step[k], 8);
        uint32_t crc = answer(resp, p->data_step[k] + 8, 4);
        if (crc != biss_crc4_sent(value, 8) || (write && value != data[k])) {
            return BISS_E_CD_ANSWER;
        }
        if (!write) {
            data[k] = (uint8_t)value;
        }
    }
    return BISS_OK;
}

static int reg_access(biss_t *h, unsigned id, uint8_t addr, bool write, uint8_t *data, unsigned n) {
    if (!h || !data || id > 7 || addr > 0x7f || n < 1 || n > BISS_REG_MAX_SEQ || addr + n > 0x80) {
        return BISS_E_INVAL;
    }
    struct reg_prog p;
    build(&p, id, addr, write, data, n);
    uint8_t resp[BISS_CD_MAX_STEPS / 8];
    memset(resp, 0, sizeof resp);
    int rc = biss_cd_run(h, p.ops, p.n, REG_WAIT_LIMIT, h->timeout_ms, resp);
    return rc ? rc : check_answer(&p, resp, write, data, n);
}

int biss_reg_read(biss_t *h, unsigned id, uint8_t addr, uint8_t *buf, unsigned n) {
    return reg_access(h, id, addr, false, buf, n);
}

int biss_reg_write(biss_t *h, unsigned id, uint8_t addr, const uint8_t *buf, unsigned n) {
    uint8_t copy[BISS_REG_MAX_SEQ];
    if (!buf || n > BISS_REG_MAX_SEQ) {
        return BISS_E_INVAL;
    }
    memcpy(copy, buf, n);
    return reg_access(h, id, addr, true, copy, n);
}
