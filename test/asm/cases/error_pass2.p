// A branch out of range is only known in pass 2.
.origin 0
        qba far
.origin 600
far:    halt

// Expected first error (checked against pasm 0.87 -V3):
// expect-error: error_pass2.p:3: Error: Operand 1 relative jump out of range
