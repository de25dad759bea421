/* An SSI absolute encoder from its pins.
 *
 * Idle: SL high. The first falling MA edge while idle triggers the
 * monoflop and latches the position; each rising edge then shifts out one
 * bit, MSB first (binary or Gray code); rising edges after the last bit
 * give 0. Once MA has not moved for the monoflop time, SL returns high and
 * the encoder is ready for the next read. Every SL change comes out_delay
 * after the MA edge that caused it. */
#ifndef SSI_SLAVE_H
#define SSI_SLAVE_H

#include "event_queue.h"
#include "sim_time.h"
#include "slave_status.h"

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#define SSI_RECORD_RING 256

typedef struct {
    unsigned bits; /* 1..64, default 13 */
    bool gray;     /* Gray-coded output, default false */
    uint64_t pos0;
    double speed_cps;
    sim_ps out_delay_ps; /* default 20 ns */
    sim_ps monoflop_ps;  /* default 20 us */
} ssi_cfg;

void ssi_cfg_default(ssi_cfg *c);
/* Checks a configuration against its table (ssi_model.c). Returns 0, or
 * -1 with a message naming the field in err. */
int ssi_cfg_check(const ssi_cfg *c, char *err, size_t errlen);

typedef struct {
    uint64_t frame;
    sim_ps start_ps, end_ps; /* start_ps: the first fall, where the position is latched */
    sim_ps last_bit_ps;      /* the rise that put the word's last bit on SL (0: none) */
    uint64_t position;       /* binary */
    uint64_t code;           /* as sent (Gray if configured) */
    unsigned clocks;
    bool complete;
} ssi_frame_record;

typedef struct {
    slave_status st; /* closed frames; in a frame (from its first fall to the monoflop's end) */
    ssi_cfg cfg;
    event_queue *q;
    sim_edge_sink out;
    int ma;
    unsigned rises;
    int sl_sched;
    eq_id monoflop_ev;
    ssi_frame_record cur;
    ssi_frame_record ring[SSI_RECORD_RING];
} ssi_slave;

void ssi_slave_init(ssi_slave *s, const ssi_cfg *cfg, event_queue *q, sim_edge_sink out);
void ssi_slave_ma_edge(ssi_slave *s, sim_ps t, int level);
sim_edge_sink ssi_slave_sink(ssi_slave *s);
const ssi_frame_record *ssi_slave_record(const ssi_slave *s, uint64_t n);
uint64_t ssi_slave_position_at(const ssi_slave *s, sim_ps t);

uint64_t ssi_to_gray(uint64_t v);

#endif
