// biss_master.p - BiSS-C interface master for either PRU of an AM335x/AM437x
// PRU-ICSS (pasm dialect).
//
// MA is R30 bit MA_BIT (default 1), SL is R31 bit 0 in 28-bit shift mode,
// sampled at 8x the MA rate. The host configures and reads results through
// the PRU's own data RAM, laid out in include/biss/biss_shm.h. Assembled
// once per PRU (-DPRU_NUM=0, the default, or -DPRU_NUM=1): the PRU's CONTROL
// block, GPCFG and scratch-pad bank are in the instruction words, so each
// image runs only on the PRU it was built for (it says which in BISS_ST_PRU).
//
// A frame (MA period p = 0, 1, ...; each period exactly 2H PRU cycles):
//   WAIT_ACK    clock until the newest 8 samples show SL low (the ACK edge);
//               the position of that edge (ones before it) gives this
//               frame's line delay in bit/8, averaged with the last 3 frames
//   LAG         clock while the sample point and lag are derived from it
//   START_WAIT  clock while the slave is busy; count it, abort over the limit
//   CDS         read the CDS bit, load the first slave's record
//   slaves      data bits and CRC bits of each slave, CRC computed per bit;
//               clocking stops by itself after the clock that follows the
//               last bit (on it the slave starts its timeout, SL low), and
//               the remaining bits are read from the samples: no extra
//               clocks for the line delay
// Then, outside the clocked part: CDM on MA, CRC verdicts, publication,
// and the wait for the slave's timeout to end (SL high).
//
// The clocked periods are in biss_periods.hp; their timing rules are
// described there. The code is in files by role, included below in the
// order of the image (pru_fw/README.md has the map): startup.p, config.p,
// frame.p, results.p, cd.p, ssi.p; the definitions in icss_regs.hp (the
// PRU-ICSS registers), layout.hp (the private data RAM) and regs.hp
// (the register map: what each register holds in each phase).

.origin 0
.entrypoint START

#include "../include/biss/biss_shm.h"

#ifndef MA_BIT
#define MA_BIT          1               // R30 bit driving MA: 0..7
#endif
#ifndef PRU_NUM
#define PRU_NUM         0               // the PRU of its PRU-ICSS this image is for: 0 or 1
#endif
// This PRU's scratch-pad bank: PRU0 bank 0 (XFR device 10), PRU1 bank 1 (11).
// Both PRUs on one bank in one cycle stall PRU1 (docs/pru-facts.md §3), and
// the bank is part of the XIN/XOUT word: one bank each, never the other's.
// (-DXFR_BANK=n only for test_e2e_twopru's image that breaks this rule.)
#ifndef XFR_BANK
#define XFR_BANK        (10 + PRU_NUM)
#endif
#define MA_MASK         (1 << MA_BIT)
#define LAG             2               // extra whole periods between a bit and its read
#define MAJORITY5       0xfee8e880      // bit k set: three or more of k's five bits are 1
#define IDLE_MASK       0x0f            // R31 samples that must all be high for SL idle: half
                                        // a period, longer than any glitch of under 3 samples
#define IDLE_TURNS      36000           // SL idle polls (4 cycles) of SLAVE_IDLE: 720 us
#define FE_TURNS        16384           // FE_POLL's: 328 us (4 FE_TURNS = 0x10000, a constant
                                        // of the upper half). SL low through a poll and
                                        // then through SLAVE_IDLE's (MAIN's FRAME) is no
                                        // slave: 1.05 ms after a frame (two SLAVE_IDLE's
                                        // after one that ends with MA low, or aborted),
                                        // more than the longest slave timeout, 1 ms

#include "icss_regs.hp"

// IEP count at which every IEP-triggered frame's period 0 falls (IEP_START):
// the period starts when the count is reset to 0, so this is the trigger to
// the first MA fall (an SSI frame's comes 12 cycles later: SSI_STAMPED to
// LAG_TOP). IEP_D0 is IEP_START's: from the count's read to the fall, 12
// cycles and the wait, on the path to the next period's count (the path to
// this period's is one shorter, and CMP0 is P - 1). IEP_C0 is FRAME_END's:
// its count read comes at most IEP_C0 cycles after the start of the MA
// period after the frame's last (IEP_PERIOD, P_IEP_FIX; measured: 48 to 70
// cycles by the shape of the last slave, the last switch period taken as a
// whole one where SWITCH_SHORT cut its tails; 6 more for FRAME_END's
// branches before it).
// The idle polls after a frame (FE_POLL, IEP_POLL, SLAVE_IDLE) take SL's
// newest IDLE_MASK samples all high for the end of the slave's timeout,
// which iC-MB4 has "terminated and signaled to the BiSS master by a rising
// edge" (datasheet, BiSS C frame); a last bit of 1 looks the same until
// the samples reach past its end, where the timeout's low begins. The last
// bit is read from the last switch period's R31 snapshot as soon as its
// sample point is in it, with as few as 0 newer samples; its end is 4
// samples (H / 2) after the sample point. The work after the frame up to
// the first poll's read takes at least POST_MIN cycles (biss_shm.h; the
// shortest measured, 173, an SSI frame's through FE_SLOW; every frame's
// count checked by `test/bench/post_frame.py`); where 5 samples
// (H + H / 4 cycles, one past the end) take longer than that, the last
// period keeps its tails instead of cutting them (SWITCH_SHORT; CFG: the
// end record at 0xff), and the frame ends 2H after that read: publication
// about 2H - 20 cycles later, only at the slow rates (H > CUT_MAX_HALF =
// 136: 625 kHz and below). Found at 200 kHz on 200 m
// (`test/bench/long_lines.py`): a free-running master started its next
// frame inside the slave's timeout.
#define POST_MIN        BISS_POST_MIN_CYCLES
#define CUT_MAX_HALF    BISS_CUT_MAX_HALF

#define IEP_ALIGN       36
#define IEP_D0          (IEP_ALIGN - 12)
#define IEP_C0          76

#include "layout.hp"
#include "regs.hp"

// (after the equates: macro bodies take equates as they are read)
#include "biss_periods.hp"
#define REC_BASE        52                  // register-file byte address of r13

#include "startup.p"
#include "config.p"
#include "frame.p"
#include "results.p"
#include "cd.p"
#include "ssi.p"
