// ssi.p - SSI frames. Included by biss_master.p.

// ============================================================================
// SSI: no ACK to measure the line by, no start bit, CDS or CRC. The slave
// shifts its word out on the rising edges from the first one; the master
// reads bit j (rise j) m + LAG periods later at the sample point the
// configured round trip gives (P_SSI), exactly as a BiSS-C frame's bits.

// Its configuration: CFG_SSI (APPLY_CONFIG).
SSI_FRAME:
    jal     RET_SUB, FRAME_REGS
    lbco    r1.w2, c28, P_SSI, SIZE(BissPriv) - P_SSI  // Q' (and r1.w2 is what FRAME_END records),
                                            // the clocks (to r2.w0: docs/pru-facts.md §1.7)
    IEP_ALIGN_IF SSI_ALIGNED
SSI_ALIGNED:
    mov     MA_EDGES, r2.w0
    FRAME_STAMP
    SAMPLE_POINT r1.w2                      // sample point and lag as LAG1 derives them
    lsr     r3, r2, 3
    add     r3, r3, LAG                     // periods before bit 0 is read: m + LAG
    ldi     r8, 0
    LOAD_RECORD                             // the slave's data bits, no CRC
    jmp     LAG_TOP                         // the idle periods, then NEXT_ENTRY
