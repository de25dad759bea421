// startup.p - start-up and the main loop: clear the private RAM, set up
// CTPPR0, the shift mode and the scratch-pad; then wait for a
// configuration, a trigger, the IEP or the host, and start a frame.
// Included by biss_master.p; nothing in it is clocked.

.enter startup
.assign Word, r0, r0, Zeros                 // 0, the first of r0..r29 cleared: a store of zeros
.assign Word, r1, r1, PruNum                // PRU_NUM, stored with the magic after it
.assign Word, r2, r2, Value                 // a word to store
.assign Word, r28, r28, Addr                // an address: CTPPR0, then the private area's
.assign Word, r29, r29, C28Page             // C28's page (CTPPR0[15:0])
START:
    ldi     Zeros, 0                        // R0[4:0] = 0: no XFR shift, whatever SPP holds
    zero    &Zeros, 120                     // r0..r29
    mov     Addr, PRU_CTPPR0
    ldi     C28Page, BISS_PRIV >> 8
    sbbo    C28Page, Addr, 0, 4             // C28 -> the private area
    set     MA_OUT, MA_OUT, MA_BIT          // MA idles high
    // status and private areas start clear: stores of r0.. (zero)
    sbco    Zeros, c24, BISS_ST_SEQ, BISS_ST_END - BISS_ST_SEQ
    sbco    Zeros, c24, BISS_ST_OFF_GRID, BISS_ST_LINK_END - BISS_ST_OFF_GRID
    ldi     Addr, BISS_PRIV
    loop    CLEAR_PRIV, (BISS_PRIV_END - BISS_PRIV) / 64
    sbbo    Zeros, Addr, 0, 64
    add     Addr, Addr, 64
CLEAR_PRIV:
    not     Value, Zeros                    // ~0: no configuration applied yet
    sbco    Value, c24, BISS_ST_CFG_ACK, 4
    ldi     PruNum, PRU_NUM                 // the PRU this image is for, and last the
    mov     Value, BISS_MAGIC               // magic: a host that sees it sees a clear status
    sbco    PruNum, c24, BISS_ST_PRU, 8
    // IEP: count PRU cycles (increment 1), free running
    ldi     Value, 0x0111
    sbco    Value, c26, IEP_GLOBAL_CFG, 4
    // Scratch pad: XIN/XOUT shifted by R0[4:0] registers (the slaves'
    // result slots: CFG_PROC); PRU0 keeps priority over PRU1 on a bank
    // (docs/silicon-assumptions.md A6), though each PRU uses only its own
    // (XFR_BANK). Both PRUs write this same value.
    ldi     Value, SPP_XFR_SHIFT
    sbco    Value, c4, CFG_SPP, 4
.leave startup

// ---- the main loop: configuration, trigger, frame --------------------------
// Its names, and those of the frame's set-up that reopens it (FRAME,
// SSI_FRAME). r2 is read word by word: the configuration's
// sequence number, then P_PROC's word, then P_NSLAVES' two bytes over its
// upper half (the trigger stays there until the frame starts).
.enter main_loop
.assign Word, r2, r2, CfgSeq                // BISS_CFG_SEQ: the host's configuration, if new
.assign Word, r2, r2, PrivProc              // P_PROC's word: processing-time limit, TrainDue, Running
.assign Byte, r2.b2, r2.b2, TrainDue        //   a training frame is due (P_TRAIN_DUE)
.assign Byte, r2.b3, r2.b3, Running         //   the configuration is running (P_RUNNING)
.assign Byte, r2.b2, r2.b2, NSlaves         // P_NSLAVES: slaves, and after it
.assign Byte, r2.b3, r2.b3, Trigger         //   the trigger (BISS_TRIG_*), kept to IEP_START
.assign Half, r2.w0, r2.w0, SsiAck          // P_SSI's ACK position (FRAME: 0 for BiSS-C)
.assign Word, r3, r3, CfgAck                // BISS_ST_CFG_ACK: the last configuration applied
.assign Word, r3, r3, HostCmd               // BISS_CMD_TRIGGER
MAIN:
    lbco    CfgSeq, c24, BISS_CFG_SEQ, 4
    lbco    CfgAck, c24, BISS_ST_CFG_ACK, 4
    qbeq    MAIN_CFG_OK, CfgSeq, CfgAck
    qbne    APPLY_CONFIG, CfgSeq, 0         // (0: the host has written none yet)
MAIN_CFG_OK:
    lbco    &PrivProc, c28, P_PROC, P_PROC_END - P_PROC
    qbeq    MAIN, Running, 0                // not running (no or a refused configuration)
    qbeq    TRIGGER_DONE, TrainDue, 0
    jmp     TRAIN                           // a training frame is due first
TRIGGER_DONE:
    // Trigger, for FRAME and SSI_FRAME (SLAVE_IDLE, the P_SSI loads and
    // FRAME_REGS keep it): the host's, or a free-run or IEP frame at once
    // (IEP_START waits for its period)
    lbco    &NSlaves, c28, P_NSLAVES, P_REC_END - P_NSLAVES
    qbne    FRAME, Trigger, BISS_TRIG_HOST

WAIT_HOST:
    lbco    HostCmd, c24, BISS_CMD_TRIGGER, 4
    qbeq    MAIN, HostCmd, 0
    ldi     HostCmd, 0
    sbco    HostCmd, c24, BISS_CMD_TRIGGER, 4
    jmp     FRAME
