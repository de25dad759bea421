// biss_slave_shm.h - the shared-memory interface between the BiSS-C slave
// firmware (pru_slave/, an encoder on either PRU) and the host: byte
// offsets into that PRU's data RAM, flags, error codes and limits.
//
// Read by both sides, like biss_shm.h: by the PRU assembler (pasm dialect:
// nothing but #define lines and // comments) and by C (the struct view in
// biss_slave_shm_struct.h checks every offset at compile time). All values
// are little-endian; offsets are from the start of the PRU's own data RAM
// (local address 0, constant table entry C24). The layout fits the 4 KB
// data RAM of AM437x ICSS0 and keeps the master's identification block
// (BISS_ID..BISS_ID_END of biss_shm.h) at its top.
// (Laid out by hand, in columns: clang-format leaves it alone.)
// clang-format off
//
// Protocol:
//  - The host writes the configuration block (and, as it likes, the
//    register files, the bank pool and the position table), then
//    increments CFG_SEQ. Between two frames (or while idle, within about
//    1.3 ms) the firmware checks and applies it, echoes CFG_SEQ in
//    ST_CFG_ACK and sets ST_CFG_ERROR (0: accepted). Applying restarts
//    every slave: positions from their initial values, life counters at 0,
//    control communication idle, counters cleared. Until a configuration
//    is accepted SL stays low (no slave answers), and after a refused one
//    likewise.
//  - LIVE_EW, the register files, the bank pool and the position table are
//    read by the firmware between frames: a change takes effect from the
//    next frame, without restarting anything.
//  - FRAME_REC is written before the frame it describes: what the slaves
//    will send in the frame numbered REC_FRAME (ST_FRAMES + 1 at that time;
//    frames count from 1). It is written only between frames, so a reader
//    during a frame sees it whole.

#ifndef BISS_SLAVE_SHM_H
#define BISS_SLAVE_SHM_H

#define BISS_SLV_SHM_VERSION        1

// ---- limits -------------------------------------------------------------
#define BISS_SLV_MAX_SLAVES         8
#define BISS_SLV_MAX_DATA_BITS      64      // position + fill + nE + nW + life counter
#define BISS_SLV_MAX_CRC_BITS       16
#define BISS_SLV_MAX_LC_BITS        32
#define BISS_SLV_TABLE_ENTRIES      128     // position table, 8 bytes an entry
#define BISS_SLV_POOL_BANKS         16      // register banks (0x00..0x3F) shared by the slaves
#define BISS_SLV_MAX_TIMEOUT        262140  // PRU cycles (1.31 ms): 65535 poll turns of 4 cycles

// ---- configuration (host writes, then increments CFG_SEQ) ------------------
#define BISS_SLV_CFG_SEQ            0x000   // u32
#define BISS_SLV_CFG_NSLAVES        0x004   // u8:  slaves in the chain, 1..8 (slave 0 nearest the master)
#define BISS_SLV_CFG_TMO_MODE       0x005   // u8:  BISS_SLV_TMO_*
#define BISS_SLV_CFG_TMO_FACTOR     0x006   // u8:  adaptive: the timeout is the MA period x factor / 16
                                            //      (24: 1.5), clamped to [TMO_MIN, TIMEOUT]
#define BISS_SLV_CFG_RSVD0          0x007   // u8:  0
#define BISS_SLV_CFG_TIMEOUT        0x008   // u32: fixed: the timeout; adaptive: its longest; PRU cycles
#define BISS_SLV_CFG_TMO_MIN        0x00C   // u32: adaptive: its shortest, PRU cycles
#define BISS_SLV_CFG_BUSY_CYCLES    0x010   // u32: processing time: the start bit comes no earlier
                                            //      than this many PRU cycles after the ACK edge ...
#define BISS_SLV_CFG_BUSY_CLOCKS    0x014   // u16: ... and no earlier than this many MA clocks after it
#define BISS_SLV_CFG_RSVD1          0x016   // u16: 0
#define BISS_SLV_LIVE_EW            0x018   // u8 per slave (8): BISS_SLV_EW_*, read every frame
#define BISS_SLV_CFG_SLAVE0         0x020   // first of BISS_SLV_MAX_SLAVES slave blocks
#define BISS_SLV_CFG_SLAVE_SIZE     32
// per slave block, offsets within it. The data word, MSB first on the wire:
//   [position (POS_BITS)][fill zeros (FILL_BITS)][nE][nW][life counter (LC_BITS)]
// then the CRC (CRC_BITS, MSB first, inverted) over the data word.
#define BISS_SLV_S_POS_BITS         0       // u8:  1..64
#define BISS_SLV_S_FILL_BITS        1       // u8:  zeros after the position
#define BISS_SLV_S_LC_BITS          2       // u8:  life counter, 0..32: +1 every frame, from 0
#define BISS_SLV_S_FLAGS            3       // u8:  BISS_SLV_SF_*
#define BISS_SLV_S_CRC_BITS         4       // u8:  0..16 (0: no CRC)
#define BISS_SLV_S_ID               5       // u8:  control-communication ID, 0..7
#define BISS_SLV_S_REG_WAIT         6       // u8:  register processing time: frames of S = 0 (late S)
                                            //      before the slave's S in a register access
#define BISS_SLV_S_BANKS            7       // u8:  its register banks in the pool (0..16)
#define BISS_SLV_S_CRC_POLY         8       // u16: CRC polynomial without its top term (0x43 -> 0x03)
#define BISS_SLV_S_CRC_START        10      // u16: CRC start value, < 2^CRC_BITS
#define BISS_SLV_S_BANK0            12      // u8:  its first bank in the pool
#define BISS_SLV_S_TABLE_START      13      // u8:  table mode: its first table entry
#define BISS_SLV_S_TABLE_LEN        14      // u16: 0: the position moves by STEP a frame; 1..128:
                                            //      table mode, frame k sends entry START + k mod LEN
#define BISS_SLV_S_POSITION         16      // u64: the first frame's position (its low POS_BITS)
#define BISS_SLV_S_STEP             24      // u64: counts added every frame, modulo 2^POS_BITS
                                            //      (two's complement: a negative step counts down)
#define BISS_SLV_CFG_END            0x120

#define BISS_SLV_TMO_FIXED          0
#define BISS_SLV_TMO_ADAPTIVE       1

#define BISS_SLV_SF_NE              0x01    // the data word has nE
#define BISS_SLV_SF_NW              0x02    // the data word has nW
#define BISS_SLV_SF_NO_CONTROL      0x04    // a data channel only: never answers control communication
                                            // (its device answers through another slave of the same ID)
#define BISS_SLV_SF_EXEC_0          0x08    // a BiSS command executes on an execute bit of 0 (the
                                            // register access's stop bit P) instead of 1 (iC-MB4's EX)
#define BISS_SLV_SF_PROTECT         0x10    // write-protected registers (WP bits) refuse writes
#define BISS_SLV_SF_IDL_AT_CTS      0x20    // the ID lock IDL0..7 answers CTS and the 7 bits after
                                            // it, in a register access only; without it, S and
                                            // the 7 bits after it (host/CD.md, "IDL slots")

#define BISS_SLV_EW_ERROR           0x01    // nE sent active (0)
#define BISS_SLV_EW_WARNING         0x02    // nW sent active (0)

// ---- status (firmware writes) ----------------------------------------------
#define BISS_SLV_ST_MAGIC           0x120   // u32: BISS_SLV_MAGIC once the firmware runs
#define BISS_SLV_ST_PRU             0x124   // u32: the PRU this image was assembled for (0 or 1)
#define BISS_SLV_ST_CFG_ACK         0x128   // u32: CFG_SEQ of the configuration in force (or refused)
#define BISS_SLV_ST_CFG_ERROR       0x12C   // u32: BISS_SLV_CFGERR_*, 0 = accepted
#define BISS_SLV_ST_FRAMES          0x130   // u32: frames begun (an MA fall while idle), since the
                                            //      configuration
#define BISS_SLV_ST_LATCHES         0x134   // u32: frames with a first rising MA edge (the data latched)
#define BISS_SLV_ST_CD_FRAMES       0x138   // u32: frames whose timeout passed a CDM (two rising edges)
#define BISS_SLV_ST_CDM             0x13C   // u8:  the last CDM received (0xff: none yet)
#define BISS_SLV_ST_CDS             0x13D   // u8:  the CDS of the next frame
#define BISS_SLV_ST_CTRL_STATE      0x13E   // u8:  the control-frame state (BISS_SLV_CS_*)
#define BISS_SLV_ST_MA_BIT          0x13F   // u8:  the R31 bit the image takes MA from (MA_IN_BIT)
#define BISS_SLV_ST_CANCELS         0x140   // u16: control frames cancelled by 14 CDM = 0
#define BISS_SLV_ST_HDR_CRC_ERRORS  0x142   // u16: control-frame headers with a wrong CRC4
#define BISS_SLV_ST_PERIOD          0x144   // u32: the MA period of the last frame, PRU cycles (rising
                                            //      edges 1 and 2; 0: none measured)
#define BISS_SLV_ST_TIMEOUT         0x148   // u32: the timeout after the ACK in the next frame, PRU cycles
#define BISS_SLV_ST_WORK            0x14C   // u16: the longest work between two frames so far, PRU
                                            //      cycles (the timeout's end waits for WORK_PAD)
#define BISS_SLV_ST_WORK_PAD        0x14E   // u16: the work's allowance in the timeout, PRU cycles
#define BISS_SLV_ST_SLAVE0          0x150   // per slave (8 x 16 bytes): what control communication did
#define BISS_SLV_ST_SLAVE_SIZE      16
#define BISS_SLV_SS_COMMANDS        0       // u16: BiSS commands executed
#define BISS_SLV_SS_DROPPED         2       // u16: commands addressed to it but dropped (the execute
                                            //      bit had the other value: an IDA test failed)
#define BISS_SLV_SS_LAST_CMD        4       // u8:  the last command executed (0xff: none)
#define BISS_SLV_SS_LAST_ADDR       5       // u8:  the last register accessed (0xff: none)
#define BISS_SLV_SS_LAST_VALUE      6       // u8:  the byte read or written there
#define BISS_SLV_SS_RSVD            7       // u8
#define BISS_SLV_SS_READS           8       // u16: register bytes read
#define BISS_SLV_SS_WRITES          10      // u16: register bytes written
#define BISS_SLV_SS_REFUSED         12      // u16: writes refused (read-only, protected, missing bank)
#define BISS_SLV_SS_CRC_ERRORS      14      // u16: writes dropped for a wrong CRC4
#define BISS_SLV_ST_END             0x1D0

#define BISS_SLV_MAGIC              0x564c5342  // "BSLV"

// Control-frame states (ST_CTRL_STATE).
#define BISS_SLV_CS_IDLE            0       // waiting for 14 zeros (armed after them) and the start S
#define BISS_SLV_CS_HEADER          1       // CTS, ID/ADR or IDS/CMD, CRC4
#define BISS_SLV_CS_RWS             2       // R, W and the master's S
#define BISS_SLV_CS_WAIT            3       // late S: register processing
#define BISS_SLV_CS_DATA            4       // 8 data bits
#define BISS_SLV_CS_DCRC            5       // their CRC4
#define BISS_SLV_CS_STOP            6       // P
#define BISS_SLV_CS_SEQ             7       // S: the next register, or the end
#define BISS_SLV_CS_IDA             8       // a command's ID acknowledge
#define BISS_SLV_CS_EXEC            9       // its execute bit
#define BISS_SLV_CS_IGNORE          10      // not addressed (or a bad header): until the 14 zeros

// ---- the next frame (firmware writes between frames) -------------------------
#define BISS_SLV_REC_FRAME          0x1D0   // u32: the frame number (ST_FRAMES counting) of the words
#define BISS_SLV_REC_CDS            0x1D4   // u8:  the CDS that frame will send
#define BISS_SLV_REC_NSLAVES        0x1D5   // u8
#define BISS_SLV_REC_RSVD           0x1D6   // u16
#define BISS_SLV_REC_WORD0          0x1D8   // u64 per slave (8): its data word, left-aligned: the
                                            //      first bit on the wire at bit 63 (the word of
                                            //      n data bits is REC_WORD >> (64 - n))
#define BISS_SLV_REC_END            0x218

// ---- firmware-private area (the host must not write it) ---------------------
#define BISS_SLV_PRIV               0x218
#define BISS_SLV_PRIV_END           0x400

// ---- register files: per slave, addresses 0x40..0x7F and the access rights ---
// Addresses 0x00..0x3F are the bank chosen by the byte at 0x40: bank b of a
// slave is pool bank BANK0 + b when b < BANKS; a missing bank reads 0 and
// refuses writes (POSITAL IXARC manual §4: 0x00..0x3F banked, 0x40 the bank
// select, 0x40..0x7F direct).
#define BISS_SLV_REGS               0x400   // 8 x BISS_SLV_REGS_SIZE
#define BISS_SLV_REGS_SIZE          96
#define BISS_SLV_R_DIRECT           0       // 64 bytes: addresses 0x40..0x7F
#define BISS_SLV_R_RO               64      // 16 bytes: bit (a % 8) of byte a / 8: address a read-only
#define BISS_SLV_R_WP               80      // 16 bytes: likewise write-protected (SF_PROTECT)
#define BISS_SLV_POOL               0x700   // BISS_SLV_POOL_BANKS x 64 bytes
#define BISS_SLV_BANK_SIZE          64
#define BISS_SLV_TABLE              0xB00   // BISS_SLV_TABLE_ENTRIES x u64, positions right-aligned
#define BISS_SLV_TABLE_END          0xF00

// ---- firmware-private, a second part (the host must not write it) ----------
#define BISS_SLV_PRIV2              0xF00   // the control state before a step taken in a frame's
#define BISS_SLV_PRIV2_END          0xF20   // tail (pru_slave/README.md, "Work between frames")

// ---- configuration errors (ST_CFG_ERROR) -------------------------------------
#define BISS_SLV_CFGERR_NONE        0
#define BISS_SLV_CFGERR_NSLAVES     1       // 0 or more than 8 slaves
#define BISS_SLV_CFGERR_DATA_BITS   2       // position 0 or > 64 bits, or the whole data word > 64
#define BISS_SLV_CFGERR_CRC_BITS    3       // more than 16 CRC bits, or a start value wider than them
#define BISS_SLV_CFGERR_LC_BITS     4       // a life counter over 32 bits
#define BISS_SLV_CFGERR_ID          5       // an ID over 7, or two answering slaves with one ID
#define BISS_SLV_CFGERR_TABLE       6       // table entries past BISS_SLV_TABLE_ENTRIES
#define BISS_SLV_CFGERR_BANKS       7       // banks past BISS_SLV_POOL_BANKS
#define BISS_SLV_CFGERR_TIMEOUT     8       // timeout 0 or over BISS_SLV_MAX_TIMEOUT, unknown mode,
                                            // adaptive with factor 0 or TMO_MIN > TIMEOUT
#define BISS_SLV_CFGERR_BUSY        9       // processing time over 2^24 cycles (84 ms)

#endif
