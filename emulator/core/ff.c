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
 */
#include "core_priv.h"

#include <string.h>

#define FF_MAX_BODY 16u /* words; longer loops are not idle polls */

/* A probe snapshot is taken only when the last iteration read an input
 * (pure countdown loops never pay for it) and no backoff is pending. */
static void arm(struct pru_core *c, uint32_t top, int64_t now, uint64_t insns) {
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
}

static bool same_state(const struct pru_core *c) {
    const struct ff_probe *f = &c->ff;
    return f->have_snap && !f->dirty && f->carry == c->carry &&
           memcmp(f->regs, c->r, 31 * sizeof c->r[0]) == 0;
}

/* Called by a taken branch from pc back to top, before its cycle is counted. */
void ff_backward_branch(struct pru_core *c, uint32_t pc, uint32_t top, int64_t limit) {
    struct ff_probe *f = &c->ff;
    int64_t now = c->cycle + 1; /* the branch itself takes one cycle */
    uint64_t insns = c->insns + 1;

    if (pc - top >= FF_MAX_BODY) {
        f->top = NO_LOOP;
        f->have_snap = false;
        return;
    }
    if (f->top == top && f->have_snap && !same_state(c)) {
        /* a busy loop, not an idle one: probe it less and less often */
        f->fails = f->fails < 10 ? f->fails + 1 : 10;
        f->backoff = 1u << f->fails;
    } else if (f->top == top && same_state(c)) {
        f->fails = 0;
        int64_t len = now - f->cycle0;
        int64_t n = (limit - now) / len;
        if (f->horizon != CYCLE_NEVER) {
            int64_t hn = (f->horizon - f->cycle0) / len - 1;
            if (hn < n)
                n = hn;
        }
        if (n > 0) {
            uint64_t di = (uint64_t)n * (insns - f->insn0);
            c->cycle += n * len;
            c->insns += di;
            c->stall_total += n * (c->stall_total - f->stall0);
            f->skipped += (uint64_t)n;
            now += n * len;
            insns += di;
        }
        f->saw_input = true; /* the same reads: keep probing */
    }
    arm(c, top, now, insns);
}
