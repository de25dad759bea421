/* biss_cd.h - host codec for BiSS-C control communication (register
 * access, sequential access, BiSS commands) over the firmware's CDM
 * program (include/biss/biss_shm.h, "control communication").
 *
 * The firmware runs a program of 4-bit steps (op and class), one per BiSS
 * frame, records as answer i the CDS of the frame after the one that sent
 * step i, computes the CRC4 of what it sends, and checks CRC4, echo and
 * IDA of what comes back. This module builds such programs for whole
 * control frames, remembers which steps carry which protocol field, and
 * turns the recorded answers and the firmware's verdict back into register
 * bytes and errors. It does no I/O: the caller moves
 * the program and the answers between the data RAM and these structs
 * (biss_cd_shm_put / biss_cd_shm_get work on a data RAM image).
 *
 * Frames as built here (CDM = master bit per frame, MSB first everywhere;
 * classes in brackets, CRC = the firmware's CRC4 bits):
 *   register access  S=1, CTS=1 ID(3) ADR(7) [DATA] (the answers to S and the
 *                    7 bits after it: ID lock IDL0..7; host/CD.md, "IDL"),
 *                    CRC, R W [ECHO], then
 *                    per byte: S=1, WAIT (CDM 1 while the slave's S is
 *                    late), D(8), CRC4(4), P=0 (read: D 0s
 *                    [DATA], CRC 0s [CHECK]; write: D [ECHO], CRC [ECHO]);
 *                    finally S=0
 *   BiSS command     S=1, CTS=0 IDS(8, first = ID 0) CMD(2) [DATA], CRC,
 *                    8 IDA slots (CDM 0; IDA0 answers the last CRC bit,
 *                    host/CD.md, "IDA"), then the bit that executes it:
 *                    EX = 1 by default (iC-MB4 rev B2, Table 31: "EX bit
 *                    after IDA"), or P = 0 (biss_cd_build_command_ex);
 *                    with the IDA test it goes out inverted if the IDA
 *                    answers differ from the IDs addressed
 * and then BISS_CD_TAIL_ZEROS steps of CDM 0 (none: the firmware itself
 * sends 14 frames of CDM 0 after a program before it starts the next).
 * CRC4: polynomial 0x13 (x^4+x+1), start 0, sent inverted, over CTS and
 * the following 10 header bits, or over the 8 data bits. */
#ifndef BISS_CD_H
#define BISS_CD_H

#include "biss/biss_shm.h"

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#define BISS_CD_MAX_BYTES  64                      /* bytes per register access */
#define BISS_CD_PROG_BYTES (BISS_CD_MAX_STEPS / 2) /* 512: 2 steps a byte */
#define BISS_CD_RESP_BYTES (BISS_CD_MAX_STEPS / 8) /* 128: 8 answers a byte */
#define BISS_CD_IDLE_ZEROS 14                      /* CDM 0 frames before a frame's S */
#define BISS_CD_TAIL_ZEROS 0 /* CDM 0 steps after a frame ends (biss_cd_build.c) */
/* A program step: op BISS_CDOP_* and class BISS_CDCL_* (biss_shm.h). */
#define BISS_CD_STEP(op, cl) ((uint8_t)((op) | (cl) << 2))
#define BISS_CD_STEP_OP(s)   ((s)&3u)
#define BISS_CD_STEP_CL(s)   ((s) >> 2 & 3u)

typedef enum {
    BISS_CD_OK = 0,
    BISS_CD_E_ARG,      /* builder argument out of range */
    BISS_CD_E_TOO_LONG, /* more than BISS_CD_MAX_STEPS steps */
    BISS_CD_E_REFUSED,  /* the firmware refused the program (CDST_ERR_STEPS) */
    BISS_CD_E_NOT_DONE, /* no end status yet (CDST_IDLE / CDST_BUSY) */
    BISS_CD_E_FRAME,    /* a BiSS frame failed mid-program (CDST_ERR_FRAME) */
    BISS_CD_E_NO_ECHO,  /* R/W not echoed: no slave took the header (ID, header CRC) */
    BISS_CD_E_NO_START, /* the slave's S did not come within the wait limit (nDELAYERR) */
    BISS_CD_E_CRC,      /* read: CRC4 of a data byte wrong */
    BISS_CD_E_ECHO,     /* write: data or CRC4 not echoed as sent */
    BISS_CD_E_IDA,      /* command: IDA bits differ from the addressed IDs */
    BISS_CD_E_WITHHELD, /* command: IDA test failed, P sent inverted: not executed */
} biss_cd_err;

typedef enum { BISS_CD_RAW, BISS_CD_READ, BISS_CD_WRITE, BISS_CD_COMMAND } biss_cd_kind;

/* Steps that carry one register byte. */
typedef struct {
    uint16_t start; /* master S; its answer is 1 if the slave's S came in time */
    uint16_t wait;  /* WAIT for a late slave S */
    uint16_t data;  /* first of 8 data steps; answers: register bits or echo */
    uint16_t crc;   /* first of 4 CRC steps; answers: the slave's CRC4, inverted */
    uint16_t stop;  /* P */
} biss_cd_byte_steps;

/* A program and where its fields are. Build it with a biss_cd_build_*. */
typedef struct {
    uint8_t op[BISS_CD_MAX_STEPS]; /* BISS_CD_STEP(op, class) per step */
    uint16_t len;                  /* steps, 1..BISS_CD_MAX_STEPS */
    biss_cd_kind kind;
    uint8_t id, addr, count;          /* register access */
    uint8_t wdata[BISS_CD_MAX_BYTES]; /* write: the bytes sent */
    uint8_t ids, cmd;                 /* command: ids bit i = slave ID i */
    uint16_t rw;                      /* register access: R step (W is rw + 1) */
    uint16_t idl; /* register access: step whose answer is IDL0 (S, or CTS: biss_cd_set_idl) */
    biss_cd_byte_steps byte[BISS_CD_MAX_BYTES];
    uint16_t ida;  /* command: step whose answer is IDA slot 0 (slot i: ida + i; biss_cd_set_ida) */
    bool ida_test; /* command: the firmware withholds P unless the IDA answers are ids */
    uint16_t end;  /* the step ending the control frame: last S = 0, or a command's P */
    uint16_t lead; /* CDM 0 steps before the frame's S (biss_cd_lead_in); every index above counts
                      them */
} biss_cd_prog;

/* What the firmware reports for a program (the data RAM words). */
typedef struct {
    uint32_t seq;   /* ST_CD_SEQ: CD_CMD of the program ended */
    uint8_t status; /* BISS_CDST_* */
    uint8_t bytes;  /* register bytes transferred correctly (the firmware's count) */
    uint16_t steps; /* steps executed: answers are recorded below it */
    uint8_t resp[BISS_CD_RESP_BYTES];
} biss_cd_answer;

/* How the slave's start bit S of a register byte came. */
typedef enum {
    BISS_CD_S_NOT_REACHED, /* the program stopped before it */
    BISS_CD_S_IN_TIME,     /* in the frame right after the master's S */
    BISS_CD_S_LATE,        /* after register processing frames (WAIT passed) */
    BISS_CD_S_MISSING,     /* not within the wait limit */
} biss_cd_start;

typedef struct {
    biss_cd_start start;
    bool answered; /* all 12 data and CRC answers were recorded */
    uint8_t data;  /* read: the register; write: the slave's echo */
    uint8_t crc;   /* the 4 CRC answers as on the line (inverted CRC4) */
    bool crc_ok;   /* crc is the line CRC4 of data */
    bool echo_ok;  /* write: data and CRC came back as sent (read: false) */
} biss_cd_byte;

typedef struct {
    biss_cd_err err;     /* the first error in line order, BISS_CD_OK if none */
    unsigned good_bytes; /* bytes transferred correctly before the first error (REGBYTES) */
    unsigned nbytes;     /* entries of byte[] filled (the program's count) */
    bool rw_echo_ok;     /* register access: R and W echoed */
    biss_cd_byte byte[BISS_CD_MAX_BYTES];
    uint8_t idl;          /* register access: ID-lock answers IDL0..7, bit i = ID i */
    bool idl_answered;    /* all 8 IDL answers were recorded */
    uint8_t ida;          /* command: IDA slot answers, bit i = ID i */
    uint8_t ida_expected; /* command: the addressed IDs (0 for a broadcast) */
    /* The slots that answered 1 around those fields, whichever reading of
     * them is right (host/CD.md): a register access's answers to S and
     * the 8 steps after it (bit k: step k, S = 0), a command's to its last
     * header CRC step and the 8 IDA steps (bit 0: the CRC step); 0 for
     * slots not recorded. */
    uint16_t header_cds;
    uint16_t ida_cds;
} biss_cd_result;

/* ---- CRC and header bits (biss_cd_crc.c) ---- */

/* CRC4 (0x13, start 0) over the low nbits of bits, MSB first; as computed. */
uint8_t biss_cd_crc4(uint32_t bits, unsigned nbits);
/* The same as sent on the line: inverted. */
uint8_t biss_cd_crc4_line(uint32_t bits, unsigned nbits);
/* The 11 header bits the header CRC covers, CTS first. */
uint16_t biss_cd_reg_header(uint8_t id, uint8_t addr);
uint16_t biss_cd_cmd_header(uint8_t ids, uint8_t cmd);

/* ---- builders (biss_cd_build.c) ---- */

/* Sequential read of count (1..64) registers of slave id (0..7) from addr
 * (0..0x7F; the address wraps after 0x7F as the slave's does). */
biss_cd_err biss_cd_build_read(biss_cd_prog *p, unsigned id, unsigned addr, unsigned count);
/* Sequential write of count bytes of data. */
biss_cd_err biss_cd_build_write(biss_cd_prog *p, unsigned id, unsigned addr, const uint8_t *data,
                                unsigned count);
/* BiSS command cmd (0..3) to the slaves in ids (bit i = ID i; 0 = all,
 * broadcast without IDA). ida_test: the firmware checks the IDA answers
 * before the execute bit and withholds the command (the bit inverted) if
 * they are not ids. The execute bit is BISS_CD_EX_DEFAULT. */
biss_cd_err biss_cd_build_command(biss_cd_prog *p, uint8_t ids, unsigned cmd, bool ida_test);
/* The bit after the IDA slots that executes a command: 1, iC-MB4 rev B2's
 * EX bit ("the slaves feedback (IDA) is tested before execution (EX bit
 * after IDA)", Table 31), the only document that speaks of that bit for a
 * command; the stop bit P = 0 of TIDEP0022 and the POSITAL manual is a
 * register access's. With 1, every CDM 0 a master sends when it stops
 * (an error, a failed frame, idle) withholds a command. */
#define BISS_CD_EX_DEFAULT 1
/* As biss_cd_build_command, with the execute bit ex (0 or 1) the slaves want. */
biss_cd_err biss_cd_build_command_ex(biss_cd_prog *p, uint8_t ids, unsigned cmd, bool ida_test,
                                     unsigned ex);
/* Where the ID-lock answers sit (host/CD.md, "IDL"): IDL0 the answer to
 * the frame's S (the default: the only source that places it, an encoder
 * maker's open master) or to CTS (one slot later). BISS_CD_E_ARG unless p
 * is a register access. */
typedef enum { BISS_CD_IDL_AT_S, BISS_CD_IDL_AT_CTS } biss_cd_idl_at;
#define BISS_CD_IDL_DEFAULT BISS_CD_IDL_AT_S
biss_cd_err biss_cd_set_idl(biss_cd_prog *p, biss_cd_idl_at at);
/* Where a command's IDA slots sit (host/CD.md, "IDA"): IDA0 the answer to
 * the last header CRC bit (the default; the firmware's IDA test reads
 * these) or to the first IDA step (one slot later: reported only, so not
 * with ida_test). BISS_CD_E_ARG unless p is a command that allows it. */
typedef enum { BISS_CD_IDA_AT_CRC, BISS_CD_IDA_AT_SLOT } biss_cd_ida_at;
#define BISS_CD_IDA_DEFAULT BISS_CD_IDA_AT_CRC
biss_cd_err biss_cd_set_ida(biss_cd_prog *p, biss_cd_ida_at at);
/* frames (1..BISS_CD_MAX_STEPS) of CDM 0: lets a slave left inside a
 * frame (after BISS_CD_E_NO_START or BISS_CD_E_FRAME) finish it and re-arm. */
biss_cd_err biss_cd_build_idle(biss_cd_prog *p, unsigned frames);
/* A program that stopped inside a control frame (status ERR_FRAME: a BiSS
 * frame failed, a new configuration's training frame among them; ERR_WAIT)
 * leaves the slave where it was. The 14 zeros the firmware sends before the
 * next program cancel a frame still open at the 14th (TIDEP0022 §2.1.3), but
 * a slave whose frame ended on one of them (a read byte's D, CRC, P and final
 * S = 0 are all CDM 0) wants 14 fresh zeros from there (biss_cd_build.c,
 * put_tail): up to 13 more before the next S. */
#define BISS_CD_REARM_ZEROS 13
/* frames (1..BISS_CD_MAX_STEPS) of CDM 0 put before a built program's S, every
 * field's step moved with it (BISS_CD_E_TOO_LONG if it no longer fits). */
biss_cd_err biss_cd_lead_in(biss_cd_prog *p, unsigned frames);
/* Any program: n (1..BISS_CD_MAX_STEPS) BISS_CD_STEP values. */
biss_cd_err biss_cd_build_raw(biss_cd_prog *p, const uint8_t *ops, unsigned n);

/* ---- what a BiSS command does (biss_cd_cmd.c; host/CD.md, "Commands") ----
 * The BiSS C command table, as Microchip's dsPIC33A BiSS documentation
 * reproduces it (the reference documents give the codes but not their
 * effects: iC-MB4 Table 33 "CMD(1:0) ... BiSS Command 00 .. 11", "some ...
 * are predefined in the BiSS C Protocol Description, others can be used for
 * device specific functionality of the slave"). */
typedef struct {
    const char *effect; /* what the addressed slaves (or all, broadcast) do */
    /* It changes how an encoder works (switches something off, bypass,
     * reserved or the slave maker's own): bissctl sends it with --force only. */
    bool changes_encoder;
} biss_cd_cmd_info;
/* The effect of cmd (0..3) sent to ids (0: broadcast); NULL for cmd > 3. */
const biss_cd_cmd_info *biss_cd_cmd_effect(uint8_t ids, unsigned cmd);
/* Where the table comes from, for help texts. */
extern const char biss_cd_cmd_source[];

/* ---- answers (biss_cd_parse.c) ---- */

/* Answer bit i as recorded (meaningful only for steps the firmware ran). */
int biss_cd_answer_bit(const biss_cd_answer *a, unsigned step);
/* Decodes the answers to a built program. Returns r->err. */
biss_cd_err biss_cd_parse(const biss_cd_prog *p, const biss_cd_answer *a, biss_cd_result *r);
const char *biss_cd_strerror(biss_cd_err e);

/* ---- data RAM words (biss_cd_shm.c) ---- */

/* The program as BISS_CD_PROG holds it: step i in the low nibble of byte
 * i/2 if i is even, the high nibble if odd; steps past the length are 0. */
void biss_cd_pack(const biss_cd_prog *p, uint8_t prog[BISS_CD_PROG_BYTES]);
/* The word at BISS_CD_IDA_STEP: P's step | the IDs expected << 16 for a
 * command with IDA test, else 0. */
uint32_t biss_cd_ida_word(const biss_cd_prog *p);
/* Writes BISS_CD_PROG, BISS_CD_STEPS, BISS_CD_WAIT_LIMIT and the IDA test
 * (BISS_CD_IDA_STEP, BISS_CD_IDA_EXPECT) into a data RAM
 * image (at least BISS_CD_RESP bytes). CD_CMD is the caller's to increment
 * afterwards, so the firmware never starts half a program. */
biss_cd_err biss_cd_shm_put(const biss_cd_prog *p, uint16_t wait_limit, uint8_t *dram,
                            size_t dram_len);
/* Reads ST_CD_SEQ, ST_CD_STATUS and BISS_CD_RESP from a data RAM image
 * (at least BISS_CD_RESP + BISS_CD_RESP_BYTES bytes). */
biss_cd_err biss_cd_shm_get(const uint8_t *dram, size_t dram_len, biss_cd_answer *a);

#endif
