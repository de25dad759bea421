/* The slave side of BiSS-C control communication: one CDM bit in per BiSS
 * frame (sampled in the timeout), one CDS bit out in the next frame.
 *
 * Frame layout, as this model implements it (CDM = master, CDS = slave;
 * "after bit X" means the CDS sent in the frame after the CDM X arrived):
 *
 *   idle        >= 14 consecutive CDM = 0 arm the slave
 *   S           CDM = 1 while armed starts a control frame
 *   header      CTS, then 10 bits, then CRC4 (poly 0x13, start 0, sent
 *               inverted) over CTS and the 10 bits; CDS after S and the
 *               next 7 bits: IDL0..7, 1 in the slot of the slave's own ID
 *               (ID lock; or, idl_at_cts, after CTS and the next 7 bits of
 *               a register access; host/CD.md, "IDL")
 *                 CTS = 1 register access: ID(3) ADR(7)
 *                 CTS = 0 BiSS command:    IDS(8, first bit = ID 0) CMD(2)
 *               bad CRC -> error counter +1, frame ignored; other ID ->
 *               ignored
 *   register    R W S from the master (read 1 0 1, write 0 1 1); CDS echoes
 *               R after R and W after W; after S the slave answers its own S:
 *               1 at once, or 0 for reg_proc_frames frames first (late S,
 *               register processing time)
 *     data      8 CDM bits follow, the first in the frame that carried the
 *               slave's S = 1; CDS after each: the register bit (read, MSB
 *               first) or the echo of the received bit (write)
 *     CRC       4 CDM bits (write: inverted CRC4 of the data; read: 0); CDS
 *               after each: inverted CRC4 of the data the slave sent; a
 *               write is stored after the 4th if its CRC is right (else error
 *               counter +1)
 *     P         one CDM (stop); CDS 0
 *     S         one more CDM: 1 = sequential access of the next address
 *               (same direction; the slave's S/late-S and data follow as
 *               above), 0 = end of the frame
 *   command     after the CRC, 8 IDA slots: CDS after the CRC and after each
 *               of the first 7 slots is 1 in slot i if this slave has ID i and
 *               was addressed (never for a broadcast, IDS = 0); then the
 *               execute bit, on which the command is executed (recorded)
 *               if it equals cmd_stop; the other value breaks the frame:
 *               the command is dropped (counted). cmd_stop is 1 by default
 *               (iC-MB4 rev B2, Table 31: "EX bit after IDA"); 0 models a
 *               slave that takes the register access's stop bit P = 0
 *               (TIDEP0022, the Posital manual) there. A master's IDA test
 *               withholds a command by inverting the bit, which works for
 *               either.
 *
 * After a frame ends the slave needs 14 zero CDMs again before a new S.
 * 14 zero CDMs in a row cancel a control frame in any state ([TI]
 * TIDEP0022 §2.1.3: "any control frame"), counted in `cancels`. */
#ifndef BISS_CTRL_H
#define BISS_CTRL_H

#include "regfile.h"

#include <stdbool.h>
#include <stdint.h>

/* The bit after the IDA slots that executes a command: iC-MB4 rev B2,
 * Table 31, "EX bit after IDA" (1); 0 for a slave that takes the register
 * access's stop bit P = 0 ([TI], [POS]) there. */
#define BISS_CTRL_CMD_EXEC_DEFAULT 1

typedef enum {
    CTRL_IDLE,
    CTRL_HEADER,
    CTRL_RWS,
    CTRL_WAIT,
    CTRL_DATA,
    CTRL_DCRC,
    CTRL_STOP,
    CTRL_SEQ,
    CTRL_IDA,
    CTRL_CMD_STOP,
    CTRL_IGNORE,
} biss_ctrl_state;

typedef struct {
    uint8_t id;               /* 0..7 */
    unsigned reg_proc_frames; /* late S: frames of register processing */
    uint8_t cmd_stop;         /* the bit after IDA that executes a command (default 1) */
    bool idl_at_cts;          /* IDL0 answers CTS, not S (host/CD.md, "IDL") */
    regfile *regs;

    biss_ctrl_state state;
    unsigned zeros; /* consecutive zero CDMs */
    bool armed;     /* idle and seen >= 14 zeros */
    uint32_t shift; /* bits being collected */
    unsigned count; /* bits collected in this state */
    int cds;        /* CDS to send in the next frame */

    uint8_t addr;
    bool write;
    uint8_t value;     /* byte sent (read) or received (write) */
    uint8_t slave_crc; /* inverted CRC4 the slave sends */
    unsigned wait_left;
    uint8_t ids, cmd;
    bool addressed, broadcast;

    /* what happened, for the bench and tests */
    unsigned long crc_errors, reads, writes, write_refused, commands, commands_dropped, frames;
    unsigned long cancels; /* control frames cancelled by 14 zero CDMs */
    int last_cmd;          /* -1 until a command executes */
    int last_addr, last_value;
} biss_ctrl;

void biss_ctrl_init(biss_ctrl *c, uint8_t id, regfile *regs, unsigned reg_proc_frames);

/* Takes the CDM sampled at the end of a frame; returns the CDS for the next. */
int biss_ctrl_cdm(biss_ctrl *c, int cdm);

/* Builds the 11 bits a header CRC4 covers: register access or command. */
uint16_t biss_ctrl_reg_header(uint8_t id, uint8_t addr);
uint16_t biss_ctrl_cmd_header(uint8_t ids, uint8_t cmd);

/* Inverted CRC4 as sent on the line for n bits of value. */
uint8_t biss_ctrl_crc4_sent(uint32_t value, unsigned nbits);

#endif
