/*
 * leaf.h - a leaf call's replay, in line in the fast loop (exec.c); the
 * recording is in leaf.c.
 */
#ifndef PRU_LEAF_H
#define PRU_LEAF_H

#include "exec_priv.h"

/* A memo's key: the routine and the call's link field. */
static inline uint64_t leaf_key(const struct pd *jal, uint32_t target) {
    return target | (uint64_t)jal->rd << 16 | (uint64_t)jal->rdsh << 24 |
           (uint64_t)jal->rdmask << 32;
}

/* leaf.c: a new record of the call into m (true if accepted: then it
 * applies to the registers as they are); the inputs and outputs past the
 * first two (m->more). Out of line: rare, or past the common case. */
__attribute__((noinline)) bool leaf_learn(struct pru_core *c, struct leaf_memo *m,
                                          const struct pd *jal, uint32_t jal_pc, uint32_t target,
                                          int carry);
/* leaf.c: memo m, accepted, does not apply to these inputs: a new record
 * of the call into m (true if accepted: then it applies), or none for now
 * (false). */
__attribute__((noinline)) bool leaf_other(struct pru_core *c, struct leaf_memo *m,
                                          const struct pd *jal, uint32_t jal_pc, uint32_t target,
                                          int carry);
__attribute__((noinline)) bool leaf_more_same(const struct leaf_memo *m, const uint8_t *rf);
__attribute__((noinline)) void leaf_more_apply(const struct leaf_memo *m, uint8_t *rf);

/*
 * The call by `jal` at jal_pc of `target` (the link written, the call's
 * cycle issued at cyc not yet counted): when a memo of the routine applies
 * (recorded now if there is none, or none for these inputs), its writes and
 * carry are made and its cycles returned, the caller going on at the return
 * (jal_pc + 1) as if the routine had run; else 0 and nothing changed. It
 * must end before `limit` (the fast loop would stop inside it) and meet no
 * LOOP end (loop_end: neither at a pc it runs nor at its return).
 */
static inline __attribute__((always_inline)) uint32_t
leaf_call(struct pru_core *c, const struct pd *jal, uint32_t jal_pc, uint32_t target, int *carry,
          int64_t cyc, int64_t limit, uint32_t loop_end) {
    struct leaf_memo *m = &c->leaf[target % LEAF_MEMOS];
    uint8_t *rf = (uint8_t *)c->r; /* with r[32]: byte RF_BYTES reads 0 */
    if (__builtin_expect(m->key != leaf_key(jal, target) || m->iram_gen != c->iram_gen, 0)) {
        if (!leaf_learn(c, m, jal, jal_pc, target, *carry))
            return 0;
    } else if (__builtin_expect(!m->cycles, 0)) {
        if (m->retry) {
            m->retry--;
            return 0;
        }
        if (!leaf_learn(c, m, jal, jal_pc, target, *carry))
            return 0;
    } else {
        unsigned diff = (unsigned)(rf[m->in0_at] ^ m->in0_val) |
                        (unsigned)(rf[m->in1_at] ^ m->in1_val) |
                        ((unsigned)(*carry ^ m->cin_val) & m->cin_read);
        bool same = diff == 0 && (!m->more || leaf_more_same(m, rf));
        if (__builtin_expect(!same, 0) && !leaf_other(c, m, jal, jal_pc, target, *carry))
            return 0; /* other inputs */
    }
    uint32_t ret = jal_pc + 1;
    if (cyc + m->cycles >= limit || m->pc_max >= jal_pc || ret >= c->iram_words ||
        (((ret & jal->rdmask) & 0xffffu) != ret))
        return 0;
    if (__builtin_expect(loop_end != NO_LOOP, 0)) {
        if (loop_end == ret)
            return 0;
        for (unsigned i = 0; i < m->cycles; i++)
            if (m->pcs[i] == loop_end)
                return 0;
    }
    /* no store to r[32] for an unused one: every immediate operand reads
     * that word, and a byte stored into it would stall the load */
    if (m->n_out) {
        rf[m->out0_at] = m->out0_val;
        if (m->n_out > 1) {
            rf[m->out1_at] = m->out1_val;
            if (m->more)
                leaf_more_apply(m, rf);
        }
    }
    *carry = (*carry & m->carry_keep) | m->carry_set;
    m->hits++;
    c->leaf_hits++;
    return m->cycles;
}

#endif
