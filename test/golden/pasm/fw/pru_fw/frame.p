// frame.p - a BiSS-C frame: the result-buffer macros, FRAME_REGS and the
// timestamp, then the clocked part (WAIT_ACK, LAG, START_WAIT, CDS and the
// slaves' entries; the periods themselves are in biss_periods.hp).
// Included by biss_master.p.

// The result buffer's address for the buffer number (0/1) in buf, to reg:
// BISS_RES0 (0x100, bit 8) + buf * BISS_RES_SIZE (< 0x100), branch-free (the
// same number of cycles either way: FRAME_REGS lies between an IEP trigger
// and the frame). biss_shm_struct.h asserts that layout.
.macro RESULT_ADDR
.mparam reg, buf
    rsb     reg, buf, 0                     // 0 or ~0
    and     reg, reg, BISS_RES_SIZE
    set     reg, reg, 8                     // + BISS_RES0 (0x100)
.endm

// reg = the result buffer being filled (P_BUF).
.macro RESULT_BASE
.mparam reg
    lbco    reg, c28, P_BUF, SIZE(BissPriv.buf)
    RESULT_ADDR reg, reg
.endm

// ============================================================================
// Before a frame: the slave must be idle (SL high); then the registers the
// clocked code starts from (FRAME_REGS), and the frame's timestamp.
//   r3 = 8p (ACK position base), r4.w0/w2, r5.w0 = history, r5.w2 = K,
//   r7.w0 = ACK limit, r7.w2 = processing-time limit, r4.w2 = history sum.
// A subroutine (returns through r12.w0; r2 it leaves alone) so that a
// free-run frame can have it done before SL is high (FE_IDLE_YES).
FRAME_REGS:
    // r3 delays, r4 r5 history (r5.w2 = K), r6 its sum, r7 P_BUF,
    // r8 P_NSLAVES, r9 P_HALF, r10 P_PROC
    lbco    r3, c28, P_DELAYS, P_SPARE - P_DELAYS
    lsl     r0, r10.b3, 8                   // XFR shift 0: slave 0's slot, the step to
                                            // the next (CFG_PROC), no busy clocks
    ldi     r11, MA_MASK | (MA_MASK << 8)   // period 0 clocks
    mov     r11.b2, r8.b2                   // the end record (SWITCH_SHORT)
    mov     r7.w0, r9.w2                    // ACK limit
    mov     r7.w2, r10.w0                   // processing-time limit
    mov     r9, r3                          // the tails (DELAY)
    mov     r4.w2, r6.w0                    // history sum (r10 is the delay's)
    lbco    r4.w0, c28, P_CDM, P_CD_LEN - P_CDM  // the CDM edge for either CDS
    ldi     r1.w0, REC_BASE                 // r1.b1 = 0
    ldi     r6, 0
    ldi     r8, 0
    jmp     RET_SUB

// The timestamp, then the first period. It waits in bank register 2 (r0.b0
// = 0: unshifted; the slots start at 4) for FRAME_END or ABORT_FRAME: no
// data-RAM store between the IEP read and the first MA edge.
.macro FRAME_STAMP
    ldi     r3, 0
    lbco    r2, c26, IEP_COUNT, 4
    xout    XFR_BANK, r2, 4
.endm

FRAME:
    jal     RET_SUB, SLAVE_IDLE
    qbeq    NO_SLAVE_IDLE, r3, 0
    lbco    r2, c28, P_SSI, SIZE(BissPriv.ssi_ack)
    qbeq    FRAME_BISS, r2.w0, 0
    jmp     SSI_FRAME
FRAME_BISS:
    jal     RET_SUB, FRAME_REGS
    IEP_ALIGN_IF FRAME_STAMPED
FRAME_STAMPED:                              // the free-run path comes in here
    fill    &MA_EDGES, 4                    // r12 all ones while the start bit is
                                            // awaited (r0.b0 = 0: no XFR shift)
FRAME_CLOCKED:                              // TRAIN comes in here, r12 its two clocks
    FRAME_STAMP
    // fall into the first period

// ---- WAIT_ACK ---------------------------------------------------------------
// Clock until the newest 8 samples hold the ACK edge (a 0), then go to
// ACK_FOUND at t = 3 with the samples in r2.b0 and 8p in r3. The only
// pre-data period that counts MA edges down (r12): a training frame stops
// after two clocks; a normal frame clocks on until its start bit is seen.
    // Period 0 looks at nothing: its samples date from before the frame
    // (the ACK cannot come before the second rising edge), so the frame may
    // start as soon as SL is high.
    MA_FALL
    add     r3, r3, 8                       // 1
    jal     RET_LEAF, DLY_S6                // 2..8
    DELAY
    MA_RISE
    NEXT_CLOCK                              // 1..4
    jal     RET_LEAF, DLY_S2                // 5..7
    DELAY
    PAD
WA_TOP:
    MA_FALL
    mov     r2, r31                         // 1
    qbne    ACK_FOUND, r2.b0, 0xff          // 2
    add     r3, r3, 8                       // 3
    jal     RET_LEAF, DLY_S4                // 4..8
    DELAY
    MA_RISE
    qble    NO_ACK, r3, r7.w0               // 1: limit <= 8p: give up after this rise
    NEXT_CLOCK                              // 2..5
    jal     RET_LEAF, DLY_S1                // 6..7
    DELAY
    qba     WA_TOP

// The ones before the ACK edge in r2.b0 (a constant-time count: a glitch
// moves it by one, not to another bit), as Q' = 8p + ones in r1.w2.
// A one-period ACK reaches the master shortened by the line's rise/fall
// skew, so when its edge lies just before the oldest sample the newest
// sample already reads the start bit (0x01 would count 1, not 0). Such
// trailing ones come after the ACK, not before it: b0 & (b0 + 1) clears
// them; an ACK pattern (ones, then zeros) ends in a 0 and keeps every bit.
// Split over the two halves: 6 cycles, then 7.
.macro ONES_A
    add     r8, r2.b0, 1
    and     r2.b0, r2.b0, r8.b0             // no trailing ones (start bit)
    lsr     r6, r2.b0, 1
    and     r6, r6, 0x55
    sub     r6, r2.b0, r6                   // 2-bit sums
    lsr     r8, r6, 2
.endm
.macro ONES_B
    and     r8, r8, 0x33
    and     r6, r6, 0x33
    add     r6, r6, r8                      // 4-bit sums
    lsr     r8, r6, 4
    add     r6, r6, r8
    and     r6, r6, 0x0f                    // ones before the edge
    add     r1.w2, r3, r6                   // Q'
.endm

// From here to the start bit MA clocks on (r11 stays MA_MASK both ways): r12
// is all ones (FRAME_STAMPED) less 2 MA_MASK for each period that counted it
// down, a few hundred at most (the ACK limit is some 400 periods, the lag as
// many), so its bit 30 stays set. A training frame has made its two clocks (r11 =
// 0, r12 = 0) and ends after this period.
ACK_FOUND:                                  // t = 3
    ONES_A                                  // 3..8
    DELAY
    MA_RISE
    ONES_B                                  // 1..7
    DELAY
    qbbc    TRAIN_DONE, MA_EDGES, EDGES_UNCOUNTED        // training: no more periods

// ---- LAG: sample point and lag from the averaged ACK position ------------------
LAG1:
    MA_FALL
    add     r2, r1.w2, r4.w2                // 1  Q' + h0 + h1 + h2 + 2
    lsr     r2, r2, 2                       // 2  Qf': the 4-frame average
    SAMPLE_POINT r2                         // 3..5
    lsr     r8, r2, 3                       // 6  m = (Qf' - 4) / 8
    lsr     r6, r3, 3                       // 7  p (this frame's ACK period)
    add     r3, r8, LAG                     // 8
    DELAY
    MA_RISE
    max     r3, r3, r6                      // 1
    sub     r3, r3, r6                      // 2  idle periods before the first read
    PAD                                     // 3
    rsb     r5.w0, SAMPLE_SHIFT, 29         // 4  R31 >> r5.w0: bit 2 the sample point
    jal     RET_LEAF, DLY_S2                // 5..7
    DELAY
    qbeq    SW_TOP, r3, 0

// r3 >= 1 idle periods. An SSI frame's come here too (SSI_FRAME) and go on
// to its slave's entry; they count MA edges down for its sake (a BiSS-C
// frame's r12 keeps bit 30 set, see ACK_FOUND).
LAG_TOP:
    MA_FALL
    jal     RET_LEAF, DLY_S7                // 1..8
    DELAY
    MA_RISE
    sub     r3, r3, 1                       // 1
    NEXT_CLOCK                              // 2..5
    qbeq    LAG_LAST, r3, 0                 // 6
    PAD                                     // 7
    DELAY
    qba     LAG_TOP
LAG_LAST:
    qbbc    SSI_LAG_LAST, MA_EDGES, EDGES_UNCOUNTED      // 7
    DELAY
    PAD

// ---- START_WAIT: ACK and busy read 0, the start bit 1 ------------------------
// The start bit is taken by a majority of five samples (the sample point
// and two on either side, all inside the bit): two samples flipped by a
// glitch (25 ns at 10 MHz) neither start the data early (in the busy) nor
// miss the start bit.
SW_TOP:
    MA_FALL
    lsr     r2, r31, r5.w0                  // 1  bits 4..0: sample point -2 .. +2
    and     r2, r2, 0x1f                    // 2
    mov     r3, MAJORITY5                   // 3..4
    qbbs    START_FOUND, r3, r2             // 5  three of the five are 1
    add     BUSY_CLOCKS, BUSY_CLOCKS, 1     // 6  busy clocks (0 from FRAME_REGS)
    jal     RET_LEAF, DLY_S1                // 7..8
    DELAY
    MA_RISE
    qblt    PROC_ERROR, BUSY_CLOCKS, r7.w2  // 1: limit < busy: give up after this rise
    jal     RET_LEAF, DLY_S5                // 2..7
    DELAY
    qba     SW_TOP

SSI_LAG_LAST:                               // t = H + 8
    DELAY
    jmp     NEXT_ENTRY

START_FOUND:                                // t = 6
    max     r3, r5.w2, r8                   // 6  clocks after this period:
    sub     r3, r3, r8                      // 7  max(N + 2 - LAG - m, 0), 2 edges each
    lsl     MA_EDGES, r3, MA_BIT + 1        // 8
    DELAY
    MA_RISE
    ldi     r8, 0                           // 1  (r8.w0 stays 0 from here on)
    NEXT_CLOCK                              // 2..5
    PAD                                     // 6
    ldi     r6, 0                           // 7  (r6.w0 stays 0 from here on)
    DELAY
    PAD

// ---- CDS, then the slaves ----------------------------------------------------
// The CDM of this frame may depend on its CDS (a WAIT step): r4.b0 holds
// the CDM edge (0 or MA_MASK) for CDS = 0, r4.b1 the change for CDS = 1.
// A CDM of 1 is one more MA edge after the last clock: MA low.
CDS_PERIOD:
    MA_FALL
    SAMPLE                                  // 1
    lsr     r1.b1, r2, 31                   // 2
    LOAD_RECORD                             // 3..6
    rsb     r3, r1.b1, 0                    // 7  CDS ? ~0 : 0
    and     r3, r3, r4.b1                   // 8
    DELAY
    MA_RISE
    xor     r3, r3, r4.b0                   // 1  the CDM edge
    add     MA_EDGES, MA_EDGES, r3          // 2
    NEXT_CLOCK                              // 3..6
    PAD                                     // 7
    DELAY
    jmp     NEXT_ENTRY

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
