// biss_shm.h - the shared-memory interface between the BiSS-C master
// firmware (on PRU0 or PRU1) and the host: byte offsets into that PRU's
// data RAM, flags, error codes and limits.
//
// This one file is read by both sides: by the PRU assembler (pasm dialect,
// so it holds nothing but #define lines and // comments) and by C (the
// struct view in biss_shm_struct.h checks every offset at compile time).
// All values are little-endian; offsets are from the start of the PRU's
// own data RAM (local address 0, constant table entry C24; the host sees
// PRU1's 0x2000 above PRU0's).
// (Laid out by hand, in columns: clang-format leaves it alone.)
// clang-format off
//
// Protocol:
//  - The host writes the configuration block, then increments CFG_SEQ.
//    The firmware applies a new CFG_SEQ at the next frame boundary, checks
//    it, and echoes the sequence number in ST_CFG_ACK (with ST_CFG_ERROR
//    set to the reason when it refuses the configuration; it then runs no
//    frames until a valid one arrives).
//  - Results go to a ring of result slots (BISS_RING0..BISS_RING_END): the
//    firmware fills the slot ST_RING_NEXT names, stores its publication
//    number in it (R_FRAME), then publishes it: ST_BUF names the slot (its
//    byte offset), then ST_SEQ is incremented; then ST_RING_NEXT moves on
//    one stride, back to BISS_RING0 where a whole slot no longer fits. The
//    newest sample: a reader reads ST_SEQ, ST_BUF, that slot, then ST_SEQ
//    again; equal sequence numbers mean a consistent frame (the firmware
//    starts filling a slot only after publishing the one before it).
//    Every frame: the slot of publication s is (s - ST_SEQ) strides from
//    ST_BUF's, modulo the ring; it holds s until the firmware starts
//    filling it again, after publishing s + slots - 1. A reader copies the
//    slots, then reads ST_SEQ again: the copies of publications from
//    ST_SEQ - slots + 2 on are whole; older ones are lost (overwritten).
//    The ring lives in the PRU's own data RAM, not in the PRU-ICSS shared
//    RAM: AM437x's PRU-ICSS0 has none (and 4 KB of data RAM per PRU), and
//    each PRU's master keeps its own ring beside its own results.
//    A configuration accepted starts the ring afresh at BISS_RING0 with
//    the stride of its slave count.

#ifndef BISS_SHM_H
#define BISS_SHM_H

#define BISS_SHM_VERSION        4       // 4: CFG_PROC_LIMIT ends a busy count (3: ST_OFF_GRID;
                                        // 2: the result ring; 1: two buffers)
#define BISS_DRAM_BYTES         4096    // fits AM437x ICSS0's 4 KB data RAM

// ---- limits ------------------------------------------------------------
#define BISS_MAX_SLAVES         8
#define BISS_MAX_DATA_BITS      64      // single-cycle data per slave, before the CRC
#define BISS_MAX_CRC_BITS       16
#define BISS_MIN_HALF           10      // MA half period, PRU cycles: 10 = 10 MHz
#define BISS_MAX_HALF           1024    // 16 x 16 divider: 97.7 kHz
#define BISS_MAX_DELAY_NS       40000   // longest line delay (round trip) the firmware waits for

// ---- configuration (host writes) ---------------------------------------
#define BISS_CFG_SEQ            0x000   // u32: host increments after writing the block
#define BISS_CFG_HALF           0x004   // u16: MA half period H in PRU cycles; f = 100 MHz / H
#define BISS_CFG_NSLAVES        0x006   // u8:  slaves in the chain, 1..8
#define BISS_CFG_TRIGGER        0x007   // u8:  BISS_TRIG_*
#define BISS_CFG_IEP_PERIOD     0x008   // u32: frame period in IEP counts (5 ns) for BISS_TRIG_IEP
#define BISS_CFG_PROC_LIMIT     0x00C   // u16: busy clocks at which a frame is given up, the longest
                                        // accepted + 1 (so every value ends a busy that never ends)
#define BISS_CFG_SSI_DELAY_NS   0x00E   // u16: SSI only: the line's round trip in ns (an SSI
                                        //      slave gives no ACK to measure it by)
#define BISS_CFG_SLAVE0         0x010   // first of BISS_MAX_SLAVES slave blocks
#define BISS_CFG_SLAVE_SIZE     8
// per slave block, offsets within the block:
#define BISS_CFG_S_DATA_BITS    0       // u8:  1..64 bits before the CRC (position, fill, nE, nW, life counter ...)
#define BISS_CFG_S_CRC_BITS     1       // u8:  0..16 (0: no CRC)
#define BISS_CFG_S_EW_SHIFT     2       // u8:  bit of nW counted from the data word's LSB (nE is the next one up)
#define BISS_CFG_S_FLAGS        3       // u8:  BISS_SF_*
#define BISS_CFG_S_CRC_POLY     4       // u16: CRC polynomial without its top term (0x43 -> 0x03)
#define BISS_CFG_S_CRC_START    6       // u16: CRC start value
#define BISS_CFG_END            0x050

#define BISS_SF_EW              0x01    // the slave sends nE and nW (at EW_SHIFT)
#define BISS_SF_SSI             0x02    // slave 0 only: an SSI encoder (no ACK, start, CDS, CRC;
                                        // its data word on the rising edges from the first one)

#define BISS_TRIG_HOST          0       // one frame per write of CMD_TRIGGER
#define BISS_TRIG_IEP           1       // one frame every CFG_IEP_PERIOD IEP counts (IEP CMP0)
#define BISS_TRIG_FREERUN       2       // next frame as soon as the slave is ready
#define BISS_TRIG_IEP_FOLLOW    3       // one frame per IEP period that the other PRU of this
                                        // PRU-ICSS set up with BISS_TRIG_IEP, starting on the same
                                        // IEP count as its frames; this channel leaves the IEP alone

// ---- commands (host writes, firmware clears) ---------------------------
#define BISS_CMD_TRIGGER        0x050   // u32: nonzero: start one frame (BISS_TRIG_HOST); the
                                        // firmware clears it as it starts the frame

// ---- status (firmware writes) -------------------------------------------
#define BISS_ST_PRU             0x07C   // u32: the PRU this image was assembled for (PRU_NUM: 0 or
                                        // 1), written with ST_MAGIC; the host refuses a mismatch
#define BISS_ST_MAGIC           0x080   // u32: BISS_MAGIC once the firmware runs
#define BISS_ST_SEQ             0x084   // u32: publication counter (see protocol above)
#define BISS_ST_BUF             0x088   // u32: the slot of the last publication (its offset)
#define BISS_ST_CFG_ACK         0x08C   // u32: CFG_SEQ of the configuration in force (or refused)
#define BISS_ST_CFG_ERROR       0x090   // u32: BISS_CFGERR_* of the last configuration, 0 = accepted
#define BISS_ST_STATE           0x094   // u32: BISS_STATE_*
#define BISS_ST_FRAMES          0x098   // u32: frames completed (counted on every publication)
#define BISS_ST_CRC_ERRORS      0x09C   // u32: frames with a CRC error in any slave
#define BISS_ST_NO_SLAVE        0x0A0   // u32: frames without ACK (or SL low when idle)
#define BISS_ST_PROC_ERRORS     0x0A4   // u32: frames aborted for processing time over the limit
#define BISS_ST_TRAINING        0x0A8   // u32: training frames (line delay measured, data not used)
#define BISS_ST_END             0x0AC

// ---- control communication: a CDM program, one step per frame ------------
// The host writes the program (BISS_CD_PROG, 4 bits a step: step i in the
// low nibble of byte i/2 when i is even, the high nibble when odd; bits 1..0
// the op, bits 3..2 the class), its length, the wait limit and the IDA
// check, then increments CD_CMD. The firmware starts it once at least 14
// frames in a row went out with CDM = 0 since the last program ended (and
// keeps sending 0 until then), executes one step per frame, and stores in
// BISS_CD_RESP bit i (byte i/8, bit i%8) the CDS of the frame after the one
// that sent step i. Two CRC4 registers (polynomial 0x13, start 0, MSB
// first) run beside it: CRC_M over the CDM of DATA and ECHO steps (an op
// CRC step sends its next bit, inverted), CRC_S over their answers (a CHECK
// step's answer must be its next bit, inverted); both start afresh at the
// program's start and after each WAIT. When the program ends it sets
// ST_CD_STATUS and echoes CD_CMD in ST_CD_SEQ. Frames keep coming as usual
// throughout: control data never stops position data.
#define BISS_CD_CMD             0x0B0   // u32 (host): incremented to run the program (past 0: none)
#define BISS_CD_STEPS           0x0B4   // u16 (host): program length, 1..BISS_CD_MAX_STEPS
#define BISS_CD_WAIT_LIMIT      0x0B6   // u16 (host): frames with CDS 0 a WAIT may see (0: at once)
#define BISS_ST_CD_SEQ          0x0B8   // u32: CD_CMD of the program last ended (or refused)
#define BISS_ST_CD_STATUS       0x0BC   // u8: BISS_CDST_*; u8 at +1: bytes transferred correctly;
                                        // u16 at +2: steps executed (answers recorded below it)
#define BISS_CD_IDA_STEP        0x0C0   // u16 (host): IDA test: the step of a command's P (0: none);
                                        // its CDM is inverted (the command withheld) unless the
                                        // answers of the 8 steps 9..2 before it equal IDA_EXPECT
#define BISS_CD_IDA_EXPECT      0x0C2   // u8 (host): those answers, bit k = step P - 9 + k
#define BISS_ST_CD_END          0x0C4

// ---- the result ring's pointer and geometry (firmware writes on each
// accepted configuration; ST_RING_NEXT on each publication) --------------
#define BISS_ST_RING_NEXT       0x0C4   // u32: the slot the next frame fills (the firmware's own)
#define BISS_ST_RING_STRIDE     0x0C8   // u16: the slots' stride in force, BISS_R_SLAVE0 +
                                        //      slaves x BISS_R_SLAVE_SIZE
#define BISS_ST_RING_LAST       0x0CA   // u16: the last slot's highest start, BISS_RING_END - stride
#define BISS_ST_RING_END        0x0CC

// ---- link quality (firmware writes on each frame refused for it) ---------
#define BISS_ST_OFF_GRID        0x0CC   // u32: frames with an SL edge off the bit grid (BISS_RF_OFF_GRID)
#define BISS_ST_LINK_END        0x0D0

// (control communication, continued: the program and its answers)
#define BISS_CD_PROG            0x200   // 512 bytes
#define BISS_CD_RESP            0x400   // 128 bytes
#define BISS_CD_MAX_STEPS       1024

#define BISS_CDOP_0             0       // send CDM 0
#define BISS_CDOP_1             1       // send CDM 1
#define BISS_CDOP_WAIT          2       // CDM 1 until a frame's CDS is 1, then the next step in that
                                        // frame (never followed by another WAIT or a CRC step)
#define BISS_CDOP_CRC           3       // send the next bit of CRC_M, inverted
#define BISS_CDCL_NONE          0       // (class, bits 3..2 of a step) answer only recorded
#define BISS_CDCL_DATA          1       // CDM into CRC_M (ops 0/1), the answer into CRC_S
#define BISS_CDCL_CHECK         2       // the answer must be the next bit of CRC_S, inverted
#define BISS_CDCL_ECHO          3       // as DATA, and the answer must equal the CDM sent

// A program ends at its length, or early: a WAIT over its limit stops it at
// once; a CHECK, ECHO or IDA error lets the current register byte finish (so
// a slave never takes a half-sent write) and ends the control frame at the
// next step that is a master S (op 1, class NONE), sending 0 there instead.
// The bytes count is the WAITs passed whose byte then reached its next
// class-NONE step with no error pending.
#define BISS_CDST_IDLE          0       // no program since start
#define BISS_CDST_BUSY          1       // waiting for the 14 zeros, or running
#define BISS_CDST_DONE          2       // ended normally
#define BISS_CDST_ERR_WAIT      3       // a WAIT step saw no CDS = 1 within CD_WAIT_LIMIT frames
#define BISS_CDST_ERR_STEPS     4       // CD_STEPS out of range
#define BISS_CDST_ERR_FRAME     5       // a frame failed (no ACK, processing time) while running
#define BISS_CDST_ERR_CRC       6       // a CHECK answer was wrong (register data CRC4)
#define BISS_CDST_ERR_ECHO      7       // an ECHO answer differed from the CDM sent
#define BISS_CDST_ERR_IDA       8       // the IDA test failed: P went out inverted

#define BISS_MAGIC              0x42695353  // "SSiB"

#define BISS_STATE_STOPPED      0
#define BISS_STATE_RUNNING      1
#define BISS_STATE_CFG_ERROR    2
#define BISS_STATE_NO_SLAVE     3

// ---- result ring (firmware writes, host reads after ST_SEQ) ----------------
// Slots of BISS_R_SLAVE0 + slaves x BISS_R_SLAVE_SIZE bytes (a header and
// the configured slaves' results), from BISS_RING0 on, as many as fit below
// BISS_RING_END: 60 for one slave (48 bytes), 18 for eight (160 bytes).
// (biss_shm_struct.h has the stride and slot count as C macros: the
// assembler has no macros with arguments.)
#define BISS_RING0              0x480   // the first slot
#define BISS_RING_END           0xFE0   // the ring's end (BISS_ID follows)
// per slot, offsets within it:
#define BISS_R_FRAME            0x00    // u32: frame number: its publication number (ST_SEQ,
                                        //      ST_FRAMES at publication)
#define BISS_R_FLAGS            0x04    // u32: BISS_RF_*
#define BISS_R_TIMESTAMP        0x08    // u32: IEP COUNT when the frame's first MA edge was due
#define BISS_R_PROC_CLOCKS      0x0C    // u16: processing time (busy) of the slave, MA clocks
#define BISS_R_CDS              0x0E    // u8:  CDS bit received
#define BISS_R_NSLAVES          0x0F    // u8
#define BISS_R_DELAY_RAW        0x10    // u16: ACK position of this frame, bit/8 units (see below)
#define BISS_R_DELAY_AVG        0x12    // u16: its moving average over the last 4 frames
#define BISS_R_SAMPLE_POINT     0x14    // u8:  sample (0..7 within a bit) used for this frame
#define BISS_R_LAG_PERIODS      0x15    // u8:  whole MA periods between a clock and its bit
#define BISS_R_HALF             0x16    // u16: MA half period H of this frame
#define BISS_R_CDM              0x18    // u8:  CDM sent in this frame's timeout
#define BISS_R_SLAVE0           0x20    // first of the slaves' results (the header's size)
#define BISS_R_SLAVE_SIZE       16
// per slave result, offsets within it:
#define BISS_R_S_DATA_LO        0       // u32: data bits 31..0 (right-aligned, masked)
#define BISS_R_S_DATA_HI        4       // u32: data bits 63..32
#define BISS_R_S_CRC_REG        8       // u32: CRC register after the CRC bits, left-aligned;
                                        //      equals the polynomial's residue exactly when the CRC is right
#define BISS_R_S_STATUS         12      // u32: BISS_RS_*
// Line delay: DELAY_RAW and DELAY_AVG count bit/8 units (one unit = H/4
// PRU cycles = one 8x sample) of the slave's ACK edge, from a fixed point
// of the frame. The round trip from an MA rising edge at the master pin to
// the slave's answer at the master pin is
//     (DELAY - BISS_DELAY_ZERO) * H / 4 - BISS_DELAY_ADJ_CYCLES  PRU cycles,
// to within one bit/8 and one PRU cycle (the phase of the 8x sample clock
// is not known to the firmware, and R31 is read on whole cycles while the
// samples may fall between them). BISS_DELAY_ADJ_CYCLES is the firmware's read one cycle
// after the period starts less the PRU's input synchronizer (2 cycles,
// docs/pru-facts.md §3, an estimate).
#define BISS_DELAY_ZERO         20
#define BISS_DELAY_ADJ_CYCLES   1

#define BISS_RF_VALID           0x01    // data of every slave received (CRC status per slave)
#define BISS_RF_CRC_ERROR       0x02    // at least one slave's CRC failed
#define BISS_RF_NO_SLAVE        0x04    // no ACK within the limit, or SL low before the frame
#define BISS_RF_PROC_ERROR      0x08    // processing time over CFG_PROC_LIMIT: frame aborted
#define BISS_RF_TRAINING        0x10    // first frame at a new rate: delay measured, data not checked
#define BISS_RF_SMA             0x20    // the moving average is filled (4 frames at this rate)
#define BISS_RF_ACK_JUMP        0x40    // the ACK lay over half a bit from the average: bits read
                                        // at the wrong place, so never VALID (see pru_fw/README)
#define BISS_RF_IEP_LATE        0x80    // IEP trigger: this frame did not start on its period's
                                        // count (SL was not idle in time), or it ran into the
                                        // next period (which then has no frame): the period is
                                        // too short for the frame. With VALID and any flag it
                                        // may have; every period without a frame lies next to
                                        // a frame flagged so
#define BISS_RF_OFF_GRID        0x100   // SL's samples around a bit's sample point disagreed (an
                                        // edge off the bit grid: a glitch, a clock gained or
                                        // lost), so never VALID; checked from H = 16 (below
                                        // 10 MHz), never at H = 10 (pru_fw/README, "Bit grid")
// The bit-grid check's window (BISS_RF_OFF_GRID): the samples before and
// after each bit's sample point that must agree with it, from H = 16 on.
// One after, two before: the next bit's edge lies about 3.5 samples after
// the sample point and this bit's 4.5 before it, so each side keeps two
// samples to spare (pru_fw/README, "Bit grid": the evidence).
#define BISS_GRID_OLDER         2
#define BISS_GRID_NEWER         1
#define BISS_GRID_MIN_HALF      16
// The frame's last period and the idle polls after it (pru_fw/biss_master.p,
// POST_MIN): the fewest cycles from the last R31 read of a frame to the
// first poll for the slave's timeout end (measured 173, an SSI frame), and
// the largest H at which the last period may cut its tails: 5 samples (one
// past the last bit's end, H + H / 4 cycles) within those cycles. Above it
// the frame ends 2H after that read (publication about 2H - 20 later).
#define BISS_POST_MIN_CYCLES    170
#define BISS_CUT_MAX_HALF       (BISS_POST_MIN_CYCLES * 4 / 5)
#define BISS_RF_SL_INIT         0x200   // SL stayed low: iC-MB4's INIT sent (two clocks, no
                                        // measurement), with NO_SLAVE; a training follows

#define BISS_RS_CRC_OK          0x01
#define BISS_RS_NE              0x02    // nE as received (1: no error); 0 if the slave has none
#define BISS_RS_NW              0x04    // nW as received (1: no warning)

// ---- configuration errors (ST_CFG_ERROR) ---------------------------------
#define BISS_CFGERR_NONE        0
#define BISS_CFGERR_NSLAVES     1       // 0 or more than 8 slaves
#define BISS_CFGERR_HALF        2       // H out of range or no exact 8x shift clock for it
#define BISS_CFGERR_DATA_BITS   3       // a slave with 0 or more than 64 data bits
#define BISS_CFGERR_CRC_BITS    4       // a slave with more than 16 CRC bits
#define BISS_CFGERR_TRIGGER     5       // unknown trigger mode
#define BISS_CFGERR_EW          6       // nE/nW position outside the data word
#define BISS_CFGERR_IEP_PERIOD  7       // IEP period shorter than a frame can be
#define BISS_CFGERR_SSI         8       // SSI: one slave, no CRC

// ---- firmware-private area (the host must not write it) -------------------
#define BISS_PRIV               0x100   // (C28's page: a multiple of 256)
#define BISS_PRIV_END           0x200   // (the CD program and answers follow)

// ---- image identification and remoteproc resource table -------------------
// The top 32 bytes of the 4 KB data RAM, which the firmware never touches:
// loaded with the image (by the host's /dev/mem loader, or by the kernel's
// pru_rproc from the ELF's data segment), read by a host that attaches.
#define BISS_ID                 0xFE0   // u32 BISS_ID_MAGIC, u32 BISS_SHM_VERSION the image was
                                        // built with, u32 CRC-32 (IEEE, as zlib) of the IRAM
                                        // image, u32 image bytes
#define BISS_ID_MAGIC           0x44495342  // "BSID"
#define BISS_RSC_TABLE          0xFF0   // 16 bytes: remoteproc resource table, version 1, empty
#define BISS_ID_END             0x1000

#endif
