// cd.p - control communication (CDM program): CD_PREPARE and CD_COMMIT.
// Included by biss_master.p.

// ============================================================================
// Control communication: the CDM program (include/biss/biss_shm.h). Not
// clocked: CD_PREPARE after a frame works out the next frame's CDM for
// either CDS (so nothing of variable length lies between a trigger and the
// frame), the CDS period picks one, CD_COMMIT after the frame records and
// checks the answers.
// State in P_CD: CdState below.
#define CD_PAST_END     0x10                // CD_OP past the program's length
#define CD_F_CDM        0                   // the CDM of the step being answered
#define CD_F_OPEN       1                   // a register byte is under way (a WAIT passed)
#define CD_ERR          0x10                // Cd.flags at or above: an error is pending

// The registers of control communication: P_CD as Cd, and each step's
// scratch. RET_POST returns from CD_PREPARE, CD_COMMIT and CD_ABORT; CD_OP
// returns through RET_LEAF.
.struct CdState                             // BissPriv from cd_cmd to cd_bytes (layout.hp)
    .u32    cmd                             // CD_CMD being run (0: none)
    .u16    step                            // the next step
    .u16    answered                        // the step answered by this frame's CDS (+1, 0: none)
    .u16    zeros                           // frames with CDM 0 in a row
    .u16    waits                           // frames in a WAIT
    .u8     cdm0                            // the CDM edge for CDS 0
    .u8     cdm1                            // its change for CDS 1
    .u16    len                             // the program's length
    .u8     crc_m                           // CRC_M, in bits 7..4 (CRC4_FEED)
    .u8     crc_s                           // CRC_S, likewise
    .u8     flags                           // CD_F_*; bits 7..4 the first error (BISS_CDST_*),
                                        // pending until the control frame ends
    .u8     bytes                           // bytes transferred
.ends
.enter cd
.assign Byte, r1.b0, r1.b0, CdmSent         // CD_COMMIT: the CDM this frame sent
.assign Byte, r1.b1, r1.b1, Cds             // the frame's CDS bit
.assign CdState, r2, r6, Cd
.assign Word, r3, r3, CdSteps               // Cd.step and Cd.answered as one
.assign Half, r5.w0, r5.w0, CdCdm           // Cd.cdm0 and Cd.cdm1 as one
.assign Word, r6, r6, CdByteState           // Cd.crc_m .. Cd.bytes as one
.assign Half, r6.w0, r6.w0, CdCrcs          // Cd.crc_m and Cd.crc_s as one
.assign Word, r7, r7, Op                    // CD_OP: the step's op (bits 1..0) and class (3..2);
                                        // CD_PAST_END past the program's length
.assign Word, r8, r8, OpStep                // CD_OP: the step to look up
.assign Word, r7, r7, NewCmd                // CD_PREPARE: BISS_CD_CMD,
.assign Half, r8.w0, r8.w0, NewSteps        //   BISS_CD_STEPS,
.assign Word, r9, r9, DoneSeq               //   BISS_ST_CD_SEQ (the last program run)
.assign Word, r9, r9, MaxSteps              // BISS_CD_MAX_STEPS
.assign Word, r8, r8, BadStatus             // BISS_ST_CD_STATUS for a refused program
.assign Word, r7, r7, CdStatus              // BISS_ST_CD_STATUS: the outcome,
.assign Byte, r7.b1, r7.b1, CdStatusBytes   //  bytes transferred,
.assign Half, r7.w2, r7.w2, CdStatusSteps   //  steps executed
.assign Word, r9, r9, OpKind                // the op alone; then the bit it sends
.assign Half, r9.w0, r9.w0, IdaP            // BISS_CD_IDA_STEP: the step of the command's P,
.assign Byte, r9.b2, r9.b2, IdaExp          //   the IDA answers expected
.assign Word, r9, r9, RespAddr              // the byte of BISS_CD_RESP for the step answered,
.assign Word, r11, r11, RespByte            //   that byte,
.assign Word, r12, r12, RespBit             //   and the step's bit in it
.assign Word, r11, r11, IdaSlot             // k = step - (P - 9): IDA slot k if k < 8
.assign Word, r9, r9, IdaBit                // the IDA answer against the expected one
.assign Word, r9, r9, CheckBit              // CRC_S's next bit, inverted, against the CDS
.assign Word, r9, r9, EchoBit               // the CDM sent against its echo
.assign Word, r11, r11, ErrCode             // the error a failed check sets (<< 4)
.assign Half, r9.w0, r9.w0, WaitLimit       // BISS_CD_WAIT_LIMIT
.assign Word, r11, r11, FeedBit             // the bit fed to CRC_M
.assign Word, r12, r12, Crc4Fb              // CRC4_FEED: the feedback bit

// crc = CRC4 (x^4 + x + 1, MSB first) of crc and bit 0 of bit. The CRC
// register is a byte field's bits 7..4 (Cd.crc_m, Cd.crc_s; bits 3..0
// stay 0): its shift drops the top bit by itself, a byte written keeping
// the result's low 8 bits. 5 cycles at most; Crc4Fb is scratch.
.macro CRC4_FEED
.mparam crc, bit
    lsr     Crc4Fb, crc, 7
    xor     Crc4Fb, Crc4Fb, bit             // feedback
    lsl     crc, crc, 1
    qbbc    CRC4_FEED_END, Crc4Fb, 0
    xor     crc, crc, 0x03 << 4
CRC4_FEED_END:
.endm

// Op = step OpStep of the program: bits 1..0 its op, 3..2 its class;
// CD_PAST_END past the length. (biss_shm_struct.h asserts BISS_CD_PROG.)
#define CD_PROG_BIT     9                   // BISS_CD_PROG = 0x200: bit 9 above step / 2 <= 511
#define CD_RESP_BIT     10                  // BISS_CD_RESP = 0x400: bit 10 above step / 8 <= 127
CD_OP_STEP:                                 // the same for step Cd.step
    mov     OpStep, Cd.step
CD_OP:
    ldi     Op, CD_PAST_END
    qble    CD_OP_DONE, OpStep, Cd.len      // length <= step
    lsr     Op, OpStep, 1
    set     Op, Op, CD_PROG_BIT             // BISS_CD_PROG + step / 2
    lbco    Op, c24, Op, 1
    qbbc    CD_OP_LOW, OpStep, 0
    lsr     Op, Op, 4                       // odd steps: the high nibble
CD_OP_LOW:
    and     Op, Op, 0x0f
CD_OP_DONE:
    jmp     RET_LEAF


// A frame failed: a running program cannot go on (the slave saw a broken
// frame) and stops as CDC_STOP stops one, with ERR_FRAME; the zeros start
// again (the failed frame counts as one without CDM 0). Then CD_PREPARE.
CD_ABORT:
    lbco    &Cd.cmd, c28, P_CD, P_CD_END - P_CD
    ldi     CdmSent, 1
    qbeq    CDC_ZEROS, Cd.cmd, 0            // no program
    ldi     CdStatus, BISS_CDST_ERR_FRAME
    qba     CDC_STOP

// After a frame with CDS Cds and CDM CdmSent (FRAME_END: MA low after it
// for 1); then CD_PREPARE, which stores the state and returns.
// (Calls nest through RET_POST and RET_LEAF (CD_OP): r0.w2 keeps the busy
// clocks for BUF_STAMP, r13..r29 hold the slave records, r10.b0 is the
// caller's.)
CD_COMMIT:
    lbco    &Cd.cmd, c28, P_CD, P_CD_END - P_CD
    qbeq    CDC_ZEROS, Cd.cmd, 0            // no program
    qbeq    CDC_SENT_STEP, Cd.answered, 0
    // the answer: recorded, then checked as its step's class asks
    sub     OpStep, Cd.answered, 1          // the step this CDS answers
    lsr     RespAddr, OpStep, 3
    set     RespAddr, RespAddr, CD_RESP_BIT // BISS_CD_RESP + step / 8
    lbco    RespByte, c24, RespAddr, 1
    and     RespBit, OpStep, 7
    clr     RespByte, RespByte, RespBit
    qbbc    CDC_BIT0, Cds, 0
    set     RespByte, RespByte, RespBit
CDC_BIT0:
    sbco    RespByte, c24, RespAddr, 1
    lbco    &IdaP, c24, BISS_CD_IDA_STEP, 4 // IdaP, IdaExp
    add     IdaSlot, OpStep, 9
    sub     IdaSlot, IdaSlot, IdaP          // k = step - (P - 9): IDA slot k if k < 8
    qblt    CDC_CLASS, IdaSlot, 7
    lsr     IdaBit, IdaExp, IdaSlot
    xor     IdaBit, IdaBit, Cds
    ldi     ErrCode, BISS_CDST_ERR_IDA << 4
    qbbs    CDC_ERR, IdaBit, 0
CDC_CLASS:
    jal     RET_LEAF, CD_OP
    lsr     Op, Op, 2
    qbeq    CDC_SENT_STEP, Op, BISS_CDCL_NONE
    qbne    CDC_FEED_S, Op, BISS_CDCL_CHECK
    lsr     CheckBit, Cd.crc_s, 7           // CHECK: the next bit of CRC_S, inverted
    xor     CheckBit, CheckBit, Cds
    lsl     Cd.crc_s, Cd.crc_s, 1           // (fed its uninverted value: a shift)
    ldi     ErrCode, BISS_CDST_ERR_CRC << 4
    qbbc    CDC_ERR, CheckBit, 0
    qba     CDC_SENT_STEP
CDC_FEED_S:
    CRC4_FEED Cd.crc_s, Cds                 // DATA and ECHO
    qbne    CDC_SENT_STEP, Op, BISS_CDCL_ECHO
    xor     EchoBit, Cd.flags, Cds          // ECHO: the CDM sent (CD_F_CDM)
    ldi     ErrCode, BISS_CDST_ERR_ECHO << 4
    qbbc    CDC_SENT_STEP, EchoBit, 0
CDC_ERR:
    qble    CDC_SENT_STEP, Cd.flags, CD_ERR // the first error stays
    or      Cd.flags, Cd.flags, ErrCode
CDC_SENT_STEP:
    // the step that went out in this frame
    ldi     Cd.answered, 0
    jal     RET_LEAF, CD_OP_STEP
    qbbs    CDC_END, Op, 4
    qbgt    CDC_NOT_END, Cd.flags, CD_ERR   // an error pending: a master S sent as 0
    qbne    CDC_NOT_END, CdmSent, 0         // ended the control frame (one that went out
    qbeq    CDC_END, Op, BISS_CDOP_1        // as 1 before the error was seen did not)
CDC_NOT_END:
    qbne    CDC_SENT, Op, BISS_CDOP_WAIT
    qbbs    CDC_WAITED, Cds, 0
    add     Cd.waits, Cd.waits, 1           // another frame in the WAIT
    lbco    WaitLimit, c24, BISS_CD_WAIT_LIMIT, 2
    qbge    CDC_ZEROS, Cd.waits, WaitLimit  // waits <= limit: go on
    ldi     CdStatus, BISS_CDST_ERR_WAIT
    qba     CDC_STOP
CDC_WAITED:
    add     Cd.step, Cd.step, 1             // past the WAIT: its next step went out
    ldi     Cd.waits, 0
    ldi     CdCrcs, 0                       // the byte's CRCs start afresh
    set     Cd.flags, Cd.flags, CD_F_OPEN
    jal     RET_LEAF, CD_OP_STEP
    qbbs    CDC_END, Op, 4
CDC_SENT:
    clr     Cd.flags, Cd.flags, CD_F_CDM
    or      Cd.flags, Cd.flags, CdmSent     // for the echo check of its answer
    qbgt    CDC_CLOSE, Op, BISS_CDOP_CRC    // class NONE, op 0 or 1
    mov     FeedBit, CdmSent
    and     OpKind, Op, 3
    qbne    CDC_FEED_M, OpKind, BISS_CDOP_CRC
    xor     FeedBit, FeedBit, 1             // a CRC bit feeds its uninverted value
CDC_FEED_M:
    CRC4_FEED Cd.crc_m, FeedBit
    qba     CDC_NEXT
CDC_CLOSE:
    // a byte under way is over (its P): count it if it had no error
    qble    CDC_NEXT, Cd.flags, CD_ERR
    qbbc    CDC_NEXT, Cd.flags, CD_F_OPEN
    clr     Cd.flags, Cd.flags, CD_F_OPEN
    add     Cd.bytes, Cd.bytes, 1
CDC_NEXT:
    add     Cd.step, Cd.step, 1
    mov     Cd.answered, Cd.step            // its CDS comes with the next frame
    qba     CDC_ZEROS
CDC_END:
    lsr     CdStatus, Cd.flags, 4           // the error pending (BISS_CDST_ERR_* > DONE),
    max     CdStatus, CdStatus, BISS_CDST_DONE // else 0: DONE
CDC_STOP:
    mov     CdStatusBytes, Cd.bytes         // bytes transferred
    mov     CdStatusSteps, Cd.step          // steps executed
    sbco    CdStatus, c24, BISS_ST_CD_STATUS, 4
    sbco    Cd.cmd, c24, BISS_ST_CD_SEQ, 4
    ldi     Cd.cmd, 0
    ldi     Cd.zeros, 0                     // the slaves count 14 zeros afresh after a frame
CDC_ZEROS:
    add     Cd.zeros, Cd.zeros, 1           // frames with CDM 0 in a row
    min     Cd.zeros, Cd.zeros, 255
    qbeq    CD_PREPARE, CdmSent, 0
    ldi     Cd.zeros, 0                     // and the next frame's CDM: CD_PREPARE stores it all

// The next frame's CDM for either CDS (the state in Cd: CD_COMMIT and
// CD_ABORT fall or branch into it), and the state stored. (A frame's path
// through here keeps the length it had when a PAD stood here: FRAME_END's
// bit-grid test took its cycle, so the next free-run frame's poll, FE_POLL,
// reads SL on the same cycles, against the same phase of the 8x shift clock.)
CD_PREPARE:
    ldi     CdCdm, 0                        // CDM 0 whatever the CDS
    qbne    CDP_RUN, Cd.cmd, 0
    lbco    NewCmd, c24, BISS_CD_CMD, 12    // NewCmd, NewSteps, DoneSeq
    qbeq    CDP_OUT, NewCmd, DoneSeq        // no new program
    qbgt    CDP_OUT, Cd.zeros, 14           // not before 14 frames with CDM 0
    mov     MaxSteps, BISS_CD_MAX_STEPS
    qbeq    CDP_BAD, NewSteps, 0
    qblt    CDP_BAD, NewSteps, MaxSteps
    mov     Cd.cmd, NewCmd                  // run it from step 0
    ldi     CdSteps, 0
    ldi     Cd.waits, 0
    mov     Cd.len, NewSteps
    ldi     CdByteState, 0                  // CRCs 0, no byte, no error
    ldi     CdStatus, BISS_CDST_BUSY
    sbco    CdStatus, c24, BISS_ST_CD_STATUS, 4
CDP_RUN:
    jal     RET_LEAF, CD_OP_STEP
    qbbs    CDP_OUT, Op, 4                  // past the end: CDM 0
    qbgt    CDP_STEP, Cd.flags, CD_ERR
    qbeq    CDP_OUT, Op, BISS_CDOP_1        // an error ends the frame at the next master S
CDP_STEP:
    and     OpKind, Op, 3
    qbeq    CDP_WAIT, OpKind, BISS_CDOP_WAIT
    qbne    CDP_BIT, OpKind, BISS_CDOP_CRC
    lsr     OpKind, Cd.crc_m, 7             // CRC_M's next bit, inverted
    xor     OpKind, OpKind, 1
CDP_BIT:
    qbbc    CDP_IDA, OpKind, 0
    ldi     Cd.cdm0, MA_MASK
CDP_IDA:
    // A command's P with the IDA test failed goes out inverted: the slaves
    // take that as a broken control frame and do not execute it.
    lbco    &IdaP, c24, BISS_CD_IDA_STEP, 2
    qbne    CDP_OUT, IdaP, Cd.step
    qbgt    CDP_OUT, Cd.flags, CD_ERR
    xor     Cd.cdm0, Cd.cdm0, MA_MASK
    qba     CDP_OUT
CDP_WAIT:
    // While the slave's S is late the master sends CDM 1 (MA low in the
    // timeout): 13 CDM 0 already follow a read byte (D, CRC, P), and any
    // control frame is cancelled by 14 (TIDEP0022 §2.1.3). TI's own PRU
    // firmware does the same: it keeps its S (clock held low) until the
    // slave's start bit comes (motor-control-sdk, bissc_main.asm,
    // BISSC_SKIP_CTRL_SB?). CDS 1 ends the wait: send the next step now.
    ldi     Cd.cdm0, MA_MASK
    add     OpStep, Cd.step, 1
    jal     RET_LEAF, CD_OP
    and     Op, Op, CD_PAST_END | 3
    qbeq    CDP_OUT, Op, BISS_CDOP_1        // 1 either way
    ldi     Cd.cdm1, MA_MASK                // 0 once CDS is 1
CDP_OUT:
    sbco    &Cd.cmd, c28, P_CD, P_CD_END - P_CD
    jmp     RET_POST
CDP_BAD:                                    // refused: ST_CD_SEQ, then ST_CD_STATUS
    ldi     BadStatus, BISS_CDST_ERR_STEPS  // (the next word: one store, in that order)
    sbco    NewCmd, c24, BISS_ST_CD_SEQ, 8
    qba     CDP_OUT

.leave cd
