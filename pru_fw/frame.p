// frame.p - a BiSS-C frame: FRAME_REGS and the
// timestamp, then the clocked part (WAIT_ACK, LAG, START_WAIT, CDS and the
// slaves' entries; the periods themselves are in biss_periods.hp).
// Included by biss_master.p.

// ============================================================================
// Before a frame: the slave must be idle (SL high); then the registers the
// clocked code starts from (FRAME_REGS), and the frame's timestamp.
// A subroutine (returns through RET_SUB; r2 it leaves alone: Trigger) so
// that a free-run frame can have it done before SL is high (FE_IDLE_YES).
// It loads P_DELAYS .. P_PROC (BissPriv, layout.hp) into r3..r9 as Priv
// and sets up the clocked part's and the front's registers (regs.hp) from it.
.struct PrivRun                             // BissPriv from delays to running
    .u32    delays
    .u16    h0
    .u16    h1
    .u16    h2
    .u16    k
    .u16    hsum
    .u16    iep_slack
    .u8     nslaves
    .u8     trigger
    .u8     rec_end
    .u8     navg
    .u16    half
    .u16    ack_limit
    .u16    proc_limit
    .u8     train_due
    .u8     running
.ends
// The names of the next frame's start (results.p: FE_START, IEP_START; the
// frame set up by FRAME_REGS, Edges all ones): the registers it leaves free.
.enter fe_start
.assign Half, r1.w2, r1.w2, FastLeft        // FE_POLL's turns left (RecWord's upper half)
.assign Word, r2, r2, FastBase              // the timestamp's count base
.assign Byte, r2.b0, r2.b0, FastIdle8       // SL's newest samples
.assign Half, r2.w2, r2.w2, FastBaseHi      //   its upper half
.leave fe_start
.enter iep_start
.assign Word, r3, r3, IepEnd                // bank register 3: the count at the last frame's
                                            // end (FRAME_END; 0 after an overrun or an abort)
.assign Word, r8, r8, IepKey                // P_IEP_KEY: the CMP0 of P_IEP_SLACK
.assign Word, r10, r10, IepCnt              // the count
.assign Word, r2, r2, IepP                  // CMP0: the period less 1 (IEP_PERIOD's IepReg)
.assign Word, r8, r8, IepD                  // the cycles left to wait, plus the poll's budget
.assign Half, r8.w2, r8.w2, IepDHi          //   (IEP_BUDGET) until the poll ends (over IepKey)
.assign Half, r8.w0, r8.w0, IepLate         // IEP_LATE: its entry (LAG1, LOAD_RECORD write r8)
.assign Word, r2, r2, IepStamp              // bank register 2's word (BUF_STAMP)
.assign Byte, r2.b0, r2.b0, IepIdle8        // SL's newest samples
.assign Half, r6.w2, r6.w2, IepTarget       // period 0 (Crc: START_FOUND, LOAD_RECORD write it)
.leave iep_start

.enter frame_regs
.assign PrivRun, r3, r9, Priv
.using clocked
.using front
FRAME_REGS:
    lbco    &Priv.delays, c28, P_DELAYS, P_PROC_END - P_DELAYS
FRAME_REGS_SET:                             // (FE: Priv loaded, and the history updated)
    lsl     SlotWord, Priv.running, 8       // XFR shift 0: slave 0's slot, the step to
                                            // the next (CFG_PROC), no busy clocks
    ldi     Masks, MA_MASK | (MA_MASK << 8) // period 0 clocks
    mov     EndRec, Priv.rec_end            // the end record (SWITCH_SHORT)
    mov     AckLimit, Priv.ack_limit        // ACK limit
    mov     ProcLimit, Priv.proc_limit      // processing-time limit
    mov     Tails, Priv.delays              // the tails (DELAY)
    mov     HistSum, Priv.hsum.w0           // history sum
    lbco    &CdmEdge, c28, P_CDM, P_CD_LEN - P_CDM // the CDM edge for either CDS
    ldi     RecWord, REC_BASE               // the first record, Cds = 0, no FE_POLL turns
                                            // (the timestamp: BUF_STAMP)
.using iep_start
    ldi     IepTarget, FRAME_PERIOD0        // an IEP frame's period 0 (SSI_FRAME: its own)
.leave iep_start
    jmp     RET_SUB                         // (Crc, Poly: START_FOUND zeroes them)
.leave frame_regs

// The timestamp, then the first period. It waits in bank register 2 (Slot
// = 0: unshifted; the slots start at 4) for FRAME_END or ABORT_FRAME: no
// data-RAM store between the IEP read and the first MA edge. Two
// instructions (IEP_LATE enters STAMP_WORDS before the period 0 it is for).
.macro FRAME_STAMP
    lbco    Stamp, c26, IEP_COUNT, 4
    xout    XFR_BANK, Stamp, 4
.endm
#define STAMP_WORDS     2

.using main_loop
FRAME:
    jal     RET_SUB, SLAVE_IDLE
    qbeq    NO_SLAVE_IDLE, IDLE_LEFT, 0
    lbco    &SsiAck, c28, P_SSI, SIZE(BissPriv.ssi_ack)
    qbeq    FRAME_BISS, SsiAck, 0
    jmp     SSI_FRAME
FRAME_BISS:
    jal     RET_SUB, FRAME_REGS
FRAME_SET:                                  // (test_fw_timing's frames return here)
    fill    &Edges, 4                       // all ones while the start bit is awaited
    qbbs    IEP_START_SLOW, Trigger, 0      // BISS_TRIG_IEP (1), IEP_FOLLOW (3): its count
.leave main_loop
FRAME_CLOCKED:                              // TRAIN comes in here, Edges its two clocks
    FRAME_STAMP
    // fall into the first period

// ---- WAIT_ACK ---------------------------------------------------------------
// Clock until the newest 8 samples hold the ACK edge (a 0), then go to
// ACK_FOUND at t = 3 with the samples in Newest8 and 8p in AckBase. The only
// pre-data period that counts MA edges down (Edges): a training frame stops
// after two clocks; a normal frame clocks on until its start bit is seen.
    // Period 0 looks at nothing: its samples date from before the frame
    // (the ACK cannot come before the second rising edge), so the frame may
    // start as soon as SL is high.
FRAME_PERIOD0:
    MA_FALL
    ldi     AckBase, 8                      // 1  WAIT_ACK's 8p from here (whatever r3 held)
    xout    XFR_BANK, RecWord, 4            // 2  FE_POLL's turns left to bank register 1
    jal     RET_LEAF, DLY_S5                // 3..8
    DELAY
    MA_RISE
    NEXT_CLOCK                              // 1..4
    jal     RET_LEAF, DLY_S2                // 5..7
    DELAY
    PAD
WA_TOP:
    MA_FALL
    mov     Sample, SL_IN                   // 1
    qbne    ACK_FOUND, Newest8, 0xff        // 2
    add     AckBase, AckBase, 8             // 3
    jal     RET_LEAF, DLY_S4                // 4..8
    DELAY
    MA_RISE
    qble    NO_ACK, AckBase, AckLimit       // 1: limit <= 8p: give up after this rise
    NEXT_CLOCK                              // 2..5
    jal     RET_LEAF, DLY_S1                // 6..7
    DELAY
    qba     WA_TOP

// The ones before the ACK edge in Newest8 (a constant-time count: a glitch
// moves it by one, not to another bit), as Q' = 8p + ones in AckPos.
// A one-period ACK reaches the master shortened by the line's rise/fall
// skew, so when its edge lies just before the oldest sample the newest
// sample already reads the start bit (0x01 would count 1, not 0). Such
// trailing ones come after the ACK, not before it: b0 & (b0 + 1) clears
// them; an ACK pattern (ones, then zeros) ends in a 0 and keeps every bit.
// Split over the two halves: 6 cycles, then 7.
.macro ONES_A
    add     OnesT, Newest8, 1
    and     Newest8, Newest8, OnesTLo       // no trailing ones (start bit)
    lsr     Ones, Newest8, 1
    and     Ones, Ones, 0x55
    sub     Ones, Newest8, Ones             // 2-bit sums
    lsr     OnesT, Ones, 2
.endm
.macro ONES_B
    and     OnesT, OnesT, 0x33
    and     Ones, Ones, 0x33
    add     Ones, Ones, OnesT               // 4-bit sums
    lsr     OnesT, Ones, 4
    add     Ones, Ones, OnesT
    and     Ones, Ones, 0x0f                // ones before the edge
    add     AckPos, AckBase, Ones           // Q'
.endm

// From here to the start bit MA clocks on (both masks stay MA_MASK): Edges
// is all ones (FRAME_BISS, FE) less 2 MA_MASK for each period that counted it
// down, a few hundred at most (the ACK limit is some 400 periods, the lag as
// many), so its bit 30 stays set. A training frame has made its two clocks (the
// masks 0, Edges 0) and ends after this period.
ACK_FOUND:                                  // t = 3
    ONES_A                                  // 3..8
    DELAY
    MA_RISE
    ONES_B                                  // 1..7
    DELAY
    qbbc    TRAIN_DONE, Edges, EDGES_UNCOUNTED // training: no more periods

// ---- LAG: sample point and lag from the averaged ACK position ------------------
LAG1:
    MA_FALL
    add     Qf, AckPos, HistSum             // 1  Q' + h0 + h1 + h2 + 2
    lsr     Qf, Qf, 2                       // 2  Qf': the 4-frame average
    SAMPLE_POINT Qf                         // 3..5
    lsr     LineM, Qf, 3                    // 6  m = (Qf' - 4) / 8
    lsr     AckPeriod, AckBase, 3           // 7  p (this frame's ACK period)
    add     IdlePeriods, LineM, LAG         // 8
    DELAY
    MA_RISE
    max     IdlePeriods, IdlePeriods, AckPeriod // 1
    sub     IdlePeriods, IdlePeriods, AckPeriod // 2  idle periods before the first read
    PAD                                     // 3
    rsb     SwShift, Shift, 29              // 4  R31 >> SwShift: bit 2 the sample point
    jal     RET_LEAF, DLY_S2                // 5..7
    DELAY
    qbeq    SW_TOP, IdlePeriods, 0

// IdlePeriods >= 1 idle periods. An SSI frame's come here too (SSI_FRAME) and go on
// to its slave's entry; they count MA edges down for its sake (a BiSS-C
// frame's Edges keeps bit 30 set, see ACK_FOUND).
LAG_TOP:
    MA_FALL
    jal     RET_LEAF, DLY_S7                // 1..8
    DELAY
    MA_RISE
    sub     IdlePeriods, IdlePeriods, 1     // 1
    NEXT_CLOCK                              // 2..5
    qbeq    LAG_LAST, IdlePeriods, 0        // 6
    PAD                                     // 7
    DELAY
    qba     LAG_TOP
LAG_LAST:
    qbbc    SSI_LAG_LAST, Edges, EDGES_UNCOUNTED // 7
    DELAY
    PAD

// ---- START_WAIT: ACK and busy read 0, the start bit 1 ------------------------
// The start bit is taken by a majority of five samples (the sample point
// and two on either side, all inside the bit): two samples flipped by a
// glitch (25 ns at 10 MHz) neither start the data early (in the busy) nor
// miss the start bit.
SW_TOP:
    MA_FALL
    lsr     Sample, SL_IN, SwShift          // 1  bits 4..0: sample point -2 .. +2
    and     Sample, Sample, 0x1f            // 2
    mov     Tmp, MAJORITY5                  // 3..4
    qbbs    START_FOUND, Tmp, Sample        // 5  three of the five are 1
    add     Busy, Busy, 1                   // 6  busy clocks (0 from FRAME_REGS)
    jal     RET_LEAF, DLY_S1                // 7..8
    DELAY
    MA_RISE
    qble    PROC_ERROR, Busy, ProcLimit     // 1: busy reached the limit: give up after this rise
    jal     RET_LEAF, DLY_S5                // 2..7
    DELAY
    qba     SW_TOP

SSI_LAG_LAST:                               // t = H + 8
    DELAY
    jmp     Entry

START_FOUND:                                // t = 6
    max     Tmp, KClocks, LineM             // 6  clocks after this period:
    sub     Tmp, Tmp, LineM                 // 7  max(N + 2 - LAG - m, 0), 2 edges each
    lsl     Edges, Tmp, MA_BIT + 1          // 8
    DELAY
    MA_RISE
    ldi     Poly, 0                         // 1  (its w0 stays 0 from here on)
    NEXT_CLOCK                              // 2..5
    ldi     GridMarks, 0                    // 6  (WAIT_ACK's raw samples marked it)
    ldi     Crc, 0                          // 7  (its w0 stays 0 from here on)
    DELAY
    PAD

// ---- CDS, then the slaves ----------------------------------------------------
// The CDM of this frame may depend on its CDS (a WAIT step): CdmEdge holds
// the CDM edge (0 or MA_MASK) for CDS = 0, CdmChange the change for CDS = 1.
// A CDM of 1 is one more MA edge after the last clock: MA low.
CDS_PERIOD:
    MA_FALL
    SAMPLE                                  // 1
    lsr     Cds, Sample, 31                 // 2
    LOAD_RECORD                             // 3..6
    rsb     Tmp, Cds, 0                     // 7  CDS ? ~0 : 0
    and     Tmp, Tmp, CdmChange             // 8
    DELAY
    MA_RISE
    xor     Tmp, Tmp, CdmEdge               // 1  the CDM edge
    add     Edges, Edges, Tmp               // 2
    NEXT_CLOCK                              // 3..6
    PAD                                     // 7
    DELAY
    jmp     Entry
.leave front

// A slave's bits: n data bits, then w CRC bits, the last bit switching to the
// next slave. One entry per shape of slave.
ENTRY_CRC2:                                 // w >= 2
    DATA_PERIOD
    CRC_PERIOD
    CRC_SWITCH
ENTRY_CRC1:                                 // w = 1
    DATA_PERIOD
    CRC_SWITCH
ENTRY_PLAIN:                                // w = 0, n >= 2
    PLAIN_PERIOD
ENTRY_PLAIN1:                               // w = 0, n = 1
    PLAIN_SWITCH
.leave clocked
