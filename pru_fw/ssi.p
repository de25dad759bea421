// ssi.p - SSI frames. Included by biss_master.p.

// ============================================================================
// SSI: no ACK to measure the line by, no start bit, CDS or CRC. The slave
// shifts its word out on the rising edges from the first one; the master
// reads bit j (rise j) m + LAG periods later at the sample point the
// configured round trip gives (P_SSI), exactly as a BiSS-C frame's bits.

// Its configuration: CFG_SSI (APPLY_CONFIG).
.using main_loop
.using clocked
.using front
SSI_FRAME:
    jal     RET_SUB, FRAME_REGS
    ldi     Crc, 0                          // (its w0 stays 0: LOAD_RECORD sets w2)
    xout    XFR_BANK, RecWord, 4            // no FE_POLL turns (BUF_STAMP; period 0 is LAG_TOP's)
    lbco    AckPos, c28, P_SSI, SIZE(BissPriv.ssi_ack) // Q' (and AckPos is what FRAME_END records)
    lbco    SsiEdges, c28, P_SSI + 2, SIZE(BissPriv.ssi_edges) // the clocks
    qbbc    SSI_ALIGNED, Trigger, 0         // not BISS_TRIG_IEP (1) or IEP_FOLLOW (3)
.leave main_loop
.using iep_start
    ldi     IepTarget, SSI_STAMPED          // (Crc's upper half: LOAD_RECORD writes it)
    jmp     IEP_START_SLOW
.leave iep_start
SSI_ALIGNED:
    FRAME_STAMP
SSI_STAMPED:                                // an IEP frame on its count comes in here
    mov     Edges, SsiEdges
    SAMPLE_POINT AckPos                     // sample point and lag as LAG1 derives them
    lsr     IdlePeriods, Qf, 3
    add     IdlePeriods, IdlePeriods, LAG   // periods before bit 0 is read: m + LAG
    ldi     Poly, 0
    LOAD_RECORD                             // the slave's data bits, no CRC
    jmp     LAG_TOP                         // the idle periods, then Entry
.leave front
.leave clocked
