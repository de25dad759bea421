/* wrong_frame.h - why a frame the firmware published as valid holds a
 * wrong word (CRC good, not what the encoder sent): what the master read
 * against what was sent, and whether SL at the master was a clean frame.
 *
 * Two views of one frame, each from what the bench records:
 *   the words   the bits the master read (the word, and its CRC, which
 *               passed) against those the slave sent (then the bit after
 *               them): slips, bits gained or lost with none flipped (a
 *               clock the slave got and the master never made, or one it
 *               missed: one slip from bit k on, where k may lie anywhere
 *               in a run of equal bits; the fewest that explain it), and
 *               the bits that differ (their difference is a multiple of
 *               the CRC polynomial, as both words pass it: P(x) x^k itself
 *               in the fewest bits, three for a CRC6);
 *   the wire    SL at the master from the start bit to the slave's
 *               timeout: every edge on the bit grid (the master's clock
 *               plus the round trip, within a fifth of a bit: jitter is a
 *               few ns) or not (an edge at a glitch's instant, or a glitch
 *               on SL itself).
 * The class: "off-grid" (an SL edge off the grid that the master's samples
 * saw: a check that SL holds still through each bit would see the frame),
 * "between samples" (edges off the grid, but each a pulse that began and
 * ended between two of the master's sample instants: its samples were a
 * clean frame, no 8x sampling master sees it), "valid on the wire" (every
 * edge on the grid and the words a slip or more apart: SL at the master
 * was a clean frame of the wrong word, which no master can tell from a
 * true one), "other" (every edge on the grid but the words no slips apart:
 * the master misread a clean frame; or the frame's record was gone). */
#ifndef WRONG_FRAME_H
#define WRONG_FRAME_H

#include "biss_slave.h"
#include "pru_core.h"
#include "waveform.h"

#include <stdint.h>

enum wrong_class { WRONG_ON_WIRE, WRONG_OFF_GRID, WRONG_BETWEEN, WRONG_OTHER, WRONG_CLASSES };

enum wrong_words {
    WORDS_SHIFT_AHEAD,  /* the slave one bit ahead from bit shift_at on */
    WORDS_SHIFT_BEHIND, /* one bit behind */
    WORDS_SLIPS,        /* more than one such slip (clocks gained or lost): slips */
    WORDS_FLIPPED,      /* bits flipped: flipped_bits of them */
    WORDS_UNKNOWN,      /* no word to compare (the frame's record is gone) */
};

#define WRONG_MAX_EDGES 8 /* off-grid edges kept per frame */

struct wrong_frame {
    uint32_t frame;                    /* the firmware's frame number */
    unsigned slave;                    /* the first slave whose word is wrong */
    unsigned nbits;                    /* its data + CRC bits */
    uint64_t read;                     /* its data word as read, */
    uint64_t sent;                     /* ... as sent */
    char read_bits[82], sent_bits[82]; /* data, CRC (and the bit after, sent) as 0/1 */
    int64_t counts;                    /* position read - position sent (as read: the top bits) */
    enum wrong_words words;
    unsigned shift_at;               /* a shift: its first bit (0 = the data's MSB) ... */
    unsigned shift_run;              /* ... and how many places explain it (a run) */
    unsigned slips;                  /* the fewest bits gained or lost that turn sent into read */
    unsigned flipped_bits;           /* bits flipped (data + CRC) */
    int crc_poly_shifted;            /* the flipped bits are the CRC polynomial times x^k */
    unsigned edges;                  /* SL edges at the master in the frame */
    unsigned off_grid;               /* of those, off the bit grid */
    unsigned off_grid_seen;          /* of those, seen by the master's samples (a level that
                                        still differed at the next sample instant) */
    int64_t off_ps[WRONG_MAX_EDGES]; /* their distance from the grid, ps */
    enum wrong_class cls;
};

const char *wrong_class_name(enum wrong_class c);

/* Classifies the valid frame published with smp_data[] (the firmware's
 * words) against the record rec of what the chain sent; sl is SL at the
 * master (its history covers the frame), now the time it is recorded to
 * (a frame still in its timeout ends there), period_ps the MA period the
 * frame was clocked at; core the master's PRU, whose GPI sample instants
 * tell the edges its samples saw (NULL: every edge counts as seen). */
void wrong_frame_classify(const biss_chain_cfg *cfg, const biss_frame_record *rec,
                          const uint64_t *smp_data, uint32_t frame, waveform *sl, sim_ps now,
                          int64_t period_ps, const struct pru_core *core, struct wrong_frame *out);

/* One line describing it ("frame 1234: off-grid: slave 0 shift ahead at bit 9 ..."). */
void wrong_frame_describe(const struct wrong_frame *w, char *buf, size_t len);

#endif
