/*
 * iep_track.h - every IEP-triggered frame's start against its publication:
 * whether the firmware flagged (BISS_RF_IEP_LATE) each frame that did not
 * keep its period (emulator/bench/INSTRUMENTS.md, frame_starts.iep).
 *
 * A frame is known by the slave's number for it. Its start (the IEP period
 * its first MA fall lies in, and the time from that period's start) comes
 * from the frame marks (frame_marks.c) after a run step; its flags from the
 * publication (fw_check.c), during one: either may come first, so a frame
 * is judged when both are in, and a pair of frames k - 1, k when both are.
 * Judged against the firmware's promise: a frame published without the
 * flag started the same time after its period's start as the first such
 * frame; a period in which no frame started lies next to a flagged frame
 * (the one before ran into it, or the one after came late).
 */
#ifndef IEP_TRACK_H
#define IEP_TRACK_H

#include <stdbool.h>
#include <stdint.h>

#define IEP_TRACK_FRAMES 64 /* frames kept for judging: far more than are ever under way */

struct iep_track {
    struct iep_track_frame {
        uint64_t frame;   /* the slave's number */
        int64_t start;    /* its IEP period's first cycle */
        int64_t phase_ps; /* from there to the first fall at the pin */
        uint32_t flags;   /* BISS_RF_* as published */
        unsigned have;    /* 1: the start, 2: the flags */
    } slot[IEP_TRACK_FRAMES];
    int64_t period; /* cycles */
    int64_t ref_phase_ps;
    bool ref_set;
    uint64_t judged;          /* frames with both parts */
    uint64_t late;            /* ... published with BISS_RF_IEP_LATE */
    uint64_t unflagged_off;   /* ... without it, at another time in their period */
    uint64_t unflagged_skips; /* periods without a frame, next to no flagged frame */
};

/* Frame `frame` began in the period starting at cycle `start` (`period`
 * cycles long), phase_ps after that start. */
void iep_track_start(struct iep_track *t, uint64_t frame, int64_t start, int64_t period,
                     int64_t phase_ps);

/* Frame `frame` was published with `flags`. */
void iep_track_flags(struct iep_track *t, uint64_t frame, uint32_t flags);

#endif
