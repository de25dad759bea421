#include "biss_ctrl.h"

#include "biss_crc.h"

#define ARM_ZEROS 14

void biss_ctrl_init(biss_ctrl *c, uint8_t id, regfile *regs, unsigned reg_proc_frames) {
    *c = (biss_ctrl){0};
    c->id = id & 7;
    c->regs = regs;
    c->reg_proc_frames = reg_proc_frames;
    c->cmd_stop = BISS_CTRL_CMD_EXEC_DEFAULT;
    c->state = CTRL_IDLE;
    c->last_cmd = -1;
    c->last_addr = -1;
    c->last_value = -1;
}

uint8_t biss_ctrl_crc4_sent(uint32_t value, unsigned nbits) {
    return (uint8_t)(~biss_crc_bits(BISS_CRC4_POLY, 0, value, nbits) & 0xf);
}

uint16_t biss_ctrl_reg_header(uint8_t id, uint8_t addr) {
    return (uint16_t)(0x400u | ((id & 7u) << 7) | (addr & 0x7fu));
}

uint16_t biss_ctrl_cmd_header(uint8_t ids, uint8_t cmd) {
    return (uint16_t)(((unsigned)ids << 2) | (cmd & 3u));
}

static void go(biss_ctrl *c, biss_ctrl_state s) {
    c->state = s;
    c->shift = 0;
    c->count = 0;
}

/* The frame is over; the slave wants 14 fresh zeros before the next S. */
static int finish(biss_ctrl *c, int cdm) {
    go(c, CTRL_IDLE);
    c->armed = false;
    c->zeros = cdm ? 0 : 1;
    c->frames++;
    return 0;
}

/* After a master S (first access or sequential): the slave's S, maybe late. */
static int begin_access(biss_ctrl *c) {
    if (c->reg_proc_frames > 0) {
        c->wait_left = c->reg_proc_frames;
        go(c, CTRL_WAIT);
        return 0;
    }
    go(c, CTRL_DATA);
    return 1;
}

static void load_data(biss_ctrl *c) {
    if (!c->write) {
        c->value = regfile_read(c->regs, c->addr);
    } else {
        c->value = 0;
    }
}

static int ida_bit(const biss_ctrl *c, unsigned slot) {
    return c->addressed && !c->broadcast && slot == c->id;
}

/* ID lock: every slave answers eight CDMs of the header with IDL0..7, 1
 * in the slot of its own ID ([AD38] control-frame drawings: CDS "IDL0..7"
 * during the header, before R W S; [POS] §3.1.2: "ID Lock bits (IDL) are
 * sent back to communicate which slaves are occupied"; [TI] §2.1.3: IDs are
 * carried out by setting the IDL bits for the first eight IDs). Which
 * eight (host/CD.md, "IDL"): by default the answers to S and the 7 header
 * bits after it, as an encoder maker's open master reads them (IDL0 in the
 * CDS answering S); the first is sent before CTS has come, so a slave
 * answers them in every control frame. idl_at_cts: the answers to CTS and
 * the 7 bits after it, in a register access (CTS = 1) only. header_bit is
 * the header bit just received (0: CTS), -1 for S itself. */
static int idl_bit(const biss_ctrl *c, int header_bit) {
    if (!c->idl_at_cts) {
        return header_bit + 1 < 8 && header_bit + 1 == c->id;
    }
    if (header_bit < 0 || header_bit >= 8) {
        return 0;
    }
    unsigned k = (unsigned)header_bit;
    bool cts = (c->shift >> k) & 1u; /* CTS, k bits back */
    return cts && k == c->id;
}

static int on_header_done(biss_ctrl *c) {
    uint16_t payload = (uint16_t)(c->shift >> 4);
    uint8_t crc = c->shift & 0xf;
    if (crc != biss_ctrl_crc4_sent(payload, 11)) {
        c->crc_errors++;
        go(c, CTRL_IGNORE);
        return 0;
    }
    if (payload & 0x400u) {
        uint8_t id = (payload >> 7) & 7u;
        c->addr = payload & 0x7fu;
        go(c, id == c->id ? CTRL_RWS : CTRL_IGNORE);
        return 0;
    }
    c->ids = (uint8_t)(payload >> 2);
    c->cmd = payload & 3u;
    c->broadcast = c->ids == 0;
    c->addressed = c->broadcast || ((c->ids >> (7 - c->id)) & 1u);
    go(c, CTRL_IDA);
    return ida_bit(c, 0);
}

static int on_rws(biss_ctrl *c, int cdm) {
    c->shift = (c->shift << 1) | (unsigned)cdm;
    c->count++;
    if (c->count < 3) {
        return cdm; /* echo R, then W */
    }
    unsigned rws = c->shift & 7u;
    if (rws != 5u && rws != 3u) {
        go(c, CTRL_IGNORE);
        return 0;
    }
    c->write = rws == 3u;
    int s = begin_access(c);
    if (s) {
        load_data(c);
    }
    return s;
}

static int on_data(biss_ctrl *c, int cdm) {
    unsigned j = c->count++;
    int out;
    if (c->write) {
        c->value = (uint8_t)((c->value << 1) | (unsigned)cdm);
        out = cdm;
    } else {
        out = (c->value >> (7 - j)) & 1;
    }
    if (c->count == 8) {
        c->slave_crc = biss_ctrl_crc4_sent(c->value, 8);
        go(c, CTRL_DCRC);
    }
    return out;
}

static int on_dcrc(biss_ctrl *c, int cdm) {
    c->shift = (c->shift << 1) | (unsigned)cdm;
    int out = (c->slave_crc >> (3 - c->count)) & 1;
    c->count++;
    if (c->count < 4) {
        return out;
    }
    c->last_addr = c->addr;
    c->last_value = c->value;
    if (c->write) {
        if ((c->shift & 0xfu) != biss_ctrl_crc4_sent(c->value, 8)) {
            c->crc_errors++;
        } else if (regfile_write(c->regs, c->addr, c->value)) {
            c->writes++;
        } else {
            c->write_refused++;
        }
    } else {
        c->reads++;
    }
    go(c, CTRL_STOP);
    return out;
}

int biss_ctrl_cdm(biss_ctrl *c, int cdm) {
    cdm = cdm ? 1 : 0;
    c->zeros = cdm ? 0 : c->zeros + 1;
    int cds = 0;
    bool in_frame = c->state != CTRL_IDLE;
    switch (c->state) {
    case CTRL_IDLE:
        if (cdm && c->armed) {
            c->armed = false;
            go(c, CTRL_HEADER);
            cds = idl_bit(c, -1);
        } else if (c->zeros >= ARM_ZEROS) {
            c->armed = true;
        }
        break;
    case CTRL_IGNORE:
    case CTRL_HEADER:
        if (c->state == CTRL_IGNORE) {
            break;
        }
        c->shift = (c->shift << 1) | (unsigned)cdm;
        if (++c->count == 15) {
            cds = on_header_done(c);
        } else {
            cds = idl_bit(c, (int)c->count - 1);
        }
        break;
    case CTRL_RWS:
        cds = on_rws(c, cdm);
        break;
    case CTRL_WAIT:
        if (--c->wait_left == 0) {
            go(c, CTRL_DATA);
            load_data(c);
            cds = 1;
        }
        break;
    case CTRL_DATA:
        cds = on_data(c, cdm);
        break;
    case CTRL_DCRC:
        cds = on_dcrc(c, cdm);
        break;
    case CTRL_STOP:
        go(c, CTRL_SEQ);
        break;
    case CTRL_SEQ:
        if (cdm) {
            c->addr = (c->addr + 1) & 0x7fu;
            cds = begin_access(c);
            if (cds) {
                load_data(c);
            }
        } else {
            cds = finish(c, cdm);
        }
        break;
    case CTRL_IDA:
        if (++c->count < 8) {
            cds = ida_bit(c, c->count);
        } else {
            go(c, CTRL_CMD_STOP);
        }
        break;
    case CTRL_CMD_STOP:
        if (cdm != c->cmd_stop) {
            c->commands_dropped += c->addressed;
        } else if (c->addressed) {
            c->commands++;
            c->last_cmd = c->cmd;
        }
        cds = finish(c, cdm);
        break;
    }
    if (in_frame && c->state != CTRL_IDLE && c->zeros >= ARM_ZEROS) {
        /* [TI] TIDEP0022 §2.1.3: "Any control frame can be cancelled by
         * transmitting 14 numbers of CDM equaling 0", in whatever state it
         * is (header, late S, data, IDA): back to idle, armed. A frame
         * that this zero ends as the layout says (a final S = 0, a
         * command's P) has ended already, and wants 14 fresh zeros. */
        go(c, CTRL_IDLE);
        c->armed = true;
        c->cancels++;
        cds = 0;
    }
    c->cds = cds;
    return cds;
}
