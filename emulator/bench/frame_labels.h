/*
 * frame_labels.h - names of the bits of one frame on SL at the slave, for
 * the scope picture: ACK (with busy), start, CDS, then per slave its
 * position bits (by bit number), fill, nE, nW, life counter and CRC bits,
 * and the timeout; or an SSI frame's data bits.
 */
#ifndef FRAME_LABELS_H
#define FRAME_LABELS_H

#include "link_model.h"
#include "svg_scope.h"

#define FRAME_LABELS_MAX 700

/* Fills out[] from frame k's record and the MA edges at the slave (ma_slave
 * must cover the frame). Returns the number of labels. */
size_t frame_labels(const link_model *l, uint64_t k, waveform *ma_slave, struct svg_label *out,
                    size_t max);

#endif
