/* fw_timing.c - the clocked blocks stepped and timed (see fw_timing.h). */
#include "fw_timing.h"

#include "biss_proto.h"

#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define STEP_LIMIT  4000000 /* instructions per run: far more than any frame */
#define CFG_GPCFG0  0x08    /* CFG register: GPI mode (0: direct) */
#define SHORT_HALF  10      /* a switch cut short: both halves 1 + 0 + 9 cycles */
#define WRITES_KEEP 4       /* R30 writes remembered for a failure message */
#define TRAIL_CHARS 200

static const char *const end_labels[] = {"FINAL_PLAIN2", "FINAL_PLAIN", "FINAL_CRC2", "FINAL_CRC",
                                         "FRAME_END",    "TRAIN_DONE",  "NO_ACK",     "PROC_ERROR"};
#define N_END (sizeof(end_labels) / sizeof(end_labels[0]))

static void fail(char *err, size_t len, const char *fmt, ...) {
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(err, len, fmt, ap);
    va_end(ap);
}

static int need_label(const struct fw *f, const char *name, uint32_t *pc, char *err, size_t len) {
    int32_t a = fw_label_pc(&f->lst, name);
    if (a < 0) {
        fail(err, len,
             "label %s not found in pru_fw/biss_master.p (the timing test finds the "
             "clocked blocks by name)",
             name);
        return -1;
    }
    *pc = (uint32_t)a;
    return 0;
}

/* Whether word pc writes R30 (an ALU op or LDI with R30 as destination). */
static int writes_r30(const struct fw *f, uint32_t pc) {
    if (pc >= f->img.nwords || !f->ok[pc])
        return 0;
    const struct pru_insn *in = &f->dec[pc];
    unsigned fmt = pru_optable[in->op].fmt;
    return (fmt == PRU_FMT_ALU || fmt == PRU_FMT_LDI) && in->rd == 30;
}

static int is_cond_branch(const struct fw *f, uint32_t pc) {
    if (pc >= f->img.nwords || !f->ok[pc])
        return 0;
    unsigned fmt = pru_optable[f->dec[pc].op].fmt;
    return fmt == PRU_FMT_QB || fmt == PRU_FMT_QBB;
}

int fw_load(struct fw *f, const char *src_dir, const char *text, unsigned pru, char *err,
            size_t errlen) {
    memset(f, 0, sizeof(*f));
    char fw_dir[1024], path[1100], inc[1100];
    snprintf(fw_dir, sizeof(fw_dir), "%s/pru_fw", src_dir);
    snprintf(path, sizeof(path), "%s/biss_master.p", fw_dir);
    snprintf(inc, sizeof(inc), "%s/include/biss", src_dir);
    const char *dirs[] = {inc};
    const char *defs[] = {pru ? "PRU_NUM=1" : "PRU_NUM=0"};
    struct pruasm_options opt = {.core = 3,
                                 .include_dirs = dirs,
                                 .ninclude_dirs = 1,
                                 .defines = defs,
                                 .ndefines = 1,
                                 .want_listing = 1};
    struct pruasm_diag diag = {0};
    int rc = text ? pruasm_assemble_string(&opt, path, text, &f->img, &diag)
                  : pruasm_assemble_file(&opt, path, &f->img, &diag);
    if (rc != 0) {
        fail(err, errlen, "assembling %s: %s", path, diag.first_error);
        return -1;
    }
    if (!f->img.listing) {
        fail(err, errlen, "assembling %s: no listing", path);
        return -1;
    }
    if (fw_listing_parse(&f->lst, f->img.listing, f->img.nwords, fw_dir, text, err, errlen) != 0)
        return -1;
    f->dec = calloc(f->img.nwords, sizeof(*f->dec));
    f->ok = calloc(f->img.nwords, 1);
    if (!f->dec || !f->ok) {
        fail(err, errlen, "out of memory");
        return -1;
    }
    for (size_t i = 0; i < f->img.nwords; i++)
        f->ok[i] = pru_decode(f->img.words[i], &f->dec[i]) == 0;
    f->at = calloc(f->img.nwords, sizeof(*f->at));
    f->entry = calloc(f->img.nwords, 1);
    if (!f->at || !f->entry) {
        fail(err, errlen, "out of memory");
        return -1;
    }
    for (size_t i = 0; i < f->lst.nlabels; i++) {
        const struct fw_label *lb = &f->lst.labels[i];
        if (lb->pc >= f->img.nwords)
            continue;
        char *old = f->at[lb->pc];
        size_t n = (old ? strlen(old) + 1 : 0) + strlen(lb->base) + 1;
        char *names = malloc(n);
        if (!names) {
            fail(err, errlen, "out of memory");
            return -1;
        }
        snprintf(names, n, "%s%s%s", old ? old : "", old ? "/" : "", lb->base);
        free(old);
        f->at[lb->pc] = names;
        if (!lb->in_macro && strncmp(lb->name, "ENTRY_", 6) == 0)
            f->entry[lb->pc] = 1;
    }
    /* period 0 has no label of its own: its first instruction is the first
     * R30 write after FRAME_CLOCKED (what comes before it is the timestamp) */
    uint32_t clocked;
    if (need_label(f, "FRAME_CLOCKED", &clocked, err, errlen) != 0)
        return -1;
    for (f->lo = clocked; f->lo < f->img.nwords && !writes_r30(f, f->lo); f->lo++)
        ;
    f->hi = (uint32_t)f->img.nwords;
    for (size_t i = 0; i < 5; i++) { /* the FINAL_* and FRAME_END: after the clocked part */
        uint32_t a;
        if (need_label(f, end_labels[i], &a, err, errlen) != 0)
            return -1;
        if (a < f->hi)
            f->hi = a;
    }
    if (f->lo >= f->hi) {
        fail(err, errlen, "no R30 write between FRAME_CLOCKED and the end of the clocked part");
        return -1;
    }
    return 0;
}

void fw_free(struct fw *f) {
    for (size_t i = 0; f->at && i < f->img.nwords; i++)
        free(f->at[i]);
    free(f->at);
    free(f->entry);
    pruasm_image_free(&f->img);
    fw_listing_free(&f->lst);
    free(f->dec);
    free(f->ok);
    memset(f, 0, sizeof(*f));
}

/* ---- configuration ------------------------------------------------------ */

static uint32_t dram(const struct pru_core *c) {
    (void)c;
    return pru_soc_base(PRU_SOC_AM335X) + PRU_OFS_DRAM0;
}

/* The core's data RAM for the protocol layer (proto/biss_proto.h): the
 * configuration goes in and the verdict comes back as a host's would. */
static int io_read(void *ctx, uint32_t off, void *buf, size_t n) {
    struct pru_core *c = ctx;
    return pru_host_read(c, dram(c) + off, buf, n) ? BISS_E_IO : BISS_OK;
}

static int io_write(void *ctx, uint32_t off, const void *buf, size_t n) {
    struct pru_core *c = ctx;
    return pru_host_write(c, dram(c) + off, buf, n) ? BISS_E_IO : BISS_OK;
}

static struct biss_shm_status status_of(struct pru_core *c) {
    struct biss_proto_io io = {.read = io_read, .write = io_write, .ctx = c};
    struct biss_shm_status st;
    if (biss_proto_status_get(&io, &st) != BISS_OK)
        memset(&st, 0, sizeof st);
    return st;
}

/* A CRC polynomial (without its top term) that fits w bits. */
static uint16_t poly_for(unsigned w) {
    return w == 0 ? 0 : (uint16_t)((0x03u & ((1u << w) - 1u)) | 1u);
}

struct pru_core *fw_configure(const struct fw *f, const struct fw_config *cf, uint32_t *cfg_error,
                              char *err, size_t errlen) {
    struct pru_params p;
    pru_params_default(&p);
    p.fast_forward = 0; /* every instruction stepped as it is */
    p.gpi_delay_ps = 0; /* R31 shows what the run set for this period */
    struct pru_core *c = pru_core_new(PRU_SOC_AM335X, &p);
    if (!c) {
        fail(err, errlen, "pru_core_new failed");
        return NULL;
    }
    if (pru_load_image(c, f->img.words, f->img.nwords * 4) != 0) {
        fail(err, errlen, "image of %zu words does not fit IRAM", f->img.nwords);
        pru_core_free(c);
        return NULL;
    }
    /* the block proto encodes (the half period as given: it is what is
     * timed), then CFG_SEQ */
    struct biss_config bc;
    biss_config_default(&bc);
    bc.nslaves = cf->nslaves;
    bc.trigger = BISS_TRIGGER_HOST;
    bc.proc_limit = cf->proc_limit;
    bc.ssi_delay_ns = 150;
    for (unsigned i = 0; i < cf->nslaves && i < BISS_MAX_SLAVES; i++) {
        unsigned w = cf->s[i].w;
        bc.slave[i] = (struct biss_slave_config){
            .data_bits = cf->s[i].n,
            .crc_bits = w,
            .crc_poly = w ? (uint32_t)poly_for(w) | 1u << w : 0,
            .ssi = cf->ssi && i == 0,
        };
    }
    struct biss_shm_config blk;
    biss_config_encode_half(&bc, cf->half, &blk);
    uint32_t seq = 1;
    struct biss_proto_io io = {.read = io_read, .write = io_write, .ctx = c};
    if (biss_proto_config_put(&io, &blk, seq) != BISS_OK) {
        fail(err, errlen, "configuring H=%u: data RAM not writable", cf->half);
        goto out;
    }
    pru_set_inputs(c, 0x3fffffffu); /* SL high: idle */
    pru_start(c);
    uint32_t main_pc;
    if (need_label(f, "MAIN", &main_pc, err, errlen) != 0)
        goto out;
    for (long n = 0; n < STEP_LIMIT; n++) {
        /* start-up writes ~0 to ST_CFG_ACK first: acked once it names ours */
        if (pru_pc(c) == main_pc && status_of(c).cfg_ack == seq)
            break;
        if (pru_step(c) != PRU_STOP_STEP) {
            fail(err, errlen, "configuring H=%u: the core stopped at %#x", cf->half, pru_pc(c));
            goto out;
        }
    }
    if (pru_pc(c) != main_pc || status_of(c).cfg_ack != seq) {
        fail(err, errlen, "configuring H=%u: no ST_CFG_ACK / back in MAIN", cf->half);
        goto out;
    }
    uint32_t e = status_of(c).cfg_error;
    if (cfg_error)
        *cfg_error = e;
    if (e != BISS_CFGERR_NONE) {
        fail(err, errlen, "configuration with H=%u refused: BISS_CFGERR %u", cf->half, e);
        goto out;
    }
    /* R31 in direct mode: each period's samples are what the run sets */
    pru_host_write32(c, pru_soc_base(PRU_SOC_AM335X) + PRU_OFS_CFG + CFG_GPCFG0, 0);
    return c;
out:
    pru_core_free(c);
    return NULL;
}

/* ---- coverage ----------------------------------------------------------- */

void fw_cover_init(struct fw_cover *cv, const struct fw *f) {
    memset(cv, 0, sizeof(*cv));
    cv->seen = calloc(f->img.nwords, 1);
}

void fw_cover_free(struct fw_cover *cv) {
    free(cv->seen);
    memset(cv, 0, sizeof(*cv));
}

/* Whether word pc is a delay site's test: a quick branch on a field of r9
 * (the delay's entry r9.w0, or a switch's flag r9.b2) against 0. It goes
 * one way at a given H (r9.w0 is 0 exactly at H = 10), so each H covers one
 * way; the switch flag's both ways are required by the runs themselves
 * (switches cut short and full). */
static int is_delay_test(const struct fw *f, uint32_t pc) {
    const struct pru_insn *in = &f->dec[pc];
    return is_cond_branch(f, pc) && pru_optable[in->op].fmt == PRU_FMT_QB && in->rs1 == 9 &&
           in->io && in->imm == 0;
}

int fw_cover_check(const struct fw_cover *cv, const struct fw *f, unsigned half, char *err,
                   size_t errlen) {
    for (uint32_t pc = f->lo; pc < f->hi; pc++) {
        char where[400];
        const char *miss = NULL;
        /* at H = 10 no delay is called: the call after a delay test is not run */
        int delay_call = half == 10 && pc > f->lo && is_delay_test(f, pc - 1);
        int branch = is_cond_branch(f, pc) && !is_delay_test(f, pc);
        if (!(cv->seen[pc] & 1) && !delay_call)
            miss = "never executed";
        else if (branch && !(cv->seen[pc] & 2))
            miss = "a branch never taken";
        else if (branch && !(cv->seen[pc] & 4))
            miss = "a branch that never fell through";
        if (miss) {
            fw_describe_pc(&f->lst, pc, where, sizeof(where));
            fail(err, errlen,
                 "clocked code not covered by the timing runs (%u runs): %s, %s - add a run "
                 "that takes this path",
                 cv->runs, where, miss);
            return -1;
        }
    }
    return 0;
}

/* ---- a run -------------------------------------------------------------- */

struct write_rec {
    int64_t cycle;
    uint32_t pc;
    int edge;
    char trail[TRAIL_CHARS]; /* labels passed since the previous write */
};

struct run_state {
    const struct fw *f;
    unsigned half;
    struct write_rec w[WRITES_KEEP]; /* the last ones, by index % WRITES_KEEP */
    long nw;                         /* R30 writes so far */
    int64_t start;                   /* cycle of the first */
    long short_from;                 /* index of the first short half, -1 */
    char trail[TRAIL_CHARS];
    unsigned wa, sw; /* WA_TOP and START_WAIT periods seen */
    uint32_t lcg;
};

static void trail_add(struct run_state *s, const char *name) {
    size_t n = strlen(s->trail);
    if (n + strlen(name) + 4 < sizeof(s->trail))
        snprintf(s->trail + n, sizeof(s->trail) - n, "%s%s", n ? " > " : "", name);
}

/* "the half period from <pc a> to <pc b> (labels passed: ...)" */
static void describe_half(const struct run_state *s, const struct write_rec *a,
                          const struct write_rec *b, char *buf, size_t len) {
    char wa[400], wb[400];
    fw_describe_pc(&s->f->lst, a->pc, wa, sizeof(wa));
    fw_describe_pc(&s->f->lst, b->pc, wb, sizeof(wb));
    snprintf(buf, len, "from the R30 write at %s to the one at %s (labels passed: %s)", wa, wb,
             b->trail[0] ? b->trail : "none");
}

/* R31 for the period whose MA_FALL is at pc: what a slave shows then. */
static uint32_t period_inputs(struct run_state *s, const struct fw_run *r, uint32_t pc,
                              uint32_t wa_top, uint32_t sw_top, uint32_t cds) {
    const uint32_t high = 0x3fffffffu;
    if (pc == wa_top) {
        s->wa++;
        return s->wa == r->ack_at ? ((high & ~0xffu) | r->ack_pattern) : high;
    }
    if (pc == sw_top) {
        s->sw++;
        return s->sw > r->busy ? high : 0; /* busy reads 0, the start bit 1 */
    }
    if (pc >= cds && pc < s->f->hi) {
        s->lcg = s->lcg * 1103515245u + 12345u;
        return (s->lcg >> 16) & 1 ? high : 0;
    }
    return 0;
}

/* One R30 write (index s->nw) at cycle cyc. */
static int on_write(struct run_state *s, const struct fw_run *r, int64_t cyc, uint32_t pc, int edge,
                    char *err, size_t errlen) {
    struct write_rec *cur = &s->w[s->nw % WRITES_KEEP];
    cur->cycle = cyc;
    cur->pc = pc;
    cur->edge = edge;
    snprintf(cur->trail, sizeof(cur->trail), "%s", s->trail);
    s->trail[0] = '\0';
    if (s->nw == 0) {
        s->start = cyc;
        s->nw++;
        return 0;
    }
    const struct write_rec *prev = &s->w[(s->nw - 1) % WRITES_KEEP];
    int64_t d = cyc - prev->cycle;
    char half[1200];
    if (d != (int64_t)s->half) {
        /* The last slave's switch may be cut short (SWITCH_SHORT) when no
         * MA edge is left: both its halves 10 cycles, MA still. */
        int short_ok = r->chain_periods >= 0 && d == SHORT_HALF && !edge && !prev->edge &&
                       (s->short_from < 0 ? (s->nw % 2) == 1 : s->nw == s->short_from + 1);
        if (!short_ok) {
            describe_half(s, prev, cur, half, sizeof(half));
            fail(err, errlen,
                 "H=%u: R30 write %ld (%s) came %lld cycles after the previous one (%s), expected "
                 "H = %u (%s); the half period %s",
                 s->half, s->nw, edge ? "an MA edge" : "MA unchanged", (long long)d,
                 prev->edge ? "an MA edge" : "MA unchanged", s->half,
                 s->nw % 2 ? "MA falls at t = 0 and rises at t = H"
                           : "the next period starts 2H after the last",
                 half);
            return -1;
        }
        if (s->short_from < 0)
            s->short_from = s->nw;
    } else if (s->short_from >= 0) {
        describe_half(s, prev, cur, half, sizeof(half));
        fail(err, errlen,
             "H=%u: R30 write %ld: a period after a switch cut short (only the frame's last "
             "period may be): the half period %s",
             s->half, s->nw, half);
        return -1;
    }
    if (edge && s->short_from >= 0) {
        describe_half(s, prev, cur, half, sizeof(half));
        fail(err, errlen, "H=%u: an MA edge in a switch cut short: the half period %s", s->half,
             half);
        return -1;
    }
    s->nw++;
    return 0;
}

int fw_run(const struct fw *f, struct pru_core *c, const uint32_t regs[30], unsigned half,
           const struct fw_run *r, struct fw_cover *cv, char *err, size_t errlen) {
    uint32_t start, hook = 0, wa_top, sw_top, cds, ends[N_END];
    if (need_label(f, r->start, &start, err, errlen) != 0 ||
        (r->hook && need_label(f, r->hook, &hook, err, errlen) != 0) ||
        need_label(f, "WA_TOP", &wa_top, err, errlen) != 0 ||
        need_label(f, "SW_TOP", &sw_top, err, errlen) != 0 ||
        need_label(f, "CDS_PERIOD", &cds, err, errlen) != 0)
        return -1;
    for (size_t i = 0; i < N_END; i++)
        if (need_label(f, end_labels[i], &ends[i], err, errlen) != 0)
            return -1;
    for (unsigned i = 0; i < 30; i++)
        pru_set_reg(c, i, regs[i]);
    pru_set_reg(c, 12, r->start_r12);
    pru_set_reg(c, 30, pru_reg(c, 30) | FW_MA_MASK); /* MA idles high */
    pru_set_pc(c, start);
    pru_set_inputs(c, 0x3fffffffu);

    struct run_state s = {.f = f, .half = half, .short_from = -1, .lcg = r->seed};
    int hooked = r->hook == NULL;
    int64_t chain_at = -1;    /* cycle the slave chain was entered (first ENTRY_*) */
    const char *ended = NULL; /* where the clocked part ended */
    int64_t now = 0;          /* and when */
    long nw_end = 0;          /* R30 writes until then */
    struct write_rec last_end = {0};
    uint32_t frame_end = ends[4];
    long n;
    for (n = 0; n < STEP_LIMIT; n++) {
        uint32_t pc = pru_pc(c);
        if (!hooked && pc == hook) {
            /* r4.w0 the CDM edges, r4.w2 the ACK history sum (FRAME_REGS) */
            if (r->hsum >= 0)
                pru_set_reg(c, 4, (pru_reg(c, 4) & 0xffffu) | (uint32_t)r->hsum << 16);
            if (r->cdm >= 0)
                pru_set_reg(c, 4, (pru_reg(c, 4) & 0xffff0000u) | (uint32_t)r->cdm);
            hooked = 1;
        }
        if (s.nw > 0) {
            /* The FINAL_* code runs on to FRAME_END; FINAL_PLAIN2 and
             * FINAL_CRC2 write R30 first (the period after the switch). */
            if (ended && pc == frame_end)
                break;
            for (size_t i = 0; i < N_END && !ended; i++) {
                if (pc != ends[i])
                    continue;
                ended = end_labels[i];
                now = pru_cycles(c);
                nw_end = s.nw;
                last_end = s.w[(s.nw - 1) % WRITES_KEEP];
                if (pc == frame_end || i >= 5)
                    goto done;
            }
            if (f->entry[pc] && chain_at < 0)
                chain_at = pru_cycles(c);
            if (f->at[pc])
                trail_add(&s, f->at[pc]);
        }
        int64_t cyc = pru_cycles(c);
        int ma_before = (int)((pru_reg(c, 30) >> FW_MA_BIT) & 1);
        int wr = writes_r30(f, pc);
        if (pru_step(c) != PRU_STOP_STEP) {
            char where[400];
            fw_describe_pc(&f->lst, pc, where, sizeof(where));
            fail(err, errlen, "H=%u: the core stopped (fault or halt) at %s", half, where);
            return -1;
        }
        uint32_t next = pru_pc(c);
        if (pc >= f->lo && pc < f->hi) {
            cv->seen[pc] |= 1;
            if (is_cond_branch(f, pc))
                cv->seen[pc] |= next == pc + 1 ? 4 : 2;
        }
        if (wr) {
            int edge = (int)((pru_reg(c, 30) >> FW_MA_BIT) & 1) != ma_before;
            int rc = on_write(&s, r, cyc, pc, edge, err, errlen);
            if (rc != 0)
                return rc;
            if (s.nw % 2 == 1) /* a period's first write: its samples follow */
                pru_set_inputs(c, period_inputs(&s, r, pc, wa_top, sw_top, cds));
        }
    }
done:
    cv->runs++;
    const struct write_rec *last = &last_end;
    char where[400];
    fw_describe_pc(&f->lst, pru_pc(c), where, sizeof(where));
    int in_final = ended && strncmp(ended, "FINAL_", 6) == 0;
    if (!ended || (in_final && pru_pc(c) != frame_end)) {
        fail(err, errlen, "H=%u: no end of the clocked part after %ld instructions (now at %s)",
             half, n, where);
        return -1;
    }
    if (strcmp(ended, r->end) != 0) {
        fail(err, errlen, "H=%u: the clocked part ended at %s, expected %s (after %ld R30 writes)",
             half, ended, r->end, s.nw);
        return -1;
    }
    if (nw_end % 2 != 0) {
        fail(err, errlen, "H=%u: %s reached after %ld R30 writes: a period without its rising edge",
             half, ended, nw_end);
        return -1;
    }
    long final_writes = strcmp(ended, "FINAL_PLAIN2") == 0 || strcmp(ended, "FINAL_CRC2") == 0;
    if (s.nw - nw_end != final_writes) {
        fail(err, errlen, "H=%u: %ld R30 writes from %s to FRAME_END, expected %ld", half,
             s.nw - nw_end, ended, final_writes);
        return -1;
    }
    int64_t want;
    if (strcmp(ended, "NO_ACK") == 0 || strcmp(ended, "PROC_ERROR") == 0) {
        /* given up right after a rising edge; MA stays high */
        want = last->cycle + 2; /* the branch right after the rise */
        if (!((pru_reg(c, 30) >> FW_MA_BIT) & 1)) {
            fail(err, errlen, "H=%u: %s reached with MA low", half, ended);
            return -1;
        }
    } else if (s.short_from >= 0) {
        want = last->cycle + SHORT_HALF;
        cv->short_switches++;
    } else {
        want = s.start + (int64_t)nw_end * half;
        if (r->chain_periods >= 0)
            cv->full_switches++;
    }
    if (now != want) {
        fail(err, errlen,
             "H=%u: %s reached %lld cycles after the first R30 write, expected %lld (%ld "
             "writes): the period that ends there is miscounted, from the write at %s",
             half, ended, (long long)(now - s.start), (long long)(want - s.start), nw_end,
             (fw_describe_pc(&f->lst, last->pc, where, sizeof(where)), where));
        return -1;
    }
    if (r->chain_periods >= 0) {
        if (chain_at < 0) {
            fail(err, errlen, "H=%u: %s reached without passing an ENTRY_* label", half, ended);
            return -1;
        }
        int64_t periods = (now - chain_at + 2 * half - 1) / (2 * half);
        if (periods != r->chain_periods) {
            fail(err, errlen,
                 "H=%u: the slave chain took %lld periods (from its first ENTRY_* to %s), "
                 "expected %d",
                 half, (long long)periods, ended, r->chain_periods);
            return -1;
        }
    }
    return 0;
}
