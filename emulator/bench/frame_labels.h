/*
 * frame_labels.h - names of the bits of one frame on SL at the slave, for
 * the scope picture, by the link's model (slave_model labels): a BiSS-C
 * chain's ACK (with busy), start, CDS, then per slave its position bits
 * (by bit number), fill, nE, nW, life counter and CRC bits, and the
 * timeout; an SSI frame's data bits.
 */
#ifndef FRAME_LABELS_H
#define FRAME_LABELS_H

#include "link_model.h"
#include "svg_scope.h"

#define FRAME_LABELS_MAX SLAVE_LABELS_MAX

/* Fills out[] from a frame's record (the link's model's, slave_model
 * record) and the MA edges at the slave (ma_slave must cover the frame),
 * by the model's labels. Returns the number of labels. */
size_t frame_labels(const link_model *l, const void *rec, waveform *ma_slave, struct svg_label *out,
                    size_t max);

#endif
