// frame.p - the clocked frame: from the MA fall that begins it to the
// slave's timeout. Included by biss_encoder.p.
//
// Every rising edge has a block: its first instruction puts the bit on SL
// (`lsr SL_OUT, word, 31`, or an ACK/busy/tail 0), the second restarts the
// timeout, the rest prepares the next edge's bit; then the block's polls
// wait for the fall and the next rise (waits.hp). At H = 10 (10 MHz) a
// rise comes every 20 cycles; the longest block (SWITCH) takes 14 after
// its output and the polls 3 more, so every rise is met by a poll.
// Only register instructions, QBxx, JMP, XIN from the scratch pad and LBBO
// of this PRU's CYCLE register run here: no LOOP, no MVI, no data-RAM
// access (docs/silicon-assumptions.md A1, A6; CYCLE: pru_slave/README.md).
//
// SL, bit by bit (rising edges counted from the frame's first):
//   1         nothing goes out: the slaves latch their data (iC-MB4
//             datasheet, "BiSS C Frame": "With the first rising edge at
//             MAx all sensors start calculating their sensor data")
//   2         0: the ACK ("The second rising edge of MAx forces all slaves
//             to acknowledge the BiSS C frame with a falling edge at SLO")
//   3 ...     0 while busy (TIDEP0022 §2.1.2: a slave requests processing
//             time by delaying the start bit)
//   then      1 (start), CDS, then per slave its data word MSB first and
//             its CRC MSB first, inverted (TIDEP0022 §2.1); then 0 (the
//             last slave's SLI is low, iC-MB4 "Functional description")
// MA still for the timeout ends the frame: END_FRAME (between.p).

.using frame

// ---- the frame begins: MA fell while idle --------------------------------
// FRAME_READY (between.p) has set Tmo and TmoLeft (TMO_MAX), DataHi
// (PRE_WORD), Left (2) and Slot (0).
FRAME_START:
    WAIT_RISE R1_ROSE, TMO_NOLATCH

// 1st rise: the data are latched; nothing goes out (SL written as it is,
// so that CYCLE is read as many cycles after the edge as at the ACK). CYCLE
// now, for the MA period.
R1_ROSE:
    mov     SL_OUT, SL_OUT
    lbbo    LatchCyc, CTRL_BASE, CTRL_CYCLE, 4
    mov     TmoLeft, Tmo
    WAIT_FALL_RISE R2_ROSE, TMO_LATCHED, TMO_LATCHED

// 2nd rise: the ACK. The MA period from rise 1 to here chooses the
// timeout for the rest of the frame: the adaptive one (TMO_ADAPT, from the
// last frame's period), unless MA now runs slower than GUARD allows; then
// TMO_MAX, which holds at every rate. The next rise brings the start bit
// when no busy clock is due and the processing time is over by then (one
// period after the ACK).
R2_ROSE:
    ldi     SL_OUT, 0
    lbbo    AckCyc, CTRL_BASE, CTRL_CYCLE, 4
    sub     Period, AckCyc, LatchCyc
    mov     Tmo, TMO_ADAPT
    qbge    R2_TMO, Period, GUARD           // Period <= GUARD
    mov     Tmo, TMO_MAX
R2_TMO:
    mov     TmoLeft, Tmo
    mov     BusyLeft, BUSY_CLK
    qbne    BUSY_WAIT, BusyLeft, 0
    qbgt    BUSY_WAIT, Period, BUSY_CYC     // BUSY_CYC > Period: not yet
    jmp     CRC_WAIT                        // the start bit next

// A busy rise: SL stays 0. The next rise brings the start bit once the
// busy clocks are done and the time from the ACK to that rise (now + one
// period) reaches the processing time.
BUSY_ROSE:
    ldi     SL_OUT, 0                       // (SL stays low: CYCLE then read one
    lbbo    Now, CTRL_BASE, CTRL_CYCLE, 4   //  cycle after the edge, as at the ACK)
    mov     TmoLeft, Tmo
    sub     Tmp, Now, AckCyc
    add     Tmp, Tmp, Period
    qbeq    BUSY_CLOCKS_DONE, BusyLeft, 0
    sub     BusyLeft, BusyLeft, 1
BUSY_CLOCKS_DONE:
    qbne    BUSY_WAIT, BusyLeft, 0
    qbgt    BUSY_WAIT, Tmp, BUSY_CYC        // BUSY_CYC > Tmp: not yet
    jmp     CRC_WAIT
BUSY_WAIT:
    WAIT_FALL_RISE BUSY_ROSE, TMO_HIGH, TMO_LOW

// ---- a CRC bit; the start bit and the CDS go the same way (PRE_WORD in
// DataHi, Left = 2) -----------------------------------------------------------
CRC_ROSE:
    lsr     SL_OUT, DataHi, 31
    mov     TmoLeft, Tmo
    sub     Left, Left, 1
    qbeq    SWITCH, Left, 0
    lsl     DataHi, DataHi, 1
CRC_WAIT:
    WAIT_FALL_RISE CRC_ROSE, TMO_HIGH, TMO_LOW

// ---- the next slave: its record from the two scratch-pad banks (XFR
// shift Slot = 2k): the polynomial and the CRC start with the counts, then
// the data word; or, past the last slave, the tail --------------------------
SWITCH:
    qbeq    TAIL, Slot, END_SLOT
    xin     BANK_CRC, &RecPoly, 8
    mov     Poly, RecPoly
    mov     Crc, RecCrc
    xin     BANK_DATA, &DataHi, 8
    mov     Left, RecN
    mov     CrcW, RecW
    ldi     CrcCounts, 0
    add     Slot, Slot, 2
    qbeq    PLAIN_WAIT, CrcW, 0
    WAIT_FALL_RISE DATA_ROSE, TMO_HIGH, TMO_LOW

// ---- a data bit of a slave with a CRC: out, then into the CRC register --
DATA_ROSE:
    lsr     SL_OUT, DataHi, 31
    mov     TmoLeft, Tmo
    xor     Tmp, Crc, DataHi                // bit 31: the feedback
    lsl     Crc, Crc, 1
    qbbc    DATA_NOFB, Tmp, 31
    xor     Crc, Crc, Poly
DATA_NOFB:
    sub     Left, Left, 1
    qbeq    DATA_LAST, Left, 0
    add     DataLo, DataLo, DataLo          // DataHi:DataLo << 1, through the carry
    adc     DataHi, DataHi, DataHi
DATA_WAIT:
    WAIT_FALL_RISE DATA_ROSE, TMO_HIGH, TMO_LOW
DATA_LAST:                                  // the CRC next, inverted, MSB first
    not     DataHi, Crc
    mov     Left, CrcW
    jmp     CRC_WAIT

// ---- a data bit of a slave without a CRC ------------------------------------
PLAIN_ROSE:
    lsr     SL_OUT, DataHi, 31
    mov     TmoLeft, Tmo
    sub     Left, Left, 1
    qbeq    SWITCH, Left, 0
    add     DataLo, DataLo, DataLo
    adc     DataHi, DataHi, DataHi
PLAIN_WAIT:
    WAIT_FALL_RISE PLAIN_ROSE, TMO_HIGH, TMO_LOW

// ---- after the last slave: 0 on every rise. The next frame's words need
// not wait for the timeout: once MA has stood still for 3/4 of a period,
// more than any half period of this frame, the master has stopped
// clocking, and PREWORK (between.p) builds them there, then the tail
// waits out the rest of the timeout (TAIL_BUILT). The timeout's end then
// has little left to do. A master that clocks on after all only restarts
// the timeout: SL is 0 whatever comes.
TAIL:
    mov     FullTmo, Tmo
    lsr     Tmo, Period, 3                  // turns of 4 cycles: 3/16 P = (P / 8 + P / 16)
    lsr     Tmp, Period, 4
    add     Tmo, Tmo, Tmp
    max     Tmo, Tmo, 1
    mov     TmoLeft, Tmo
    qba     TAIL_WAIT
TAIL_ROSE:
    ldi     SL_OUT, 0
    mov     TmoLeft, Tmo
TAIL_WAIT:
    WAIT_FALL_RISE TAIL_ROSE, TAIL_STILL_HIGH, TAIL_STILL_LOW
TAIL_STILL_HIGH:
    ldi     END_KIND, END_CDM0              // (the level it is still at)
    jmp     PREWORK
TAIL_STILL_LOW:
    ldi     END_KIND, END_CDM1
    jmp     PREWORK

// After PREWORK: the rest of the timeout (TmoLeft, set by PREWORK), at the
// level MA stood still at.
TAIL_BUILT_ROSE:
    ldi     SL_OUT, 0
    mov     TmoLeft, Tmo
TAIL_BUILT_HIGH:
    WAIT_FALL TAIL_BUILT_FELL, TMO_BUILT_HIGH
TAIL_BUILT_FELL:
    mov     TmoLeft, Tmo
TAIL_BUILT_LOW:
    WAIT_RISE TAIL_BUILT_ROSE, TMO_BUILT_LOW

// ---- the timeout: MA stood still for Tmo turns --------------------------
TMO_NOLATCH:                                // before the first rise: nothing latched
    ldi     END_KIND, END_NONE
    jmp     END_FRAME
TMO_LATCHED:                                // before the ACK: no CDM
    ldi     END_KIND, END_LATCHED
    jmp     END_FRAME
TMO_HIGH:                                   // MA high: CDM = 0
    ldi     END_KIND, END_CDM0
    jmp     END_FRAME
TMO_LOW:                                    // MA low: CDM = 1
    ldi     END_KIND, END_CDM1
    jmp     END_FRAME
TMO_BUILT_HIGH:                             // likewise, the next frame built in the tail
    ldi     END_KIND, END_CDM0 | END_BUILT
    jmp     END_FRAME
TMO_BUILT_LOW:
    ldi     END_KIND, END_CDM1 | END_BUILT
    jmp     END_FRAME

.leave frame

// The frame is over; the work between frames (between.p) follows. The
// period goes with it (0 when the frame had no ACK: none measured).
END_FRAME:
.using frame
    ldi     LAST_PERIOD, 0
    qbgt    END_WORK, END_KIND, END_CDM0
    mov     LAST_PERIOD, Period
.leave frame
