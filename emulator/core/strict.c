/*
 * strict.c - strict mode and data-RAM contention (emulator/core/TIMING.md,
 * "Strict mode" and "Contention mode").
 *
 * Strict mode traps the constructs docs/silicon-assumptions.md marks
 * UNCERTAIN. Their risk is a cost (or a count) that may differ on silicon,
 * which matters where the firmware counts cycles between MA edges. The core
 * cannot know which code that is, so it takes it from the pins: an
 * instruction is in clocked code when it is issued between two changes of
 * R30 at most strict_window cycles apart. A violation therefore waits until
 * the next R30 change decides; then it is recorded (and, without
 * strict_log, stops the core with the instruction's own PC and cycle).
 * strict_everywhere applies the rules to every instruction at once.
 *
 * Contention models a host (the ARM) reading the local RAMs at fixed or
 * seeded-random cycles; a PRU load or store that overlaps one stalls.
 */
#include "core_priv.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char *const rule_names[] = {"loop1", "loop0", "loopfield", "mvi", "dram", "spad"};
static const char *const rule_what[] = {
    "LOOP whose body is one instruction",
    "LOOP with a register count of 0",
    "LOOP counted by a field other than rN or rN.w0",
    "MVI (register-pointer move)",
    "load or store to data or shared RAM",
    "PRU1 on the scratch-pad bank PRU0 uses in this cycle: PRU1 stalls",
};
#define N_RULES (sizeof rule_names / sizeof rule_names[0])

static int rule_index(unsigned rule) {
    for (unsigned i = 0; i < N_RULES; i++)
        if (rule == 1u << i)
            return (int)i;
    return -1;
}

const char *pru_strict_rule_name(unsigned rule) {
    int i = rule_index(rule);
    return i < 0 ? NULL : rule_names[i];
}

int pru_strict_parse(const char *list, unsigned *rules, const char **bad) {
    *rules = 0;
    if (!list || !*list || strcmp(list, "all") == 0) {
        *rules = PRU_STRICT_ALL;
        return 0;
    }
    const char *p = list;
    for (;;) {
        size_t len = strcspn(p, ",");
        unsigned i = 0;
        while (i < N_RULES &&
               !(strlen(rule_names[i]) == len && strncmp(p, rule_names[i], len) == 0))
            i++;
        if (i == N_RULES) {
            if (bad)
                *bad = p;
            return -1;
        }
        *rules |= 1u << i;
        if (!p[len])
            return 0;
        p += len + 1;
    }
}

void strict_reset(struct pru_core *c) {
    c->st.last_edge = INT64_MIN;
    c->st.inputs_seen = 0;
    c->st.n_pending = 0;
    c->st.pending_over = 0;
}

size_t pru_strict_hits(const struct pru_core *c, const struct pru_strict_hit **hits,
                       uint64_t *lost) {
    *hits = c->st.hits;
    if (lost)
        *lost = c->st.lost;
    return c->st.n_hits;
}

void pru_strict_clear(struct pru_core *c) {
    c->st.n_hits = 0;
    c->st.lost = 0;
}

uint64_t pru_spad_collisions(const struct pru_core *c) {
    return c->spad_collisions;
}

void pru_contend_stats(const struct pru_core *c, uint64_t *collisions, uint64_t *stall_cycles) {
    *collisions = c->st.collisions;
    *stall_cycles = c->st.stall_cycles;
}

bool strict_local_ram(const struct pru_core *c, uint32_t addr, unsigned n) {
    uint64_t a = addr, end = a + n;
    return end <= c->dram_bytes || (a >= 0x2000u && end <= 0x2000u + c->dram_bytes) ||
           (c->shared_bytes && a >= 0x10000u && end <= 0x10000u + c->shared_bytes);
}

uint32_t strict_burst_addr(struct pru_core *c, const struct pd *d) {
    uint32_t base = d->flags & PD_BURST_CBASE ? const_table(c, d->in.base) : c->r[d->in.base];
    return base + (fld(c->r, d->rs2, d->rs2sh, d->rs2mask) | d->imm);
}

static unsigned burst_bytes(const struct pru_core *c, const struct pd *d) {
    unsigned n = d->burst_bytes ? d->burst_bytes : pru_len_bytes(d->in.len, c->r[0]);
    return n ? n : 1;
}

/* The rules instruction d at c->pc breaks, as it would run now. */
static unsigned broken(struct pru_core *c, const struct pd *d) {
    unsigned fmt = d->kind == PD_BAD ? PRU_FMT_PSEUDO : pru_optable[d->kind].fmt;
    unsigned r = 0;
    switch (fmt) {
    case PRU_FMT_LOOP:
        if (d->target == c->pc + 2u)
            r |= PRU_STRICT_LOOP1;
        if (!d->in.io) {
            uint32_t n = fld(c->r, d->rs2, d->rs2sh, d->rs2mask) & 0xffffu;
            if (n == 0)
                r |= PRU_STRICT_LOOP0;
            if (d->in.rs2sel != PRU_SEL_R && d->in.rs2sel != PRU_SEL_W0)
                r |= PRU_STRICT_LOOPFIELD;
        }
        break;
    case PRU_FMT_MVI:
        r |= PRU_STRICT_MVI;
        break;
    case PRU_FMT_BURST:
        if (strict_local_ram(c, strict_burst_addr(c, d), burst_bytes(c, d)))
            r |= PRU_STRICT_DRAM;
        break;
    case PRU_FMT_XFR:
        if (spad_collides(c, d->in.dev))
            r |= PRU_STRICT_SPAD;
        break;
    default:
        break;
    }
    return r & c->p.strict;
}

/* Into the log: one entry per (pc, rule). */
static void log_hit(struct pru_core *c, const struct pru_strict_hit *h) {
    for (size_t i = 0; i < c->st.n_hits; i++) {
        if (c->st.hits[i].pc == h->pc && c->st.hits[i].rule == h->rule) {
            c->st.hits[i].count++;
            return;
        }
    }
    if (c->st.n_hits == PRU_STRICT_MAX_HITS) {
        c->st.lost++;
        return;
    }
    c->st.hits[c->st.n_hits] = *h;
    c->st.hits[c->st.n_hits].count = 1;
    c->st.n_hits++;
}

static void strict_fault(struct pru_core *c, const struct pru_strict_hit *h, int64_t from,
                         int64_t to) {
    if (c->fault.cause != PRU_FAULT_NONE)
        return;
    c->fault = (struct pru_fault){.cause = PRU_FAULT_STRICT,
                                  .pc = h->pc,
                                  .cycle = h->first_cycle,
                                  .word = h->word,
                                  .rule = h->rule,
                                  .edge_from = from,
                                  .edge_to = to};
    c->stop = true;
    c->stop_reason = PRU_STOP_FAULT;
}

bool strict_before(struct pru_core *c, const struct pd *d) {
    unsigned r = broken(c, d);
    if (!r)
        return false;
    for (unsigned i = 0; i < N_RULES; i++) {
        if (!(r & (1u << i)))
            continue;
        struct pru_strict_hit h = {.pc = c->pc,
                                   .word = c->pc < c->iram_words ? c->iram0[c->pc] : 0,
                                   .rule = 1u << i,
                                   .first_cycle = c->cycle};
        if (c->p.strict_everywhere) {
            log_hit(c, &h);
            if (!c->p.strict_log) {
                strict_fault(c, &h, -1, -1);
                return true;
            }
        } else if (c->st.n_pending < STRICT_PENDING) {
            c->st.pending[c->st.n_pending++] = h;
        } else {
            c->st.pending_over++; /* counted as lost if the window proves clocked */
        }
    }
    return false;
}

void pru_strict_inputs(struct pru_core *c, uint32_t mask) {
    c->st.inputs = mask;
    c->st.inputs_seen = c->r[31] & mask;
}

void strict_edge(struct pru_core *c, int64_t cycle) {
    struct strict_state *s = &c->st;
    bool clocked = s->last_edge != INT64_MIN && cycle - s->last_edge <= (int64_t)c->p.strict_window;
    if (clocked) {
        for (unsigned i = 0; i < s->n_pending; i++)
            log_hit(c, &s->pending[i]);
        s->lost += s->pending_over;
        if (s->n_pending && !c->p.strict_log)
            strict_fault(c, &s->pending[0], s->last_edge, cycle);
    }
    s->n_pending = 0;
    s->pending_over = 0;
    s->last_edge = cycle;
}

/* A 64-bit mix (splitmix64's finaliser): cycle h is a host access when
 * mix(seed, h) mod K is 0, so the pattern is a pure function of the cycle. */
static uint64_t mix(uint64_t x) {
    x += 0x9e3779b97f4a7c15u;
    x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9u;
    x = (x ^ (x >> 27)) * 0x94d049bb133111ebu;
    return x ^ (x >> 31);
}

static bool host_at(const struct pru_core *c, int64_t h) {
    uint64_t k = c->p.contend_period;
    if (c->p.contend_random)
        return mix(((uint64_t)c->p.contend_seed << 32) ^ (uint64_t)h) % k == 0;
    return (uint64_t)h % k == c->p.contend_phase % k;
}

unsigned contend_stall(struct pru_core *c, int64_t t, unsigned n) {
    for (unsigned i = 0; i < n; i++) {
        if (host_at(c, t + (int64_t)i)) {
            c->st.collisions++;
            c->st.stall_cycles += c->p.contend_stall;
            return c->p.contend_stall;
        }
    }
    return 0;
}

static int parse_uint(const char *s, char **end, unsigned long max, unsigned long *v) {
    if (*s < '0' || *s > '9')
        return -1;
    *v = strtoul(s, end, 0);
    return *v > max ? -1 : 0;
}

int pru_contend_parse(const char *spec, struct pru_params *p, char *err, size_t errlen) {
    unsigned long k, s, x = 1; /* phase or seed */
    char *e;
    const char *form = "K,S[,periodic[:PHASE]|random[:SEED]] with K >= 1 host period, S stall";
    if (!spec || parse_uint(spec, &e, 1000000, &k) || k == 0 || *e != ',' ||
        parse_uint(e + 1, &e, 1000000, &s)) {
        snprintf(err, errlen, "'%s' is not %s", spec ? spec : "", form);
        return -1;
    }
    int random = 1; /* default: random, seed 1 (a periodic host can alias with the
                     * firmware's own period and never meet it; TIMING.md) */
    if (*e == ',') {
        random = 0;
        const char *m = e + 1;
        size_t len = strcspn(m, ":");
        if (len == 6 && strncmp(m, "random", 6) == 0)
            random = 1;
        else if (!(len == 8 && strncmp(m, "periodic", 8) == 0)) {
            snprintf(err, errlen, "'%s': pattern must be periodic or random (%s)", spec, form);
            return -1;
        }
        e = (char *)m + len;
        x = random; /* seed 1, phase 0 unless given */
        if (*e == ':' && parse_uint(e + 1, &e, random ? 0xffffffffu : k - 1, &x)) {
            snprintf(err, errlen, "'%s': %s must be %s", spec, random ? "SEED" : "PHASE",
                     random ? "0..2^32-1" : "0..K-1");
            return -1;
        }
    }
    if (*e) {
        snprintf(err, errlen, "'%s' is not %s", spec, form);
        return -1;
    }
    p->contend_period = (unsigned)k;
    p->contend_stall = (unsigned)s;
    p->contend_random = random;
    p->contend_phase = random ? 0 : (unsigned)x;
    p->contend_seed = random ? (uint32_t)x : 0;
    return 0;
}

void strict_print_fault(const struct pru_core *c, FILE *f) {
    const struct pru_fault *ft = &c->fault;
    char dis[96];
    int i = rule_index(ft->rule);
    pru_disasm(ft->word, ft->pc, dis, sizeof dis);
    fprintf(f, "fault: strict rule %s (%s) at pc=0x%04x cycle=%lld: %s (word=0x%08x)",
            rule_names[i], rule_what[i], ft->pc, (long long)ft->cycle, dis, ft->word);
    if (ft->edge_from >= 0)
        fprintf(f, ", between R30 changes at cycles %lld and %lld", (long long)ft->edge_from,
                (long long)ft->edge_to);
    fputc('\n', f);
}
