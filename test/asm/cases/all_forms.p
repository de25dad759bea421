// Every V3 instruction and operand form, as pasm 0.87 -V3 encodes it.
.origin 0
start:
back:
add r1, r2, r3
add r1.b1, r2.w1, 0xff
adc r1, r2, 5
sub r3.w2, r4.b3, r5.w0
lsl r1, r1, 31
lsr r1, r1, r2.b0
rsb r1, r2, 7
or r1, r2, 1
max r1, r2, 9
mov r1, r2
mov r1.w0, r2.b1
mov r1, 0x12
mov r1, 0x12345678
mov r1.b2, 0xab
ldi r1.b0, 0x1ff
lmbd r1, r2, 1
jmp start
jmp r2.w0
jal r3.w2, r4
call start
ret
halt
slp 0
slp 1
xin 10, r2, 8
xout 14, r2.b2, b2
xchg 12, r4, 124
sxin 10, r2, 8
qble fwd, r1, r2
qbeq back, r1, 0
qbne fwd, r1, r2.w1
wbs r31.t30
wbc r31, 3
.codeword 0xdeadbeef
not r1, r2
not r1, r2, r3
clr r30.t5
set r30, 5
clr r1.b1, r1.b0.t5
set r1, r2, r3.b2
nop0 r1, r2, r3
nopf r1.w1, r2.b3, 200
loop lend, 5
add r1, r1, 1
lend:
loop lend2, r2.b0
sub r2,r2,1
lend2:
iloop lend3, 256
add r0, r0, r0
lend3:
mvib r2, *r1.b0
mvid *r1.b0++, r14
mvid *--r1.b0, r14
mvib r2, r3
mviw r2, r3
mvid r2, r3
mvib r2, r3.w2
mviw *r1.b1, *r1.b2++
mvib *&r3, *r1.b3
zero &r0, 8
fill &r2, 4
zero 4, 120
xin 10, 8, 4
lbbo r2, r1, 5, 8
lbbo &r2, r1, r3.w0, b0
sbbo r2.b1, r1, 0, 124
lbco r3, c24, 0, 4
sbco r3, c31, r4, b3
sbbo 17, r5, r6.b2, b1
lbbo r2.w1, r1, 255, 1
qbgt back, r1, r2
qbge fwd, r1.b0, 0xff
qblt back, r1.w1, r0
qba back
qbbs back, r31, 30
qbbc fwd, r31.t31
qbbs fwd, r5.w1.t15, 
qbbc back, r5, r6
ldi r30.b0, &r2
ldi r1, &r3.w1
ldi r1, &r5.w1.b1
add r1.w1.b1, r2.w2.b0, r3.b3
fwd:
halt

// Expected words (checked against pasm 0.87 -V3):
// expect: 00e3e2e1 01ffa221 0305e2e1 048564c3 091fe1e1 0a02e1e1 0d07e2e1 1301e2e1
// expect: 1b09e2e1 10e2e2e1 10222281 240012e1 241234c1 24567881 2400ab41 2401ff01
// expect: 2701e2e1 21000000 20820000 22e400c3 2300009e 209e0000 2a000000 3e000000
// expect: 3e800000 2e850382 2f073f42 2f863d84 2e854382 58e2e134 5700e1e2 68a2e132
// expect: c91eff00 d103ff00 deadbeef 1700e2e1 16e3e2e1 1d05fefe 1f05fefe 1d050121
// expect: 1e43e2e1 a0e3e2e1 bfc862a1 31040002 0101e1e1 30020002 0501e2e2 31ff8002
// expect: 00e0e0e0 2c2001e2 2d02ee01 2d82ee01 100303e2 108383e2 10e3e3e2 104343e2
// expect: 2cc14121 2c206103 2eff8380 2eff0182 2effbb81 2e850182 f1056182 fe83c102
// expect: ef00a1a2 91003883 8ee4ff83 ee46c5a4 f1ff0122 66e2e1bb 71ff010b 4ee0a1b9
// expect: 7f0000b8 d71effb7 c91fff07 d10fa506 cee6e5b4 2400081e 24000de1 240016e1
// expect: 00634241 2a000000
