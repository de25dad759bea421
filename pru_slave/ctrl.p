// ctrl.p - control communication, from the slave's side: CTRL_STEP takes
// the CDM of one frame (CDM_IN) and returns the CDS of the next (CDS_OUT).
// Called between frames (between.p), returns through RET_SUB.
//
// The control frame as the documents describe it (CF: the control-frame
// notes; TI: TIDEP0022 §2.1.3; MB4: iC-MB4 datasheet, "Control
// communication", "BiSS commands"; POS: the POSITAL manual §3.1.2; AD38:
// the Hengstler notes' control-frame drawings):
//   - at least 14 CDM = 0 before a control frame; CDM = 1 then is its start
//     S (CF, TI, POS); 14 CDM = 0 cancel any control frame (TI: "Any
//     control frame can be cancelled by transmitting 14 numbers of CDM
//     equaling 0")
//   - the header: CTS, then ID (3) and ADR (7) for a register access (CTS =
//     1), or IDS (8, the first for ID 0) and CMD (2) for a command (CTS =
//     0), then CRC4 (polynomial 0x13, start 0, sent inverted) over CTS and
//     the 10 bits (TI Table 3: control CRC 4 bits, 0x13; CF)
//   - in a register access the CDS answering CTS and the 7 bits after it
//     carry the ID lock IDL0..7: each slave answers 1 in the slot of its
//     ID (AD38 drawings "IDL0..7"; POS: "ID Lock bits (IDL) are sent back";
//     TI: "setting the IDL bits for the first eight IDs"; which 8 of the
//     header's answers the drawings do not settle: the first 8, as the
//     slave model, emulator/slave/MODELS.md)
//   - R W S: read 1 0 1, write 0 1 1 (CF, POS); the slave echoes R and W and
//     answers S with its own S: 1, or 0 for REG_WAIT frames first (late S,
//     CF's note: "the encoder [may request] additional processing time ...
//     by responding with S = 0")
//   - 8 data bits, MSB first: the register's bits (read) or the echo of
//     the master's (write: POS "the slave sends back the read value ... for
//     confirmation"); then 4 CRC bits, the slave's inverted CRC4 of the
//     byte, while the master sends the inverted CRC4 of a written byte (a
//     write is stored only when that is right) or zeros (a read)
//   - P (the stop bit, 0), then S: 1 = the next address (sequential
//     access: CF "a stop bit (P = 1) immediately followed by another start
//     bit (S = 1)"; iC-MB4 REGNUM), 0 = the end (TI: "A stop bit (P = 0) is
//     at the end of the frame")
//   - a command: after the header 8 IDA slots, the CDS after the CRC and
//     after each of the first 7 being 1 in slot i when the slave with ID i
//     is addressed (not for a broadcast, IDS = 0: MB4 "In contrast to
//     broadcast BiSS commands, the reception of an addressed BiSS command
//     is confirmed during IDA"); then the execute bit: each addressed slave
//     executes the command when it has its value (1, iC-MB4's EX bit; 0
//     with BISS_SLV_SF_EXEC_0) and drops it otherwise, which is how a
//     master's IDA test withholds it (MB4 IDA_TEST)
// A chain has one control frame for all: every slave sees the same CDM,
// so one state machine runs for the chain, and the CDS is the OR of the
// slaves' answers. The register files and command counters are per slave.

#define CRC4_POLY       0x03            // 0x13 without its top term
#define ARM_ZEROS       14

.enter ctrl
.assign CtrlState, r1, r4, Cs           // the state (layout.hp), loaded and stored whole
.assign Word, r5, r5, NsWord            // P_NSLAVES' word:
.assign Byte, r5.b0, r5.b0, NSlaves     //   slaves
.assign Byte, r5.b1, r5.b1, Idl         //   IDs of the answering slaves (bit k: ID k)
.assign Byte, r6.b0, r6.b0, InFrame     // a control frame was under way before this CDM
.assign Byte, r6.b1, r6.b1, Bit         // scratch bits
.assign Byte, r6.b2, r6.b2, Fb          //   (the CRC4 feedback)
.assign Byte, r6.b3, r6.b3, Rws
.assign Word, r7, r7, Addr              // an address in data RAM
.assign Word, r8, r8, Scr               // scratch
.assign Word, r9, r9, Scr2
.assign Word, r10, r10, Base            // a slave's register file
.assign Word, r12, r12, SvAddr          // a slave's SlvCtl, and from it its settings:
.assign Byte, r13.b0, r13.b0, SvFlags   //   flags
.assign Byte, r13.b1, r13.b1, SvId      //   ID
.assign Byte, r13.b2, r13.b2, SvWait    //   late S frames
.assign Byte, r13.b3, r13.b3, SvBanks   //   banks
.assign Byte, r14.b0, r14.b0, SvBank0   //   first bank
.assign Word, r13, r13, SvWord          // (SvFlags .. SvBanks as loaded)
.assign Word, r14, r14, SvWord2         // (SvBank0 ..)
.assign Byte, r15.b0, r15.b0, Idx       // a slave's index
.assign Byte, r15.b1, r15.b1, Value     // a register byte
.assign Byte, r15.b2, r15.b2, Ok        // REG_WRITE: 1 stored
.assign Half, r25.w0, r25.w0, Count16   // a u16 counter
.assign Word, r26, r26, RetStep         // CTRL_STEP's own return (RET_SUB is reused inside)
.assign Byte, r27.b0, r27.b0, BitsLeft      // loop counter

// One CRC4 step (poly 0x13, MSB first) of Cs.crc4 with the bit in `bit`.
.macro CRC4_STEP
.mparam bit
    lsr     Fb, Cs.crc4, 3
    xor     Fb, Fb, bit
    lsl     Cs.crc4, Cs.crc4, 1
    and     Cs.crc4, Cs.crc4, 0x0f
    qbbc    C4S_NOFB, Fb, 0
    xor     Cs.crc4, Cs.crc4, CRC4_POLY
C4S_NOFB:
.endm

CTRL_STEP:
    mov     RetStep, RET_SUB
    ldi     Addr, P_CTRL
    lbbo    &Cs, Addr, 0, SIZE(CtrlState)
    ldi     Addr, P_NSLAVES
    lbbo    NsWord, Addr, 0, 4
    ldi     CDS_OUT, 0
    // CDM = 0 in a row, up to 255
    qbne    CS_ONE, CDM_IN, 0
    qbeq    CS_ZEROS_DONE, Cs.zeros, 255
    add     Cs.zeros, Cs.zeros, 1
    qba     CS_ZEROS_DONE
CS_ONE:
    ldi     Cs.zeros, 0
CS_ZEROS_DONE:
    ldi     InFrame, 0
    qbeq    CS_IDLE, Cs.state, BISS_SLV_CS_IDLE
    ldi     InFrame, 1
    qbeq    CS_DONE, Cs.state, BISS_SLV_CS_IGNORE
    qbeq    CS_HEADER, Cs.state, BISS_SLV_CS_HEADER
    qbeq    CS_RWS, Cs.state, BISS_SLV_CS_RWS
    qbeq    CS_WAIT, Cs.state, BISS_SLV_CS_WAIT
    qbeq    CS_DATA, Cs.state, BISS_SLV_CS_DATA
    qbeq    CS_DCRC, Cs.state, BISS_SLV_CS_DCRC
    qbeq    CS_STOP, Cs.state, BISS_SLV_CS_STOP
    qbeq    CS_SEQ, Cs.state, BISS_SLV_CS_SEQ
    qbeq    CS_IDA, Cs.state, BISS_SLV_CS_IDA
    qba     CS_EXEC

// ---- idle: armed after 14 zeros; then a 1 is the start S -------------------
CS_IDLE:
    qbeq    CS_IDLE_ZERO, CDM_IN, 0
    qbeq    CS_DONE, Cs.armed, 0
    ldi     Cs.armed, 0
    ldi     Cs.state, BISS_SLV_CS_HEADER
    ldi     Cs.count, 0
    ldi     Cs.shift, 0
    ldi     Cs.crc4, 0
    qba     CS_DONE
CS_IDLE_ZERO:
    qbgt    CS_DONE, Cs.zeros, ARM_ZEROS
    ldi     Cs.armed, 1
    qba     CS_DONE

// ---- the header: 15 bits; the CRC4 over the first 11 --------------------------
CS_HEADER:
    lsl     Cs.shift, Cs.shift, 1
    or      Cs.shift, Cs.shift, CDM_IN
    add     Cs.count, Cs.count, 1
    qblt    CS_HEADER_CRC, Cs.count, 11     // 11 < count: a CRC bit
    CRC4_STEP CDM_IN
CS_HEADER_CRC:
    qbeq    CS_HEADER_DONE, Cs.count, 15
    // IDL: in a register access, the answer to header bit k = count - 1
    // (k = 0: CTS) for k < 8 is 1 when a slave has ID k
    qblt    CS_DONE, Cs.count, 8            // 8 < count: k >= 8
    sub     Scr, Cs.count, 1
    lsr     Scr2, Cs.shift, Scr             // CTS, the first bit
    qbbc    CS_DONE, Scr2, 0
    lsr     Scr2, Idl, Scr
    and     CDS_OUT, Scr2, 1
    qba     CS_DONE
CS_HEADER_DONE:
    // the CRC: the 4 bits received must be the inverted CRC4
    not     Scr, Cs.crc4
    and     Scr, Scr, 0x0f
    and     Scr2, Cs.shift, 0x0f
    qbeq    CS_HEADER_OK, Scr, Scr2
    ldi     Addr, BISS_SLV_ST_HDR_CRC_ERRORS
    lbbo    Count16, Addr, 0, 2
    add     Count16, Count16, 1
    sbbo    Count16, Addr, 0, 2
    ldi     Cs.state, BISS_SLV_CS_IGNORE
    qba     CS_DONE
CS_HEADER_OK:
    lsr     Scr, Cs.shift, 4                // CTS and the 10 bits
    ldi     Cs.count, 0
    ldi     Cs.shift, 0
    qbbc    CS_COMMAND, Scr, 10
    // a register access: ID (bits 9..7), ADR (6..0); the slave of that ID
    and     Cs.addr, Scr, 0x7f
    lsr     Scr2, Scr, 7
    and     Scr2, Scr2, 7
    ldi     Cs.state, BISS_SLV_CS_IGNORE
    ldi     Idx, 0
    mov     SvAddr, P_CTL
CS_FIND:
    lbbo    &SvWord, SvAddr, 0, CTL_SIZE
    qbbs    CS_FIND_NEXT, SvFlags, 2        // BISS_SLV_SF_NO_CONTROL
    qbne    CS_FIND_NEXT, SvId, Scr2
    mov     Cs.slave, Idx
    ldi     Cs.state, BISS_SLV_CS_RWS
    qba     CS_DONE
CS_FIND_NEXT:
    add     SvAddr, SvAddr, CTL_SIZE
    add     Idx, Idx, 1
    qbne    CS_FIND, Idx, NSlaves
    qba     CS_DONE
CS_COMMAND:
    // a command: IDS (bits 9..2, bit 9 for ID 0), CMD (1..0)
    lsr     Scr2, Scr, 2
    mov     Cs.ids, Scr2
    and     Cs.cmd, Scr, 3
    ldi     Cs.bcast, 0
    qbne    CS_COMMAND_IDS, Cs.ids, 0
    ldi     Cs.bcast, 1
CS_COMMAND_IDS:
    ldi     Cs.state, BISS_SLV_CS_IDA
    // the answer to the CRC's last bit: IDA slot 0
    ldi     Scr, 0
    jal     RET_LEAF, IDA_BIT
    qba     CS_DONE

// ---- R, W, and the master's S --------------------------------------------
CS_RWS:
    lsl     Cs.shift, Cs.shift, 1
    or      Cs.shift, Cs.shift, CDM_IN
    add     Cs.count, Cs.count, 1
    qbeq    CS_RWS_S, Cs.count, 3
    mov     CDS_OUT, CDM_IN                 // the echo of R, then of W
    qba     CS_DONE
CS_RWS_S:
    and     Rws, Cs.shift, 7
    ldi     Cs.write, 1
    qbeq    CS_ACCESS, Rws, 3               // 0 1 1: write
    ldi     Cs.write, 0
    qbeq    CS_ACCESS, Rws, 5               // 1 0 1: read
    ldi     Cs.state, BISS_SLV_CS_IGNORE
    qba     CS_DONE
// The slave's S after a master's S: late (REG_WAIT frames of 0) or at once.
CS_ACCESS:
    jal     RET_LEAF, SLAVE_SETTINGS
    qbeq    CS_ACCESS_NOW, SvWait, 0
    mov     Cs.wait_left, SvWait
    ldi     Cs.state, BISS_SLV_CS_WAIT
    qba     CS_DONE
CS_ACCESS_NOW:
    jal     RET_SUB, DATA_BEGIN
    ldi     CDS_OUT, 1
    qba     CS_DONE

// ---- late S ------------------------------------------------------------------
CS_WAIT:
    sub     Cs.wait_left, Cs.wait_left, 1
    qbne    CS_DONE, Cs.wait_left, 0
    jal     RET_LEAF, SLAVE_SETTINGS
    jal     RET_SUB, DATA_BEGIN
    ldi     CDS_OUT, 1
    qba     CS_DONE

// ---- 8 data bits: the register's (read) or the echo (write) -------------------
CS_DATA:
    qbeq    CS_DATA_READ, Cs.write, 0
    lsl     Cs.value, Cs.value, 1
    or      Cs.value, Cs.value, CDM_IN
    mov     CDS_OUT, CDM_IN
    qba     CS_DATA_NEXT
CS_DATA_READ:
    rsb     Scr, Cs.count, 7
    lsr     Scr2, Cs.value, Scr
    and     CDS_OUT, Scr2, 1
CS_DATA_NEXT:
    add     Cs.count, Cs.count, 1
    qbne    CS_DONE, Cs.count, 8
    // the slave's CRC4 of the byte, inverted: 8 steps
    ldi     Cs.crc4, 0
    ldi     BitsLeft, 8
CS_DATA_CRC:
    sub     BitsLeft, BitsLeft, 1
    lsr     Bit, Cs.value, BitsLeft
    and     Bit, Bit, 1
    CRC4_STEP Bit
    qbne    CS_DATA_CRC, BitsLeft, 0
    not     Cs.scrc, Cs.crc4
    and     Cs.scrc, Cs.scrc, 0x0f
    ldi     Cs.state, BISS_SLV_CS_DCRC
    ldi     Cs.count, 0
    ldi     Cs.shift, 0
    qba     CS_DONE

// ---- 4 CRC bits: the slave's out, the master's in -----------------------------
CS_DCRC:
    lsl     Cs.shift, Cs.shift, 1
    or      Cs.shift, Cs.shift, CDM_IN
    rsb     Scr, Cs.count, 3
    lsr     Scr2, Cs.scrc, Scr
    and     CDS_OUT, Scr2, 1
    add     Cs.count, Cs.count, 1
    qbne    CS_DONE, Cs.count, 4
    ldi     Cs.state, BISS_SLV_CS_STOP
    jal     RET_LEAF, SLAVE_SETTINGS
    // the status: the register and its byte
    ldi     Addr, BISS_SLV_ST_SLAVE0
    lsl     Scr, Cs.slave, 4
    add     Addr, Addr, Scr
    sbbo    Cs.addr, Addr, BISS_SLV_SS_LAST_ADDR, 1
    sbbo    Cs.value, Addr, BISS_SLV_SS_LAST_VALUE, 1
    qbeq    CS_DCRC_READ, Cs.write, 0
    // a write: stored if its CRC is right and the register takes it
    and     Scr, Cs.shift, 0x0f
    qbeq    CS_DCRC_CRC_OK, Scr, Cs.scrc
    add     Addr, Addr, BISS_SLV_SS_CRC_ERRORS
    qba     CS_COUNT
CS_DCRC_CRC_OK:
    mov     Value, Cs.value
    jal     RET_SUB, REG_WRITE
    ldi     Addr, BISS_SLV_ST_SLAVE0        // (REG_WRITE used it)
    lsl     Scr, Cs.slave, 4
    add     Addr, Addr, Scr
    add     Addr, Addr, BISS_SLV_SS_WRITES
    qbne    CS_COUNT, Ok, 0
    add     Addr, Addr, BISS_SLV_SS_REFUSED - BISS_SLV_SS_WRITES
    qba     CS_COUNT
CS_DCRC_READ:
    add     Addr, Addr, BISS_SLV_SS_READS
// A u16 counter at Addr, + 1.
CS_COUNT:
    lbbo    Count16, Addr, 0, 2
    add     Count16, Count16, 1
    sbbo    Count16, Addr, 0, 2
    qba     CS_DONE

// ---- P, then S: the next register, or the end --------------------------------
CS_STOP:
    ldi     Cs.state, BISS_SLV_CS_SEQ
    qba     CS_DONE
CS_SEQ:
    qbeq    CS_FINISH, CDM_IN, 0
    add     Cs.addr, Cs.addr, 1
    and     Cs.addr, Cs.addr, 0x7f
    qba     CS_ACCESS

// ---- a command's IDA slots, then its execute bit --------------------------------
CS_IDA:
    add     Cs.count, Cs.count, 1
    qbeq    CS_IDA_LAST, Cs.count, 8
    mov     Scr, Cs.count
    jal     RET_LEAF, IDA_BIT
    qba     CS_DONE
CS_IDA_LAST:
    ldi     Cs.state, BISS_SLV_CS_EXEC
    qba     CS_DONE
CS_EXEC:
    // every answering slave the command addresses executes it, or drops it
    // on the other value
    ldi     Idx, 0
    mov     SvAddr, P_CTL
CS_EXEC_SLAVE:
    lbbo    &SvWord, SvAddr, 0, CTL_SIZE
    qbbs    CS_EXEC_NEXT, SvFlags, 2        // BISS_SLV_SF_NO_CONTROL
    qbne    CS_EXEC_ADDRESSED, Cs.bcast, 0
    rsb     Scr, SvId, 7
    lsr     Scr2, Cs.ids, Scr
    qbbc    CS_EXEC_NEXT, Scr2, 0
CS_EXEC_ADDRESSED:
    lsr     Bit, SvFlags, 3                 // BISS_SLV_SF_EXEC_0: 1 executes on 0
    and     Bit, Bit, 1
    xor     Bit, Bit, 1                     // the executing value
    ldi     Addr, BISS_SLV_ST_SLAVE0
    lsl     Scr, Idx, 4
    add     Addr, Addr, Scr
    qbne    CS_EXEC_DROP, Bit, CDM_IN
    sbbo    Cs.cmd, Addr, BISS_SLV_SS_LAST_CMD, 1
    add     Addr, Addr, BISS_SLV_SS_COMMANDS
    qba     CS_EXEC_COUNT
CS_EXEC_DROP:
    add     Addr, Addr, BISS_SLV_SS_DROPPED
CS_EXEC_COUNT:
    lbbo    Count16, Addr, 0, 2
    add     Count16, Count16, 1
    sbbo    Count16, Addr, 0, 2
CS_EXEC_NEXT:
    add     SvAddr, SvAddr, CTL_SIZE
    add     Idx, Idx, 1
    qbne    CS_EXEC_SLAVE, Idx, NSlaves
// The control frame is over: 14 fresh zeros before the next, this CDM the
// first if it is one.
CS_FINISH:
    ldi     Cs.state, BISS_SLV_CS_IDLE
    ldi     Cs.armed, 0
    xor     Cs.zeros, CDM_IN, 1
    ldi     CDS_OUT, 0
    qba     CS_STORE

CS_DONE:
    // 14 zeros cancel a control frame in any state (a frame this zero
    // ended as its layout says has ended already: CS_FINISH)
    qbeq    CS_STORE, InFrame, 0
    qbeq    CS_STORE, Cs.state, BISS_SLV_CS_IDLE
    qbgt    CS_STORE, Cs.zeros, ARM_ZEROS
    ldi     Cs.state, BISS_SLV_CS_IDLE
    ldi     Cs.armed, 1
    ldi     CDS_OUT, 0
    ldi     Addr, BISS_SLV_ST_CANCELS
    lbbo    Count16, Addr, 0, 2
    add     Count16, Count16, 1
    sbbo    Count16, Addr, 0, 2
CS_STORE:
    // quiet from here on when idle and armed: a CDM = 0 then changes
    // nothing (between.p skips the step)
    ldi     CTRL_QUIET, 0
    qbne    CS_QUIET_DONE, Cs.state, BISS_SLV_CS_IDLE
    qbeq    CS_QUIET_DONE, Cs.armed, 0
    ldi     CTRL_QUIET, 1
CS_QUIET_DONE:
    ldi     Addr, P_CTRL
    sbbo    &Cs, Addr, 0, SIZE(CtrlState)
    ldi     Addr, BISS_SLV_ST_CDS
    sbbo    CDS_OUT, Addr, 0, 1
    sbbo    Cs.state, Addr, 1, 1            // ST_CTRL_STATE
    jmp     RetStep

// ---- helpers -------------------------------------------------------------------
// IDA_BIT: CDS_OUT = 1 when the command addresses (not broadcast) ID Scr
// and an answering slave has it. Returns through RET_LEAF.
IDA_BIT:
    ldi     CDS_OUT, 0
    qbne    IDA_BIT_DONE, Cs.bcast, 0
    rsb     Scr2, Scr, 7
    lsr     Scr2, Cs.ids, Scr2
    qbbc    IDA_BIT_DONE, Scr2, 0
    lsr     Scr2, Idl, Scr
    and     CDS_OUT, Scr2, 1
IDA_BIT_DONE:
    jmp     RET_LEAF

// SLAVE_SETTINGS: the addressed slave's SlvCtl (SvWord, SvWord2: flags ..
// first bank) from SvAddr, and its register file in Base.
SLAVE_SETTINGS:
    lsl     SvAddr, Cs.slave, 3             // P_CTL + 8 slave
    mov     Scr, P_CTL
    add     SvAddr, SvAddr, Scr
    lbbo    &SvWord, SvAddr, 0, CTL_SIZE
    lsl     Base, Cs.slave, 6               // Base = BISS_SLV_REGS + 96 slave
    lsl     Scr, Cs.slave, 5
    add     Base, Base, Scr
    ldi     Scr, BISS_SLV_REGS
    add     Base, Base, Scr
    jmp     RET_LEAF

// DATA_BEGIN: the data bits next; a read loads the register's byte.
// Returns through RET_SUB.
DATA_BEGIN:
    ldi     Cs.state, BISS_SLV_CS_DATA
    ldi     Cs.count, 0
    ldi     Cs.value, 0
    qbne    DATA_BEGIN_DONE, Cs.write, 0
    // REG_READ: 0x40..0x7F direct; 0x00..0x3F in the bank the byte at
    // 0x40 selects, 0 when the slave has no such bank
    qbbc    DB_BANKED, Cs.addr, 6
    and     Scr, Cs.addr, 0x3f
    lbbo    Cs.value, Base, Scr, 1
    qba     DATA_BEGIN_DONE
DB_BANKED:
    lbbo    Scr2, Base, 0, 1                // the bank select, 0x40
    and     Scr2, Scr2, 0xff
    qble    DATA_BEGIN_DONE, Scr2, SvBanks  // banks <= bank: none
    jal     RET_LEAF, BANK_ADDR
    lbbo    Cs.value, Scr, 0, 1
DATA_BEGIN_DONE:
    jmp     RET_SUB

// BANK_ADDR: Scr = the pool address of address Cs.addr (< 0x40) in bank
// Scr2 (< SvBanks) of the slave. Returns through RET_LEAF.
BANK_ADDR:
    add     Scr, Scr2, SvBank0
    lsl     Scr, Scr, 6
    add     Scr, Scr, Cs.addr
    ldi     Scr2, BISS_SLV_POOL
    add     Scr, Scr, Scr2
    jmp     RET_LEAF

// REG_WRITE: Value to Cs.addr of the slave; Ok = 1 when stored, 0 when
// refused (read-only, write-protected while SF_PROTECT, a missing bank).
// Returns through RET_SUB.
REG_WRITE:
    ldi     Ok, 0
    lsr     Scr, Cs.addr, 3                 // the access bits: byte addr / 8,
    and     Scr2, Cs.addr, 7                //   bit addr % 8
    add     Addr, Base, BISS_SLV_R_RO
    lbbo    Bit, Addr, Scr, 1
    lsr     Bit, Bit, Scr2
    qbbs    RW_DONE, Bit, 0
    qbbc    RW_OPEN, SvFlags, 4             // BISS_SLV_SF_PROTECT
    add     Addr, Base, BISS_SLV_R_WP
    lbbo    Bit, Addr, Scr, 1
    lsr     Bit, Bit, Scr2
    qbbs    RW_DONE, Bit, 0
RW_OPEN:
    qbbc    RW_BANKED, Cs.addr, 6
    and     Scr, Cs.addr, 0x3f
    sbbo    Value, Base, Scr, 1
    ldi     Ok, 1
    qba     RW_DONE
RW_BANKED:
    lbbo    Scr2, Base, 0, 1
    and     Scr2, Scr2, 0xff
    qble    RW_DONE, Scr2, SvBanks
    jal     RET_LEAF, BANK_ADDR
    sbbo    Value, Scr, 0, 1
    ldi     Ok, 1
RW_DONE:
    jmp     RET_SUB
.leave ctrl
