/*
 * exec.c - the execute loop: one predecoded instruction per iteration,
 * exact cycle costs (docs/pru-facts.md §3), LOOP hardware, sleep and stop.
 */
#include "core_priv.h"
#include "exec_priv.h"
#include "leaf.h"

#include <string.h>

_Static_assert(__BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__,
               "the register file is addressed bytewise as little-endian");

static inline uint32_t rs1v(const uint32_t *r, const struct pd *d) {
    return fld(r, d->rs1, d->rs1sh, d->rs1mask);
}

static inline uint32_t op2v(const uint32_t *r, const struct pd *d) {
    return fld(r, d->rs2, d->rs2sh, d->rs2mask) | d->imm;
}

/* op2 of a kind whose op2 is a whole register or an immediate (r[32] = 0,
 * imm 0 for a register) */
static inline uint32_t op2w(const uint32_t *r, const struct pd *d) {
    return r[d->rs2] | d->imm;
}

static inline void wr(uint32_t *r, const struct pd *d, uint32_t v) {
    fld_set(r, d->rd, d->rdsh, d->rdmask, v);
}

/* Byte and word fields in place: the register file is little-endian, byte
 * 4n + k is rn.bk (the fast kinds PD_MINB32I ...). */
static inline uint8_t *rf_byte(uint32_t *r, unsigned reg, unsigned sh) {
    return (uint8_t *)r + 4u * reg + sh / 8u;
}
static inline uint32_t rs1_byte(uint32_t *r, const struct pd *d) {
    return *rf_byte(r, d->rs1, d->rs1sh);
}
static inline uint32_t rs1_word(uint32_t *r, const struct pd *d) {
    uint16_t w;
    memcpy(&w, rf_byte(r, d->rs1, d->rs1sh), sizeof w);
    return w;
}
static inline uint32_t op2_byte(uint32_t *r, const struct pd *d) {
    return *rf_byte(r, d->rs2, d->rs2sh);
}
static inline void wr_byte(uint32_t *r, const struct pd *d, uint32_t v) {
    *rf_byte(r, d->rd, d->rdsh) = (uint8_t)v;
}

/* carry = bit W of the untruncated sum (W = destination width) */
static inline uint32_t add_c(int *carry, const struct pd *d, uint64_t a, uint64_t b, uint64_t cin) {
    uint64_t s = a + b + cin;
    *carry = (int)((s >> d->rdw) & 1u);
    return (uint32_t)s;
}

/* carry = NOT borrow: NOT bit W of the wide difference (docs/pru-facts.md §1.3) */
static inline uint32_t sub_c(int *carry, const struct pd *d, uint64_t a, uint64_t b, uint64_t bin) {
    uint64_t s = a - b - bin;
    *carry = (int)(((s >> d->rdw) & 1u) ^ 1u);
    return (uint32_t)s;
}

static uint32_t lmbd(uint32_t v, uint32_t mask, uint32_t bit) {
    uint32_t x = (bit & 1u) ? v : (~v & mask);
    return x ? 31u - (uint32_t)__builtin_clz(x) : 32u;
}

/* Tell the pins about an R30 change; the new level lands after the
 * instruction's last cycle. */
void exec_r30_changed(struct pru_core *c, int64_t end_cycle) {
    if (c->r[30] == c->r30_pins)
        return;
    c->r30_pins = c->r[30];
    ff_dirty(c);
    if (c->have_pins && c->pins.outputs_changed)
        c->pins.outputs_changed(c->pins.ctx, end_cycle * PRU_PS_PER_CYCLE + c->p.gpo_delay_ps,
                                c->r[30]);
}

/* An R31 write: bit 5 with a channel in bits 3:0 pulses system event 16+n. */
void exec_r31_written(struct pru_core *c, uint32_t written_mask) {
    ff_dirty(c);
    if ((written_mask & 0x2fu) != 0x2fu)
        return;
    uint32_t v = c->r[31];
    if (v & 0x20u)
        intc_event(c, 16u + (v & 0xfu));
}

static void do_loop(struct pru_core *c, const struct pd *d) {
    uint32_t n = op2v(c->r, d);
    if (!d->in.io)
        n &= 0xffffu; /* only the 16 LS bits of the field count */
    ff_dirty(c);
    if (n == 0) {
        c->pc = d->target;
        return;
    }
    c->loop_top = c->pc + 1;
    c->loop_end = d->target;
    c->loop_count = n;
    c->pc = c->pc + 1;
}

static inline void loop_back(struct pru_core *c) {
    ff_dirty(c);
    if (--c->loop_count)
        c->pc = c->loop_top;
    else
        c->loop_end = NO_LOOP;
}

static void do_halt(struct pru_core *c) {
    c->halted = true;
    c->ctrl.control &= ~PRU_CTRL_ENABLE;
    ctrl_counting_update(c, c->cycle + 1);
    c->stop = true;
    c->stop_reason = PRU_STOP_HALT;
}

static void do_slp(struct pru_core *c, const struct pd *d) {
    c->sleeping = true;
    c->sleep_wake_on_event = d->in.flag != 0;
    c->ctrl.control |= PRU_CTRL_SLEEPING;
    ctrl_counting_update(c, c->cycle + 1);
    c->pc++;
    exec_recheck(c);
}

/*
 * The instructions that only touch registers, carry and PC: ALU, LDI, LMBD,
 * jumps and quick branches. Returns false for every other kind. Works on
 * plain variables so the fast loop can keep its state in registers.
 */
/* always_inline: the fast loop's state must stay in registers */
static inline __attribute__((always_inline)) bool exec_simple(uint32_t *restrict r,
                                                              const struct pd *restrict d,
                                                              unsigned kind, uint32_t *pc,
                                                              int *carry) {
    uint32_t p = *pc;
    switch (kind) {
    case PRU_OP_ADD:
        wr(r, d, add_c(carry, d, rs1v(r, d), op2v(r, d), 0));
        break;
    case PRU_OP_ADC:
        wr(r, d, add_c(carry, d, rs1v(r, d), op2v(r, d), (uint64_t)*carry));
        break;
    case PRU_OP_SUB:
        wr(r, d, sub_c(carry, d, rs1v(r, d), op2v(r, d), 0));
        break;
    case PRU_OP_SUC:
        wr(r, d, sub_c(carry, d, rs1v(r, d), op2v(r, d), (uint64_t) !*carry));
        break;
    case PRU_OP_RSB:
        wr(r, d, sub_c(carry, d, op2v(r, d), rs1v(r, d), 0));
        break;
    case PRU_OP_RSC:
        wr(r, d, sub_c(carry, d, op2v(r, d), rs1v(r, d), (uint64_t) !*carry));
        break;
    case PRU_OP_LSL:
        wr(r, d, rs1v(r, d) << (op2v(r, d) & 31u));
        break;
    case PRU_OP_LSR:
        wr(r, d, rs1v(r, d) >> (op2v(r, d) & 31u));
        break;
    case PRU_OP_AND:
        wr(r, d, rs1v(r, d) & op2v(r, d));
        break;
    case PRU_OP_OR:
        wr(r, d, rs1v(r, d) | op2v(r, d));
        break;
    case PRU_OP_XOR:
        wr(r, d, rs1v(r, d) ^ op2v(r, d));
        break;
    case PRU_OP_NOT:
        wr(r, d, ~rs1v(r, d));
        break;
    case PRU_OP_MIN: {
        uint32_t a = rs1v(r, d), b = op2v(r, d);
        wr(r, d, a < b ? a : b);
        break;
    }
    case PRU_OP_MAX: {
        uint32_t a = rs1v(r, d), b = op2v(r, d);
        wr(r, d, a > b ? a : b);
        break;
    }
    case PRU_OP_CLR:
        wr(r, d, rs1v(r, d) & ~(1u << (op2v(r, d) & 31u)));
        break;
    case PRU_OP_SET:
        wr(r, d, rs1v(r, d) | (1u << (op2v(r, d) & 31u)));
        break;
    case PRU_OP_NOP0: /* every NOPn */
        break;
    case PRU_OP_LDI:
        wr(r, d, d->imm);
        break;
    case PRU_OP_LMBD:
        wr(r, d, lmbd(rs1v(r, d), d->rs1mask, op2v(r, d)));
        break;
    case PRU_OP_JMP:
        *pc = op2v(r, d) & 0xffffu;
        return true;
    case PRU_OP_JAL: {
        uint32_t t = op2v(r, d) & 0xffffu; /* read before the link write */
        wr(r, d, p + 1);
        *pc = t;
        return true;
    }
#define QB(cond)                                                                                   \
    *pc = (cond) ? d->target : p + 1;                                                              \
    return true
    case PRU_OP_QBGT:
        QB(op2v(r, d) > rs1v(r, d));
    case PRU_OP_QBGE:
        QB(op2v(r, d) >= rs1v(r, d));
    case PRU_OP_QBLT:
        QB(op2v(r, d) < rs1v(r, d));
    case PRU_OP_QBLE:
        QB(op2v(r, d) <= rs1v(r, d));
    case PRU_OP_QBEQ:
        QB(op2v(r, d) == rs1v(r, d));
    case PRU_OP_QBNE:
        QB(op2v(r, d) != rs1v(r, d));
    case PRU_OP_QBA:
        *pc = d->target;
        return true;
    case PRU_OP_QBBS:
        QB((rs1v(r, d) >> (op2v(r, d) & 31u)) & 1u);
    case PRU_OP_QBBC:
        QB(!((rs1v(r, d) >> (op2v(r, d) & 31u)) & 1u));
    /* the whole-register forms (fast loop only): carry from bit 32 (ADD),
     * NOT borrow (SUB) */
    case PD_ADD32: {
        uint32_t a = r[d->rs1], sum = a + op2v(r, d);
        *carry = sum < a;
        r[d->rd] = sum;
        break;
    }
    case PD_SUB32: {
        uint32_t a = r[d->rs1], b = op2v(r, d);
        *carry = a >= b;
        r[d->rd] = a - b;
        break;
    }
    case PD_ADD32I: {
        uint32_t a = r[d->rs1];
        *carry = a + d->imm < a;
        r[d->rd] = a + d->imm;
        break;
    }
    case PD_SUB32I: {
        uint32_t a = r[d->rs1];
        *carry = a >= d->imm;
        r[d->rd] = a - d->imm;
        break;
    }
    case PD_ADC32: {
        uint64_t sum = (uint64_t)r[d->rs1] + op2w(r, d) + (uint64_t)*carry;
        *carry = (int)(sum >> 32);
        r[d->rd] = (uint32_t)sum;
        break;
    }
    case PD_AND32:
        r[d->rd] = r[d->rs1] & op2w(r, d);
        break;
    case PD_OR32:
        r[d->rd] = r[d->rs1] | op2w(r, d);
        break;
    case PD_XOR32:
        r[d->rd] = r[d->rs1] ^ op2w(r, d);
        break;
    case PD_LSL32:
        r[d->rd] = r[d->rs1] << (op2w(r, d) & 31u);
        break;
    case PD_LSR32:
        r[d->rd] = r[d->rs1] >> (op2w(r, d) & 31u);
        break;
    case PD_LSL32I:
        r[d->rd] = r[d->rs1] << (d->imm & 31u);
        break;
    case PD_LSR32I:
        r[d->rd] = r[d->rs1] >> (d->imm & 31u);
        break;
    case PD_LDI32:
        r[d->rd] = d->imm;
        break;
    case PD_SUBI:
        wr(r, d, sub_c(carry, d, rs1v(r, d), d->imm, 0));
        break;
    case PD_MINI: {
        uint32_t a = rs1v(r, d);
        wr(r, d, a < d->imm ? a : d->imm);
        break;
    }
    case PD_MINB32I: {
        uint32_t a = r[d->rs1];
        wr_byte(r, d, a < d->imm ? a : d->imm);
        break;
    }
    case PD_SUB32B: {
        uint32_t a = r[d->rs1], b = op2_byte(r, d);
        *carry = a >= b;
        r[d->rd] = a - b;
        break;
    }
    case PD_SUBBBI:
        wr_byte(r, d, sub_c(carry, d, rs1_byte(r, d), d->imm, 0));
        break;
    case PD_JALI:
        wr(r, d, p + 1);
        *pc = d->imm & 0xffffu;
        return true;
    case PD_QBEQI:
        QB(d->imm == rs1v(r, d));
    case PD_QBNEI:
        QB(d->imm != rs1v(r, d));
    case PD_QBEQBI:
        QB(d->imm == rs1_byte(r, d));
    case PD_QBNEBI:
        QB(d->imm != rs1_byte(r, d));
    case PD_QBEQWI:
        QB(d->imm == rs1_word(r, d));
    case PD_QBNEWI:
        QB(d->imm != rs1_word(r, d));
    case PD_QBNE32:
        QB(op2v(r, d) != r[d->rs1]);
    case PD_QBEQ32:
        QB(op2v(r, d) == r[d->rs1]);
    case PD_QBNE32I:
        QB(d->imm != r[d->rs1]);
    case PD_QBEQ32I:
        QB(d->imm == r[d->rs1]);
    case PD_QBBS32:
        QB((r[d->rs1] >> (op2v(r, d) & 31u)) & 1u);
    case PD_QBBC32:
        QB(!((r[d->rs1] >> (op2v(r, d) & 31u)) & 1u));
    case PD_QBBS32I:
        QB((r[d->rs1] >> (d->imm & 31u)) & 1u);
    case PD_QBBC32I:
        QB(!((r[d->rs1] >> (d->imm & 31u)) & 1u));
#undef QB
    default:
        return false;
    }
    *pc = p + 1;
    return true;
}

/* Execute the instruction at c->pc: any kind, any flags. Advances pc,
 * cycle and insns. */
static __attribute__((noinline)) void exec_one(struct pru_core *c, const struct pd *d,
                                               int64_t limit) {
    uint32_t pc = c->pc;
    unsigned cost = 1;

    if (d->flags & PD_READS_R31)
        c->r[31] = gpi_r31(c, c->cycle);

    if (exec_simple(c->r, d, d->kind, &c->pc, &c->carry)) {
        if (c->pc <= pc && c->ff_on && !ff_backward_quick(c, pc, c->pc)) /* a backward jump */
            ff_backward_branch(c, pc, c->pc, limit);
    } else {
        switch ((enum pru_fmt)(d->kind == PD_BAD ? PRU_FMT_PSEUDO : pru_optable[d->kind].fmt)) {
        case PRU_FMT_LOOP:
            do_loop(c, d);
            if (c->ff_on)
                ff_loop_entered(c, limit);
            break;
        case PRU_FMT_BURST: {
            /* contention: the address before a load may change its base */
            uint32_t addr = c->p.contend_period ? strict_burst_addr(c, d) : 0;
            cost = exec_burst(c, d, c->pc, c->cycle);
            if (c->fault.cause == PRU_FAULT_NONE) {
                c->pc++;
                if (c->p.contend_period && strict_local_ram(c, addr, 1))
                    cost += contend_stall(c, c->cycle, cost);
            }
            break;
        }
        case PRU_FMT_XFR:
            cost += exec_xfr(c, d);
            break;
        case PRU_FMT_MVI:
            exec_mvi(c, d);
            break;
        case PRU_FMT_NONE: /* HALT */
            do_halt(c);
            break;
        case PRU_FMT_SLP:
            do_slp(c, d);
            break;
        default:
            core_fault(c, PRU_FAULT_BAD_OPCODE, 0);
            return;
        }
        if (c->fault.cause != PRU_FAULT_NONE)
            return; /* the faulting instruction does not complete */
    }

    if (d->flags & (PD_WRITES_R30 | PD_WRITES_R31)) {
        if (d->flags & PD_WRITES_R30)
            exec_r30_changed(c, c->cycle + cost);
        if (d->flags & PD_WRITES_R31)
            exec_r31_written(c, d->rdmask << d->rdsh);
    }
    c->cycle += cost;
    c->stall_total += cost - 1;
    c->insns++;
    if (c->pc == c->loop_end)
        loop_back(c);
}

/* Sleep until woken or limit; returns true when awake. */
static bool sleep_until(struct pru_core *c, int64_t limit) {
    while (c->cycle < limit) {
        if (!(c->ctrl.control & PRU_CTRL_SLEEPING)) {
            c->sleeping = false; /* woken by a write of SLEEPING = 0 */
        } else if (c->sleep_wake_on_event) {
            uint32_t v = gpi_r31(c, c->cycle) & c->ctrl.wakeup_en;
            if (v) {
                c->sleeping = false;
                c->ctrl.control &= ~PRU_CTRL_SLEEPING;
            } else {
                int64_t h = gpi_stable_until(c, c->cycle);
                int64_t next = h > c->cycle ? h : c->cycle + 1;
                c->cycle = next < limit ? next : limit;
                continue;
            }
        } else {
            c->cycle = limit; /* SLP 0: until reset */
            continue;
        }
        ctrl_counting_update(c, c->cycle);
        return true;
    }
    return false;
}

static bool enabled(const struct pru_core *c) {
    return (c->ctrl.control & PRU_CTRL_ENABLE) != 0;
}

/* Trace wrapper: the same instruction with a before/after register dump. */
static void exec_traced(struct pru_core *c, const struct pd *d, int64_t limit) {
    uint32_t before[32];
    uint32_t pc = c->pc;
    int64_t cyc = c->cycle;
    int carry = c->carry;
    memcpy(before, c->r, sizeof before);
    uint64_t skipped = c->ff.skipped;
    exec_one(c, d, limit);
    trace_insn(c, pc, cyc, before, carry);
    if (c->ff.skipped != skipped)
        fprintf(c->trace, "        (fast-forward: %llu loop iterations skipped, now cycle %lld)\n",
                (unsigned long long)(c->ff.skipped - skipped), (long long)c->cycle);
}

/* Strict or contention mode: the rules before the instruction, the R30
 * change after it (strict.c); traced too if tracing. */
static void exec_checked(struct pru_core *c, const struct pd *d, int64_t limit) {
    if (c->p.strict && strict_before(c, d))
        return;
    uint32_t r30 = c->r30_pins;
    int64_t issued = c->cycle;
    if (c->trace_on)
        exec_traced(c, d, limit);
    else
        exec_one(c, d, limit);
    if (c->p.strict && !c->p.strict_everywhere) {
        uint32_t in = c->r[31] & c->st.inputs; /* as the instruction read R31, if it did */
        if (c->r30_pins != r30 || in != c->st.inputs_seen) {
            c->st.inputs_seen = in;
            strict_edge(c, issued);
        }
    }
}

/* PD_MVI_LD as exec_mvi() does it: the pointer, R31 refreshed, the bytes,
 * the pointer moved on; false (nothing done) if the read wraps past the
 * file's end. Out of line: in run_fast() its temporaries changed the
 * register allocation of every handler (the countdown 6 % slower). */
static __attribute__((noinline)) bool mvi_load(struct pru_core *c, uint32_t *r, const struct pd *d,
                                               int64_t cyc) {
    uint32_t ptr = ((r[d->rs1] >> d->rs1sh) - d->rs2) & d->rs1mask;
    if (ptr > RF_BYTES - d->rdw)
        return false; /* the read wraps (or the pointer is out of the file) */
    if (d->rs2)
        fld_set(r, d->rs1, d->rs1sh, d->rs1mask, ptr);
    if (ptr + d->rdw > 124u) /* the word reaches R31 (as exec_mvi()) */
        r[31] = gpi_r31(c, cyc);
    uint32_t val;
    memcpy(&val, (uint8_t *)r + ptr, sizeof val); /* up to byte 130: r[32] */
    if (d->rs2sh)
        fld_set(r, d->rs1, d->rs1sh, d->rs1mask, ptr + d->rs2sh);
    fld_set(r, d->rd, d->rdsh, d->rdmask, val & d->imm);
    return true;
}

/* exec_simple() out of line, for a leaf call's recording (leaf.c). */
__attribute__((cold)) bool exec_simple_step(uint32_t *r, const struct pd *d, unsigned kind,
                                            uint32_t *pc, int *carry) {
    return exec_simple(r, d, kind, pc, carry);
}

/* Run-ahead (pruss.c): whether the instruction at cyc of fast kind `kind`,
 * a cross-PRU event (an R31 read: if gpi_r31_shared() says so), must wait
 * for the other PRU. Out of line: a core alone never calls it. */
static __attribute__((noinline)) bool xpru_blocks(struct pru_core *c, int64_t cyc, unsigned kind) {
    if ((kind == PD_R31_READ || kind == PD_MVI_LD) && !gpi_r31_shared(c, cyc))
        return false;
    return xpru_wait(c, cyc);
}

/* Leave the fast loop so that exec_run() re-evaluates enable/sleep/step. */
void exec_recheck(struct pru_core *c) {
    c->recheck = true;
    c->stop = true;
}

/*
 * The hot path (no trace, no single step): register-only instructions run
 * here with PC, carry and counters in local variables; everything else goes
 * through exec_one(). Stops on limit, end of IRAM or anything setting stop.
 *
 * Threaded dispatch (computed goto, a GNU C extension that GCC and Clang
 * have): every handler ends in its own jump to the next one, so the host's
 * branch predictor sees one indirect jump per kind instead of one for all.
 * A straight-line instruction never compares pc with the end of IRAM: the
 * predecoded word one past it leaves the loop (PD_END), and quick branches
 * out of IRAM go through exec_one() (predecode.c); only JMP and JAL check.
 *
 * It dispatches on the predecoded .go (core_priv.h): a straight run of
 * register-only instructions (.run) that ends before the cycle limit and
 * before any LOOP end runs in the handlers of rkinds[], which only advance
 * to the next (pc and cycle moved to the run's end once, at its start);
 * the firmware's frequent pairs run there as one (PD_PAIR_*), and a quick
 * branch forward skips BRANCHED()'s look back (PD_FORWARD).
 */
static void run_fast(struct pru_core *c, int64_t limit) {
    /* every kind not named (PD_SLOW, ...) goes the slow way */
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Woverride-init"
    /* the kinds that are not straight (the quick branches and the rest),
     * and their handlers */
#define OTHER_KINDS(X)                                                                             \
    PD_QUICK_KINDS(X)                                                                              \
    X(jmp, PRU_OP_JMP)                                                                             \
    X(jal, PRU_OP_JAL)                                                                             \
    X(r31, PD_R31_READ)                                                                            \
    X(r30, PD_R30_WRITE)                                                                           \
    X(r30_xor, PD_R30_XOR)                                                                         \
    X(jali, PD_JALI)                                                                               \
    X(r30_xorb, PD_R30_XORB)                                                                       \
    X(mvi_ld, PD_MVI_LD)                                                                           \
    X(xfr_fixed, PD_XFR_FIXED)                                                                     \
    X(xpru, PD_XPRU)
#define K_ENTRY(label, kind)  [kind] = &&k_##label,
#define R_ENTRY(label, kind)  [kind] = &&r_##label,
#define E_ENTRY(label, kind)  [PD_RUN + PD_PLACE_##label] = &&e_##label,
#define RE_ENTRY(label, kind) [PD_RUN + PD_PLACE_##label] = &&r_##label,
#define F_ENTRY(label, kind)  [PD_FORWARD + PD_PLACE_##label] = &&f_##label,
    static const void *const kinds[PD_GO_END] = {
        [0 ... PD_GO_END - 1] = &&k_slow,
        OTHER_KINDS(K_ENTRY) PD_STRAIGHT_KINDS(K_ENTRY) PD_STRAIGHT_KINDS(E_ENTRY)
            PD_QUICK_KINDS(F_ENTRY)[PD_RUN_R31] = &&e_r31,
        [PD_PAIR_MIN_SUB] = &&e_min_sub,
        [PD_PAIR_LSL_XOR] = &&e_lsl_xor,
        [PD_PAIR_XOR_QBBS] = &&k_xor32,
        [PD_PAIR_CALL_RET] = &&e_call_ret,
        [PD_PAIR_ADD_ADC2] = &&e_add_adc2,
        [PD_END] = &&out,
    };
    /* inside a straight run: its instructions without the checks, and
     * after its last one the next instruction's own handler */
    static const void *const rkinds[PD_GO_END] = {
        [0 ... PD_GO_END - 1] = &&k_slow,
        OTHER_KINDS(K_ENTRY) PD_STRAIGHT_KINDS(R_ENTRY) PD_STRAIGHT_KINDS(RE_ENTRY)
            PD_QUICK_KINDS(F_ENTRY)[PD_R31_READ] = &&r_r31,
        [PD_RUN_R31] = &&r_r31,
        [PD_PAIR_MIN_SUB] = &&r_min_sub,
        [PD_PAIR_LSL_XOR] = &&r_lsl_xor,
        [PD_PAIR_XOR_QBBS] = &&r_xor_qbbs,
        [PD_PAIR_CALL_RET] = &&e_call_ret,
        [PD_PAIR_ADD_ADC2] = &&r_add_adc2,
        [PD_END] = &&out,
    };
#undef K_ENTRY
#undef R_ENTRY
#undef E_ENTRY
#undef RE_ENTRY
#undef F_ENTRY
#undef OTHER_KINDS
#pragma GCC diagnostic pop
    const struct pd *pd = c->pd;
    const uint32_t n = c->iram_words;
    const bool ff = c->ff_on;
    const bool leaf = c->p.leaf_call != 0;
    const bool runs = c->p.straight_run != 0;
    uint32_t run_pc = 0; /* (the pc a straight instruction in a run sets: unused) */
    uint32_t *r = c->r;
    uint32_t pc = c->pc;
    int carry = c->carry;
    int64_t cyc = c->cycle;
    /* instructions - cycles: changes only where an instruction takes
     * more than one cycle, so the loop counts cycles alone */
    uint64_t ins_less = c->insns - (uint64_t)c->cycle;
    uint32_t loop_end = c->loop_end;
    const struct pd *d;
    uint32_t old;

#define SYNC_OUT()                                                                                 \
    (c->pc = pc, c->carry = carry, c->cycle = cyc, c->insns = (uint64_t)cyc + ins_less)
#define SYNC_IN()                                                                                  \
    (pc = c->pc, carry = c->carry, cyc = c->cycle, ins_less = c->insns - (uint64_t)c->cycle,       \
     loop_end = c->loop_end)
    /* the next instruction, if the run has cycles left */
#define DISPATCH()                                                                                 \
    do {                                                                                           \
        if (__builtin_expect(cyc >= limit, 0))                                                     \
            goto out;                                                                              \
        d = &pd[pc];                                                                               \
        goto *kinds[d->go];                                                                        \
    } while (0)
    /* after a one-cycle instruction that went on to pc + 1 */
#define NEXT()                                                                                     \
    do {                                                                                           \
        cyc++;                                                                                     \
        if (__builtin_expect(pc == loop_end, 0))                                                   \
            goto at_loop_end;                                                                      \
        DISPATCH();                                                                                \
    } while (0)
    /* after a branch from `old` (its target in IRAM): the fast-forward
     * looks at a jump back before the branch's cycle is counted */
#define BRANCHED()                                                                                 \
    do {                                                                                           \
        if (pc <= old && ff && !ff_backward_quick(c, old, pc)) {                                   \
            SYNC_OUT();                                                                            \
            ff_backward_branch(c, old, pc, limit);                                                 \
            SYNC_IN();                                                                             \
        }                                                                                          \
        NEXT();                                                                                    \
    } while (0)
#define STRAIGHT(kind)                                                                             \
    exec_simple(r, d, kind, &pc, &carry);                                                          \
    NEXT()
#define BRANCH(kind)                                                                               \
    old = pc;                                                                                      \
    exec_simple(r, d, kind, &pc, &carry);                                                          \
    BRANCHED()
    /* after a branch or jump that may go further back than the loops the
     * fast-forward looks at: there all ff_backward_branch() would do is
     * disarm it */
#define BRANCHED_FAR()                                                                             \
    do {                                                                                           \
        if (pc + FF_MAX_BODY <= old) {                                                             \
            if (ff)                                                                                \
                ff_disarm(c);                                                                      \
            NEXT();                                                                                \
        }                                                                                          \
        BRANCHED();                                                                                \
    } while (0)
    /* ... for the kinds of loops longer than the fast-forward looks at */
#define BRANCH_FAR(kind)                                                                           \
    old = pc;                                                                                      \
    exec_simple(r, d, kind, &pc, &carry);                                                          \
    BRANCHED_FAR()

    /* at the first instruction of a straight run (pru_params.straight_run):
     * on as inside the run (rkinds: no checks between its instructions,
     * pc and cycle at its end from the start) if no limit and no LOOP end
     * falls within it or at its end, else to `otherwise` */
#define RUN_ENTER(otherwise)                                                                       \
    do {                                                                                           \
        if (!runs || (uint64_t)(limit - cyc) <= d->run || loop_end - pc - 1u < d->run)             \
            goto otherwise;                                                                        \
        pc += d->run;                                                                              \
        cyc += d->run;                                                                             \
    } while (0)

    /* after JMP or JAL from `old`, each with its own dispatch (a return's
     * next instruction is not a call's): a register target may lie outside
     * IRAM (exec_run() faults); a call of a routine further up (the
     * firmware's delays) is no loop the fast-forward looks at */
#define JUMPED()                                                                                   \
    do {                                                                                           \
        if (pc >= n) {                                                                             \
            cyc++;                                                                                 \
            if (pc == loop_end) /* (a LOOP may end there too) */                                   \
                goto at_loop_end;                                                                  \
            goto out;                                                                              \
        }                                                                                          \
        BRANCHED_FAR();                                                                            \
    } while (0)

    /* a call from far below (what JUMPED() does only disarm for) of a
     * routine with a memo that applies: replayed, the JAL's disarm done,
     * on at the return with the JAL's and the routine's cycles */
#define LEAF_CALL()                                                                                \
    do {                                                                                           \
        if (leaf && pc + FF_MAX_BODY <= old) {                                                     \
            uint32_t routine = leaf_call(c, d, old, pc, &carry, cyc, limit, loop_end);             \
            if (routine) {                                                                         \
                if (ff)                                                                            \
                    ff_disarm(c);                                                                  \
                pc = old + 1;                                                                      \
                cyc += routine;                                                                    \
                NEXT();                                                                            \
            }                                                                                      \
        }                                                                                          \
    } while (0)

top:
    if (pc >= n)
        goto out;
    DISPATCH();

    /* each straight kind: its handler (k_); at the start of a straight run
     * (e_), the run (r_) if it fits */
#define STRAIGHT_HANDLERS(label, kind)                                                             \
    k_##label : STRAIGHT(kind);                                                                    \
    e_##label : RUN_ENTER(k_##label);                                                              \
    r_##label : exec_simple(r, d, kind, &run_pc, &carry);                                          \
    d++;                                                                                           \
    goto *rkinds[d->go];
    PD_STRAIGHT_KINDS(STRAIGHT_HANDLERS)
#undef STRAIGHT_HANDLERS
k_qbgt:
    BRANCH(PRU_OP_QBGT);
k_qbge:
    BRANCH(PRU_OP_QBGE);
k_qblt:
    BRANCH(PRU_OP_QBLT);
k_qble:
    BRANCH(PRU_OP_QBLE);
k_qbeq:
    BRANCH(PRU_OP_QBEQ);
k_qbne:
    BRANCH(PRU_OP_QBNE);
k_qba:
    BRANCH_FAR(PRU_OP_QBA);
k_qbbs:
    BRANCH(PRU_OP_QBBS);
k_qbbc:
    BRANCH(PRU_OP_QBBC);
k_qbne32:
    BRANCH(PD_QBNE32);
k_qbeq32:
    BRANCH(PD_QBEQ32);
k_qbbs32:
    BRANCH(PD_QBBS32);
k_qbbc32:
    BRANCH(PD_QBBC32);
k_qbne32i:
    BRANCH(PD_QBNE32I);
k_qbeq32i:
    BRANCH(PD_QBEQ32I);
k_qbeqi:
    BRANCH_FAR(PD_QBEQI);
k_qbnei:
    BRANCH_FAR(PD_QBNEI);
k_qbbs32i:
    BRANCH(PD_QBBS32I);
k_qbbc32i:
    BRANCH(PD_QBBC32I);
k_qbeqbi:
    BRANCH_FAR(PD_QBEQBI);
k_qbnebi:
    BRANCH_FAR(PD_QBNEBI);
k_qbeqwi:
    BRANCH_FAR(PD_QBEQWI);
k_qbnewi:
    BRANCH_FAR(PD_QBNEWI);
    /* a quick branch forward (PD_FORWARD): nothing for BRANCHED() */
#define FORWARD_HANDLER(label, kind)                                                               \
    f_##label : exec_simple(r, d, kind, &pc, &carry);                                              \
    NEXT();
    PD_QUICK_KINDS(FORWARD_HANDLER)
#undef FORWARD_HANDLER
k_jmp:
    old = pc;
    exec_simple(r, d, PRU_OP_JMP, &pc, &carry);
    JUMPED();
k_jal:
    old = pc;
    exec_simple(r, d, PRU_OP_JAL, &pc, &carry);
    LEAF_CALL();
    JUMPED();
k_jali:
    old = pc;
    exec_simple(r, d, PD_JALI, &pc, &carry);
jali_called:
    LEAF_CALL();
    JUMPED();
e_call_ret: /* PD_PAIR_CALL_RET: the JAL (in IRAM, far back: no JUMPED()
             * but the disarm), and if a JMP there returns, within the
             * limit and meeting no LOOP end at the routine, the JMP too
             * (forward: nothing for BRANCHED()); else as k_jali */
    old = pc;
    pc = d->imm & 0xffffu;
    wr(r, d, old + 1);
    if (runs && pd[pc].go == PRU_OP_JMP && cyc + 1 < limit && pc != loop_end &&
        (op2v(r, &pd[pc]) & 0xffffu) == old + 1) {
        if (ff)
            ff_disarm(c);
        pc = old + 1;
        cyc++;
        NEXT();
    }
    goto jali_called;
k_r31: /* R31 read first; then the instruction's own handler */
    r[31] = gpi_r31(c, cyc);
    goto *kinds[d->inner];
    /* the firmware's pairs (PD_PAIR_*) in a run: the second reads the
     * first's result as computed */
e_min_sub:
    RUN_ENTER(k_minb32i);
r_min_sub : {
    uint32_t a = r[d->rs1];
    uint8_t m = (uint8_t)(a < d->imm ? a : d->imm);
    *rf_byte(r, d->rd, d->rdsh) = m;
    carry = a >= m;
    r[d->rs1] = a - m;
    d += 2;
    goto *rkinds[d->go];
}
e_lsl_xor:
    RUN_ENTER(k_lsl32i);
r_lsl_xor : {
    uint32_t v = r[d->rs1] << (d->imm & 31u);
    r[d->rd] = v;
    r[d[1].rd] = v ^ op2w(r, &d[1]); /* op2 after the first's write */
    d += 2;
    goto *rkinds[d->go];
}
e_add_adc2:
    RUN_ENTER(k_add32);
r_add_adc2 : { /* each in turn, the carry passed on */
    uint32_t a = r[d->rs1], s = a + op2v(r, d);
    r[d->rd] = s;
    uint64_t t = (uint64_t)r[d[1].rs1] + op2w(r, &d[1]) + (s < a);
    r[d[1].rd] = (uint32_t)t;
    uint64_t u = (uint64_t)r[d[2].rs1] + op2w(r, &d[2]) + (t >> 32);
    r[d[2].rd] = (uint32_t)u;
    carry = (int)(u >> 32);
    d += 3;
    goto *rkinds[d->go];
}
r_xor_qbbs : { /* the run's last; the branch at pc, in its cycle */
    uint32_t v = r[d->rs1] ^ op2w(r, d);
    r[d->rd] = v;
    d++;
    pc = (v >> (d->imm & 31u)) & 1u ? d->target : pc + 1;
    NEXT();
}
e_r31: /* an R31 read (k_r31), the first of a straight run */
    RUN_ENTER(k_r31);
r_r31: /* ... or in a run: cyc is d->run cycles on, at the run's end */
    r[31] = gpi_r31(c, cyc - d->run);
    goto *rkinds[d->inner];

k_r30: /* as exec_one(): the pins see the new R30 at the end of its cycle */
    exec_simple(r, d, d->kind, &pc, &carry);
    goto r30_written;
k_r30_xor:
    exec_simple(r, d, PRU_OP_XOR, &pc, &carry);
    goto r30_written;
k_r30_xorb: /* a byte of R30 flipped by a byte mask (read as the byte it is) */
    r[30] ^= op2_byte(r, d) << d->rdsh;
    pc++;
r30_written:
    if (r[30] != c->r30_pins) {
        SYNC_OUT();
        exec_r30_changed(c, cyc + 1);
        SYNC_IN();
        if (c->stop) { /* a pin callback stopped the core */
            cyc++;
            if (pc == loop_end) {
                SYNC_OUT();
                loop_back(c);
                SYNC_IN();
            }
            goto out;
        }
    }
    NEXT();

k_mvi_ld:
    if (!mvi_load(c, r, d, cyc))
        goto k_general;
    pc++;
    NEXT();
k_xfr_fixed : {
    int stall = exec_xfr_fixed(c, d, cyc);
    if (stall < 0)
        goto k_general;
    pc++;
    cyc += 1 + stall;
    ins_less -= (unsigned)stall;
    c->stall_total += stall;
    if (pc == loop_end)
        goto at_loop_end;
    DISPATCH();
}

at_loop_end:
    SYNC_OUT();
    loop_back(c);
    SYNC_IN();
    goto top;

k_xpru: /* a PRU of a PRU-ICSS: a cross-PRU event (predecode.c) */
    if (xpru_blocks(c, cyc, d->xfast))
        goto xblocked;
    goto *kinds[d->xfast];

k_slow:
    if (d->burst_bytes && (d->flags & PD_EFFECTS) == 0) {
        /* a fixed-length burst without R31 or pin effects: what
         * exec_one() does, without its checks, for speed */
        unsigned cost = exec_burst(c, d, pc, cyc);
        if (c->stop) {
            /* a fault, or a store to a control register (which may have
             * reset the core): finish as exec_one() does, on the core */
            if (c->fault.cause != PRU_FAULT_NONE)
                goto out;
            c->carry = carry;
            c->insns = (uint64_t)cyc + ins_less;
            c->pc++;
            c->cycle += cost;
            c->stall_total += cost - 1;
            c->insns++;
            if (c->pc == c->loop_end)
                loop_back(c);
            SYNC_IN();
            goto out;
        }
        pc++;
        cyc += cost;
        ins_less -= cost - 1;
        c->stall_total += cost - 1;
        if (pc == loop_end)
            goto at_loop_end;
        goto top;
    }
k_general:
    SYNC_OUT();
    exec_one(c, d, limit);
    SYNC_IN();
    if (c->stop)
        goto out;
    goto top;

xblocked: /* in front of a cross-PRU event the other PRU has not reached */
    c->stop = true;
    c->stop_reason = PRU_STOP_LIMIT;
out:
    SYNC_OUT();
#undef SYNC_OUT
#undef SYNC_IN
#undef DISPATCH
#undef NEXT
#undef BRANCHED
#undef STRAIGHT
#undef BRANCH
#undef BRANCH_FAR
#undef BRANCHED_FAR
#undef JUMPED
#undef LEAF_CALL
#undef RUN_ENTER
}

enum pru_stop exec_run(struct pru_core *c, int64_t limit, bool one_step) {
    c->stop = false;
    c->recheck = false;
    if (c->fault.cause != PRU_FAULT_NONE)
        return PRU_STOP_FAULT;
    c->ff.top = NO_LOOP; /* inputs may have changed between runs */
    c->ff.have_snap = false;
    bool unbounded = limit >= PRU_MAX_CYCLE; /* "until HALT": time stays put when idle */
    if (unbounded)
        limit = PRU_MAX_CYCLE;
    /* run-ahead (pruss.c): idle time and the general path go no further
     * than the other PRU (a wake-up, an enable, any instruction there may
     * be a cross-PRU event); CYCLE_NEVER otherwise */
    int64_t xlim = limit < c->xlimit ? limit : c->xlimit;
    for (;;) {
        if (!enabled(c)) {
            if (!unbounded && c->cycle < xlim && !one_step)
                c->cycle = xlim;
            return c->halted ? PRU_STOP_HALT : PRU_STOP_DISABLED;
        }
        if (c->sleeping) {
            if (!sleep_until(c, one_step ? c->cycle + 1 : xlim))
                return one_step ? PRU_STOP_STEP : PRU_STOP_LIMIT;
        }
        if (c->cycle >= limit)
            return PRU_STOP_LIMIT;
        if (c->pc >= c->iram_words) {
            core_fault(c, PRU_FAULT_PC_RANGE, c->pc);
            return PRU_STOP_FAULT;
        }
        bool stepping = one_step || (c->ctrl.control & PRU_CTRL_SINGLE_STEP);
        if (c->trace_on || stepping || c->checked || !c->p.fast_loop) {
            const struct pd *d = &c->pd[c->pc];
            if (c->cycle >= xlim)
                return PRU_STOP_LIMIT;
            if (c->checked)
                exec_checked(c, d, xlim);
            else if (c->trace_on)
                exec_traced(c, d, xlim);
            else
                exec_one(c, d, xlim);
        } else {
            run_fast(c, limit);
        }
        if (c->stop) {
            if (!c->recheck)
                return c->stop_reason;
            c->stop = false;
            c->recheck = false;
        }
        if (stepping && enabled(c)) {
            if (c->ctrl.control & PRU_CTRL_SINGLE_STEP) {
                c->ctrl.control &= ~PRU_CTRL_ENABLE;
                ctrl_counting_update(c, c->cycle);
            }
            return PRU_STOP_STEP;
        }
    }
}
