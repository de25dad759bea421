// between.p - after the timeout, before SL goes high: the counters, the
// control frame's step (the CDM this frame brought, the CDS of the next),
// the adaptive timeout, and the next frame's data words (BUILD: the
// motion, to the scratch-pad records and to FRAME_REC); then a new
// configuration if the host wrote one; then SL high (READY, startup.p)
// exactly WORK_PAD cycles after the timeout ended, whatever the work took,
// so the slave's timeout is what the host set (config.p counts WORK_PAD
// into it). None of it is clocked: MA stands still until SL is high
// (iC-MB4 datasheet, "BiSS C Frame": after detecting the slave's timeout
// with SLO = 1 the master may change MA). Included by biss_encoder.p.

.enter between
.assign Byte, r0.b0, r0.b0, Xfr         // the XFR shift: 2 k for slave k's records
.assign Byte, r0.b1, r0.b1, Advance     // BUILD: 1 moves every slave on a frame first
.assign Byte, r0.b2, r0.b2, RecAhead    // BUILD: FRAME_REC's frame is ST_FRAMES + this
.assign SlvRun, r1, r12, Run            // a slave's data word and motion (layout.hp)
.assign Word, r1, r1, Frames            // the counters, ST_FRAMES on
.assign Word, r2, r2, Latches
.assign Word, r3, r3, CdFrames
.assign Word, r1, r1, PeriodX           // ADAPT: the period times the factor
.assign Word, r2, r2, Multiplicand      //   the period, shifted up
.assign Word, r3, r3, FactorBits        //   the factor's bits left
.assign Word, r4, r4, Timeout           //   the timeout, PRU cycles
.assign Byte, r5.b2, r5.b2, Factor      //   P_NSLAVES' word: the factor (b2)
.assign Word, r5, r5, NsWord            //   that word
.assign Word, r6, r6, TmoMinC           //   the clamps (P_TMO_MIN),
.assign Word, r7, r7, TmoMaxC           //   (the fixed timeout)
.assign Word, r8, r8, WorkPadC          //   and WORK_PAD
.assign Word, r1, r1, Pad               // the pad wait: WORK_PAD,
.assign Word, r2, r2, TmoEnd                //   CYCLE at the timeout,
.assign Word, r3, r3, Elapsed           //   CYCLE since
.assign Half, r4.w0, r4.w0, WorkMax     //   ST_WORK
.assign Word, r5, r5, PadTurns          //   the burn's turns of 2 cycles
.assign Word, r13, r13, Addr            // an address in data RAM
.assign Byte, r13.b0, r13.b0, LiveEw    // LIVE_EW of the slave (after its address is used)
.assign Word, r14, r14, OutHi           // a data word, left-aligned: the XOUT to BANK_DATA
.assign Word, r15, r15, OutLo
.assign Word, r24, r24, RunAddr         // the slave's SlvRun (LAST_PERIOD is used by then)
.assign Word, r25, r25, RecAddr         // its word in FRAME_REC
.assign Word, r29, r29, Scr             // scratch (SHL64's too)
.assign CtrlState, r1, r4, Shadow       // the control state before the step ahead,
.assign Byte, r5.b0, r5.b0, ShadowFlags //   and CTRL_FLAGS (P_SHADOW)

END_WORK:
    lbbo    Scr, CTRL_BASE, CTRL_CYCLE, 4   // the timeout's end: the pad counts from here
    ldi     Addr, P_WORK_PAD
    sbbo    Scr, Addr, OFFSET(SlvPriv.tmo_end) - OFFSET(SlvPriv.work_pad), 4
    qbbs    END_COUNTED, END_KIND, 2        // END_BUILT: PREWORK counted the frame
    jal     RET_LEAF, COUNT_FRAME
END_COUNTED:
    qbgt    END_MOTION, END_KIND, END_CDM0  // no CDM without the ACK
    // The CDM: NOT MA at the timeout (TIDEP0022 §2.1: "The CDM bit is the
    // inverted state of MA line during the BiSS time-out"); the control
    // frame takes it, and its answer is the next frame's CDS. With every
    // slave armed, a 0 changes nothing.
    and     CDM_IN, END_KIND, 1
    ldi     Addr, BISS_SLV_ST_CDM
    sbbo    CDM_IN, Addr, 0, 1
    qbbc    END_STEP, CTRL_FLAGS, CTRL_AHEAD
    // the tail took the step ahead, for the CDM MA then stood for: done
    // if it is this one (PRE_WORD and FRAME_REC's CDS are set); else the
    // state before it, and the step again
    clr     CTRL_FLAGS, CTRL_FLAGS, CTRL_AHEAD
    lsr     Scr, CTRL_FLAGS, CTRL_AHEAD_CDM
    and     Scr, Scr, 1
    qbeq    END_BUILT_DONE, Scr, CDM_IN
    ldi     Addr, P_SHADOW
    lbbo    &Shadow, Addr, 0, SIZE(CtrlState) + 4
    ldi     Addr, P_CTRL
    sbbo    &Shadow, Addr, 0, SIZE(CtrlState)
    mov     CTRL_FLAGS, ShadowFlags
END_STEP:
    qbne    END_CTRL, CDM_IN, 0
    qbbs    END_CTRL_DONE, CTRL_FLAGS, CTRL_QUIET
END_CTRL:
    jal     RET_SUB, CTRL_STEP
    lsl     PRE_WORD, CDS_OUT, 30
    set     PRE_WORD, PRE_WORD, 31          // the start bit, then the CDS
END_CTRL_DONE:
    qbbc    END_ADAPT, END_KIND, 2          // END_BUILT: the next frame's words and
    lsr     Scr, PRE_WORD, 30               // timeout are there; FRAME_REC's CDS now
    and     Scr, Scr, 1
    ldi     Addr, BISS_SLV_REC_CDS
    sbbo    Scr, Addr, 0, 1
END_BUILT_DONE:
    qba     END_CFG
END_ADAPT:
    jal     RET_SUB, ADAPT
END_MOTION:
    ldi     Advance, 0                      // latched: the next frame's values
    qbeq    END_BUILD, END_KIND, END_NONE
    ldi     Advance, 1
END_BUILD:
    ldi     RecAhead, 1
    jal     RET_SUB, BUILD
END_CFG:
    ldi     Addr, BISS_SLV_CFG_SEQ          // a new configuration?
    lbbo    Scr, Addr, 0, 4
    ldi     Addr, BISS_SLV_ST_CFG_ACK
    lbbo    Addr, Addr, 0, 4
    qbeq    END_PAD, Scr, Addr
    jmp     APPLY_CONFIG
END_PAD:
    // the work's length (ST_WORK: the longest so far), then the rest of
    // the pad, to the cycle: the cycles from the CYCLE read to the end of
    // the burn are PAD_SELF plus the burn
    ldi     Addr, P_WORK_PAD
    lbbo    &Pad, Addr, 0, 8
    lbbo    Elapsed, CTRL_BASE, CTRL_CYCLE, 4
    sub     Elapsed, Elapsed, TmoEnd
    ldi     Addr, BISS_SLV_ST_WORK
    lbbo    WorkMax, Addr, 0, 2
    qbge    END_PAD_REST, Elapsed, WorkMax  // WorkMax >= Elapsed
    sbbo    Elapsed, Addr, 0, 2
END_PAD_REST:
    lbbo    Elapsed, CTRL_BASE, CTRL_CYCLE, 4
    sub     Elapsed, Elapsed, TmoEnd
    add     Elapsed, Elapsed, PAD_SELF
    qbge    END_PAD_DONE, Pad, Elapsed      // late: no pad left
    sub     Elapsed, Pad, Elapsed           // cycles to burn: 2 a turn,
    lsr     PadTurns, Elapsed, 1            //   1 more when odd
    qbbc    END_PAD_EVEN, Elapsed, 0
    ldi     Addr, 0
END_PAD_EVEN:
    qbeq    END_PAD_DONE, PadTurns, 0
END_PAD_WAIT:
    sub     PadTurns, PadTurns, 1
    qbne    END_PAD_WAIT, PadTurns, 0
END_PAD_DONE:
    // CYCLE stops at 2^32 (about 21 s): past 2^31 it starts again from 0,
    // here where nothing measures across it (it takes a write only while
    // COUNTER_ENABLE is clear, docs/pru-facts.md §3)
    lbbo    Scr, CTRL_BASE, CTRL_CYCLE, 4
    qbbc    READY, Scr, 31
    lbbo    Scr, CTRL_BASE, CTRL_CONTROL, 4
    clr     Scr, Scr, CTRL_CTR_EN
    sbbo    Scr, CTRL_BASE, CTRL_CONTROL, 4
    ldi     Addr, 0
    sbbo    Addr, CTRL_BASE, CTRL_CYCLE, 4
    set     Scr, Scr, CTRL_CTR_EN
    sbbo    Scr, CTRL_BASE, CTRL_CONTROL, 4
    jmp     READY

// ---- PREWORK: from the tail, once MA has stood still for 3/4 of a
// period (frame.p, TAIL): ADAPT and BUILD for the next frame, and what the
// last control step left (COMMIT, ctrl.p), here rather
// than after the timeout, which then has little left to do (WORK_PAD
// holds it). Then back to the tail for the rest of the timeout: its turns
// less the ones PREWORK took (CYCLE says how many), at the level MA stood
// still at (END_KIND: END_CDM0 high, END_CDM1 low).
.enter prework
.using frame
.assign Word, r24, r24, PwLastPeriod    // (LAST_PERIOD)
.assign Word, r13, r13, PwAddr
.assign Word, r1, r1, PwRest            // P_SPARE: the turns of the timeout left, in w0 (then
                                        //   CYCLE, after the work)
.assign Word, r2, r2, PwStart           // tmo_end's word: CYCLE before the work
.assign Byte, r0.b1, r0.b1, PwAdvance   // (between's Advance)
.assign Byte, r0.b2, r0.b2, PwRecAhead  // (between's RecAhead)
.assign Byte, r0.b3, r0.b3, PwBurn      // cycles to burn: the work made whole turns
PREWORK:
    mov     PwLastPeriod, Period
    sub     PwRest, FullTmo, Tmo            // the turns left: the whole less the 3/4 period
    lsl     PwRest, PwRest, 16              //   (in w2; FullTmo in w0)
    or      PwRest, PwRest, FullTmo
    lbbo    PwStart, CTRL_BASE, CTRL_CYCLE, 4
    ldi     PwAddr, P_WORK_PAD
    sbbo    PwStart, PwAddr, OFFSET(SlvPriv.tmo_end) - OFFSET(SlvPriv.work_pad), 4
    sbbo    PwRest, PwAddr, OFFSET(SlvPriv.spare) - OFFSET(SlvPriv.work_pad), 4
    jal     RET_SUB, ADAPT
    ldi     PwAdvance, 1                    // (frames with a tail are latched)
    ldi     PwRecAhead, 2                   // FRAME_REC: this frame is not counted yet
    jal     RET_SUB, BUILD
    qbbc    PREWORK_COMMITTED, CTRL_FLAGS, CTRL_PENDING
    jal     RET_SUB, CTRL_COMMIT            // what the last control step left
PREWORK_COMMITTED:
    jal     RET_LEAF, COUNT_FRAME           // the frame's counters (END_WORK leaves them)
    // The control step ahead, for the CDM MA stands for now (END_KIND: its
    // level), the state before it kept (P_SHADOW) for the timeout's end to
    // go back to if MA moves after all (END_WORK). Nothing but the control
    // state changes in a step: what else it does is COMMIT's, later.
    ldi     PwAddr, P_CTRL
    lbbo    &Shadow, PwAddr, 0, SIZE(CtrlState)
    mov     ShadowFlags, CTRL_FLAGS
    ldi     PwAddr, P_SHADOW
    sbbo    &Shadow, PwAddr, 0, SIZE(CtrlState) + 4
    and     CDM_IN, END_KIND, 1
    set     CTRL_FLAGS, CTRL_FLAGS, CTRL_AHEAD
    clr     CTRL_FLAGS, CTRL_FLAGS, CTRL_AHEAD_CDM
    qbeq    PREWORK_CDM0, CDM_IN, 0
    set     CTRL_FLAGS, CTRL_FLAGS, CTRL_AHEAD_CDM
    qba     PREWORK_STEP
PREWORK_CDM0:
    qbbs    PREWORK_STEPPED, CTRL_FLAGS, CTRL_QUIET
PREWORK_STEP:
    jal     RET_SUB, CTRL_STEP
    lsl     PRE_WORD, CDS_OUT, 30
    set     PRE_WORD, PRE_WORD, 31          // the start bit, then the CDS
PREWORK_STEPPED:
    lsr     PwRest, PRE_WORD, 30            // FRAME_REC's CDS
    and     PwRest, PwRest, 1
    ldi     PwAddr, BISS_SLV_REC_CDS
    sbbo    PwRest, PwAddr, 0, 1
    ldi     PwAddr, P_WORK_PAD
    lbbo    PwStart, PwAddr, OFFSET(SlvPriv.tmo_end) - OFFSET(SlvPriv.work_pad), 4
    lbbo    PwRest, PwAddr, OFFSET(SlvPriv.spare) - OFFSET(SlvPriv.work_pad), 4
    mov     Tmo, PwRest                     // FullTmo, the reload
    lsr     TmoLeft, PwRest, 16             // the turns left
    // less the work's: its cycles (CYCLE) and PW_OUTSIDE, the tail's own
    // around them, made whole turns by burning 0..3 cycles more, so that
    // the timeout ends where it would without the work (at least one turn)
    lbbo    PwRest, CTRL_BASE, CTRL_CYCLE, 4
    sub     PwRest, PwRest, PwStart
    add     PwRest, PwRest, PW_OUTSIDE + 3
    and     PwBurn, PwRest, 3               // burn 3 - (w + 3) % 4
    xor     PwBurn, PwBurn, 3
    lsr     PwRest, PwRest, 2               // ceil(w / 4) turns
    qble    PREWORK_NONE, PwRest, TmoLeft   // left <= the work's
    sub     TmoLeft, TmoLeft, PwRest
    qbbc    PREWORK_BURN2, PwBurn, 0        // 1 cycle, or 2
    ldi     PwRest, 0
PREWORK_BURN2:
    qbbc    PREWORK_LEFT, PwBurn, 1         // 1 cycle, or 3
    ldi     PwRest, 0
    ldi     PwRest, 0
    qba     PREWORK_LEFT
PREWORK_NONE:
    ldi     TmoLeft, 1
PREWORK_LEFT:
    qbeq    TAIL_BUILT_HIGH, END_KIND, END_CDM0
    jmp     TAIL_BUILT_LOW
.leave frame
.leave prework

// COUNT_FRAME: the frame in the counters ST_FRAMES, ST_LATCHES and
// ST_CD_FRAMES, as END_KIND says. Returns through RET_LEAF.
COUNT_FRAME:
    ldi     Addr, BISS_SLV_ST_FRAMES
    lbbo    &Frames, Addr, 0, 12
    add     Frames, Frames, 1
    qbeq    COUNT_FRAME_DONE, END_KIND, END_NONE
    add     Latches, Latches, 1
    qbgt    COUNT_FRAME_DONE, END_KIND, END_CDM0
    add     CdFrames, CdFrames, 1
COUNT_FRAME_DONE:
    sbbo    &Frames, Addr, 0, 12
    jmp     RET_LEAF

// ---- ADAPT: the next frame's timeout after its ACK, from this frame's MA
// period P (LAST_PERIOD, PRU cycles). The timeout T: the fixed one, or P x
// factor / 16 clamped to [TMO_MIN, TIMEOUT] (adaptive). SL goes high
// WORK_PAD cycles after the polls see the timeout end, so they count
// D = T - WORK_PAD - TMO_FIXED (SL then rises T after the last MA edge);
// but never less than 3/4 P, more than any MA half period of a frame at
// this rate: a timeout shorter than the work ends later than T, at
// 3/4 P + WORK_PAD. TMO_ADAPT = D in turns of 4 cycles; GUARD = 1.5 D, the
// longest period D serves: a frame whose MA period is longer (a half
// period over two thirds of D) keeps TMO_MAX, the uncounted T (frame.p,
// R2_ROSE).
ADAPT:
    ldi     Addr, BISS_SLV_ST_PERIOD
    sbbo    LAST_PERIOD, Addr, 0, 4
    ldi     Addr, P_NSLAVES
    lbbo    NsWord, Addr, 0, 4
    ldi     Addr, P_TMO_MIN
    lbbo    &TmoMinC, Addr, 0, 12           // min, max (T fixed), WORK_PAD
    mov     Timeout, TmoMaxC
    qbeq    ADAPT_T, Factor, 0
    ldi     PeriodX, 0
    mov     Multiplicand, LAST_PERIOD
    mov     FactorBits, Factor
ADAPT_MUL:
    qbbc    ADAPT_MUL_NEXT, FactorBits, 0
    add     PeriodX, PeriodX, Multiplicand
ADAPT_MUL_NEXT:
    lsl     Multiplicand, Multiplicand, 1
    lsr     FactorBits, FactorBits, 1
    qbne    ADAPT_MUL, FactorBits, 0
    lsr     Timeout, PeriodX, 4
    max     Timeout, Timeout, TmoMinC
    min     Timeout, Timeout, TmoMaxC
ADAPT_T:
    ldi     Addr, BISS_SLV_ST_TIMEOUT
    sbbo    Timeout, Addr, 0, 4
    add     WorkPadC, WorkPadC, TMO_FIXED   // D = T - pad - fixed, or 0
    sub     PeriodX, Timeout, WorkPadC
    qble    ADAPT_D, Timeout, WorkPadC      // pad + fixed <= T
    ldi     PeriodX, 0
ADAPT_D:
    lsr     Multiplicand, LAST_PERIOD, 2    // at least 3/4 P
    rsb     Multiplicand, Multiplicand, 0
    add     Multiplicand, Multiplicand, LAST_PERIOD
    max     PeriodX, PeriodX, Multiplicand
    lsr     GUARD, PeriodX, 1
    add     GUARD, GUARD, PeriodX
    add     PeriodX, PeriodX, 2             // turns of 4 cycles (the nearest), at
    lsr     PeriodX, PeriodX, 2             //   least one
    max     PeriodX, PeriodX, 1
    mov     TMO_ADAPT, PeriodX
    jmp     RET_SUB

// ---- BUILD: the next frame's data words. Each slave's word, MSB first:
//   [position][fill zeros][nE][nW][life counter]
// (TIDEP0022 §2.1: position MSB first, then nE and nW, active low; the
// life counter after them as the AD38's third slave sends it). With
// Advance, every slave first moves on a frame (its position by its step,
// or the table's next entry; its life counter by one). The word goes to the
// slave's BANK_DATA record (XFR shift 2 k) and, left-aligned, to
// FRAME_REC; then FRAME_REC's frame number, CDS and slave count.
BUILD:
    ldi     Xfr, 0
    ldi     RunAddr, P_RUN
    ldi     RecAddr, BISS_SLV_REC_WORD0
BUILD_SLAVE:
    lbbo    &Run, RunAddr, 0, RUN_SIZE
    qbeq    BUILD_COMPOSE, Advance, 0
    qbne    BUILD_ADV_TABLE, Run.tab_len, 0
    add     Run.pos_lo, Run.pos_lo, Run.step_lo     // left-aligned: the sum wraps
    adc     Run.pos_hi, Run.pos_hi, Run.step_hi     // modulo 2^(position bits)
    qba     BUILD_ADV_LC
BUILD_ADV_TABLE:
    add     Run.tab_idx, Run.tab_idx, 1
    qbne    BUILD_ADV_TAB_OK, Run.tab_idx, Run.tab_len
    ldi     Run.tab_idx, 0
BUILD_ADV_TAB_OK:
    sbbo    Run.tab_idx, RunAddr, OFFSET(SlvRun.tab_idx), 1
BUILD_ADV_LC:
    add     Run.tail_lo, Run.tail_lo, Run.inc_lo
    adc     Run.tail_hi, Run.tail_hi, Run.inc_hi
    and     Run.tail_lo, Run.tail_lo, Run.lmask_lo
    and     Run.tail_hi, Run.tail_hi, Run.lmask_hi
    sbbo    &Run, RunAddr, 0, OFFSET(SlvRun.inc_lo)    // position, step, life counter
BUILD_COMPOSE:
    qbne    BUILD_TABLE, Run.tab_len, 0
    or      OutHi, Run.pos_hi, Run.tail_hi
    or      OutLo, Run.pos_lo, Run.tail_lo
    qba     BUILD_EW
BUILD_TABLE:                                // entry tab_start + tab_idx, left-aligned
    add     Scr, Run.tab_start, Run.tab_idx
    lsl     Scr, Scr, 3
    ldi     Addr, BISS_SLV_TABLE
    add     Addr, Addr, Scr
    lbbo    &SH_LO, Addr, 0, 8
    mov     SH_K, Run.pshift
    jal     RET_LEAF, SHL64
    or      OutHi, SH_HI, Run.tail_hi
    or      OutLo, SH_LO, Run.tail_lo
BUILD_EW:
    // nE and nW: 1 (no error, no warning) unless the host turned them on
    lsr     Addr, Xfr, 1
    add     Addr, Addr, BISS_SLV_LIVE_EW
    lbbo    LiveEw, Addr, 0, 1
    qbeq    BUILD_NE_DONE, Run.ne_word, 0
    qbbs    BUILD_NE_DONE, LiveEw, 0        // BISS_SLV_EW_ERROR: nE = 0
    qbeq    BUILD_NE_LO, Run.ne_word, 1
    set     OutHi, OutHi, Run.ne_bit
    qba     BUILD_NE_DONE
BUILD_NE_LO:
    set     OutLo, OutLo, Run.ne_bit
BUILD_NE_DONE:
    qbeq    BUILD_NW_DONE, Run.nw_word, 0
    qbbs    BUILD_NW_DONE, LiveEw, 1        // BISS_SLV_EW_WARNING: nW = 0
    qbeq    BUILD_NW_LO, Run.nw_word, 1
    set     OutHi, OutHi, Run.nw_bit
    qba     BUILD_NW_DONE
BUILD_NW_LO:
    set     OutLo, OutLo, Run.nw_bit
BUILD_NW_DONE:
    xout    BANK_DATA, &OutHi, 8            // slave k's record (XFR shift 2 k)
    sbbo    OutLo, RecAddr, 0, 4            // FRAME_REC: a u64, low word first
    sbbo    OutHi, RecAddr, 4, 4
    add     RecAddr, RecAddr, 8
    add     RunAddr, RunAddr, RUN_SIZE
    add     Xfr, Xfr, 2
    qbne    BUILD_SLAVE, Xfr, END_SLOT
    ldi     Xfr, 0                          // R0[4:0] = 0 again
    // FRAME_REC's head, after the words: the frame they are for, its CDS
    // and the slave count
    ldi     Addr, BISS_SLV_ST_FRAMES
    lbbo    OutLo, Addr, 0, 4
    add     OutLo, OutLo, RecAhead
    lsr     Scr, PRE_WORD, 30
    and     Scr, Scr, 1                     // the CDS in byte 0,
    lsr     OutHi, END_SLOT, 1
    lsl     OutHi, OutHi, 8
    or      Scr, Scr, OutHi                 //   the slaves in byte 1
    ldi     Addr, BISS_SLV_REC_FRAME
    sbbo    OutLo, Addr, 0, 4
    sbbo    Scr, Addr, 4, 4
    jmp     RET_SUB
.leave between

// ---- leaves, each returning through RET_LEAF --------------------------------
// SHL64: SH_HI:SH_LO << SH_K (0..63).
.enter leaves
.assign Word, r29, r29, ShTmp
SHL64:
    qbeq    SHL64_DONE, SH_K, 0
    qble    SHL64_BIG, SH_K, 32             // 32 <= K
    rsb     ShTmp, SH_K, 32
    lsr     ShTmp, SH_LO, ShTmp
    lsl     SH_HI, SH_HI, SH_K
    or      SH_HI, SH_HI, ShTmp
    lsl     SH_LO, SH_LO, SH_K
    jmp     RET_LEAF
SHL64_BIG:
    sub     ShTmp, SH_K, 32
    lsl     SH_HI, SH_LO, ShTmp
    ldi     SH_LO, 0
SHL64_DONE:
    jmp     RET_LEAF
.leave leaves
