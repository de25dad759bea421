/* fw_cd.c - control communication on the bench (see fw_cd.h). */
#include "fw_cd.h"

#include "biss/biss_shm.h"

#include <string.h>

static uint32_t base(struct bench *b) {
    return pru_soc_base(bench_config(b)->soc);
}

void fw_cd_issue(struct fw_cd *cd, struct bench *b, const biss_cd_prog *p, uint16_t wait_limit) {
    static uint8_t dram[BISS_DRAM_BYTES];
    memset(cd, 0, sizeof(*cd));
    cd->b = b;
    cd->prog = p;
    struct pru_core *c = bench_core(b);
    pru_host_read(c, base(b), dram, sizeof dram);
    biss_cd_shm_put(p, wait_limit, dram, sizeof dram);
    pru_host_write(c, base(b) + BISS_CD_PROG, dram + BISS_CD_PROG, BISS_CD_PROG_BYTES);
    pru_host_write(c, base(b) + BISS_CD_STEPS, dram + BISS_CD_STEPS, 4); /* length, limit */
    pru_host_write(c, base(b) + BISS_CD_IDA_STEP, dram + BISS_CD_IDA_STEP, 4);
    pru_host_read(c, base(b) + BISS_CD_CMD, &cd->cmd, 4);
    cd->cmd++;
    pru_host_write(c, base(b) + BISS_CD_CMD, &cd->cmd, 4);
    cd->frame0 = link_frames(bench_link(b));
}

int fw_cd_poll(struct fw_cd *cd) {
    if (cd->done) {
        return 1;
    }
    static uint8_t dram[BISS_DRAM_BYTES];
    struct pru_core *c = bench_core(cd->b);
    uint32_t seq;
    pru_host_read(c, base(cd->b) + BISS_ST_CD_SEQ, &seq, 4);
    if (seq != cd->cmd) {
        return 0;
    }
    pru_host_read(c, base(cd->b), dram, sizeof dram);
    biss_cd_answer a;
    biss_cd_shm_get(dram, sizeof dram, &a);
    cd->err = biss_cd_parse(cd->prog, &a, &cd->result);
    cd->status = a.status;
    cd->frames = link_frames(bench_link(cd->b)) - cd->frame0;
    cd->done = 1;
    return 1;
}
