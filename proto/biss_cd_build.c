/* Builders: whole control frames as CDM programs, with the step index of
 * every field kept for the parser. */
#include "biss_cd.h"

#include <string.h>

/* Steps of a register access: S, header (15), R W, then per byte S WAIT
 * D(8) CRC(4) P, then the final S = 0 and the tail. */
#define REG_FIXED_STEPS (19u + BISS_CD_TAIL_ZEROS)
#define REG_BYTE_STEPS  15u
/* Steps of a command: S, header (15), 8 IDA slots, P, the tail. */
#define CMD_STEPS (25u + BISS_CD_TAIL_ZEROS)

static void start(biss_cd_prog *p, biss_cd_kind kind) {
    memset(p, 0, sizeof *p);
    p->kind = kind;
}

/* Callers size the program before putting steps, so this cannot overflow. */
static void put(biss_cd_prog *p, unsigned step) {
    p->op[p->len++] = (uint8_t)step;
}

/* nbits of value, MSB first, as steps of class cl. */
static void put_bits(biss_cd_prog *p, uint32_t value, unsigned nbits, unsigned cl) {
    for (unsigned i = nbits; i-- > 0;) {
        put(p, BISS_CD_STEP((value >> i) & 1u, cl));
    }
}

/* The 4 CRC4 bits of the CDM fed so far, computed and sent by the firmware. */
static void put_crc(biss_cd_prog *p, unsigned cl) {
    for (unsigned i = 0; i < 4; i++) {
        put(p, BISS_CD_STEP(BISS_CDOP_CRC, cl));
    }
}

static void put_zeros(biss_cd_prog *p, unsigned n) {
    while (n--) {
        put(p, BISS_CDOP_0);
    }
}

/* S, then the 11 header bits the firmware's CRC4 covers, then that CRC. */
static void put_header(biss_cd_prog *p, uint16_t header) {
    put(p, BISS_CDOP_1); /* S */
    put_bits(p, header, 11, BISS_CDCL_DATA);
    put_crc(p, BISS_CDCL_NONE);
}

/* After its frame ends (on a CDM 0) a slave wants 14 zeros in a row before
 * the next S; the firmware counts every CDM 0 frame, those inside the frame
 * just ended too, and may start the next program at once. The tail re-arms
 * the slave inside the program itself, so programs can follow each other
 * without the host waiting. */
static void put_tail(biss_cd_prog *p) {
    put_zeros(p, BISS_CD_TAIL_ZEROS);
}

/* One register byte with its master S. Read: zeros out, the data into
 * CRC_S, the slave's CRC checked against it. Write: the byte and the
 * firmware's CRC of it out, each bit's echo checked. The WAIT restarts
 * both CRC registers. */
static void put_byte(biss_cd_prog *p, biss_cd_byte_steps *at, bool write, uint8_t value) {
    at->start = p->len;
    put(p, BISS_CDOP_1);
    at->wait = p->len;
    put(p, BISS_CDOP_WAIT);
    at->data = p->len;
    at->crc = (uint16_t)(p->len + 8u);
    if (write) {
        put_bits(p, value, 8, BISS_CDCL_ECHO);
        put_crc(p, BISS_CDCL_ECHO);
    } else {
        put_bits(p, 0, 8, BISS_CDCL_DATA);
        put_bits(p, 0, 4, BISS_CDCL_CHECK);
    }
    at->stop = p->len;
    put(p, BISS_CDOP_0);
}

static biss_cd_err build_register(biss_cd_prog *p, bool write, unsigned id, unsigned addr,
                                  const uint8_t *data, unsigned count) {
    if (id > 7 || addr > 0x7f || count < 1 || count > BISS_CD_MAX_BYTES || (write && !data)) {
        return BISS_CD_E_ARG;
    }
    if (REG_FIXED_STEPS + REG_BYTE_STEPS * count > BISS_CD_MAX_STEPS) {
        return BISS_CD_E_TOO_LONG;
    }
    start(p, write ? BISS_CD_WRITE : BISS_CD_READ);
    p->id = (uint8_t)id;
    p->addr = (uint8_t)addr;
    p->count = (uint8_t)count;
    p->idl = (uint16_t)(p->len + (BISS_CD_IDL_DEFAULT == BISS_CD_IDL_AT_CTS));
    put_header(p, biss_cd_reg_header(p->id, p->addr));
    p->rw = p->len;
    put_bits(p, write ? 1u : 2u, 2, BISS_CDCL_ECHO); /* R W, echoed by the slave */
    for (unsigned i = 0; i < count; i++) {
        if (write) {
            p->wdata[i] = data[i];
        }
        put_byte(p, &p->byte[i], write, write ? data[i] : 0u);
    }
    p->end = p->len;
    put(p, BISS_CDOP_0); /* S = 0: no further address */
    put_tail(p);
    return BISS_CD_OK;
}

biss_cd_err biss_cd_build_read(biss_cd_prog *p, unsigned id, unsigned addr, unsigned count) {
    return build_register(p, false, id, addr, NULL, count);
}

biss_cd_err biss_cd_build_write(biss_cd_prog *p, unsigned id, unsigned addr, const uint8_t *data,
                                unsigned count) {
    return build_register(p, true, id, addr, data, count);
}

biss_cd_err biss_cd_build_command(biss_cd_prog *p, uint8_t ids, unsigned cmd, bool ida_test) {
    return biss_cd_build_command_ex(p, ids, cmd, ida_test, BISS_CD_EX_DEFAULT);
}

biss_cd_err biss_cd_build_command_ex(biss_cd_prog *p, uint8_t ids, unsigned cmd, bool ida_test,
                                     unsigned ex) {
    if (cmd > 3 || ex > 1) {
        return BISS_CD_E_ARG;
    }
    _Static_assert(CMD_STEPS <= BISS_CD_MAX_STEPS, "a command fits a program");
    start(p, BISS_CD_COMMAND);
    p->ids = ids;
    p->cmd = (uint8_t)cmd;
    put_header(p, biss_cd_cmd_header(ids, p->cmd));
    /* IDA slot 0 is the CDS right after the last CRC bit (the default) */
    p->ida = (uint16_t)(p->len - (BISS_CD_IDA_DEFAULT == BISS_CD_IDA_AT_CRC));
    put_bits(p, 0, 8, BISS_CDCL_NONE); /* the IDA slots */
    p->end = p->len;
    p->ida_test = ida_test;
    put(p, ex ? BISS_CDOP_1 : BISS_CDOP_0); /* the slaves execute the command on it */
    put_tail(p);
    return BISS_CD_OK;
}

/* The frame's S is step 0 of a register access; the header's last CRC
 * step is 15 of a command. */
biss_cd_err biss_cd_set_idl(biss_cd_prog *p, biss_cd_idl_at at) {
    if ((p->kind != BISS_CD_READ && p->kind != BISS_CD_WRITE) ||
        (at != BISS_CD_IDL_AT_S && at != BISS_CD_IDL_AT_CTS)) {
        return BISS_CD_E_ARG;
    }
    p->idl = (uint16_t)(p->lead + (at == BISS_CD_IDL_AT_CTS));
    return BISS_CD_OK;
}

biss_cd_err biss_cd_set_ida(biss_cd_prog *p, biss_cd_ida_at at) {
    if (p->kind != BISS_CD_COMMAND || (at != BISS_CD_IDA_AT_CRC && at != BISS_CD_IDA_AT_SLOT) ||
        (p->ida_test && at != BISS_CD_IDA_DEFAULT)) {
        return BISS_CD_E_ARG;
    }
    p->ida = (uint16_t)(p->lead + 15u + (at == BISS_CD_IDA_AT_SLOT));
    return BISS_CD_OK;
}

biss_cd_err biss_cd_build_idle(biss_cd_prog *p, unsigned frames) {
    if (frames < 1) {
        return BISS_CD_E_ARG;
    }
    if (frames > BISS_CD_MAX_STEPS) {
        return BISS_CD_E_TOO_LONG;
    }
    start(p, BISS_CD_RAW);
    put_zeros(p, frames);
    return BISS_CD_OK;
}

biss_cd_err biss_cd_lead_in(biss_cd_prog *p, unsigned frames) {
    if (frames < 1) {
        return BISS_CD_E_ARG;
    }
    if (frames > BISS_CD_MAX_STEPS - (unsigned)p->len) {
        return BISS_CD_E_TOO_LONG;
    }
    memmove(p->op + frames, p->op, p->len);
    memset(p->op, BISS_CDOP_0, frames);
    p->len = (uint16_t)(p->len + frames);
    uint16_t *at[] = {&p->rw, &p->idl, &p->ida, &p->end, &p->lead};
    for (unsigned i = 0; i < sizeof at / sizeof at[0]; i++) {
        *at[i] = (uint16_t)(*at[i] + frames);
    }
    for (unsigned i = 0; i < p->count; i++) {
        biss_cd_byte_steps *b = &p->byte[i];
        uint16_t *step[] = {&b->start, &b->wait, &b->data, &b->crc, &b->stop};
        for (unsigned k = 0; k < sizeof step / sizeof step[0]; k++) {
            *step[k] = (uint16_t)(*step[k] + frames);
        }
    }
    return BISS_CD_OK;
}

biss_cd_err biss_cd_build_raw(biss_cd_prog *p, const uint8_t *ops, unsigned n) {
    if (!ops || n < 1) {
        return BISS_CD_E_ARG;
    }
    if (n > BISS_CD_MAX_STEPS) {
        return BISS_CD_E_TOO_LONG;
    }
    start(p, BISS_CD_RAW);
    for (unsigned i = 0; i < n; i++) {
        if (ops[i] > 15) {
            return BISS_CD_E_ARG;
        }
        put(p, ops[i]);
    }
    return BISS_CD_OK;
}

/* ---- the program as the firmware reads it (biss_shm.h, BISS_CD_PROG, BISS_CD_IDA_STEP) ---- */

void biss_cd_pack(const biss_cd_prog *p, uint8_t prog[BISS_CD_PROG_BYTES]) {
    memset(prog, 0, BISS_CD_PROG_BYTES);
    for (unsigned i = 0; i < p->len && i < BISS_CD_MAX_STEPS; i++) {
        prog[i / 2] |= (uint8_t)((p->op[i] & 15u) << 4 * (i % 2));
    }
}

uint32_t biss_cd_ida_word(const biss_cd_prog *p) {
    if (p->kind != BISS_CD_COMMAND || !p->ida_test) {
        return 0;
    }
    return p->end | (uint32_t)p->ids << 16;
}
