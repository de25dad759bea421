// config.p - APPLY_CONFIG: the host's block checked (BISS_SLV_CFGERR_* for
// the first thing wrong) and turned into what the frame and the work
// between frames need: the persistent registers (regs.hp), each slave's
// SlvRun and SlvCtl (layout.hp) and its BANK_CRC record, the work's pad and
// the first frame's words (BUILD). Then READY, or, refused, WAIT_CONFIG
// (SL low). Included by biss_encoder.p; nothing in it is clocked.

// P_NSLAVES' word (SlvPriv).
.struct SlvChain
    .u8     nslaves
    .u8     idl
    .u8     factor
    .u8     idl_cts
.ends

// A slave's block of the host's configuration, its first 16 bytes
// (biss_slave_shm.h); the position and the step follow.
.struct HostSlave
    .u8     pos_bits
    .u8     fill_bits
    .u8     lc_bits
    .u8     flags
    .u8     crc_bits
    .u8     id
    .u8     reg_wait
    .u8     banks
    .u16    crc_poly
    .u16    crc_start
    .u8     bank0
    .u8     table_start
    .u16    table_len
.ends

.enter config
.assign Byte, r0.b0, r0.b0, Xfr         // the XFR shift: 2 k (R0[4:0])
.assign Byte, r0.b1, r0.b1, Bits        // scratch bytes above it
.assign Byte, r1.b0, r1.b0, IdlCts      // the IDs answering the ID lock at CTS
.assign Byte, r1.b1, r1.b1, CtlAll      // the slaves taking part in control communication
.assign Byte, r0.b2, r0.b2, Idx         // the slave's index
.assign Byte, r0.b3, r0.b3, Idl         // the answering slaves' IDs, bit k: ID k
.assign Byte, r2.b0, r2.b0, CSlaves     // the chain's block from BISS_SLV_CFG_NSLAVES on:
.assign Byte, r2.b1, r2.b1, CTmoMode    //   slaves, timeout mode,
.assign Byte, r2.b2, r2.b2, CFactor     //   adaptive factor,
.assign Byte, r2.b3, r2.b3, NBits       //   (reserved: a slave's data bits)
.assign Word, r3, r3, CTimeout          //   timeout (the longest),
.assign Word, r4, r4, CTmoMin           //   the adaptive one's shortest,
.assign Word, r5, r5, CBusyCyc          //   processing time, cycles
.assign Half, r6.w0, r6.w0, CBusyClk    //   and clocks
.assign Half, r6.w2, r6.w2, Err         // the verdict, BISS_SLV_CFGERR_*
.assign Word, r7, r7, RunAddr           // the slave's SlvRun
.assign HostSlave, r8, r11, Hs          // the slave's block, its first 16 bytes
.assign Word, r12, r12, Scr
.assign Word, r13, r13, Scr2
.assign Word, r14, r14, RecPolyOut      // its BANK_CRC record: the polynomial and the CRC
.assign Word, r15, r15, RecCrcOut       //   start with the counts (frame.p SWITCH)
.assign Word, r23, r23, NewSeq          // the CFG_SEQ being applied
.assign Word, r24, r24, Addr
.assign Word, r25, r25, HostAddr        // the slave's block in the host's configuration
.assign SlvChain, r12, r12, Chain       // P_NSLAVES' word as it is stored
.assign Byte, r13.b0, r13.b0, Byte0xff  // 0xff
.assign Word, r14, r14, WordOut         // a word to store (before the BANK_CRC record)

APPLY_CONFIG:
    ldi     Addr, BISS_SLV_CFG_SEQ
    lbbo    NewSeq, Addr, 0, 4
    lbbo    &CSlaves, Addr, BISS_SLV_CFG_NSLAVES, BISS_SLV_CFG_BUSY_CLOCKS + 2 - BISS_SLV_CFG_NSLAVES
    ldi     NBits, 0
    ldi     Err, BISS_SLV_CFGERR_NSLAVES
    qbeq    CFG_REFUSE, CSlaves, 0
    qblt    CFG_REFUSE, CSlaves, BISS_SLV_MAX_SLAVES  // 8 < slaves
    // the timeout: 1 .. BISS_SLV_MAX_TIMEOUT cycles; adaptive needs a
    // factor and its shortest not above its longest
    ldi     Err, BISS_SLV_CFGERR_TIMEOUT
    qbeq    CFG_REFUSE, CTimeout, 0
    mov     Scr, BISS_SLV_MAX_TIMEOUT
    qblt    CFG_REFUSE, CTimeout, Scr       // MAX < timeout
    qblt    CFG_REFUSE, CTmoMode, BISS_SLV_TMO_ADAPTIVE
    qbne    CFG_TMO_IS_FIXED, CTmoMode, BISS_SLV_TMO_ADAPTIVE
    qbeq    CFG_REFUSE, CFactor, 0
    qblt    CFG_REFUSE, CTmoMin, CTimeout   // timeout < min
    qba     CFG_TMO_OK
CFG_TMO_IS_FIXED:
    ldi     CFactor, 0
CFG_TMO_OK:
    ldi     Err, BISS_SLV_CFGERR_BUSY
    lsr     Scr, CBusyCyc, 24
    qbne    CFG_REFUSE, Scr, 0

    // ---- every slave -----------------------------------------------------------
    ldi     Byte0xff, 0xff                  // SlvCtl.by_id: no slave of any ID yet
    mov     Addr, P_CTL + OFFSET(SlvCtl.by_id)
    ldi     Idx, 0
CFG_BY_ID:
    sbbo    Byte0xff, Addr, 0, 1
    add     Addr, Addr, CTL_SIZE
    add     Idx, Idx, 1
    qbne    CFG_BY_ID, Idx, BISS_SLV_MAX_SLAVES
    ldi     Idx, 0
    ldi     Idl, 0
    ldi     IdlCts, 0
    ldi     CtlAll, 0
    ldi     HostAddr, BISS_SLV_CFG_SLAVE0
    ldi     RunAddr, P_RUN
CFG_SLAVE:
    lbbo    &Hs, HostAddr, 0, SIZE(HostSlave)
    // data bits: position 1..64, life counter 0..32, the word 1..64
    ldi     Err, BISS_SLV_CFGERR_LC_BITS
    qblt    CFG_REFUSE, Hs.lc_bits, BISS_SLV_MAX_LC_BITS
    ldi     Err, BISS_SLV_CFGERR_DATA_BITS
    qbeq    CFG_REFUSE, Hs.pos_bits, 0
    qblt    CFG_REFUSE, Hs.pos_bits, BISS_SLV_MAX_DATA_BITS
    add     Scr, Hs.pos_bits, Hs.fill_bits
    add     Scr, Scr, Hs.lc_bits
    and     Scr2, Hs.flags, BISS_SLV_SF_NE
    add     Scr, Scr, Scr2
    lsr     Scr2, Hs.flags, 1               // BISS_SLV_SF_NW
    and     Scr2, Scr2, 1
    add     Scr, Scr, Scr2
    qblt    CFG_REFUSE, Scr, BISS_SLV_MAX_DATA_BITS
    mov     NBits, Scr
    // CRC: 0..16 bits, the start value inside them
    ldi     Err, BISS_SLV_CFGERR_CRC_BITS
    qblt    CFG_REFUSE, Hs.crc_bits, BISS_SLV_MAX_CRC_BITS
    lsr     Scr, Hs.crc_start, Hs.crc_bits
    qbne    CFG_REFUSE, Scr, 0
    // ID: 0..7, one answering slave each
    ldi     Err, BISS_SLV_CFGERR_ID
    qblt    CFG_REFUSE, Hs.id, 7
    qbbs    CFG_ID_OK, Hs.flags, 2          // BISS_SLV_SF_NO_CONTROL: answers for nobody
    lsr     Scr, Idl, Hs.id
    qbbs    CFG_REFUSE, Scr, 0
    set     Idl, Idl, Hs.id
    set     CtlAll, CtlAll, Idx
    lsl     Addr, Hs.id, 3                  // its ID's entry: by_id = this slave
    mov     Scr, P_CTL + OFFSET(SlvCtl.by_id)
    add     Addr, Addr, Scr
    sbbo    Idx, Addr, 0, 1
    qbbc    CFG_ID_OK, Hs.flags, 5          // BISS_SLV_SF_IDL_AT_CTS
    set     IdlCts, IdlCts, Hs.id
CFG_ID_OK:
    // the table and the banks inside theirs
    ldi     Err, BISS_SLV_CFGERR_TABLE
    qbeq    CFG_TABLE_OK, Hs.table_len, 0
    add     Scr, Hs.table_start, Hs.table_len
    qblt    CFG_REFUSE, Scr, BISS_SLV_TABLE_ENTRIES
CFG_TABLE_OK:
    ldi     Err, BISS_SLV_CFGERR_BANKS
    add     Scr, Hs.bank0, Hs.banks
    qblt    CFG_REFUSE, Scr, BISS_SLV_POOL_BANKS

    // ---- its SlvCtl (the control-communication settings) ------------------------
    lsl     Addr, Idx, 3                    // P_CTL + 8 k
    mov     Scr, P_CTL
    add     Addr, Addr, Scr
    sbbo    Hs.flags, Addr, OFFSET(SlvCtl.flags), 1
    sbbo    Hs.id, Addr, OFFSET(SlvCtl.id), 1
    sbbo    Hs.reg_wait, Addr, OFFSET(SlvCtl.reg_wait), 1
    sbbo    Hs.banks, Addr, OFFSET(SlvCtl.banks), 1
    sbbo    Hs.bank0, Addr, OFFSET(SlvCtl.bank0), 1

    // ---- its SlvRun: the word left-aligned, the first bit at bit 63 ------------
    rsb     Bits, Hs.pos_bits, 64           // the position << (64 - position bits)
    sbbo    Bits, RunAddr, OFFSET(SlvRun.pshift), 1
    lbbo    &SH_LO, HostAddr, BISS_SLV_S_POSITION, 8
    mov     SH_K, Bits
    jal     RET_LEAF, SHL64
    sbbo    &SH_LO, RunAddr, OFFSET(SlvRun.pos_lo), 8
    lbbo    &SH_LO, HostAddr, BISS_SLV_S_STEP, 8
    jal     RET_LEAF, SHL64
    sbbo    &SH_LO, RunAddr, OFFSET(SlvRun.step_lo), 8
    // the life counter (0) and its step, 1 << (64 - n), and its field
    ldi     SH_LO, 0
    ldi     SH_HI, 0
    sbbo    &SH_LO, RunAddr, OFFSET(SlvRun.tail_lo), 8
    rsb     SH_K, NBits, 64
    qbeq    CFG_NO_LC, Hs.lc_bits, 0
    ldi     SH_LO, 1
CFG_NO_LC:
    jal     RET_LEAF, SHL64
    sbbo    &SH_LO, RunAddr, OFFSET(SlvRun.inc_lo), 8
    mov     SH_LO, 0xffffffff               // the field: 2^lc - 1 (all 32 bits: ~0)
    qbeq    CFG_LC_FIELD, Hs.lc_bits, 32
    ldi     SH_LO, 1
    lsl     SH_LO, SH_LO, Hs.lc_bits
    sub     SH_LO, SH_LO, 1
CFG_LC_FIELD:
    ldi     SH_HI, 0
    jal     RET_LEAF, SHL64
    sbbo    &SH_LO, RunAddr, OFFSET(SlvRun.lmask_lo), 8
    // nW right above the life counter, nE above nW: bit 64 - n + lc (+1)
    // of the left-aligned word, as (word, bit): word 1 the low, 2 the high
    rsb     Scr, NBits, 64
    add     Scr, Scr, Hs.lc_bits            // the bit above the life counter
    ldi     WordOut, 0                      // (ne_word, ne_bit, nw_word, nw_bit)
    qbbc    CFG_NW_DONE, Hs.flags, 1        // BISS_SLV_SF_NW
    jal     RET_LEAF, CFG_BIT_AT
    lsl     Scr2, Scr2, 16                  //   into nw_word, nw_bit
    or      WordOut, WordOut, Scr2
    add     Scr, Scr, 1
CFG_NW_DONE:
    qbbc    CFG_NE_DONE, Hs.flags, 0        // BISS_SLV_SF_NE
    jal     RET_LEAF, CFG_BIT_AT
    or      WordOut, WordOut, Scr2          //   into ne_word, ne_bit
CFG_NE_DONE:
    sbbo    WordOut, RunAddr, OFFSET(SlvRun.ne_word), 4
    sbbo    Hs.table_start, RunAddr, OFFSET(SlvRun.tab_start), 1
    sbbo    Hs.table_len, RunAddr, OFFSET(SlvRun.tab_len), 1
    ldi     Bits, 0
    sbbo    Bits, RunAddr, OFFSET(SlvRun.tab_idx), 1

    // ---- its BANK_CRC record: the polynomial and the start value
    // left-aligned, the CRC and data bits in the low half (frame.p SWITCH)
    ldi     RecPolyOut, 0
    mov     RecCrcOut, NBits
    qbeq    CFG_REC, Hs.crc_bits, 0
    rsb     Bits, Hs.crc_bits, 32
    lsl     RecPolyOut, Hs.crc_poly, Bits
    lsl     Scr2, Hs.crc_start, Bits
    lsl     Scr, Hs.crc_bits, 8
    or      RecCrcOut, RecCrcOut, Scr
    or      RecCrcOut, RecCrcOut, Scr2
CFG_REC:
    lsl     Xfr, Idx, 1
    xout    BANK_CRC, &RecPolyOut, 8
    ldi     Xfr, 0
    add     HostAddr, HostAddr, BISS_SLV_CFG_SLAVE_SIZE
    add     RunAddr, RunAddr, RUN_SIZE
    add     Idx, Idx, 1
    qbne    CFG_SLAVE, Idx, CSlaves

    // ---- accepted: the chain's settings and the registers of every phase ------
    mov     Chain.nslaves, CSlaves
    mov     Chain.idl, Idl
    mov     Chain.factor, CFactor
    mov     Chain.idl_cts, IdlCts
    ldi     Addr, P_NSLAVES
    sbbo    &Chain, Addr, 0, 4
    ldi     Addr, P_TMO_MIN
    sbbo    CTmoMin, Addr, 0, 4
    sbbo    CTimeout, Addr, 4, 4
    // the work after the timeout's end, counted into the timeout
    // (pru_slave/README.md, "Timeout")
    ldi     WordOut, WORK_PAD
    ldi     Addr, P_WORK_PAD
    sbbo    WordOut, Addr, 0, 4
    ldi     Addr, BISS_SLV_ST_WORK_PAD
    sbbo    WordOut, Addr, 0, 2
    // TMO_MAX, the timeout with no period known (the first frame, a frame
    // slower than the last): T - WORK_PAD - TMO_FIXED where that is still
    // over T / 1.1, longer than any MA half period a master may use with a
    // slave of timeout T (iC-MB4 datasheet, I306: T >= 55 % of the period);
    // else all of T (SL then rises WORK_PAD and TMO_FIXED later)
    add     Scr, WordOut, TMO_FIXED         // pad + fixed
    lsl     Scr2, Scr, 3                    // x 11 <= T?
    add     Scr2, Scr2, Scr
    add     Scr2, Scr2, Scr
    add     Scr2, Scr2, Scr
    mov     WordOut, CTimeout
    qbgt    CFG_TMO_MAX, CTimeout, Scr2     // 11 (pad + fixed) > T: all of T
    sub     WordOut, WordOut, Scr
CFG_TMO_MAX:
    add     WordOut, WordOut, 2             // turns of 4 cycles, the nearest
    lsr     WordOut, WordOut, 2
    max     WordOut, WordOut, 1
    mov     TMO_MAX, WordOut
    mov     TMO_ADAPT, WordOut
    ldi     GUARD, 0
    mov     BUSY_CYC, CBusyCyc              // one cycle less: the frame's reads of CYCLE
    qbeq    CFG_BUSY, BUSY_CYC, 0           // are a cycle apart at most (frame.p)
    sub     BUSY_CYC, BUSY_CYC, 1
CFG_BUSY:
    mov     BUSY_CLK, CBusyClk
    lsl     END_SLOT, Idx, 1                // (Idx = the slaves now)
    mov     PRE_WORD, 0x80000000            // the start bit, CDS 0
    ldi     CTRL_FLAGS, 0                   // control communication from the start
    // a clear control state
    ldi     WordOut, 0
    ldi     Addr, P_CTRL
    sbbo    WordOut, Addr, 0, 4
    sbbo    WordOut, Addr, 4, 4
    sbbo    WordOut, Addr, 8, 4
    sbbo    WordOut, Addr, 12, 4
    sbbo    CtlAll, Addr, OFFSET(CtrlState.all), 1  // none armed: 14 zeros first
    // the status: counters 0, no CDM yet, no command or register yet
    ldi     Addr, BISS_SLV_ST_TIMEOUT
    sbbo    CTimeout, Addr, 0, 4
    ldi     Addr, BISS_SLV_ST_FRAMES
    ldi     Scr2, BISS_SLV_ST_TIMEOUT
CFG_CLEAR:
    sbbo    WordOut, Addr, 0, 4
    add     Addr, Addr, 4
    qbgt    CFG_CLEAR, Addr, Scr2           // ST_TIMEOUT > Addr
    ldi     Addr, BISS_SLV_ST_WORK
    sbbo    WordOut, Addr, 0, 2
    ldi     Addr, BISS_SLV_ST_SLAVE0
    ldi     Scr2, BISS_SLV_ST_END
CFG_CLEAR_SLAVES:
    sbbo    WordOut, Addr, 0, 4
    add     Addr, Addr, 4
    qbgt    CFG_CLEAR_SLAVES, Addr, Scr2
    ldi     Byte0xff, 0xff
    ldi     Addr, BISS_SLV_ST_CDM
    sbbo    Byte0xff, Addr, 0, 1
    ldi     Bits, MA_IN_BIT                 // (cleared with the word it is in)
    ldi     Addr, BISS_SLV_ST_MA_BIT
    sbbo    Bits, Addr, 0, 1
    ldi     Addr, BISS_SLV_ST_SLAVE0 + BISS_SLV_SS_LAST_CMD
    ldi     Idx, 0
CFG_STATUS:
    sbbo    Byte0xff, Addr, 0, 1            // last command
    sbbo    Byte0xff, Addr, 1, 1            // last register
    add     Addr, Addr, BISS_SLV_ST_SLAVE_SIZE
    add     Idx, Idx, 1
    qbne    CFG_STATUS, Idx, BISS_SLV_MAX_SLAVES
    // the verdict, the first frame's words (BUILD keeps r23, NewSeq), then
    // the sequence number
    ldi     Addr, BISS_SLV_ST_CFG_ERROR
    ldi     WordOut, BISS_SLV_CFGERR_NONE
    sbbo    WordOut, Addr, 0, 4
    ldi     Bits, 0                         // (between.p's Advance: no step first,
    ldi     Idx, 1                          //   RecAhead: FRAME_REC is for frame 1)
    jal     RET_SUB, BUILD
    ldi     Addr, BISS_SLV_ST_CFG_ACK
    sbbo    NewSeq, Addr, 0, 4
    jmp     READY

// ---- refused: no slave answers until a configuration is accepted -----------
CFG_REFUSE:
    ldi     WordOut, 0
    ldi     Addr, P_NSLAVES
    sbbo    WordOut, Addr, 0, 4             // not running
    mov     WordOut, Err
    ldi     Addr, BISS_SLV_ST_CFG_ERROR
    sbbo    WordOut, Addr, 0, 4
    ldi     Addr, BISS_SLV_ST_CFG_ACK
    sbbo    NewSeq, Addr, 0, 4
    jmp     WAIT_CONFIG

// CFG_BIT_AT: where bit Scr (0..63) of the left-aligned word is, as
// Scr2 = word (1 low, 2 high) | bit << 8. Returns through RET_LEAF.
CFG_BIT_AT:
    and     Scr2, Scr, 31
    lsl     Scr2, Scr2, 8
    qble    CFG_BIT_HI, Scr, 32             // 32 <= bit
    or      Scr2, Scr2, 1
    jmp     RET_LEAF
CFG_BIT_HI:
    or      Scr2, Scr2, 2
    jmp     RET_LEAF
.leave config
