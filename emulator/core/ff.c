/*
 * ff.c - fast-forward of idle polling loops.
 *
 * When a backward branch reaches a loop top, the core arms a probe: it
 * saves the registers and carry, and while the next iteration runs every
 * input read (R31, IEP, INTC, CFG, CTRL) lowers a horizon: the first cycle
 * at which that read could return something else. If the iteration comes
 * back to the same top with identical registers and no side effect (store,
 * R30 change, R31 event, XOUT, LOOP, peripheral write), every later
 * iteration repeats it exactly until the horizon, so whole iterations are
 * skipped: cycles, instructions and STALL advance as if they had run.
 *
 * Two refinements, each with its own switch (pru_params):
 * - ff_counted: a poll with a time-out counts a register down (or up) by a
 *   constant and closes the loop with QBNE on it. When the body (decoded
 *   from IRAM) uses that register nowhere else, iterations differ only in
 *   it, so they are skipped up to the one before the counter would end the
 *   loop (or wrap), with the counter advanced by as many steps.
 * - ff_r31_bits: when the body looks at R31 only through QBBS/QBBC, the
 *   horizon of its R31 reads covers only the bits it tests, so e.g. the
 *   Cnt_16 pulses of a shift-mode input do not cut the skip short.
 */
#include "core_priv.h"
#include "pru_isa.h"

#include <string.h>

#define FF_MAX_BODY 16u /* words; longer loops are not idle polls */

/* ---- the loop body, decoded ---- */

static bool body_insn(const struct pru_core *c, uint32_t pc, struct pru_insn *in) {
    return pc < c->iram_words && pru_decode(c->iram0[pc], in) == 0;
}

static bool is_alu(const struct pru_insn *in) {
    return pru_optable[in->op].fmt == PRU_FMT_ALU;
}

/* Register operands an instruction of the formats a poll uses reads. */
static bool reads_reg(const struct pru_insn *in, unsigned r) {
    enum pru_fmt f = pru_optable[in->op].fmt;
    if (f != PRU_FMT_ALU && f != PRU_FMT_QB && f != PRU_FMT_QBB)
        return false;
    return in->rs1 == r || (!in->io && in->rs2 == r);
}

/* The R31 bits the body [top, pc] looks at: the bits of QBBS/QBBC r31, n
 * (whole register, immediate bit), everything if R31 is read otherwise or
 * an instruction is of a kind not looked into. */
static uint32_t body_r31_mask(const struct pru_core *c, uint32_t top, uint32_t pc) {
    uint32_t mask = 0;
    for (uint32_t a = top; a <= pc; a++) {
        struct pru_insn in;
        if (!body_insn(c, a, &in))
            return ~0u;
        enum pru_fmt f = pru_optable[in.op].fmt;
        if (f == PRU_FMT_QBB && in.rs1 == 31 && in.rs1sel == PRU_SEL_R && in.io)
            mask |= 1u << (in.imm & 31u);
        else if (f == PRU_FMT_QBB || f == PRU_FMT_QB || f == PRU_FMT_ALU) {
            if (reads_reg(&in, 31))
                return ~0u;
        } else if (f != PRU_FMT_LDI && f != PRU_FMT_QBA)
            return ~0u;
    }
    return mask;
}

/* A counted poll (see the top): register x changes by `step` per iteration
 * through one ADD/SUB x, x, imm, and the closing branch at pc is QBNE
 * top, x, imm; no other instruction reads or writes x, and every one is of
 * a kind a poll uses (ALU, LDI, QB*, QBB*). Returns how many more
 * iterations keep the counter off the end value and without carry, or -1
 * if the body is not such a loop. */
static int64_t counted_room(const struct pru_core *c, uint32_t top, uint32_t pc, unsigned x,
                            uint32_t step) {
    struct pru_insn in;
    if (!body_insn(c, pc, &in) || in.op != PRU_OP_QBNE || in.rs1 != x || in.rs1sel != PRU_SEL_R ||
        !in.io)
        return -1;
    uint32_t end = in.imm;
    int updates = 0;
    bool down = false;
    for (uint32_t a = top; a < pc; a++) {
        if (!body_insn(c, a, &in))
            return -1;
        enum pru_fmt f = pru_optable[in.op].fmt;
        bool writes = (is_alu(&in) || f == PRU_FMT_LDI) && in.rd == x;
        if (writes) {
            if ((in.op != PRU_OP_ADD && in.op != PRU_OP_SUB) || in.rdsel != PRU_SEL_R ||
                in.rs1 != x || in.rs1sel != PRU_SEL_R || !in.io || in.imm == 0)
                return -1;
            down = in.op == PRU_OP_SUB;
            if (step != (down ? 0u - in.imm : in.imm))
                return -1; /* not one update per iteration */
            updates++;
        } else if (reads_reg(&in, x) || (f != PRU_FMT_ALU && f != PRU_FMT_LDI && f != PRU_FMT_QB &&
                                         f != PRU_FMT_QBA && f != PRU_FMT_QBB)) {
            return -1;
        }
    }
    /* the iteration seen must not have wrapped either (its carry) */
    uint32_t k = down ? 0u - step : step;
    uint32_t before = c->r[x] - step;
    if (updates != 1 || (down ? before < k : before > 0xffffffffu - k))
        return -1;
    /* the values after the next n updates must all differ from `end` and
     * not wrap (the carry of ADD/SUB stays what this iteration left) */
    uint32_t v = c->r[x];
    if (down) {
        uint32_t lo = end < v ? end + 1 : 0;
        return (int64_t)((v - lo) / k);
    }
    uint32_t hi = end > v ? end - 1 : 0xffffffffu;
    return (int64_t)((hi - v) / k);
}

/* The one register (r0..r30) that differs from the snapshot, or -1. */
static int one_changed(const struct pru_core *c) {
    int x = -1;
    for (unsigned i = 0; i < 31; i++) {
        if (c->r[i] != c->ff.regs[i]) {
            if (x >= 0)
                return -1;
            x = (int)i;
        }
    }
    return x;
}

/* A probe snapshot is taken only when the last iteration read an input
 * (pure countdown loops never pay for it) and no backoff is pending. */
static void arm(struct pru_core *c, uint32_t top, uint32_t pc, int64_t now, uint64_t insns) {
    struct ff_probe *f = &c->ff;
    if (f->top != top)
        f->fails = f->backoff = 0;
    bool snap = f->top == top && f->saw_input && f->backoff == 0;
    if (f->backoff)
        f->backoff--;
    f->top = top;
    f->saw_input = false;
    f->have_snap = snap;
    f->dirty = false;
    if (!snap)
        return;
    f->cycle0 = now;
    f->insn0 = insns;
    f->stall0 = c->stall_total;
    f->horizon = CYCLE_NEVER;
    memcpy(f->regs, c->r, sizeof f->regs);
    f->carry = c->carry;
    f->r31_mask = c->p.ff_r31_bits ? body_r31_mask(c, top, pc) : ~0u;
}

/* Iterations that may still be skipped when this one repeats the last,
 * or -1 if it does not: unlimited with the same registers, a counter's
 * room in a counted poll. *x is the counter (-1 none), *step its step. */
static int64_t repeat_room(const struct pru_core *c, uint32_t top, uint32_t pc, int *x,
                           uint32_t *step) {
    const struct ff_probe *f = &c->ff;
    *x = -1;
    if (!f->have_snap || f->dirty || f->carry != c->carry)
        return -1;
    if (memcmp(f->regs, c->r, 31 * sizeof c->r[0]) == 0)
        return INT64_MAX;
    if (!c->p.ff_counted || (*x = one_changed(c)) < 0)
        return -1;
    *step = c->r[*x] - f->regs[*x];
    return counted_room(c, top, pc, (unsigned)*x, *step);
}

/* Called by a taken branch from pc back to top, before its cycle is counted. */
void ff_backward_branch(struct pru_core *c, uint32_t pc, uint32_t top, int64_t limit) {
    struct ff_probe *f = &c->ff;
    int64_t now = c->cycle + 1; /* the branch itself takes one cycle */
    uint64_t insns = c->insns + 1;

    if (pc - top >= FF_MAX_BODY) {
        f->top = NO_LOOP;
        f->have_snap = false;
        f->r31_mask = ~0u;
        return;
    }
    int x = -1;
    uint32_t step = 0;
    int64_t room = f->top == top && f->have_snap ? repeat_room(c, top, pc, &x, &step) : -2;
    if (room == -1) {
        /* a busy loop, not an idle one: probe it less and less often */
        f->fails = f->fails < 10 ? f->fails + 1 : 10;
        f->backoff = 1u << f->fails;
    } else if (room >= 0) {
        f->fails = 0;
        int64_t len = now - f->cycle0;
        int64_t n = (limit - now) / len;
        if (f->horizon != CYCLE_NEVER) {
            int64_t hn = (f->horizon - f->cycle0) / len - 1;
            if (hn < n)
                n = hn;
        }
        if (room < n)
            n = room;
        if (n > 0) {
            uint64_t di = (uint64_t)n * (insns - f->insn0);
            c->cycle += n * len;
            c->insns += di;
            c->stall_total += n * (c->stall_total - f->stall0);
            if (x >= 0)
                c->r[x] += (uint32_t)n * step;
            f->skipped += (uint64_t)n;
            now += n * len;
            insns += di;
        }
        f->saw_input = true; /* the same reads: keep probing */
    }
    arm(c, top, pc, now, insns);
}
