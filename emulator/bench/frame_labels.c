/* frame_labels.c - bit names of a frame at the slave (see frame_labels.h). */
#include "frame_labels.h"

#include <string.h>

size_t frame_labels(const link_model *l, const void *rec, waveform *ma_slave, struct svg_label *out,
                    size_t max) {
    slave_label lab[FRAME_LABELS_MAX];
    size_t n = l->model->labels(link_model_cfg(l), rec, ma_slave, lab,
                                max < FRAME_LABELS_MAX ? max : FRAME_LABELS_MAX);
    for (size_t i = 0; i < n; i++) {
        out[i] = (struct svg_label){.t0 = lab[i].t0, .t1 = lab[i].t1};
        memcpy(out[i].text, lab[i].text, sizeof out[i].text);
    }
    return n;
}
