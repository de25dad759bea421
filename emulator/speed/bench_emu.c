/*
 * pru-bench-emu - simulated PRU cycles per host second for three loops:
 *   (a) ALU and branch, (b) load/store to data RAM, (c) polling a GPI
 *   shift-mode input fed by a 100 kHz square wave (with and without
 *   fast-forward). Real time is 200 M cycles per second.
 *
 * usage: pru-bench-emu [SECONDS_OF_SIMULATED_TIME]   (default 1)
 */
#include "pru_core.h"
#include "pru_isa.h"

#include <stdlib.h>
#include <time.h>

#define REAL_HZ 200e6

static uint32_t enc(struct pru_insn in) {
    return pru_encode(&in);
}

static uint32_t alu(int op, unsigned d, unsigned s1, unsigned s2) {
    return enc((struct pru_insn){.op = (uint8_t)op,
                                 .rd = (uint8_t)d,
                                 .rdsel = 7,
                                 .rs1 = (uint8_t)s1,
                                 .rs1sel = 7,
                                 .rs2 = (uint8_t)s2,
                                 .rs2sel = 7});
}

static uint32_t alui(int op, unsigned d, unsigned s1, unsigned imm) {
    return enc((struct pru_insn){.op = (uint8_t)op,
                                 .rd = (uint8_t)d,
                                 .rdsel = 7,
                                 .rs1 = (uint8_t)s1,
                                 .rs1sel = 7,
                                 .io = 1,
                                 .imm = (uint16_t)imm});
}

static uint32_t qb(int op, int off, unsigned s1, unsigned imm) {
    return enc((struct pru_insn){.op = (uint8_t)op,
                                 .broff = (int16_t)off,
                                 .rs1 = (uint8_t)s1,
                                 .rs1sel = 7,
                                 .io = 1,
                                 .imm = (uint16_t)imm});
}

static uint32_t burst(int op, unsigned rx, unsigned base, unsigned off, unsigned bytes) {
    return enc((struct pru_insn){.op = (uint8_t)op,
                                 .rx = (uint8_t)rx,
                                 .base = (uint8_t)base,
                                 .io = 1,
                                 .imm = (uint16_t)off,
                                 .len = (uint8_t)(bytes - 1)});
}

static uint32_t ldi(unsigned d, unsigned sel, unsigned imm) {
    return enc((struct pru_insn){
        .op = PRU_OP_LDI, .rd = (uint8_t)d, .rdsel = (uint8_t)sel, .imm = (uint16_t)imm});
}

/* square wave on input bit 0: toggles every half period */
#define HALF_PS 5000000LL

static uint32_t sq_in(void *ctx, int64_t t) {
    (void)ctx;
    return (uint32_t)((t / HALF_PS) & 1);
}

static int64_t sq_next(void *ctx, int64_t t) {
    (void)ctx;
    return (t / HALF_PS + 1) * HALF_PS;
}

static double now_s(void) {
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + (double)ts.tv_nsec * 1e-9;
}

static void bench(const char *name, const uint32_t *w, size_t n, int64_t cycles, int shift,
                  int ff) {
    struct pru_params p;
    pru_params_default(&p);
    p.fast_forward = ff;
    struct pru_core *c = pru_core_new(PRU_SOC_AM335X, &p);
    if (!c || pru_load_image(c, w, n * 4) != 0) {
        fprintf(stderr, "pru-bench-emu: setup failed\n");
        exit(1);
    }
    struct pru_pins pins = {.inputs_at = sq_in, .next_input_change = sq_next};
    if (shift)
        pru_set_pins(c, &pins);
    pru_start(c);
    double t0 = now_s();
    enum pru_stop st = pru_run_until_cycle(c, cycles);
    double dt = now_s() - t0;
    if (st != PRU_STOP_LIMIT) {
        pru_print_fault(c, stderr);
        exit(1);
    }
    double rate = (double)pru_cycles(c) / dt;
    printf("%-34s %12.0f cycles/s  %7.2fx real time  (%lld cycles, %llu instructions, "
           "%.3f s)\n",
           name, rate, rate / REAL_HZ, (long long)pru_cycles(c),
           (unsigned long long)pru_instructions(c), dt);
    pru_core_free(c);
}

int main(int argc, char **argv) {
    double sim_s = argc > 1 ? atof(argv[1]) : 1.0;
    if (sim_s <= 0 || sim_s > 100) {
        fprintf(stderr, "usage: pru-bench-emu [SECONDS_OF_SIMULATED_TIME (0..100]]\n");
        return 1;
    }
    int64_t cycles = (int64_t)(sim_s * REAL_HZ);

    /* (a) ALU/branch: 5 instructions, 5 cycles per iteration */
    const uint32_t a[] = {
        alu(PRU_OP_ADD, 2, 2, 1),  alu(PRU_OP_XOR, 3, 3, 2),  alui(PRU_OP_LSL, 4, 3, 1),
        alui(PRU_OP_ADD, 1, 1, 1), qb(PRU_OP_QBNE, -4, 1, 0), qb(PRU_OP_QBA, -5, 0, 0),
    };
    bench("(a) ALU/branch loop", a, sizeof a / 4, cycles, 0, 1);

    /* (b) load/store: lbbo (3) + add + sbbo (1) + add + and + qba = 8 cycles */
    const uint32_t b[] = {
        burst(PRU_OP_LBBO, 5, 2, 0, 4), alui(PRU_OP_ADD, 5, 5, 1),
        burst(PRU_OP_SBBO, 5, 2, 0, 4), alui(PRU_OP_ADD, 2, 2, 4),
        alui(PRU_OP_AND, 2, 2, 0xff),   qb(PRU_OP_QBA, -5, 0, 0),
    };
    bench("(b) load/store loop", b, sizeof b / 4, cycles, 0, 1);

    /* (c) shift mode 8 MHz (codes 8, 8): wait for the start bit, clear it
     * through GPCFG0 bit 13, count, repeat */
    const uint32_t cw[] = {
        ldi(1, 6, 0),
        ldi(1, 4, 2u | 8u << 3 | 8u << 8),
        burst(PRU_OP_SBCO, 1, 4, 8, 4),
        alui(PRU_OP_SET, 6, 1, 13),
        qb(PRU_OP_QBBC, 0, 31, 29), /* wbs r31.t29 */
        burst(PRU_OP_SBCO, 6, 4, 8, 4),
        alui(PRU_OP_ADD, 9, 9, 1),
        qb(PRU_OP_QBA, -3, 0, 0),
    };
    bench("(c) shift-mode poll, fast-forward", cw, sizeof cw / 4, cycles, 1, 1);
    bench("(c) shift-mode poll, no fast-fwd", cw, sizeof cw / 4, cycles / 10, 1, 0);
    return 0;
}
