/* probe_frames.c - raw frames from the slave model (emulator/slave), clocked
 * as the firmware's capture layout clocks them: MA edges straight into
 * biss_slave, SL read one output delay after each rising edge. */
#include "probe_frames.h"

#include "biss_slave.h"
#include "event_queue.h"

#include <string.h>

struct sl_probe {
    int level;
};

static void on_sl(void *ctx, sim_ps t, int level) {
    (void)t;
    ((struct sl_probe *)ctx)->level = level;
}

/* One MA rising edge at t and the SL level that answers it. */
static int clock_bit(biss_slave *b, event_queue *q, struct sl_probe *sl, sim_ps t, sim_ps half) {
    biss_slave_ma_edge(b, t, 1);
    eq_run_until(q, t + half - 1);
    int level = sl->level;
    biss_slave_ma_edge(b, t + half, 0);
    eq_run_until(q, t + half);
    return level;
}

int probe_frames_from_model(const biss_chain_cfg *cfg, unsigned nframes, unsigned nbits,
                            sim_ps half, sim_ps period, uint8_t *bits, uint32_t *frame_no) {
    static event_queue q;
    static biss_slave b;
    struct sl_probe sl = {1};
    eq_init(&q);
    biss_slave_init(&b, cfg, &q, (sim_edge_sink){on_sl, &sl});
    int rc = 0;
    sim_ps t0 = 0;
    for (unsigned f = 0; f < nframes; f++) {
        sim_ps t = t0;
        biss_slave_ma_edge(&b, t, 0); /* the frame starts */
        eq_run_until(&q, t + half);
        t += half;
        unsigned guard = 0;
        /* first rise, ACK, busy until the start bit */
        clock_bit(&b, &q, &sl, t, half);
        t += 2 * half;
        int level;
        do {
            level = clock_bit(&b, &q, &sl, t, half);
            t += 2 * half;
        } while (level == 0 && ++guard < 100000);
        if (level != 1) {
            rc = -1;
            break;
        }
        for (unsigned k = 0; k < nbits; k++) {
            bits[(size_t)f * nbits + k] = (uint8_t)clock_bit(&b, &q, &sl, t, half);
            t += 2 * half;
        }
        biss_slave_ma_edge(&b, t, 1); /* MA idles high: the slave times out */
        eq_run_until(&q, t + 200 * SIM_PS_PER_US);
        if (frame_no) {
            frame_no[f] = f;
        }
        t0 += period;
        if (t0 < t + 200 * SIM_PS_PER_US) {
            t0 = t + 200 * SIM_PS_PER_US;
        }
    }
    eq_free(&q);
    return rc;
}
