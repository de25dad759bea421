/*
 * leaf.c - leaf calls (pru_params.leaf_call): the firmware ends its clocked
 * half periods in a call of a shared delay routine, a few single-cycle
 * instructions that the fast loop would run one by one. A call from far
 * below (no loop the fast-forward looks at: JUMPED() in exec.c only
 * disarms it) of such a routine is recorded here once and then replayed
 * by leaf_call() (leaf.h), when what it reads is the same, in one step
 * (struct leaf_memo).
 */
#include "leaf.h"

/* What a fast kind the recording allows reads and writes (LEAF_*), 0 if
 * it allows none of it. */
#define LEAF_OK     0x01u
#define LEAF_RS1    0x02u /* reads the rs1 field */
#define LEAF_OP2    0x04u /* reads the op2 field (no bytes when immediate) */
#define LEAF_RD     0x08u /* writes the rd field */
#define LEAF_CIN    0x10u /* reads the carry */
#define LEAF_COUT   0x20u /* writes the carry */
#define LEAF_BRANCH 0x40u /* a quick branch */
#define LEAF_ALU    (LEAF_OK | LEAF_RS1 | LEAF_OP2 | LEAF_RD)
#define LEAF_QB     (LEAF_OK | LEAF_RS1 | LEAF_OP2 | LEAF_BRANCH)
static unsigned leaf_kind(unsigned kind) {
    switch (kind) {
    case PRU_OP_ADD:
    case PRU_OP_SUB:
    case PRU_OP_RSB:
    case PD_ADD32:
    case PD_SUB32:
    case PD_ADD32I:
    case PD_SUB32I:
    case PD_SUBI:
    case PD_SUB32B:
    case PD_SUBBBI:
        return LEAF_ALU | LEAF_COUT;
    case PRU_OP_ADC:
    case PRU_OP_SUC:
    case PRU_OP_RSC:
    case PD_ADC32:
        return LEAF_ALU | LEAF_CIN | LEAF_COUT;
    case PRU_OP_LSL:
    case PRU_OP_LSR:
    case PRU_OP_AND:
    case PRU_OP_OR:
    case PRU_OP_XOR:
    case PRU_OP_NOT:
    case PRU_OP_MIN:
    case PRU_OP_MAX:
    case PRU_OP_CLR:
    case PRU_OP_SET:
    case PRU_OP_LMBD:
    case PD_AND32:
    case PD_OR32:
    case PD_XOR32:
    case PD_LSL32:
    case PD_LSR32:
    case PD_LSL32I:
    case PD_LSR32I:
    case PD_MINI:
    case PD_MINB32I:
        return LEAF_ALU;
    case PRU_OP_LDI:
    case PD_LDI32:
        return LEAF_OK | LEAF_RD;
    case PRU_OP_NOP0:
        return LEAF_OK;
    case PRU_OP_QBGT:
    case PRU_OP_QBGE:
    case PRU_OP_QBLT:
    case PRU_OP_QBLE:
    case PRU_OP_QBEQ:
    case PRU_OP_QBNE:
    case PRU_OP_QBBS:
    case PRU_OP_QBBC:
    case PD_QBNE32:
    case PD_QBEQ32:
    case PD_QBBS32:
    case PD_QBBC32:
    case PD_QBNE32I:
    case PD_QBEQ32I:
    case PD_QBBS32I:
    case PD_QBBC32I:
    case PD_QBEQI:
    case PD_QBNEI:
    case PD_QBEQBI:
    case PD_QBNEBI:
    case PD_QBEQWI:
    case PD_QBNEWI:
        return LEAF_QB;
    case PRU_OP_QBA:
        return LEAF_OK | LEAF_BRANCH;
    default:
        return 0;
    }
}

/* The register-file bytes of a field (reg 32, the zero register: none). */
static inline uint32_t leaf_bytes(unsigned reg, unsigned sh, uint32_t mask) {
    uint32_t bits = mask << sh, bytes = 0;
    if (reg >= 32)
        return 0;
    for (unsigned i = 0; i < 4; i++)
        if ((bits >> (8u * i)) & 0xffu)
            bytes |= 1u << i;
    return bytes; /* bit i: byte 4 reg + i */
}

enum { LB_NONE, LB_READ, LB_WRITTEN, LB_LINK };

/* Reads of field (reg, sh, mask) by the recording: the bytes not written
 * yet are inputs (their values now); false if one is the link's. */
static bool leaf_read(struct leaf_memo *m, uint8_t *st, const uint8_t *rf, unsigned reg,
                      unsigned sh, uint32_t mask) {
    uint32_t bytes = leaf_bytes(reg, sh, mask);
    for (unsigned i = 0; i < 4; i++) {
        if (!((bytes >> i) & 1u))
            continue;
        unsigned b = 4u * reg + i;
        if (st[b] == LB_LINK)
            return false;
        if (st[b] != LB_NONE)
            continue;
        if (m->n_in == LEAF_MAX_BYTES)
            return false;
        st[b] = LB_READ;
        m->in_at[m->n_in] = (uint8_t)b;
        m->in_val[m->n_in++] = rf[b];
    }
    return true;
}

static bool leaf_write(uint8_t *st, unsigned reg, unsigned sh, uint32_t mask) {
    uint32_t bytes = leaf_bytes(reg, sh, mask);
    for (unsigned i = 0; i < 4; i++) {
        if (!((bytes >> i) & 1u))
            continue;
        unsigned b = 4u * reg + i;
        if (st[b] == LB_LINK)
            return false;
        st[b] = LB_WRITTEN;
    }
    return true;
}

/*
 * Records into m the routine at `target` called by `jal` at jal_pc (its
 * link already written): run on a copy of the registers, it is accepted
 * (m->cycles > 0) if every instruction up to a JMP through exactly the
 * link field is one of leaf_kind()'s with no flags (no R30/R31, memory,
 * pin or event effect), every branch taken goes forward, every pc lies
 * below jal_pc, and the link is neither read nor written before the JMP.
 * The fast loop's state is not touched.
 */
static __attribute__((noinline)) void leaf_record(struct pru_core *c, struct leaf_memo *m,
                                                  const struct pd *jal, uint32_t jal_pc,
                                                  uint32_t target, int carry) {
    uint32_t r[33];
    uint8_t st[RF_BYTES] = {0};
    const uint8_t *rf = (const uint8_t *)r;
    memcpy(r, c->r, sizeof r);
    c->leaf_records++;
    *m = (struct leaf_memo){.key = leaf_key(jal, target),
                            .iram_gen = c->iram_gen,
                            .retry = LEAF_RETRY,
                            .in0_at = RF_BYTES,
                            .in1_at = RF_BYTES,
                            .out0_at = RF_BYTES,
                            .out1_at = RF_BYTES,
                            .carry_keep = 1};
    uint32_t link = leaf_bytes(jal->rd, jal->rdsh, jal->rdmask);
    for (unsigned i = 0; i < 4; i++)
        if ((link >> i) & 1u)
            st[4u * jal->rd + i] = LB_LINK;
    int cst = LB_NONE;
    uint32_t pc = target;
    for (unsigned n = 0; n < LEAF_MAX_INSNS && pc < jal_pc; n++) {
        const struct pd *d = &c->pd[pc];
        m->pcs[n] = (uint16_t)pc;
        if (pc > m->pc_max)
            m->pc_max = pc;
        if (d->flags != 0)
            return;
        if (d->fast == PRU_OP_JMP) {
            if (d->in.io || d->rs2 != jal->rd || d->rs2sh != jal->rdsh || d->rs2mask != jal->rdmask)
                return;
            for (unsigned b = 0; b < RF_BYTES; b++) {
                if (st[b] != LB_WRITTEN)
                    continue;
                if (m->n_out == LEAF_MAX_BYTES)
                    return;
                m->out_at[m->n_out] = (uint8_t)b;
                m->out_val[m->n_out++] = rf[b];
            }
            if (cst == LB_WRITTEN) {
                m->carry_keep = 0;
                m->carry_set = (uint8_t)carry;
            }
            /* the first two of each in the replay's own fields */
            if (m->n_in > 0)
                m->in0_at = m->in_at[0], m->in0_val = m->in_val[0];
            if (m->n_in > 1)
                m->in1_at = m->in_at[1], m->in1_val = m->in_val[1];
            if (m->n_out > 0)
                m->out0_at = m->out_at[0], m->out0_val = m->out_val[0];
            if (m->n_out > 1)
                m->out1_at = m->out_at[1], m->out1_val = m->out_val[1];
            m->more = m->n_in > 2 || m->n_out > 2;
            m->cycles = n + 1;
            return;
        }
        unsigned k = leaf_kind(d->fast);
        if (!k)
            return;
        if (insn_is_identity(&d->in)) { /* a pad: neither read nor written */
            pc++;
            continue;
        }
        if (k & LEAF_RS1 && !leaf_read(m, st, rf, d->rs1, d->rs1sh, d->rs1mask))
            return;
        if (k & LEAF_OP2 && !leaf_read(m, st, rf, d->rs2, d->rs2sh, d->rs2mask))
            return;
        if (k & LEAF_CIN && cst == LB_NONE) {
            cst = LB_READ;
            m->cin_read = 1;
            m->cin_val = (uint8_t)carry;
        }
        uint32_t next = pc;
        if (!exec_simple_step(r, d, d->fast, &next, &carry))
            return;
        if (k & LEAF_BRANCH && next != pc + 1 && next <= pc)
            return; /* a taken branch back: the fast-forward's business */
        if (k & LEAF_RD && !leaf_write(st, d->rd, d->rdsh, d->rdmask))
            return;
        if (k & LEAF_COUT)
            cst = LB_WRITTEN;
        pc = next;
    }
}

/* The calls to let pass before the next look: LEAF_RETRY, then twice the
 * last, up to LEAF_RETRY_MAX. */
static uint32_t leaf_backoff(uint32_t last) {
    if (!last)
        return LEAF_RETRY;
    return last < LEAF_RETRY_MAX / 2 ? 2 * last : LEAF_RETRY_MAX;
}

/* A new record of the call into m, which it replaces when accepted, or
 * when refused unless m is a memo of another routine still current (a
 * routine refused at once costs little to look at again). True if
 * accepted: then it applies to the registers as they are. */
bool leaf_learn(struct pru_core *c, struct leaf_memo *m, const struct pd *jal, uint32_t jal_pc,
                uint32_t target, int carry) {
    struct leaf_memo rec;
    leaf_record(c, &rec, jal, jal_pc, target, carry);
    bool again = m->key == rec.key && m->iram_gen == rec.iram_gen && !m->cycles;
    if (rec.cycles)
        rec.retry = 0; /* accepted: leaf_other()'s from here */
    else if (again)    /* refused again: look twice as seldom */
        rec.retry = leaf_backoff(m->retry_next);
    rec.retry_next = rec.retry;
    if (rec.cycles || !m->cycles || m->iram_gen != c->iram_gen)
        *m = rec;
    return rec.cycles != 0;
}

/* A recording costs several times the routine's run, so a memo that has
 * not repaid its own (LEAF_PAID replays) when the inputs change is not
 * recorded again at once: calls with other inputs run the routine, the
 * next `retry` of them, a number that doubles each time (leaf_backoff()).
 * A routine that reads data does that: the firmware's delay tails end in
 * the bit-grid check from H = 16 on (pru_fw/config.p DLY_CHK), which reads
 * the sample register, a pattern that changes at almost every call; at
 * H = 16 to 25 (4 to 6.25 MHz) the tails have no turn back and would be
 * recorded every time. */
bool leaf_other(struct pru_core *c, struct leaf_memo *m, const struct pd *jal, uint32_t jal_pc,
                uint32_t target, int carry) {
    if (m->retry) {
        m->retry--;
        return false;
    }
    uint32_t next = m->hits >= LEAF_PAID ? 0 : leaf_backoff(m->retry_next);
    struct leaf_memo rec;
    leaf_record(c, &rec, jal, jal_pc, target, carry);
    if (!rec.cycles) { /* refused for these inputs: m stays for its own */
        m->hits = 0;
        m->retry = m->retry_next = next;
        return false;
    }
    rec.retry = rec.retry_next = next;
    *m = rec;
    return true;
}

/* The inputs and outputs past the first two (m->more). */
bool leaf_more_same(const struct leaf_memo *m, const uint8_t *rf) {
    for (unsigned i = 2; i < m->n_in; i++)
        if (rf[m->in_at[i]] != m->in_val[i])
            return false;
    return true;
}
void leaf_more_apply(const struct leaf_memo *m, uint8_t *rf) {
    for (unsigned i = 2; i < m->n_out; i++)
        rf[m->out_at[i]] = m->out_val[i];
}
