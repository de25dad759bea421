/* Parser: the firmware's answer bits back into register bytes, IDA bits
 * and verdicts. */
#include "biss_cd.h"

#include <string.h>

int biss_cd_answer_bit(const biss_cd_answer *a, unsigned step) {
    if (step >= BISS_CD_MAX_STEPS) {
        return 0;
    }
    return (a->resp[step / 8] >> (step % 8)) & 1;
}

static unsigned answer_bits(const biss_cd_answer *a, unsigned step, unsigned nbits) {
    unsigned v = 0;
    for (unsigned i = 0; i < nbits; i++) {
        v = v << 1 | (unsigned)biss_cd_answer_bit(a, step + i);
    }
    return v;
}

/* The firmware's verdict alone (a raw program has no fields to parse). */
static biss_cd_err fw_error(const biss_cd_answer *a) {
    switch (a->status) {
    case BISS_CDST_ERR_WAIT:
        return BISS_CD_E_NO_START;
    case BISS_CDST_ERR_FRAME:
        return BISS_CD_E_FRAME;
    case BISS_CDST_ERR_CRC:
        return BISS_CD_E_CRC;
    case BISS_CDST_ERR_ECHO:
        return BISS_CD_E_ECHO;
    case BISS_CDST_ERR_IDA:
        return BISS_CD_E_WITHHELD;
    default:
        return BISS_CD_OK;
    }
}

/* Steps below the result have their answers recorded. A WAIT that timed
 * out stops at the WAIT itself (the S before it was answered in the first
 * WAIT frame); an error ends the control frame at a master S, sent as 0,
 * whose frame records the answer before it. A failed frame loses the
 * answer of the step sent last. */
static unsigned answered_limit(const biss_cd_prog *p, const biss_cd_answer *a) {
    switch (a->status) {
    case BISS_CDST_DONE:
        return p->len;
    case BISS_CDST_ERR_WAIT:
    case BISS_CDST_ERR_CRC:
    case BISS_CDST_ERR_ECHO:
    case BISS_CDST_ERR_IDA:
        return a->steps;
    case BISS_CDST_ERR_FRAME:
        return a->steps > 0 ? a->steps - 1u : 0u;
    default:
        return 0;
    }
}

/* Errors of the program as a whole, before any field is looked at. */
static biss_cd_err status_error(const biss_cd_answer *a) {
    switch (a->status) {
    case BISS_CDST_DONE:
    case BISS_CDST_ERR_WAIT:  /* placed at its byte by parse_byte */
    case BISS_CDST_ERR_FRAME: /* placed after the bytes that made it */
    case BISS_CDST_ERR_CRC:   /* these three: found again in the answers */
    case BISS_CDST_ERR_ECHO:
    case BISS_CDST_ERR_IDA:
        return BISS_CD_OK;
    case BISS_CDST_ERR_STEPS:
        return BISS_CD_E_REFUSED;
    default:
        return BISS_CD_E_NOT_DONE;
    }
}

static biss_cd_start start_verdict(const biss_cd_byte_steps *at, const biss_cd_answer *a,
                                   unsigned limit) {
    if (at->start >= limit) {
        return BISS_CD_S_NOT_REACHED;
    }
    if (biss_cd_answer_bit(a, at->start)) {
        return BISS_CD_S_IN_TIME;
    }
    if (a->steps > at->wait) { /* the firmware went past the WAIT: S came */
        return BISS_CD_S_LATE;
    }
    return a->status == BISS_CDST_ERR_WAIT ? BISS_CD_S_MISSING : BISS_CD_S_NOT_REACHED;
}

/* Decodes register byte i; returns its error (BISS_CD_OK if it came right). */
static biss_cd_err parse_byte(const biss_cd_prog *p, const biss_cd_answer *a, unsigned limit,
                              unsigned i, biss_cd_byte *b) {
    const biss_cd_byte_steps *at = &p->byte[i];
    b->start = start_verdict(at, a, limit);
    b->answered = at->crc + 4u <= limit;
    if (b->start == BISS_CD_S_MISSING) {
        return BISS_CD_E_NO_START;
    }
    if (!b->answered) {
        return BISS_CD_E_FRAME;
    }
    b->data = (uint8_t)answer_bits(a, at->data, 8);
    b->crc = (uint8_t)answer_bits(a, at->crc, 4);
    b->crc_ok = b->crc == biss_cd_crc4_line(b->data, 8);
    if (p->kind == BISS_CD_WRITE) {
        b->echo_ok = b->data == p->wdata[i] && b->crc == biss_cd_crc4_line(p->wdata[i], 8);
        return b->echo_ok ? BISS_CD_OK : BISS_CD_E_ECHO;
    }
    return b->crc_ok ? BISS_CD_OK : BISS_CD_E_CRC;
}

/* R and W come back as sent from the addressed slave; a slave that did
 * not take the header answers 0 to both. */
static bool rw_echoed(const biss_cd_prog *p, const biss_cd_answer *a, unsigned limit) {
    if (p->rw + 2u > limit) {
        return false;
    }
    int write = p->kind == BISS_CD_WRITE;
    return biss_cd_answer_bit(a, p->rw) == !write && biss_cd_answer_bit(a, p->rw + 1u) == write;
}

/* A failed BiSS frame matters up to the control frame's last step; one
 * lost in the tail after it costs nothing. */
static bool frame_ended(const biss_cd_prog *p, const biss_cd_answer *a, unsigned limit) {
    return a->status != BISS_CDST_ERR_FRAME || limit > p->end;
}

/* Answers to steps from .. from + n - 1 that were recorded, bit k = step
 * from + k. */
static uint16_t recorded(const biss_cd_answer *a, unsigned from, unsigned n, unsigned limit) {
    uint16_t m = 0;
    for (unsigned k = 0; k < n && from + k < limit; k++) {
        m |= (uint16_t)(biss_cd_answer_bit(a, from + k) << k);
    }
    return m;
}

static void parse_register(const biss_cd_prog *p, const biss_cd_answer *a, biss_cd_result *r) {
    unsigned limit = answered_limit(p, a);
    r->nbytes = p->count;
    /* ID lock: recorded with the other answers, no verdict (which IDs are
     * locked is the slaves' business; a missing one shows as no echo) */
    r->idl_answered = p->idl + 8u <= limit;
    for (unsigned i = 0; r->idl_answered && i < 8; i++) {
        r->idl |= (uint8_t)(biss_cd_answer_bit(a, p->idl + i) << i);
    }
    r->header_cds = recorded(a, p->lead, 9, limit);
    r->rw_echo_ok = rw_echoed(p, a, limit);
    if (!r->rw_echo_ok) {
        r->err = p->rw + 2u > limit ? BISS_CD_E_FRAME : BISS_CD_E_NO_ECHO;
    }
    for (unsigned i = 0; i < p->count; i++) {
        biss_cd_err e = parse_byte(p, a, limit, i, &r->byte[i]);
        if (r->err == BISS_CD_OK) {
            r->err = e;
        }
    }
    if (r->err == BISS_CD_OK && !frame_ended(p, a, limit)) {
        r->err = BISS_CD_E_FRAME;
    }
    bool checked = a->status == BISS_CDST_ERR_CRC || a->status == BISS_CDST_ERR_ECHO;
    if (r->err == BISS_CD_OK && checked) {
        r->err = fw_error(a); /* the firmware saw what the answers do not show */
    }
    r->good_bytes = a->bytes;
}

static void parse_command(const biss_cd_prog *p, const biss_cd_answer *a, biss_cd_result *r) {
    r->ida_cds = recorded(a, p->lead + 15u, 9, answered_limit(p, a));
    if (p->ida + 8u > answered_limit(p, a)) {
        r->err = BISS_CD_E_FRAME;
        return;
    }
    /* (a frame failing at P may or may not have let the command execute) */
    if (!frame_ended(p, a, answered_limit(p, a))) {
        r->err = BISS_CD_E_FRAME;
    }
    for (unsigned i = 0; i < 8; i++) {
        r->ida |= (uint8_t)(biss_cd_answer_bit(a, p->ida + i) << i);
    }
    if (r->err == BISS_CD_OK && r->ida != r->ida_expected) {
        r->err = BISS_CD_E_IDA;
    }
    if (r->err == BISS_CD_E_IDA && a->status == BISS_CDST_ERR_IDA) {
        r->err = BISS_CD_E_WITHHELD;
    }
}

biss_cd_err biss_cd_parse(const biss_cd_prog *p, const biss_cd_answer *a, biss_cd_result *r) {
    memset(r, 0, sizeof *r);
    if (p->kind == BISS_CD_COMMAND) {
        /* a broadcast is acknowledged by nobody */
        r->ida_expected = p->ids;
    }
    r->err = status_error(a);
    if (r->err != BISS_CD_OK) {
        return r->err;
    }
    switch (p->kind) {
    case BISS_CD_READ:
    case BISS_CD_WRITE:
        parse_register(p, a, r);
        break;
    case BISS_CD_COMMAND:
        parse_command(p, a, r);
        break;
    case BISS_CD_RAW:
        r->err = fw_error(a);
        r->good_bytes = a->bytes;
        break;
    }
    return r->err;
}

const char *biss_cd_strerror(biss_cd_err e) {
    static const char *const text[] = {
        [BISS_CD_OK] = "ok",
        [BISS_CD_E_ARG] = "argument out of range",
        [BISS_CD_E_TOO_LONG] = "program longer than the firmware takes",
        [BISS_CD_E_REFUSED] = "program refused by the firmware",
        [BISS_CD_E_NOT_DONE] = "program not ended",
        [BISS_CD_E_FRAME] = "a BiSS frame failed during the program",
        [BISS_CD_E_NO_ECHO] = "R/W not echoed: no slave took the header",
        [BISS_CD_E_NO_START] = "slave start bit missing",
        [BISS_CD_E_CRC] = "register data CRC error",
        [BISS_CD_E_ECHO] = "write not echoed as sent",
        [BISS_CD_E_IDA] = "IDA bits differ from the addressed slaves",
        [BISS_CD_E_WITHHELD] = "IDA test failed: command withheld",
    };
    if ((unsigned)e >= sizeof text / sizeof text[0] || !text[e]) {
        return "unknown error";
    }
    return text[e];
}
