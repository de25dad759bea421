// results.p - after the last bit (not clocked): the last bits read from
// the samples, the CRC verdicts, the ACK history, publication, the SL
// idle wait; then the frames that end early and the training frame (which
// end where a frame's results are written, so they stay beside them).
// Included by biss_master.p.

// ============================================================================
// After the last bit. MA is high: the clocks ran out before the last reads.
// Nothing below is clocked.

// The last slave's last one or two bits, when its switch read the bit
// before them (CFG_SHAPE). That switch's R31 snapshot (r2, shifted to
// put its sample at bit 31) holds them 8 and 16 samples newer, at bits 23
// and 15 (indices 8 (LAG - 1) + s and 8 (LAG - 2) + s: sampled, and the
// same samples as reads one and two periods later would take at 8 LAG + s,
// 16 shift edges falling in every 2 periods). The switch has stored the
// slave's result in its slot, moved r0.b0 to the next one and loaded the
// end record. Not clocked: this
// comes at t = 0 of the period after the switch, whose MA edge (the CDM,
// if the line delay is under two periods: m = 1) is made here; otherwise
// r11.b0 = 0, and SWITCH_SHORT may have cut the switch short.
FINAL_PLAIN2:
    MA_FALL
    lsl     r2, r2, 8
    SHIFT_IN
FINAL_PLAIN:
    lsl     r2, r2, 8
    SHIFT_IN
    sub     r0.b0, r0.b0, r0.b1             // the last slave's slot
    xout    XFR_BANK, r4, 12
    qba     FRAME_END
FINAL_CRC2:
    MA_FALL
    ldi     r7.b0, 2
    qba     FINAL_CRC_GO
FINAL_CRC:
    ldi     r7.b0, 1
FINAL_CRC_GO:
    sub     r0.b0, r0.b0, r0.b1             // the last slave's slot:
    xin     XFR_BANK, r6, 4                       // its CRC register
    sub     r1.b0, r1.b0, 12                // the last slave's polynomial
    mviw    r8.w2, *r1.b0++
FINAL_CRC_BIT:
    lsl     r2, r2, 8
    CRC_STEP
    sub     r7.b0, r7.b0, 1
    qbne    FINAL_CRC_BIT, r7.b0, 0
    xout    XFR_BANK, r6, 4

FRAME_END:
    jal     r0.w0, CD_COMMIT               // r1.b1 = CDS; r1.b0 = the CDM sent
    jal     r3.w0, BUF_STAMP               // r2 = the result buffer, r0.w0 = 0:
    lbco    r0.b1, c28, P_RUNNING, SIZE(BissPriv.running)  // slave 0's slot, and the step to the next
    sbbo    r1.b0, r2, BISS_R_CDM, 1
    lbco    r1.b0, c28, P_NSLAVES, SIZE(BissPriv.nslaves)  // slaves to check
    rsb     r3, SAMPLE_SHIFT, 31 - 8 * LAG  // sample point 0..7 within the bit
    sbbo    r3.b0, r2, BISS_R_SAMPLE_POINT, 1
    sbbo    r1.b1, r2, BISS_R_CDS, 1
    ldi     RES_FLAGS, BISS_RF_VALID        // frame flags
    add     r3, r2, BISS_R_SLAVE0           // slave result
    mov     r11, BISS_PRIV + P_SLAVES       // slave check data
FE_SLAVE:
    xin     XFR_BANK, r4, 12                      // data lo, data hi, CRC register: its slot
    add     r0.b0, r0.b0, r0.b1             // the next slave's
    lbbo    r7, r11, 0, SIZE(BissSlave)     // mask lo, mask hi, residue, [n, w, ew, flags]
    and     r4, r4, r7
    and     r5, r5, r8
    ldi     r7, BISS_RS_CRC_OK              // slave status (r4..r7: the slave's result)
    qbeq    FE_CRC_DONE, r10.b1, 0          // no CRC
    qbeq    FE_CRC_DONE, r6, r9
    ldi     r7, 0
    or      RES_FLAGS, RES_FLAGS, BISS_RF_CRC_ERROR
FE_CRC_DONE:
    qbbc    FE_EW_DONE, r10.b3, 0           // no nE/nW
    // nW (data bit ew) to r8 bit 0, nE (bit ew + 1) to bit 1
    lsr     r8, r5, r10.b2                  // 32 <= ew: the shift uses ew & 31
    qble    FE_EW_GOT, r10.b2, 32
    lsr     r8, r4, r10.b2
    lsl     r9, r5, 1
    qbne    FE_EW_GOT, r10.b2, 31
    or      r8, r8, r9                      // ew = 31: nE is bit 0 of the high word
FE_EW_GOT:
    qbbc    FE_NE_DONE, r8, 1
    set     r7, r7, 1                       // nE: BISS_RS_NE (0x02)
FE_NE_DONE:
    qbbc    FE_EW_DONE, r8, 0
    set     r7, r7, 2                       // nW: BISS_RS_NW (0x04)
FE_EW_DONE:
    sbbo    r4, r3, BISS_R_S_DATA_LO, 16    // data, CRC register, status
    add     r3, r3, BISS_R_SLAVE_SIZE
    add     r11, r11, SIZE(BissSlave)
    sub     r1.b0, r1.b0, 1
    qbne    FE_SLAVE, r1.b0, 0
    // frame counters
    qbbc    FE_NO_CRC_ERR, RES_FLAGS, 1
    lbco    r3, c24, BISS_ST_CRC_ERRORS, 4
    add     r3, r3, 1
    sbco    r3, c24, BISS_ST_CRC_ERRORS, 4
FE_NO_CRC_ERR:
    // line delay: this frame's ACK position and the average it was read with
    lbco    r4, c28, P_HIST, P_HALF - P_HIST  // r4 r5 history, r6 its sum, r8 P_NSLAVES
    add     r3, r6, r1.w2
    lsr     r3, r3, 2                       // Qf'
    sbbo    r1.w2, r2, BISS_R_DELAY_RAW, 2
    sbbo    r3.w0, r2, BISS_R_DELAY_AVG, 2
    add     r6, r3, 8 * LAG - 4             // m + LAG = (Qf' - 4) / 8 + LAG (SAMPLE_POINT)
    lsr     r6, r6, 3                       // (Qf' >= 8: every Q' is)
    sbbo    r6.b0, r2, BISS_R_LAG_PERIODS, 1
    // History. An ACK more than half a bit from the average it was read
    // with means this frame's bits were read at the wrong place (a glitch
    // in WAIT_ACK, or an average spoilt by one) or the line changed: the
    // frame is not valid, whatever its CRC says. One such ACK is left out of
    // the average; a second in a row starts the average afresh from it.
    // P_NSLAVES bit 31 (r8 here) remembers the first.
    sub     r6, r1.w2, r3                   // Q' - Qf' + 4 in 0..8: no jump
    add     r6, r6, 4
    qblt    FE_ACK_JUMP, r6, 8
    clr     r8, r8, 31
    mov     r5.w0, r4.w2                    // h2 = h1
    mov     r4.w2, r4.w0                    // h1 = h0
    mov     r4.w0, r1.w2                    // h0 = Q'
    qble    FE_HIST_SAVE, r8.b3, 3          // 3 <= frames in the average: full
    add     r8.b3, r8.b3, 1
    qba     FE_HIST_SAVE
FE_ACK_JUMP:
    xor     RES_FLAGS, RES_FLAGS, BISS_RF_VALID | BISS_RF_ACK_JUMP  // VALID set since FRAME_END,
                                            // ACK_JUMP not: one clear, one set
    qbbs    FE_HIST_RESET, r8, 31           // the second in a row
    set     r8, r8, 31
    qba     FE_NO_SMA                       // the history stays as it was
FE_HIST_RESET:
    mov     r4.w0, r1.w2
    mov     r4.w2, r1.w2
    mov     r5.w0, r1.w2
    ldi     r8.b3, 0
FE_HIST_SAVE:
    qbgt    FE_NO_SMA, r8.b3, 3
    or      RES_FLAGS, RES_FLAGS, BISS_RF_SMA
FE_NO_SMA:
    sbco    r8, c28, P_NSLAVES, P_HALF - P_NSLAVES
    jal     r0.w0, HIST_SAVE
    jal     r0.w0, PUBLISH                 // and CD_PREPARE: the next frame's CDM
    // The next frame, when it is a free-run BiSS-C one with no training due,
    // is set up now, while the slave's timeout runs: all MAIN and FRAME look
    // at changes only with a configuration, so once SL is high only a new
    // one is checked for (MAIN applies it), and the frame starts at once.
    // (No training can be due here: only a refused configuration or a
    // missing slave asks for one, and both go through MAIN.)
    lbco    r3, c28, P_NSLAVES, P_HALF - P_NSLAVES
    qbne    FE_SLOW, r3.b1, BISS_TRIG_FREERUN
    lbco    r3, c28, P_SSI, SIZE(BissPriv.ssi_ack)
    qbne    FE_SLOW, r3.w0, 0
    jal     RET_SUB, FRAME_REGS
    jal     RET_SUB, SLAVE_IDLE             // the slave's timeout has ended: SL high,
    qbeq    FE_MAIN, r3, 0                  // or not in time: MAIN and FRAME find it so again
FE_IDLE_YES:
    lbco    r2, c24, BISS_CFG_SEQ, 4        // (loaded before MA may rise: no data-RAM
    lbco    r3, c24, BISS_ST_CFG_ACK, 4     // access between that edge and the frame's)
    set     r30, r30, MA_BIT                // CDM done: MA idles high
    qbne    FE_MAIN, r2, r3                 // a new configuration: MAIN applies it
    jmp     FRAME_STAMPED
FE_SLOW:
    jal     RET_SUB, SLAVE_IDLE             // the slave's timeout ends: SL high
FE_MAIN:
    set     r30, r30, MA_BIT                // CDM done: MA idles high
    jmp     MAIN

// History r4.w0, r4.w2, r5.w0 and its sum + 2 (rounding) to P_HIST/P_HSUM;
// HIST_FILL: all three r1.w2 (a history started afresh from one position).
HIST_FILL:
    mov     r4.w0, r1.w2
    mov     r4.w2, r1.w2
    mov     r5.w0, r1.w2
HIST_SAVE:
    sbco    r4, c28, P_HIST, OFFSET(BissPriv.k) - P_HIST
    add     r3, r4.w0, r4.w2
    add     r3, r3, r5.w0
    add     r3, r3, 2
    sbco    r3, c28, P_HSUM, SIZE(BissPriv.hsum)
    jmp     r0.w0

// Publish the result buffer r2 with the flags in r12: header words, then
// the sequence number (its low bit names the buffer), then the next buffer.
// Every publication is followed by CD_PREPARE (the next frame's CDM): it
// goes on there, and returns through r0.w0 from it.
PUBLISH:
    lbco    r3, c24, BISS_ST_FRAMES, 4
    add     r3, r3, 1
    sbco    r3, c24, BISS_ST_FRAMES, 4
    sbbo    r3, r2, BISS_R_FRAME, 4
    sbbo    RES_FLAGS, r2, BISS_R_FLAGS, 4
    lbco    r4, c28, P_BUF, P_PROC - P_BUF  // r4 P_BUF, r5 P_NSLAVES, r6 P_HALF
    sbbo    r5.b0, r2, BISS_R_NSLAVES, 1
    sbbo    r6.w0, r2, BISS_R_HALF, 2
    sbco    r4, c24, BISS_ST_BUF, 4
    lbco    r3, c24, BISS_ST_SEQ, 4
    add     r3, r3, 1                       // odd seq: buffer 1, even: buffer 0
    sbco    r3, c24, BISS_ST_SEQ, 4
    xor     r4, r4, 1
    sbco    r4, c28, P_BUF, SIZE(BissPriv.buf)
    ldi     r3, BISS_STATE_RUNNING
    sbco    r3, c24, BISS_ST_STATE, 4
    jmp     CD_PREPARE                      // which returns through r0.w0

// Wait for SL high: the slave's timeout has ended. High means the newest
// 4 samples (IDLE_MASK, half an MA period) are all 1, not just the newest:
// a glitch on SL during the timeout must not start a frame while the slave
// still ignores MA (it would misframe this frame and the next two). Half
// a period keeps the master's overhead low at 1 MHz and still outlasts a
// glitch of two samples (25 ns at 10 MHz). At most IDLE_TURNS turns of 4
// cycles; r3 = 0 if SL did not come high (the turns left if it did). r2
// is scratch. Returns through r12.w0: free before a frame (FRAME_STAMPED
// and TRAIN_GO set r12). A free-run frame waits here after FRAME_REGS
// (FE_IDLE_YES): of what that sets up, r2, r3 and r12 are not used.
SLAVE_IDLE:
    mov     r3, IDLE_TURNS
SLAVE_IDLE_POLL:
    and     r2.b0, r31.b0, IDLE_MASK
    qbeq    SLAVE_IDLE_YES, r2.b0, IDLE_MASK
    sub     r3, r3, 1
    qbne    SLAVE_IDLE_POLL, r3, 0
SLAVE_IDLE_YES:
    jmp     RET_SUB

// r2 = the result buffer being filled, with the frame's timestamp (bank
// register 2, FRAME_STAMP) and busy clocks (r0.w2, START_WAIT) stored in it: the
// clocked part stores nothing. r0.w0 = 0 after (no XFR shift), r5 = r2.
// Returns through r3.w0.
BUF_STAMP:
    ldi     r0.w0, 0
    xin     XFR_BANK, r2, 4
    RESULT_BASE r5
    sbbo    r2, r5, BISS_R_TIMESTAMP, 4
    sbbo    r0.w2, r5, BISS_R_PROC_CLOCKS, 2
    mov     r2, r5
    jmp     r3.w0

// ---- frames that end early ---------------------------------------------------
// No slave: the line delay is measured again once one answers (a slave
// may come back on another cable, or in the middle of a frame).
NO_SLAVE_IDLE:                              // SL low before a frame:
    ldi     r0, 0                           // no busy clocks (BUF_STAMP)
NO_ACK:                                     // after a rising edge: MA stays high
    ldi     RES_FLAGS, BISS_RF_NO_SLAVE
NO_SLAVE_FLAGS:                             // (SL_INIT_DONE: r12 its own flags)
    ldi     r2, 1
    sbco    r2.b0, c28, P_TRAIN_DUE, SIZE(BissPriv.train_due)  // training due
    ldi     r3, BISS_ST_NO_SLAVE

// r12 = flags, r3 = the counter to increment; publish, wait for the slave.
ABORT_FRAME:
    jal     r0.w0, CD_ABORT
    lbbo    r4, r3, 0, 4
    add     r4, r4, 1
    sbbo    r4, r3, 0, 4
    jal     r3.w0, BUF_STAMP               // r2 = the result buffer
    jal     r0.w0, PUBLISH                 // and CD_PREPARE
    jmp     FE_SLOW                         // wait for the slave, MA high, MAIN

// The ACK came but the start bit did not: this frame's ACK position is a
// measurement all the same, and the average starts afresh from it (an
// average gone wrong would make every frame miss its start bit).
PROC_ERROR:                                 // after a rising edge: MA stays high
    jal     r0.w0, HIST_FILL
    ldi     RES_FLAGS, BISS_RF_PROC_ERROR
    ldi     r3, BISS_ST_PROC_ERRORS
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
    qbne    TRAIN_GO, r3, 0
SL_INIT:                                    // SL stuck low: INIT first (see SL_INIT_DONE)
    ldi     r2, 2                           // training due, as the INIT
    sbco    r2.b0, c28, P_TRAIN_DUE, SIZE(BissPriv.train_due)
TRAIN_GO:
    jal     RET_SUB, FRAME_REGS
    ldi     MA_EDGES, 2 * MA_MASK           // one clock after period 0's
    jmp     FRAME_CLOCKED
TRAIN_DONE:
    lbco    r2.b0, c28, P_TRAIN_DUE, SIZE(BissPriv.train_due)
    qbne    SL_INIT_DONE, r2.b0, 1          // it was the INIT of a low SL
    jal     r0.w0, HIST_FILL                // r4.w0, r4.w2 = Q' too
    jal     r3.w0, BUF_STAMP               // r2 = the result buffer (r4 kept)
    sbbo    r4, r2, BISS_R_DELAY_RAW, 4     // and DELAY_AVG
    sbco    r0.b0, c28, P_TRAIN_DUE, SIZE(BissPriv.train_due)  // training done (r0.w0 = 0: BUF_STAMP)
    sbco    r0.b0, c28, P_NAVG, SIZE(BissPriv.navg)  // the average starts at this frame
    ldi     RES_FLAGS, BISS_RF_TRAINING
    ldi     r3, BISS_ST_TRAINING
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
    ldi     RES_FLAGS, BISS_RF_NO_SLAVE | BISS_RF_SL_INIT
    qba     NO_SLAVE_FLAGS
