/* fake_backend.h - a backend over plain memory with a scripted firmware:
 * it acks configurations and publishes frames by the biss_shm.h protocol,
 * one word at a time, interleaved with the host's accesses. */
#ifndef FAKE_BACKEND_H
#define FAKE_BACKEND_H

#include "biss_priv.h"

#include "biss/biss_shm_struct.h"

#include <stdbool.h>
#include <stdint.h>

/* Frames of every slave: the ring's widest slots, fewest of them. */
#define FAKE_RESULT_WORDS (BISS_RING_STRIDE(BISS_MAX_SLAVES) / 4)
#define FAKE_SLOTS        BISS_RING_SLOTS(BISS_MAX_SLAVES)

struct fake {
    uint8_t *mem; /* the PRU-ICSS window */
    uint64_t now_us;
    /* firmware model */
    bool acks;             /* answers CFG_SEQ in advance() */
    uint32_t cfg_error;    /* with this ST_CFG_ERROR */
    bool publishing;       /* publishes frames */
    bool cd_answers;       /* ends a CD program in advance() ... */
    uint16_t cd_status;    /* ... with this ST_CD_STATUS */
    unsigned max_steps;    /* before each host access: 0..max_steps words */
    bool fixed_steps;      /* ... or exactly max_steps */
    unsigned steps_per_us; /* in advance() */
    uint32_t rng;
    uint32_t frame; /* the frame being written, from 1 */
    unsigned word;  /* its next word (its slot: frame - 1 modulo the ring's
                       FAKE_SLOTS); then ST_BUF, then ST_SEQ */
    /* called before each host read (a data-RAM offset), to script the
     * firmware's stores in the middle of a reader's sequence */
    void (*before_read)(struct fake *f, uint32_t off, size_t n);
    /* what the host did */
    unsigned long accesses;
};

/* Makes a handle over a new fake; *f stays valid until biss_close. */
biss_t *fake_handle(struct fake **f);

uint32_t fake_dram32(const struct fake *f, uint32_t off);
/* k of the firmware's stores (publishing: result words, ST_BUF, ST_SEQ). */
void fake_steps(struct fake *f, unsigned k);
void fake_set_dram32(struct fake *f, uint32_t off, uint32_t v);

/* The word the fake writes at index i of frame k's result slot. */
uint32_t fake_result_word(uint32_t k, unsigned i);

#endif
