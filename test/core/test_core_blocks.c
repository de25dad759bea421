/*
 * Check suite: the PRU-ICSS register blocks' table (icss_block.h): the
 * blocks where docs/pru-facts.md §5.1 puts them (pruss/pruss_map.h), in
 * address order without overlap, above the RAMs; each with what the memory
 * map calls; and the table at work: a PRU load from each block costs its
 * own pru_params field, a host write reaches the block's state.
 */
#include "check_run.h"
#include "core_priv.h" /* the table and the blocks' state */
#include "core_test_util.h"

#include <stddef.h>
#include <string.h>

static const struct icss_block *named(const char *name) {
    for (size_t i = 0; i < icss_nblocks; i++)
        if (strcmp(icss_blocks[i]->name, name) == 0)
            return icss_blocks[i];
    return NULL;
}

START_TEST(blocks_where_the_map_says) {
    static const struct {
        const char *name;
        uint32_t base;
    } want[] = {{"INTC", PRUSS_OFS_INTC},
                {"CTRL0", PRUSS_OFS_CTRL0},
                {"CTRL1", PRUSS_OFS_CTRL1},
                {"CFG", PRUSS_OFS_CFG},
                {"IEP", PRUSS_OFS_IEP}};
    ck_assert_uint_eq(icss_nblocks, sizeof want / sizeof want[0]);
    for (size_t i = 0; i < sizeof want / sizeof want[0]; i++) {
        const struct icss_block *b = named(want[i].name);
        ck_assert_msg(b != NULL, "no block %s", want[i].name);
        ck_assert_uint_eq(b->base, want[i].base);
    }
    for (size_t i = 0; i < icss_nblocks; i++) {
        const struct icss_block *b = icss_blocks[i];
        ck_assert_ptr_nonnull(b->read);
        ck_assert_ptr_nonnull(b->write);
        ck_assert_uint_gt(b->size, 0);
        ck_assert_uint_eq(b->base % 0x1000u, 0);
        ck_assert_uint_ge(b->base, PRUSS_OFS_SHARED + PRUSS_AM437X_ICSS1_SHARED_BYTES);
        ck_assert_uint_le(b->load_cycles + sizeof(unsigned), sizeof(struct pru_params));
        if (i > 0) /* address order, no overlap */
            ck_assert_uint_ge(b->base, icss_blocks[i - 1]->base + icss_blocks[i - 1]->size);
        ck_assert_uint_le((uint64_t)b->base + b->size, PRUSS_OFS_IRAM0);
    }
}
END_TEST

/* LBCO from each block's first word: the cycles are its own load cost
 * (pru_params), as a changed value of that field shows. */
START_TEST(load_costs_by_block) {
    static const struct {
        uint32_t addr;
        size_t field;
    } blocks[] = {{PRUSS_OFS_INTC, offsetof(struct pru_params, load_intc_cycles)},
                  {PRUSS_OFS_CTRL0, offsetof(struct pru_params, load_ctrl_cycles)},
                  {PRUSS_OFS_CFG, offsetof(struct pru_params, load_cfg_cycles)},
                  {PRUSS_OFS_IEP, offsetof(struct pru_params, load_iep_cycles)}};
    for (size_t i = 0; i < sizeof blocks / sizeof blocks[0]; i++) {
        uint32_t w[8];
        unsigned n = 0;
        mov32(w, &n, 1, blocks[i].addr);
        w[n++] = burst(PRU_OP_LBBO, 4 * 2, 1, 0, 4);
        w[n++] = halt();
        int64_t cycles[2];
        for (unsigned k = 0; k < 2; k++) {
            struct pru_params p;
            pru_params_default(&p);
            unsigned *cost = (unsigned *)((char *)&p + blocks[i].field);
            *cost += 10 * k;
            struct pru_core *c = core_loaded(&p, w, n);
            pru_start(c);
            ck_assert_int_eq(pru_run_until_cycle(c, 1000), PRU_STOP_HALT);
            cycles[k] = pru_cycles(c);
            pru_core_free(c);
        }
        ck_assert_int_eq(cycles[1] - cycles[0], 10);
    }
}
END_TEST

/* A host write through the table lands in the block's state; a new core's
 * blocks are reset (IEP GLOBAL_CFG 0x550, CONTROL's soft reset bit). */
START_TEST(host_access_through_the_table) {
    struct pru_core *c = pru_core_new(PRU_SOC_AM335X, NULL);
    ck_assert_ptr_nonnull(c);
    uint32_t v = 0;
    ck_assert_int_eq(pru_host_read32(c, PRUSS_AM335X_BASE + PRUSS_OFS_IEP, &v), 0);
    ck_assert_uint_eq(v, 0x550u);
    ck_assert_int_eq(pru_host_read32(c, PRUSS_AM335X_BASE + PRUSS_OFS_CTRL0, &v), 0);
    ck_assert_uint_eq(v & PRU_CTRL_SOFT_RST_N, PRU_CTRL_SOFT_RST_N);
    ck_assert_int_eq(pru_host_write32(c, PRUSS_AM335X_BASE + PRUSS_OFS_IEP, 0x551u), 0);
    ck_assert_uint_eq(c->iep.global_cfg, 0x551u);
    ck_assert_int_eq(pru_host_write32(c, PRUSS_AM335X_BASE + PRUSS_OFS_INTC + 0x10u, 1u), 0);
    ck_assert_uint_eq(c->intc.ger & 1u, 1u); /* GER */
    pru_core_free(c);
}
END_TEST

Suite *blocks_suite(void) {
    Suite *s = suite_create("core_blocks");
    TCase *t = tcase_create("blocks");
    tcase_add_test(t, blocks_where_the_map_says);
    tcase_add_test(t, load_costs_by_block);
    tcase_add_test(t, host_access_through_the_table);
    suite_add_tcase(s, t);
    return s;
}

int main(void) {
    return check_run(blocks_suite());
}
