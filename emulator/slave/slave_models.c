/* slave_models.c - the table of encoder models (slave_model.h): a new
 * protocol model is a file and a row here. */
#include "scenario.h"

#include <string.h>

static const slave_model *const table[] = {
    &slave_model_biss,
    &slave_model_ssi,
};

#define NTABLE     (sizeof table / sizeof table[0])
#define MAX_EXTRAS 8

/* Models registered at run time (slave_model_register). */
static const slave_model *extras[MAX_EXTRAS];
static size_t nextras;

const slave_model *slave_model_at(size_t i) {
    if (i < NTABLE) {
        return table[i];
    }
    return i - NTABLE < nextras ? extras[i - NTABLE] : NULL;
}

const slave_model *slave_model_find(const char *name) {
    const slave_model *m;
    for (size_t i = 0; (m = slave_model_at(i)); i++) {
        if (!strcmp(m->name, name)) {
            return m;
        }
    }
    return NULL;
}

int slave_model_register(const slave_model *m) {
    if (nextras == MAX_EXTRAS || slave_model_find(m->name) ||
        m->cfg_offset != offsetof(scenario, ext) || m->cfg_size > SCENARIO_EXT_BYTES ||
        m->state_size > sizeof(slave_state_room)) {
        return -1;
    }
    extras[nextras++] = m;
    return 0;
}

void scenario_set_model(scenario *s, const slave_model *m) {
    s->model = m;
    if (m->cfg_offset == offsetof(scenario, ext)) {
        memset(s->ext, 0, sizeof s->ext);
        m->cfg_default(s->ext);
    }
}

size_t slave_bit_starts(waveform *ma_slave, sim_ps from, sim_ps to, sim_ps delay, sim_ps *t,
                        size_t max) {
    size_t n = 0;
    for (sim_ps e = from; e <= to && n < max; e = waveform_next_after(ma_slave, e)) {
        if (waveform_level_at(ma_slave, e) == 1) {
            t[n++] = e + delay;
        }
    }
    return n;
}
