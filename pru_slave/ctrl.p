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
// A chain has one control frame for all, but the slaves' parts in it
// differ: every slave sees the same CDM and keeps its own state (as the
// slave model does, one state machine each), and the CDS is the OR of the
// slaves' answers. Their states fall into a few groups, kept as masks of
// slaves (bit k: slave k) beside one state machine:
//   - active: the slaves in the control frame, all in Cs.state (IDLE: none);
//     the slaves armed at its S, then, after a register access's header,
//     the addressed slave alone
//   - ignore: the slaves a header did not address, or that took a wrong
//     CRC or R W S, until 14 zeros cancel the frame for them
//   - armed: idle after 14 zeros; a CDM = 1 is their S
//   - the rest of `all` (the slaves taking part, not SF_NO_CONTROL): idle,
//     waiting for 14 zeros: counted from the last CDM = 1 (Cs.zeros), or,
//     for the slaves that ended a control frame since it (fmask), from that
//     end (Cs.fzeros: "14 fresh zeros"; the end's own CDM = 0 the first)
// Which groups can be there at once follows from the zeros: a slave arms
// after 14 zeros with no CDM = 1 among them, which cancel a control frame,
// so a CDM = 1 finds either armed slaves (and no control frame) or a
// control frame (and no armed slave). The register files and the command
// counters are per slave; the slave of an ID is found through
// SlvCtl.by_id (config.p). ST_CANCELS and ST_HDR_CRC_ERRORS count events
// (the slaves of a chain that one cancels count it once).

#define CRC4_POLY       0x03            // 0x13 without its top term
#define ARM_ZEROS       14
#define CF_WRITE        0               // Cs.flags: a write access (else a read)
#define CF_BCAST        1               //   a command to all (IDS = 0)
#define CF_ACCESS       2               //   COMMIT: an access's CRC has come (its end)
#define CF_EXEC         3               //   COMMIT: a command's execute bit has come,
#define CF_EXEC_CDM     4               //     this one
#define CF_LOAD         5               //   COMMIT: a read's byte to load (into value)
#define CF_CANCEL       6               //   COMMIT: a cancel to count (ST_CANCELS)
#define CF_HDR_ERROR    7               //   COMMIT: a header CRC error to count

.enter ctrl
.assign CtrlState, r1, r4, Cs           // the state (layout.hp), loaded and stored whole
.assign Byte, r2.b3, r2.b3, Ids         // (Cs.addr: a command's IDS, bit 7 for ID 0)
.assign Byte, r3.b1, r3.b1, Cmd         // (Cs.value: a command's CMD)
.assign Word, r5, r5, NsWord            // P_NSLAVES' word:
.assign Byte, r5.b0, r5.b0, NSlaves     //   slaves
.assign Byte, r5.b3, r5.b3, IdlCts      //   the IDs whose ID lock answers CTS
.assign Byte, r6.b1, r6.b1, Bit         // scratch bits
.assign Byte, r6.b2, r6.b2, Fb          //   (the CRC4 feedback)
.assign Byte, r6.b3, r6.b3, Rws
.assign Byte, r6.b0, r6.b0, Grp         // ID_SLOT: the group asked about
.assign Word, r7, r7, Addr              // an address in data RAM
.assign Word, r8, r8, Scr               // scratch
.assign Word, r9, r9, Scr2
.assign Word, r10, r10, Base            // a slave's register file
.assign Word, r11, r11, Mask            // a mask of slaves
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
.assign Byte, r15.b3, r15.b3, Answer    // ID_SLOT: 1 when the group has the ID
.assign Half, r25.w0, r25.w0, Count16   // a u16 counter
.assign Word, r26, r26, RetStep         // CTRL_STEP's own return (RET_SUB is reused inside)
.assign Half, r27.w2, r27.w2, RetIda    // IDA_BIT's return
.assign Half, r27.w0, r27.w0, RetCommit // COMMIT's

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

// A u16 counter at Addr, + 1.
.macro COUNT16
    lbbo    Count16, Addr, 0, 2
    add     Count16, Count16, 1
    sbbo    Count16, Addr, 0, 2
.endm

CTRL_STEP:
    mov     RetStep, RET_SUB
    ldi     Addr, P_CTRL                    // Cs, then P_NSLAVES' word
    lbbo    &Cs, Addr, 0, SIZE(CtrlState) + 4
    qbbc    CS_COMMITTED, CTRL_FLAGS, CTRL_PENDING
    jal     RetCommit, COMMIT               // the last step's work, if PREWORK did not
CS_COMMITTED:
    ldi     CDS_OUT, 0
    qbne    CS_ONE, CDM_IN, 0
    // ---- CDM = 0: the zeros (up to 255); idle slaves with 14 arm -------------
    qbeq    CS_ZERO_F, Cs.zeros, 255
    add     Cs.zeros, Cs.zeros, 1
CS_ZERO_F:
    qbeq    CS_ZERO_ARM, Cs.fzeros, 255
    add     Cs.fzeros, Cs.fzeros, 1
CS_ZERO_ARM:
    qbgt    CS_GROUP, Cs.zeros, ARM_ZEROS   // fzeros <= zeros
    or      Mask, Cs.active, Cs.ignore      // the idle slaves not armed
    or      Mask, Mask, Cs.armed
    not     Mask, Mask
    and     Mask, Mask, Cs.all
    qbeq    CS_GROUP, Mask, 0
    not     Scr, Cs.fmask                   // those counting from the last 1
    and     Scr, Scr, Mask
    or      Cs.armed, Cs.armed, Scr
    qbgt    CS_GROUP, Cs.fzeros, ARM_ZEROS  // those counting from their frame's end
    and     Scr, Mask, Cs.fmask
    or      Cs.armed, Cs.armed, Scr
    ldi     Cs.fmask, 0
    qba     CS_GROUP
    // ---- CDM = 1: the start S for the armed slaves -----------------------------
CS_ONE:
    ldi     Cs.zeros, 0
    ldi     Cs.fzeros, 0
    ldi     Cs.fmask, 0
    qbeq    CS_GROUP, Cs.armed, 0
    mov     Cs.active, Cs.armed             // (no control frame was under way)
    ldi     Cs.armed, 0
    ldi     Cs.state, BISS_SLV_CS_HEADER
    ldi     Cs.count, 0
    ldi     Cs.shift, 0
    ldi     Cs.crc4, 0
    // the ID lock's first slot, IDL0, answers S itself (host/CD.md, "IDL
    // slots": an encoder maker's open master reads it there): before CTS
    // has come, so in every control frame
    ldi     Scr, 0
    mov     Grp, Cs.active
    jal     RET_LEAF, ID_SLOT
    qbbs    CS_STORE, IdlCts, 0
    mov     CDS_OUT, Answer
    qba     CS_STORE

// ---- the active group's step ---------------------------------------------------
CS_GROUP:
    qbeq    CS_DONE, Cs.state, BISS_SLV_CS_IDLE
    qbeq    CS_HEADER, Cs.state, BISS_SLV_CS_HEADER
    qbeq    CS_RWS, Cs.state, BISS_SLV_CS_RWS
    qbeq    CS_WAIT, Cs.state, BISS_SLV_CS_WAIT
    qbeq    CS_DATA, Cs.state, BISS_SLV_CS_DATA
    qbeq    CS_DCRC, Cs.state, BISS_SLV_CS_DCRC
    qbeq    CS_STOP, Cs.state, BISS_SLV_CS_STOP
    qbeq    CS_SEQ, Cs.state, BISS_SLV_CS_SEQ
    qbeq    CS_IDA, Cs.state, BISS_SLV_CS_IDA
    qba     CS_EXEC

// ---- the header: 15 bits; the CRC4 over the first 11 --------------------------
CS_HEADER:
    lsl     Cs.shift, Cs.shift, 1
    or      Cs.shift, Cs.shift, CDM_IN
    add     Cs.count, Cs.count, 1
    qblt    CS_HEADER_CRC, Cs.count, 11     // 11 < count: a CRC bit
    CRC4_STEP CDM_IN
CS_HEADER_CRC:
    qbeq    CS_HEADER_DONE, Cs.count, 15
    // The ID lock, 1 in slot i for the slave of ID i: the answer to header
    // bit k = count - 1 (k = 0: CTS) is slot k + 1 for a slave answering
    // from S on; slot k for one answering from CTS on, in a register access
    qblt    CS_DONE, Cs.count, 8            // 8 < count: k >= 8
    mov     Grp, Cs.active
    qbeq    CS_HEADER_CTS, Cs.count, 8      // slot 8: none
    mov     Scr, Cs.count                   // from S: slot count
    jal     RET_LEAF, ID_SLOT
    qbbs    CS_HEADER_CTS, Scr2, 0          //   (not if that ID answers at CTS)
    mov     CDS_OUT, Answer
CS_HEADER_CTS:
    qbeq    CS_DONE, IdlCts, 0              // (no slave answers at CTS)
    sub     Scr, Cs.count, 1
    lsr     Scr2, Cs.shift, Scr             // CTS, the first bit
    qbbc    CS_DONE, Scr2, 0
    jal     RET_LEAF, ID_SLOT               // from CTS: slot k
    qbbc    CS_DONE, Scr2, 0                //   (if that ID answers there)
    or      CDS_OUT, CDS_OUT, Answer
    qba     CS_DONE
CS_HEADER_DONE:
    // the CRC: the 4 bits received must be the inverted CRC4
    not     Scr, Cs.crc4
    and     Scr, Scr, 0x0f
    and     Scr2, Cs.shift, 0x0f
    qbeq    CS_HEADER_OK, Scr, Scr2
    set     Cs.flags, Cs.flags, CF_HDR_ERROR    // (counted by COMMIT)
    set     CTRL_FLAGS, CTRL_FLAGS, CTRL_PENDING
    qba     CS_DROP
CS_HEADER_OK:
    lsr     Scr, Cs.shift, 4                // CTS and the 10 bits
    ldi     Cs.count, 0
    ldi     Cs.shift, 0
    qbbc    CS_COMMAND, Scr, 10
    // a register access: ID (bits 9..7), ADR (6..0): the slave of that ID
    // goes on if it is in the group, the others ignore the frame
    and     Cs.addr, Scr, 0x7f
    lsr     Scr, Scr, 7
    and     Scr, Scr, 7
    mov     Grp, Cs.active
    jal     RET_LEAF, ID_SLOT
    qbeq    CS_DROP, Answer, 0
    mov     Cs.slave, Idx
    ldi     Mask, 0
    set     Mask, Mask, Idx
    xor     Scr, Cs.active, Mask
    or      Cs.ignore, Cs.ignore, Scr
    mov     Cs.active, Mask
    ldi     Cs.state, BISS_SLV_CS_RWS
    qba     CS_DONE
CS_COMMAND:
    // a command: IDS (bits 9..2, bit 9 for ID 0), CMD (1..0), for the
    // whole group
    lsr     Ids, Scr, 2
    and     Cmd, Scr, 3
    ldi     Cs.flags, 0
    qbne    CS_COMMAND_IDS, Ids, 0
    set     Cs.flags, Cs.flags, CF_BCAST
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
    ldi     Cs.flags, 0
    set     Cs.flags, Cs.flags, CF_WRITE
    qbeq    CS_ACCESS, Rws, 3               // 0 1 1: write
    ldi     Cs.flags, 0
    qbeq    CS_ACCESS, Rws, 5               // 1 0 1: read
    qba     CS_DROP
// The slave's S after a master's S: late (REG_WAIT frames of 0) or at once.
CS_ACCESS:
    lsl     Addr, Cs.slave, 3               // its SlvCtl.reg_wait
    ldi     Scr, P_CTL
    add     Addr, Addr, Scr
    lbbo    SvWait, Addr, OFFSET(SlvCtl.reg_wait), 1
    qbeq    CS_DATA_BEGIN, SvWait, 0
    mov     Cs.count, SvWait                // (WAIT: the frames left)
    ldi     Cs.state, BISS_SLV_CS_WAIT
    qba     CS_DONE

// ---- late S ------------------------------------------------------------------
CS_WAIT:
    sub     Cs.count, Cs.count, 1
    qbne    CS_DONE, Cs.count, 0
// The slave's S, then the data bits; a read's byte is COMMIT's to load.
CS_DATA_BEGIN:
    ldi     Cs.state, BISS_SLV_CS_DATA
    ldi     Cs.count, 0
    ldi     Cs.value, 0
    ldi     Cs.crc4, 0
    ldi     CDS_OUT, 1
    qbbs    CS_DONE, Cs.flags, CF_WRITE
    set     Cs.flags, Cs.flags, CF_LOAD
    set     CTRL_FLAGS, CTRL_FLAGS, CTRL_PENDING
    qba     CS_DONE

// ---- 8 data bits: the register's (read) or the echo (write); the slave's
// CRC4 of them as they go (DATA_BEGIN starts it), inverted after the 8th ----
CS_DATA:
    qbbc    CS_DATA_READ, Cs.flags, CF_WRITE
    lsl     Cs.value, Cs.value, 1
    or      Cs.value, Cs.value, CDM_IN
    mov     CDS_OUT, CDM_IN
    qba     CS_DATA_NEXT
CS_DATA_READ:
    rsb     Scr, Cs.count, 7
    lsr     Scr2, Cs.value, Scr
    and     CDS_OUT, Scr2, 1
CS_DATA_NEXT:
    CRC4_STEP CDS_OUT
    add     Cs.count, Cs.count, 1
    qbne    CS_DONE, Cs.count, 8
    not     Cs.crc4, Cs.crc4                // the slave's CRC4 of the byte, inverted
    and     Cs.crc4, Cs.crc4, 0x0f
    ldi     Cs.state, BISS_SLV_CS_DCRC
    ldi     Cs.count, 0
    ldi     Cs.shift, 0
    qba     CS_DONE

// ---- 4 CRC bits: the slave's out, the master's in -----------------------------
CS_DCRC:
    lsl     Cs.shift, Cs.shift, 1
    or      Cs.shift, Cs.shift, CDM_IN
    rsb     Scr, Cs.count, 3
    lsr     Scr2, Cs.crc4, Scr
    and     CDS_OUT, Scr2, 1
    add     Cs.count, Cs.count, 1
    qbne    CS_DONE, Cs.count, 4
    ldi     Cs.state, BISS_SLV_CS_STOP
    set     Cs.flags, Cs.flags, CF_ACCESS   // the access's end, for COMMIT
    set     CTRL_FLAGS, CTRL_FLAGS, CTRL_PENDING
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
    // every slave of the group the command addresses executes it, or
    // drops it on the other value: COMMIT counts which (the group is in
    // fmask then)
    set     Cs.flags, Cs.flags, CF_EXEC
    qbeq    CS_EXEC_PENDING, CDM_IN, 0
    set     Cs.flags, Cs.flags, CF_EXEC_CDM
CS_EXEC_PENDING:
    set     CTRL_FLAGS, CTRL_FLAGS, CTRL_PENDING
// The control frame is over for the group: 14 fresh zeros before its next,
// this CDM the first if it is one.
CS_FINISH:
    mov     Cs.fmask, Cs.active
    xor     Cs.fzeros, CDM_IN, 1
    ldi     Cs.active, 0
    ldi     Cs.state, BISS_SLV_CS_IDLE
    ldi     CDS_OUT, 0
    qba     CS_DONE

// The group ignores the rest of the frame (a wrong header CRC, no slave of
// the ID, a wrong R W S).
CS_DROP:
    or      Cs.ignore, Cs.ignore, Cs.active
    ldi     Cs.active, 0
    ldi     Cs.state, BISS_SLV_CS_IDLE
    ldi     CDS_OUT, 0

CS_DONE:
    // 14 zeros cancel a control frame in any state, and end the ignoring
    // (a frame this zero ended as its layout says has ended already:
    // CS_FINISH, no longer active)
    qbgt    CS_STORE, Cs.zeros, ARM_ZEROS
    or      Mask, Cs.active, Cs.ignore
    qbeq    CS_STORE, Mask, 0
    or      Cs.armed, Cs.armed, Mask
    ldi     Cs.active, 0
    ldi     Cs.ignore, 0
    ldi     Cs.state, BISS_SLV_CS_IDLE
    ldi     CDS_OUT, 0
    set     Cs.flags, Cs.flags, CF_CANCEL   // (counted by COMMIT)
    set     CTRL_FLAGS, CTRL_FLAGS, CTRL_PENDING
CS_STORE:
    // quiet from here on when every slave is armed: a CDM = 0 then changes
    // nothing (between.p skips the step)
    clr     CTRL_FLAGS, CTRL_FLAGS, CTRL_QUIET
    qbne    CS_QUIET_DONE, Cs.armed, Cs.all
    set     CTRL_FLAGS, CTRL_FLAGS, CTRL_QUIET
CS_QUIET_DONE:
    ldi     Addr, P_CTRL
    sbbo    &Cs, Addr, 0, SIZE(CtrlState)
    ldi     Addr, BISS_SLV_ST_CDS
    sbbo    CDS_OUT, Addr, 0, 1
    // ST_CTRL_STATE: the group's, or IGNORE while only ignoring slaves are
    // in the frame
    mov     Scr, Cs.state
    qbne    CS_STATE, Cs.active, 0
    qbeq    CS_STATE, Cs.ignore, 0
    ldi     Scr, BISS_SLV_CS_IGNORE
CS_STATE:
    sbbo    Scr, Addr, 1, 1                 // ST_CTRL_STATE
    jmp     RetStep

// ---- COMMIT: the work a step leaves for later ---------------------------------
// The status and the register file at the end of an access, and the
// commands of an execute bit, need not be done before the next frame's
// CDS: a step leaves them to COMMIT (CTRL_PENDING), which runs in the next
// frame's tail (PREWORK, through CTRL_COMMIT) or, in a frame without one,
// at the start of the next step; so that the work after the timeout's end
// stays short (WORK_PAD). Nothing they change is read before: the state a
// step leaves for them (the access: slave, addr, value, the master's CRC in
// shift, the slave's in crc4; the command: the group in fmask, IDS, CMD)
// stays until the next step.

// CTRL_COMMIT: COMMIT from PREWORK (between.p). Returns through RET_SUB.
CTRL_COMMIT:
    mov     RetStep, RET_SUB
    ldi     Addr, P_CTRL                    // Cs, then P_NSLAVES' word
    lbbo    &Cs, Addr, 0, SIZE(CtrlState) + 4
    jal     RetCommit, COMMIT
    ldi     Addr, P_CTRL
    sbbo    &Cs, Addr, 0, SIZE(CtrlState)
    jmp     RetStep

// COMMIT, on the state in Cs. Returns through RetCommit.
COMMIT:
    clr     CTRL_FLAGS, CTRL_FLAGS, CTRL_PENDING
    qbbc    COMMIT_HDR, Cs.flags, CF_CANCEL
    clr     Cs.flags, Cs.flags, CF_CANCEL
    ldi     Addr, BISS_SLV_ST_CANCELS
    COUNT16
COMMIT_HDR:
    qbbc    COMMIT_LOAD, Cs.flags, CF_HDR_ERROR
    clr     Cs.flags, Cs.flags, CF_HDR_ERROR
    ldi     Addr, BISS_SLV_ST_HDR_CRC_ERRORS
    COUNT16
COMMIT_LOAD:
    qbbc    COMMIT_ACCESS, Cs.flags, CF_LOAD
    clr     Cs.flags, Cs.flags, CF_LOAD
    // a read's byte: 0x40..0x7F direct; 0x00..0x3F in the bank the byte at
    // 0x40 selects, 0 when the slave has no such bank
    jal     RET_LEAF, SLAVE_SETTINGS
    qbbc    COMMIT_BANKED, Cs.addr, 6
    and     Scr, Cs.addr, 0x3f
    lbbo    Cs.value, Base, Scr, 1
    qba     COMMIT_ACCESS
COMMIT_BANKED:
    lbbo    Scr2, Base, 0, 1                // the bank select, 0x40
    and     Scr2, Scr2, 0xff
    qble    COMMIT_ACCESS, Scr2, SvBanks    // banks <= bank: none
    jal     RET_LEAF, BANK_ADDR
    lbbo    Cs.value, Scr, 0, 1
COMMIT_ACCESS:
    qbbc    COMMIT_EXEC, Cs.flags, CF_ACCESS
    clr     Cs.flags, Cs.flags, CF_ACCESS
    // the access: the register and its byte in the status
    jal     RET_LEAF, SLAVE_SETTINGS
    ldi     Addr, BISS_SLV_ST_SLAVE0
    lsl     Scr, Cs.slave, 4
    add     Addr, Addr, Scr
    sbbo    Cs.addr, Addr, BISS_SLV_SS_LAST_ADDR, 1
    sbbo    Cs.value, Addr, BISS_SLV_SS_LAST_VALUE, 1
    qbbc    COMMIT_READ, Cs.flags, CF_WRITE
    // a write: stored if its CRC is right and the register takes it
    and     Scr, Cs.shift, 0x0f
    qbeq    COMMIT_CRC_OK, Scr, Cs.crc4
    add     Addr, Addr, BISS_SLV_SS_CRC_ERRORS
    qba     COMMIT_COUNT
COMMIT_CRC_OK:
    mov     Value, Cs.value
    jal     RET_SUB, REG_WRITE
    ldi     Addr, BISS_SLV_ST_SLAVE0        // (REG_WRITE used it)
    lsl     Scr, Cs.slave, 4
    add     Addr, Addr, Scr
    add     Addr, Addr, BISS_SLV_SS_WRITES
    qbne    COMMIT_COUNT, Ok, 0
    add     Addr, Addr, BISS_SLV_SS_REFUSED - BISS_SLV_SS_WRITES
    qba     COMMIT_COUNT
COMMIT_READ:
    add     Addr, Addr, BISS_SLV_SS_READS
COMMIT_COUNT:
    COUNT16
COMMIT_EXEC:
    qbbc    COMMIT_DONE, Cs.flags, CF_EXEC
    // the command: each slave of the group it addresses executes it on
    // its executing value of the bit (1, or 0 with SF_EXEC_0) and drops it
    // on the other
    ldi     Idx, 0
    mov     SvAddr, P_CTL
COMMIT_SLAVE:
    lsr     Scr, Cs.fmask, Idx
    qbbc    COMMIT_NEXT, Scr, 0
    lbbo    &SvWord, SvAddr, 0, CTL_SIZE
    qbbs    COMMIT_ADDRESSED, Cs.flags, CF_BCAST
    rsb     Scr, SvId, 7
    lsr     Scr2, Ids, Scr
    qbbc    COMMIT_NEXT, Scr2, 0
COMMIT_ADDRESSED:
    lsr     Bit, SvFlags, 3                 // BISS_SLV_SF_EXEC_0: 1 executes on 0
    lsr     Scr, Cs.flags, CF_EXEC_CDM      // the bit
    xor     Bit, Bit, Scr
    ldi     Addr, BISS_SLV_ST_SLAVE0
    lsl     Scr, Idx, 4
    add     Addr, Addr, Scr
    qbbc    COMMIT_DROP, Bit, 0             // (flags ^ bit) & 1 = 0: not its value
    sbbo    Cmd, Addr, BISS_SLV_SS_LAST_CMD, 1
    add     Addr, Addr, BISS_SLV_SS_COMMANDS
    qba     COMMIT_EXEC_COUNT
COMMIT_DROP:
    add     Addr, Addr, BISS_SLV_SS_DROPPED
COMMIT_EXEC_COUNT:
    COUNT16
COMMIT_NEXT:
    add     SvAddr, SvAddr, CTL_SIZE
    add     Idx, Idx, 1
    qbne    COMMIT_SLAVE, Idx, NSlaves
    clr     Cs.flags, Cs.flags, CF_EXEC
    clr     Cs.flags, Cs.flags, CF_EXEC_CDM
COMMIT_DONE:
    jmp     RetCommit

// ---- helpers -------------------------------------------------------------------
// IDA_BIT: CDS_OUT = 1 when the command addresses (not broadcast) ID Scr
// and the group has the slave of that ID. Returns through RET_LEAF (its
// own return in RetIda: it calls ID_SLOT).
IDA_BIT:
    ldi     CDS_OUT, 0
    qbbs    IDA_BIT_DONE, Cs.flags, CF_BCAST
    rsb     Scr2, Scr, 7
    lsr     Scr2, Ids, Scr2
    qbbc    IDA_BIT_DONE, Scr2, 0
    mov     RetIda, RET_LEAF
    mov     Grp, Cs.active
    jal     RET_LEAF, ID_SLOT
    mov     CDS_OUT, Answer
    mov     RET_LEAF, RetIda
IDA_BIT_DONE:
    jmp     RET_LEAF

// ID_SLOT: for ID Scr (0..7), Idx = the index of the answering slave of
// that ID (0xff: none; SlvCtl.by_id), Answer = 1 when that slave is in
// the group Grp, and Scr2 = 1 when that ID's lock answers CTS
// (SF_IDL_AT_CTS; IdlCts). Returns through RET_LEAF.
ID_SLOT:
    lsl     Addr, Scr, 3                    // the by_id of entry Scr
    ldi     Scr2, P_CTL
    add     Addr, Addr, Scr2
    lbbo    Idx, Addr, OFFSET(SlvCtl.by_id), 1
    ldi     Answer, 0
    qbbs    ID_SLOT_CTS, Idx, 7             // none
    lsr     Answer, Grp, Idx
    and     Answer, Answer, 1
ID_SLOT_CTS:
    lsr     Scr2, IdlCts, Scr
    and     Scr2, Scr2, 1
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
