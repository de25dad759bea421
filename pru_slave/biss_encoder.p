// biss_encoder.p - a BiSS-C slave (an encoder, or a chain of up to 8) for
// either PRU of an AM335x/AM437x PRU-ICSS (pasm dialect): the other end of
// the line from pru_fw/, written from the protocol documents, not from the
// master (pru_slave/README.md cites them).
//
// MA comes in on R31 bit MA_IN_BIT (default 1) in direct GPI mode, SL goes
// out on R30 bit 0. The host configures the chain and reads its status
// through the PRU's own data RAM, laid out in include/biss/biss_slave_shm.h.
// Assembled once per PRU (-DPRU_NUM=0, or 1): the CONTROL block (the
// cycle counter), GPCFG and the scratch-pad banks are in the instruction
// words.
//
// A frame, from the slave's side (frame.p):
//   idle        SL high; MA falls: the frame begins
//   1st rise    the data are latched (they were built for this frame)
//   2nd rise    SL low: the ACK
//   busy        SL low on further rises until the processing time is over
//   then        start bit, CDS, each slave's data word and CRC, then 0
//   timeout     MA still for the timeout: CDM = NOT MA; the control frame
//               moves on, the next frame's data are built (between.p), and
//               SL goes high
// Every rising edge that puts a bit on SL does it with its first
// instruction, `lsr r30, word, 31`: the response is the input synchronizer,
// the poll's step (2 cycles) and that one instruction.
//
// Files, in image order: startup.p (start, the idle wait), frame.p (the
// clocked frame), between.p (after the timeout), ctrl.p (control
// communication), config.p (the host's configuration); the definitions in
// regs.hp (the register map) and layout.hp (the private data RAM).

.origin 0
.entrypoint START

#include "../include/biss/biss_slave_shm.h"

#ifndef PRU_NUM
#define PRU_NUM         0               // the PRU of its PRU-ICSS this image is for: 0 or 1
#endif
#ifndef MA_IN_BIT
#define MA_IN_BIT       1               // R31 bit MA comes in on (never 0 on a board whose
                                        // R30 bit 0, SL, shares its pad with R31 bit 0)
#endif

// PRU-ICSS registers
#define CTRL_ADDR       (0x22000 + 0x2000 * PRU_NUM)    // this PRU's CONTROL block
#define CTRL_CONTROL    0x00            //   CONTROL: bit 3 COUNTER_ENABLE
#define CTRL_CYCLE      0x0c            //   CYCLE: counts PRU cycles while enabled
#define CTRL_CTR_EN     3
#define GPCFG_OWN       (0x08 + 4 * PRU_NUM)            // CFG (C4): GPCFG0 or GPCFG1
#define CFG_SPP         0x34            // CFG (C4): scratch-pad priority and shift
#define SPP_XFR_SHIFT   2               // XFR_SHIFT_EN (bit 1), PRU1_PAD_HP_EN (bit 0) 0: the
                                        // value the master writes too (pru_fw/startup.p)
// The scratch-pad banks of the records: the two the master on the other
// PRU never uses (it keeps bank 10 + its PRU number: pru_fw/README.md),
// so neither PRU ever waits for the other on a bank.
#define BANK_CRC        (10 + PRU_NUM)  // per slave: polynomial, CRC start and counts
#define BANK_DATA       12              // per slave: the data word, left-aligned
// The records sit in bank registers 14 + 2k, 15 + 2k (XFR shift 2k, up)
// or 14 - 2k, 15 - 2k (down: TI gives the shift's size, not its sign,
// docs/silicon-assumptions.md A6); XIN and XOUT of one shift meet the same
// bank registers either way, and for k <= 7 both stay within 0..29.
#define REC_REG_BASE    14

// The timeout (pru_slave/README.md, "Timeout"): SL goes high WORK_PAD
// cycles after the polls saw the timeout end, whatever the work there took
// (test_slave_fw holds it below); the polls' own cycles around it are
// TMO_FIXED. The turns of 4 cycles make up the rest of the timeout.
#define WORK_PAD        56
#define TMO_FIXED       19
#define PW_OUTSIDE      21              // PREWORK's cycles outside its CYCLE reads (between.p)
#define PAD_SELF        11              // END_PAD's from its CYCLE read to the burn's end

#define IDLE_CHECK      0               // idle poll turns between looks at the host's block:
                                        // 65536 turns of 4 cycles, 1.3 ms (0 wraps to 65535)

#include "regs.hp"
#include "layout.hp"
#include "waits.hp"

#include "startup.p"
#include "frame.p"
#include "between.p"
#include "ctrl.p"
#include "config.p"
