/*
 * Check suite: both PRUs of one PRU-ICSS (pruss.h): the cross-mapped data
 * RAMs and the shared RAM, one IEP read by both in the same cycle, each
 * PRU's GPI following its own GPCFG, each PRU's own CONTROL block and
 * constant table, the host's view of PRU1 (IRAM1, CTRL1, data RAM1), and
 * PRU1's stall when both use one scratch-pad bank in a cycle.
 */
#include "check_run.h"
#include "core_test_util.h"
#include "pruss.h"

#define BASE   0x4A300000u
#define DRAM1  (BASE + 0x2000u)
#define SHARED (BASE + 0x10000u)
#define CTRL1  (BASE + 0x24000u)
#define CFG    (BASE + 0x26000u)
#define IEP    (BASE + 0x2E000u)
#define COUNT  0x0Cu

static struct pru_icss *icss_with(const uint32_t *w0, size_t n0, const uint32_t *w1, size_t n1) {
    struct pru_icss *s = pru_icss_new(PRU_SOC_AM335X, NULL);
    ck_assert_ptr_nonnull(s);
    struct pru_core *c0 = pru_icss_core(s, 0), *c1 = pru_icss_core(s, 1);
    ck_assert_uint_eq(pru_core_index(c0), 0);
    ck_assert_uint_eq(pru_core_index(c1), 1);
    if (w0) {
        ck_assert_int_eq(pru_load_image(c0, w0, n0 * 4), 0);
        pru_start(c0);
    }
    if (w1) {
        ck_assert_int_eq(pru_load_image(c1, w1, n1 * 4), 0);
        pru_start(c1);
    }
    return s;
}

static uint32_t host32(struct pru_core *c, uint32_t addr) {
    uint32_t v = 0;
    ck_assert_int_eq(pru_host_read32(c, addr, &v), 0);
    return v;
}

/* Each PRU reads its own data RAM at 0x0 (a value, and where in the
 * shared RAM to put it) and the other's at 0x2000, and stores both there. */
START_TEST(data_rams_cross_mapped) {
    uint32_t w[16];
    unsigned n = 0;
    w[n++] = ldi(R(1), 0);
    w[n++] = burst(PRU_OP_LBBO, 4 * 2, 1, 0, 8); /* own: r2 value, r3 place */
    mov32(w, &n, 1, 0x2000);
    w[n++] = burst(PRU_OP_LBBO, 4 * 4, 1, 0, 4); /* the other's value */
    mov32(w, &n, 1, 0x10000);
    w[n++] = alu(PRU_OP_ADD, R(1), R(1), R(3));
    w[n++] = burst(PRU_OP_SBBO, 4 * 2, 1, 0, 4);
    w[n++] = burst(PRU_OP_SBBO, 4 * 4, 1, 4, 4);
    w[n++] = halt();
    struct pru_icss *s = icss_with(w, n, w, n);
    struct pru_core *c0 = pru_icss_core(s, 0), *c1 = pru_icss_core(s, 1);
    ck_assert_int_eq(pru_host_write32(c0, BASE, 0x11111111u), 0);
    ck_assert_int_eq(pru_host_write32(c0, BASE + 4, 0), 0);
    ck_assert_int_eq(pru_host_write32(c1, DRAM1, 0x22222222u), 0);
    ck_assert_int_eq(pru_host_write32(c1, DRAM1 + 4, 8), 0);
    ck_assert_int_eq(pru_icss_run_until_cycle(s, 1000), PRU_STOP_HALT);
    ck_assert(pru_halted(c0) && pru_halted(c1));
    ck_assert_uint_eq(host32(c0, SHARED + 0), 0x11111111u);
    ck_assert_uint_eq(host32(c0, SHARED + 4), 0x22222222u);
    ck_assert_uint_eq(host32(c1, SHARED + 8), 0x22222222u);
    ck_assert_uint_eq(host32(c1, SHARED + 12), 0x11111111u);
    ck_assert_int_eq(pru_icss_cycles(s), 1000);
    pru_icss_free(s);
}
END_TEST

/* Both read COUNT in the same cycle and get the same value; PRU1 three
 * cycles later gets three more. */
START_TEST(one_iep_same_cycle) {
    for (unsigned late = 0; late <= 3; late += 3) {
        uint32_t w0[8], w1[8];
        unsigned n0 = 0, n1 = 0;
        w0[n0++] = burst(PRU_OP_LBCO, 4 * 2, 26, COUNT, 4);
        w0[n0++] = halt();
        for (unsigned i = 0; i < late; i++)
            w1[n1++] = alu(PRU_OP_ADD, R(0), R(0), R(0));
        w1[n1++] = burst(PRU_OP_LBCO, 4 * 2, 26, COUNT, 4);
        w1[n1++] = halt();
        struct pru_icss *s = icss_with(w0, n0, w1, n1);
        struct pru_core *c0 = pru_icss_core(s, 0), *c1 = pru_icss_core(s, 1);
        ck_assert_int_eq(pru_host_write32(c0, IEP, 0x111), 0); /* count by 1 */
        ck_assert_int_eq(pru_icss_run_until_cycle(s, 100), PRU_STOP_HALT);
        ck_assert_uint_eq(pru_reg(c0, 2), 0); /* the host enabled it at boundary 0 */
        ck_assert_uint_eq(pru_reg(c1, 2), late);
        /* the host sees one counter through either core */
        ck_assert_uint_eq(host32(c0, IEP + COUNT), host32(c1, IEP + COUNT));
        pru_icss_free(s);
    }
}
END_TEST

/* PRU1 polls COUNT until it reaches 500 while PRU0 counts its own loop
 * turns: they leave their loops within one poll turn of each other. */
START_TEST(iep_poll_in_lock_step) {
    uint32_t w[16];
    unsigned n = 0;
    w[n++] = ldi(R(3), 500);
    w[n++] = burst(PRU_OP_LBCO, 4 * 2, 26, COUNT, 4); /* 3 cycles */
    w[n++] = qb(PRU_OP_QBGT, -1, R(2), R(3));         /* while 500 > count */
    w[n++] = halt();
    struct pru_icss *s = icss_with(w, n, w, n);
    struct pru_core *c0 = pru_icss_core(s, 0), *c1 = pru_icss_core(s, 1);
    ck_assert_int_eq(pru_host_write32(c0, IEP, 0x111), 0);
    ck_assert_int_eq(pru_icss_run_until_cycle(s, 2000), PRU_STOP_HALT);
    ck_assert_uint_ge(pru_reg(c0, 2), 500);
    ck_assert_uint_eq(pru_reg(c0, 2), pru_reg(c1, 2));
    ck_assert_uint_eq(pru_instructions(c0), pru_instructions(c1));
    pru_icss_free(s);
}
END_TEST

/* GPCFG0 puts PRU0's GPI in shift mode, GPCFG1 PRU1's: each samples its
 * own input bit 0. */
START_TEST(gpcfg_per_pru) {
    uint32_t w[4] = {alu(PRU_OP_ADD, R(0), R(0), R(0)), jmpi(0)};
    struct pru_icss *s = icss_with(w, 2, w, 2);
    struct pru_core *c0 = pru_icss_core(s, 0), *c1 = pru_icss_core(s, 1);
    pru_set_inputs(c0, 1);
    pru_set_inputs(c1, 1);
    ck_assert_int_eq(pru_host_write32(c0, CFG + 0x0C, 2), 0); /* PRU1: shift, divider 1 */
    ck_assert_int_eq(pru_icss_run_until_cycle(s, 100), PRU_STOP_LIMIT);
    ck_assert_uint_eq(pru_reg(c0, 31) & 0x3fffffffu, 1);       /* direct: the pin */
    ck_assert_uint_eq(pru_reg(c1, 31) & (1u << 29), 1u << 29); /* SB */
    ck_assert_uint_eq(pru_reg(c1, 31) & 0x0fffffffu, 0x0fffffffu);
    ck_assert_uint_eq(host32(c0, CFG + 0x0C) & (1u << 13), 1u << 13); /* GPCFG1.SB */
    ck_assert_uint_eq(host32(c0, CFG + 0x08) & (1u << 13), 0);
    pru_icss_free(s);
}
END_TEST

/* PRU1 points its C28 through its own CTPPR0 (0x24028); PRU0's stays. */
START_TEST(own_control_block) {
    uint32_t w[16];
    unsigned n = 0;
    mov32(w, &n, 1, 0x24028);
    w[n++] = ldi(R(2), 0x0100); /* C28 -> 0x10000 */
    w[n++] = burst(PRU_OP_SBBO, 4 * 2, 1, 0, 4);
    w[n++] = ldi(R(3), 0x5A5A);
    w[n++] = burst(PRU_OP_SBCO, 4 * 3, 28, 0, 4);
    w[n++] = halt();
    struct pru_icss *s = icss_with(NULL, 0, w, n);
    struct pru_core *c0 = pru_icss_core(s, 0), *c1 = pru_icss_core(s, 1);
    ck_assert_int_eq(pru_icss_run_until_cycle(s, 100), PRU_STOP_HALT);
    ck_assert(pru_halted(c1) && !pru_halted(c0));
    ck_assert_uint_eq(host32(c0, SHARED), 0x5A5A);
    ck_assert_uint_eq(host32(c0, CTRL1 + 0x28), 0x0100);
    ck_assert_uint_eq(host32(c0, BASE + 0x22028), 0);
    /* PRU1's registers through its debug block, its IRAM through IRAM1 */
    ck_assert_uint_eq(host32(c0, CTRL1 + 0x400 + 4 * 3), 0x5A5A);
    ck_assert_uint_eq(host32(c0, BASE + 0x38000u), w[0]);
    ck_assert_uint_eq(host32(c0, BASE + 0x34000u), 0);
    ck_assert_int_eq(pru_cycles(c0), 100); /* PRU0 never ran: its time passed */
    pru_icss_free(s);
}
END_TEST

/* One set of scratch-pad banks: what PRU0 puts in bank 0 in cycle 1,
 * PRU1 reads there in cycle 1 (it stalls for PRU0, which comes first),
 * and not before. */
START_TEST(scratch_pad_shared) {
    uint32_t w0[4] = {ldi(R(2), 0x1234), xfr(PRU_OP_XOUT, 10, 4 * 2, 4), halt()};
    uint32_t w1[4] = {xfr(PRU_OP_XIN, 10, 4 * 3, 4), xfr(PRU_OP_XIN, 10, 4 * 2, 4),
                      xfr(PRU_OP_XIN, 11, 4 * 4, 4), halt()};
    struct pru_icss *s = icss_with(w0, 3, w1, 4);
    struct pru_core *c1 = pru_icss_core(s, 1);
    pru_set_reg(c1, 4, 0xffffffffu);
    ck_assert_int_eq(pru_icss_run_until_cycle(s, 100), PRU_STOP_HALT);
    ck_assert_uint_eq(pru_reg(c1, 3), 0);      /* cycle 0: not yet there */
    ck_assert_uint_eq(pru_reg(c1, 2), 0x1234); /* cycle 1: PRU0's XOUT came first */
    ck_assert_uint_eq(pru_reg(c1, 4), 0);      /* another bank */
    pru_icss_free(s);
}
END_TEST

/* PRU0 and PRU1 issue an XOUT in cycle 0, on bank `bank1` for PRU1 (bank 0
 * for PRU0), then PRU1 runs ADDs: the instructions PRU1 has issued before
 * cycle 5 show its stall. */
static struct pru_icss *xout_race(unsigned bank1, const struct pru_params *p) {
    uint32_t a0[2] = {xfr(PRU_OP_XOUT, 10, 4 * 2, 4), halt()};
    uint32_t a1[6] = {xfr(PRU_OP_XOUT, bank1, 4 * 3, 4), alu(PRU_OP_ADD, R(4), R(4), R(4)),
                      alu(PRU_OP_ADD, R(4), R(4), R(4)), alu(PRU_OP_ADD, R(4), R(4), R(4)),
                      alu(PRU_OP_ADD, R(4), R(4), R(4)), halt()};
    struct pru_icss *s = pru_icss_new(PRU_SOC_AM335X, p);
    ck_assert_ptr_nonnull(s);
    struct pru_core *c0 = pru_icss_core(s, 0), *c1 = pru_icss_core(s, 1);
    ck_assert_int_eq(pru_load_image(c0, a0, sizeof a0), 0);
    ck_assert_int_eq(pru_load_image(c1, a1, sizeof a1), 0);
    pru_set_reg(c0, 2, 0x00000a0au);
    pru_set_reg(c1, 3, 0x00000b0bu);
    pru_start(c0);
    pru_start(c1);
    return s;
}

/* Both PRUs on one scratch-pad bank in one cycle: PRU0 goes first, PRU1
 * stalls spad_stall_cycles (TI: "PRU0 is given priority"); on different
 * banks neither waits. PRU0 never stalls. */
START_TEST(spad_collision_stalls_pru1) {
    struct pru_params p;
    pru_params_default(&p);
    ck_assert_uint_eq(p.spad_stall_cycles, 1);
    for (unsigned stall = 1; stall <= 3; stall += 2) {
        p.spad_stall_cycles = stall;
        struct pru_icss *s = xout_race(10, &p);
        struct pru_core *c0 = pru_icss_core(s, 0), *c1 = pru_icss_core(s, 1);
        ck_assert_int_eq(pru_icss_run_until_cycle(s, 5), PRU_STOP_HALT);
        ck_assert_uint_eq(pru_instructions(c0), 2);         /* XOUT, HALT: no wait */
        ck_assert_uint_eq(pru_instructions(c1), 5 - stall); /* XOUT took 1 + stall */
        ck_assert_uint_eq(pru_spad_collisions(c1), 1);
        ck_assert_uint_eq(pru_spad_collisions(c0), 0);
        pru_icss_free(s);
    }
    struct pru_icss *s = xout_race(11, NULL);
    struct pru_core *c0 = pru_icss_core(s, 0), *c1 = pru_icss_core(s, 1);
    ck_assert_int_eq(pru_icss_run_until_cycle(s, 5), PRU_STOP_HALT);
    ck_assert_uint_eq(pru_instructions(c1), 5);
    ck_assert_uint_eq(pru_spad_collisions(c1), 0);
    ck_assert_uint_eq(pru_spad_collisions(c0), 0);
    pru_icss_free(s);
}
END_TEST

/* Strict rule spad: PRU1's XOUT on PRU0's bank in the same cycle faults
 * (PRU1's, at its PC 0); on another bank both run to the end. */
START_TEST(spad_collision_strict) {
    struct pru_params p;
    pru_params_default(&p);
    p.strict = PRU_STRICT_SPAD;
    p.strict_everywhere = 1;
    struct pru_icss *s = xout_race(10, &p);
    struct pru_core *c0 = pru_icss_core(s, 0), *c1 = pru_icss_core(s, 1);
    ck_assert_int_eq(pru_icss_run_until_cycle(s, 100), PRU_STOP_FAULT);
    const struct pru_fault *f = pru_get_fault(c1);
    ck_assert_int_eq(f->cause, PRU_FAULT_STRICT);
    ck_assert_uint_eq(f->rule, PRU_STRICT_SPAD);
    ck_assert_uint_eq(f->pc, 0);
    ck_assert_int_eq(f->cycle, 0);
    ck_assert_int_eq(pru_get_fault(c0)->cause, PRU_FAULT_NONE);
    ck_assert_str_eq(pru_strict_rule_name(PRU_STRICT_SPAD), "spad");
    pru_icss_free(s);
    s = xout_race(11, &p);
    ck_assert_int_eq(pru_icss_run_until_cycle(s, 100), PRU_STOP_HALT);
    ck_assert(pru_halted(pru_icss_core(s, 0)) && pru_halted(pru_icss_core(s, 1)));
    ck_assert_int_eq(pru_get_fault(pru_icss_core(s, 1))->cause, PRU_FAULT_NONE);
    pru_icss_free(s);
}
END_TEST

/* An AM335x PRU-ICSS, PRU0 running w0 and PRU1 w1, run ahead or in turns
 * of a cycle, with the fast-forward or without. */
static struct pru_icss *pair_started(const uint32_t *w0, unsigned n0, const uint32_t *w1,
                                     unsigned n1, bool ahead, bool ff) {
    struct pru_params p;
    pru_params_default(&p);
    p.run_ahead = ahead;
    p.fast_forward = ff;
    struct pru_icss *s = pru_icss_new(PRU_SOC_AM335X, &p);
    ck_assert_ptr_nonnull(s);
    ck_assert_int_eq(pru_load_image(pru_icss_core(s, 0), w0, n0 * 4), 0);
    ck_assert_int_eq(pru_load_image(pru_icss_core(s, 1), w1, n1 * 4), 0);
    pru_start(pru_icss_core(s, 0));
    pru_start(pru_icss_core(s, 1));
    return s;
}

/* PRU0 polls a register of PRU1 through PRU1's CONTROL block (its debug
 * registers, 0x24414: R5) until PRU1, after a delay, sets it: the same
 * instructions with the fast-forward on as with it off (the block gives no
 * horizon of its own: the two cores run in turns of a cycle, pruss.c).
 * Cycle by cycle only: with run_ahead a look at the other PRU's registers
 * faults (PRU_FAULT_RUN_AHEAD) where that PRU has run past it. */
static void poll_other_pru(bool ff, uint64_t *insns, uint32_t *pc, bool ahead) {
    uint32_t w0[16], w1[8];
    unsigned n0 = 0, n1 = 0;
    mov32(w0, &n0, 1, 0x24000u + 0x400u + 4u * 5u);
    w0[n0++] = burst(PRU_OP_LBBO, 4 * 2, 1, 0, 4);
    w0[n0++] = qbi(PRU_OP_QBEQ, -1, R(2), 0);
    w0[n0++] = halt();
    w1[n1++] = ldi(R(3), 400);
    w1[n1++] = alui(PRU_OP_SUB, R(3), R(3), 1);
    w1[n1++] = qbi(PRU_OP_QBNE, -1, R(3), 0);
    w1[n1++] = ldi(R(5), 7);
    w1[n1++] = halt();
    struct pru_icss *s = pair_started(w0, n0, w1, n1, ahead, ff);
    struct pru_core *c0 = pru_icss_core(s, 0), *c1 = pru_icss_core(s, 1);
    if (ahead) {
        /* PRU1's countdown touches nothing of PRU0's: it runs ahead of
         * PRU0's first look at its registers, which then could not see
         * them as they were: a fault, not a wrong value */
        ck_assert_int_eq(pru_icss_run_until_cycle(s, 100000), PRU_STOP_FAULT);
        const struct pru_fault *f = pru_get_fault(c0);
        ck_assert_int_eq(f->cause, PRU_FAULT_RUN_AHEAD);
        ck_assert_uint_eq(f->pc, 2); /* the LBBO */
        ck_assert_uint_eq(f->addr, 0x24414u);
        ck_assert_int_eq(f->cycle, 2);
        ck_assert_int_eq(pru_get_fault(c1)->cause, PRU_FAULT_NONE);
        pru_icss_free(s);
        return;
    }
    ck_assert_int_eq(pru_icss_run_until_cycle(s, 100000), PRU_STOP_HALT);
    ck_assert(pru_halted(c0) && pru_halted(c1));
    ck_assert_uint_eq(pru_reg(c0, 2), 7);
    *insns = pru_instructions(c0);
    *pc = pru_pc(c0);
    pru_icss_free(s);
}

START_TEST(poll_other_pru_ff) {
    uint64_t on, off;
    uint32_t pc_on, pc_off;
    poll_other_pru(true, &on, &pc_on, false);
    poll_other_pru(false, &off, &pc_off, false);
    poll_other_pru(true, &on, &pc_on, true); /* (asserts the fault) */
    /* PRU1's 400 turns of 2 cycles: about 800 cycles of polls, each 2
     * instructions and a few cycles */
    ck_assert_uint_gt(off, 300);
    ck_assert_uint_lt(off, 500);
    ck_assert_uint_eq(on, off);
    ck_assert_uint_eq(pc_on, pc_off);
}
END_TEST

/* ---- run-ahead (pruss.c): the same run as cycle by cycle ---- */

#define IEP_LOCAL 0x2E000u

/* What a run leaves: each PRU's time, instructions, registers, PC,
 * bank stalls, its data RAM's first 512 bytes and the shared RAM's. */
struct pair_end {
    int64_t cycles[2];
    uint64_t insns[2], collisions[2];
    uint32_t pc[2], regs[2][30];
    uint8_t dram[2][512], shared[64];
};

static void run_pair(const uint32_t *w0, unsigned n0, const uint32_t *w1, unsigned n1, bool ahead,
                     bool ff, int64_t cycles, struct pair_end *e) {
    struct pru_icss *s = pair_started(w0, n0, w1, n1, ahead, ff);
    struct pru_core *c[2] = {pru_icss_core(s, 0), pru_icss_core(s, 1)};
    /* in steps, as the bench runs: each run ends with both at its limit */
    for (int64_t t = 0; t < cycles; t += 997)
        ck_assert_int_ne(pru_icss_run_until_cycle(s, t + 997), PRU_STOP_FAULT);
    memset(e, 0, sizeof *e);
    for (unsigned i = 0; i < 2; i++) {
        e->cycles[i] = pru_cycles(c[i]);
        e->insns[i] = pru_instructions(c[i]);
        e->collisions[i] = pru_spad_collisions(c[i]);
        e->pc[i] = pru_pc(c[i]);
        for (unsigned r = 0; r < 30; r++)
            e->regs[i][r] = pru_reg(c[i], r);
        ck_assert_int_eq(pru_host_read(c[0], BASE + 0x2000u * i, e->dram[i], sizeof e->dram[i]), 0);
    }
    ck_assert_int_eq(pru_host_read(c[0], SHARED, e->shared, sizeof e->shared), 0);
    pru_icss_free(s);
}

static void same_end(const struct pair_end *a, const struct pair_end *b) {
    for (unsigned i = 0; i < 2; i++) {
        ck_assert_int_eq(a->cycles[i], b->cycles[i]);
        ck_assert_uint_eq(a->insns[i], b->insns[i]);
        ck_assert_uint_eq(a->collisions[i], b->collisions[i]);
        ck_assert_uint_eq(a->pc[i], b->pc[i]);
        ck_assert_mem_eq(a->regs[i], b->regs[i], sizeof a->regs[i]);
        ck_assert_mem_eq(a->dram[i], b->dram[i], sizeof a->dram[i]);
    }
    ck_assert_mem_eq(a->shared, b->shared, sizeof a->shared);
}

/*
 * The PRUs interact through every path two firmwares use: PRU0 starts the
 * IEP; PRU1, after a delay that grows each turn (private work, run
 * ahead), counts, stores the count in shared RAM, XOUTs it to bank 10 for
 * 8 cycles and reads the IEP; PRU0 polls the shared RAM for a new count, then XOUTs to
 * the same bank (PRU1 stalls when both meet there), XINs it and stores
 * the IEP count and what it read into its data RAM; PRU1 logs PRU0's last
 * store from PRU0's data RAM (0x2000) into its own. Run ahead, with and
 * without the fast-forward, and cycle by cycle: the same in every byte.
 */
START_TEST(run_ahead_same_as_turns) {
    uint32_t w0[32], w1[32];
    unsigned n0 = 0, n1 = 0;
    mov32(w0, &n0, 1, 0x10000u);  /* 0, 1 */
    mov32(w0, &n0, 8, IEP_LOCAL); /* 2, 3 */
    w0[n0++] = ldi(R(2), 0x11);   /* 4: count, increment 1 */
    w0[n0++] = burst(PRU_OP_SBBO, 4 * 2, 8, 0, 4);
    w0[n0++] = ldi(R(5), 0);
    w0[n0++] = ldi(R(12), 0x100);
    w0[n0++] = burst(PRU_OP_LBBO, 4 * 4, 1, 0, 4); /* 8: poll */
    w0[n0++] = qb(PRU_OP_QBEQ, -1, R(4), R(5));
    w0[n0++] = alui(PRU_OP_ADD, R(5), R(4), 0);
    w0[n0++] = xfr(PRU_OP_XOUT, 10, 4 * 5, 4);
    w0[n0++] = xfr(PRU_OP_XIN, 10, 4 * 7, 4);
    w0[n0++] = burst(PRU_OP_LBBO, 4 * 9, 8, COUNT, 4);
    w0[n0++] = burst(PRU_OP_SBBO, 4 * 9, 12, 0, 8); /* r9, r10 */
    w0[n0++] = burst(PRU_OP_SBBO, 4 * 7, 12, 8, 4);
    w0[n0++] = alui(PRU_OP_ADD, R(12), R(12), 12);
    w0[n0++] = qbi(PRU_OP_QBNE, -9, R(5), 40);
    w0[n0++] = halt();
    mov32(w1, &n1, 1, 0x10000u);  /* 0, 1 */
    mov32(w1, &n1, 8, IEP_LOCAL); /* 2, 3 */
    w1[n1++] = ldi(R(6), 0);
    w1[n1++] = ldi(R(12), 0x100);
    w1[n1++] = alui(PRU_OP_ADD, R(3), R(6), 5); /* 6: delay 2 (r6 + 5) cycles */
    w1[n1++] = alui(PRU_OP_SUB, R(3), R(3), 1);
    w1[n1++] = qbi(PRU_OP_QBNE, -1, R(3), 0);
    w1[n1++] = alui(PRU_OP_ADD, R(6), R(6), 1);
    w1[n1++] = burst(PRU_OP_SBBO, 4 * 6, 1, 0, 4);
    for (unsigned k = 0; k < 8; k++) /* over the cycles in which PRU0 XOUTs its copy */
        w1[n1++] = xfr(PRU_OP_XOUT, 10, 4 * 6, 4);
    w1[n1++] = burst(PRU_OP_LBBO, 4 * 9, 8, COUNT, 4);
    w1[n1++] = burst(PRU_OP_LBBO, 4 * 10, 12, 0x2000u - 0x100u, 4); /* PRU0's RAM at 0x2000 */
    w1[n1++] = burst(PRU_OP_SBBO, 4 * 9, 12, 0, 8);
    w1[n1++] = alui(PRU_OP_ADD, R(12), R(12), 8);
    w1[n1++] = qbi(PRU_OP_QBNE, -17, R(6), 40);
    w1[n1++] = halt();
    ck_assert_uint_le(n0, 32);
    ck_assert_uint_le(n1, 32);
    struct pair_end turns, ahead, ahead_ff;
    run_pair(w0, n0, w1, n1, false, true, 20000, &turns);
    run_pair(w0, n0, w1, n1, true, false, 20000, &ahead);
    run_pair(w0, n0, w1, n1, true, true, 20000, &ahead_ff);
    /* they did interact: PRU0 saw every count, PRU1 stalled on the bank */
    ck_assert_uint_eq(turns.regs[0][5], 40);
    ck_assert_uint_eq(turns.regs[1][6], 40);
    ck_assert_uint_gt(turns.collisions[1], 0);
    ck_assert_uint_eq(turns.collisions[0], 0);
    ck_assert_int_ge(turns.cycles[0], 20000); /* both halted: time ran on to the limit */
    same_end(&ahead, &turns);
    same_end(&ahead_ff, &turns);
}
END_TEST

/* PRU1 counts down (run ahead, nothing of it shared) while PRU0 turns the
 * INTC on (GER, then host 0): PRU1's R31 reads would have seen the host
 * line from there on, so run ahead that store faults; cycle by cycle it
 * runs. */
START_TEST(run_ahead_intc_on_faults) {
    uint32_t w0[16], w1[8];
    unsigned n0 = 0, n1 = 0;
    mov32(w0, &n0, 1, 0x20000u);
    w0[n0++] = ldi(R(2), 1);
    w0[n0++] = burst(PRU_OP_SBBO, 4 * 2, 1, 0x10, 4); /* 3: GER */
    w0[n0++] = ldi(R(2), 0);
    w0[n0++] = burst(PRU_OP_SBBO, 4 * 2, 1, 0x34, 4); /* 5: HIEISR host 0 */
    w0[n0++] = halt();
    w1[n1++] = ldi(R(3), 400);
    w1[n1++] = alui(PRU_OP_SUB, R(3), R(3), 1);
    w1[n1++] = qbi(PRU_OP_QBNE, -1, R(3), 0);
    w1[n1++] = halt();
    struct pair_end e;
    run_pair(w0, n0, w1, n1, false, true, 2000, &e);
    ck_assert_uint_eq(e.pc[0], 6);
    struct pru_params p;
    pru_params_default(&p);
    struct pru_icss *s = pru_icss_new(PRU_SOC_AM335X, &p);
    struct pru_core *c0 = pru_icss_core(s, 0), *c1 = pru_icss_core(s, 1);
    ck_assert_int_eq(pru_load_image(c0, w0, n0 * 4), 0);
    ck_assert_int_eq(pru_load_image(c1, w1, n1 * 4), 0);
    pru_start(c0);
    pru_start(c1);
    ck_assert_int_eq(pru_icss_run_until_cycle(s, 2000), PRU_STOP_FAULT);
    const struct pru_fault *f = pru_get_fault(c0);
    ck_assert_int_eq(f->cause, PRU_FAULT_RUN_AHEAD);
    ck_assert_uint_eq(f->pc, 5); /* GER alone leaves the host lines off */
    ck_assert_uint_eq(f->addr, 0x20034u);
    pru_icss_free(s);
}
END_TEST

/* The host starts PRU1 through CTRL1 and may not write IRAM1 while it runs. */
START_TEST(host_controls_pru1) {
    uint32_t w[2] = {alu(PRU_OP_ADD, R(0), R(0), R(0)), jmpi(0)};
    struct pru_icss *s = icss_with(NULL, 0, NULL, 0);
    struct pru_core *c0 = pru_icss_core(s, 0), *c1 = pru_icss_core(s, 1);
    ck_assert_int_eq(pru_host_write(c0, BASE + 0x38000u, w, sizeof w), 0);
    ck_assert_int_eq(pru_host_write32(c0, CTRL1, 2), 0); /* ENABLE, reset: PC 0 */
    ck_assert_int_eq(pru_icss_run_until_cycle(s, 50), PRU_STOP_LIMIT);
    ck_assert_uint_eq(pru_instructions(c1), 50);
    ck_assert_uint_eq(pru_instructions(c0), 0);
    ck_assert_int_eq(pru_host_write(c0, BASE + 0x38000u, w, 4), -2);
    ck_assert_int_eq(pru_get_fault(c1)->cause, PRU_FAULT_IRAM_RUNNING);
    ck_assert_int_eq(pru_get_fault(c0)->cause, PRU_FAULT_NONE);
    ck_assert_int_eq(pru_icss_run_until_cycle(s, 60), PRU_STOP_FAULT);
    pru_icss_free(s);
}
END_TEST

Suite *pruss_suite(void) {
    Suite *s = suite_create("core_pruss");
    TCase *t = tcase_create("pruss");
    tcase_add_test(t, data_rams_cross_mapped);
    tcase_add_test(t, one_iep_same_cycle);
    tcase_add_test(t, iep_poll_in_lock_step);
    tcase_add_test(t, gpcfg_per_pru);
    tcase_add_test(t, own_control_block);
    tcase_add_test(t, host_controls_pru1);
    tcase_add_test(t, poll_other_pru_ff);
    tcase_add_test(t, scratch_pad_shared);
    tcase_add_test(t, spad_collision_stalls_pru1);
    tcase_add_test(t, spad_collision_strict);
    tcase_add_test(t, run_ahead_same_as_turns);
    tcase_add_test(t, run_ahead_intc_on_faults);
    suite_add_tcase(s, t);
    return s;
}

int main(void) {
    return check_run(pruss_suite());
}
