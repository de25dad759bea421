/* slave_status.h - what the link reads of an encoder model on every MA
 * edge, without a call: the first member of every model's state
 * (slave_model.h). */
#ifndef SLAVE_STATUS_H
#define SLAVE_STATUS_H

#include <stdbool.h>
#include <stdint.h>

typedef struct {
    uint64_t frames; /* closed frames */
    bool in_frame;   /* from a frame's first MA edge to its end (timeout, monoflop) */
} slave_status;

#endif
