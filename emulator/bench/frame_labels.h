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

/* Fills out[] from a frame's record (br for a BiSS-C chain, sr for an SSI
 * encoder; the one l's protocol names is used) and the MA edges at the
 * slave (ma_slave must cover the frame). Returns the number of labels. */
size_t frame_labels(const link_model *l, const biss_frame_record *br, const ssi_frame_record *sr,
                    waveform *ma_slave, struct svg_label *out, size_t max);

#endif
