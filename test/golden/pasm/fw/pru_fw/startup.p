// startup.p - start-up and the main loop: clear the private RAM, set up
// CTPPR0, the shift mode and the scratch-pad; then wait for a
// configuration, a trigger, the IEP or the host, and start a frame.
// Included by biss_master.p; nothing in it is clocked.

START:
    ldi     r0, 0                           // R0[4:0] = 0: no XFR shift, whatever SPP holds
    zero    &r0, 120                        // r0..r29
    mov     r28, PRU_CTPPR0
    ldi     r29, BISS_PRIV >> 8
    sbbo    r29, r28, 0, 4                  // C28 -> the private area
    set     r30, r30, MA_BIT                // MA idles high
    // status and private areas start clear: stores of r0.. (zero)
    sbco    r0, c24, BISS_ST_SEQ, BISS_ST_END - BISS_ST_SEQ
    ldi     r28, BISS_PRIV
    loop    CLEAR_PRIV, (BISS_PRIV_END - BISS_PRIV) / 64
    sbbo    r0, r28, 0, 64
    add     r28, r28, 64
CLEAR_PRIV:
    not     r2, r0                          // ~0: no configuration applied yet
    sbco    r2, c24, BISS_ST_CFG_ACK, 4
    ldi     r1, PRU_NUM                     // the PRU this image is for, and last the
    mov     r2, BISS_MAGIC                  // magic: a host that sees it sees a clear status
    sbco    r1, c24, BISS_ST_PRU, 8
    // IEP: count PRU cycles (increment 1), free running
    ldi     r2, 0x0111
    sbco    r2, c26, IEP_GLOBAL_CFG, 4
    // Scratch pad: XIN/XOUT shifted by R0[4:0] registers (the slaves'
    // result slots: CFG_PROC); PRU0 keeps priority over PRU1 on a bank
    // (docs/silicon-assumptions.md A6), though each PRU uses only its own
    // (XFR_BANK). Both PRUs write this same value.
    ldi     r2, SPP_XFR_SHIFT
    sbco    r2, c4, CFG_SPP, 4

// ---- the main loop: configuration, trigger, frame --------------------------
MAIN:
    lbco    r2, c24, BISS_CFG_SEQ, 4
    lbco    r3, c24, BISS_ST_CFG_ACK, 4
    qbeq    MAIN_CFG_OK, r2, r3
    qbne    APPLY_CONFIG, r2, 0             // (0: the host has written none yet)
MAIN_CFG_OK:
    lbco    r2, c28, P_PROC, P_SPARE - P_PROC
    qbeq    MAIN, r2.b3, 0                  // not running (no or a refused configuration)
    qbeq    TRIGGER_DONE, r2.b2, 0
    jmp     TRAIN                           // a training frame is due first
TRIGGER_DONE:
    // r2.b3 = the trigger, for IEP_ALIGN_IF (SLAVE_IDLE, the P_SSI loads and
    // FRAME_REGS keep it)
    lbco    r2.w2, c28, P_NSLAVES, P_REC_END - P_NSLAVES
    qbeq    WAIT_HOST, r2.b3, BISS_TRIG_HOST
    qbeq    WAIT_IEP, r2.b3, BISS_TRIG_IEP
    qbne    FRAME, r2.b3, BISS_TRIG_IEP_FOLLOW  // free-run
// The other PRU owns the IEP and its CMP0 status: a new period is a count
// below IEP_ALIGN (a MAIN turn is far shorter than IEP_ALIGN). From there
// on the owner's path: the same loads, then IEP_AT_ALIGN, so both frames
// start on the same count; a frame too late for it goes at once, as the
// owner's does.
WAIT_FOLLOW:
    lbco    r3, c26, IEP_COUNT, 4
    qble    MAIN, r3, IEP_ALIGN             // count >= IEP_ALIGN: not yet
    ldi     r2.b3, BISS_TRIG_IEP            // aligned as the owner's (IEP_ALIGN_IF)
    jmp     FRAME
WAIT_IEP:
    lbco    r3, c26, IEP_CMP_STATUS, 4
    qbbc    MAIN, r3, 0
    sbco    r3, c26, IEP_CMP_STATUS, 4      // clear the CMP0 hit (write 1 to clear: any
                                            // other compare's too; none is used)
    jmp     FRAME                           // which aligns before period 0 (IEP_ALIGN_IF)

// The hit was seen up to one turn of MAIN late, and the loads before a
// frame (FRAME, FRAME_REGS, SSI_FRAME) stall while the host reads the data
// RAM (docs/silicon-assumptions.md A5). So every IEP-triggered frame starts
// at the same count after the period's reset instead, with only this code,
// no data-RAM access, between the count's read and period 0. Entered by
// `jal r12.w0, IEP_AT_ALIGN` once the frame's last load is done
// (IEP_ALIGN_IF); it writes r3 and returns through r12.w0.
IEP_AT_ALIGN:
    lbco    r3, c26, IEP_COUNT, 4
    rsb     r3, r3, IEP_ALIGN               // d: cycles to wait; none if later
    qbne    IEP_ALIGNED, r3.w2, 0           // upper half set: late, go now
    // 3 + d cycles for every d, from single-cycle instructions only (no
    // LOOP of one instruction, no count of 0: docs/silicon-assumptions.md)
    qbbc    IEP_EVEN, r3, 0
    mov     r0, r0                          // d odd: one more
IEP_EVEN:
    lsr     r3, r3, 1
    qbeq    IEP_ALIGNED, r3, 0
IEP_WAIT:
    sub     r3, r3, 1                       // 2 cycles a turn
    qbne    IEP_WAIT, r3, 0
IEP_ALIGNED:
    jmp     RET_SUB

// An IEP-triggered frame (r2.b3 = BISS_TRIG_IEP: TRIGGER_DONE, WAIT_FOLLOW)
// aligns here, right after its last load; any other goes on to `next` at
// once (one cycle more, before the frame: not clocked).
.macro IEP_ALIGN_IF
.mparam next
    qbne    next, r2.b3, BISS_TRIG_IEP
    jal     RET_SUB, IEP_AT_ALIGN
.endm

WAIT_HOST:
    lbco    r3, c24, BISS_CMD_TRIGGER, 4
    qbeq    MAIN, r3, 0
    ldi     r3, 0
    sbco    r3, c24, BISS_CMD_TRIGGER, 4
    jmp     FRAME
