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
    lbco    &AckPos, c28, P_SSI, SIZE(BissPriv) - P_SSI // Q' (and AckPos is what FRAME_END
                                            // records), the clocks (to r2.w0: docs/pru-facts.md §1.7)
    IEP_ALIGN_IF SSI_ALIGNED
.leave main_loop
SSI_ALIGNED:
    mov     Edges, SsiEdges
    FRAME_STAMP
    SAMPLE_POINT AckPos                     // sample point and lag as LAG1 derives them
    lsr     IdlePeriods, Qf, 3
    add     IdlePeriods, IdlePeriods, LAG   // periods before bit 0 is read: m + LAG
    ldi     Poly, 0
    LOAD_RECORD                             // the slave's data bits, no CRC
    jmp     LAG_TOP                         // the idle periods, then Entry
.leave front
.leave clocked
