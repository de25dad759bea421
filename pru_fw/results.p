// results.p - after the last bit (not clocked): the last bits read from
// the samples, the CRC verdicts, the ACK history, publication, the SL
// idle wait; then the frames that end early and the training frame (which
// end where a frame's results are written, so they stay beside them).
// Included by biss_master.p.

// ============================================================================
// After the last bit. MA is high: the clocks ran out before the last reads.
// Nothing below is clocked.

// The last slave's last one or two bits, when its switch read the bit
// before them (CFG_SHAPE). That switch's R31 snapshot (Sample, shifted to
// put its sample at bit 31) holds them 8 and 16 samples newer, at bits 23
// and 15 (indices 8 (LAG - 1) + s and 8 (LAG - 2) + s: sampled, and the
// same samples as reads one and two periods later would take at 8 LAG + s,
// 16 shift edges falling in every 2 periods). The switch has stored the
// slave's result in its slot, moved Slot to the next one and loaded the
// end record. Not clocked: this
// comes at t = 0 of the period after the switch, whose MA edge (the CDM,
// if the line delay is under two periods: m = 1) is made here; otherwise
// FallMask = 0, and SWITCH_SHORT may have cut the switch short.
.using clocked
FINAL_PLAIN2:
    MA_FALL
    lsl     Sample, Sample, 8
    SHIFT_IN
FINAL_PLAIN:
    lsl     Sample, Sample, 8
    SHIFT_IN
    sub     Slot, Slot, SlotStep            // the last slave's slot
    xout    XFR_BANK, DataLo, 12
    qba     FRAME_END
FINAL_CRC2:
    MA_FALL
    ldi     FinalBits, 2
    qba     FINAL_CRC_GO
FINAL_CRC:
    ldi     FinalBits, 1
FINAL_CRC_GO:
    sub     Slot, Slot, SlotStep            // the last slave's slot:
    xin     XFR_BANK, Crc, 4                // its CRC register
    sub     RecPtr, RecPtr, 12              // the last slave's polynomial
    mviw    RecPoly, *RecPtr++
FINAL_CRC_BIT:
    lsl     Sample, Sample, 8
    CRC_STEP
    sub     FinalBits, FinalBits, 1
    qbne    FINAL_CRC_BIT, FinalBits, 0
    xout    XFR_BANK, Crc, 4

.leave clocked

// The registers after the frame: what the clocked part leaves (r0, r1, the
// results in the scratch pad), the result buffer and flags, and each
// routine's own.
.enter results
.assign Byte, r0.b0, r0.b0, Slot            // the XFR shift: the slot FE_SLAVE reads
.assign Byte, r0.b1, r0.b1, SlotStep        // the step to the next slot (P_RUNNING)
.assign Half, r0.w0, r0.w0, XfrShift        // both, 0 after BUF_STAMP (no shift)
.assign Half, r0.w2, r0.w2, Busy            // the busy clocks (START_WAIT), for BUF_STAMP
.assign Word, r0, r0, SlotWord              // all three: 0 for a frame that did not start
.assign Byte, r1.b0, r1.b0, CdmSent         // the CDM this frame sent (CD_COMMIT)
.assign Byte, r1.b0, r1.b0, SlavesLeft      // FE_SLAVE: slaves left to check
.assign Byte, r1.b1, r1.b1, Cds             // the CDS bit (CDS_PERIOD)
.assign Half, r1.w2, r1.w2, AckPos          // this frame's ACK position Q' (ONES_B)
.assign Word, r2, r2, ResBuf                // the result buffer being filled (BUF_STAMP)
.assign Word, r2, r2, Stamp                 // BUF_STAMP: the frame's timestamp (bank register 2)
.assign Byte, r2.b0, r2.b0, Due             // P_TRAIN_DUE: 1 a training, 2 the INIT of a low SL
.assign Word, r2, r2, DueWord               //   as a word, to set it
.assign Byte, r2.b0, r2.b0, Idle8           // SLAVE_IDLE: SL's newest samples
.assign Word, r3, r3, SamplePoint           // the sample point within the bit, 0..7
.assign Word, r3, r3, SlaveRes              // FE_SLAVE: the slave's result in the buffer
.assign Word, r3, r3, CrcErrors             // BISS_ST_CRC_ERRORS
.assign Word, r3, r3, Qf                    // Qf', the average the frame was read with
.assign Word, r3, r3, NextNs                // P_NSLAVES' word, for the next frame:
.assign Byte, r3.b1, r3.b1, NextTrigger     //   its trigger
.assign Half, r3.w0, r3.w0, NextSsi         // P_SSI's ACK position (0: BiSS-C)
.assign Word, r3, r3, Sum                   // HIST_SAVE: h0 + h1 + h2 + 2
.assign Word, r3, r3, Frames                // PUBLISH: BISS_ST_FRAMES,
.assign Word, r3, r3, Seq                   //   BISS_ST_SEQ,
.assign Word, r3, r3, State                 //   BISS_ST_STATE
.assign Word, r3, r3, TallyAddr             // ABORT_FRAME: the status counter to count in,
.assign Word, r4, r4, TallyVal              //   its value
.assign Word, r4, r4, DataLo                // FE_SLAVE: a slave's result from its slot (data,
.assign Word, r5, r5, DataHi                //   CRC register), then stored with its status
.assign Word, r6, r6, Crc
.assign Word, r7, r7, Status                //   (BISS_RS_*)
.assign BissSlave, r7, r10, Chk             // FE_SLAVE: the slave's check data (layout.hp)
.assign Word, r5, r5, StampBuf              // BUF_STAMP: the result buffer
.assign Word, r6, r6, LagPeriods            // m + LAG, as published
.assign Word, r6, r6, AckJump               // Q' - Qf' + 4: 0..8 is no jump
.assign Word, r8, r8, EwBits                // FE_SLAVE: nW at bit 0, nE at bit 1
.assign Word, r8, r8, PrivNs                // P_NSLAVES' word; bit 31 (navg's bit 7): the last
                                        // ACK jumped
.assign Word, r9, r9, NeHigh                // DataHi << 1: nE at bit 0 when ew = 31
.assign PrivRun, r3, r10, Priv              // the history as P_HIST .. P_HALF loads it (r4..r8)
.assign PrivRun, r0, r7, Pub                // PUBLISH: P_BUF .. P_PROC, laid so that buf is r4
.assign Byte, r10.b0, r10.b0, Shift         // the frame's sample shift (SAMPLE_POINT), until FE_SLAVE
.assign Word, r11, r11, SlaveChk            // FE_SLAVE: the slave's check data (P_SLAVES)
.assign Word, r12, r12, ResFlags            // the result's flags, BISS_RF_*

FRAME_END:
    jal     RET_POST, CD_COMMIT             // Cds in; CdmSent out
    jal     RET_STAMP, BUF_STAMP            // ResBuf; XfrShift = 0:
    lbco    SlotStep, c28, P_RUNNING, SIZE(BissPriv.running) // slave 0's slot, and the step to the next
    sbbo    CdmSent, ResBuf, BISS_R_CDM, 1
    lbco    SlavesLeft, c28, P_NSLAVES, SIZE(BissPriv.nslaves) // slaves to check
    rsb     SamplePoint, Shift, 31 - 8 * LAG // sample point 0..7 within the bit
    sbbo    SamplePoint, ResBuf, BISS_R_SAMPLE_POINT, 1
    sbbo    Cds, ResBuf, BISS_R_CDS, 1
    ldi     ResFlags, BISS_RF_VALID         // frame flags
    add     SlaveRes, ResBuf, BISS_R_SLAVE0 // slave result
    mov     SlaveChk, BISS_PRIV + P_SLAVES  // slave check data
FE_SLAVE:
    xin     XFR_BANK, DataLo, 12            // data lo, data hi, CRC register: its slot
    add     Slot, Slot, SlotStep            // the next slave's
    lbbo    &Chk.mask_lo, SlaveChk, 0, SIZE(BissSlave) // mask lo, mask hi, residue, [n, w, ew, flags]
    and     DataLo, DataLo, Chk.mask_lo
    and     DataHi, DataHi, Chk.mask_hi
    ldi     Status, BISS_RS_CRC_OK          // slave status (DataLo..Status: the result)
    qbeq    FE_CRC_DONE, Chk.wbits, 0       // no CRC
    qbeq    FE_CRC_DONE, Crc, Chk.residue
    ldi     Status, 0
    or      ResFlags, ResFlags, BISS_RF_CRC_ERROR
FE_CRC_DONE:
    qbbc    FE_EW_DONE, Chk.sflags, 0       // no nE/nW
    // nW (data bit ew) to EwBits bit 0, nE (bit ew + 1) to bit 1
    lsr     EwBits, DataHi, Chk.ewbits      // 32 <= ew: the shift uses ew & 31
    qble    FE_EW_GOT, Chk.ewbits, 32
    lsr     EwBits, DataLo, Chk.ewbits
    lsl     NeHigh, DataHi, 1
    qbne    FE_EW_GOT, Chk.ewbits, 31
    or      EwBits, EwBits, NeHigh          // ew = 31: nE is bit 0 of the high word
FE_EW_GOT:
    qbbc    FE_NE_DONE, EwBits, 1
    set     Status, Status, 1               // nE: BISS_RS_NE (0x02)
FE_NE_DONE:
    qbbc    FE_EW_DONE, EwBits, 0
    set     Status, Status, 2               // nW: BISS_RS_NW (0x04)
FE_EW_DONE:
    sbbo    DataLo, SlaveRes, BISS_R_S_DATA_LO, 16 // data, CRC register, status
    add     SlaveRes, SlaveRes, BISS_R_SLAVE_SIZE
    add     SlaveChk, SlaveChk, SIZE(BissSlave)
    sub     SlavesLeft, SlavesLeft, 1
    qbne    FE_SLAVE, SlavesLeft, 0
    // frame counters
    qbbc    FE_NO_CRC_ERR, ResFlags, 1
    lbco    CrcErrors, c24, BISS_ST_CRC_ERRORS, 4
    add     CrcErrors, CrcErrors, 1
    sbco    CrcErrors, c24, BISS_ST_CRC_ERRORS, 4
FE_NO_CRC_ERR:
    // line delay: this frame's ACK position and the average it was read with
    lbco    &Priv.h0, c28, P_HIST, P_HALF - P_HIST // history, its sum, P_BUF, P_NSLAVES
    add     Qf, Priv.hsum, AckPos
    lsr     Qf, Qf, 2                       // Qf'
    sbbo    AckPos, ResBuf, BISS_R_DELAY_RAW, 2
    sbbo    Qf, ResBuf, BISS_R_DELAY_AVG, 2
    add     LagPeriods, Qf, 8 * LAG - 4     // m + LAG = (Qf' - 4) / 8 + LAG (SAMPLE_POINT)
    lsr     LagPeriods, LagPeriods, 3       // (Qf' >= 8: every Q' is)
    sbbo    LagPeriods, ResBuf, BISS_R_LAG_PERIODS, 1
    // History. An ACK more than half a bit from the average it was read
    // with means this frame's bits were read at the wrong place (a glitch
    // in WAIT_ACK, or an average spoilt by one) or the line changed: the
    // frame is not valid, whatever its CRC says. One such ACK is left out of
    // the average; a second in a row starts the average afresh from it.
    // P_NSLAVES bit 31 (PrivNs) remembers the first.
    sub     AckJump, AckPos, Qf             // Q' - Qf' + 4 in 0..8: no jump
    add     AckJump, AckJump, 4
    qblt    FE_ACK_JUMP, AckJump, 8
    clr     PrivNs, PrivNs, 31
    mov     Priv.h2, Priv.h1                // h2 = h1
    mov     Priv.h1, Priv.h0                // h1 = h0
    mov     Priv.h0, AckPos                 // h0 = Q'
    qble    FE_HIST_SAVE, Priv.navg, 3      // 3 <= frames in the average: full
    add     Priv.navg, Priv.navg, 1
    qba     FE_HIST_SAVE
FE_ACK_JUMP:
    xor     ResFlags, ResFlags, BISS_RF_VALID | BISS_RF_ACK_JUMP // VALID set since FRAME_END,
                                            // ACK_JUMP not: one clear, one set
    qbbs    FE_HIST_RESET, PrivNs, 31       // the second in a row
    set     PrivNs, PrivNs, 31
    qba     FE_NO_SMA                       // the history stays as it was
FE_HIST_RESET:
    mov     Priv.h0, AckPos
    mov     Priv.h1, AckPos
    mov     Priv.h2, AckPos
    ldi     Priv.navg, 0
FE_HIST_SAVE:
    qbgt    FE_NO_SMA, Priv.navg, 3
    or      ResFlags, ResFlags, BISS_RF_SMA
FE_NO_SMA:
    sbco    PrivNs, c28, P_NSLAVES, P_HALF - P_NSLAVES
    jal     RET_POST, HIST_SAVE
    jal     RET_POST, PUBLISH               // and CD_PREPARE: the next frame's CDM
    // The next frame, when it is a free-run BiSS-C one with no training due,
    // is set up now, while the slave's timeout runs: all MAIN and FRAME look
    // at changes only with a configuration, so once SL is high only a new
    // one is checked for (MAIN applies it), and the frame starts at once.
    // (No training can be due here: only a refused configuration or a
    // missing slave asks for one, and both go through MAIN.)
    lbco    &NextNs, c28, P_NSLAVES, P_HALF - P_NSLAVES
    qbne    FE_SLOW, NextTrigger, BISS_TRIG_FREERUN
    lbco    NextSsi, c28, P_SSI, SIZE(BissPriv.ssi_ack)
    qbne    FE_SLOW, NextSsi, 0
    jal     RET_SUB, FRAME_REGS
    jal     RET_SUB, SLAVE_IDLE             // the slave's timeout has ended: SL high,
    qbeq    FE_MAIN, IDLE_LEFT, 0           // or not in time: MAIN and FRAME find it so again
.using main_loop
FE_IDLE_YES:
    lbco    CfgSeq, c24, BISS_CFG_SEQ, 4    // (loaded before MA may rise: no data-RAM
    lbco    CfgAck, c24, BISS_ST_CFG_ACK, 4 // access between that edge and the frame's)
    set     MA_OUT, MA_OUT, MA_BIT          // CDM done: MA idles high
    qbne    FE_MAIN, CfgSeq, CfgAck         // a new configuration: MAIN applies it
    jmp     FRAME_STAMPED
.leave main_loop
FE_SLOW:
    jal     RET_SUB, SLAVE_IDLE             // the slave's timeout ends: SL high
FE_MAIN:
    set     MA_OUT, MA_OUT, MA_BIT          // CDM done: MA idles high
    jmp     MAIN

// History Priv.h0, h1, h2 and its sum + 2 (rounding) to P_HIST/P_HSUM;
// HIST_FILL: all three AckPos (a history started afresh from one position).
HIST_FILL:
    mov     Priv.h0, AckPos
    mov     Priv.h1, AckPos
    mov     Priv.h2, AckPos
HIST_SAVE:
    sbco    &Priv.h0, c28, P_HIST, OFFSET(BissPriv.k) - P_HIST
    add     Sum, Priv.h0, Priv.h1
    add     Sum, Sum, Priv.h2
    add     Sum, Sum, 2
    sbco    Sum, c28, P_HSUM, SIZE(BissPriv.hsum)
    jmp     RET_POST

// Publish the result buffer ResBuf with the flags in ResFlags: header words, then
// the sequence number (its low bit names the buffer), then the next buffer.
// Every publication is followed by CD_PREPARE (the next frame's CDM): it
// goes on there, and returns through RET_POST from it.
PUBLISH:
    lbco    Frames, c24, BISS_ST_FRAMES, 4
    add     Frames, Frames, 1
    sbco    Frames, c24, BISS_ST_FRAMES, 4
    sbbo    Frames, ResBuf, BISS_R_FRAME, 4
    sbbo    ResFlags, ResBuf, BISS_R_FLAGS, 4
    lbco    &Pub.buf, c28, P_BUF, P_PROC - P_BUF // P_BUF, P_NSLAVES, P_HALF
    sbbo    Pub.nslaves, ResBuf, BISS_R_NSLAVES, 1
    sbbo    Pub.half, ResBuf, BISS_R_HALF, 2
    sbco    Pub.buf, c24, BISS_ST_BUF, 4
    lbco    Seq, c24, BISS_ST_SEQ, 4
    add     Seq, Seq, 1                     // odd seq: buffer 1, even: buffer 0
    sbco    Seq, c24, BISS_ST_SEQ, 4
    xor     Pub.buf, Pub.buf, 1
    sbco    Pub.buf, c28, P_BUF, SIZE(BissPriv.buf)
    ldi     State, BISS_STATE_RUNNING
    sbco    State, c24, BISS_ST_STATE, 4
    jmp     CD_PREPARE                      // which returns through RET_POST

// Wait for SL high: the slave's timeout has ended. High means the newest
// 4 samples (IDLE_MASK, half an MA period) are all 1, not just the newest:
// a glitch on SL during the timeout must not start a frame while the slave
// still ignores MA (it would misframe this frame and the next two). Half
// a period keeps the master's overhead low at 1 MHz and still outlasts a
// glitch of two samples (25 ns at 10 MHz). At most IDLE_TURNS turns of 4
// cycles; IDLE_LEFT = 0 if SL did not come high (the turns left if it did).
// r2.b0 is scratch (Idle8). Returns through RET_SUB: free before a frame
// (FRAME_STAMPED and TRAIN_GO set Edges). A free-run frame waits here after
// FRAME_REGS (FE_IDLE_YES): of what that sets up, r2, r3 and r12 are not used.
SLAVE_IDLE:
    mov     IDLE_LEFT, IDLE_TURNS
SLAVE_IDLE_POLL:
    and     Idle8, SL_IN.b0, IDLE_MASK
    qbeq    SLAVE_IDLE_YES, Idle8, IDLE_MASK
    sub     IDLE_LEFT, IDLE_LEFT, 1
    qbne    SLAVE_IDLE_POLL, IDLE_LEFT, 0
SLAVE_IDLE_YES:
    jmp     RET_SUB

// ResBuf = the result buffer being filled, with the frame's timestamp (bank
// register 2, FRAME_STAMP) and busy clocks (Busy, START_WAIT) stored in it:
// the clocked part stores nothing. XfrShift = 0 after (no XFR shift),
// StampBuf = ResBuf. Returns through RET_STAMP.
BUF_STAMP:
    ldi     XfrShift, 0
    xin     XFR_BANK, Stamp, 4
    RESULT_BASE StampBuf
    sbbo    Stamp, StampBuf, BISS_R_TIMESTAMP, 4
    sbbo    Busy, StampBuf, BISS_R_PROC_CLOCKS, 2
    mov     ResBuf, StampBuf
    jmp     RET_STAMP

// ---- frames that end early ---------------------------------------------------
// No slave: the line delay is measured again once one answers (a slave
// may come back on another cable, or in the middle of a frame).
NO_SLAVE_IDLE:                              // SL low before a frame:
    ldi     SlotWord, 0                     // no busy clocks (BUF_STAMP)
NO_ACK:                                     // after a rising edge: MA stays high
    ldi     ResFlags, BISS_RF_NO_SLAVE
NO_SLAVE_FLAGS:                             // (SL_INIT_DONE: its own ResFlags)
    ldi     DueWord, 1
    sbco    Due, c28, P_TRAIN_DUE, SIZE(BissPriv.train_due) // training due
    ldi     TallyAddr, BISS_ST_NO_SLAVE

// ResFlags = flags, TallyAddr = the counter to increment; publish, wait for the slave.
ABORT_FRAME:
    jal     RET_POST, CD_ABORT
    lbbo    TallyVal, TallyAddr, 0, 4
    add     TallyVal, TallyVal, 1
    sbbo    TallyVal, TallyAddr, 0, 4
    jal     RET_STAMP, BUF_STAMP            // ResBuf = the result buffer
    jal     RET_POST, PUBLISH               // and CD_PREPARE
    jmp     FE_SLOW                         // wait for the slave, MA high, MAIN

// The ACK came but the start bit did not: this frame's ACK position is a
// measurement all the same, and the average starts afresh from it (an
// average gone wrong would make every frame miss its start bit).
PROC_ERROR:                                 // after a rising edge: MA stays high
    jal     RET_POST, HIST_FILL
    ldi     ResFlags, BISS_RF_PROC_ERROR
    ldi     TallyAddr, BISS_ST_PROC_ERRORS
    jmp     ABORT_FRAME

// ---- training: the line delay at a new rate -----------------------------------
// Two clocks only (as iC-MB4's INIT): the slave answers the second with its
// ACK and, clocked no further, holds SL low until its timeout. The periods
// go on without clocks until the ACK edge is seen; its position fills the
// history, so the next frame samples at the right point from its first bit.
// The frame's own WAIT_ACK and ACK periods make them: ACK_FOUND comes back
// to TRAIN_DONE.
TRAIN:
    jal     RET_SUB, SLAVE_IDLE
    qbne    TRAIN_GO, IDLE_LEFT, 0
SL_INIT:                                    // SL stuck low: INIT first (see SL_INIT_DONE)
    ldi     DueWord, 2                      // training due, as the INIT
    sbco    Due, c28, P_TRAIN_DUE, SIZE(BissPriv.train_due)
TRAIN_GO:
    jal     RET_SUB, FRAME_REGS
.leave results
.using clocked
    ldi     Edges, 2 * MA_MASK              // one clock after period 0's
    jmp     FRAME_CLOCKED
.leave clocked
.using results
TRAIN_DONE:
    lbco    Due, c28, P_TRAIN_DUE, SIZE(BissPriv.train_due)
    qbne    SL_INIT_DONE, Due, 1            // it was the INIT of a low SL
    jal     RET_POST, HIST_FILL             // Priv.h0, h1 = Q' too
    jal     RET_STAMP, BUF_STAMP            // ResBuf (Priv.h0, h1 kept)
    sbbo    &Priv.h0, ResBuf, BISS_R_DELAY_RAW, 4 // and DELAY_AVG
    sbco    XfrShift, c28, P_TRAIN_DUE, SIZE(BissPriv.train_due) // training done (XfrShift = 0: BUF_STAMP)
    sbco    XfrShift, c28, P_NAVG, SIZE(BissPriv.navg) // the average starts at this frame
    ldi     ResFlags, BISS_RF_TRAINING
    ldi     TallyAddr, BISS_ST_TRAINING
    jmp     ABORT_FRAME

// A slave that keeps SL low (the last slave undefined after a disconnect or
// a broken frame) never lets TRAIN see SL high. iC-MB4's INIT exists for
// it: "necessary, if the last slave ... is not defined and the data line SLx
// is digital low"; two low pulses on MA, the slave answers and releases SL
// after its timeout; "The INIT sequence does not test the SLx state"
// (datasheet, BiSS C Initialization Sequence; INIT, Table 46). The training
// frame's two clocks are that sequence; with SL low from the start its
// ACK position means nothing, so it is published flagged (SL_INIT and
// NO_SLAVE, counted as no slave) and training stays due: the next MAIN
// trains at once, with SL high if the slave came back. (SL_INIT, above,
// marks the training frame as that INIT.)
SL_INIT_DONE:                               // a training proper next
    ldi     ResFlags, BISS_RF_NO_SLAVE | BISS_RF_SL_INIT
    qba     NO_SLAVE_FLAGS
.leave results
