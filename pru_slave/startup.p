// startup.p - start-up, the wait for a configuration, and the idle wait
// for a frame. Included by biss_encoder.p; nothing in it is clocked.

.enter startup
.assign Word, r0, r0, Zeros                 // 0: the first of r0..r29 cleared, a store of zeros
.assign Word, r1, r1, Control               // the CONTROL register
.assign Word, r2, r2, Value                 // a word to store
.assign Word, r3, r3, PruNum                // PRU_NUM and, after it, the magic
.assign Word, r4, r4, Magic
.assign Word, r5, r5, Addr                  // an address in data RAM
.assign Word, r6, r6, Left                  // words left to clear
START:
    ldi     Zeros, 0                        // R0[4:0] = 0: no XFR shift for the ZERO
    zero    &Zeros, 120                     // r0..r29
    ldi     SL_OUT, 0                       // SL low: no slave until a configuration
    mov     CTRL_BASE, CTRL_ADDR
    // the cycle counter (CYCLE) on: the frame measures the MA period and
    // the processing time with it
    lbbo    Control, CTRL_BASE, CTRL_CONTROL, 4
    set     Control, Control, CTRL_CTR_EN
    sbbo    Control, CTRL_BASE, CTRL_CONTROL, 4
    // GPI in direct mode (MA is a plain input bit); the scratch-pad shift
    // on (the records, biss_encoder.p), the value the master writes too
    sbco    Zeros, c4, GPCFG_OWN, 4
    ldi     Value, SPP_XFR_SHIFT
    sbco    Value, c4, CFG_SPP, 4
    // status, frame record and private area clear (ST_MAGIC ..
    // BISS_SLV_PRIV_END, whole words)
    ldi     Addr, BISS_SLV_ST_MAGIC
    ldi     Left, (BISS_SLV_PRIV_END - BISS_SLV_ST_MAGIC) / 4
START_CLEAR:
    sbbo    Zeros, Addr, 0, 4
    add     Addr, Addr, 4
    sub     Left, Left, 1
    qbne    START_CLEAR, Left, 0
    not     Value, Zeros                    // ~0: no configuration applied yet
    ldi     Addr, BISS_SLV_ST_CFG_ACK
    sbbo    Value, Addr, 0, 4
    ldi     PruNum, PRU_NUM                 // the PRU this image is for, and last the
    mov     Magic, BISS_SLV_MAGIC           // magic: a host that sees it sees a clear status
    ldi     Addr, BISS_SLV_ST_PRU
    sbbo    PruNum, Addr, 0, 4
    ldi     PruNum, MA_IN_BIT               // and the R31 bit MA comes in on
    ldi     Addr, BISS_SLV_ST_MA_BIT
    sbbo    PruNum, Addr, 0, 1
    ldi     Addr, BISS_SLV_ST_MAGIC
    sbbo    Magic, Addr, 0, 4
.leave startup

// ---- no configuration in force: SL low, wait for one ------------------------
.enter wait_config
.assign Word, r1, r1, Seq                   // CFG_SEQ
.assign Word, r2, r2, Ack                   // ST_CFG_ACK
.assign Word, r3, r3, Addr
WAIT_CONFIG:
    ldi     SL_OUT, 0
WAIT_CONFIG_POLL:
    ldi     Addr, BISS_SLV_CFG_SEQ
    lbbo    Seq, Addr, 0, 4
    ldi     Addr, BISS_SLV_ST_CFG_ACK
    lbbo    Ack, Addr, 0, 4
    qbeq    WAIT_CONFIG_POLL, Seq, Ack
    qbeq    WAIT_CONFIG_POLL, Seq, 0        // (0: the host has written none yet)
    jmp     APPLY_CONFIG
.leave wait_config

// ---- READY: the registers a frame starts from, SL high, idle ----------------
// Entered after every frame (between.p) and every configuration accepted
// (config.p).
.using frame
READY:
    mov     Tmo, TMO_MAX
    mov     TmoLeft, TMO_MAX
    mov     DataHi, PRE_WORD
    ldi     Left, 2
    ldi     Slot, 0
    ldi     SL_OUT, 1
.leave frame

// ---- idle: SL high, wait for MA to fall --------------------------------------
// After a frame that ended with CDM = 1, MA is low until the master has
// seen SL high: first wait for it to rise (a rise while idle begins no
// frame). Then the first fall begins one. Each 4-cycle turn looks at MA
// twice; every IDLE_CHECK turns (1.3 ms) a look at the host's CFG_SEQ, so
// a configuration is taken even while no frames come. That look delays a
// frame's start by up to 9 cycles: the first rise, which sends nothing,
// may then be seen that much late, never missed (at 10 MHz it comes 10
// cycles after the fall).
.enter idle
.assign Half, r11.w0, r11.w0, IdleLeft      // turns to the next look at the host
.assign Word, r12, r12, Seq
.assign Word, r13, r13, Ack
.assign Word, r24, r24, Addr
IDLE:
    ldi     IdleLeft, IDLE_CHECK
IDLE_LOW:
    qbbs    IDLE_HIGH, MA_IN, MA_IN_BIT
    sub     IdleLeft, IdleLeft, 1
    qbbs    IDLE_HIGH, MA_IN, MA_IN_BIT
    qbne    IDLE_LOW, IdleLeft, 0
    jal     RET_SUB, HOST_CHECK
    qba     IDLE_LOW
IDLE_HIGH:
    qbbc    FRAME_START, MA_IN, MA_IN_BIT
    sub     IdleLeft, IdleLeft, 1
    qbbc    FRAME_START, MA_IN, MA_IN_BIT
    qbne    IDLE_HIGH, IdleLeft, 0
    jal     RET_SUB, HOST_CHECK
    qba     IDLE_HIGH

// A new configuration (CFG_SEQ moved): APPLY_CONFIG, which ends in READY
// or WAIT_CONFIG; otherwise back to the idle poll.
HOST_CHECK:
    ldi     Addr, BISS_SLV_CFG_SEQ
    lbbo    Seq, Addr, 0, 4
    ldi     Addr, BISS_SLV_ST_CFG_ACK
    lbbo    Ack, Addr, 0, 4
    qbeq    HOST_SAME, Seq, Ack
    jmp     APPLY_CONFIG
HOST_SAME:
    jmp     RET_SUB
.leave idle
