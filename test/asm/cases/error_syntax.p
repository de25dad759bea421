// Operand errors are reported with file:line.
.origin 0
        add r1, r2
        ldi r1, 0x10000

// Expected first error (checked against pasm 0.87 -V3):
// expect-error: error_syntax.p:3: Error: Expected 3 operands
