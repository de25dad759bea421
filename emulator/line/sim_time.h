/* Simulation time for the bench and its models.
 *
 * Time is a signed 64-bit count of picoseconds: fine enough to place an edge
 * well inside one PRU cycle (5000 ps) and wide enough for about 106 days of
 * simulated time, so no model ever needs to worry about wrap-around. */
#ifndef SIM_TIME_H
#define SIM_TIME_H

#include <stdint.h>

typedef int64_t sim_ps;

#define SIM_PS_PER_NS        INT64_C(1000)
#define SIM_PS_PER_US        INT64_C(1000000)
#define SIM_PS_PER_MS        INT64_C(1000000000)
#define SIM_PS_PER_S         INT64_C(1000000000000)
#define SIM_PS_PER_PRU_CYCLE INT64_C(5000) /* 200 MHz PRU clock */

/* "Never": later than any event a simulation can reach. */
#define SIM_NEVER INT64_MAX

/* Something that accepts logic edges: a wire model, a slave, a recorder.
 * Edges are delivered in time order, each at the simulation time it happens. */
typedef void (*sim_edge_fn)(void *ctx, sim_ps t, int level);

typedef struct {
    sim_edge_fn fn;
    void *ctx;
} sim_edge_sink;

static inline void sim_edge_send(const sim_edge_sink *s, sim_ps t, int level) {
    if (s->fn) {
        s->fn(s->ctx, t, level);
    }
}

#endif
