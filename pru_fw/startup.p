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
// SSI_FRAME: IEP_ALIGN_IF). r2 is read word by word: the configuration's
// sequence number, then P_PROC's word, then P_NSLAVES' two bytes over its
// upper half (the trigger stays there until the frame starts).
.enter main_loop
.assign Word, r2, r2, CfgSeq                // BISS_CFG_SEQ: the host's configuration, if new
.assign Word, r2, r2, PrivProc              // P_PROC's word: processing-time limit, TrainDue, Running
.assign Byte, r2.b2, r2.b2, TrainDue        //   a training frame is due (P_TRAIN_DUE)
.assign Byte, r2.b3, r2.b3, Running         //   the configuration is running (P_RUNNING)
.assign Byte, r2.b2, r2.b2, NSlaves         // P_NSLAVES: slaves, and after it
.assign Byte, r2.b3, r2.b3, Trigger         //   the trigger (BISS_TRIG_*), kept to IEP_ALIGN_IF
.assign Half, r2.w0, r2.w0, SsiAck          // P_SSI's ACK position (FRAME: 0 for BiSS-C)
.assign Word, r3, r3, CfgAck                // BISS_ST_CFG_ACK: the last configuration applied
.assign Word, r3, r3, IepCount              // the IEP count (IEP follow)
.assign Word, r3, r3, IepStatus             // the IEP's CMP status
.assign Word, r3, r3, HostCmd               // BISS_CMD_TRIGGER
MAIN:
    lbco    CfgSeq, c24, BISS_CFG_SEQ, 4
    lbco    CfgAck, c24, BISS_ST_CFG_ACK, 4
    qbeq    MAIN_CFG_OK, CfgSeq, CfgAck
    qbne    APPLY_CONFIG, CfgSeq, 0         // (0: the host has written none yet)
MAIN_CFG_OK:
    lbco    &PrivProc, c28, P_PROC, P_SPARE - P_PROC
    qbeq    MAIN, Running, 0                // not running (no or a refused configuration)
    qbeq    TRIGGER_DONE, TrainDue, 0
    jmp     TRAIN                           // a training frame is due first
TRIGGER_DONE:
    // Trigger, for IEP_ALIGN_IF (SLAVE_IDLE, the P_SSI loads and
    // FRAME_REGS keep it)
    lbco    &NSlaves, c28, P_NSLAVES, P_REC_END - P_NSLAVES
    qbeq    WAIT_HOST, Trigger, BISS_TRIG_HOST
    qbeq    WAIT_IEP, Trigger, BISS_TRIG_IEP
    qbne    FRAME, Trigger, BISS_TRIG_IEP_FOLLOW // free-run
// The other PRU owns the IEP and its CMP0 status: a new period is a count
// below IEP_ALIGN (a MAIN turn is far shorter than IEP_ALIGN). From there
// on the owner's path: the same loads, then IEP_AT_ALIGN, so both frames
// start on the same count; a frame too late for it goes at once, as the
// owner's does.
WAIT_FOLLOW:
    lbco    IepCount, c26, IEP_COUNT, 4
    qble    MAIN, IepCount, IEP_ALIGN       // count >= IEP_ALIGN: not yet
    ldi     Trigger, BISS_TRIG_IEP          // aligned as the owner's (IEP_ALIGN_IF)
    jmp     FRAME
WAIT_IEP:
    lbco    IepStatus, c26, IEP_CMP_STATUS, 4
    qbbc    MAIN, IepStatus, 0
    sbco    IepStatus, c26, IEP_CMP_STATUS, 4 // clear the CMP0 hit (write 1 to clear: any
                                            // other compare's too; none is used)
    jmp     FRAME                           // which aligns before period 0 (IEP_ALIGN_IF)

// The hit was seen up to one turn of MAIN late, and the loads before a
// frame (FRAME, FRAME_REGS, SSI_FRAME) stall while the host reads the data
// RAM (docs/silicon-assumptions.md A5). So every IEP-triggered frame starts
// at the same count after the period's reset instead, with only this code,
// no data-RAM access, between the count's read and period 0. Entered by
// `jal RET_SUB, IEP_AT_ALIGN` once the frame's last load is done
// (IEP_ALIGN_IF); it writes AlignWait (r3) and returns through RET_SUB.
.enter iep_align
.assign Word, r3, r3, AlignWait             // cycles to wait for IEP_ALIGN, then turns of 2
.assign Half, r3.w2, r3.w2, AlignLate       // its upper half: set when the count is past it
IEP_AT_ALIGN:
    lbco    AlignWait, c26, IEP_COUNT, 4
    rsb     AlignWait, AlignWait, IEP_ALIGN // d: cycles to wait; none if later
    qbne    IEP_ALIGNED, AlignLate, 0       // upper half set: late, go now
    // 3 + d cycles for every d, from single-cycle instructions only (no
    // LOOP of one instruction, no count of 0: docs/silicon-assumptions.md)
    qbbc    IEP_EVEN, AlignWait, 0
    PAD                                     // d odd: one more
IEP_EVEN:
    lsr     AlignWait, AlignWait, 1
    qbeq    IEP_ALIGNED, AlignWait, 0
IEP_WAIT:
    sub     AlignWait, AlignWait, 1         // 2 cycles a turn
    qbne    IEP_WAIT, AlignWait, 0
IEP_ALIGNED:
    jmp     RET_SUB
.leave iep_align

// An IEP-triggered frame (Trigger = BISS_TRIG_IEP: TRIGGER_DONE, WAIT_FOLLOW)
// aligns here, right after its last load; any other goes on to `next` at
// once (one cycle more, before the frame: not clocked).
.macro IEP_ALIGN_IF
.mparam next
    qbne    next, Trigger, BISS_TRIG_IEP
    jal     RET_SUB, IEP_AT_ALIGN
.endm

WAIT_HOST:
    lbco    HostCmd, c24, BISS_CMD_TRIGGER, 4
    qbeq    MAIN, HostCmd, 0
    ldi     HostCmd, 0
    sbco    HostCmd, c24, BISS_CMD_TRIGGER, 4
    jmp     FRAME
