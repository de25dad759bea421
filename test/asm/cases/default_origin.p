// Without .origin the code starts at word 8 (pasm warns) after 8 zero words.
start:  add r1, r2, r3
        qba start

// Expected words (checked against pasm 0.87 -V3):
// expect: 00000000 00000000 00000000 00000000 00000000 00000000 00000000 00000000
// expect: 00e3e2e1 7f0000ff
