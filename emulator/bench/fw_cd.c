/* fw_cd.c - control communication on the bench (see fw_cd.h): the
 * program goes in and the answer comes back through proto's transfers, as
 * libbiss does it. */
#include "fw_cd.h"

#include <string.h>

void fw_cd_issue(struct fw_cd *cd, struct bench *b, const biss_cd_prog *p, uint16_t wait_limit) {
    memset(cd, 0, sizeof(*cd));
    cd->b = b;
    cd->prog = p;
    struct biss_proto_io io = bench_fw_io(b);
    cd->put_error = biss_proto_cd_put(&io, p, wait_limit, &cd->cmd);
    cd->frame0 = link_frames(bench_link(b));
}

int fw_cd_poll(struct fw_cd *cd) {
    if (cd->done) {
        return 1;
    }
    static biss_cd_answer a;
    struct biss_proto_io io = bench_fw_io(cd->b);
    if (cd->put_error) {
        cd->err = BISS_CD_E_REFUSED; /* never handed over */
    } else if (biss_proto_cd_ended(&io, cd->cmd, &a) != 1) {
        return 0;
    } else {
        cd->err = biss_cd_parse(cd->prog, &a, &cd->result);
        cd->status = a.status;
    }
    cd->frames = link_frames(bench_link(cd->b)) - cd->frame0;
    cd->done = 1;
    return 1;
}
