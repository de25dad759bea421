/* sim_encoder.c - the encoder firmware on PRU1 as the slave end (sim_encoder.h). */
#include "sim_encoder.h"

#include "biss/biss_slave_shm.h"

#include <inttypes.h>
#include <stdio.h>

int sim_encoder_start(struct sim_encoder *e, struct bench *b, const void *image, size_t bytes,
                      const biss_chain_cfg *chain, char *err, size_t errlen) {
    struct pru_core *core = bench_encoder_core(b);
    e->b = b;
    if (!core) {
        snprintf(err, errlen, "the bench has no encoder core");
        return -1;
    }
    if (pru_load_image(core, image, bytes) != 0) {
        snprintf(err, errlen, "the encoder image (%zu bytes) does not fit PRU1's IRAM", bytes);
        return -1;
    }
    slave_fw_ram_init(&e->ram, core, bench_config(b)->soc, 1);
    e->io = slave_fw_io(&e->ram);
    pru_start(core);
    /* its start-up clears its status and says which PRU and MA bit */
    int64_t t = pru_time_ps(bench_core(b));
    bench_run_until(b, t + 5 * SIM_PS_PER_US);
    struct biss_slv_status st;
    if (biss_proto_encoder_status(&e->io, &st) != 0 || st.magic != BISS_SLV_MAGIC) {
        snprintf(err, errlen,
                 "the encoder image did not start (no BISS_SLV_MAGIC): not "
                 "biss_encoder_pru1.bin?");
        return -1;
    }
    if (st.pru != 1) {
        snprintf(err, errlen,
                 "the encoder image was assembled for PRU%" PRIu32
                 ", not PRU1 (biss_encoder_pru1.bin)",
                 st.pru);
        return -1;
    }
    if (bench_set_encoder_ma_bit(b, st.ma_bit) != 0) {
        snprintf(err, errlen, "the encoder image takes MA on R31 bit %u: not an input", st.ma_bit);
        return -1;
    }
    if (slave_fw_load(&e->io, chain, err, errlen) != 0) {
        return -1;
    }
    uint32_t seq = 0;
    biss_proto_encoder_seq_get(&e->io, &seq);
    for (int i = 0; i < 100; i++) {
        t = pru_time_ps(bench_core(b));
        bench_run_until(b, t + 10 * SIM_PS_PER_US);
        if (biss_proto_encoder_status(&e->io, &st) == 0 && st.cfg_ack == seq) {
            if (st.cfg_error) {
                snprintf(err, errlen, "the encoder firmware refused the chain: %s",
                         biss_encoder_cfg_error_text(st.cfg_error));
                return -1;
            }
            return 0;
        }
    }
    snprintf(err, errlen, "the encoder firmware did not take its configuration in 1 ms");
    return -1;
}

/* Bytes of the register files (0x40..0x7F and every bank) in which the
 * firmware's differ from the model's, which took the same control frames;
 * -1 when they cannot be read. */
static long regs_differ(const struct sim_encoder *e, const link_model *l) {
    long n = 0;
    unsigned bank0 = 0;
    for (unsigned i = 0; i < l->sc.biss.n; i++) {
        const regfile *m = &link_biss((link_model *)l)->cfg.s[i].regs;
        struct biss_slv_regs fw;
        if (biss_proto_encoder_regs_get(&e->io, i, &fw) != 0) {
            return -1;
        }
        for (unsigned a = 0; a < 64; a++) {
            n += fw.direct[a] != m->direct[a];
        }
        for (unsigned b = 0; b < m->nbanks; b++) {
            uint8_t bank[BISS_SLV_BANK_SIZE];
            if (biss_proto_encoder_bank_get(&e->io, bank0 + b, bank) != 0) {
                return -1;
            }
            for (unsigned a = 0; a < 64; a++) {
                n += bank[a] != m->bank[b][a];
            }
        }
        bank0 += m->nbanks;
    }
    return n;
}

int sim_encoder_report(const struct sim_encoder *e, cJSON *j) {
    struct biss_slv_status st = {0};
    int io = biss_proto_encoder_status(&e->io, &st);
    const link_model *l = bench_link(e->b);
    long regs = regs_differ(e, l);
    bool ok = io == 0 && st.magic == BISS_SLV_MAGIC && l->ext_differ == 0 && regs == 0;
    double first_us = l->ext_differ ? (double)l->ext_first_differ / SIM_PS_PER_US : -1;
    if (j) {
        cJSON *o = cJSON_AddObjectToObject(j, "encoder");
        cJSON_AddStringToObject(o, "where", "PRU1 (pru_slave/ firmware)");
        cJSON_AddNumberToObject(o, "ma_bit", st.ma_bit);
        cJSON_AddNumberToObject(o, "frames", st.frames);
        cJSON_AddNumberToObject(o, "latches", st.latches);
        cJSON_AddNumberToObject(o, "cd_frames", st.cd_frames);
        cJSON_AddNumberToObject(o, "model_frames", (double)link_frames(l));
        cJSON_AddNumberToObject(o, "sl_compared", (double)l->ext_compared);
        cJSON_AddNumberToObject(o, "sl_differ", (double)l->ext_differ);
        cJSON_AddNumberToObject(o, "sl_first_differ_us", first_us);
        cJSON_AddNumberToObject(o, "register_bytes_differ", (double)regs);
        cJSON_AddNumberToObject(o, "timeout_ns", st.timeout * 5.0);
        cJSON_AddNumberToObject(o, "period_ns", st.period * 5.0);
        cJSON_AddNumberToObject(o, "work_cycles", st.work);
        cJSON_AddNumberToObject(o, "work_pad_cycles", st.work_pad);
        cJSON_AddNumberToObject(o, "cancels", st.cancels);
        cJSON_AddNumberToObject(o, "header_crc_errors", st.hdr_crc_errors);
        cJSON *sl = cJSON_AddArrayToObject(o, "slaves");
        for (unsigned i = 0; i < l->sc.biss.n; i++) {
            const struct biss_slv_slave_status *s = &st.slave[i];
            cJSON *x = cJSON_CreateObject();
            cJSON_AddNumberToObject(x, "reads", s->reads);
            cJSON_AddNumberToObject(x, "writes", s->writes);
            cJSON_AddNumberToObject(x, "refused", s->refused);
            cJSON_AddNumberToObject(x, "write_crc_errors", s->crc_errors);
            cJSON_AddNumberToObject(x, "commands", s->commands);
            cJSON_AddNumberToObject(x, "dropped", s->dropped);
            cJSON_AddItemToArray(sl, x);
        }
    } else {
        printf("encoder (PRU1)       %" PRIu32 " frames begun, %" PRIu32 " latched, %" PRIu32
               " with a CDM (the model beside it: %" PRIu64 " frames)\n",
               st.frames, st.latches, st.cd_frames, link_frames(l));
        printf("encoder SL vs model  %" PRIu64 " rising MA edges compared, %" PRIu64 " differ%s\n",
               l->ext_compared, l->ext_differ, l->ext_differ ? "" : " (the same bits)");
        if (l->ext_differ) {
            printf("                     the first at %.3f us\n", first_us);
        }
        printf("encoder registers    %s\n",
               regs == 0  ? "the same as the model's (0x40..0x7F and every bank)"
               : regs < 0 ? "not read"
                          : "differ from the model's");
        if (regs > 0) {
            printf("                     in %ld bytes\n", regs);
        }
        printf("encoder timeout      %.0f ns after the ACK (the last frame's MA period %.0f ns)\n",
               st.timeout * 5.0, st.period * 5.0);
        printf("encoder work         at most %u cycles after a timeout (WORK_PAD %u; over it "
               "only after a frame the master ended inside the data, e.g. its training "
               "frame)\n",
               st.work, st.work_pad);
    }
    return ok ? 0 : 5;
}
