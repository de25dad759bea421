// clock_frames.p - clocks BiSS frames on MA without decoding SL.
//
// A stand-in master for testing the bench before (and beside) the real
// firmware: FRAMES frames of CLOCKS MA clock periods, each half period
// exactly HALF PRU cycles, then MA high for GAP cycles, then HALT.
// Override any of them with -D.

#ifndef MA_BIT
#define MA_BIT 1
#endif
#ifndef HALF
#define HALF 10
#endif
#ifndef CLOCKS
#define CLOCKS 30
#endif
#ifndef FRAMES
#define FRAMES 10
#endif
#ifndef GAP
#define GAP 8000
#endif

.origin 0
.entrypoint start

start:
    set     r30, r30, MA_BIT        // MA idles high
    mov     r1, FRAMES
frame:
    mov     r2, CLOCKS
clock:
    // low half: clr + loop setup + (HALF - 2) loop bodies = HALF cycles
    clr     r30, r30, MA_BIT
    loop    low_end, HALF - 2
    mov     r4, r4
low_end:
    // high half: set + loop setup + (HALF - 4) bodies + sub + qbne = HALF
    set     r30, r30, MA_BIT
    loop    high_end, HALF - 4
    mov     r4, r4
high_end:
    sub     r2, r2, 1
    qbne    clock, r2, 0
    // gap: MA stays high; 2 cycles per iteration
    mov     r3, GAP / 2
gap:
    sub     r3, r3, 1
    qbne    gap, r3, 0
    sub     r1, r1, 1
    qbne    frame, r1, 0
    halt
