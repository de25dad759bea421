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
 * - ff_counted: a poll with a time-out counts a register or a field of one
 *   (the firmware's FE_POLL: r1.w2) down (or up) by a constant and closes
 *   the loop with QBNE on it. When the body (decoded from IRAM) uses that
 *   register nowhere else, iterations differ only in the field, so they
 *   are skipped up to the one before the counter would end the loop (or
 *   wrap at the field's width), with the counter advanced by as many
 *   steps. The same for a register counted down and tested by QBBC on
 *   its bit 31 (the firmware's IEP_POLL: until the count goes below 0).
 * - ff_r31_bits: when the body looks at R31 only through QBBS/QBBC, the
 *   horizon of its R31 reads covers only the bits it tests, so e.g. the
 *   Cnt_16 pulses of a shift-mode input do not cut the skip short.
 * And a third kind of skip (ff_loop_delay): a LOOP over one instruction
 * that changes nothing (AND/OR of a register with itself, pasm's
 * "mov rN, rN") is a delay of one cycle an iteration, run at once.
 * And a fourth (ff_count_loop): a delay written without LOOP, a backward
 * QBNE on a counter field against 0 whose body only steps that counter
 * down by one SUB of a constant and otherwise does what gives the same
 * result every turn (pads), runs its turns at once (the last with them
 * when the counter ends on 0 exactly).
 */
#include "core_priv.h"
#include "pru_isa.h"

#include <string.h>

/* ---- the loop body, decoded ---- */

/* Register operands an instruction of the formats a poll uses reads. */
static bool reads_reg(const struct pru_insn *in, unsigned r) {
    enum pru_fmt f = pru_optable[in->op].fmt;
    if (f != PRU_FMT_ALU && f != PRU_FMT_QB && f != PRU_FMT_QBB)
        return false;
    return in->rs1 == r || (!in->io && in->rs2 == r);
}

/* The kinds of instruction the analyses below look into. */
static bool poll_kind(const struct pru_insn *in) {
    enum pru_fmt f = pru_optable[in->op].fmt;
    return f == PRU_FMT_ALU || f == PRU_FMT_LDI || f == PRU_FMT_QB || f == PRU_FMT_QBA ||
           f == PRU_FMT_QBB;
}

/* The bits of a register that an operand field selects. */
static uint32_t field_bits(unsigned sel) {
    static const uint32_t bits[8] = {0xffu,   0xff00u,   0xff0000u,   0xff000000u,
                                     0xffffu, 0xffff00u, 0xffff0000u, 0xffffffffu};
    return bits[sel & 7u];
}

/* The R31 bits the body looks at: the bit of QBBS/QBBC r31, n (immediate
 * bit), the field of any other operand that reads R31 (e.g. and rX,
 * r31.b0, mask); everything if an instruction is of a kind not looked
 * into. */
static uint32_t r31_mask(const struct pru_insn *in, uint32_t n) {
    uint32_t mask = 0;
    for (uint32_t i = 0; i < n; i++) {
        const struct pru_insn *a = &in[i];
        if (!poll_kind(a))
            return ~0u;
        enum pru_fmt f = pru_optable[a->op].fmt;
        if (f == PRU_FMT_QBB && a->rs1 == 31 && a->io) {
            /* the bit counts from the field's lowest; one past the field:
             * the whole field, to be safe */
            uint32_t fb = field_bits(a->rs1sel);
            uint32_t bit = (a->imm & 31u) + (uint32_t)__builtin_ctz(fb);
            mask |= bit < 32 && (fb >> bit & 1u) ? 1u << bit : fb;
            continue;
        }
        if (!reads_reg(a, 31))
            continue;
        if (a->rs1 == 31)
            mask |= field_bits(a->rs1sel);
        if (!a->io && a->rs2 == 31)
            mask |= field_bits(a->rs2sel);
    }
    return mask;
}

/* The largest value of a field (its bits shifted down). */
static uint32_t field_max(unsigned sel) {
    uint32_t bits = field_bits(sel);
    return bits >> __builtin_ctz(bits);
}

/* A counted poll (see the top): the closing branch in[n-1] is QBNE top,
 * x.f, imm, or QBBC top, x, 31 (x whole: until x goes below 0); one
 * ADD/SUB x.f, x.f, imm steps the field (x.f the same field throughout:
 * x, or x.w2 and so on; for QBBC a SUB); no other instruction reads or
 * writes register x, and every one is of a kind a poll uses. Sets
 * b->counter (x, or -1 if the body is no such loop), b->sel, b->step and
 * b->end or b->sign_end. */
static void counted(struct ff_body *b, const struct pru_insn *in, uint32_t n) {
    b->counter = -1;
    const struct pru_insn *br = &in[n - 1];
    bool sign = br->op == PRU_OP_QBBC && br->io && br->imm == 31 && br->rs1sel == 7;
    if ((br->op != PRU_OP_QBNE && !sign) || !br->io || br->rs1 > 30)
        return;
    unsigned x = br->rs1, sel = br->rs1sel;
    int updates = 0;
    for (uint32_t i = 0; i + 1 < n; i++) {
        const struct pru_insn *a = &in[i];
        enum pru_fmt f = pru_optable[a->op].fmt;
        if (!poll_kind(a))
            return;
        if ((f == PRU_FMT_ALU || f == PRU_FMT_LDI) && a->rd == x) {
            if ((a->op != PRU_OP_ADD && a->op != PRU_OP_SUB) || a->rdsel != sel || a->rs1 != x ||
                a->rs1sel != sel || !a->io || a->imm == 0 || a->imm > field_max(sel))
                return;
            b->step = (a->op == PRU_OP_SUB ? 0u - a->imm : a->imm) & field_max(sel);
            updates++;
        } else if (reads_reg(a, x)) {
            return;
        }
    }
    if (updates == 1 && sign && b->step <= 0x80000000u)
        return; /* counted up: bit 31 sets at the wrap, not below 0 */
    if (updates == 1 && (sign || br->imm <= field_max(sel))) {
        b->counter = (int)x;
        b->sel = (uint8_t)sel;
        b->end = sign ? 0 : br->imm;
        b->sign_end = sign;
    }
}

/* The instructions that write the carry (docs/pru-facts.md §1.3) ... */
static bool writes_carry(unsigned op) {
    return op == PRU_OP_ADD || op == PRU_OP_ADC || op == PRU_OP_SUB || op == PRU_OP_SUC ||
           op == PRU_OP_RSB || op == PRU_OP_RSC;
}

/* ... and those that read it. */
static bool reads_carry(unsigned op) {
    return op == PRU_OP_ADC || op == PRU_OP_SUC || op == PRU_OP_RSC;
}

/* A count loop (see the top): the closing branch in[n-1] is QBNE top,
 * x.f, 0; one SUB x.f, x.f, k (k > 0) steps it; every other instruction is
 * an ALU one or LDI (one cycle, registers only: no branch, no R31 read, no
 * R30/R31 write), neither reads nor writes the carry, and reads nothing
 * the body writes (counter included) unless it writes a field back to
 * itself (a pad). Then every turn gives the other registers the same
 * values, so only the counter, time and the carry differ from turn to
 * turn. Sets b->cl_reg (-1 if the body is no such loop), cl_sel, cl_step. */
static void count_loop(struct ff_body *b, const struct pru_insn *in, uint32_t n) {
    b->cl_reg = -1;
    const struct pru_insn *br = &in[n - 1];
    if (br->op != PRU_OP_QBNE || !br->io || br->imm != 0 || br->rs1 > 29)
        return;
    uint32_t written[32] = {0};
    int sub = -1;
    for (uint32_t i = 0; i + 1 < n; i++) {
        const struct pru_insn *a = &in[i];
        enum pru_fmt f = pru_optable[a->op].fmt;
        if ((f != PRU_FMT_ALU && f != PRU_FMT_LDI) || !pru_op_register_only(a->op))
            return;
        if (insn_is_identity(a))
            continue;
        if (a->rd > 29)
            return;
        if (a->op == PRU_OP_SUB && a->rd == br->rs1 && a->rdsel == br->rs1sel)
            sub = sub < 0 ? (int)i : -2; /* the counter's step; two: none */
        written[a->rd] |= field_bits(a->rdsel);
    }
    if (sub < 0)
        return;
    const struct pru_insn *s = &in[sub];
    if (s->rs1 != s->rd || s->rs1sel != s->rdsel || !s->io || s->imm == 0)
        return;
    uint32_t cmask = field_bits(br->rs1sel);
    if (written[br->rs1] != cmask)
        return; /* another instruction writes part of the counter's register */
    for (uint32_t i = 0; i + 1 < n; i++) {
        const struct pru_insn *a = &in[i];
        if ((int)i == sub || insn_is_identity(a))
            continue;
        if (writes_carry(a->op) || reads_carry(a->op))
            return;
        if (pru_optable[a->op].fmt == PRU_FMT_LDI)
            continue;
        if (a->rs1 == 31 || (written[a->rs1] & field_bits(a->rs1sel)))
            return;
        if (!a->io && (a->rs2 == 31 || (written[a->rs2] & field_bits(a->rs2sel))))
            return;
    }
    b->cl_reg = br->rs1;
    b->cl_sel = br->rs1sel;
    b->cl_step = s->imm;
}

/* The body [top, pc] decoded and analysed into cache entry b; NULL if it
 * does not decode. */
static __attribute__((noinline)) const struct ff_body *
body_decode(struct pru_core *c, struct ff_body *b, uint32_t top, uint32_t pc) {
    uint32_t n = pc - top + 1;
    c->ff_decoded++;
    const uint32_t *w = &c->iram0[top];
    struct pru_insn in[FF_MAX_BODY];
    for (uint32_t i = 0; i < n; i++) {
        if (pru_decode(w[i], &in[i]) != 0) {
            b->top = 1;
            b->pc = 0; /* none */
            return NULL;
        }
    }
    b->iram_gen = c->iram_gen;
    b->top = top;
    b->pc = pc;
    b->r31_mask = r31_mask(in, n);
    counted(b, in, n);
    count_loop(b, in, n);
    return b;
}

/* Whether cache entry b holds the body [top, pc] of IRAM as it is. */
static inline bool body_is(const struct pru_core *c, const struct ff_body *b, uint32_t top,
                           uint32_t pc) {
    return b->top == top && b->pc == pc && b->iram_gen == c->iram_gen;
}

/* The body [top, pc] analysed, from the cache while IRAM is unchanged (in
 * line: the decoding's stack frame costs more than the look-up); NULL if
 * it does not decode. Any entry holds any body, the oldest replaced: the
 * firmware's loops lie at tops that share their low bits (its period loop
 * and SL poll at 10 MHz at 623 and 727, its delay turns and polls at
 * 1 MHz at 258, 366 and 742), and with one entry by the top modulo 8 they
 * took each other's place, decoded again every frame. */
static inline const struct ff_body *body(struct pru_core *c, uint32_t top, uint32_t pc) {
    if (pc >= c->iram_words || pc - top + 1 > FF_MAX_BODY)
        return NULL;
    if (body_is(c, &c->ff.body[c->ff_body_last], top, pc)) /* the same loop again */
        return &c->ff.body[c->ff_body_last];
    for (unsigned i = 0; i < FF_BODIES; i++) {
        if (body_is(c, &c->ff.body[i], top, pc)) {
            c->ff_body_last = i;
            return &c->ff.body[i];
        }
    }
    c->ff_body_last = c->ff_body_next++ % FF_BODIES;
    return body_decode(c, &c->ff.body[c->ff_body_last], top, pc);
}

/* Iterations a counted poll (body b, NULL if none) may still skip:
 * register x changed from `old` this iteration. Only the counter's field
 * may have changed, by the body's step; the values after the next n steps
 * must all differ from the end value and not wrap at the field's width,
 * nor may this iteration's step have wrapped (the carry of ADD/SUB, bit
 * W of the wide result, stays what it left). -1 if the loop is no counted
 * poll with this counter and step. *step is the field's step. */
static int64_t counted_room(struct pru_core *c, const struct ff_body *b, int x, uint32_t old,
                            uint32_t *step) {
    if (!b || b->counter != x)
        return -1;
    uint32_t bits = field_bits(b->sel), max = field_max(b->sel);
    unsigned sh = (unsigned)__builtin_ctz(bits);
    uint32_t v = (c->r[x] & bits) >> sh, before = (old & bits) >> sh;
    if (((c->r[x] ^ old) & ~bits) != 0 || ((v - before) & max) != b->step)
        return -1;
    *step = b->step;
    bool down = b->step > max / 2;
    uint32_t k = down ? (0u - b->step) & max : b->step;
    if (down ? before < k : before > max - k)
        return -1;
    if (b->sign_end) /* down (counted()): the next n values stay at 0 or above */
        return (int64_t)(v / k);
    if (down) {
        uint32_t lo = b->end < v ? b->end + 1 : 0;
        return (int64_t)((v - lo) / k);
    }
    uint32_t hi = b->end > v ? b->end - 1 : max;
    return (int64_t)((hi - v) / k);
}

/* The one register (r0..r30) that differs from the snapshot, or -1;
 * called when at least one does: the first one found, the rest compared
 * in one memcmp() (the counter of a poll is one of the first registers). */
static int one_changed(const struct pru_core *c) {
    unsigned x = 0;
    while (c->r[x] == c->ff.regs[x])
        x++;
    size_t rest = (30u - x) * sizeof c->r[0];
    return memcmp(&c->r[x + 1], &c->ff.regs[x + 1], rest) == 0 ? (int)x : -1;
}

/* A probe snapshot is taken only when the last iteration read an input
 * (pure countdown loops never pay for it) and no backoff is pending. */
static void arm(struct pru_core *c, const struct ff_body *b, uint32_t top, int64_t now,
                uint64_t insns) {
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
    f->r31_mask = c->p.ff_r31_bits && b ? b->r31_mask : ~0u;
}

/* Iterations that may still be skipped when this one repeats the last,
 * or -1 if it does not: unlimited with the same registers, a counter's
 * room in a counted poll. *x is the counter (-1 none), *step its step. */
static int64_t repeat_room(struct pru_core *c, const struct ff_body *b, int *x, uint32_t *step) {
    const struct ff_probe *f = &c->ff;
    *x = -1;
    if (!f->have_snap || f->dirty || f->carry != c->carry)
        return -1;
    if (memcmp(f->regs, c->r, 31 * sizeof c->r[0]) == 0)
        return INT64_MAX;
    if (!c->p.ff_counted || (*x = one_changed(c)) < 0)
        return -1;
    return counted_room(c, b, *x, f->regs[*x], step);
}

/* A count loop's branch from pc back to top was taken, before its cycle
 * is counted: runs the turns after this one at once, up to `limit` (which
 * the caller has already bounded by every event that may be observed). A
 * turn takes one cycle an instruction and leaves the counter 1..k above 0
 * while it goes on, with no borrow: carry 1. When the counter ends on 0
 * exactly and the limit allows, the last turn runs too (counter 0, no
 * borrow: carry 1) and the core goes on after the loop (c->pc = pc + 1);
 * otherwise the last turn and its exit are left to the core. Returns false
 * if the body is no count loop. */
static bool count_loop_skip(struct pru_core *c, const struct ff_body *b, uint32_t pc, uint32_t top,
                            int64_t limit) {
    if (c->loop_end >= top && c->loop_end <= pc)
        return false; /* a LOOP ends inside: its turns are not alike */
    if (!b || b->cl_reg < 0)
        return false;
    uint32_t mask = field_bits(b->cl_sel);
    unsigned sh = (unsigned)__builtin_ctz(mask);
    uint32_t v = (c->r[b->cl_reg] & mask) >> sh; /* > 0: the branch was taken */
    int64_t len = (int64_t)(pc - top + 1);
    int64_t now = c->cycle + 1; /* the branch itself takes one cycle */
    int64_t n = v ? (int64_t)((v - 1) / b->cl_step) : 0;
    int64_t room = limit > now ? (limit - now) / len : 0;
    if (v && v % b->cl_step == 0 && room > n) {
        /* every turn to the end: the counter ends on 0 */
        n++;
        c->r[b->cl_reg] &= ~mask;
        c->carry = 1;
        c->cycle += n * len;
        c->insns += (uint64_t)(n * len);
        c->ff.skipped += (uint64_t)n;
        c->pc = pc + 1;
        return true;
    }
    if (room < n)
        n = room;
    if (n > 0) {
        v -= (uint32_t)n * b->cl_step;
        c->r[b->cl_reg] = (c->r[b->cl_reg] & ~mask) | v << sh;
        c->carry = 1;
        c->cycle += n * len;
        c->insns += (uint64_t)(n * len);
        c->ff.skipped += (uint64_t)n;
    }
    return true;
}

/* Called by a taken branch from pc back to top, before its cycle is counted. */
void ff_backward_branch(struct pru_core *c, uint32_t pc, uint32_t top, int64_t limit) {
    struct ff_probe *f = &c->ff;
    int64_t now = c->cycle + 1; /* the branch itself takes one cycle */
    uint64_t insns = c->insns + 1;

    if (pc - top >= FF_MAX_BODY) {
        ff_disarm(c);
        return;
    }
    /* the body, looked up once for the analyses below */
    const struct ff_body *b = body(c, top, pc);
    if (c->p.ff_count_loop && count_loop_skip(c, b, pc, top, limit)) {
        /* unarmed, so that the next arrival here (the next call of the
         * delay) comes back through this function, not the in-line one */
        ff_disarm(c);
        return;
    }
    int x = -1;
    uint32_t step = 0;
    int64_t room = f->top == top && f->have_snap ? repeat_room(c, b, &x, &step) : -2;
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
            if (x >= 0) {
                /* the field's n steps, the rest of the register as it is */
                uint32_t bits = field_bits(b->sel);
                unsigned sh = (unsigned)__builtin_ctz(bits);
                uint32_t v = ((c->r[x] & bits) >> sh) + (uint32_t)n * step;
                c->r[x] = (c->r[x] & ~bits) | ((v << sh) & bits);
            }
            f->skipped += (uint64_t)n;
            now += n * len;
            insns += di;
        }
        f->saw_input = true; /* the same reads: keep probing */
    }
    arm(c, b, top, now, insns);
}

/* A delay: AND/OR of a field (not of R30/R31) with itself into it. */
static bool is_delay(const struct pd *d) {
    /* the word as predecoded (kept up to date with IRAM) */
    return d->kind != PD_BAD && insn_is_identity(&d->in) && d->in.rd < 30;
}

void ff_loop_entered(struct pru_core *c, int64_t limit) {
    if (!c->p.ff_loop_delay || c->loop_end != c->loop_top + 1 || c->pc != c->loop_top ||
        c->loop_top >= c->iram_words || !is_delay(&c->pd[c->loop_top]))
        return;
    /* the LOOP instruction's own cycle is counted after this */
    int64_t room = limit - (c->cycle + 1);
    if (room <= 0)
        return;
    int64_t n = room < (int64_t)c->loop_count ? room : (int64_t)c->loop_count;
    c->cycle += n;
    c->insns += (uint64_t)n;
    c->ff.skipped += (uint64_t)n;
    c->loop_count -= (uint32_t)n;
    if (c->loop_count == 0) {
        c->pc = c->loop_end;
        c->loop_end = NO_LOOP;
    }
}
