/*
 * core_priv.h - internal state of the PRU core emulator, shared by its
 * source files. Not part of the public API (pru_core.h).
 */
#ifndef PRU_CORE_PRIV_H
#define PRU_CORE_PRIV_H

#include "icss_block.h"
#include "pru_core.h"
#include "pru_isa.h"

#include <stdbool.h>
#include <string.h>

#define NO_LOOP     0xffffffffu
#define CYCLE_NEVER INT64_MAX
#define IEP_BYTES   0x1000u
#define INTC_BYTES  0x2000u
#define CFG_BYTES   0x2000u
#define CTRL_BYTES  0x1000u
#define SPAD_BYTES  120u /* scratch-pad bank: R0..R29 */
#define LOCAL_LIMIT 0x80000u

/*
 * What the execute loop runs for a predecoded word (struct pd .kind and
 * .fast): the instruction's enum pru_op, a row of the instruction list in
 * pru_isa.h (every NOPn as PRU_OP_NOP0), or one of these.
 */
enum {
    PD_BAD = PRU_OP_COUNT, /* no V3 instruction: a fault when executed */
    PD_SLOW,               /* fast loop: hand over to exec_one() */
    PD_R31_READ,           /* fast loop: refresh R31, then run `inner` */
    PD_R30_WRITE,          /* fast loop: run `kind` (ALU or LDI), then tell the pins */
    PD_R30_XOR,            /* ... for XOR (the firmware's MA edges) */
    PD_R30_XORB,           /* ... xor r30.bN, r30.bN, rM.bK (op2 a byte) */
    /* fast loop: the same ops when the destination and rs1 are whole
     * registers (rN, no field), without the field shifts and masks */
    PD_ADD32,
    PD_SUB32,
    PD_QBNE32,
    PD_QBEQ32,
    PD_QBBS32,
    PD_QBBC32,
    /* ... and with an immediate op2 */
    PD_ADD32I,
    PD_SUB32I,
    PD_QBNE32I,
    PD_QBEQ32I,
    PD_QBBS32I,
    PD_QBBC32I,
    /* more whole-register forms: rd, rs1 and op2 whole (I: op2 immediate) */
    PD_ADC32,
    PD_AND32,
    PD_OR32,
    PD_XOR32,
    PD_LSL32,
    PD_LSR32,
    PD_LSL32I,
    PD_LSR32I,
    PD_LDI32, /* LDI into a whole register */
    /* fields (any) with an immediate op2 */
    PD_SUBI,
    PD_MINI,
    PD_QBEQI,
    PD_QBNEI,
    PD_JALI, /* JAL to an immediate target (a call) */
    /* byte and word fields read and written as bytes and half-words of the
     * little-endian register file (B: byte, W: word, 32: whole register, I:
     * immediate; destination, rs1, op2), so that a store of a field and a
     * load of it are the same size and the host forwards the one to the
     * other */
    PD_MINB32I,
    PD_SUB32B,
    PD_SUBBBI,
    PD_QBEQBI,
    PD_QBNEBI,
    PD_QBEQWI,
    PD_QBNEWI,
    /* MVIB/W/D loading through a register pointer (IND, POSTINC, PREDEC; the
     * pointer a field of r0..r29) into a field of r0..r29: the record
     * loads of the firmware's slave switches. rs1 is the pointer field, rd
     * the destination; imm the value mask of the size, rdw the size in
     * bytes, rs2 / rs2sh what the pointer moves by before / after the
     * read. A read that wraps past byte 127 goes the general way. */
    PD_MVI_LD,
    /* XIN/XOUT (SXIN/SXOUT) of a scratch-pad bank, ZERO and FILL, of a
     * fixed length within r0..r29: imm the bytes, target the register-file
     * start (exec_xfr_fixed(); what it cannot do goes the general way) */
    PD_XFR_FIXED,
    /* a PRU of a PRU-ICSS: an instruction that is a cross-PRU event
     * (TIMING.md "Two PRUs"): the kinds PD_SLOW, PD_R31_READ, PD_MVI_LD and
     * PD_XFR_FIXED, in .xfast; the fast loop sees first whether it must
     * wait for the other PRU (run-ahead, pruss.c) */
    PD_XPRU,
    PD_END, /* fast loop: one past the end of IRAM (leave the loop) */
    PD_KIND_END,
};
_Static_assert(PD_KIND_END <= UINT8_MAX, "struct pd keeps kinds in a uint8_t");

/*
 * The fast kinds of the single-cycle instructions that only touch registers
 * and carry and go on to pc + 1 (no branch, jump, R30 or R31): what a
 * straight run is made of (with R31 reads of them, PD_R31_READ). X(label,
 * kind), the label naming the fast loop's handlers (exec.c).
 */
#define PD_STRAIGHT_KINDS(X)                                                                       \
    X(add, PRU_OP_ADD)                                                                             \
    X(adc, PRU_OP_ADC)                                                                             \
    X(sub, PRU_OP_SUB)                                                                             \
    X(suc, PRU_OP_SUC)                                                                             \
    X(lsl, PRU_OP_LSL)                                                                             \
    X(lsr, PRU_OP_LSR)                                                                             \
    X(rsb, PRU_OP_RSB)                                                                             \
    X(rsc, PRU_OP_RSC)                                                                             \
    X(and, PRU_OP_AND)                                                                             \
    X(or, PRU_OP_OR)                                                                               \
    X(xor, PRU_OP_XOR)                                                                             \
    X(not, PRU_OP_NOT)                                                                             \
    X(min, PRU_OP_MIN)                                                                             \
    X(max, PRU_OP_MAX)                                                                             \
    X(clr, PRU_OP_CLR)                                                                             \
    X(set, PRU_OP_SET)                                                                             \
    X(nop, PRU_OP_NOP0)                                                                            \
    X(ldi, PRU_OP_LDI)                                                                             \
    X(lmbd, PRU_OP_LMBD)                                                                           \
    X(add32, PD_ADD32)                                                                             \
    X(sub32, PD_SUB32)                                                                             \
    X(add32i, PD_ADD32I)                                                                           \
    X(sub32i, PD_SUB32I)                                                                           \
    X(adc32, PD_ADC32)                                                                             \
    X(and32, PD_AND32)                                                                             \
    X(or32, PD_OR32)                                                                               \
    X(xor32, PD_XOR32)                                                                             \
    X(lsl32, PD_LSL32)                                                                             \
    X(lsr32, PD_LSR32)                                                                             \
    X(lsl32i, PD_LSL32I)                                                                           \
    X(lsr32i, PD_LSR32I)                                                                           \
    X(ldi32, PD_LDI32)                                                                             \
    X(subi, PD_SUBI)                                                                               \
    X(mini, PD_MINI)                                                                               \
    X(minb32i, PD_MINB32I)                                                                         \
    X(sub32b, PD_SUB32B)                                                                           \
    X(subbbi, PD_SUBBBI)

/* The fast kinds of the quick branches (QBxx, QBA), as above */
#define PD_QUICK_KINDS(X)                                                                          \
    X(qbgt, PRU_OP_QBGT)                                                                           \
    X(qbge, PRU_OP_QBGE)                                                                           \
    X(qblt, PRU_OP_QBLT)                                                                           \
    X(qble, PRU_OP_QBLE)                                                                           \
    X(qbeq, PRU_OP_QBEQ)                                                                           \
    X(qbne, PRU_OP_QBNE)                                                                           \
    X(qba, PRU_OP_QBA)                                                                             \
    X(qbbs, PRU_OP_QBBS)                                                                           \
    X(qbbc, PRU_OP_QBBC)                                                                           \
    X(qbne32, PD_QBNE32)                                                                           \
    X(qbeq32, PD_QBEQ32)                                                                           \
    X(qbbs32, PD_QBBS32)                                                                           \
    X(qbbc32, PD_QBBC32)                                                                           \
    X(qbne32i, PD_QBNE32I)                                                                         \
    X(qbeq32i, PD_QBEQ32I)                                                                         \
    X(qbeqi, PD_QBEQI)                                                                             \
    X(qbnei, PD_QBNEI)                                                                             \
    X(qbbs32i, PD_QBBS32I)                                                                         \
    X(qbbc32i, PD_QBBC32I)                                                                         \
    X(qbeqbi, PD_QBEQBI)                                                                           \
    X(qbnebi, PD_QBNEBI)                                                                           \
    X(qbeqwi, PD_QBEQWI)                                                                           \
    X(qbnewi, PD_QBNEWI)

/*
 * What the fast loop dispatches on (struct pd .go): .fast, or
 * - PD_RUN + the place of its kind in PD_STRAIGHT_KINDS (PD_RUN_R31 for an
 *   R31 read) for the first of a straight run of two or more (.run): the
 *   run goes without the checks between its instructions (the cycle limit,
 *   a LOOP end) if neither falls within it or at its end
 *   (pru_params.straight_run);
 * - PD_FORWARD + the place of its kind in PD_QUICK_KINDS for a quick branch
 *   forward: taken or not, it comes to no loop the fast-forward looks at;
 * - PD_PAIR_* for a pair of instructions of the firmware's clocked bit
 *   loops (pru_fw/) that runs as one in a straight run, the second reading
 *   the first's result (outside a run: the first's own handler):
 *   PD_PAIR_MIN_SUB  min rB.bK, rA, imm; sub rA, rA, rB.bK (B not A), the
 *                    first of a run;
 *   PD_PAIR_LSL_XOR  lsl rA, rB, imm; xor rC, rA, op2, the first of a run;
 *   PD_PAIR_XOR_QBBS xor rA, rB, op2; qbbs forward, rA, imm: a run's last
 *                    and the branch after it;
 *   PD_PAIR_ADD_ADC2 add rA, rB, op2; adc rC, rD, rE; adc rF, rG, rH: the
 *                    carry chain of three (the firmware's SHIFT_IN), in a
 *                    run (each reads what the one before it wrote);
 *   PD_PAIR_CALL_RET jal rX, imm (a call of a routine FF_MAX_BODY words or
 *                    more back): with a JMP there that returns (the
 *                    firmware's shortest delay, DLY_S1), the call and the
 *                    return as one, checked as it runs (the JMP is another
 *                    word: otherwise the call's own handler)
 *   (registers whole where no field is named).
 */
enum {
#define PD_PLACE(label, kind) PD_PLACE_##label,
    PD_STRAIGHT_KINDS(PD_PLACE) PD_STRAIGHT_COUNT,
};
enum {
    PD_QUICK_KINDS(PD_PLACE) PD_QUICK_COUNT,
#undef PD_PLACE
};
enum {
    PD_RUN = PD_KIND_END,
    PD_RUN_R31 = PD_RUN + PD_STRAIGHT_COUNT,
    PD_FORWARD,
    PD_PAIR_MIN_SUB = PD_FORWARD + PD_QUICK_COUNT,
    PD_PAIR_LSL_XOR,
    PD_PAIR_XOR_QBBS,
    PD_PAIR_CALL_RET,
    PD_PAIR_ADD_ADC2,
    PD_GO_END,
};
_Static_assert(PD_GO_END <= UINT8_MAX, "struct pd keeps .go in a uint8_t");

/* Flags of a predecoded instruction that need work outside the handler. */
#define PD_READS_R31  0x01u /* refresh R31 from the inputs before executing */
#define PD_WRITES_R30 0x02u /* tell the pins if R30 changed */
#define PD_WRITES_R31 0x04u /* an R31 write raises system events */
#define PD_EFFECTS    0x07u /* the three above */
/* and what a burst is, from its row (docs/pru-facts.md §1.7) */
#define PD_BURST_LOAD  0x08u /* LBBO, LBCO (bit 28) */
#define PD_BURST_CBASE 0x10u /* LBCO, SBCO: the base is a constant-table entry */

/*
 * One IRAM word decoded once. Register operands are (reg, shift, mask);
 * an immediate operand uses register 32 (always 0) with mask 0 and puts the
 * value in imm, so "field | imm" reads either form without a branch.
 */
struct pd {
    /* one cache line each (core.c allocates them aligned) */
    _Alignas(64) uint8_t fast; /* kind for the fast loop: PD_SLOW if flags or not register-only */
    uint8_t kind;
    uint8_t flags;
    uint8_t rd, rdsh;
    uint8_t rs1, rs1sh;
    uint8_t rs2, rs2sh;
    uint8_t rdw; /* destination width in bits (carry position) */
    /* bursts with a fixed length that stay below r30 (no pin or event
     * effects): bytes and register-file start; 0 bytes otherwise */
    uint8_t burst_bytes, burst_rf;
    uint32_t rdmask, rs1mask, rs2mask;
    uint32_t imm;
    uint32_t target; /* absolute branch/jump target, LOOP end */
    struct pru_insn in;
    uint8_t inner; /* PD_R31_READ: the fast kind to run once R31 is read */
    uint8_t xfast; /* PD_XPRU: the fast kind once the other PRU is there */
    uint8_t go;    /* what the fast loop dispatches on: .fast, or PD_RUN ... */
    /* the straight run from here: how many of PD_STRAIGHT_KINDS (or R31
     * reads of them) follow from this one on, this one included (0: this
     * is none of them; UINT16_MAX: so many or more) */
    uint16_t run;
};

/* Lazily evaluated 28-bit GPI shift register (cfg_gpi.c). */
struct gpi_shift {
    int64_t t_cfg_ps;        /* reference for edge times */
    int64_t period_ps;       /* shift period, exact integer ps */
    int64_t k_done;          /* edges already applied (edge k at t_cfg + phase + k*period) */
    int64_t next_edge_cycle; /* first cycle that sees edge k_done + 1 */
    uint32_t reg;            /* 28 bits */
    bool sb;
    int64_t cnt16_k; /* edge that captured the start bit; Cnt_16 at +16j */
};

struct iep {
    uint32_t global_cfg, global_status, compen, count, cmp_cfg, cmp_status;
    uint32_t cmp[8];
    int64_t synced;          /* state is as of this cycle boundary */
    uint8_t regs[IEP_BYTES]; /* backing store for the registers not modelled */
};

struct intc {
    uint32_t ger, hier;
    uint32_t raw[2], enabled[2];
    uint8_t cmr[64]; /* channel per event */
    uint8_t hmr[16]; /* host per channel */
    uint8_t regs[INTC_BYTES];
};

struct ctrl {
    uint32_t control, wakeup_en, ctbir0, ctbir1, ctppr0, ctppr1;
    /* CYCLE/STALL, evaluated lazily: value = saved + elapsed since `since`. */
    bool counting;
    uint32_t cycle_saved, stall_saved;
    int64_t cycle_since, stall_since;
};

struct ext_window {
    uint32_t base, size;
    uint8_t *mem;
};

/* A loop body as the fast-forward decoded it (ff.c), kept while IRAM
 * is not written (pru_core.iram_gen). */
#define FF_MAX_BODY 16u /* words; longer loops are not idle polls */
#define FF_BODIES   8u  /* loop bodies kept (a firmware's period loops and its polls) */
struct ff_body {
    uint32_t top, pc;  /* [top, pc], pc the closing branch; top > pc: none */
    uint64_t iram_gen; /* IRAM's generation when decoded */
    uint32_t r31_mask; /* R31 bits it looks at */
    int counter;       /* a counted poll's counter register, -1 if it is none */
    uint8_t sel;       /* ... its field (a whole register or part of one) */
    uint32_t step;     /* ... added to the field per iteration (mod 2^width) */
    uint32_t end;      /* ... the value that ends the loop */
    bool sign_end;     /* ... or: it ends when the counter goes below 0 (QBBC top, x, 31) */
    int cl_reg;        /* a count loop's counter register (ff.c), -1 if it is none */
    uint8_t cl_sel;    /* ... its field */
    uint32_t cl_step;  /* ... subtracted from it per turn (> 0) */
};

/*
 * A leaf call's memo (leaf.c, leaf.h): a routine reached by a call
 * from far below it (JAL to FF_MAX_BODY words or more back, the firmware's
 * delay tails), made of single-cycle register-only instructions without
 * a taken branch back, returning by a JMP through the call's link field.
 * Its effect is a function of the register-file bytes (and carry) it reads
 * before writing them: recorded once, replayed while those are the same.
 */
#define LEAF_MEMOS     16u    /* by target modulo LEAF_MEMOS */
#define LEAF_MAX_INSNS 32u    /* the routine's instructions, its return included */
#define LEAF_MAX_BYTES 16u    /* bytes read first, bytes written */
#define LEAF_RETRY     64u    /* calls a refused routine lets pass before another look, */
#define LEAF_RETRY_MAX 65536u /* ... doubled each time it is refused again */
#define LEAF_PAID      16u    /* replays that repay a recording (leaf.c leaf_other) */
struct leaf_memo {
    /* what a replay looks at first */
    uint64_t key;      /* target | link rd << 16 | link shift << 24 | link mask << 32 */
    uint64_t iram_gen; /* IRAM's generation when recorded (0: no memo) */
    uint32_t cycles;   /* = instructions, the return included; 0: refused */
    uint32_t pc_max;   /* the highest pc it runs */
    /* the first two inputs (unused: byte 128, r[32]'s, always 0, with 0)
     * and outputs (n_out of them); more: there are others (in_at[2..],
     * out_at[2..]) */
    uint8_t in0_at, in0_val, in1_at, in1_val;
    uint8_t out0_at, out0_val, out1_at, out1_val;
    uint8_t cin_read, cin_val;     /* the carry read before written: 1 and its value */
    uint8_t carry_keep, carry_set; /* after it: carry & keep | set */
    bool more;
    uint32_t hits; /* replays since it was recorded */
    /* the record */
    uint32_t retry;      /* refused: calls to let pass before another look; */
                         /* accepted: calls with other inputs (leaf_other) */
    uint32_t retry_next; /* ... what retry started from */
    uint8_t n_in, n_out;
    uint8_t in_at[LEAF_MAX_BYTES], in_val[LEAF_MAX_BYTES];
    uint8_t out_at[LEAF_MAX_BYTES], out_val[LEAF_MAX_BYTES];
    uint16_t pcs[LEAF_MAX_INSNS]; /* the pcs it runs, pcs[0] the target */
};

/* Fast-forward probe of an idle polling loop (ff.c). */
struct ff_probe {
    uint32_t top; /* loop top, NO_LOOP when unarmed */
    int64_t cycle0;
    uint64_t insn0;
    int64_t stall0;
    int64_t horizon;  /* first cycle at which a read of this iteration may differ */
    bool dirty;       /* a side effect happened since arming */
    bool have_snap;   /* regs/carry hold a snapshot: this iteration is a probe */
    bool saw_input;   /* an input was read since the last arrival at top */
    unsigned fails;   /* probes in a row that found the state changed */
    unsigned backoff; /* arrivals to let pass before the next probe */
    uint32_t regs[32];
    int carry;
    uint64_t skipped;
    uint32_t r31_mask;              /* R31 bits the armed loop looks at (horizons of R31 reads) */
    struct ff_body body[FF_BODIES]; /* any body in any entry (ff.c body()) */
};

/* Strict and contention modes (strict.c). Violations wait in `pending`
 * until the R30 change that closes their window says whether it was a
 * clocked one. */
#define STRICT_PENDING 64u
struct strict_state {
    int64_t last_edge;    /* issue cycle of the last R30 change, INT64_MIN: none */
    uint32_t inputs;      /* R31 bits whose changes are edges too (pru_strict_inputs) */
    uint32_t inputs_seen; /* their last levels an instruction read */
    struct pru_strict_hit pending[STRICT_PENDING];
    unsigned n_pending;
    uint64_t pending_over; /* violations beyond `pending` in this window */
    struct pru_strict_hit hits[PRU_STRICT_MAX_HITS];
    size_t n_hits;
    uint64_t lost;
    uint64_t collisions, stall_cycles; /* contention */
};

struct pru_core {
    /* store watch (pru_set_store_watch): checked on stores to data RAM */
    uint32_t watch_addr; /* UINT32_MAX: none */
    void (*watch_fn)(void *ctx, uint32_t addr);
    void *watch_ctx;
    /* hot state first */
    uint32_t r[33]; /* r[32] is a constant 0 for immediate operands */
    uint32_t pc;
    int carry;
    int64_t cycle; /* current time in cycles */
    uint64_t insns;
    int64_t stall_total; /* cycles in which no instruction was fetched */
    uint32_t loop_end, loop_top, loop_count;
    uint32_t iram_words;
    uint64_t iram_gen; /* counts IRAM word changes (predecode_word) */
    struct pd *pd;
    bool stop;    /* leave the run loop after this instruction */
    bool recheck; /* ... and re-evaluate enable/sleep/step (not a stop) */
    enum pru_stop stop_reason;
    bool trace_on;
    bool ff_on;

    struct pru_params p;
    enum pru_soc soc;
    uint32_t dram_bytes, shared_bytes, iram_bytes;
    uint8_t *dram0, *dram1, *shared;
    uint32_t *iram0, *iram1;
    /* the PRU-ICSS's three scratch-pad banks, one set for both PRUs:
     * own_spad, or PRU0's (pruss.c) */
    uint8_t (*spad)[SPAD_BYTES];
    uint8_t own_spad[3][SPAD_BYTES];
    /* The issue cycle of this core's last XFR on each bank (-1: none):
     * PRU1 looks at PRU0's to find a collision (exec_mem.c) */
    int64_t spad_cycle[3];
    uint64_t spad_collisions; /* stalls of this core for one (PRU1 only) */

    bool halted, sleeping, sleep_wake_on_event;
    struct pru_fault fault;

    struct ctrl ctrl;
    uint8_t ctrl1[CTRL_BYTES];
    uint32_t *cfg_regs; /* the PRU-ICSS's CFG block: own_cfg, or PRU0's (pruss.c) */
    uint32_t own_cfg[CFG_BYTES / 4];
    struct gpi_shift sh;
    struct iep iep;
    struct intc intc;
    struct ext_window ext[4];
    unsigned n_ext;

    struct pru_pins pins;
    bool have_pins;
    uint32_t const_inputs;
    uint32_t r30_pins; /* last R30 value given to the pins */
    FILE *trace;
    struct ff_probe ff;
    struct leaf_memo leaf[LEAF_MEMOS];
    uint64_t leaf_hits;    /* leaf calls replayed from a memo */
    uint64_t leaf_records; /* leaf calls recorded (leaf.c leaf_record) */
    bool checked;          /* strict or contention on: every instruction through exec_checked() */
    struct strict_state st;

    /* The PRU-ICSS around the core (pruss.c): pru0 holds the blocks both
     * PRUs share (INTC, CFG, IEP; itself when the core is alone), pru1 is
     * PRU1 when there is one (NULL alone); pru_idx says which this is.
     * A borrowed core uses pru0's data and shared RAMs (not freed here). */
    struct pru_core *pru0, *pru1;
    unsigned pru_idx;
    bool borrowed;
    /* Run-ahead (pruss.c, TIMING.md "Two PRUs"): a cross-PRU event issued
     * in this cycle or later waits for the other PRU (the core stops in
     * front of it); CYCLE_NEVER while the core runs alone or the two take
     * turns cycle by cycle. */
    int64_t xlimit;
    /* ff.c body(): the entry of ff.body looked up last, the one to take
     * next, and the bodies decoded (last in the struct: the fields above
     * keep their places, which the two-PRU runs' speed turned out to
     * depend on by a few per cent) */
    uint32_t ff_body_last, ff_body_next;
    uint64_t ff_decoded;
};

/* pruss.c: run-ahead. Whether the cross-PRU event at cycle (an
 * instruction issued then) must wait for the other PRU; when it may go on
 * under a fast-forward probe, the probe's horizon is that PRU's next event
 * at the earliest (xlimit). */
static inline bool xpru_wait(struct pru_core *c, int64_t cycle);
/* An access that changes what the other PRU may already have run ahead
 * through (its CONTROL block or GPCFG, the INTC turned on), by c at
 * c->cycle: a PRU_FAULT_RUN_AHEAD (at addr) if the other PRU is past it. */
void xpru_exclusive(struct pru_core *c, uint32_t addr);
/* cfg_gpi.c: whether an R31 read at cycle is a cross-PRU event: the INTC
 * drives R31[31:30], or the read brings a Cnt_16 event to the INTC. */
bool gpi_r31_shared(struct pru_core *c, int64_t cycle);

/* core.c */
void core_fault(struct pru_core *c, enum pru_fault_cause cause, uint32_t addr);

/* predecode.c */
void predecode_word(struct pru_core *c, uint32_t pc);
void predecode_all(struct pru_core *c);

/* exec.c */
enum pru_stop exec_run(struct pru_core *c, int64_t limit, bool one_step);

/* memmap.c: PRU data-space access; return 0 or -1 (fault recorded; a load
 * then leaves dst as it was). mem_load/mem_store below are the entry points. */
int mem_load_any(struct pru_core *c, uint32_t addr, uint8_t *dst, unsigned n, unsigned *cycles);
int mem_store_any(struct pru_core *c, uint32_t addr, const uint8_t *src, unsigned n,
                  unsigned *cycles);
uint32_t const_table(const struct pru_core *c, unsigned n);

/* Access cost (docs/pru-facts.md §3, emulator/core/TIMING.md): 32-bit beats. */
static inline unsigned mem_beats(unsigned n) {
    return (n + 3u) / 4u;
}
static inline unsigned mem_local_load_cycles(const struct pru_core *c, unsigned n) {
    return c->p.load_local_base + mem_beats(n);
}
static inline unsigned mem_store_cycles(const struct pru_core *c, unsigned n) {
    unsigned cyc = mem_beats(n) * c->p.store_beat_cycles;
    return cyc ? cyc : 1;
}

/* The register blocks (ctrl.c, cfg_gpi.c, iep.c, intc.c): icss_block.h. */

/* ff.c */
void ff_backward_branch(struct pru_core *c, uint32_t pc, uint32_t top, int64_t limit);
/* No loop armed: what a branch back further than FF_MAX_BODY leaves. */
static inline void ff_disarm(struct pru_core *c) {
    c->ff.top = NO_LOOP;
    c->ff.have_snap = false;
    c->ff.r31_mask = ~0u;
}
/*
 * The common case of ff_backward_branch() done in line: a branch back to
 * the top it came to last time with no probe running and none to start
 * (no input read since, or a backoff pending) only counts the backoff down
 * and forgets the reads; returns false when the full call is needed. Pure
 * countdown loops and busy loops in backoff take only this.
 */
static inline bool ff_backward_quick(struct pru_core *c, uint32_t pc, uint32_t top) {
    struct ff_probe *f = &c->ff;
    if (f->top != top || f->have_snap || pc - top >= FF_MAX_BODY)
        return false;
    if (f->backoff)
        f->backoff--;
    else if (f->saw_input)
        return false;
    f->saw_input = false;
    f->dirty = false;
    return true;
}
/* Called when a LOOP instruction (ending before `limit`) has entered its
 * loop: runs the iterations of a pure delay at once. */
void ff_loop_entered(struct pru_core *c, int64_t limit);
/* An input was read; true if its horizon is wanted (a probe is running). */
static inline bool ff_input_read(struct pru_core *c) {
    if (c->ff.top == NO_LOOP)
        return false;
    c->ff.saw_input = true;
    return c->ff.have_snap;
}
static inline void ff_horizon(struct pru_core *c, int64_t cycle) {
    if (cycle < c->ff.horizon)
        c->ff.horizon = cycle;
}
static inline void ff_dirty(struct pru_core *c) {
    c->ff.dirty = true;
}

static inline bool xpru_wait(struct pru_core *c, int64_t cycle) {
    if (cycle >= c->xlimit)
        return true;
    if (c->xlimit != CYCLE_NEVER && ff_input_read(c))
        ff_horizon(c, c->xlimit);
    return false;
}

/* exec_mem.c: whether XFR device dev, issued by c in this cycle, meets
 * PRU0 on the same scratch-pad bank (c is PRU1 of a PRU-ICSS). */
bool spad_collides(const struct pru_core *c, unsigned dev);

/* strict.c */
void strict_reset(struct pru_core *c);
/* Before executing d at c->pc: record the rules it breaks; true if that
 * stopped the core (everywhere scope, no log) and d must not run. */
bool strict_before(struct pru_core *c, const struct pd *d);
/* R30 changed by the instruction issued in cycle `cycle`. */
void strict_edge(struct pru_core *c, int64_t cycle);
/* The data address of burst d as it would run now. */
uint32_t strict_burst_addr(struct pru_core *c, const struct pd *d);
/* Whether [addr, addr+n) lies in data RAM 0/1 or shared RAM. */
bool strict_local_ram(const struct pru_core *c, uint32_t addr, unsigned n);
/* Extra cycles for a local-RAM access issued in cycle t lasting n cycles. */
unsigned contend_stall(struct pru_core *c, int64_t t, unsigned n);
void strict_print_fault(const struct pru_core *c, FILE *f);

/* trace.c */
void trace_insn(struct pru_core *c, uint32_t pc, int64_t cycle, const uint32_t *before,
                int carry_before);

/* AND/OR of a field with itself into it (pasm's `mov rN, rN`): writes what
 * was there, so it changes nothing (ff.c's delays and count loops, a leaf
 * call's pads). */
static inline bool insn_is_identity(const struct pru_insn *a) {
    return (a->op == PRU_OP_AND || a->op == PRU_OP_OR) && !a->io && a->rd == a->rs1 &&
           a->rs1 == a->rs2 && a->rdsel == a->rs1sel && a->rs1sel == a->rs2sel;
}

/* Field helpers */
static inline uint32_t fld(const uint32_t *r, unsigned reg, unsigned sh, uint32_t mask) {
    return (r[reg] >> sh) & mask;
}
static inline void fld_set(uint32_t *r, unsigned reg, unsigned sh, uint32_t mask, uint32_t v) {
    r[reg] = (r[reg] & ~(mask << sh)) | ((v & mask) << sh);
}

/* A store to [addr, addr + n) of data RAM by the instruction at pc, issued
 * in `cycle`, just happened: tell the watch. The fast loop keeps pc and
 * cycle in registers (c->pc and c->cycle lag behind), so they are brought
 * up to date first, on a hit only: the callback's pru_cycles() and
 * pru_pc() are the store's (the loop overwrites both when it syncs out,
 * with what they already were or later values). */
static inline void core_store_watch(struct pru_core *c, uint32_t addr, unsigned n, uint32_t pc,
                                    int64_t cycle) {
    if (c->watch_addr - addr < n) {
        c->pc = pc;
        c->cycle = cycle;
        c->watch_fn(c->watch_ctx, c->watch_addr);
    }
}

/*
 * Copy a burst's n bytes (n <= 128) between the register file and data RAM
 * (never overlapping): in 8-byte pieces, the last one overlapping the one
 * before. GCC makes memcpy() of a variable length a `rep movs` here, whose
 * start-up costs more than the few bytes a burst moves.
 */
static inline void burst_copy(uint8_t *dst, const uint8_t *src, unsigned n) {
    if (n >= 8) {
        for (unsigned i = 0; i + 8 < n; i += 8)
            memcpy(dst + i, src + i, 8);
        memcpy(dst + n - 8, src + n - 8, 8);
    } else if (n >= 4) {
        memcpy(dst, src, 4);
        memcpy(dst + n - 4, src + n - 4, 4);
    } else if (n >= 2) {
        memcpy(dst, src, 2);
        memcpy(dst + n - 2, src + n - 2, 2);
    } else if (n) {
        dst[0] = src[0];
    }
}

/*
 * Load n bytes of the PRU data space at the instruction at pc, issued in
 * cycle `cycle`: the own data RAM in place (the common case, inline for the
 * execute loop), the rest in memmap.c, which needs c->pc and c->cycle
 * current (the caller may keep them in registers until then). Returns 0
 * on success, -1 after a fault.
 */
static inline int mem_load(struct pru_core *c, uint32_t addr, uint8_t *dst, unsigned n,
                           unsigned *cycles, uint32_t pc, int64_t cycle) {
    if ((uint64_t)addr + n <= c->dram_bytes) {
        burst_copy(dst, c->dram0 + addr, n);
        *cycles = mem_local_load_cycles(c, n);
        return 0;
    }
    c->pc = pc;
    c->cycle = cycle;
    return mem_load_any(c, addr, dst, n, cycles);
}

/* Store n bytes; as mem_load. */
static inline int mem_store(struct pru_core *c, uint32_t addr, const uint8_t *src, unsigned n,
                            unsigned *cycles, uint32_t pc, int64_t cycle) {
    if ((uint64_t)addr + n <= c->dram_bytes) {
        burst_copy(c->dram0 + addr, src, n);
        core_store_watch(c, addr, n, pc, cycle);
        *cycles = mem_store_cycles(c, n);
        return 0;
    }
    c->pc = pc;
    c->cycle = cycle;
    return mem_store_any(c, addr, src, n, cycles);
}

#endif
