/*
 * trace.c - one line per executed instruction: issue cycle, PC, the
 * instruction as pasm would write it, and every register it changed.
 */
#include "core_priv.h"

void trace_insn(struct pru_core *c, uint32_t pc, int64_t cycle, const uint32_t *before,
                int carry_before) {
    char text[96];
    pru_disasm(c->iram0[pc], pc, text, sizeof text);
    fprintf(c->trace, "%10lld  %04x  %-32s", (long long)cycle, pc, text);
    for (unsigned i = 0; i < 32; i++)
        if (c->r[i] != before[i])
            fprintf(c->trace, " r%u=0x%08x", i, c->r[i]);
    if (c->carry != carry_before)
        fprintf(c->trace, " c=%d", c->carry);
    if (c->fault.cause != PRU_FAULT_NONE)
        fprintf(c->trace, " FAULT");
    fputc('\n', c->trace);
}
