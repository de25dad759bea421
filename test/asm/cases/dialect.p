// The pasm dialect: comments, equates, conditionals, macros, structures,
// scopes, SIZE/OFFSET, .setcallreg, .proc and expressions.
.setcallreg r29.w0
#include "dialect.hp"
.origin 0
.entrypoint start
#define TWO 2
#define FOUR TWO*2
#define NOPX mov r0, r0
/* block
   comment */
start:  ldi r1, CONST_A ; semicolon comment
        ldi REG_X, FOUR + 1
        NOPX
/* c */ldi r2, 6
        add r1, r1, \
            3
        incr r1
        incr r2, 5
        ldi r3, 8>>1+1
        ldi r3, 1|2&3
        ldi r3, 10-2-3
        ldi r3, -1&0xff
        ldi r3, 017
        ldi r3, 0b101
        ldi r3, (~(1<<3))&0xff
        ldi r3, 7%3*5
        ldi r3, ((1+2)*(3+4))
        ldi r3, #5
        ldi r3, start + 3
        ldi r3, (lbl)
        ADD R1, R2.W1, 3
.macro waitloop
.mparam cnt
        ldi r20, cnt
lp:     sub r20, r20, 1
        qbne lp, r20, 0
.endm
        waitloop 10
        waitloop 20
        jmp _lp_1_2_
lbl:
.struct Frame
    .u32 pos
    .u16 crc
    .u8  flags
    .u8  status
.ends
.assign Frame, r10, r11, fr
        mov fr.pos, r1
        mov fr.crc, 0x1234
        mov fr.flags, 3
        ldi r1, SIZE(Frame)
        ldi r1, OFFSET(Frame.status)
        ldi r1, SIZE(fr.crc)
        ldi r1, OFFSET(fr.pos.w2)
        ldi r1, SIZE(r2.w1)
        mov r1, fr.crc.b1
        set fr.flags.t3
.enter Sc1
.assign Frame, r12.w0, *, f2
        mov f2.status, 1
.leave Sc1
.using Sc1
        mov f2.status, 2
.leave Sc1
#ifdef NOT_DEFINED
        halt
#else
        call start
#endif
.proc sub1
        ret
        jmp .sub1
        halt

// Expected words (checked against pasm 0.87 -V3):
// expect: 240010e1 240005e5 10e0e0e0 240006e2 0103e1e1 0101e1e1 0105e2e2 240002e3
// expect: 240003e3 240005e3 2400ffe3 24000fe3 240005e3 2400f7e3 240005e3 240015e3
// expect: 240005e3 240003e3 24001be3 0103a2e1 24000af4 0501f4f4 6f00f4ff 240014f4
// expect: 0501f4f4 6f00f4ff 21001800 10e1e1ea 2412348b 2400034b 240008e1 240007e1
// expect: 240002e1 240002e1 240002e1 102b2be1 1f034b4b 2400016d 2400026d 2300009d
// expect: 209d0000 21002800 2a000000
