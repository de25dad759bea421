// cd.p - control communication (CDM program): CD_PREPARE and CD_COMMIT.
// Included by biss_master.p.

// ============================================================================
// Control communication: the CDM program (include/biss/biss_shm.h). Not
// clocked: CD_PREPARE after a frame works out the next frame's CDM for
// either CDS (so nothing of variable length lies between a trigger and the
// frame), the CDS period picks one, CD_COMMIT after the frame records and
// checks the answers.
// State in P_CD: r2 program run, r3.w0 step, r3.w2 answered step + 1,
// r4.w0 zeros in a row, r4.w2 WAIT frames, r5.b0/b1 CDM edge, r5.w2 length,
// r6.b0 CRC_M, r6.b1 CRC_S, r6.b2 flags (CD_F_*; bits 7..4 the first error,
// BISS_CDST_*, pending until the control frame ends), r6.b3 bytes.
#define CD_PAST_END     0x10                // CD_OP past the program's length
#define CD_F_CDM        0                   // the CDM of the step being answered
#define CD_F_OPEN       1                   // a register byte is under way (a WAIT passed)
#define CD_ERR          0x10                // r6.b2 at or above: an error is pending

// crc = CRC4 (x^4 + x + 1, MSB first) of crc and bit 0 of bit. 6 cycles at
// most; r12 is scratch.
.macro CRC4_FEED
.mparam crc, bit
    lsr     r12, crc, 3
    xor     r12, r12, bit                   // feedback
    lsl     crc, crc, 1
    and     crc, crc, 0x0f
    qbbc    CRC4_FEED_END, r12, 0
    xor     crc, crc, 0x03
CRC4_FEED_END:
.endm

// r7 = step r8 of the program: bits 1..0 its op, 3..2 its class;
// CD_PAST_END past the length. (biss_shm_struct.h asserts BISS_CD_PROG.)
CD_OP_STEP:                                 // the same for step r8 = r3.w0
    mov     r8, r3.w0
CD_OP:
    ldi     r7, CD_PAST_END
    qble    CD_OP_DONE, r8, r5.w2           // length <= step
    lsr     r7, r8, 1
    set     r7, r7, 10                      // BISS_CD_PROG (0x400) + step / 2
    lbco    r7, c24, r7, 1
    qbbc    CD_OP_LOW, r8, 0
    lsr     r7, r7, 4                       // odd steps: the high nibble
CD_OP_LOW:
    and     r7, r7, 0x0f
CD_OP_DONE:
    jmp     RET_LEAF

CD_PREPARE:
    lbco    r2, c28, P_CD, P_SSI - P_CD
    ldi     r5.w0, 0                        // CDM 0 whatever the CDS
    qbne    CDP_RUN, r2, 0
    lbco    r7, c24, BISS_CD_CMD, 12        // r7 CD_CMD, r8.w0 CD_STEPS, r9 ST_CD_SEQ
    qbeq    CDP_OUT, r7, r9                 // no new program
    qbgt    CDP_OUT, r4.w0, 14              // not before 14 frames with CDM 0
    mov     r9, BISS_CD_MAX_STEPS
    qbeq    CDP_BAD, r8.w0, 0
    qblt    CDP_BAD, r8.w0, r9
    mov     r2, r7                          // run it from step 0
    ldi     r3, 0
    ldi     r4.w2, 0
    mov     r5.w2, r8.w0
    ldi     r6, 0                           // CRCs 0, no byte, no error
    ldi     r7, BISS_CDST_BUSY
    sbco    r7, c24, BISS_ST_CD_STATUS, 4
CDP_RUN:
    jal     RET_LEAF, CD_OP_STEP
    qbbs    CDP_OUT, r7, 4                  // past the end: CDM 0
    qbgt    CDP_STEP, r6.b2, CD_ERR
    qbeq    CDP_OUT, r7, BISS_CDOP_1        // an error ends the frame at the next master S
CDP_STEP:
    and     r9, r7, 3
    qbeq    CDP_WAIT, r9, BISS_CDOP_WAIT
    qbne    CDP_BIT, r9, BISS_CDOP_CRC
    lsr     r9, r6.b0, 3                    // CRC_M's next bit, inverted
    xor     r9, r9, 1
CDP_BIT:
    qbbc    CDP_IDA, r9, 0
    ldi     r5.b0, MA_MASK
CDP_IDA:
    // A command's P with the IDA test failed goes out inverted: the slaves
    // take that as a broken control frame and do not execute it.
    lbco    r9, c24, BISS_CD_IDA_STEP, 2
    qbne    CDP_OUT, r9.w0, r3.w0
    qbgt    CDP_OUT, r6.b2, CD_ERR
    xor     r5.b0, r5.b0, MA_MASK
    qba     CDP_OUT
CDP_WAIT:
    // While the slave's S is late the master sends CDM 1 (MA low in the
    // timeout): 13 CDM 0 already follow a read byte (D, CRC, P), and any
    // control frame is cancelled by 14 (TIDEP0022 §2.1.3). TI's own PRU
    // firmware does the same: it keeps its S (clock held low) until the
    // slave's start bit comes (motor-control-sdk, bissc_main.asm,
    // BISSC_SKIP_CTRL_SB?). CDS 1 ends the wait: send the next step now.
    ldi     r5.b0, MA_MASK
    add     r8, r3.w0, 1
    jal     RET_LEAF, CD_OP
    and     r7, r7, CD_PAST_END | 3
    qbeq    CDP_OUT, r7, BISS_CDOP_1        // 1 either way
    ldi     r5.b1, MA_MASK                  // 0 once CDS is 1
CDP_OUT:
    sbco    r2, c28, P_CD, P_SSI - P_CD
    jmp     r0.w0
CDP_BAD:                                    // refused: ST_CD_SEQ, then ST_CD_STATUS
    ldi     r8, BISS_CDST_ERR_STEPS         // (the next word: one store, in that order)
    sbco    r7, c24, BISS_ST_CD_SEQ, 8
    qba     CDP_OUT

// After a frame with CDS r1.b1: returns the CDM it sent in r2.b0.
// (Calls nest through r0.w0 and r10.w2 (CD_OP): r0.w2 keeps the busy
// clocks for BUF_STAMP, r13..r29 hold the slave records, r10.b0 is the
// caller's.)
CD_COMMIT:
    lbco    r2, c28, P_CD, P_SSI - P_CD
    rsb     r7, r1.b1, 0                    // the CDM edge that went out
    and     r7, r7, r5.b1
    xor     r7, r7, r5.b0
    min     r1.b0, r7, 1
    qbeq    CDC_ZEROS, r2, 0                // no program
    qbeq    CDC_SENT_STEP, r3.w2, 0
    // the answer: recorded, then checked as its step's class asks
    sub     r8, r3.w2, 1                    // the step this CDS answers
    lsr     r9, r8, 3
    mov     r11, BISS_CD_RESP
    add     r9, r9, r11
    lbco    r11, c24, r9, 1
    and     r12, r8, 7
    clr     r11, r11, r12
    qbbc    CDC_BIT0, r1.b1, 0
    set     r11, r11, r12
CDC_BIT0:
    sbco    r11, c24, r9, 1
    lbco    r9, c24, BISS_CD_IDA_STEP, 4    // r9.w0 P, r9.b2 the IDA expected
    add     r11, r8, 9
    sub     r11, r11, r9.w0                 // k = step - (P - 9): IDA slot k if k < 8
    qblt    CDC_CLASS, r11, 7
    lsr     r9, r9.b2, r11
    xor     r9, r9, r1.b1
    ldi     r11, BISS_CDST_ERR_IDA << 4
    qbbs    CDC_ERR, r9, 0
CDC_CLASS:
    jal     RET_LEAF, CD_OP
    lsr     r7, r7, 2
    qbeq    CDC_SENT_STEP, r7, BISS_CDCL_NONE
    qbne    CDC_FEED_S, r7, BISS_CDCL_CHECK
    lsr     r9, r6.b1, 3                    // CHECK: the next bit of CRC_S, inverted
    xor     r9, r9, r1.b1
    lsl     r6.b1, r6.b1, 1                 // (fed its uninverted value: a shift)
    and     r6.b1, r6.b1, 0x0f
    ldi     r11, BISS_CDST_ERR_CRC << 4
    qbbc    CDC_ERR, r9, 0
    qba     CDC_SENT_STEP
CDC_FEED_S:
    CRC4_FEED r6.b1, r1.b1                  // DATA and ECHO
    qbne    CDC_SENT_STEP, r7, BISS_CDCL_ECHO
    xor     r9, r6.b2, r1.b1                // ECHO: the CDM sent (CD_F_CDM)
    ldi     r11, BISS_CDST_ERR_ECHO << 4
    qbbc    CDC_SENT_STEP, r9, 0
CDC_ERR:
    qble    CDC_SENT_STEP, r6.b2, CD_ERR    // the first error stays
    or      r6.b2, r6.b2, r11
CDC_SENT_STEP:
    // the step that went out in this frame
    ldi     r3.w2, 0
    jal     RET_LEAF, CD_OP_STEP
    qbbs    CDC_END, r7, 4
    qbgt    CDC_NOT_END, r6.b2, CD_ERR      // an error pending: a master S sent as 0
    qbne    CDC_NOT_END, r1.b0, 0           // ended the control frame (one that went out
    qbeq    CDC_END, r7, BISS_CDOP_1        // as 1 before the error was seen did not)
CDC_NOT_END:
    qbne    CDC_SENT, r7, BISS_CDOP_WAIT
    qbbs    CDC_WAITED, r1.b1, 0
    add     r4.w2, r4.w2, 1                 // another frame in the WAIT
    lbco    r9, c24, BISS_CD_WAIT_LIMIT, 2
    qbge    CDC_ZEROS, r4.w2, r9.w0         // waits <= limit: go on
    ldi     r7, BISS_CDST_ERR_WAIT
    qba     CDC_STOP
CDC_WAITED:
    add     r3.w0, r3.w0, 1                 // past the WAIT: its next step went out
    ldi     r4.w2, 0
    ldi     r6.w0, 0                        // the byte's CRCs start afresh
    set     r6.b2, r6.b2, CD_F_OPEN
    jal     RET_LEAF, CD_OP_STEP
    qbbs    CDC_END, r7, 4
CDC_SENT:
    clr     r6.b2, r6.b2, CD_F_CDM
    or      r6.b2, r6.b2, r1.b0             // for the echo check of its answer
    qbgt    CDC_CLOSE, r7, BISS_CDOP_CRC    // class NONE, op 0 or 1
    mov     r11, r1.b0
    and     r9, r7, 3
    qbne    CDC_FEED_M, r9, BISS_CDOP_CRC
    xor     r11, r11, 1                     // a CRC bit feeds its uninverted value
CDC_FEED_M:
    CRC4_FEED r6.b0, r11
    qba     CDC_NEXT
CDC_CLOSE:
    // a byte under way is over (its P): count it if it had no error
    qble    CDC_NEXT, r6.b2, CD_ERR
    qbbc    CDC_NEXT, r6.b2, CD_F_OPEN
    clr     r6.b2, r6.b2, CD_F_OPEN
    add     r6.b3, r6.b3, 1
CDC_NEXT:
    add     r3.w0, r3.w0, 1
    mov     r3.w2, r3.w0                    // its CDS comes with the next frame
    qba     CDC_ZEROS
CDC_END:
    ldi     r7, BISS_CDST_DONE
    qbgt    CDC_STOP, r6.b2, CD_ERR
    lsr     r7, r6.b2, 4                    // the error pending
CDC_STOP:
    mov     r7.b1, r6.b3                    // bytes transferred
    mov     r7.w2, r3.w0                    // steps executed
    sbco    r7, c24, BISS_ST_CD_STATUS, 4
    sbco    r2, c24, BISS_ST_CD_SEQ, 4
    ldi     r2, 0
    ldi     r4.w0, 0                        // the slaves count 14 zeros afresh after a frame
CDC_ZEROS:
    add     r4.w0, r4.w0, 1                 // frames with CDM 0 in a row
    min     r4.w0, r4.w0, 255
    qbeq    CDC_SAVE, r1.b0, 0
    ldi     r4.w0, 0
CDC_SAVE:
    sbco    r2, c28, P_CD, P_SSI - P_CD
    mov     r2.b0, r1.b0
    jmp     r0.w0

// A frame failed: a running program cannot go on (the slave saw a broken
// frame), and the zeros start again. r3 and r12 are the caller's.
CD_ABORT:
    lbco    r4, c28, P_CD, P_SSI - P_CD     // r4 program, r5.w0 step, r8.b3 bytes
    ldi     r9, 0
    sbco    r9, c28, P_CD_ZEROS, SIZE(BissPriv.cd_zeros)  // zeros in a row: none
    qbeq    CDA_DONE, r4, 0
    sbco    r9, c28, P_CD, SIZE(BissPriv.cd_cmd)  // no program
    sbco    r4, c24, BISS_ST_CD_SEQ, 4
    mov     r9.w2, r5.w0
    ldi     r9.b0, BISS_CDST_ERR_FRAME
    mov     r9.b1, r8.b3
    sbco    r9, c24, BISS_ST_CD_STATUS, 4
CDA_DONE:
    jmp     r0.w0
