/*
 * test_fw_timing.c - the static timing proof of the firmware's clocked part
 * (issue 13 item 2): every clocked block and every path through it, at
 * H = 10, 15, 16, 20, 22, 25, 100 and 1024 (16..22: the bit-grid check's
 * short and shortest long tails), stepped in the emulator from the block's
 * label with R30 writes timed: exactly H between MA's falling and rising
 * edge, 2H per period (fw_timing.h says how, and what a failure names).
 *
 * H = 13 of the issue is no rate the firmware runs: the 8x shift clock
 * needs H = a * b with 2 <= a, b <= 32 (pru_fw/README.md "Rates"), and 13
 * is prime; the firmware refuses it (h13_refused below). 15 = 3 * 5 is the
 * nearest legal odd H and takes its place.
 *
 * Runs per H: frames of every slave shape the configuration makes (w >= 2,
 * w = 1, w = 0 with n >= 2, n = 1; last slaves with one or two bits read
 * after the switch, FINAL_*; chains of up to 8 slaves), each with ACKs in
 * different periods, line delays that leave the clocks running past the
 * last bit or stop them early (shortened switches), busy periods, CDS 0/1
 * and a CDM edge; a frame without ACK (NO_ACK), one whose start bit never
 * comes (PROC_ERROR), training frames, SSI frames. Afterwards every
 * instruction of the clocked part must have run and every conditional
 * branch in it gone both ways, so a new path without a run fails too.
 */
#include "biss/biss_shm.h"
#include "check_run.h"
#include "fw_timing.h"

#include <check.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const unsigned halves[] = {10, 15, 16, 20, 22, 25, 100, 128, 160, 1024};
#define N_HALVES (sizeof(halves) / sizeof(halves[0]))

static struct fw fw;
static char err[4096];

/* The tree whose pru_fw/ is proven: this one, or FW_TIMING_SRC_DIR (a
 * copy with a change to try). */
static const char *src_dir(void) {
    const char *d = getenv("FW_TIMING_SRC_DIR");
    return d && *d ? d : FW_SRC_DIR;
}

static void setup(void) {
    if (fw_load(&fw, src_dir(), NULL, 0, err, sizeof(err)) != 0)
        ck_abort_msg("%s", err);
}

static void teardown(void) {
    fw_free(&fw);
}

/* ---- what the configuration makes of a slave chain ----------------------- */

static unsigned total_bits(const struct fw_config *cf) {
    unsigned n = 0;
    for (unsigned i = 0; i < cf->nslaves; i++)
        n += cf->s[i].n + cf->s[i].w;
    return n;
}

/* The last slave's bits read after its switch (pru_fw/README.md "One
 * frame": its last one or two CRC bits, or data bits without CRC), and the
 * label the clocked part ends at. */
static unsigned final_bits(const struct fw_config *cf, const char **end) {
    const struct fw_slave *s = &cf->s[cf->nslaves - 1];
    if (s->w == 0) {
        *end = s->n == 1 ? "FRAME_END" : s->n == 2 ? "FINAL_PLAIN" : "FINAL_PLAIN2";
        return s->n == 1 ? 0 : s->n == 2 ? 1 : 2;
    }
    *end = s->w == 1 ? "FRAME_END" : s->w == 2 ? "FINAL_CRC" : "FINAL_CRC2";
    return s->w == 1 ? 0 : s->w == 2 ? 1 : 2;
}

static void describe_config(const struct fw_config *cf, char *buf, size_t len) {
    size_t n = (size_t)snprintf(buf, len, "%s[", cf->ssi ? "SSI " : "");
    for (unsigned i = 0; i < cf->nslaves && n < len; i++)
        n += (size_t)snprintf(buf + n, len - n, "%sn=%u w=%u", i ? " | " : "", cf->s[i].n,
                              cf->s[i].w);
    if (n < len)
        snprintf(buf + n, len - n, "]");
}

/* ---- the runs ------------------------------------------------------------- */

struct h_ctx {
    unsigned half;
    struct fw_cover cv;
};

/* Configures cf and runs each of runs[]; fails the test naming the run. */
static void run_config(struct h_ctx *h, const struct fw_config *cf, const struct fw_run *runs,
                       size_t nruns, const char *const *names) {
    char what[200];
    describe_config(cf, what, sizeof(what));
    struct pru_core *c = fw_configure(&fw, cf, NULL, err, sizeof(err));
    ck_assert_msg(c != NULL, "%s: %s", what, err);
    uint32_t regs[30];
    for (unsigned i = 0; i < 30; i++)
        regs[i] = pru_reg(c, i);
    regs[2] = 0; /* MAIN's trigger byte (r2.b3): the host's, as configured */
    for (size_t i = 0; i < nruns; i++) {
        int rc = fw_run(&fw, c, regs, h->half, &runs[i], &h->cv, err, sizeof(err));
        if (rc != 0) {
            pru_core_free(c);
            ck_abort_msg("timing: frame %s, run \"%s\": %s", what, names[i], err);
        }
    }
    pru_core_free(c);
}

/* Q' (8 x the ACK's period + the ones before its edge) for an ACK seen in
 * WA_TOP period a with pattern b0, and the history sum that makes the
 * averaged position put the first read m periods after the ACK's. */
static int64_t hsum_for(unsigned a, uint8_t pattern, int m) {
    unsigned b = pattern & (uint8_t)(pattern + 1), ones = 0;
    for (; b; b >>= 1)
        ones += b & 1;
    int64_t q = 8 * (int64_t)a + ones;
    int64_t want = 8 * ((int64_t)a + m) + 8; /* the 4-frame average */
    int64_t sum = 4 * want - q;
    return sum < 0 ? 0 : sum;
}

/* BiSS-C frames of one configuration: ACK period, line delay (the first
 * read m periods after the ACK's: clocks past the last bit, or stopped
 * early, none at all), busy periods, CDM. */
static void biss_frames(struct h_ctx *h, const struct fw_config *cf) {
    const char *end;
    unsigned f = final_bits(cf, &end);
    int n = (int)total_bits(cf);
    int chain = n - (int)f;
    uint32_t frame_set = (uint32_t)fw_label_pc(&fw.lst, "FRAME_SET");
    ck_assert_msg(fw_label_pc(&fw.lst, "FRAME_SET") >= 0, "label FRAME_SET not found");
    struct {
        unsigned ack_at;
        uint8_t pattern;
        int m;
        unsigned busy;
        int64_t cdm;
        const char *name;
    } v[] = {
        {3, 0x0f, -2, 0, 0, "ACK in WAIT_ACK period 3, no idle period, no busy"},
        {1, 0xf8, -1, 2, FW_MA_MASK << 8, "ACK in the first period, busy 2, CDM 1 if CDS 1"},
        {2, 0x0f, 1, 1, FW_MA_MASK, "one idle period or two, busy 1, CDM 1"},
        {2, 0x0f, 0, 0, FW_MA_MASK, "the usual line delay (m = 2), CDM 1"},
        {1, 0xf0, n - 2, 3, 0, "clocks stop two bits before the end"},
        {2, 0x0f, n + 2, 0, FW_MA_MASK, "no clock left after the start bit's"},
    };
    struct fw_run runs[sizeof(v) / sizeof(v[0])];
    const char *names[sizeof(v) / sizeof(v[0])];
    for (size_t i = 0; i < sizeof(v) / sizeof(v[0]); i++) {
        runs[i] = (struct fw_run){.start = "FRAME_REGS",
                                  .start_r12 = frame_set,
                                  .hook = "FRAME_SET",
                                  .hsum = hsum_for(v[i].ack_at, v[i].pattern, v[i].m),
                                  .cdm = v[i].cdm,
                                  .ack_at = v[i].ack_at,
                                  .ack_pattern = v[i].pattern,
                                  .busy = v[i].busy,
                                  .seed = 0x1234u + (uint32_t)i * 977u + (uint32_t)n,
                                  .end = end,
                                  .chain_periods = chain};
        names[i] = v[i].name;
    }
    run_config(h, cf, runs, sizeof(v) / sizeof(v[0]), names);
}

/* Frames that end before the data, and training frames. */
static void other_frames(struct h_ctx *h) {
    struct fw_config cf = {.half = h->half, .nslaves = 1, .s = {{12, 6}}, .proc_limit = 4};
    uint32_t frame_set = (uint32_t)fw_label_pc(&fw.lst, "FRAME_SET");
    struct fw_run runs[] = {
        {.start = "FRAME_REGS",
         .start_r12 = frame_set,
         .hsum = -1,
         .cdm = -1,
         .ack_at = FW_NEVER,
         .busy = 0,
         .end = "NO_ACK",
         .chain_periods = -1},
        {.start = "FRAME_REGS",
         .start_r12 = frame_set,
         .hook = "FRAME_SET",
         .hsum = hsum_for(2, 0x0f, 0),
         .cdm = -1,
         .ack_at = 2,
         .ack_pattern = 0x0f,
         .busy = FW_NEVER,
         .end = "PROC_ERROR",
         .chain_periods = -1},
        {.start = "TRAIN_GO",
         .hsum = -1,
         .cdm = -1,
         .ack_at = 1,
         .ack_pattern = 0x0f,
         .end = "TRAIN_DONE",
         .chain_periods = -1},
        {.start = "TRAIN_GO",
         .hsum = -1,
         .cdm = -1,
         .ack_at = 4,
         .ack_pattern = 0xfc,
         .end = "TRAIN_DONE",
         .chain_periods = -1},
    };
    const char *names[] = {"no ACK within the limit", "start bit never comes (busy over the limit)",
                           "training, ACK at once", "training, ACK after the clocks stopped"};
    run_config(h, &cf, runs, sizeof(runs) / sizeof(runs[0]), names);
}

/* SSI frames: the idle periods (LAG_TOP, SSI_LAG_LAST), then the word. */
static void ssi_frames(struct h_ctx *h) {
    static const unsigned bits[] = {1, 2, 3, 4, 13, 64};
    for (size_t i = 0; i < sizeof(bits) / sizeof(bits[0]); i++) {
        struct fw_config cf = {
            .half = h->half, .nslaves = 1, .s = {{bits[i], 0}}, .ssi = 1, .proc_limit = 4};
        const char *end;
        unsigned f = final_bits(&cf, &end);
        struct fw_run run = {.start = "SSI_FRAME",
                             .hsum = -1,
                             .cdm = -1,
                             .ack_at = FW_NEVER,
                             .seed = 99u + bits[i],
                             .end = end,
                             .chain_periods = (int)(bits[i] - f)};
        const char *name = "SSI word";
        run_config(h, &cf, &run, 1, &name);
    }
}

static const struct fw_slave chains[][8] = {
    /* middle slaves of every shape, last ones of every kind */
    {{3, 3}, {2, 1}, {3, 0}, {1, 0}, {4, 4}},
    {{1, 0}, {3, 0}, {2, 1}, {3, 3}, {5, 0}},
    {{2, 2}, {1, 0}, {2, 1}},
    {{1, 1}, {2, 0}},
    {{12, 6}, {12, 6}, {12, 6}},
    {{1, 0}, {1, 0}, {1, 0}, {1, 0}, {1, 0}, {1, 0}, {1, 0}, {1, 0}},
};
static const unsigned chain_len[] = {5, 5, 3, 2, 3, 8};

START_TEST(clocked_blocks) {
    struct h_ctx h = {.half = halves[_i]};
    fw_cover_init(&h.cv, &fw);
    /* one slave of every shape the configuration distinguishes */
    static const unsigned ns[] = {1, 2, 3, 4, 5}, ws[] = {0, 1, 2, 3, 4, 5};
    for (size_t a = 0; a < sizeof(ns) / sizeof(ns[0]); a++)
        for (size_t b = 0; b < sizeof(ws) / sizeof(ws[0]); b++) {
            struct fw_config cf = {
                .half = h.half, .nslaves = 1, .s = {{ns[a], ws[b]}}, .proc_limit = 4};
            biss_frames(&h, &cf);
        }
    struct fw_config wide = {.half = h.half, .nslaves = 1, .s = {{64, 16}}, .proc_limit = 4};
    biss_frames(&h, &wide);
    for (size_t i = 0; i < sizeof(chain_len) / sizeof(chain_len[0]); i++) {
        struct fw_config cf = {.half = h.half, .nslaves = chain_len[i], .proc_limit = 4};
        memcpy(cf.s, chains[i], sizeof(cf.s));
        biss_frames(&h, &cf);
    }
    other_frames(&h);
    ssi_frames(&h);
    int rc = fw_cover_check(&h.cv, &fw, h.half, err, sizeof(err));
    unsigned shortened = h.cv.short_switches, full = h.cv.full_switches;
    fw_cover_free(&h.cv);
    ck_assert_msg(rc == 0, "H=%u: %s", h.half, err);
    if (h.half > BISS_CUT_MAX_HALF) /* the last period keeps its tails (POST_MIN) */
        ck_assert_msg(shortened == 0 && full > 0,
                      "H=%u: switches cut short %u, full %u: none may be", h.half, shortened, full);
    else if (h.half != 10) /* at H = 10 a shortened switch is no shorter */
        ck_assert_msg(shortened > 0 && full > 0,
                      "H=%u: switches cut short %u, full %u: both must be run", h.half, shortened,
                      full);
}
END_TEST

/* H = 13 (the odd value) is refused; 15, its stand-in, is taken. */
START_TEST(h13_refused) {
    struct fw_config cf = {.half = 13, .nslaves = 1, .s = {{12, 6}}, .proc_limit = 4};
    uint32_t e = 0;
    struct pru_core *c = fw_configure(&fw, &cf, &e, err, sizeof(err));
    ck_assert_msg(c == NULL && e == 2, "H=13: expected BISS_CFGERR_HALF, got %u", e);
    cf.half = 15;
    c = fw_configure(&fw, &cf, &e, err, sizeof(err));
    ck_assert_msg(c != NULL, "H=15: %s", err);
    pru_core_free(c);
}
END_TEST

/* ---- the proof can fail: one extra cycle in a block is found and named ---- */

static char *read_text(const char *path) {
    FILE *f = fopen(path, "rb");
    ck_assert_msg(f != NULL, "%s: cannot open", path);
    fseek(f, 0, SEEK_END);
    long n = ftell(f);
    fseek(f, 0, SEEK_SET);
    char *t = malloc((size_t)n + 1);
    ck_assert_ptr_nonnull(t);
    ck_assert_int_eq(fread(t, 1, (size_t)n, f), (size_t)n);
    t[n] = '\0';
    fclose(f);
    return t;
}

/* text with `insert` added after the line that is exactly `line` (spaces
 * around it ignored); NULL if there is none. */
static char *insert_after_line(const char *text, const char *line, const char *insert) {
    size_t ll = strlen(line);
    for (const char *p = text; *p;) {
        const char *eol = strchr(p, '\n');
        const char *s = p;
        while (*s == ' ')
            s++;
        if (strncmp(s, line, ll) == 0 && (s[ll] == '\n' || s[ll] == ' ' || s[ll] == '\0')) {
            size_t head = (size_t)((eol ? eol + 1 : s + ll) - text);
            char *out = malloc(strlen(text) + strlen(insert) + 2);
            memcpy(out, text, head);
            strcpy(out + head, insert);
            strcat(out, eol ? eol + 1 : "");
            return out;
        }
        if (!eol)
            break;
        p = eol + 1;
    }
    return NULL;
}

/* The text of pru_fw/<name> with every `#include "x"` of a file of pru_fw/
 * (its parts, pru_fw/README.md) replaced by that file's text, recursively;
 * other includes (include/biss) are left as they are. */
static char *flattened(const char *name, unsigned depth) {
    ck_assert_msg(depth < 8, "pru_fw/%s: includes nested too deep", name);
    char path[1024];
    snprintf(path, sizeof(path), "%s/pru_fw/%s", src_dir(), name);
    char *text = read_text(path);
    for (;;) {
        char *inc = strstr(text, "#include \"");
        char part[128] = "";
        while (inc) {
            const char *q = strchr(inc + 10, '"');
            size_t n = q ? (size_t)(q - (inc + 10)) : 0;
            if (q && n < sizeof(part) && !memchr(inc + 10, '/', n)) {
                memcpy(part, inc + 10, n);
                part[n] = '\0';
                break;
            }
            inc = strstr(inc + 10, "#include \"");
        }
        if (!inc)
            return text;
        char *body = flattened(part, depth + 1);
        const char *after = strchr(inc, '\n');
        char *out = malloc(strlen(text) + strlen(body) + 2);
        memcpy(out, text, (size_t)(inc - text));
        strcpy(out + (inc - text), body);
        strcat(out, after ? after : "");
        free(body);
        free(text);
        text = out;
    }
}

/* biss_master.p with its parts inlined (so that a mutation of any of them is
 * assembled from memory, the tree left alone) and `insert` after `line`. */
static char *mutated_source(const char *line, const char *insert) {
    char *flat = flattened("biss_master.p", 0);
    char *out = insert_after_line(flat, line, insert);
    ck_assert_msg(out != NULL, "no line `%s` in the firmware to mutate", line);
    free(flat);
    return out;
}

static const struct {
    const char *line;  /* insert one cycle after this line */
    const char *named; /* the failure must name it */
    unsigned n, w;     /* a slave whose frame passes that way */
} mutations[] = {
    {"DP_TOP:", "DP_TOP", 3, 3},           /* DATA_PERIOD, biss_periods.hp */
    {"CP_TOP:", "CP_TOP", 3, 5},           /* CRC_PERIOD */
    {"WA_TOP:", "WA_TOP", 3, 3},           /* WAIT_ACK, frame.p */
    {"START_FOUND:", "START_FOUND", 2, 0}, /* the start bit's period */
    {"FINAL_CRC2:", "FINAL_CRC2", 3, 4},   /* its MA edge after the last switch */
};

START_TEST(extra_cycle_is_named) {
    char *src = mutated_source(mutations[_i].line, "    mov     r0, r0\n");
    struct fw bad;
    int rc = fw_load(&bad, src_dir(), src, 0, err, sizeof(err));
    free(src);
    ck_assert_msg(rc == 0, "%s", err);
    struct fw_config cf = {
        .half = 25, .nslaves = 1, .s = {{mutations[_i].n, mutations[_i].w}}, .proc_limit = 4};
    struct pru_core *c = fw_configure(&bad, &cf, NULL, err, sizeof(err));
    ck_assert_msg(c != NULL, "%s", err);
    uint32_t regs[30];
    for (unsigned i = 0; i < 30; i++)
        regs[i] = pru_reg(c, i);
    regs[2] = 0; /* MAIN's trigger byte (r2.b3): the host's, as configured */
    const char *end;
    unsigned f = final_bits(&cf, &end);
    struct fw_run run = {.start = "FRAME_REGS",
                         .start_r12 = (uint32_t)fw_label_pc(&bad.lst, "FRAME_SET"),
                         .hook = "FRAME_SET",
                         .hsum = hsum_for(2, 0x0f, 0),
                         .cdm = 0,
                         .ack_at = 2,
                         .ack_pattern = 0x0f,
                         .busy = 1,
                         .seed = 7,
                         .end = end,
                         .chain_periods = (int)(total_bits(&cf) - f)};
    struct fw_cover cv;
    fw_cover_init(&cv, &bad);
    rc = fw_run(&bad, c, regs, 25, &run, &cv, err, sizeof(err));
    fw_cover_free(&cv);
    pru_core_free(c);
    fw_free(&bad);
    ck_assert_msg(rc != 0, "one cycle more after `%s` went unnoticed", mutations[_i].line);
    ck_assert_msg(strstr(err, mutations[_i].named) != NULL, "the failure does not name %s: %s",
                  mutations[_i].named, err);
    fprintf(stderr, "(as it must) one cycle after `%s` fails: %s\n", mutations[_i].line, err);
}
END_TEST

/* ---- PRU1's image ---------------------------------------------------------- */

/* The scratch-pad bank an XFR word uses (10..12), or 0 for any other word. */
static unsigned bank_of(const struct fw *f, size_t pc) {
    if (!f->ok[pc] || pru_optable[f->dec[pc].op].fmt != PRU_FMT_XFR)
        return 0;
    unsigned dev = f->dec[pc].dev;
    return dev >= 10 && dev <= 12 ? dev : 0;
}

/* Whether a and b are the same instruction but for the device (XFR), the
 * immediate (LDI) or the offset (SBCO): what PRU_NUM may change. */
static bool same_but(const struct pru_insn *a, const struct pru_insn *b, unsigned fmt) {
    struct pru_insn x = *a, y = *b;
    if (fmt == PRU_FMT_XFR)
        x.dev = y.dev = 0;
    else
        x.imm = y.imm = 0;
    return memcmp(&x, &y, sizeof x) == 0;
}

/* PRU1's image (-DPRU_NUM=1) is PRU0's, word for word and label for label,
 * except in the fields that do not change an instruction's cycles: every
 * scratch-pad XFR on bank 1 (device 11) where PRU0's is on bank 0 (10),
 * the low half of CTPPR0's address (0x22028 -> 0x24028, one LDI), the
 * value published in ST_PRU (0 -> 1, one LDI) and the GPCFG offset (0x08
 * -> 0x0c, one SBCO). So the timing proven above for
 * PRU0's holds for PRU1's, and each image uses one bank only, never the
 * other's. */
START_TEST(pru1_image_times_as_pru0) {
    struct fw f1;
    if (fw_load(&f1, src_dir(), NULL, 1, err, sizeof(err)) != 0)
        ck_abort_msg("%s", err);
    ck_assert_uint_eq(f1.img.nwords, fw.img.nwords);
    ck_assert_uint_eq(f1.lst.nlabels, fw.lst.nlabels);
    for (size_t i = 0; i < fw.lst.nlabels; i++) {
        ck_assert_str_eq(f1.lst.labels[i].name, fw.lst.labels[i].name);
        ck_assert_uint_eq(f1.lst.labels[i].pc, fw.lst.labels[i].pc);
    }
    unsigned xfr = 0, ldi = 0, sbco = 0;
    for (size_t pc = 0; pc < fw.img.nwords; pc++) {
        unsigned b0 = bank_of(&fw, pc), b1 = bank_of(&f1, pc);
        ck_assert_msg(b0 == 0 || b0 == 10, "PRU0's image uses bank %u at %#zx", b0 - 10, pc);
        ck_assert_msg(b1 == 0 || b1 == 11, "PRU1's image uses bank %u at %#zx", b1 - 10, pc);
        if (fw.img.words[pc] == f1.img.words[pc])
            continue;
        ck_assert_msg(fw.ok[pc] && f1.ok[pc] && fw.dec[pc].op == f1.dec[pc].op,
                      "word %#zx: %08x vs %08x", pc, fw.img.words[pc], f1.img.words[pc]);
        unsigned fmt = pru_optable[fw.dec[pc].op].fmt;
        ck_assert_msg(same_but(&fw.dec[pc], &f1.dec[pc], fmt), "word %#zx: %08x vs %08x", pc,
                      fw.img.words[pc], f1.img.words[pc]);
        if (fmt == PRU_FMT_XFR) {
            ck_assert(b0 == 10 && b1 == 11);
            xfr++;
        } else if (fmt == PRU_FMT_LDI) { /* CTPPR0's address, or ST_PRU's value */
            unsigned i0 = fw.dec[pc].imm, i1 = f1.dec[pc].imm;
            ck_assert_msg((i0 == 0x2028 && i1 == 0x4028) || (i0 == 0 && i1 == 1),
                          "word %#zx: LDI %#x vs %#x", pc, i0, i1);
            ldi++;
        } else {
            ck_assert_uint_eq(fw.dec[pc].op, PRU_OP_SBCO);
            ck_assert_uint_eq(fw.dec[pc].base, 4); /* C4: CFG */
            ck_assert_uint_eq(fw.dec[pc].imm, 0x08);
            ck_assert_uint_eq(f1.dec[pc].imm, 0x0c);
            sbco++;
        }
    }
    ck_assert_uint_gt(xfr, 0);
    ck_assert_uint_eq(ldi, 2);
    ck_assert_uint_eq(sbco, 1);
    fprintf(stderr, "PRU1's image: %u XFR on bank 1, 2 LDI, 1 SBCO differ from PRU0's\n", xfr);
    fw_free(&f1);
}
END_TEST

static Suite *suite(void) {
    Suite *s = suite_create("fw_timing");
    TCase *t = tcase_create("blocks");
    tcase_add_checked_fixture(t, setup, teardown);
    tcase_set_timeout(t, 600);
    tcase_add_loop_test(t, clocked_blocks, 0, (int)N_HALVES);
    tcase_add_test(t, h13_refused);
    tcase_add_test(t, pru1_image_times_as_pru0);
    tcase_add_loop_test(t, extra_cycle_is_named, 0,
                        (int)(sizeof(mutations) / sizeof(mutations[0])));
    suite_add_tcase(s, t);
    return s;
}

int main(void) {
    return check_run(suite());
}
