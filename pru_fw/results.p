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
// results in the scratch pad, the idle turns in bank register 1 and the
// count base in bank register 2: period 0, FRAME_STAMP), the result slot
// and flags, and each routine's own.
.enter results
.assign Byte, r0.b0, r0.b0, Slot            // the XFR shift: the slot FE_SLAVE reads
.assign Byte, r0.b1, r0.b1, SlotStep        // the step to the next slot (P_RUNNING)
.assign Half, r0.w2, r0.w2, Busy            // the busy clocks (START_WAIT)
.assign Word, r0, r0, SlotWord              // all three: 0 for a frame that did not start
.assign Word, r1, r1, FrameR1               // r1 as the frame leaves it:
.assign Byte, r1.b0, r1.b0, CdmSent         //   the CDM this frame sent (CD_COMMIT)
.assign Byte, r1.b1, r1.b1, Cds             //   the CDS bit (CDS_PERIOD)
.assign Half, r1.w2, r1.w2, AckPos          //   this frame's ACK position Q' (ONES_B)
.assign Word, r1, r1, StampTurns            // bank register 1: the idle turns left (w2)
.assign Half, r1.w2, r1.w2, TurnsLeft       //   when the frame started (FE_POLL; 0 else)
.assign BissSlave, r1, r4, Chk              // FE_SLAVE: the slave's check data (layout.hp)
.assign Word, r2, r2, Stamp                 // bank register 2: the count base, then the
                                            // timestamp (IEP COUNT at the first MA edge)
.assign Word, r2, r2, EwBits                // FE_SLAVE: nW at bit 0, nE at bit 1
.assign Word, r2, r2, ResBuf                // the result slot being filled (BUF_STAMP)
.assign Byte, r2.b0, r2.b0, Due             // P_TRAIN_DUE: 1 a training, 2 the INIT of a low SL
.assign Word, r2, r2, DueWord               //   as a word, to set it
.assign Byte, r2.b0, r2.b0, Idle8           // SLAVE_IDLE: SL's newest samples
.assign Half, r6.w0, r6.w0, DelayRaw        // FRAME_END: the slot's BISS_R_DELAY_RAW .. LAG_PERIODS
                                            //   from r6 and r7.w0 (one store): Q',
.assign Half, r6.w2, r6.w2, Qf              //   Qf', the average the frame was read with,
.assign Byte, r7.b0, r7.b0, SampPt          //   the sample point 0..7,
.assign Byte, r7.b1, r7.b1, LagPer          //   and m + LAG
.assign Word, r3, r3, CrcErrors             // BISS_ST_CRC_ERRORS
.assign Word, r3, r3, OffGridFrames         // BISS_ST_OFF_GRID
.assign Word, r3, r3, Seq                   // PUBLISH: BISS_ST_SEQ, this publication's number
.assign Word, r3, r3, TallyAddr             // ABORT_FRAME: the status counter to count in,
.assign Word, r4, r4, TallyVal              //   its value
.assign Half, r5.w0, r5.w0, RingStride      // PUBLISH: ST_RING_STRIDE,
.assign Half, r5.w2, r5.w2, RingLast        //   ST_RING_LAST,
.assign Word, r6, r6, RingNext              //   the slot filled next (ST_RING_NEXT)
.assign Word, r4, r4, PubNs                 // PUBLISH: P_NSLAVES' word (slaves: b0),
.assign Byte, r4.b0, r4.b0, PubSlaves
.assign Half, r5.w0, r5.w0, PubHalf         //   and H (P_HALF)
.assign Word, r4, r4, DataLo                // FE_SLAVE: a slave's result from its slot (data,
.assign Word, r5, r5, DataHi                //   CRC register), then stored with its status
.assign Word, r6, r6, Crc
.assign Half, r6.w2, r6.w2, CrcHi           //   (the CRC register's upper half: its low is 0)
.assign Word, r7, r7, Status                //   (BISS_RS_*)
.assign Word, r4, r4, Hsum                  // FRAME_END: P_HSUM, h0 + h1 + h2 + 2,
.assign Half, r4.w0, r4.w0, HsumLo
.assign Word, r5, r5, PfNs                  //   P_NSLAVES' word:
.assign Half, r4.w2, r4.w2, PfSlack         //   (P_IEP_SLACK)
.assign Byte, r5.b0, r5.b0, PfSlaves        //   the slaves,
.assign Byte, r5.b1, r5.b1, PfTrigger       //   the trigger,
.assign Byte, r5.b3, r5.b3, PfNavg          //   frames in the average (bit 7: the last ACK jumped)
.assign Word, r9, r9, BufStamp              // BUF_STAMP: the timestamp
.assign Word, r8, r8, FeTmp                 // FRAME_END: m + LAG, the CDM, the ACK jump, navg
.assign Word, r8, r8, Idx                   // FE_SLAVE: the slave's check data in C28's window
                                            // (P_SLAVES + 16 k), and its result's from Base
.assign Word, r7, r7, PrivNs                // P_NSLAVES' word; bit 31 (navg's bit 7): the last
                                            // ACK jumped
.assign Byte, r10.b0, r10.b0, Shift         // the frame's sample shift (SAMPLE_POINT), until
.assign Word, r10, r10, Base                //   FRAME_END's Base: the result slot less RES_BIAS
.assign Word, r11, r11, Kept                // FRAME_END: r1 kept for after (CD_COMMIT's r1):
.assign Byte, r11.b0, r11.b0, KeptCdm       //   the CDM sent (in the RecPtr byte),
.assign Byte, r11.b1, r11.b1, KeptCds       //   the CDS bit,
.assign Half, r11.w2, r11.w2, KeptAck       //   the ACK position
.assign Byte, r9.b0, r9.b0, SlavesLeft      // FE_SLAVE's count (BufStamp's, once stored)
.assign Word, r3, r3, IepEnd                // FRAME_END: the count at its end, to bank
                                            // register 3 (IEP_START); 0 after an overrun
.assign Word, r12, r12, ResFlags            // the result's flags, BISS_RF_*
.assign Byte, r11.b3, r11.b3, GridSeen      // the clocked part's GridMarks (until Kept)
.assign Half, r11.w0, r11.w0, HoldLeft      // MA_HOLD: turns of 2 cycles left
.assign PrivRun, r3, r9, Priv               // FRAME_REGS' burst: the history (r4..r6), P_NSLAVES (r7)
.assign Half, r10.w0, r10.w0, FeSsi         //   and after it P_SSI's ACK position (0: BiSS-C),
.assign Word, r11, r11, FeCfgAck            //   P_CFG_ACK
.assign Byte, r10.b2, r10.b2, FeTrigger     // the trigger, past FRAME_REGS_SET

// ---- after the last bit: publication first --------------------------------
// The result slot being filled is the one ST_RING_NEXT names (BUF_STAMP);
// Base points RES_BIAS below it, so that one index (Idx) walks the slaves'
// check data in the private RAM (C28 + P_SLAVES + 16 k) and their results
// in the slot (Base + Idx = BISS_R_SLAVE0 + 16 k), and the header is at
// Base + RES_BIAS. Everything the slot gets is stored before ST_BUF and
// ST_SEQ; the history, the counters and control communication come after
// (POST).
#define RES_BIAS        (P_SLAVES - BISS_R_SLAVE0)
FRAME_END:
    ldi     ResFlags, BISS_RF_VALID
    qbne    FE_OFF_GRID, GridSeen, 0        // a bit's samples disagreed (GRID_CHECK)
FE_ON_GRID:
    mov     Kept, FrameR1                   // Cds and AckPos, for after
    jal     RET_STAMP, BUF_STAMP            // ResBuf; the timestamp, the busy clocks
    rsb     SampPt, Shift, 31 - 8 * LAG     // sample point 0..7 within the bit
    lbco    &Hsum, c28, P_HSUM, P_HALF - P_HSUM // hsum, P_NSLAVES' word
    sub     Base, ResBuf, RES_BIAS
    add     Qf, KeptAck, HsumLo
    lsr     Qf, Qf, 2                       // Qf' (Hsum: + 2, rounding)
    add     FeTmp, Qf, 8 * LAG - 4
    lsr     LagPer, FeTmp, 3                // m + LAG = (Qf' - 4) / 8 + LAG (SAMPLE_POINT)
    sbbo    KeptCds, ResBuf, BISS_R_CDS, 1
    mov     DelayRaw, KeptAck
    sbbo    &DelayRaw, ResBuf, BISS_R_DELAY_RAW, BISS_R_HALF - BISS_R_DELAY_RAW // and AVG, SP, LAG
    lsr     KeptCdm, MA_OUT.b0, MA_BIT      // MA is low after a CDM of 1 (only MA_BIT is
    xor     KeptCdm, KeptCdm, 1             // ever set in R30)
    sbbo    KeptCdm, ResBuf, BISS_R_CDM, 1
    // An ACK more than half a bit from the average it was read with means
    // this frame's bits were read at the wrong place (a glitch in WAIT_ACK,
    // or an average spoilt by one) or the line changed: the frame is not
    // valid, whatever its CRC says (the history, after the publication,
    // leaves it out). SMA: the average is full with this frame.
    sub     FeTmp, KeptAck, Qf
    add     FeTmp, FeTmp, 4
    qbge    FE_NO_JUMP, FeTmp, 8            // Q' - Qf' + 4 in 0..8: no jump
    clr     ResFlags, ResFlags, 0           // BISS_RF_VALID
    set     ResFlags, ResFlags, 6           // BISS_RF_ACK_JUMP
    qba     FE_FLAGS
FE_NO_JUMP:
    qbbc    FE_FLAGS, PfNavg, 1             // 2 or 3 (at most) before: 3 with this one
    or      ResFlags, ResFlags, BISS_RF_SMA
FE_FLAGS:
    // IEP: BISS_RF_IEP_LATE for a frame not started on its count (its
    // timestamp not IEP_ALIGN - 4: IEP_START) or one that ran into the next
    // period (its end count below its start, or its clocked part possibly a
    // period or longer: max(m + LAG, p) + busy MA periods at least
    // P_IEP_SLACK, IEP_PERIOD); for IEP_START the count now, or 0 after an
    // overrun (the next frame in the next period after this one's end).
    qbbc    FE_IEP_DONE, PfTrigger, 0       // BISS_TRIG_IEP (1), IEP_FOLLOW (3)
    qbeq    FE_IEP_ON_TIME, BufStamp, IEP_ALIGN - 4
    or      ResFlags, ResFlags, BISS_RF_IEP_LATE
    mov     FeTmp, ResBuf                   // bank register 2 back to the timestamp of a
    ldi     Stamp, IEP_ALIGN - 4            // frame on its count (FRAME_STAMP wrote this
    xout    XFR_BANK, Stamp, 4              // one's; BUF_STAMP has read it): IEP_START
    mov     ResBuf, FeTmp                   // from FE takes it as it is
FE_IEP_ON_TIME:
    lsr     FeTmp, KeptAck, 3               // p
    max     FeTmp, FeTmp, LagPer
    add     FeTmp, FeTmp, Busy
    lbco    IepEnd, c26, IEP_COUNT, 4
    qble    FE_IEP_OVER, FeTmp, PfSlack
    qble    FE_IEP_END, IepEnd, BufStamp    // still in its period
FE_IEP_OVER:
    or      ResFlags, ResFlags, BISS_RF_IEP_LATE
    ldi     IepEnd, 0
FE_IEP_END:
    xout    XFR_BANK, IepEnd, 4             // bank register 3 (Slot = 0: BUF_STAMP)
FE_IEP_DONE:
    mov     SlavesLeft, PfSlaves
    ldi     Idx, P_SLAVES
// Each slave: its result from its slot (data, CRC register), masked; the
// status: the CRC register against the residue, nE and nW from the data
// word (the MVI pointer and shift of its check data, config.p).
FE_SLAVE:
    xin     XFR_BANK, DataLo, 12            // data lo, data hi, CRC register: its slot
    add     Slot, Slot, SlotStep            // the next slave's
    lbco    &Chk, c28, Idx, OFFSET(BissSlave.spare) // pointer, shift, residue, masks
    and     DataLo, DataLo, Chk.mask_lo
    and     DataHi, DataHi, Chk.mask_hi
    ldi     Status, BISS_RS_CRC_OK
    qbeq    FE_CRC_OK, CrcHi, Chk.residue
    ldi     Status, 0
    or      ResFlags, ResFlags, BISS_RF_CRC_ERROR
FE_CRC_OK:
    mvid    EwBits, *Chk.ewptr
    lsr     EwBits, EwBits, Chk.ewshift     // nW at bit 0, nE at bit 1
    qbbc    FE_NW_DONE, EwBits, 0
    set     Status, Status, 2               // nW: BISS_RS_NW (0x04)
FE_NW_DONE:
    qbbc    FE_EW_DONE, EwBits, 1
    set     Status, Status, 1               // nE: BISS_RS_NE (0x02)
FE_EW_DONE:
    sbbo    DataLo, Base, Idx, BISS_R_SLAVE_SIZE // data, CRC register, status
    add     Idx, Idx, SIZE(BissSlave)
    sub     SlavesLeft, SlavesLeft, 1
    qbne    FE_SLAVE, SlavesLeft, 0
    add     ResBuf, Base, RES_BIAS
    jal     RET_POST, PUBLISH

// ---- after the publication: counters, control communication, history,
// then the next frame --------------------------------------------------------
    qbbc    FE_NO_CRC_ERR, ResFlags, 1
    lbco    CrcErrors, c24, BISS_ST_CRC_ERRORS, 4
    add     CrcErrors, CrcErrors, 1
    sbco    CrcErrors, c24, BISS_ST_CRC_ERRORS, 4
FE_NO_CRC_ERR:
    mov     FrameR1, Kept                   // the CDM sent, Cds, AckPos
    jal     RET_POST, CD_COMMIT             // Cds in; and CD_PREPARE: the next frame's CDM
    // The history and the next frame's set-up from one burst (FRAME_REGS'
    // Priv, with P_SSI and P_CFG_ACK after it). A jump (FRAME_END) is left
    // out of the average; a second in a row starts the average afresh from
    // it; P_NSLAVES bit 31 (PrivNs) remembers the first.
    lbco    &Priv.delays, c28, P_DELAYS, P_CFG_ACK + 4 - P_DELAYS
    qbbs    FE_ACK_JUMP, ResFlags, 6        // BISS_RF_ACK_JUMP
    clr     PrivNs, PrivNs, 31
    mov     Priv.h2, Priv.h1                // h2 = h1
    mov     Priv.h1, Priv.h0                // h1 = h0
    mov     Priv.h0, AckPos                 // h0 = Q'
    qble    FE_HIST_SAVE, Priv.navg, 3      // 3 <= frames in the average: full
    add     Priv.navg, Priv.navg, 1
FE_HIST_SAVE:
    jal     RET_POST, HIST_SAVE             // (Priv.hsum the new sum)
FE_HIST_KEPT:
    sbco    PrivNs, c28, P_NSLAVES, P_HALF - P_NSLAVES
    // The next frame, when it is a free-run or IEP BiSS-C one (no training
    // can be due: only a refused configuration or a missing slave asks for
    // one, and both go through MAIN), the configuration unchanged and MA
    // high (CDM 0), is set up now, while the slave's timeout runs, and
    // starts when SL shows the timeout's end (FE_START), or on its count
    // after that (IEP_START).
    qbne    FE_SLOW, FeSsi, 0               // SSI: MAIN's FRAME
    qbbc    FE_SLOW, MA_OUT, MA_BIT         // CDM 1: MA is raised when SL is high, then held
.using main_loop
    lbco    CfgSeq, c24, BISS_CFG_SEQ, 4
    qbne    FE_SLOW, CfgSeq, FeCfgAck       // a new configuration: MAIN applies it
.leave main_loop
    qbeq    FE_SLOW, Priv.trigger, BISS_TRIG_HOST
    mov     FeTrigger, Priv.trigger         // (FRAME_REGS_SET keeps r10 but not Priv)
    jal     RET_SUB, FRAME_REGS_SET
.using clocked
    fill    &Edges, 4                       // all ones while the start bit is awaited
.leave clocked
    qbbs    IEP_START, FeTrigger, 0         // BISS_TRIG_IEP (1), IEP_FOLLOW (3): its count

// The free-run frame's start: everything set up, the count base of the
// timestamp in bank register 2 (BUF_STAMP), then the poll for SL high
// (SLAVE_IDLE's test, at most FE_TURNS turns of 4 cycles) whose exit is
// period 0 itself: its MA fall comes 2 cycles after the R31 read that saw
// the slave's timeout end. Period 0 puts the turns left in bank register 1,
// so the timestamp is the base less 4 cycles a turn left; the base is the
// count read here, plus the cycles from that read to the fall had the
// first turn seen SL high (less FRAME_STAMP's 4: its read comes 4 cycles
// before the fall), plus 4 FE_TURNS.
#define FE_BASE         4                   // (6 cycles from the read to FE_POLL, less 2; and
                                            // 4 FE_TURNS added to the upper half)
.using fe_start
FE_START:
    ldi     FastLeft, FE_TURNS
    lbco    FastBase, c26, IEP_COUNT, 4
    add     FastBase, FastBase, FE_BASE
    add     FastBaseHi, FastBaseHi, 4 * FE_TURNS >> 16
    xout    XFR_BANK, FastBase, 4           // bank register 2
FE_POLL:
    and     FastIdle8, SL_IN.b0, IDLE_MASK
    qbeq    FRAME_PERIOD0, FastIdle8, IDLE_MASK
    sub     FastLeft, FastLeft, 1
    qbne    FE_POLL, FastLeft, 0
    jmp     MAIN                            // SL never came high: MAIN's FRAME finds it so
.leave fe_start

// ---- IEP frames (the owner's and a follower's alike) --------------------------
// Every IEP-triggered frame's period 0 starts when the count is IEP_ALIGN
// after its IEP period began (the count reset to 0), with no data-RAM
// access from the count's read to it: the loads that stall while the host
// reads the data RAM (docs/silicon-assumptions.md A5) all come before. The
// count is read once, here; then SL is polled (SLAVE_IDLE's test: register
// instructions only, 4 cycles a turn, each taking 4 off the wait), so when
// SL is high the count is known to the cycle and the rest is an exact wait
// (2 + d cycles from IEP_HIGH's test to period 0, for d). The period is the
// one after the last frame's end: its count then (IepEnd, bank register 3: FRAME_END) above the count now
// means a period began since, and the frame is due at this period's
// IEP_ALIGN; otherwise at the next period's (IepEnd = 0, after an overrun
// or an aborted frame: the next period's). The frame waits in the period
// it is for; one that cannot make its count (SL high after it) starts at
// once through FRAME_STAMP (IEP_LATE), its timestamp then not IEP_ALIGN -
// 4, and FRAME_END flags it. Entered with the frame set up (FRAME_REGS,
// Edges; SSI_FRAME's loads), IepTarget its period 0 (FRAME_PERIOD0, or
// SSI_STAMPED: after FRAME_STAMP). P_IEP_KEY not CMP0: the owner's period
// is new, and IEP_PERIOD works out its thresholds first (then MAIN).
#define IEP_BUDGET      3                   // the late poll's budget past the wait: about
                                            // 3 x 0x10000 cycles, 983 us: more than
                                            // SLAVE_IDLE's, so a frame the slow path
                                            // (FE_SLOW) made late by up to that still
                                            // comes through IEP_LATE
.using iep_start
IEP_START_SLOW:                             // MAIN's frames (FRAME_SET, SSI_FRAME):
    ldi     IepStamp, IEP_ALIGN - 4         // bank register 2: the timestamp of a frame on
    xout    XFR_BANK, IepStamp, 4           // its count (FRAME_STAMP's read comes 4 before)
IEP_START:                                  // FE: bank register 2 holds it still (an IEP
                                            // frame on its count leaves it, FE_IEP puts it
                                            // back after any other)
    xin     XFR_BANK, IepEnd, 4             // bank register 3 (Slot = 0: FRAME_REGS_SET)
    lbco    IepKey, c28, P_IEP_KEY, 4
    lbco    IepP, c26, IEP_CMP0, 4          // P - 1
    lbco    IepCnt, c26, IEP_COUNT, 4       // (the last read: from here the cycles count)
    qbne    IEP_PERIOD, IepP, IepKey        // a new period: its thresholds first
    rsb     IepD, IepCnt, IEP_D0            // to this period's IEP_ALIGN, had SL been
    qbgt    IEP_POLL, IepCnt, IepEnd        // high at the read, if a period began since the
    add     IepD, IepD, IepP                // last frame's end; else the next period's (P:
                                            // IEP_D0 has the 1)
IEP_POLL:                                   // SLAVE_IDLE's test, 4 cycles a turn, to the
    and     IepIdle8, SL_IN.b0, IDLE_MASK   // count: d = IepD when SL is high
    qbeq    IEP_HIGH, IepIdle8, IDLE_MASK
    sub     IepD, IepD, 4
    qbbc    IEP_POLL, IepD, 31
    ldi     IepDHi, IEP_BUDGET - 1          // past the count: late, if SL comes high within
IEP_LATE_POLL:                              // the budget (IepD is -1..-4: its upper half
    and     IepIdle8, SL_IN.b0, IDLE_MASK   // all ones)
    qbeq    IEP_LATE, IepIdle8, IDLE_MASK
    sub     IepD, IepD, 4
    qbbc    IEP_LATE_POLL, IepD, 31
    jmp     MAIN                            // SL never came high: MAIN's FRAME finds it so
IEP_HIGH:
    qbbs    IEP_LATE, IepD, 31              // past the count at the read
    qbbc    IEP_EVEN, IepD, 0               // 2 + d cycles for every d, from single-cycle
    sub     IepD, IepD, 1                   // instructions only (no LOOP of one instruction,
IEP_EVEN:                                   // no count of 0: docs/silicon-assumptions.md)
    qbeq    IEP_AT, IepD, 0
IEP_TURN:
    sub     IepD, IepD, 2                   // 2 cycles a turn
    qbne    IEP_TURN, IepD, 0
IEP_AT:
    jmp     IepTarget
IEP_LATE:                                   // at once, timestamped as any frame
    sub     IepLate, IepTarget, STAMP_WORDS
    jmp     IepLate                         // FRAME_STAMP, then period 0
.leave iep_start

// An edge off the bit grid (FRAME_END): not valid, and counted here,
// before the publication, so that frames on the grid pay only FRAME_END's
// test, whose cycle CD_PREPARE's PAD gave up (the path after a frame is as
// long as before the check).
FE_OFF_GRID:
    ldi     ResFlags, BISS_RF_OFF_GRID
    lbco    OffGridFrames, c24, BISS_ST_OFF_GRID, 4
    add     OffGridFrames, OffGridFrames, 1
    sbco    OffGridFrames, c24, BISS_ST_OFF_GRID, 4
    qba     FE_ON_GRID
FE_ACK_JUMP:
    qbbs    FE_HIST_RESET, PrivNs, 31       // the second in a row
    set     PrivNs, PrivNs, 31
    qba     FE_HIST_KEPT                    // the history stays as it was
FE_SLOW:
    jal     RET_SUB, SLAVE_IDLE             // the slave's timeout ends: SL high
// MA high for at least a half period before any frame's first falling edge:
// iC-MB4 gives each MA phase half the period, and after its trigger half a
// period before the first fall (datasheet I302/I303, GETSENS); after a
// CDM of 1 MA rises only here, when the slave's timeout is over. Held for
// 2H cycles (turns of 2), whatever the frame before (a NO_ACK frame's last
// rise may be as recent).
    set     MA_OUT, MA_OUT, MA_BIT          // CDM done: MA idles high
    lbco    HoldLeft, c28, P_HALF, SIZE(BissPriv.half)
MA_HOLD:
    sub     HoldLeft, HoldLeft, 1
    qbne    MA_HOLD, HoldLeft, 0
    jmp     MAIN

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
    lbbo    TallyVal, TallyAddr, 0, 4
    add     TallyVal, TallyVal, 1
    sbbo    TallyVal, TallyAddr, 0, 4
    jal     RET_POST, CD_ABORT              // and CD_PREPARE
    jal     RET_STAMP, BUF_STAMP            // ResBuf = the result slot
    ldi     IepEnd, 0                       // an IEP frame next: in the next period from
    xout    XFR_BANK, IepEnd, 4             // now (bank register 3, IEP_START; Slot = 0)
    ldi     RET_POST, FE_SLOW               // PUBLISH, then wait for the slave, MA high, MAIN

// Publish the result slot ResBuf with the flags in ResFlags: the frame
// number (its publication number), the flags, the slaves and H, then
// ST_BUF (the slot) and ST_SEQ; then ST_RING_NEXT, the slot BUF_STAMP
// fills next, one stride on, back to BISS_RING0 past ST_RING_LAST (the
// geometry the configuration set: CFG_RING). Returns through RET_POST.
PUBLISH:
    lbco    Seq, c24, BISS_ST_SEQ, 4
    add     Seq, Seq, 1
    sbbo    Seq, ResBuf, BISS_R_FRAME, 4
    sbbo    ResFlags, ResBuf, BISS_R_FLAGS, 4
    lbco    &PubNs, c28, P_NSLAVES, P_HALF + SIZE(BissPriv.half) - P_NSLAVES
    sbbo    PubSlaves, ResBuf, BISS_R_NSLAVES, 1
    sbbo    PubHalf, ResBuf, BISS_R_HALF, 2
    sbco    ResBuf, c24, BISS_ST_BUF, 4
    sbco    Seq, c24, BISS_ST_SEQ, 4        // published
    sbco    Seq, c24, BISS_ST_FRAMES, 4
    lbco    &RingStride, c24, BISS_ST_RING_STRIDE, 4 // and ST_RING_LAST
    add     RingNext, ResBuf, RingStride
    qbge    PUB_NEXT, RingNext, RingLast
    ldi     RingNext, BISS_RING0
PUB_NEXT:
    sbco    RingNext, c24, BISS_ST_RING_NEXT, 4
    jmp     RET_POST

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
    sbco    Slot, c28, P_TRAIN_DUE, SIZE(BissPriv.train_due) // training done (Slot = 0: BUF_STAMP)
    sbco    Slot, c28, P_NAVG, SIZE(BissPriv.navg) // the average starts at this frame
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

// ---- subroutines of the above ----------------------------------------------
// History Priv.h0, h1, h2 and its sum + 2 (rounding) to P_HIST/P_HSUM;
// HIST_FILL: all three AckPos (a history started afresh from one position).
// FE_HIST_RESET: the second ACK jump in a row (FE_ACK_JUMP): h0 = h1 = h2
// = Q', the average afresh from this frame's, then back to FE_HIST_KEPT.
FE_HIST_RESET:
    ldi     Priv.navg, 0
    ldi     RET_POST, FE_HIST_KEPT
HIST_FILL:
    mov     Priv.h0, AckPos
    mov     Priv.h1, AckPos
    mov     Priv.h2, AckPos
HIST_SAVE:
    sbco    &Priv.h0, c28, P_HIST, OFFSET(BissPriv.k) - P_HIST
    add     Priv.hsum, Priv.h0, Priv.h1
    add     Priv.hsum, Priv.hsum, Priv.h2
    add     Priv.hsum, Priv.hsum, 2
    sbco    Priv.hsum, c28, P_HSUM, SIZE(BissPriv.hsum)
    jmp     RET_POST


// Wait for SL high: the slave's timeout has ended. High means the newest
// 4 samples (IDLE_MASK, half an MA period) are all 1, not just the newest:
// a glitch on SL during the timeout must not start a frame while the slave
// still ignores MA (it would misframe this frame and the next two). Half
// a period keeps the master's overhead low at 1 MHz and still outlasts a
// glitch of two samples (25 ns at 10 MHz). At most IDLE_TURNS turns of 4
// cycles; IDLE_LEFT = 0 if SL did not come high (the turns left if it did).
// r2.b0 is scratch (Idle8). Returns through RET_SUB. (The free-run frame's
// own poll is FE_POLL, frame.p: the same turns, with period 0 as its exit.)
SLAVE_IDLE:
    mov     IDLE_LEFT, IDLE_TURNS
SLAVE_IDLE_POLL:
    and     Idle8, SL_IN.b0, IDLE_MASK
    qbeq    SLAVE_IDLE_YES, Idle8, IDLE_MASK
    sub     IDLE_LEFT, IDLE_LEFT, 1
    qbne    SLAVE_IDLE_POLL, IDLE_LEFT, 0
SLAVE_IDLE_YES:
    jmp     RET_SUB

// ResBuf = the result slot being filled (ST_RING_NEXT: PUBLISH), with the
// frame's timestamp and busy clocks (Busy, START_WAIT) stored in it: the
// clocked part stores nothing. The timestamp is bank register 2 (the count
// base: FRAME_STAMP, or FE_START) less four cycles for each turn of FE_POLL
// that was left when the frame started (bank register 1's upper half,
// period 0; 0 after FRAME_STAMP), left in BufStamp. Slot = 0 after (no XFR
// shift). Returns through RET_STAMP.
BUF_STAMP:
    ldi     Slot, 0
    xin     XFR_BANK, &StampTurns, 8        // bank registers 1 and 2: r1, r2
    lsl     BufStamp, TurnsLeft, 2
    sub     BufStamp, Stamp, BufStamp
    lbco    ResBuf, c24, BISS_ST_RING_NEXT, 4
    sbbo    BufStamp, ResBuf, BISS_R_TIMESTAMP, 4
    sbbo    Busy, ResBuf, BISS_R_PROC_CLOCKS, 2
    jmp     RET_STAMP
.leave results
