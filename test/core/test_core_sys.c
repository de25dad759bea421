/*
 * Check suite: memory maps per SoC, host access, CONTROL (start, reset PC,
 * single step, halt), CYCLE/STALL, faults, SLP, pins (R30 out, R31 in) and
 * R31 system events through the INTC to R31[31:30].
 */
#include "check_run.h"
#include "core_test_util.h"

#include <stdlib.h>

#define AM335X 0x4A300000u
#define ICSS1  0x54400000u
#define ICSS0  0x54440000u

/* The store watch sees every store covering its byte, in both store paths
 * (in-place data RAM bursts and the general one), with the value stored. */
struct watch_log {
    struct pru_core *c;
    int hits;
    uint32_t seen[4];
};

static void on_watch(void *ctx, uint32_t addr) {
    struct watch_log *log = ctx;
    ck_assert_uint_eq(addr, 0x84);
    ck_assert_int_lt(log->hits, 4);
    ck_assert_int_eq(pru_host_read32(log->c, AM335X + 0x84, &log->seen[log->hits]), 0);
    log->hits++;
}

START_TEST(store_watch_sees_covering_stores) {
    uint32_t w[16];
    unsigned n = 0;
    w[n++] = ldi(R(1), 0x80);
    w[n++] = ldi(R(2), 0x1111);
    w[n++] = burst(PRU_OP_SBBO, 4 * 2, 1, 4, 4); /* 0x84: hit */
    w[n++] = ldi(R(3), 0x2222);
    w[n++] = burst(PRU_OP_SBBO, 4 * 2, 1, 0, 8); /* 0x80..0x87: hit, 0x2222 */
    w[n++] = burst(PRU_OP_SBBO, 4 * 2, 1, 8, 4); /* 0x88: no hit */
    w[n++] = burst(PRU_OP_SBBO, 4 * 2, 1, 0, 4); /* 0x80: no hit */
    w[n++] = ldi(R(3), 0x3333);
    w[n++] = burst(PRU_OP_SBBO, 4 * 3, 1, 3, 2); /* 0x83..0x84: hit */
    w[n++] = halt();
    struct pru_core *c = core_with(PRU_SOC_AM335X, w, n);
    struct watch_log log = {c, 0, {0}};
    pru_set_store_watch(c, 0x84, on_watch, &log);
    ck_assert_int_eq(pru_run(c, 1000), PRU_STOP_HALT);
    ck_assert_int_eq(log.hits, 3);
    ck_assert_uint_eq(log.seen[0], 0x1111);
    ck_assert_uint_eq(log.seen[1], 0x2222);
    ck_assert_uint_eq(log.seen[2], 0x2233); /* byte 0x84 := 0x33 */
    pru_set_store_watch(c, 0, NULL, NULL);
    pru_core_free(c);
}
END_TEST

/* Load 4 bytes from a local address; returns the stop reason. */
static enum pru_stop load_from(enum pru_soc soc, uint32_t addr, uint32_t *val) {
    uint32_t w[8];
    unsigned n = 0;
    mov32(w, &n, 1, addr);
    w[n++] = burst(PRU_OP_LBBO, 4 * 2, 1, 0, 4);
    w[n++] = halt();
    struct pru_core *c = core_with(soc, w, n);
    enum pru_stop st = pru_run(c, 1000);
    if (st == PRU_STOP_FAULT) {
        ck_assert_int_eq(pru_get_fault(c)->cause, PRU_FAULT_UNMAPPED);
        ck_assert_uint_eq(pru_get_fault(c)->addr, addr);
        ck_assert_uint_eq(pru_get_fault(c)->pc, 2);
        ck_assert_int_eq(pru_get_fault(c)->cycle, 2);
    }
    *val = pru_reg(c, 2);
    pru_core_free(c);
    return st;
}

START_TEST(memmap_am335x) {
    uint32_t v;
    ck_assert_uint_eq(pru_soc_base(PRU_SOC_AM335X), AM335X);
    ck_assert_int_eq(load_from(PRU_SOC_AM335X, 0x1FFC, &v), PRU_STOP_HALT);
    ck_assert_int_eq(load_from(PRU_SOC_AM335X, 0x3FFC, &v), PRU_STOP_HALT);
    ck_assert_int_eq(load_from(PRU_SOC_AM335X, 0x4000, &v), PRU_STOP_FAULT);
    ck_assert_int_eq(load_from(PRU_SOC_AM335X, 0x10000 + 12284, &v), PRU_STOP_HALT);
    ck_assert_int_eq(load_from(PRU_SOC_AM335X, 0x10000 + 12288, &v), PRU_STOP_FAULT);
    ck_assert_int_eq(load_from(PRU_SOC_AM335X, 0x1FFE, &v), PRU_STOP_HALT);   /* spans 2 RAMs */
    ck_assert_int_eq(load_from(PRU_SOC_AM335X, 0x28000, &v), PRU_STOP_FAULT); /* UART */
    ck_assert_int_eq(load_from(PRU_SOC_AM335X, 0x80000000u, &v), PRU_STOP_FAULT);

    struct pru_core *c = pru_core_new(PRU_SOC_AM335X, NULL);
    ck_assert_uint_eq(pru_iram_bytes(c), 8192);
    ck_assert_uint_eq(pru_shared_bytes(c), 12288);
    ck_assert_int_eq(pru_host_write32(c, AM335X + 0x10000 + 12284, 7), 0);
    ck_assert_int_eq(pru_host_write32(c, AM335X + 0x10000 + 12288, 7), -1);
    ck_assert_int_eq(pru_host_write32(c, AM335X + 0x34000 + 8188, halt()), 0);
    ck_assert_int_eq(pru_host_write32(c, AM335X + 0x34000 + 8192, halt()), -1);
    ck_assert_int_eq(pru_host_write32(c, AM335X + 0x38000 + 8188, 1), 0); /* PRU1 IRAM */
    ck_assert_int_eq(pru_host_read32(c, AM335X + 0x22000, &v), 0);
    ck_assert_uint_eq(v, 1); /* CONTROL reset value */
    ck_assert_int_eq(pru_host_read32(c, AM335X + 0x2E000, &v), 0);
    ck_assert_uint_eq(v, 0x550); /* IEP GLOBAL_CFG reset */
    ck_assert_int_eq(pru_host_read32(c, AM335X - 4, &v), -1);
    pru_core_free(c);
}
END_TEST

START_TEST(memmap_am437x) {
    uint32_t v;
    ck_assert_uint_eq(pru_soc_base(PRU_SOC_AM437X_ICSS0), ICSS0);
    ck_assert_uint_eq(pru_soc_base(PRU_SOC_AM437X_ICSS1), ICSS1);
    ck_assert_int_eq(load_from(PRU_SOC_AM437X_ICSS0, 0x0FFC, &v), PRU_STOP_HALT);
    ck_assert_int_eq(load_from(PRU_SOC_AM437X_ICSS0, 0x1000, &v), PRU_STOP_FAULT);
    ck_assert_int_eq(load_from(PRU_SOC_AM437X_ICSS0, 0x2FFC, &v), PRU_STOP_HALT);
    ck_assert_int_eq(load_from(PRU_SOC_AM437X_ICSS0, 0x3000, &v), PRU_STOP_FAULT);
    ck_assert_int_eq(load_from(PRU_SOC_AM437X_ICSS0, 0x10000, &v), PRU_STOP_FAULT);
    ck_assert_int_eq(load_from(PRU_SOC_AM437X_ICSS1, 0x10000 + 32764, &v), PRU_STOP_HALT);
    ck_assert_int_eq(load_from(PRU_SOC_AM437X_ICSS1, 0x10000 + 32768, &v), PRU_STOP_FAULT);

    struct pru_core *c = pru_core_new(PRU_SOC_AM437X_ICSS0, NULL);
    uint32_t *img = calloc(1025, 4);
    ck_assert_int_eq(pru_load_image(c, img, 4096), 0);
    ck_assert_int_eq(pru_load_image(c, img, 4100), -1);
    ck_assert_int_eq(pru_host_write32(c, ICSS0 + 0x34000 + 4092, 1), 0);
    ck_assert_int_eq(pru_host_write32(c, ICSS0 + 0x34000 + 4096, 1), -1);
    ck_assert_int_eq(pru_host_write32(c, ICSS0 + 0x10000, 1), -1);
    ck_assert_int_eq(pru_host_write32(c, ICSS0 + 0x26008, 0), 0); /* GPCFG0 */
    pru_core_free(c);
    c = pru_core_new(PRU_SOC_AM437X_ICSS1, NULL);
    ck_assert_uint_eq(pru_iram_bytes(c), 12288);
    ck_assert_int_eq(pru_host_write32(c, ICSS1 + 0x34000 + 12284, 1), 0);
    ck_assert_int_eq(pru_host_write32(c, ICSS1 + 0x10000 + 32764, 1), 0);
    pru_core_free(c);
    free(img);
}
END_TEST

/* The host drives the PRU through CONTROL as on silicon. */
START_TEST(control_start_reset_pc_halt) {
    struct pru_core *c = pru_core_new(PRU_SOC_AM335X, NULL);
    const uint32_t w[] = {ldi(R(1), 1), halt(), halt(), ldi(R(2), 2), halt()};
    for (unsigned i = 0; i < 5; i++)
        pru_host_write32(c, AM335X + 0x34000 + 4 * i, w[i]);
    /* not started: time passes, nothing runs */
    ck_assert_int_eq(pru_run_until_cycle(c, 10), PRU_STOP_DISABLED);
    ck_assert_int_eq(pru_cycles(c), 10);
    ck_assert_uint_eq(pru_instructions(c), 0);
    /* soft reset with PC reset value 3, enable */
    pru_host_write32(c, AM335X + 0x22000, (3u << 16) | PRU_CTRL_ENABLE);
    uint32_t v;
    pru_host_read32(c, AM335X + 0x22000, &v);
    ck_assert_uint_eq(v, (3u << 16) | PRU_CTRL_ENABLE | PRU_CTRL_RUNSTATE | 1u);
    ck_assert_int_eq(pru_host_read32(c, AM335X + 0x34000, &v), -2); /* IRAM while running */
    ck_assert_int_eq(pru_host_write32(c, AM335X + 0x34000, 0), -2);
    ck_assert_int_eq(pru_run(c, 100), PRU_STOP_FAULT);
    ck_assert_int_eq(pru_get_fault(c)->cause, PRU_FAULT_IRAM_RUNNING);
    pru_core_free(c);

    c = pru_core_new(PRU_SOC_AM335X, NULL);
    for (unsigned i = 0; i < 5; i++)
        pru_host_write32(c, AM335X + 0x34000 + 4 * i, w[i]);
    pru_host_write32(c, AM335X + 0x22000, (3u << 16) | PRU_CTRL_ENABLE);
    ck_assert_int_eq(pru_run(c, 100), PRU_STOP_HALT);
    ck_assert_uint_eq(pru_reg(c, 1), 0);
    ck_assert_uint_eq(pru_reg(c, 2), 2);
    pru_host_read32(c, AM335X + 0x22000, &v);
    ck_assert_uint_eq(v & (PRU_CTRL_ENABLE | PRU_CTRL_RUNSTATE), 0);
    pru_host_read32(c, AM335X + 0x22004, &v);
    ck_assert_uint_eq(v, 4); /* STATUS: PC stays on the HALT */
    /* debug registers: GPREG2 */
    pru_host_read32(c, AM335X + 0x22400 + 8, &v);
    ck_assert_uint_eq(v, 2);
    pru_host_read32(c, AM335X + 0x22480 + 4 * 24, &v);
    ck_assert_uint_eq(v, 0); /* CT_REG24 */
    pru_core_free(c);
}
END_TEST

START_TEST(control_single_step) {
    const uint32_t w[] = {ldi(R(1), 1), ldi(R(2), 2), halt()};
    struct pru_core *c = pru_core_new(PRU_SOC_AM335X, NULL);
    pru_load_image(c, w, sizeof w);
    pru_host_write32(c, AM335X + 0x22000, PRU_CTRL_SINGLE_STEP | PRU_CTRL_ENABLE | 1u);
    ck_assert_int_eq(pru_run(c, 100), PRU_STOP_STEP);
    ck_assert_uint_eq(pru_reg(c, 1), 1);
    ck_assert_uint_eq(pru_reg(c, 2), 0);
    ck_assert_uint_eq(pru_pc(c), 1);
    uint32_t v;
    pru_host_read32(c, AM335X + 0x22000, &v);
    ck_assert_uint_eq(v & PRU_CTRL_ENABLE, 0);
    pru_host_write32(c, AM335X + 0x22000, PRU_CTRL_SINGLE_STEP | PRU_CTRL_ENABLE | 1u);
    ck_assert_int_eq(pru_run(c, 100), PRU_STOP_STEP);
    ck_assert_uint_eq(pru_reg(c, 2), 2);
    /* API step */
    pru_start(c);
    pru_host_write32(c, AM335X + 0x22000, PRU_CTRL_ENABLE | 1u);
    ck_assert_int_eq(pru_step(c), PRU_STOP_HALT);
    ck_assert_uint_eq(pru_instructions(c), 3);
    pru_core_free(c);
}
END_TEST

/* CYCLE starts the boundary after the enabling store; STALL counts the
 * cycles without a fetch (load latency). */
START_TEST(cycle_and_stall) {
    uint32_t w[32];
    unsigned n = 0;
    mov32(w, &n, 2, 0x22000u);
    w[n++] = burst(PRU_OP_LBBO, 4 * 1, 2, 0, 4);    /* c=2..5: CONTROL (4 cycles) */
    w[n++] = alui(PRU_OP_SET, R(1), R(1), 3);       /* c=6 */
    w[n++] = burst(PRU_OP_SBBO, 4 * 1, 2, 0, 4);    /* c=7: counts from 8 */
    w[n++] = alui(PRU_OP_ADD, R(9), R(9), 1);       /* c=8 */
    w[n++] = burst(PRU_OP_LBCO, 4 * 5, 24, 0, 4);   /* c=9..11: 2 stalls */
    w[n++] = burst(PRU_OP_LBBO, 4 * 3, 2, 0x0C, 4); /* c=12: CYCLE = 4; 3 stalls */
    w[n++] = burst(PRU_OP_LBBO, 4 * 4, 2, 0x10, 4); /* c=16: STALL = 5 */
    w[n++] = burst(PRU_OP_SBBO, 4 * 0, 2, 0x0C, 4); /* CYCLE write ignored while counting */
    w[n++] = burst(PRU_OP_LBBO, 4 * 6, 2, 0x0C, 4); /* c=21: 13 */
    w[n++] = halt();                                /* c=25, counted */
    struct pru_core *c = run_prog(w, n);
    ck_assert_uint_eq(pru_reg(c, 3), 4);
    ck_assert_uint_eq(pru_reg(c, 4), 5);
    ck_assert_uint_eq(pru_reg(c, 6), 13);
    uint32_t v;
    pru_host_read32(c, AM335X + 0x2200C, &v);
    ck_assert_uint_eq(v, 18); /* cycles 8..25 */
    pru_host_read32(c, AM335X + 0x22010, &v);
    ck_assert_uint_eq(v, 2 + 3 + 3 + 3);
    /* stopped: the host may clear it, which clears STALL too */
    pru_host_write32(c, AM335X + 0x2200C, 0);
    pru_host_read32(c, AM335X + 0x22010, &v);
    ck_assert_uint_eq(v, 0);
    pru_core_free(c);
}
END_TEST

START_TEST(cycle_saturates) {
    const uint32_t w[] = {qba(0)};
    struct pru_core *c = pru_core_new(PRU_SOC_AM335X, NULL);
    pru_load_image(c, w, sizeof w);
    pru_host_write32(c, AM335X + 0x2200C, 0xFFFFFFF0u);
    pru_host_write32(c, AM335X + 0x22000, PRU_CTRL_CTR_EN | PRU_CTRL_ENABLE | 1u);
    pru_run(c, 100);
    uint32_t v;
    pru_host_read32(c, AM335X + 0x2200C, &v);
    ck_assert_uint_eq(v, 0xFFFFFFFFu);
    pru_host_read32(c, AM335X + 0x22000, &v);
    ck_assert_uint_eq(v & PRU_CTRL_CTR_EN, 0);
    pru_core_free(c);
}
END_TEST

static void expect_fault(const uint32_t *w, size_t n, enum pru_fault_cause cause, uint32_t pc,
                         int64_t cycle) {
    struct pru_core *c = core_with(PRU_SOC_AM335X, w, n);
    ck_assert_int_eq(pru_run(c, 1000), PRU_STOP_FAULT);
    ck_assert_int_eq(pru_get_fault(c)->cause, cause);
    ck_assert_uint_eq(pru_get_fault(c)->pc, pc);
    ck_assert_int_eq(pru_get_fault(c)->cycle, cycle);
    ck_assert_int_eq(pru_run(c, 1000), PRU_STOP_FAULT); /* stays stopped */
    pru_core_free(c);
}

START_TEST(faults) {
    const uint32_t bad[] = {ldi(R(1), 1), 0x28000000u /* SCAN: V1 only */};
    expect_fault(bad, 2, PRU_FAULT_BAD_OPCODE, 1, 1);
    const uint32_t bad2[] = {0x32000000u};
    expect_fault(bad2, 1, PRU_FAULT_BAD_OPCODE, 0, 0);
    const uint32_t past[] = {jmpi(0x1FFF)};
    expect_fault(past, 1, PRU_FAULT_PC_RANGE, 0x1FFF, 1);
    /* quick branches out of IRAM (taken, and with an R31 read) */
    const uint32_t before_start[] = {ldi(R(1), 1), qbi(PRU_OP_QBNE, -2, R(1), 0)};
    expect_fault(before_start, 2, PRU_FAULT_PC_RANGE, 0xFFFF, 2);
    const uint32_t r31_out[] = {qbi(PRU_OP_QBBC, -1, R(31), 7)};
    expect_fault(r31_out, 1, PRU_FAULT_PC_RANGE, 0xFFFF, 1);
    const uint32_t zero_len[] = {burstr(PRU_OP_LBBO, 8, 1, W0(3), 124)};
    expect_fault(zero_len, 1, PRU_FAULT_BURST, 0, 0);
    const uint32_t overrun[] = {burst(PRU_OP_LBCO, 4 * 30, 24, 0, 12)};
    expect_fault(overrun, 1, PRU_FAULT_BURST, 0, 0);
    const uint32_t xdev[] = {ldi(R(1), 1), xfr(PRU_OP_XOUT, 14, 4, 4)};
    expect_fault(xdev, 2, PRU_FAULT_XFR_DEVICE, 1, 1);
    /* GPO shift mode is refused loudly */
    uint32_t gpo[8];
    unsigned n = 0;
    mov32(gpo, &n, 1, 1u << 14);
    gpo[n++] = burst(PRU_OP_SBCO, 4, 4, 8, 4);
    gpo[n++] = halt();
    expect_fault(gpo, n, PRU_FAULT_GPO_SHIFT, 2, 2);
    /* fall off the end of a 4 KB IRAM */
    uint32_t *w = calloc(1024, 4);
    struct pru_core *c = core_with(PRU_SOC_AM437X_ICSS0, w, 1024);
    ck_assert_int_eq(pru_run(c, 5000), PRU_STOP_FAULT);
    ck_assert_int_eq(pru_get_fault(c)->cause, PRU_FAULT_PC_RANGE);
    ck_assert_int_eq(pru_get_fault(c)->cycle, 1024);
    pru_core_free(c);
    free(w);
}
END_TEST

/* ---- pins ---- */

struct rec {
    int n;
    int64_t t[8];
    uint32_t v[8];
    int64_t t_high; /* input bit 3 goes high here */
};

static uint32_t rec_in(void *ctx, int64_t t) {
    struct rec *r = ctx;
    return t >= r->t_high ? 8u : 0u;
}

static int64_t rec_next(void *ctx, int64_t t) {
    struct rec *r = ctx;
    return t < r->t_high ? r->t_high : INT64_MAX;
}

static void rec_out(void *ctx, int64_t t, uint32_t v) {
    struct rec *r = ctx;
    if (r->n < 8) {
        r->t[r->n] = t;
        r->v[r->n] = v;
    }
    r->n++;
}

START_TEST(r30_outputs_with_time) {
    struct rec r = {.t_high = INT64_MAX};
    struct pru_pins pins = {
        .ctx = &r, .inputs_at = rec_in, .next_input_change = rec_next, .outputs_changed = rec_out};
    const uint32_t w[] = {ldi(R(30), 1),
                          ldi(R(30), 1),
                          burst(PRU_OP_LBCO, 4 * 29, 24, 0, 8),
                          alui(PRU_OP_SET, R(30), R(30), 4),
                          jali(W0(30), 5),
                          halt()};
    struct pru_core *c = pru_core_new(PRU_SOC_AM335X, NULL);
    pru_load_image(c, w, sizeof w);
    pru_set_pins(c, &pins);
    pru_start(c);
    ck_assert_int_eq(pru_run(c, 100), PRU_STOP_HALT);
    ck_assert_int_eq(r.n, 4);
    ck_assert_int_eq(r.t[0], 5000);
    ck_assert_uint_eq(r.v[0], 1);
    ck_assert_int_eq(r.t[1], 30000); /* lbco r29..r30 at cycles 2..5: r30 <- 0 */
    ck_assert_uint_eq(r.v[1], 0);
    ck_assert_int_eq(r.t[2], 35000);
    ck_assert_uint_eq(r.v[2], 0x10);
    ck_assert_int_eq(r.t[3], 40000); /* CALL drives r30.w0 with the return address */
    ck_assert_uint_eq(r.v[3], 5);
    pru_core_free(c);
}
END_TEST

/* R31 reads see the pins gpi_delay_ps earlier; SLP 1 wakes on WAKEUP_EN. */
START_TEST(slp_wakeup_and_input_delay) {
    for (int ff = 0; ff < 2; ff++) {
        struct rec r = {.t_high = 50000};
        struct pru_pins pins = {.ctx = &r,
                                .inputs_at = rec_in,
                                .next_input_change = ff ? rec_next : NULL,
                                .outputs_changed = rec_out};
        const uint32_t w[] = {slp(1), alu(PRU_OP_OR, R(1), R(31), R(31)), halt()};
        struct pru_core *c = pru_core_new(PRU_SOC_AM335X, NULL);
        pru_load_image(c, w, sizeof w);
        pru_set_pins(c, &pins);
        pru_host_write32(c, AM335X + 0x22008, 8);
        pru_start(c);
        ck_assert_int_eq(pru_run_until_cycle(c, 5), PRU_STOP_LIMIT);
        ck_assert(pru_sleeping(c));
        uint32_t v;
        pru_host_read32(c, AM335X + 0x22000, &v);
        ck_assert_uint_eq(v & PRU_CTRL_SLEEPING, PRU_CTRL_SLEEPING);
        ck_assert_int_eq(pru_run(c, 100), PRU_STOP_HALT);
        /* 50000 ps + 10000 ps synchronizer = cycle 12 */
        ck_assert_int_eq(pru_cycles(c), 14);
        ck_assert_uint_eq(pru_reg(c, 1), 8);
        ck_assert_uint_eq(pru_instructions(c), 3);
        pru_core_free(c);
    }
}
END_TEST

START_TEST(slp_woken_by_host) {
    const uint32_t w[] = {slp(0), ldi(R(1), 1), halt()};
    struct pru_core *c = core_with(PRU_SOC_AM335X, w, 3);
    ck_assert_int_eq(pru_run_until_cycle(c, 100), PRU_STOP_LIMIT);
    ck_assert_int_eq(pru_cycles(c), 100);
    pru_host_write32(c, AM335X + 0x22000, PRU_CTRL_ENABLE | 1u); /* SLEEPING = 0 */
    ck_assert_int_eq(pru_run(c, 100), PRU_STOP_HALT);
    ck_assert_uint_eq(pru_reg(c, 1), 1);
    ck_assert_int_eq(pru_cycles(c), 102);
    pru_core_free(c);
}
END_TEST

/* R31 write (bit 5 + channel 3) -> system event 19 -> channel 1 -> host 1 -> R31[31]. */
START_TEST(r31_event_to_host_interrupt) {
    const uint32_t w[] = {ldi(R(1), 0), ldi(B0(31), 0x23), qbi(PRU_OP_QBBC, 0, R(31), 31), halt()};
    struct pru_core *c = pru_core_new(PRU_SOC_AM335X, NULL);
    pru_load_image(c, w, sizeof w);
    uint32_t intc = AM335X + 0x20000;
    pru_host_write32(c, intc + 0x10, 1);         /* GER */
    pru_host_write32(c, intc + 0x28, 19);        /* EISR */
    pru_host_write32(c, intc + 0x410, 1u << 24); /* CMR4 byte 3: event 19 -> channel 1 */
    pru_host_write32(c, intc + 0x800, 1u << 8);  /* HMR0 byte 1: channel 1 -> host 1 */
    pru_host_write32(c, intc + 0x34, 1);         /* HIEISR host 1 */
    pru_start(c);
    ck_assert_int_eq(pru_run(c, 100), PRU_STOP_HALT);
    ck_assert_int_eq(pru_cycles(c), 4);
    ck_assert_uint_eq(pru_reg(c, 31) >> 30, 2);
    uint32_t v;
    pru_host_read32(c, intc + 0x200, &v);
    ck_assert_uint_eq(v, 1u << 19);
    pru_host_write32(c, intc + 0x280, 1u << 19); /* SECR clears */
    ck_assert_uint_eq(pru_reg(c, 31) >> 30, 0);
    pru_core_free(c);
}
END_TEST

/* A system-bus RAM window: C31 = DDR, load cost load_ext_cycles. */
START_TEST(external_window) {
    const uint32_t w[] = {burst(PRU_OP_LBCO, 4 * 2, 31, 4, 8), alui(PRU_OP_ADD, R(2), R(2), 1),
                          burst(PRU_OP_SBCO, 4 * 2, 31, 0, 4), halt()};
    struct pru_core *c = pru_core_new(PRU_SOC_AM335X, NULL);
    ck_assert_int_eq(pru_map_ext(c, 0x80000000u, 4096), 0);
    ck_assert_int_eq(pru_map_ext(c, 0x80000800u, 4096), -1); /* overlap */
    ck_assert_int_eq(pru_map_ext(c, 0x1000u, 4096), -1);     /* local space */
    pru_load_image(c, w, sizeof w);
    pru_host_write32(c, 0x80000004u, 41);
    pru_host_write32(c, 0x80000008u, 7);
    pru_start(c);
    ck_assert_int_eq(pru_run(c, 1000), PRU_STOP_HALT);
    ck_assert_int_eq(pru_cycles(c), 37 + 1 + 1 + 1);
    uint32_t v;
    ck_assert_int_eq(pru_host_read32(c, 0x80000000u, &v), 0);
    ck_assert_uint_eq(v, 42);
    ck_assert_uint_eq(pru_reg(c, 3), 7);
    ck_assert_int_eq(pru_host_read32(c, 0x80001000u, &v), -1);
    pru_core_free(c);
}
END_TEST

START_TEST(run_until_time_and_cycle) {
    const uint32_t w[] = {qba(0)};
    struct pru_core *c = core_with(PRU_SOC_AM335X, w, 1);
    ck_assert_int_eq(pru_run_until_time(c, 12345), PRU_STOP_LIMIT);
    ck_assert_int_eq(pru_cycles(c), 3); /* cycles starting before 12345 ps */
    ck_assert_int_eq(pru_time_ps(c), 15000);
    ck_assert_int_eq(pru_run_until_cycle(c, 10), PRU_STOP_LIMIT);
    ck_assert_uint_eq(pru_instructions(c), 10);
    ck_assert_int_eq(pru_step(c), PRU_STOP_STEP);
    ck_assert_int_eq(pru_cycles(c), 11);
    pru_core_free(c);
}
END_TEST

/* wbc-style poll on a pin: fast-forward gives the same cycle as stepping. */
START_TEST(pin_poll_fast_forward) {
    int64_t cyc[2];
    for (int ff = 0; ff < 2; ff++) {
        struct pru_params p;
        pru_params_default(&p);
        p.fast_forward = ff;
        struct rec r = {.t_high = 1234567891};
        struct pru_pins pins = {.ctx = &r,
                                .inputs_at = rec_in,
                                .next_input_change = rec_next,
                                .outputs_changed = rec_out};
        const uint32_t w[] = {ldi(R(1), 0), alui(PRU_OP_ADD, R(2), R(2), 0),
                              qbi(PRU_OP_QBBC, -1, R(31), 3), alu(PRU_OP_OR, R(3), R(31), R(31)),
                              halt()};
        struct pru_core *c = pru_core_new(PRU_SOC_AM335X, &p);
        pru_load_image(c, w, sizeof w);
        pru_set_pins(c, &pins);
        pru_start(c);
        ck_assert_int_eq(pru_run(c, 1000000), PRU_STOP_HALT);
        cyc[ff] = pru_cycles(c);
        ck_assert_uint_eq(pru_reg(c, 3), 8);
        ck_assert_uint_eq(pru_instructions(c), (uint64_t)pru_cycles(c));
        if (ff)
            ck_assert_uint_gt(pru_ff_skipped(c), 100000);
        pru_core_free(c);
    }
    ck_assert_int_eq(cyc[0], cyc[1]);
    /* visible from cycle ceil((t_high + 10000) / 5000) = 246916; the poll
     * reads at odd cycles 2, 4, ... (2-cycle loop from cycle 1) */
    ck_assert_int_ge(cyc[0], 246916 + 3);
    ck_assert_int_le(cyc[0], 246916 + 4);
}
END_TEST

Suite *sys_suite(void) {
    Suite *s = suite_create("core_sys");
    TCase *t = tcase_create("memmap");
    tcase_add_test(t, memmap_am335x);
    tcase_add_test(t, memmap_am437x);
    tcase_add_test(t, external_window);
    suite_add_tcase(s, t);
    t = tcase_create("ctrl");
    tcase_add_test(t, control_start_reset_pc_halt);
    tcase_add_test(t, control_single_step);
    tcase_add_test(t, cycle_and_stall);
    tcase_add_test(t, cycle_saturates);
    tcase_add_test(t, faults);
    suite_add_tcase(s, t);
    t = tcase_create("pins");
    tcase_add_test(t, r30_outputs_with_time);
    tcase_add_test(t, slp_wakeup_and_input_delay);
    tcase_add_test(t, slp_woken_by_host);
    tcase_add_test(t, r31_event_to_host_interrupt);
    tcase_add_test(t, run_until_time_and_cycle);
    tcase_add_test(t, pin_poll_fast_forward);
    tcase_add_test(t, store_watch_sees_covering_stores);
    suite_add_tcase(s, t);
    return s;
}

int main(void) {
    return check_run(sys_suite());
}
