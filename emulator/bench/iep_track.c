/* iep_track.c - IEP frames' starts against their flags (iep_track.h). */
#include "iep_track.h"

#include "biss/biss_shm.h"

static struct iep_track_frame *slot_of(struct iep_track *t, uint64_t frame) {
    return &t->slot[frame % IEP_TRACK_FRAMES];
}

/* The frame's slot if it holds both parts. */
static const struct iep_track_frame *complete(struct iep_track *t, uint64_t frame) {
    const struct iep_track_frame *f = slot_of(t, frame);
    return f->frame == frame && f->have == 3 ? f : 0;
}

static bool late(const struct iep_track_frame *f) {
    return (f->flags & BISS_RF_IEP_LATE) != 0;
}

/* Frames a and b (b's number one more): the periods between their starts
 * without a frame need a flag on one of them. */
static void judge_pair(struct iep_track *t, const struct iep_track_frame *a,
                       const struct iep_track_frame *b) {
    int64_t gap = t->period > 0 ? (b->start - a->start) / t->period : 0;
    if (gap > 1 && !late(a) && !late(b)) {
        t->unflagged_skips += (uint64_t)(gap - 1);
    }
}

/* Judges the frame in slot f once it is complete, and its pairs with the
 * frames either side that are. */
static void judge(struct iep_track *t, struct iep_track_frame *f) {
    if (f->have != 3) {
        return;
    }
    t->judged++;
    if (late(f)) {
        t->late++;
    } else if (!(f->flags & BISS_RF_TRAINING)) { /* (a training frame is MAIN's) */
        if (!t->ref_set) {
            t->ref_phase_ps = f->phase_ps;
            t->ref_set = true;
        }
        t->unflagged_off += f->phase_ps != t->ref_phase_ps;
    }
    const struct iep_track_frame *before = f->frame ? complete(t, f->frame - 1) : 0;
    const struct iep_track_frame *after = complete(t, f->frame + 1);
    if (before) {
        judge_pair(t, before, f);
    }
    if (after) {
        judge_pair(t, f, after);
    }
}

/* The slot for frame, emptied if it held an older one. */
static struct iep_track_frame *take(struct iep_track *t, uint64_t frame) {
    struct iep_track_frame *f = slot_of(t, frame);
    if (f->frame != frame || f->have == 0) {
        *f = (struct iep_track_frame){.frame = frame};
    }
    return f;
}

void iep_track_start(struct iep_track *t, uint64_t frame, int64_t start, int64_t period,
                     int64_t phase_ps) {
    struct iep_track_frame *f = take(t, frame);
    if (f->have & 1) {
        return; /* two first falls for one slave frame: crowded_periods counts it */
    }
    f->start = start;
    f->phase_ps = phase_ps;
    f->have |= 1;
    t->period = period;
    judge(t, f);
}

void iep_track_flags(struct iep_track *t, uint64_t frame, uint32_t flags) {
    struct iep_track_frame *f = take(t, frame);
    if (f->have & 2) {
        return;
    }
    f->flags = flags;
    f->have |= 2;
    judge(t, f);
}
