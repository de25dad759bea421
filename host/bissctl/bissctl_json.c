/* bissctl_json.c - `bissctl read --json`: the frames read and the safety
 * checks' counts as one JSON object (biss-sim --json's "safety" keys), for
 * scripts. Written by hand: the board's bissctl has no cJSON. */
#include "bissctl.h"

#include <stdio.h>

const char *bissctl_frame_state(const struct biss_sample *s) {
    return s->valid        ? (s->crc_error ? "crc-error" : "valid")
           : s->training   ? "training"
           : s->no_slave   ? "no-slave"
           : s->proc_error ? "proc-error"
           : s->ack_jump   ? "ack-jump"
           : s->off_grid   ? "off-grid"
           : s->misframed  ? "misframed"
                           : "invalid";
}

static const char *life(uint32_t f) {
    return !(f & BISS_SAFE_LC_CHECKED) ? "-"
           : f & BISS_SAFE_LC_FROZEN   ? "frozen"
           : f & BISS_SAFE_LC_SKIP     ? "skip"
                                       : "ok";
}

void bissctl_json_frame(const struct biss_sample *s, const struct biss_config *c, bool first) {
    printf("%s\n    {\"frame\": %u, \"flags\": %u, \"state\": \"%s\", \"timestamp\": %u",
           first ? "" : ",", s->frame, s->flags, bissctl_frame_state(s), s->timestamp);
    if (s->flags & BISS_RF_IEP_LATE) {
        printf(", \"iep_late\": true");
    }
    if (s->link_eye >= 0) {
        printf(", \"link_eye\": %d, \"link_warning\": %s", s->link_eye,
               s->link_warning ? "true" : "false");
    }
    if (s->valid || s->training) {
        printf(", \"delay_ns\": %.1f", s->delay.ns);
    }
    if (s->valid) {
        printf(", \"slaves\": [");
        for (unsigned i = 0; i < s->nslaves; i++) {
            const struct biss_slave_result *r = &s->slave[i];
            printf("%s{\"position\": %llu, \"data\": %llu, \"error\": %s, \"warning\": %s, "
                   "\"crc_ok\": %s",
                   i ? ", " : "", (unsigned long long)r->position, (unsigned long long)r->data,
                   r->error ? "true" : "false", r->warning ? "true" : "false",
                   r->crc_ok ? "true" : "false");
            if (c && i < c->nslaves && c->slave[i].life_check) {
                printf(", \"life\": \"%s\"", life(r->safety));
            }
            printf("}");
        }
        printf("]");
        for (unsigned k = 0; c && k < c->npairs; k++) {
            uint32_t f = s->slave[c->pair[k].a].safety & s->slave[c->pair[k].b].safety;
            printf("%s\"%s\"", k ? ", " : ", \"pairs\": [",
                   !(f & BISS_SAFE_PAIR_CHECKED) ? "-"
                   : f & BISS_SAFE_DISAGREE      ? "disagree"
                                                 : "ok");
        }
        printf("%s", c && c->npairs ? "]" : "");
    }
    printf("}");
}

void bissctl_json_end(biss_t *h) {
    struct biss_config c;
    struct biss_safety_stats st;
    printf("\n  ]");
    if (biss_get_config(h, &c) == BISS_OK && biss_get_safety_stats(h, &st) == BISS_OK) {
        printf(",\n  \"safety\": {\"life_counter\": [");
        bool any = false;
        for (unsigned i = 0; i < c.nslaves; i++) {
            if (c.slave[i].life_check) {
                printf("%s{\"slave\": %u, \"checked\": %u, \"frozen\": %u, \"skipped\": %u}",
                       any ? ", " : "", i, st.lc_checked[i], st.lc_frozen[i], st.lc_skipped[i]);
                any = true;
            }
        }
        printf("], \"ew_static\": [");
        any = false;
        for (unsigned i = 0; i < c.nslaves; i++) {
            if (c.slave[i].ew_static) {
                printf("%s{\"slave\": %u, \"checked\": %u, \"misframed\": %u}", any ? ", " : "", i,
                       st.ew_checked[i], st.ew_set[i]);
                any = true;
            }
        }
        printf("], \"max_speed\": [");
        any = false;
        for (unsigned i = 0; i < c.nslaves; i++) {
            if (c.slave[i].max_speed) {
                printf("%s{\"slave\": %u, \"counts_per_s\": %.17g, \"checked\": %u, "
                       "\"jumped\": %u, \"resync\": %u, \"untimed\": %u}",
                       any ? ", " : "", i, c.slave[i].max_speed, st.pos_checked[i],
                       st.pos_jumped[i], st.pos_resync[i], st.pos_untimed[i]);
                any = true;
            }
        }
        printf("], \"pairs\": [");
        for (unsigned k = 0; k < c.npairs; k++) {
            printf(
                "%s{\"a\": %u, \"b\": %u, \"checked\": %u, \"disagree\": %u, \"last_diff\": %lld}",
                k ? ", " : "", c.pair[k].a, c.pair[k].b, st.pair_checked[k], st.pair_disagree[k],
                (long long)st.pair_last_diff[k]);
        }
        printf("]}");
    }
    printf("\n}\n");
}
