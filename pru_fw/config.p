// config.p - APPLY_CONFIG: the host's configuration checked and turned into
// what the clocked code needs; then the DLY_* delay tails (the shared
// delay routine the clocked periods jal into, docs/silicon-assumptions.md:
// they lie here, between configuration and frame, as they always have, so
// the image stays as it was). Included by biss_master.p.

// ============================================================================
// Configuration: check the host's block, derive everything the clocked code
// needs, and report the verdict.
// The registers of the configuration. r18..r29 hold through it (the slave
// records r13..r29 are loaded afresh at its end); r0..r17 are its scratch,
// named by what they hold in each step.
.struct HostSlave                           // a slave's block of the host's configuration
    .u8     n                               // data bits
    .u8     w                               // CRC bits
    .u8     ew                              // nE/nW position
    .u8     flags                           // BISS_SF_*
    .u16    poly                            // CRC polynomial
    .u16    start                           // CRC start value
.ends
.struct CfgRecord                           // a slave record as the clocked code loads it
    .u8     data_bits                       // data bits before the switch
    .u8     crc_bits                        // CRC bits before the switch
    .u16    entry                           // the code that reads its bits
    .u16    poly                            // polynomial, left-aligned to bit 15
    .u16    start                           // CRC start value, likewise
.ends
.enter config
.assign Word, r18, r18, NewSeq              // the sequence number being applied
.assign Word, r19, r19, Gpcfg               // GPCFG: shift mode at 8x the new rate (FACTOR_FOUND)
.assign Half, r20.w0, r20.w0, CfgHalf       // the host's block, BISS_CFG_HALF on: H,
.assign Byte, r20.b2, r20.b2, CfgSlaves     //   slaves,
.assign Byte, r20.b3, r20.b3, CfgTrigger    //  trigger,
.assign Half, r20.w2, r20.w2, CfgSlavesTrig //  (both),
.assign Word, r21, r21, CfgIep              //   IEP period,
.assign Half, r22.w0, r22.w0, CfgProc       //   processing-time limit,
.assign Half, r22.w2, r22.w2, CfgSsiNs      //   SSI round trip (ns)
.assign Word, r23, r23, SlaveOff          // 8 x the slave's index: its block at
                                            // BISS_CFG_SLAVE0 + SlaveOff, its record at
                                            // C28 + P_RECORDS + SlaveOff
.assign Word, r24, r24, NBits               // N + 2 - LAG: the bits of all slaves, and 2 - LAG
.assign Word, r25, r25, SlavesOff           // 8 x slaves: SlaveOff's end
.assign Word, r27, r27, Pass                // FACTOR: 1 whole ratios only, 2 any
.assign Word, r27, r27, ChkAddr             // the slave's check data in P_SLAVES
.assign Word, r27, r27, SsiWord             // P_SSI's word (0: BiSS-C):
.assign Half, r27.w0, r27.w0, SsiAckNew     //   the ACK position an SSI line shows,
.assign Half, r27.w2, r27.w2, SsiEdgesNew   // the MA edges after period 0
.assign Word, r28, r28, CfgErr              // the verdict, BISS_CFGERR_*,
.assign Word, r29, r29, CfgState            //   and ST_STATE (the next word)
.assign Word, r13, r13, Records             // r13..r29: the slave records (P_RECORDS)
// DIVIDE's operands
.assign Word, r5, r5, Num                   // the dividend; the remainder after
.assign Word, r6, r6, Den                   // the divisor
.assign Word, r7, r7, Quot                  // the quotient is added to it
.assign Half, r7.w0, r7.w0, QuotLo
// FACTOR
.assign Word, r2, r2, MaxHalf               // BISS_MAX_HALF
.assign Word, r6, r6, FactorA               // a, the divisor
.assign Word, r7, r7, FactorB               // b = H / a
// CFG_SLAVE
.assign Word, r0, r0, XfrZero               // 0: R0[4:0] = 0 for FILL
.assign HostSlave, r2, r3, Host             // the slave's block (the first word also of slave 0
.assign Half, r2.w0, r2.w0, HostNW          //   for CFG_SSI); n, w together;
.assign Word, r2, r2, HostWord              //   the first word whole
.assign Word, r3, r3, LoopTurns             // CFG_RESIDUE's turns: w
.assign Half, r3.w0, r3.w0, LoopTurnsLo
.assign Word, r4, r4, EwPlus1               // ew + 1
.assign CfgRecord, r4, r5, Rec              // the slave's record, 8 bytes
.assign Half, r4.w0, r4.w0, RecCounts       //   its counts together
.assign Word, r6, r6, Align16               // 16 - w
.assign Word, r7, r7, NextOff               // SlaveOff of the next slave
.assign BissSlave, r12, r15, Chk            // the slave's check data (layout.hp)
.assign Half, r12.w0, r12.w0, ChkEw         //   its nE/nW pointer and shift as one
.assign Word, r8, r8, MaskShift             // 64 - n
.assign Word, r16, r16, Residue             // the CRC register after w ones (left-aligned)
.assign Word, r10, r10, PolyHalf            // the polynomial left-aligned to bit 30
.assign Word, r11, r11, EndRecord           // the end record's word: its entry in w0
.assign Half, r11.w0, r11.w0, EndEntry
.assign Word, r4, r4, EndWord               // the end record: entry in w2, counts 0
.assign Word, r17, r17, LastBits            // d: the bits read after the switch's (CFG_SHAPE);
                                            // the last slave's is L (P_IEP_FIX)
.assign Word, r3, r3, IepFix                // 1 - (N + 5 - L) (P_IEP_FIX)
.assign Word, r8, r8, RingNext              // CFG_RING: BISS_ST_RING_NEXT, and after it
.assign Half, r9.w0, r9.w0, RingStride      //   ST_RING_STRIDE,
.assign Half, r9.w2, r9.w2, RingLast        //   ST_RING_LAST
// CFG_IEP, and IEP_PERIOD (which the IEP frames call, r0..r12 only)
.assign Word, r2, r2, IepReg                // a word for an IEP register: CMP0 (P - 1)
.assign Byte, r2.b0, r2.b0, OtherTrigger    // the other PRU's BISS_CFG_TRIGGER (C25)
.assign Half, r4.w0, r4.w0, IepHalf         // IEP_PERIOD: H
.assign Word, r8, r8, IepCap                // 65536 x 2H
// Accepted: the words for the private RAM
.assign Word, r0, r0, DelayWord             // P_DELAYS: the tails (DELAY), as Tails:
.assign Half, r0.w0, r0.w0, DelayEntry      //   the DLY_* entry,
.assign Byte, r0.b2, r0.b2, DelayGate       //   1 (SwGate),
.assign Byte, r0.b3, r0.b3, DelayTurns      //   the turns
.assign Word, r2, r2, DelayL                // L = H - 11 cycles, then the rest r
.assign Word, r3, r3, DelayBase             // the entry L or r counts back from
.assign Word, r1, r1, NewHist01             // P_HIST: h0, h1 (0),
.assign Word, r2, r2, NewHist2K             //   h2 (0), K (stored with DelayWord: r0..r2)
// P_NSLAVES .. P_SSI, one store (CFG_PROC) from r24..r27 (NBits, SlavesOff
// are done with by then; SsiWord is r27)
.assign Word, r24, r24, NewNs               // P_NSLAVES' word: slaves, trigger, the end record,
.assign Byte, r24.b2, r24.b2, NewRecEnd     //   frames in the average (0)
.assign Word, r25, r25, NewHalf             // P_HALF's word: H, the ACK limit
.assign Half, r25.w0, r25.w0, NewHalfLo
.assign Word, r26, r26, NewProc             // P_PROC's word: the processing-time limit,
.assign Half, r26.w0, r26.w0, NewProcLimit
.assign Byte, r26.b2, r26.b2, NewDue
.assign Byte, r26.b3, r26.b3, NewRunning    //   running = the slot step
.assign Word, r0, r0, XfrShiftCfg           // R0: the XFR shift while the step is probed
.assign Word, r6, r6, Probe                 // bank register 6's word
.assign Word, r3, r3, ProbeVal              // the word written with a shift of 29
.assign Half, r1.w2, r1.w2, HistPos         // HIST_FILL's position (an SSI line's)

APPLY_CONFIG:
    mov     NewSeq, CfgSeq                  // the sequence number being applied
.leave main_loop
    lbco    &CfgHalf, c24, BISS_CFG_HALF, 12 // CfgHalf .. CfgSsiNs
    ldi     CfgErr, BISS_CFGERR_NSLAVES
    qbeq    CFG_FAIL, CfgSlaves, 0
    qblt    CFG_FAIL, CfgSlaves, BISS_MAX_SLAVES // 8 < slaves
    ldi     CfgErr, BISS_CFGERR_TRIGGER
    qblt    CFG_FAIL, CfgTrigger, BISS_TRIG_IEP_FOLLOW
    ldi     CfgErr, BISS_CFGERR_HALF
    qbgt    CFG_FAIL, CfgHalf, BISS_MIN_HALF // H < 10
    mov     MaxHalf, BISS_MAX_HALF
    qblt    CFG_FAIL, CfgHalf, MaxHalf      // H > 1024

    // The shift clock must be exactly 8x MA: H = a * b with divide ratios
    // a/2 and b/2, 2 <= a, b <= 32. Prefer two whole ratios (even a and b).
    ldi     Pass, 1                         // pass 1: whole ratios only
FACTOR_PASS:
    ldi     FactorA, 2                      // a
FACTOR_A:
    mov     Num, CfgHalf                    // Num = H mod a, FactorB = H / a = b
    ldi     FactorB, 0
    jal     RET_DIV, DIVIDE
    qbne    FACTOR_NEXT, Num, 0
    qbgt    FACTOR_NEXT, FactorB, 2         // b < 2
    qblt    FACTOR_NEXT, FactorB, 32        // b > 32
    qbne    FACTOR_FOUND, Pass, 1
    qbbs    FACTOR_NEXT, FactorA, 0
    qbbc    FACTOR_FOUND, FactorB, 0
FACTOR_NEXT:
    add     FactorA, FactorA, 1
    qbge    FACTOR_A, FactorA, 32           // a <= 32
    add     Pass, Pass, 1
    qbeq    FACTOR_PASS, Pass, 2            // else refused: CfgErr is still CFGERR_HALF
// The verdict: refused (from any check, and from here), or accepted
// (CFG_RING); then MAIN.
CFG_FAIL:
    ldi     NewProc, 0
    sbco    NewProc, c28, P_PROC, P_PROC_END - P_PROC // not running
    ldi     CfgState, BISS_STATE_CFG_ERROR
CFG_REPORT:
    sbco    CfgErr, c24, BISS_ST_CFG_ERROR, 8 // CfgErr, CfgState (ST_STATE, the next word)
    sbco    NewSeq, c24, BISS_ST_CFG_ACK, 4 // then the sequence number: the verdict is out
    sbco    NewSeq, c28, P_CFG_ACK, 4       // (and its copy beside the frame's set-up, FE)
    lbco    &Records, c28, P_RECORDS, P_DELAYS - P_RECORDS // slave records into r13..r29
    jmp     MAIN
FACTOR_FOUND:
    // divisor codes (ratio = 1 + code / 2): a - 2 at bit 3, b - 2 at bit 8
    // (Gpcfg keeps it until the configuration is accepted: CFG_PROC)
    lsl     FactorB, FactorB, 5
    add     Gpcfg, FactorA, FactorB
    sub     Gpcfg, Gpcfg, 2 + (2 << 5)
    lsl     Gpcfg, Gpcfg, 3
    or      Gpcfg, Gpcfg, SHIFT_MODE

    // Slaves: records for the clocked code, verdict data for the checks.
    // A host block and a record are both 8 bytes (BISS_CFG_SLAVE_SIZE,
    // SIZE(CfgRecord)), so one offset walks both.
    ldi     SlaveOff, 0
    lsl     SlavesOff, CfgSlaves, 3
    ldi     NBits, 2 - LAG                  // N + 2 - LAG, from the bits of all slaves (K)
    mov     ChkAddr, BISS_PRIV + P_SLAVES
    ldi     EndRecord, FRAME_END            // the end record's entry
    ldi     XfrZero, 0                      // R0[4:0] = 0 for FILL: whether the XFR
                                            // shift moves it is not documented
CFG_SLAVE:
    lbbo    &Host.n, SlaveOff, BISS_CFG_SLAVE0, 8 // n, w, ew, flags, poly, start
    ldi     CfgErr, BISS_CFGERR_DATA_BITS
    qbeq    CFG_FAIL, Host.n, 0
    qblt    CFG_FAIL, Host.n, BISS_MAX_DATA_BITS
    ldi     CfgErr, BISS_CFGERR_CRC_BITS
    qblt    CFG_FAIL, Host.w, BISS_MAX_CRC_BITS
    // nE/nW: where FE_SLAVE's MVI finds nW, the data word's bit ew: the
    // register-file byte ew / 8 bytes into DataLo, bit ew mod 8 of the word
    // read there (nE the next bit up, in the same word: ew mod 8 + 1 <= 8).
    // Without nE/nW: the CRC register's low half, always 0.
    ldi     CfgErr, BISS_CFGERR_EW
    ldi     ChkEw, RF_CRC_LOW               // (shift 0)
    qbbc    CFG_EW_OK, Host.flags, 0
    add     EwPlus1, Host.ew, 1             // nE's bit must lie in the data word
    qble    CFG_FAIL, EwPlus1, Host.n       // n <= ew + 1
    lsr     Chk.ewptr, Host.ew, 3
    add     Chk.ewptr, Chk.ewptr, RF_DATA_LO
    and     Chk.ewshift, Host.ew, 7
CFG_EW_OK:
    add     NBits, NBits, Host.n
    add     NBits, NBits, Host.w
    // record: counts and entry by the slave's shape. LastBits = d, the bits of
    // its last kind (CRC, or data without CRC) that the loop leaves out: the
    // switch's, and for the last slave up to two more, read with the one
    // before them from the same R31 snapshot (FINAL_CRC, FINAL_PLAIN): its
    // chain is up to two bits shorter, and the frame ends as many periods
    // earlier. Only bits of the switch's kind: none where the bit before the
    // last is a data bit with CRC (w = 1) or another slave's (n = 1, w = 0).
    mov     RecCounts, HostNW               // n data bits, w CRC bits
    ldi     LastBits, 1                     // the switch's bit
    add     NextOff, SlaveOff, 8
    qbne    CFG_SHAPE, NextOff, SlavesOff   // not the last slave
    ldi     LastBits, 3                     // the last: up to two more
CFG_SHAPE:
    qbeq    CFG_NOCRC, Host.w, 0
    min     LastBits, LastBits, Host.w
    sub     Rec.crc_bits, Rec.crc_bits, LastBits // CRC bits before the switch
    ldi     Rec.entry, ENTRY_CRC2
    qbne    CFG_CRC_FINAL, Rec.crc_bits, 0
    ldi     Rec.entry, ENTRY_CRC1
CFG_CRC_FINAL:
    qbeq    CFG_REC, LastBits, 1
    ldi     EndEntry, FINAL_CRC             // one bit after the switch
    qbeq    CFG_REC, LastBits, 2
    ldi     EndEntry, FINAL_CRC2            // two
    qba     CFG_REC
CFG_NOCRC:
    min     LastBits, LastBits, Host.n
    sub     Rec.data_bits, Rec.data_bits, LastBits // data bits before the switch
    ldi     Rec.entry, ENTRY_PLAIN
    qbne    CFG_PLAIN_FINAL, Rec.data_bits, 0
    ldi     Rec.entry, ENTRY_PLAIN1
CFG_PLAIN_FINAL:
    qbeq    CFG_REC, LastBits, 1
    ldi     EndEntry, FINAL_PLAIN           // one bit after the switch
    qbeq    CFG_REC, LastBits, 2
    ldi     EndEntry, FINAL_PLAIN2          // two
CFG_REC:                                    // (the last slave's LastBits is kept: P_IEP_FIX)
    // polynomial and start value left-aligned to bit 15 (into the halves,
    // which keep the shift's low 16 bits); no CRC (w = 0): both shifted by
    // 16, out of the halves, so 0
    rsb     Align16, Host.w, 16             // 16 - w
    lsl     Rec.poly, Host.poly, Align16
    lsl     Rec.start, Host.start, Align16
    sbco    &Rec.data_bits, c28, SlaveOff, 8 // P_RECORDS (0) + SlaveOff
    // data mask: n ones. A shift takes its count & 31 (docs/pru-facts.md
    // §1.3), so ~0 >> (64 - n) is the high word's mask for n > 32 and the
    // low word's (~0 >> (32 - n)) for n <= 32 (n = 32, 64: a shift by 0).
    fill    &Chk.mask_lo, 8
    rsb     MaskShift, Host.n, 64
    lsr     Chk.mask_hi, Chk.mask_hi, MaskShift
    qblt    CFG_MASK_DONE, Host.n, 32       // 32 < n: the low word all ones
    mov     Chk.mask_lo, Chk.mask_hi
    ldi     Chk.mask_hi, 0
CFG_MASK_DONE:
    // residue: the CRC register after w inverted CRC bits of a right frame
    // = w ones fed to a zero register (linearity). A step with feedback
    // (bit 31 ^ 1 = 1: bit 31 clear) is (r << 1) ^ poly = (r ^ poly >> 1)
    // << 1: the polynomial, left-aligned to bit 31, has bit 0 clear, and
    // bit 31 goes out either way.
    ldi     Residue, 0
    lsl     PolyHalf, Rec.poly, 15          // the polynomial, left-aligned to bit 30
    qbeq    CFG_RESIDUE_DONE, Host.w, 0
    // The count from a whole register: which bits a LOOP takes from a byte
    // field is not documented (docs/silicon-assumptions.md).
    mov     LoopTurns, Host.w               // (Host.poly, start are used by then)
    loop    CFG_RESIDUE_DONE, LoopTurnsLo
    qbbs    CFG_RESIDUE_STEP, Residue, 31   // bit 31 set: no feedback
    xor     Residue, Residue, PolyHalf
CFG_RESIDUE_STEP:
    lsl     Residue, Residue, 1
CFG_RESIDUE_DONE:
    lsr     Chk.residue, Residue, 16        // (its low half is 0, as the CRC register's)
    sbbo    &Chk.ewptr, ChkAddr, 0, SIZE(BissSlave)
    add     ChkAddr, ChkAddr, SIZE(BissSlave)
    mov     SlaveOff, NextOff
    qbne    CFG_SLAVE, SlaveOff, SlavesOff  // while index < slaves
    // after the last slave: the end of the frame
    lsl     EndWord, EndRecord, 16          // entry EndEntry (w2 = 0), counts 0
    sbco    EndWord, c28, SlaveOff, 4
    // the MA periods of a BiSS-C frame from period 0 to the one FRAME_END
    // starts in, beside max(m + LAG, p) and the busy clocks: period 0 and
    // the ACK's (p + 1 in all with the idle ones up to m + LAG), LAG1, the
    // start bit's, the CDS, and the N - (L - 1) periods of the slaves' bits
    // (the last slave's last L - 1 bits are read after them, FINAL_*): N + 5
    // - L (an SSI frame has fewer; IEP_PERIOD)
    sub     IepFix, LastBits, NBits         // 1 - (N + 5 - L): IEP_PERIOD's start
    sub     IepFix, IepFix, 2 + LAG         // (NBits: N + 2 - LAG)
    sbco    IepFix, c28, P_IEP_FIX, 4

    // SSI (slave 0's BISS_SF_SSI): alone and without CRC. SsiWord = the P_SSI
    // word: SsiAckNew the ACK position a BiSS-C slave at this line delay would
    // show (Q' = 4 (rt + BISS_DELAY_ADJ_CYCLES) / H + BISS_DELAY_ZERO, rt the
    // round trip in cycles: biss_shm.h), SsiEdgesNew the MA edges after period 0
    // (2n, times MA_MASK); SsiWord = 0 for BiSS-C.
CFG_SSI:
    ldi     SsiWord, 0
    lbco    &Host.n, c24, BISS_CFG_SLAVE0, 4 // n, w, ew, flags of slave 0
    qbbc    CFG_SSI_DONE, Host.flags, 1     // BISS_SF_SSI
    ldi     CfgErr, BISS_CFGERR_SSI
    qbne    CFG_FAIL, CfgSlaves, 1          // one slave
    qbne    CFG_FAIL, Host.w, 0             // no CRC
    mov     Num, CfgSsiNs                   // CFG_SSI_DELAY_NS
    ldi     Den, 5
    ldi     Quot, 0
    jal     RET_DIV, DIVIDE                 // rt = ns / 5 cycles
    add     Num, Quot, BISS_DELAY_ADJ_CYCLES
    lsl     Num, Num, 2                     // 4 (rt + adj) ...
    mov     Den, CfgHalf
    ldi     Quot, BISS_DELAY_ZERO
    jal     RET_DIV, DIVIDE                 // ... / H + zero
    mov     SsiAckNew, QuotLo
    // n + 1 clocks: the one after the last bit makes the slave send 0 until
    // its monoflop ends (SL high again: ready), 2n edges after period 0's
    lsl     SsiEdgesNew, Host.n, MA_BIT + 1
CFG_SSI_DONE:
    // The step between the slaves' result slots in this PRU's bank, for
    // the XFR shift (R0[4:0]). TI calls R0[4:0] "the number of 32-bit
    // offset" for XIN and XOUT but gives no direction. Up, slot k sits at
    // bank registers 4 + 3k .. 6 + 3k (k <= 7: at most 27, never past the
    // bank's 30). Down, the step must be 29: 4 - 29k = 4 + 3k only modulo
    // 32, so look for exactly that: register 3 written with a shift of 29
    // lands in bank register 6 only if the shift goes down and wraps as a
    // 5-bit offset (up, it is bank register 0). Found: step 29; else 3
    // (docs/silicon-assumptions.md A6). R0[4:0] is still 0 from XfrZero
    // (DIVIDE's calls write only r0.w2), and 0 after.
    ldi     Probe, 0
    xout    XFR_BANK, Probe, 4              // bank register 6 cleared
    ldi     XfrShiftCfg, 32 - XFR_SLOT
    ldi     ProbeVal, 32 - 2 * XFR_SLOT
    xout    XFR_BANK, ProbeVal, 4           // 26 to bank register 6 (down) or 0 (up)
    ldi     XfrShiftCfg, 0
    xin     XFR_BANK, Probe, 4
    add     NewRunning, Probe, XFR_SLOT     // running = the step: 3 up, 29 down

    // IEP (owner and follower): the thresholds for the period are worked
    // out by the first IEP frame (P_IEP_KEY no CMP0: IEP_PERIOD). The owner
    // sets the period up (CMP0 = P - 1 resets the count after it); a
    // follower takes the owner's, whenever it is set up. Free-run and host:
    // the count must run free (their timestamps), so compare 0 stops
    // resetting it, which an owner before this configuration, or before a
    // restart of this firmware, left on; unless the other PRU's block asks
    // for the IEP trigger (it owns the IEP: libbiss's rule). Then on
    // through the key (unused by these triggers) to CFG_IEP_OK.
    qbbs    CFG_IEP_ON, CfgTrigger, 0       // BISS_TRIG_IEP (1) and IEP_FOLLOW (3)
    lbco    OtherTrigger, c25, BISS_CFG_TRIGGER, 1
    qbeq    CFG_IEP_OK, OtherTrigger, BISS_TRIG_IEP
    sbco    XfrZero, c26, IEP_CMP_CFG, 4    // (the probe's last R0)
CFG_IEP_ON:
    fill    &IepReg, 4
    sbco    IepReg, c28, P_IEP_KEY, 4       // none yet
    qbne    CFG_IEP_OK, CfgTrigger, BISS_TRIG_IEP
    sub     IepReg, CfgIep, 1
    sbco    IepReg, c26, IEP_CMP0, 4
    ldi     IepReg, 3                       // CMP0 enabled, resets the count
    sbco    IepReg, c26, IEP_CMP_CFG, 4
    sbco    XfrZero, c26, IEP_COUNT, 4      // 0 (the probe's last R0)
CFG_IEP_OK:


    // Accepted: commit everything.
    // The tails of the half periods (DELAY in biss_periods.hp): none at
    // H = 10 (DelayWord = 0), else the routine's entry for L = H - 11 cycles
    // (DelayEntry), DelayGate = 1, and its 4-cycle turns (DelayTurns); the
    // frame keeps this word in Tails.
    // From L = GRID_MIN_L on, every tail checks a bit's samples (DLY_CHK).
    qbeq    CFG_DELAY_SAVE, CfgHalf, 10     // (DelayWord is 0: the probe's last R0)
    ldi     DelayGate, 1
    sub     DelayL, CfgHalf, 11             // L >= 1
    ldi     DelayBase, DLY_S1 + 1           // short, no check (H 12, 14, 15): DLY_S1 + 1 - L
    qbgt    CFG_DELAY_ENTRY, DelayL, GRID_MIN_L
    ldi     DelayBase, DLY_CHK + GRID_MIN_L // short, checked: DLY_CHK + GRID_MIN_L - L
    qbge    CFG_DELAY_ENTRY, DelayL, GRID_MIN_L + 5
    sub     DelayL, DelayL, GRID_MIN_L + 2  // long: L - 7 = 4 n + r, n >= 1 (L >= 11)
    lsr     DelayTurns, DelayL, 2           // n <= (1013 - 7) / 4 = 251
    and     DelayL, DelayL, 3
    ldi     DelayBase, DLY_L0               // entry DLY_L0 - r
CFG_DELAY_ENTRY:
    sub     DelayEntry, DelayBase, DelayL
CFG_DELAY_SAVE:                             // (stored with the history: P_DELAYS..P_HSUM)
    // K = N + 2 - LAG: the clocks after the start bit's period are the CDS,
    // the N bits and one more, on which the slave starts its timeout (SL
    // low); LAG of them are already out when the start bit is seen.
    ldi     NewHist01, 0                    // history empty (training fills it)
    lsl     NewHist2K, NBits, 16            // and K (NBits: N + 2 - LAG)
    sbco    &DelayWord, c28, P_DELAYS, P_HSUM - P_DELAYS // DelayWord, NewHist01, NewHist2K
    mov     NewNs, CfgSlavesTrig            // slaves, trigger, -, frames in the average (0)
    add     NewRecEnd, SlavesOff, REC_BASE  // the end record's register-file address
    // Above CUT_MAX_HALF the frame's last period keeps its tails: no record
    // lies at 0xff, so SWITCH_SHORT never cuts them (biss_master.p says why).
    qbge    CFG_REC_END, CfgHalf, CUT_MAX_HALF
    ldi     NewRecEnd, 0xff
CFG_REC_END:
    // ACK limit in periods x 8: (BISS_MAX_DELAY_NS / 10 / H + 4) x 8
    mov     Num, BISS_MAX_DELAY_NS / 10
    mov     Den, CfgHalf
    ldi     Quot, 4
    jal     RET_DIV, DIVIDE
    lsl     NewHalf, Quot, 16 + 3           // to w2
    mov     NewHalfLo, CfgHalf
    mov     NewProcLimit, CfgProc           // processing-time limit
    ldi     NewDue, 1                       // training due (BiSS-C)
    qbeq    CFG_PROC, SsiAckNew, 0
    ldi     NewDue, 0                       // SSI: the delay is given, nothing to train
    mov     HistPos, SsiAckNew              // and the history holds it (r0, r1 are
    jal     RET_POST, HIST_FILL             // set up anew by every frame)
CFG_PROC:
    sbco    &NewNs, c28, P_NSLAVES, P_CFG_ACK - P_NSLAVES // NewNs, NewHalf, NewProc, SsiWord
    // The result ring afresh from its first slot, at this slave count's
    // stride (biss_shm_struct.h's BISS_RING_STRIDE and BISS_RING_SLOTS):
    // ST_RING_NEXT, ST_RING_STRIDE, ST_RING_LAST in one store.
CFG_RING:
    lsl     RingStride, CfgSlaves, 4        // x BISS_R_SLAVE_SIZE (16)
    add     RingStride, RingStride, BISS_R_SLAVE0
    ldi     RingNext, BISS_RING_END
    sub     RingLast, RingNext, RingStride  // the last slot's highest start
    ldi     RingNext, BISS_RING0
    sbco    RingNext, c24, BISS_ST_RING_NEXT, 8
    sbco    Gpcfg, c4, GPCFG_OWN, 4         // shift mode at 8x the new rate (FACTOR_FOUND)
    ldi     CfgErr, BISS_CFGERR_NONE
    ldi     CfgState, BISS_STATE_RUNNING
    qba     CFG_REPORT

// Quot += Num / Den, Num = Num mod Den: repeated subtraction (configuration
// only). Returns through RET_DIV.
DIVIDE_TURN:
    sub     Num, Num, Den
    add     Quot, Quot, 1
DIVIDE:
    qble    DIVIDE_TURN, Num, Den           // Den <= Num
    jmp     RET_DIV

// An IEP frame's thresholds for the period CMP0 + 1 = P (IEP_START, when
// P_IEP_KEY is not CMP0: after a configuration, or the owner's new period):
// P_IEP_SLACK, the fewest max(m + LAG, p) + busy MA periods that may take a
// frame's end count (FRAME_END's read, at most IEP_C0 into the MA period
// after its last) a period or more past its start: Q - (N + 5 - L) for Q =
// ceil((P - IEP_C0) / 2H), 0 if that is negative (no frame fits: every one
// is flagged), Q at most 65536 (DIVIDE's turns). Then MAIN sets the frame
// up again. In: IepReg = CMP0 (IEP_START's IepP).
IEP_PERIOD:
    lbco    Quot, c28, P_IEP_FIX, 4         // 1 - (N + 5 - L): Q - (N + 5 - L) after
    lbco    IepHalf, c28, P_HALF, 2
    lsl     Den, IepHalf, 1                 // 2H
    sub     Num, IepReg, IEP_C0             // Q = (P - 1 - IEP_C0) / 2H + 1
    lsl     IepCap, Den, 16
    min     Num, Num, IepCap
    jal     RET_DIV, DIVIDE
    qbbc    IEP_SLACK, Quot, 31             // -(N + 5) < Quot <= 65536 - 3
    ldi     Quot, 0
IEP_SLACK:
    sbco    QuotLo, c28, P_IEP_SLACK, SIZE(BissPriv.iep_slack)
    sbco    IepReg, c28, P_IEP_KEY, 4
    jmp     MAIN
.leave config

// The shared delay of the clocked periods: called by `jal RET_LEAF, entry`,
// it costs from its entry to its return included: DLY_Sk k cycles (k =
// 1..7), DLY_Ck 5 + k cycles (k = 0..5; DLY_C0 is DLY_CHK), DLY_Lr 7 + r + 4
// DlyTurns cycles (r = 0..3, DlyTurns >= 1, so the turn counter never starts
// at 0 nor wraps). The DLY_C and DLY_L entries end in the bit-grid check
// (GRID_CHECK): the tails of every period take them from H = 16 on (CFG's
// DelayEntry), so every bit read there has its next bit's samples checked,
// twice (both halves: the marks only accumulate). The DLY_S entries, which
// the periods also call by name for a fixed few cycles, check nothing.
// Single-cycle instructions only (docs/pru-facts.md §3): no LOOP. It writes
// DlyCount and the carry, and GridMarks from the DLY_C and DLY_L entries.
.using clocked
DLY_S7:
    PAD
DLY_S6:
    PAD
DLY_S5:
    PAD
DLY_S4:
    PAD
DLY_S3:
    PAD
DLY_S2:
    PAD
DLY_S1:
    jmp     RET_LEAF
DLY_L3:
    PAD
DLY_L2:
    PAD
DLY_L1:
    PAD
DLY_L0:
    mov     DlyCount, DlyTurns
DLY_TURN:                                   // 4 cycles a turn
    sub     DlyCount, DlyCount, 1
    PAD
    PAD
    qbne    DLY_TURN, DlyCount, 0
    qba     DLY_CHK
DLY_C5:
    PAD
DLY_C4:
    PAD
DLY_C3:
    PAD
DLY_C2:
    PAD
DLY_C1:
    PAD
DLY_CHK:
    GRID_CHECK                              // 4 cycles
    jmp     RET_LEAF
.leave clocked
