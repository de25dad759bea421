// biss_master.p - BiSS-C interface master for either PRU of an AM335x/AM437x
// PRU-ICSS (pasm dialect).
//
// MA is R30 bit MA_BIT (default 1), SL is R31 bit 0 in 28-bit shift mode,
// sampled at 8x the MA rate. The host configures and reads results through
// the PRU's own data RAM, laid out in include/biss/biss_shm.h. Assembled
// once per PRU (-DPRU_NUM=0, the default, or -DPRU_NUM=1): the PRU's CONTROL
// block, GPCFG and scratch-pad bank are in the instruction words, so each
// image runs only on the PRU it was built for (it says which in BISS_ST_PRU).
//
// A frame (MA period p = 0, 1, ...; each period exactly 2H PRU cycles):
//   WAIT_ACK    clock until the newest 8 samples show SL low (the ACK edge);
//               the position of that edge (ones before it) gives this
//               frame's line delay in bit/8, averaged with the last 3 frames
//   LAG         clock while the sample point and lag are derived from it
//   START_WAIT  clock while the slave is busy; count it, abort over the limit
//   CDS         read the CDS bit, load the first slave's record
//   slaves      data bits and CRC bits of each slave, CRC computed per bit;
//               clocking stops by itself after the clock that follows the
//               last bit (on it the slave starts its timeout, SL low), and
//               the remaining bits are read from the samples: no extra
//               clocks for the line delay
// Then, outside the clocked part: CDM on MA, CRC verdicts, publication,
// and the wait for the slave's timeout to end (SL high).
//
// The clocked periods are in biss_periods.hp; their timing rules are
// described there.

.origin 0
.entrypoint START

#include "../include/biss/biss_shm.h"

#ifndef MA_BIT
#define MA_BIT          1               // R30 bit driving MA: 0..7
#endif
#ifndef PRU_NUM
#define PRU_NUM         0               // the PRU of its PRU-ICSS this image is for: 0 or 1
#endif
// This PRU's scratch-pad bank: PRU0 bank 0 (XFR device 10), PRU1 bank 1 (11).
// Both PRUs on one bank in one cycle stall PRU1 (docs/pru-facts.md §3), and
// the bank is part of the XIN/XOUT word: one bank each, never the other's.
// (-DXFR_BANK=n only for test_e2e_twopru's image that breaks this rule.)
#ifndef XFR_BANK
#define XFR_BANK        (10 + PRU_NUM)
#endif
#define MA_MASK         (1 << MA_BIT)
#define LAG             2               // extra whole periods between a bit and its read
#define MAJORITY5       0xfee8e880      // bit k set: three or more of k's five bits are 1
#define IDLE_MASK       0x0f            // R31 samples that must all be high for SL idle: half
                                        // a period, longer than any glitch of under 3 samples
#define IDLE_TURNS      25000           // SL idle polls (4 cycles): 500 us, then no slave

// PRU-ICSS registers
#define GPCFG0          0x08            // CFG (C4); GPCFG1 at 0x0c for PRU1 (docs/pru-facts.md §4.5)
#define GPCFG_OWN       (GPCFG0 + 4 * PRU_NUM)
#define SHIFT_MODE      2               // GPCFG GPI_MODE: 28-bit shift
#define IEP_GLOBAL_CFG  0x00            // IEP (C26)
#define IEP_COUNT       0x0c
#define IEP_CMP_CFG     0x40
#define IEP_CMP_STATUS  0x44
#define IEP_CMP0        0x48
// IEP count at which periodic frames start (IEP_AT_ALIGN). From the CMP0
// reset to the count's read: at worst a turn of MAIN, then FRAME,
// FRAME_REGS (and SSI_FRAME), 52 to 60 cycles with 7 or 8 data-RAM loads.
// Each load stalls while the host reads the data RAM (docs/silicon-
// assumptions.md A5), by how much TI does not say, so the margin is wide:
// measured, the frames stay aligned up to a 22-cycle stall on every load
// (the e2e fw suite under --contend 1,22; the suites' harshest is 2,8,
// TIMING.md's plausible host 40,1). Later still, the frame goes at once.
#define IEP_ALIGN       192

// Firmware-private data RAM, reached through C28 (CTPPR0 points it at
// BISS_PRIV, since burst offsets are 8 bits). Offsets from BISS_PRIV:
#define P_RECORDS       0x00                // 68 bytes: the image of r13..r29
#define P_DELAYS        0x44                // u32: r0 (the tails: DLY_* entry, flag, turns)
#define P_HIST          0x48                // u16 h0, h1, h2 (last ACK positions), u16 K
#define P_HSUM          0x50                // u32: h0 + h1 + h2 + 2
#define P_BUF           0x54                // u32: result buffer being filled (0/1)
#define P_NSLAVES       0x58                // u8 slaves, u8 trigger, u8 REC_BASE + 8 slaves,
                                            //   u8 frames in the average
#define P_HALF          0x5c                // u16 H, u16 ACK limit (periods x 8)
#define P_PROC          0x60                // u16 processing-time limit, u8 training due, u8 running
                                            // 0x64: 4 bytes free
#define P_CD            0x68                // 20 bytes: control communication state:
                                            //   u32 CD_CMD being run (0: none), u16 next step,
                                            //   u16 step answered by this frame's CDS (+1, 0: none),
                                            //   u16 frames with CDM 0 in a row, u16 frames in a WAIT,
                                            //   u8 CDM edge for CDS 0, u8 its change for CDS 1,
                                            //   u16 program length, u8 CRC_M, u8 CRC_S, u8 flags
                                            //   (CD_F_*, error pending << 4), u8 bytes transferred
#define P_CDM           (P_CD + 12)
#define P_SSI           0x7c                // u16 the ACK position an SSI frame reads by
                                            //   (0: BiSS-C), u16 MA edges after period 0
#define P_SLAVES        0x80                // 8 x 16: mask lo, mask hi, residue, [n, w, ew, flags]
#define PRU_CTPPR0      (0x22028 + 0x2000 * PRU_NUM)    // C28 = 0x00nnnn00, nnnn = CTPPR0[15:0]:
                                            // PRU1's CONTROL block is 0x2000 above PRU0's (§5.1)
#define CFG_SPP         0x34                // CFG (C4): scratch-pad priority and shift
#define SPP_XFR_SHIFT   2                   // XFR_SHIFT_EN (bit 1) with PRU1_PAD_HP_EN (bit 0) 0
#define XFR_SLOT        3                   // a slave's result: 3 registers of the bank (r4..r6)

// (after the equates: macro bodies take equates as they are read)
#include "biss_periods.hp"
#define REC_BASE        52                  // register-file byte address of r13

// ============================================================================
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
    lbco    r2, c28, P_PROC, 4
    qbeq    MAIN, r2.b3, 0                  // not running (no or a refused configuration)
    qbeq    TRIGGER_DONE, r2.b2, 0
    jmp     TRAIN                           // a training frame is due first
TRIGGER_DONE:
    lbco    r2.w2, c28, P_NSLAVES, 2        // r2.b3 = the trigger, for IEP_ALIGN_IF (SLAVE_IDLE,
                                            // the P_SSI loads and FRAME_REGS keep it)
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
    jmp     r12.w0

// An IEP-triggered frame (r2.b3 = BISS_TRIG_IEP: TRIGGER_DONE, WAIT_FOLLOW)
// aligns here, right after its last load; any other goes on to `next` at
// once (one cycle more, before the frame: not clocked).
.macro IEP_ALIGN_IF
.mparam next
    qbne    next, r2.b3, BISS_TRIG_IEP
    jal     r12.w0, IEP_AT_ALIGN
.endm

WAIT_HOST:
    lbco    r3, c24, BISS_CMD_TRIGGER, 4
    qbeq    MAIN, r3, 0
    ldi     r3, 0
    sbco    r3, c24, BISS_CMD_TRIGGER, 4
    jmp     FRAME

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
    sbbo    r6, r27, 0, 16                  // r6..r9
    add     r27, r27, 16
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
    // The tails of the half periods (DELAY_A in biss_periods.hp): none at
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
    sbco    r0, c28, P_DELAYS, 4
    // K = N + 2 - LAG: the clocks after the start bit's period are the CDS,
    // the N bits and one more, on which the slave starts its timeout (SL
    // low); LAG of them are already out when the start bit is seen.
    ldi     r3, 0                           // history empty (training fills it)
    sub     r4, r24, LAG - 2
    lsl     r4, r4, 16                      // and K
    sbco    r3, c28, P_HIST, 8
    mov     r2, r20.w2                      // slaves, trigger, -, frames in the average (0)
    lsl     r2.b2, r20.b2, 3                // the end record's register-file address
    add     r2.b2, r2.b2, REC_BASE
    sbco    r2, c28, P_NSLAVES, 4
    // ACK limit in periods x 8: (BISS_MAX_DELAY_NS / 10 / H + 4) x 8
    mov     r5, BISS_MAX_DELAY_NS / 10
    mov     r6, r20.w0
    ldi     r7, 4
    jal     r0.w2, DIVIDE
    lsl     r7, r7, 16 + 3                  // to w2
    mov     r7.w0, r20.w0
    sbco    r7, c28, P_HALF, 4
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
    sbco    r27, c28, P_SSI, 4
    sbco    r2, c28, P_PROC, 4
    sbco    r19, c4, GPCFG_OWN, 4           // shift mode at 8x the new rate (FACTOR_FOUND)
    ldi     r28, BISS_CFGERR_NONE
    ldi     r29, BISS_STATE_RUNNING
    qba     CFG_REPORT
CFG_FAIL:
    ldi     r2, 0
    sbco    r2, c28, P_PROC, 4              // not running
    ldi     r29, BISS_STATE_CFG_ERROR
CFG_REPORT:
    sbco    r28, c24, BISS_ST_CFG_ERROR, 8  // r28 the error, r29 ST_STATE (the next word)
    sbco    r18, c24, BISS_ST_CFG_ACK, 4    // then the sequence number: the verdict is out
    lbco    r13, c28, P_RECORDS, 68         // slave records into r13..r29
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
    jmp     r10.w2
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
    jmp     r10.w2

// The result buffer's address for the buffer number (0/1) in buf, to reg:
// BISS_RES0 (0x100, bit 8) + buf * BISS_RES_SIZE (< 0x100), branch-free (the
// same number of cycles either way: FRAME_REGS lies between an IEP trigger
// and the frame). biss_shm_struct.h asserts that layout.
.macro RESULT_ADDR
.mparam reg, buf
    rsb     reg, buf, 0                     // 0 or ~0
    and     reg, reg, BISS_RES_SIZE
    set     reg, reg, 8                     // + BISS_RES0 (0x100)
.endm

// reg = the result buffer being filled (P_BUF).
.macro RESULT_BASE
.mparam reg
    lbco    reg, c28, P_BUF, 4
    RESULT_ADDR reg, reg
.endm

// ============================================================================
// Before a frame: the slave must be idle (SL high); then the registers the
// clocked code starts from (FRAME_REGS), and the frame's timestamp.
//   r3 = 8p (ACK position base), r4.w0/w2, r5.w0 = history, r5.w2 = K,
//   r7.w0 = ACK limit, r7.w2 = processing-time limit, r4.w2 = history sum.
// A subroutine (returns through r12.w0; r2 it leaves alone) so that a
// free-run frame can have it done before SL is high (FE_IDLE_YES).
FRAME_REGS:
    lbco    r3, c28, P_DELAYS, 32           // r3 delays, r4 r5 history (r5.w2 = K), r6 its
                                            // sum, r7 P_BUF, r8 P_NSLAVES, r9 P_HALF, r10 P_PROC
    lsl     r0, r10.b3, 8                   // XFR shift 0: slave 0's slot, the step to
                                            // the next (CFG_PROC), no busy clocks
    ldi     r11, MA_MASK | (MA_MASK << 8)   // period 0 clocks
    mov     r11.b2, r8.b2                   // the end record (SWITCH_SHORT)
    mov     r7.w0, r9.w2                    // ACK limit
    mov     r7.w2, r10.w0                   // processing-time limit
    mov     r9, r3                          // the tails (DELAY_A)
    mov     r4.w2, r6.w0                    // history sum (r10 is the delay's)
    lbco    r4.w0, c28, P_CDM, 2            // the CDM edge for either CDS
    ldi     r1.w0, REC_BASE                 // r1.b1 = 0
    ldi     r6, 0
    ldi     r8, 0
    jmp     r12.w0

// The timestamp, then the first period. It waits in bank register 2 (r0.b0
// = 0: unshifted; the slots start at 4) for FRAME_END or ABORT_FRAME: no
// data-RAM store between the IEP read and the first MA edge.
.macro FRAME_STAMP
    ldi     r3, 0
    lbco    r2, c26, IEP_COUNT, 4
    xout    XFR_BANK, r2, 4
.endm

FRAME:
    jal     r12.w0, SLAVE_IDLE
    qbeq    NO_SLAVE_IDLE, r3, 0
    lbco    r2, c28, P_SSI, 2
    qbeq    FRAME_BISS, r2.w0, 0
    jmp     SSI_FRAME
FRAME_BISS:
    jal     r12.w0, FRAME_REGS
    IEP_ALIGN_IF FRAME_STAMPED
FRAME_STAMPED:                              // the free-run path comes in here
    fill    &r12, 4                         // r12 all ones while the start bit is
                                            // awaited (r0.b0 = 0: no XFR shift)
FRAME_CLOCKED:                              // TRAIN comes in here, r12 its two clocks
    FRAME_STAMP
    // fall into the first period

// ---- WAIT_ACK ---------------------------------------------------------------
// Clock until the newest 8 samples hold the ACK edge (a 0), then go to
// ACK_FOUND at t = 3 with the samples in r2.b0 and 8p in r3. The only
// pre-data period that counts MA edges down (r12): a training frame stops
// after two clocks; a normal frame clocks on until its start bit is seen.
    // Period 0 looks at nothing: its samples date from before the frame
    // (the ACK cannot come before the second rising edge), so the frame may
    // start as soon as SL is high.
    MA_FALL
    add     r3, r3, 8                       // 1
    jal     r10.w2, DLY_S6                  // 2..8
    DELAY_A
    MA_RISE
    NEXT_CLOCK                              // 1..4
    jal     r10.w2, DLY_S2                  // 5..7
    DELAY_B
    PAD
WA_TOP:
    MA_FALL
    mov     r2, r31                         // 1
    qbne    ACK_FOUND, r2.b0, 0xff          // 2
    add     r3, r3, 8                       // 3
    jal     r10.w2, DLY_S4                  // 4..8
    DELAY_A
    MA_RISE
    qble    NO_ACK, r3, r7.w0               // 1: limit <= 8p: give up after this rise
    NEXT_CLOCK                              // 2..5
    jal     r10.w2, DLY_S1                  // 6..7
    DELAY_B
    qba     WA_TOP

// The ones before the ACK edge in r2.b0 (a constant-time count: a glitch
// moves it by one, not to another bit), as Q' = 8p + ones in r1.w2.
// A one-period ACK reaches the master shortened by the line's rise/fall
// skew, so when its edge lies just before the oldest sample the newest
// sample already reads the start bit (0x01 would count 1, not 0). Such
// trailing ones come after the ACK, not before it: b0 & (b0 + 1) clears
// them; an ACK pattern (ones, then zeros) ends in a 0 and keeps every bit.
// Split over the two halves: 6 cycles, then 7.
.macro ONES_A
    add     r8, r2.b0, 1
    and     r2.b0, r2.b0, r8.b0             // no trailing ones (start bit)
    lsr     r6, r2.b0, 1
    and     r6, r6, 0x55
    sub     r6, r2.b0, r6                   // 2-bit sums
    lsr     r8, r6, 2
.endm
.macro ONES_B
    and     r8, r8, 0x33
    and     r6, r6, 0x33
    add     r6, r6, r8                      // 4-bit sums
    lsr     r8, r6, 4
    add     r6, r6, r8
    and     r6, r6, 0x0f                    // ones before the edge
    add     r1.w2, r3, r6                   // Q'
.endm

// From here to the start bit MA clocks on (r11 stays MA_MASK both ways): r12
// is all ones (FRAME_STAMPED) less 2 MA_MASK for each period that counted it
// down, a few hundred at most (the ACK limit is some 400 periods, the lag as
// many), so its bit 30 stays set. A training frame has made its two clocks (r11 =
// 0, r12 = 0) and ends after this period.
ACK_FOUND:                                  // t = 3
    ONES_A                                  // 3..8
    DELAY_A
    MA_RISE
    ONES_B                                  // 1..7
    DELAY_B
    qbbc    TRAIN_DONE, r12, 30             // training: no more periods

// ---- LAG: sample point and lag from the averaged ACK position ------------------
LAG1:
    MA_FALL
    add     r2, r1.w2, r4.w2                // 1  Q' + h0 + h1 + h2 + 2
    lsr     r2, r2, 2                       // 2  Qf': the 4-frame average
    sub     r2, r2, 4                       // 3
    and     r10, r2, 7                      // 4
    add     r10, r10, 8                     // 5  r10 = 31 - (8 (m + LAG) - Qf)
    lsr     r8, r2, 3                       // 6  m = (Qf' - 4) / 8
    lsr     r6, r3, 3                       // 7  p (this frame's ACK period)
    add     r3, r8, 2                       // 8
    DELAY_A
    MA_RISE
    max     r3, r3, r6                      // 1
    sub     r3, r3, r6                      // 2  idle periods before the first read
    PAD                                     // 3
    rsb     r5.w0, r10.b0, 29               // 4  R31 >> r5.w0: bit 2 the sample point
    jal     r10.w2, DLY_S2                  // 5..7
    DELAY_B
    qbeq    SW_TOP, r3, 0

// r3 >= 1 idle periods. An SSI frame's come here too (SSI_FRAME) and go on
// to its slave's entry; they count MA edges down for its sake (a BiSS-C
// frame's r12 keeps bit 30 set, see ACK_FOUND).
LAG_TOP:
    MA_FALL
    jal     r10.w2, DLY_S7                  // 1..8
    DELAY_A
    MA_RISE
    sub     r3, r3, 1                       // 1
    NEXT_CLOCK                              // 2..5
    qbeq    LAG_LAST, r3, 0                 // 6
    PAD                                     // 7
    DELAY_B
    qba     LAG_TOP
LAG_LAST:
    qbbc    SSI_LAG_LAST, r12, 30           // 7
    DELAY_B
    PAD

// ---- START_WAIT: ACK and busy read 0, the start bit 1 ------------------------
// The start bit is taken by a majority of five samples (the sample point
// and two on either side, all inside the bit): two samples flipped by a
// glitch (25 ns at 10 MHz) neither start the data early (in the busy) nor
// miss the start bit.
SW_TOP:
    MA_FALL
    lsr     r2, r31, r5.w0                  // 1  bits 4..0: sample point -2 .. +2
    and     r2, r2, 0x1f                    // 2
    mov     r3, MAJORITY5                   // 3..4
    qbbs    START_FOUND, r3, r2             // 5  three of the five are 1
    add     r0.w2, r0.w2, 1                 // 6  busy clocks (0 from FRAME_REGS)
    jal     r10.w2, DLY_S1                  // 7..8
    DELAY_A
    MA_RISE
    qblt    PROC_ERROR, r0.w2, r7.w2        // 1: limit < busy: give up after this rise
    jal     r10.w2, DLY_S5                  // 2..7
    DELAY_B
    qba     SW_TOP

SSI_LAG_LAST:                               // t = H + 8
    DELAY_B
    jmp     r7.w2

START_FOUND:                                // t = 6
    max     r3, r5.w2, r8                   // 6  clocks after this period:
    sub     r3, r3, r8                      // 7  max(N + 2 - LAG - m, 0), 2 edges each
    lsl     r12, r3, MA_BIT + 1             // 8
    DELAY_A
    MA_RISE
    ldi     r8, 0                           // 1  (r8.w0 stays 0 from here on)
    NEXT_CLOCK                              // 2..5
    PAD                                     // 6
    ldi     r6, 0                           // 7  (r6.w0 stays 0 from here on)
    DELAY_B
    PAD

// ---- CDS, then the slaves ----------------------------------------------------
// The CDM of this frame may depend on its CDS (a WAIT step): r4.b0 holds
// the CDM edge (0 or MA_MASK) for CDS = 0, r4.b1 the change for CDS = 1.
// A CDM of 1 is one more MA edge after the last clock: MA low.
CDS_PERIOD:
    MA_FALL
    SAMPLE                                  // 1
    lsr     r1.b1, r2, 31                   // 2
    LOAD_RECORD                             // 3..6
    rsb     r3, r1.b1, 0                    // 7  CDS ? ~0 : 0
    and     r3, r3, r4.b1                   // 8
    DELAY_A
    MA_RISE
    xor     r3, r3, r4.b0                   // 1  the CDM edge
    add     r12, r12, r3                    // 2
    NEXT_CLOCK                              // 3..6
    PAD                                     // 7
    DELAY_B
    jmp     r7.w2

// A slave's bits: n data bits, then w CRC bits, the last bit switching to the
// next slave. One entry per shape of slave.
ENTRY_CRC2:                                 // w >= 2
    DATA_PERIOD
    CRC_PERIOD
    CRC_SWITCH
ENTRY_CRC1:                                 // w = 1
    DATA_PERIOD
    CRC_SWITCH
ENTRY_PLAIN:                                // w = 0, n >= 2
    PLAIN_PERIOD
ENTRY_PLAIN1:                               // w = 0, n = 1
    PLAIN_SWITCH


// ============================================================================
// After the last bit. MA is high: the clocks ran out before the last reads.
// Nothing below is clocked.

// The last slave's last one or two bits, when its switch read the bit
// before them (CFG_SHAPE). That switch's R31 snapshot (r2, shifted to
// put its sample at bit 31) holds them 8 and 16 samples newer, at bits 23
// and 15 (indices 8 (LAG - 1) + s and 8 (LAG - 2) + s: sampled, and the
// same samples as reads one and two periods later would take at 8 LAG + s,
// 16 shift edges falling in every 2 periods). The switch has stored the
// slave's result in its slot, moved r0.b0 to the next one and loaded the
// end record. Not clocked: this
// comes at t = 0 of the period after the switch, whose MA edge (the CDM,
// if the line delay is under two periods: m = 1) is made here; otherwise
// r11.b0 = 0, and SWITCH_SHORT may have cut the switch short.
FINAL_PLAIN2:
    MA_FALL
    lsl     r2, r2, 8
    SHIFT_IN
FINAL_PLAIN:
    lsl     r2, r2, 8
    SHIFT_IN
    sub     r0.b0, r0.b0, r0.b1             // the last slave's slot
    xout    XFR_BANK, r4, 12
    qba     FRAME_END
FINAL_CRC2:
    MA_FALL
    ldi     r7.b0, 2
    qba     FINAL_CRC_GO
FINAL_CRC:
    ldi     r7.b0, 1
FINAL_CRC_GO:
    sub     r0.b0, r0.b0, r0.b1             // the last slave's slot:
    xin     XFR_BANK, r6, 4                       // its CRC register
    sub     r1.b0, r1.b0, 12                // the last slave's polynomial
    mviw    r8.w2, *r1.b0++
FINAL_CRC_BIT:
    lsl     r2, r2, 8
    CRC_STEP
    sub     r7.b0, r7.b0, 1
    qbne    FINAL_CRC_BIT, r7.b0, 0
    xout    XFR_BANK, r6, 4

FRAME_END:
    jal     r0.w0, CD_COMMIT               // r1.b1 = CDS; r1.b0 = the CDM sent
    jal     r3.w0, BUF_STAMP               // r2 = the result buffer, r0.w0 = 0:
    lbco    r0.b1, c28, P_PROC + 3, 1       // slave 0's slot, and the step to the next
    sbbo    r1.b0, r2, BISS_R_CDM, 1
    lbco    r1.b0, c28, P_NSLAVES, 1        // slaves to check
    rsb     r3, r10.b0, 31 - 8 * LAG        // sample point 0..7 within the bit
    sbbo    r3.b0, r2, BISS_R_SAMPLE_POINT, 1
    sbbo    r1.b1, r2, BISS_R_CDS, 1
    ldi     r12, BISS_RF_VALID              // frame flags
    add     r3, r2, BISS_R_SLAVE0           // slave result
    mov     r11, BISS_PRIV + P_SLAVES       // slave check data
FE_SLAVE:
    xin     XFR_BANK, r4, 12                      // data lo, data hi, CRC register: its slot
    add     r0.b0, r0.b0, r0.b1             // the next slave's
    lbbo    r7, r11, 0, 16                  // mask lo, mask hi, residue, [n, w, ew, flags]
    and     r4, r4, r7
    and     r5, r5, r8
    ldi     r7, BISS_RS_CRC_OK              // slave status (r4..r7: the slave's result)
    qbeq    FE_CRC_DONE, r10.b1, 0          // no CRC
    qbeq    FE_CRC_DONE, r6, r9
    ldi     r7, 0
    or      r12, r12, BISS_RF_CRC_ERROR
FE_CRC_DONE:
    qbbc    FE_EW_DONE, r10.b3, 0           // no nE/nW
    // nW (data bit ew) to r8 bit 0, nE (bit ew + 1) to bit 1
    lsr     r8, r5, r10.b2                  // 32 <= ew: the shift uses ew & 31
    qble    FE_EW_GOT, r10.b2, 32
    lsr     r8, r4, r10.b2
    lsl     r9, r5, 1
    qbne    FE_EW_GOT, r10.b2, 31
    or      r8, r8, r9                      // ew = 31: nE is bit 0 of the high word
FE_EW_GOT:
    qbbc    FE_NE_DONE, r8, 1
    set     r7, r7, 1                       // nE: BISS_RS_NE (0x02)
FE_NE_DONE:
    qbbc    FE_EW_DONE, r8, 0
    set     r7, r7, 2                       // nW: BISS_RS_NW (0x04)
FE_EW_DONE:
    sbbo    r4, r3, BISS_R_S_DATA_LO, 16    // data, CRC register, status
    add     r3, r3, BISS_R_SLAVE_SIZE
    add     r11, r11, 16
    sub     r1.b0, r1.b0, 1
    qbne    FE_SLAVE, r1.b0, 0
    // frame counters
    qbbc    FE_NO_CRC_ERR, r12, 1
    lbco    r3, c24, BISS_ST_CRC_ERRORS, 4
    add     r3, r3, 1
    sbco    r3, c24, BISS_ST_CRC_ERRORS, 4
FE_NO_CRC_ERR:
    // line delay: this frame's ACK position and the average it was read with
    lbco    r4, c28, P_HIST, 20             // r4 r5 history, r6 its sum, r8 P_NSLAVES
    add     r3, r6, r1.w2
    lsr     r3, r3, 2                       // Qf'
    sbbo    r1.w2, r2, BISS_R_DELAY_RAW, 2
    sbbo    r3.w0, r2, BISS_R_DELAY_AVG, 2
    add     r6, r3, 8 * LAG - 4             // m + LAG = (Qf' - 4) / 8 + LAG, as LAG1
    lsr     r6, r6, 3                       // (Qf' >= 8: every Q' is)
    sbbo    r6.b0, r2, BISS_R_LAG_PERIODS, 1
    // History. An ACK more than half a bit from the average it was read
    // with means this frame's bits were read at the wrong place (a glitch
    // in WAIT_ACK, or an average spoilt by one) or the line changed: the
    // frame is not valid, whatever its CRC says. One such ACK is left out of
    // the average; a second in a row starts the average afresh from it.
    // P_NSLAVES bit 31 (r8 here) remembers the first.
    sub     r6, r1.w2, r3                   // Q' - Qf' + 4 in 0..8: no jump
    add     r6, r6, 4
    qblt    FE_ACK_JUMP, r6, 8
    clr     r8, r8, 31
    mov     r5.w0, r4.w2                    // h2 = h1
    mov     r4.w2, r4.w0                    // h1 = h0
    mov     r4.w0, r1.w2                    // h0 = Q'
    qble    FE_HIST_SAVE, r8.b3, 3          // 3 <= frames in the average: full
    add     r8.b3, r8.b3, 1
    qba     FE_HIST_SAVE
FE_ACK_JUMP:
    xor     r12, r12, BISS_RF_VALID | BISS_RF_ACK_JUMP  // VALID set since FRAME_END,
                                            // ACK_JUMP not: one clear, one set
    qbbs    FE_HIST_RESET, r8, 31           // the second in a row
    set     r8, r8, 31
    qba     FE_NO_SMA                       // the history stays as it was
FE_HIST_RESET:
    mov     r4.w0, r1.w2
    mov     r4.w2, r1.w2
    mov     r5.w0, r1.w2
    ldi     r8.b3, 0
FE_HIST_SAVE:
    qbgt    FE_NO_SMA, r8.b3, 3
    or      r12, r12, BISS_RF_SMA
FE_NO_SMA:
    sbco    r8, c28, P_NSLAVES, 4
    jal     r0.w0, HIST_SAVE
    jal     r0.w0, PUBLISH                 // and CD_PREPARE: the next frame's CDM
    // The next frame, when it is a free-run BiSS-C one with no training due,
    // is set up now, while the slave's timeout runs: all MAIN and FRAME look
    // at changes only with a configuration, so once SL is high only a new
    // one is checked for (MAIN applies it), and the frame starts at once.
    // (No training can be due here: only a refused configuration or a
    // missing slave asks for one, and both go through MAIN.)
    lbco    r3, c28, P_NSLAVES, 4
    qbne    FE_SLOW, r3.b1, BISS_TRIG_FREERUN
    lbco    r3, c28, P_SSI, 2
    qbne    FE_SLOW, r3.w0, 0
    jal     r12.w0, FRAME_REGS
    jal     r12.w0, SLAVE_IDLE              // the slave's timeout has ended: SL high,
    qbeq    FE_MAIN, r3, 0                  // or not in time: MAIN and FRAME find it so again
FE_IDLE_YES:
    lbco    r2, c24, BISS_CFG_SEQ, 4        // (loaded before MA may rise: no data-RAM
    lbco    r3, c24, BISS_ST_CFG_ACK, 4     // access between that edge and the frame's)
    set     r30, r30, MA_BIT                // CDM done: MA idles high
    qbne    FE_MAIN, r2, r3                 // a new configuration: MAIN applies it
    jmp     FRAME_STAMPED
FE_SLOW:
    jal     r12.w0, SLAVE_IDLE              // the slave's timeout ends: SL high
FE_MAIN:
    set     r30, r30, MA_BIT                // CDM done: MA idles high
    jmp     MAIN

// History r4.w0, r4.w2, r5.w0 and its sum + 2 (rounding) to P_HIST/P_HSUM;
// HIST_FILL: all three r1.w2 (a history started afresh from one position).
HIST_FILL:
    mov     r4.w0, r1.w2
    mov     r4.w2, r1.w2
    mov     r5.w0, r1.w2
HIST_SAVE:
    sbco    r4, c28, P_HIST, 6
    add     r3, r4.w0, r4.w2
    add     r3, r3, r5.w0
    add     r3, r3, 2
    sbco    r3, c28, P_HSUM, 4
    jmp     r0.w0

// Publish the result buffer r2 with the flags in r12: header words, then
// the sequence number (its low bit names the buffer), then the next buffer.
// Every publication is followed by CD_PREPARE (the next frame's CDM): it
// goes on there, and returns through r0.w0 from it.
PUBLISH:
    lbco    r3, c24, BISS_ST_FRAMES, 4
    add     r3, r3, 1
    sbco    r3, c24, BISS_ST_FRAMES, 4
    sbbo    r3, r2, BISS_R_FRAME, 4
    sbbo    r12, r2, BISS_R_FLAGS, 4
    lbco    r4, c28, P_BUF, 12              // r4 P_BUF, r5 P_NSLAVES, r6 P_HALF
    sbbo    r5.b0, r2, BISS_R_NSLAVES, 1
    sbbo    r6.w0, r2, BISS_R_HALF, 2
    sbco    r4, c24, BISS_ST_BUF, 4
    lbco    r3, c24, BISS_ST_SEQ, 4
    add     r3, r3, 1                       // odd seq: buffer 1, even: buffer 0
    sbco    r3, c24, BISS_ST_SEQ, 4
    xor     r4, r4, 1
    sbco    r4, c28, P_BUF, 4
    ldi     r3, BISS_STATE_RUNNING
    sbco    r3, c24, BISS_ST_STATE, 4
    jmp     CD_PREPARE                      // which returns through r0.w0

// Wait for SL high: the slave's timeout has ended. High means the newest
// 4 samples (IDLE_MASK, half an MA period) are all 1, not just the newest:
// a glitch on SL during the timeout must not start a frame while the slave
// still ignores MA (it would misframe this frame and the next two). Half
// a period keeps the master's overhead low at 1 MHz and still outlasts a
// glitch of two samples (25 ns at 10 MHz). At most IDLE_TURNS turns of 4
// cycles; r3 = 0 if SL did not come high (the turns left if it did). r2
// is scratch. Returns through r12.w0: free before a frame (FRAME_STAMPED
// and TRAIN_GO set r12). A free-run frame waits here after FRAME_REGS
// (FE_IDLE_YES): of what that sets up, r2, r3 and r12 are not used.
SLAVE_IDLE:
    mov     r3, IDLE_TURNS
SLAVE_IDLE_POLL:
    and     r2.b0, r31.b0, IDLE_MASK
    qbeq    SLAVE_IDLE_YES, r2.b0, IDLE_MASK
    sub     r3, r3, 1
    qbne    SLAVE_IDLE_POLL, r3, 0
SLAVE_IDLE_YES:
    jmp     r12.w0

// r2 = the result buffer being filled, with the frame's timestamp (bank
// register 2, FRAME_STAMP) and busy clocks (r0.w2, START_WAIT) stored in it: the
// clocked part stores nothing. r0.w0 = 0 after (no XFR shift), r5 = r2.
// Returns through r3.w0.
BUF_STAMP:
    ldi     r0.w0, 0
    xin     XFR_BANK, r2, 4
    RESULT_BASE r5
    sbbo    r2, r5, BISS_R_TIMESTAMP, 4
    sbbo    r0.w2, r5, BISS_R_PROC_CLOCKS, 2
    mov     r2, r5
    jmp     r3.w0

// ---- frames that end early ---------------------------------------------------
// No slave: the line delay is measured again once one answers (a slave
// may come back on another cable, or in the middle of a frame).
NO_SLAVE_IDLE:                              // SL low before a frame:
    ldi     r0, 0                           // no busy clocks (BUF_STAMP)
NO_ACK:                                     // after a rising edge: MA stays high
    ldi     r12, BISS_RF_NO_SLAVE
NO_SLAVE_FLAGS:                             // (SL_INIT_DONE: r12 its own flags)
    ldi     r2, 1
    sbco    r2.b0, c28, P_PROC + 2, 1       // training due
    ldi     r3, BISS_ST_NO_SLAVE

// r12 = flags, r3 = the counter to increment; publish, wait for the slave.
ABORT_FRAME:
    jal     r0.w0, CD_ABORT
    lbbo    r4, r3, 0, 4
    add     r4, r4, 1
    sbbo    r4, r3, 0, 4
    jal     r3.w0, BUF_STAMP               // r2 = the result buffer
    jal     r0.w0, PUBLISH                 // and CD_PREPARE
    jmp     FE_SLOW                         // wait for the slave, MA high, MAIN

// The ACK came but the start bit did not: this frame's ACK position is a
// measurement all the same, and the average starts afresh from it (an
// average gone wrong would make every frame miss its start bit).
PROC_ERROR:                                 // after a rising edge: MA stays high
    jal     r0.w0, HIST_FILL
    ldi     r12, BISS_RF_PROC_ERROR
    ldi     r3, BISS_ST_PROC_ERRORS
    jmp     ABORT_FRAME

// ---- training: the line delay at a new rate -----------------------------------
// Two clocks only (as iC-MB4's INIT): the slave answers the second with its
// ACK and, clocked no further, holds SL low until its timeout. The periods
// go on without clocks until the ACK edge is seen; its position fills the
// history, so the next frame samples at the right point from its first bit.
// The frame's own WAIT_ACK and ACK periods make them: ACK_FOUND comes back
// to TRAIN_DONE.
TRAIN:
    jal     r12.w0, SLAVE_IDLE
    qbne    TRAIN_GO, r3, 0
SL_INIT:                                    // SL stuck low: INIT first (see SL_INIT_DONE)
    ldi     r2, 2                           // training due, as the INIT
    sbco    r2.b0, c28, P_PROC + 2, 1
TRAIN_GO:
    jal     r12.w0, FRAME_REGS
    ldi     r12, 2 * MA_MASK                // one clock after period 0's
    jmp     FRAME_CLOCKED
TRAIN_DONE:
    lbco    r2.b0, c28, P_PROC + 2, 1
    qbne    SL_INIT_DONE, r2.b0, 1          // it was the INIT of a low SL
    jal     r0.w0, HIST_FILL                // r4.w0, r4.w2 = Q' too
    jal     r3.w0, BUF_STAMP               // r2 = the result buffer (r4 kept)
    sbbo    r4, r2, BISS_R_DELAY_RAW, 4     // and DELAY_AVG
    sbco    r0.b0, c28, P_PROC + 2, 1       // training done (r0.w0 = 0: BUF_STAMP)
    sbco    r0.b0, c28, P_NSLAVES + 3, 1    // the average starts at this frame
    ldi     r12, BISS_RF_TRAINING
    ldi     r3, BISS_ST_TRAINING
    jmp     ABORT_FRAME

// A slave that keeps SL low (the last slave undefined after a disconnect or
// a broken frame) never lets TRAIN see SL high. iC-MB4's INIT exists for
// it: "necessary, if the last slave ... is not defined and the data line SLx
// is digital low"; two low pulses on MA, the slave answers and releases SL
// after its timeout; "The INIT sequence does not test the SLx state"
// (datasheet, BiSS C Initialization Sequence; INIT, Table 46). The training
// frame's two clocks are that sequence; with SL low from the start its
// ACK position means nothing, so it is published flagged (SL_INIT and
// NO_SLAVE, counted as no slave) and training stays due: the next MAIN
// trains at once, with SL high if the slave came back. (SL_INIT, above,
// marks the training frame as that INIT.)
SL_INIT_DONE:                               // a training proper next
    ldi     r12, BISS_RF_NO_SLAVE | BISS_RF_SL_INIT
    qba     NO_SLAVE_FLAGS

// ============================================================================
// Control communication: the CDM program (include/biss/biss_shm.h). Not
// clocked: CD_PREPARE after a frame works out the next frame's CDM for
// either CDS (so nothing of variable length lies between a trigger and the
// frame), the CDS period picks one, CD_COMMIT after the frame records and
// checks the answers.
// State in P_CD: r2 program run, r3.w0 step, r3.w2 answered step + 1,
// r4.w0 zeros in a row, r4.w2 WAIT frames, r5.b0/b1 CDM edge, r5.w2 length,
// r6.b0 CRC_M, r6.b1 CRC_S, r6.b2 flags (CD_F_*; bits 7..4 the first error,
// BISS_CDST_*, pending until the control frame ends), r6.b3 bytes.
#define CD_PAST_END     0x10                // CD_OP past the program's length
#define CD_F_CDM        0                   // the CDM of the step being answered
#define CD_F_OPEN       1                   // a register byte is under way (a WAIT passed)
#define CD_ERR          0x10                // r6.b2 at or above: an error is pending

// crc = CRC4 (x^4 + x + 1, MSB first) of crc and bit 0 of bit. 6 cycles at
// most; r12 is scratch.
.macro CRC4_FEED
.mparam crc, bit
    lsr     r12, crc, 3
    xor     r12, r12, bit                   // feedback
    lsl     crc, crc, 1
    and     crc, crc, 0x0f
    qbbc    CRC4_FEED_END, r12, 0
    xor     crc, crc, 0x03
CRC4_FEED_END:
.endm

// r7 = step r8 of the program: bits 1..0 its op, 3..2 its class;
// CD_PAST_END past the length. (biss_shm_struct.h asserts BISS_CD_PROG.)
CD_OP_STEP:                                 // the same for step r8 = r3.w0
    mov     r8, r3.w0
CD_OP:
    ldi     r7, CD_PAST_END
    qble    CD_OP_DONE, r8, r5.w2           // length <= step
    lsr     r7, r8, 1
    set     r7, r7, 10                      // BISS_CD_PROG (0x400) + step / 2
    lbco    r7, c24, r7, 1
    qbbc    CD_OP_LOW, r8, 0
    lsr     r7, r7, 4                       // odd steps: the high nibble
CD_OP_LOW:
    and     r7, r7, 0x0f
CD_OP_DONE:
    jmp     r10.w2

CD_PREPARE:
    lbco    r2, c28, P_CD, 20
    ldi     r5.w0, 0                        // CDM 0 whatever the CDS
    qbne    CDP_RUN, r2, 0
    lbco    r7, c24, BISS_CD_CMD, 12        // r7 CD_CMD, r8.w0 CD_STEPS, r9 ST_CD_SEQ
    qbeq    CDP_OUT, r7, r9                 // no new program
    qbgt    CDP_OUT, r4.w0, 14              // not before 14 frames with CDM 0
    mov     r9, BISS_CD_MAX_STEPS
    qbeq    CDP_BAD, r8.w0, 0
    qblt    CDP_BAD, r8.w0, r9
    mov     r2, r7                          // run it from step 0
    ldi     r3, 0
    ldi     r4.w2, 0
    mov     r5.w2, r8.w0
    ldi     r6, 0                           // CRCs 0, no byte, no error
    ldi     r7, BISS_CDST_BUSY
    sbco    r7, c24, BISS_ST_CD_STATUS, 4
CDP_RUN:
    jal     r10.w2, CD_OP_STEP
    qbbs    CDP_OUT, r7, 4                  // past the end: CDM 0
    qbgt    CDP_STEP, r6.b2, CD_ERR
    qbeq    CDP_OUT, r7, BISS_CDOP_1        // an error ends the frame at the next master S
CDP_STEP:
    and     r9, r7, 3
    qbeq    CDP_WAIT, r9, BISS_CDOP_WAIT
    qbne    CDP_BIT, r9, BISS_CDOP_CRC
    lsr     r9, r6.b0, 3                    // CRC_M's next bit, inverted
    xor     r9, r9, 1
CDP_BIT:
    qbbc    CDP_IDA, r9, 0
    ldi     r5.b0, MA_MASK
CDP_IDA:
    // A command's P with the IDA test failed goes out inverted: the slaves
    // take that as a broken control frame and do not execute it.
    lbco    r9, c24, BISS_CD_IDA_STEP, 2
    qbne    CDP_OUT, r9.w0, r3.w0
    qbgt    CDP_OUT, r6.b2, CD_ERR
    xor     r5.b0, r5.b0, MA_MASK
    qba     CDP_OUT
CDP_WAIT:
    // While the slave's S is late the master sends CDM 1 (MA low in the
    // timeout): 13 CDM 0 already follow a read byte (D, CRC, P), and any
    // control frame is cancelled by 14 (TIDEP0022 §2.1.3). TI's own PRU
    // firmware does the same: it keeps its S (clock held low) until the
    // slave's start bit comes (motor-control-sdk, bissc_main.asm,
    // BISSC_SKIP_CTRL_SB?). CDS 1 ends the wait: send the next step now.
    ldi     r5.b0, MA_MASK
    add     r8, r3.w0, 1
    jal     r10.w2, CD_OP
    and     r7, r7, CD_PAST_END | 3
    qbeq    CDP_OUT, r7, BISS_CDOP_1        // 1 either way
    ldi     r5.b1, MA_MASK                  // 0 once CDS is 1
CDP_OUT:
    sbco    r2, c28, P_CD, 20
    jmp     r0.w0
CDP_BAD:                                    // refused: ST_CD_SEQ, then ST_CD_STATUS
    ldi     r8, BISS_CDST_ERR_STEPS         // (the next word: one store, in that order)
    sbco    r7, c24, BISS_ST_CD_SEQ, 8
    qba     CDP_OUT

// After a frame with CDS r1.b1: returns the CDM it sent in r2.b0.
// (Calls nest through r0.w0 and r10.w2 (CD_OP): r0.w2 keeps the busy
// clocks for BUF_STAMP, r13..r29 hold the slave records, r10.b0 is the
// caller's.)
CD_COMMIT:
    lbco    r2, c28, P_CD, 20
    rsb     r7, r1.b1, 0                    // the CDM edge that went out
    and     r7, r7, r5.b1
    xor     r7, r7, r5.b0
    min     r1.b0, r7, 1
    qbeq    CDC_ZEROS, r2, 0                // no program
    qbeq    CDC_SENT_STEP, r3.w2, 0
    // the answer: recorded, then checked as its step's class asks
    sub     r8, r3.w2, 1                    // the step this CDS answers
    lsr     r9, r8, 3
    mov     r11, BISS_CD_RESP
    add     r9, r9, r11
    lbco    r11, c24, r9, 1
    and     r12, r8, 7
    clr     r11, r11, r12
    qbbc    CDC_BIT0, r1.b1, 0
    set     r11, r11, r12
CDC_BIT0:
    sbco    r11, c24, r9, 1
    lbco    r9, c24, BISS_CD_IDA_STEP, 4    // r9.w0 P, r9.b2 the IDA expected
    add     r11, r8, 9
    sub     r11, r11, r9.w0                 // k = step - (P - 9): IDA slot k if k < 8
    qblt    CDC_CLASS, r11, 7
    lsr     r9, r9.b2, r11
    xor     r9, r9, r1.b1
    ldi     r11, BISS_CDST_ERR_IDA << 4
    qbbs    CDC_ERR, r9, 0
CDC_CLASS:
    jal     r10.w2, CD_OP
    lsr     r7, r7, 2
    qbeq    CDC_SENT_STEP, r7, BISS_CDCL_NONE
    qbne    CDC_FEED_S, r7, BISS_CDCL_CHECK
    lsr     r9, r6.b1, 3                    // CHECK: the next bit of CRC_S, inverted
    xor     r9, r9, r1.b1
    lsl     r6.b1, r6.b1, 1                 // (fed its uninverted value: a shift)
    and     r6.b1, r6.b1, 0x0f
    ldi     r11, BISS_CDST_ERR_CRC << 4
    qbbc    CDC_ERR, r9, 0
    qba     CDC_SENT_STEP
CDC_FEED_S:
    CRC4_FEED r6.b1, r1.b1                  // DATA and ECHO
    qbne    CDC_SENT_STEP, r7, BISS_CDCL_ECHO
    xor     r9, r6.b2, r1.b1                // ECHO: the CDM sent (CD_F_CDM)
    ldi     r11, BISS_CDST_ERR_ECHO << 4
    qbbc    CDC_SENT_STEP, r9, 0
CDC_ERR:
    qble    CDC_SENT_STEP, r6.b2, CD_ERR    // the first error stays
    or      r6.b2, r6.b2, r11
CDC_SENT_STEP:
    // the step that went out in this frame
    ldi     r3.w2, 0
    jal     r10.w2, CD_OP_STEP
    qbbs    CDC_END, r7, 4
    qbgt    CDC_NOT_END, r6.b2, CD_ERR      // an error pending: a master S sent as 0
    qbne    CDC_NOT_END, r1.b0, 0           // ended the control frame (one that went out
    qbeq    CDC_END, r7, BISS_CDOP_1        // as 1 before the error was seen did not)
CDC_NOT_END:
    qbne    CDC_SENT, r7, BISS_CDOP_WAIT
    qbbs    CDC_WAITED, r1.b1, 0
    add     r4.w2, r4.w2, 1                 // another frame in the WAIT
    lbco    r9, c24, BISS_CD_WAIT_LIMIT, 2
    qbge    CDC_ZEROS, r4.w2, r9.w0         // waits <= limit: go on
    ldi     r7, BISS_CDST_ERR_WAIT
    qba     CDC_STOP
CDC_WAITED:
    add     r3.w0, r3.w0, 1                 // past the WAIT: its next step went out
    ldi     r4.w2, 0
    ldi     r6.w0, 0                        // the byte's CRCs start afresh
    set     r6.b2, r6.b2, CD_F_OPEN
    jal     r10.w2, CD_OP_STEP
    qbbs    CDC_END, r7, 4
CDC_SENT:
    clr     r6.b2, r6.b2, CD_F_CDM
    or      r6.b2, r6.b2, r1.b0             // for the echo check of its answer
    qbgt    CDC_CLOSE, r7, BISS_CDOP_CRC    // class NONE, op 0 or 1
    mov     r11, r1.b0
    and     r9, r7, 3
    qbne    CDC_FEED_M, r9, BISS_CDOP_CRC
    xor     r11, r11, 1                     // a CRC bit feeds its uninverted value
CDC_FEED_M:
    CRC4_FEED r6.b0, r11
    qba     CDC_NEXT
CDC_CLOSE:
    // a byte under way is over (its P): count it if it had no error
    qble    CDC_NEXT, r6.b2, CD_ERR
    qbbc    CDC_NEXT, r6.b2, CD_F_OPEN
    clr     r6.b2, r6.b2, CD_F_OPEN
    add     r6.b3, r6.b3, 1
CDC_NEXT:
    add     r3.w0, r3.w0, 1
    mov     r3.w2, r3.w0                    // its CDS comes with the next frame
    qba     CDC_ZEROS
CDC_END:
    ldi     r7, BISS_CDST_DONE
    qbgt    CDC_STOP, r6.b2, CD_ERR
    lsr     r7, r6.b2, 4                    // the error pending
CDC_STOP:
    mov     r7.b1, r6.b3                    // bytes transferred
    mov     r7.w2, r3.w0                    // steps executed
    sbco    r7, c24, BISS_ST_CD_STATUS, 4
    sbco    r2, c24, BISS_ST_CD_SEQ, 4
    ldi     r2, 0
    ldi     r4.w0, 0                        // the slaves count 14 zeros afresh after a frame
CDC_ZEROS:
    add     r4.w0, r4.w0, 1                 // frames with CDM 0 in a row
    min     r4.w0, r4.w0, 255
    qbeq    CDC_SAVE, r1.b0, 0
    ldi     r4.w0, 0
CDC_SAVE:
    sbco    r2, c28, P_CD, 20
    mov     r2.b0, r1.b0
    jmp     r0.w0

// A frame failed: a running program cannot go on (the slave saw a broken
// frame), and the zeros start again. r3 and r12 are the caller's.
CD_ABORT:
    lbco    r4, c28, P_CD, 20               // r4 program, r5.w0 step, r8.b3 bytes
    ldi     r9, 0
    sbco    r9, c28, P_CD + 8, 2            // zeros in a row: none
    qbeq    CDA_DONE, r4, 0
    sbco    r9, c28, P_CD, 4                // no program
    sbco    r4, c24, BISS_ST_CD_SEQ, 4
    mov     r9.w2, r5.w0
    ldi     r9.b0, BISS_CDST_ERR_FRAME
    mov     r9.b1, r8.b3
    sbco    r9, c24, BISS_ST_CD_STATUS, 4
CDA_DONE:
    jmp     r0.w0

// ============================================================================
// SSI: no ACK to measure the line by, no start bit, CDS or CRC. The slave
// shifts its word out on the rising edges from the first one; the master
// reads bit j (rise j) m + LAG periods later at the sample point the
// configured round trip gives (P_SSI), exactly as a BiSS-C frame's bits.

// Its configuration: CFG_SSI (APPLY_CONFIG).
SSI_FRAME:
    jal     r12.w0, FRAME_REGS
    lbco    r1.w2, c28, P_SSI, 4            // Q' (and r1.w2 is what FRAME_END records),
                                            // the clocks (to r2.w0: docs/pru-facts.md §1.7)
    IEP_ALIGN_IF SSI_ALIGNED
SSI_ALIGNED:
    mov     r12, r2.w0
    FRAME_STAMP
    sub     r2, r1.w2, 4                    // sample point and lag as LAG1 derives them
    and     r10, r2, 7
    add     r10, r10, 8
    lsr     r3, r2, 3
    add     r3, r3, LAG                     // periods before bit 0 is read: m + LAG
    ldi     r8, 0
    LOAD_RECORD                             // the slave's data bits, no CRC
    jmp     LAG_TOP                         // the idle periods, then r7.w2
