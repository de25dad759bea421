// config.p - APPLY_CONFIG: the host's configuration checked and turned into
// what the clocked code needs; then the DLY_* delay tails (the shared
// delay routine the clocked periods jal into, docs/silicon-assumptions.md:
// they lie here, between configuration and frame, as they always have, so
// the image stays as it was). Included by biss_master.p.

// ============================================================================
// Configuration: check the host's block, derive everything the clocked code
// needs, and report the verdict.
APPLY_CONFIG:
    mov     r18, r2                         // the sequence number being applied
    lbco    r20, c24, BISS_CFG_HALF, 12     // r20.w0 H, r20.b2 slaves, r20.b3 trigger,
                                            // r21 IEP period, r22.w0 proc limit,
                                            // r22.w2 SSI round trip
    ldi     r28, BISS_CFGERR_NSLAVES
    qbeq    CFG_FAIL, r20.b2, 0
    qblt    CFG_FAIL, r20.b2, BISS_MAX_SLAVES   // 8 < slaves
    ldi     r28, BISS_CFGERR_TRIGGER
    qblt    CFG_FAIL, r20.b3, BISS_TRIG_IEP_FOLLOW
    ldi     r28, BISS_CFGERR_HALF
    qbgt    CFG_FAIL, r20.w0, BISS_MIN_HALF     // H < 10
    mov     r2, BISS_MAX_HALF
    qblt    CFG_FAIL, r20.w0, r2                // H > 1024

    // The shift clock must be exactly 8x MA: H = a * b with divide ratios
    // a/2 and b/2, 2 <= a, b <= 32. Prefer two whole ratios (even a and b).
    ldi     r27, 1                          // pass 1: whole ratios only
FACTOR_PASS:
    ldi     r6, 2                           // a
FACTOR_A:
    mov     r5, r20.w0                      // r5 = H mod a, r7 = H / a = b
    ldi     r7, 0
    jal     r0.w2, DIVIDE
    qbne    FACTOR_NEXT, r5, 0
    qbgt    FACTOR_NEXT, r7, 2              // b < 2
    qblt    FACTOR_NEXT, r7, 32             // b > 32
    qbne    FACTOR_FOUND, r27, 1
    qbbs    FACTOR_NEXT, r6, 0
    qbbc    FACTOR_FOUND, r7, 0
FACTOR_NEXT:
    add     r6, r6, 1
    qbge    FACTOR_A, r6, 32                // a <= 32
    add     r27, r27, 1
    qbeq    FACTOR_PASS, r27, 2
    jmp     CFG_FAIL                        // r28 is still CFGERR_HALF
FACTOR_FOUND:
    // divisor codes (ratio = 1 + code / 2): a - 2 at bit 3, b - 2 at bit 8
    // (r19 keeps it until the configuration is accepted: CFG_PROC)
    lsl     r7, r7, 5
    add     r19, r6, r7
    sub     r19, r19, 2 + (2 << 5)
    lsl     r19, r19, 3
    or      r19, r19, SHIFT_MODE

    // Slaves: records for the clocked code, verdict data for the checks.
    ldi     r23, 0                          // slave index
    ldi     r24, 0                          // N: bits of all slaves
    mov     r25, BISS_CFG_SLAVE0            // host block
    mov     r26, BISS_PRIV + P_RECORDS
    mov     r27, BISS_PRIV + P_SLAVES
    ldi     r11, FRAME_END                  // the end record's entry
    ldi     r0, 0                           // R0[4:0] = 0 for FILL: whether the XFR
                                            // shift moves it is not documented
CFG_SLAVE:
    lbbo    r2, r25, 0, 8                   // r2.b0 n, r2.b1 w, r2.b2 ew, r2.b3 flags, r3 poly|start
    ldi     r28, BISS_CFGERR_DATA_BITS
    qbeq    CFG_FAIL, r2.b0, 0
    qblt    CFG_FAIL, r2.b0, BISS_MAX_DATA_BITS
    ldi     r28, BISS_CFGERR_CRC_BITS
    qblt    CFG_FAIL, r2.b1, BISS_MAX_CRC_BITS
    ldi     r28, BISS_CFGERR_EW
    qbbc    CFG_EW_OK, r2.b3, 0
    add     r4, r2.b2, 1                    // nE's bit must lie in the data word
    qble    CFG_FAIL, r4, r2.b0             // n <= ew + 1
CFG_EW_OK:
    add     r24, r24, r2.b0
    add     r24, r24, r2.b1
    // record: counts and entry by the slave's shape. r6 = d, the bits of
    // its last kind (CRC, or data without CRC) that the loop leaves out: the
    // switch's, and for the last slave up to two more, read with the one
    // before them from the same R31 snapshot (FINAL_CRC, FINAL_PLAIN): its
    // chain is up to two bits shorter, and the frame ends as many periods
    // earlier. Only bits of the switch's kind: none where the bit before the
    // last is a data bit with CRC (w = 1) or another slave's (n = 1, w = 0).
    mov     r4.w0, r2.w0                    // n data bits, w CRC bits
    ldi     r6, 1                           // the switch's bit
    add     r7, r23, 1
    qbne    CFG_SHAPE, r7, r20.b2           // not the last slave
    ldi     r6, 3                           // the last: up to two more
CFG_SHAPE:
    qbeq    CFG_NOCRC, r2.b1, 0
    min     r6, r6, r2.b1
    sub     r4.b1, r4.b1, r6                // CRC bits before the switch
    ldi     r4.w2, ENTRY_CRC2
    qbne    CFG_CRC_FINAL, r4.b1, 0
    ldi     r4.w2, ENTRY_CRC1
CFG_CRC_FINAL:
    qbeq    CFG_REC, r6, 1
    ldi     r11.w0, FINAL_CRC               // one bit after the switch
    qbeq    CFG_REC, r6, 2
    ldi     r11.w0, FINAL_CRC2              // two
    qba     CFG_REC
CFG_NOCRC:
    min     r6, r6, r2.b0
    sub     r4.b0, r4.b0, r6                // data bits before the switch
    ldi     r4.w2, ENTRY_PLAIN
    qbne    CFG_PLAIN_FINAL, r4.b0, 0
    ldi     r4.w2, ENTRY_PLAIN1
CFG_PLAIN_FINAL:
    qbeq    CFG_REC, r6, 1
    ldi     r11.w0, FINAL_PLAIN             // one bit after the switch
    qbeq    CFG_REC, r6, 2
    ldi     r11.w0, FINAL_PLAIN2            // two
CFG_REC:
    // polynomial and start value left-aligned to bit 15 (the w2 halves);
    // no CRC (w = 0): both shifted by 16, out of the halves, so 0
    rsb     r6, r2.b1, 16                   // 16 - w
    lsl     r5, r3.w0, r6
    lsl     r7, r3.w2, r6
    mov     r5.w2, r7.w0
    sbbo    r4, r26, 0, 8
    add     r26, r26, 8
    // data mask: n ones. A shift takes its count & 31 (docs/pru-facts.md
    // §1.3), so ~0 >> (64 - n) is the high word's mask for n > 32 and the
    // low word's (~0 >> (32 - n)) for n <= 32 (n = 32, 64: a shift by 0).
    fill    &r6, 8
    rsb     r8, r2.b0, 64
    lsr     r7, r7, r8
    qblt    CFG_MASK_DONE, r2.b0, 32        // 32 < n: the low word all ones
    mov     r6, r7
    ldi     r7, 0
CFG_MASK_DONE:
    // residue: the CRC register after w inverted CRC bits of a right frame
    // = w ones fed to a zero register (linearity)
    ldi     r8, 0
    lsl     r10, r5.w0, 16                  // polynomial, left-aligned to bit 31
    qbeq    CFG_RESIDUE_DONE, r2.b1, 0
    // The count from a whole register: which bits a LOOP takes from a byte
    // field is not documented (docs/silicon-assumptions.md).
    mov     r3, r2.b1                       // (r3 is free after CFG_REC)
    loop    CFG_RESIDUE_DONE, r3.w0
    lsl     r9, r8, 0                       // keep bit 31 (feedback = bit31 ^ 1)
    lsl     r8, r8, 1
    qbbs    CFG_RESIDUE_STEP, r9, 31
    xor     r8, r8, r10
CFG_RESIDUE_STEP:
    mov     r0, r0
CFG_RESIDUE_DONE:
    mov     r9, r2                          // n, w, ew shift, flags
    sbbo    r6, r27, 0, SIZE(BissSlave)     // r6..r9
    add     r27, r27, SIZE(BissSlave)
    add     r25, r25, BISS_CFG_SLAVE_SIZE
    add     r23, r23, 1
    qbgt    CFG_SLAVE, r23, r20.b2          // while index < slaves
    // after the last slave: the end of the frame
    lsl     r4, r11, 16                     // entry r11.w0 (r11.w2 = 0), counts 0
    sbbo    r4, r26, 0, 4

    // SSI (slave 0's BISS_SF_SSI): alone and without CRC. r27 = the P_SSI
    // word: r27.w0 the ACK position a BiSS-C slave at this line delay would
    // show (Q' = 4 (rt + BISS_DELAY_ADJ_CYCLES) / H + BISS_DELAY_ZERO, rt the
    // round trip in cycles: biss_shm.h), r27.w2 the MA edges after period 0
    // (2n, times MA_MASK); r27 = 0 for BiSS-C.
CFG_SSI:
    ldi     r27, 0
    lbco    r2, c24, BISS_CFG_SLAVE0, 4     // n, w, ew, flags of slave 0
    qbbc    CFG_SSI_DONE, r2.b3, 1          // BISS_SF_SSI
    ldi     r28, BISS_CFGERR_SSI
    qbne    CFG_FAIL, r20.b2, 1             // one slave
    qbne    CFG_FAIL, r2.b1, 0              // no CRC
    mov     r5, r22.w2                      // CFG_SSI_DELAY_NS
    ldi     r6, 5
    ldi     r7, 0
    jal     r0.w2, DIVIDE                   // rt = ns / 5 cycles
    add     r5, r7, BISS_DELAY_ADJ_CYCLES
    lsl     r5, r5, 2                       // 4 (rt + adj) ...
    mov     r6, r20.w0
    ldi     r7, BISS_DELAY_ZERO
    jal     r0.w2, DIVIDE                   // ... / H + zero
    mov     r27.w0, r7.w0
    // n + 1 clocks: the one after the last bit makes the slave send 0 until
    // its monoflop ends (SL high again: ready), 2n edges after period 0's
    lsl     r27.w2, r2.b0, MA_BIT + 1
CFG_SSI_DONE:

    // IEP period: at least 2H (N + 8) cycles
    qbne    CFG_IEP_OK, r20.b3, BISS_TRIG_IEP
    add     r2, r24, 8
    ldi     r3, 0
    lsl     r4, r20.w0, 1                   // 2H
CFG_IEP_MIN:                                // r2 = N + 8 >= 9 turns (no LOOP of one
    add     r3, r3, r4                      // instruction: docs/silicon-assumptions.md)
    sub     r2, r2, 1
    qbne    CFG_IEP_MIN, r2, 0
    ldi     r28, BISS_CFGERR_IEP_PERIOD
    qbgt    CFG_FAIL, r21, r3               // period < minimum
    sub     r2, r21, 1                      // CMP0 = period - 1 (the count resets after it)
    sbco    r2, c26, IEP_CMP0, 4
    ldi     r2, 3                           // CMP0 enabled, resets the count
    sbco    r2, c26, IEP_CMP_CFG, 4
    ldi     r2, 0
    sbco    r2, c26, IEP_COUNT, 4
    ldi     r2, 0xff
    sbco    r2, c26, IEP_CMP_STATUS, 4
CFG_IEP_OK:

    // Accepted: commit everything.
    // The tails of the half periods (DELAY in biss_periods.hp): none at
    // H = 10 (r0 = 0), else the routine's entry for L = H - 11 cycles
    // (r0.w0), r0.b2 = 1, and its 4-cycle turns (r0.b3); the frame keeps
    // this word in r9.
    ldi     r0, 0
    qbeq    CFG_DELAY_SAVE, r20.w0, 10
    ldi     r0.b2, 1
    sub     r2, r20.w0, 11                  // L >= 1
    ldi     r3, DLY_S1 + 1                  // short: entry DLY_S1 + 1 - L
    qbge    CFG_DELAY_ENTRY, r2, 7
    sub     r2, r2, 2                       // long: L - 2 = 4 n + r, n >= 1 (L >= 8)
    lsr     r0.b3, r2, 2                    // n <= (1013 - 2) / 4 = 252
    and     r2, r2, 3
    ldi     r3, DLY_L0                      // entry DLY_L0 - r
CFG_DELAY_ENTRY:
    sub     r0.w0, r3, r2
CFG_DELAY_SAVE:
    sbco    r0, c28, P_DELAYS, SIZE(BissPriv.delays)
    // K = N + 2 - LAG: the clocks after the start bit's period are the CDS,
    // the N bits and one more, on which the slave starts its timeout (SL
    // low); LAG of them are already out when the start bit is seen.
    ldi     r3, 0                           // history empty (training fills it)
    sub     r4, r24, LAG - 2
    lsl     r4, r4, 16                      // and K
    sbco    r3, c28, P_HIST, P_HSUM - P_HIST
    mov     r2, r20.w2                      // slaves, trigger, -, frames in the average (0)
    lsl     r2.b2, r20.b2, 3                // the end record's register-file address
    add     r2.b2, r2.b2, REC_BASE
    sbco    r2, c28, P_NSLAVES, P_HALF - P_NSLAVES
    // ACK limit in periods x 8: (BISS_MAX_DELAY_NS / 10 / H + 4) x 8
    mov     r5, BISS_MAX_DELAY_NS / 10
    mov     r6, r20.w0
    ldi     r7, 4
    jal     r0.w2, DIVIDE
    lsl     r7, r7, 16 + 3                  // to w2
    mov     r7.w0, r20.w0
    sbco    r7, c28, P_HALF, P_PROC - P_HALF
    mov     r2.w0, r22.w0                   // processing-time limit
    ldi     r2.w2, 0x0101                   // running, training due (BiSS-C)
    // The step between the slaves' result slots in this PRU's bank, for
    // the XFR shift (R0[4:0]). TI calls R0[4:0] "the number of 32-bit
    // offset" for XIN and XOUT but gives no direction. Up, slot k sits at
    // bank registers 4 + 3k .. 6 + 3k (k <= 7: at most 27, never past the
    // bank's 30). Down, the step must be 29: 4 - 29k = 4 + 3k only modulo
    // 32, so look for exactly that: register 3 written with a shift of 29
    // lands in bank register 6 only if the shift goes down and wraps as a
    // 5-bit offset (up, it is bank register 0). Found: step 29; else 3
    // (docs/silicon-assumptions.md A6).
    ldi     r0, 0
    ldi     r6, 0
    xout    XFR_BANK, r6, 4                       // bank register 6 cleared
    ldi     r0, 32 - XFR_SLOT
    ldi     r3, 32 - 2 * XFR_SLOT
    xout    XFR_BANK, r3, 4                       // 26 to bank register 6 (down) or 0 (up)
    ldi     r0, 0
    xin     XFR_BANK, r6, 4
    add     r2.b3, r6, XFR_SLOT             // running = the step: 3 up, 29 down
    qbeq    CFG_PROC, r27.w0, 0
    ldi     r2.b2, 0                        // SSI: the delay is given, nothing to train
    mov     r1.w2, r27.w0                   // and the history holds it (r0, r1 are
    jal     r0.w0, HIST_FILL                // set up anew by every frame)
CFG_PROC:
    sbco    r27, c28, P_SSI, SIZE(BissPriv) - P_SSI
    sbco    r2, c28, P_PROC, P_SPARE - P_PROC
    sbco    r19, c4, GPCFG_OWN, 4           // shift mode at 8x the new rate (FACTOR_FOUND)
    ldi     r28, BISS_CFGERR_NONE
    ldi     r29, BISS_STATE_RUNNING
    qba     CFG_REPORT
CFG_FAIL:
    ldi     r2, 0
    sbco    r2, c28, P_PROC, P_SPARE - P_PROC  // not running
    ldi     r29, BISS_STATE_CFG_ERROR
CFG_REPORT:
    sbco    r28, c24, BISS_ST_CFG_ERROR, 8  // r28 the error, r29 ST_STATE (the next word)
    sbco    r18, c24, BISS_ST_CFG_ACK, 4    // then the sequence number: the verdict is out
    lbco    r13, c28, P_RECORDS, P_DELAYS - P_RECORDS  // slave records into r13..r29
    jmp     MAIN

// r7 += r5 / r6, r5 = r5 mod r6: repeated subtraction (configuration only).
// Returns through r0.w2.
DIVIDE:
    qbgt    DIVIDE_DONE, r5, r6
    sub     r5, r5, r6
    add     r7, r7, 1
    qba     DIVIDE
DIVIDE_DONE:
    jmp     r0.w2

// The shared delay of the clocked periods: called by `jal r10.w2, entry`,
// it costs from its entry to its return included: DLY_Sk k cycles (k =
// 1..7), DLY_Lr 2 + r + 4 r9.b3 cycles (r = 0..3, r9.b3 >= 1, so the turn
// counter never starts at 0 nor wraps). Single-cycle instructions only
// (docs/pru-facts.md §3): no LOOP. It writes r10.b1 and the carry.
DLY_S7:
    mov     r0, r0
DLY_S6:
    mov     r0, r0
DLY_S5:
    mov     r0, r0
DLY_S4:
    mov     r0, r0
DLY_S3:
    mov     r0, r0
DLY_S2:
    mov     r0, r0
DLY_S1:
    jmp     RET_LEAF
DLY_L3:
    mov     r0, r0
DLY_L2:
    mov     r0, r0
DLY_L1:
    mov     r0, r0
DLY_L0:
    mov     r10.b1, r9.b3
DLY_TURN:                                   // 4 cycles a turn
    sub     r10.b1, r10.b1, 1
    mov     r0, r0
    mov     r0, r0
    qbne    DLY_TURN, r10.b1, 0
    jmp     RET_LEAF
