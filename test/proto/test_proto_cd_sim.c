/* Check suite for the codec against the slave control model, through a
 * frame-by-frame stand-in for the firmware's CDM program (cd_sim.h). */
#include "biss_cd.h"
#include "cd_sim.h"
#include "scenario.h"

#include "check_run.h"

#include <check.h>
#include <stdlib.h>
#include <string.h>

/* Frames a register access of n bytes takes from its S to its end frame,
 * every slave S in time: S, header (15), R W, 14 per byte (S, D(8),
 * CRC(4), P), the final S, the tail, the frame that records the last
 * answer. */
#define REG_FRAMES(n) (20u + BISS_CD_TAIL_ZEROS + 14u * (n))

typedef struct {
    cd_sim sim;
    uint8_t dram[BISS_DRAM_BYTES];
    uint32_t cmd;
} rig;

static scenario sc; /* the tidep0022-test-encoder profile's registers */
static regfile regs;
static rig g;

static void setup(void) {
    ck_assert_int_eq(profile_by_name("tidep0022-test-encoder", &sc), 0);
    regfile_init(&regs, 4);
    cd_sim_init(&g.sim);
    memset(g.dram, 0, sizeof g.dram);
    g.cmd = 0;
}

/* Runs p as the firmware would and parses its answers. */
static biss_cd_err run(const biss_cd_prog *p, uint16_t wait_limit, biss_cd_result *r) {
    ck_assert_int_eq(biss_cd_shm_put(p, wait_limit, g.dram, sizeof g.dram), BISS_CD_OK);
    g.cmd++;
    memcpy(g.dram + BISS_CD_CMD, &g.cmd, 4);
    cd_sim_run(&g.sim, g.dram);
    biss_cd_answer a;
    ck_assert_int_eq(biss_cd_shm_get(g.dram, sizeof g.dram, &a), BISS_CD_OK);
    ck_assert_uint_eq(a.seq, g.cmd);
    return biss_cd_parse(p, &a, r);
}

static biss_cd_err read_regs(unsigned id, unsigned addr, unsigned n, uint16_t wait_limit,
                             biss_cd_result *r) {
    static biss_cd_prog p;
    ck_assert_int_eq(biss_cd_build_read(&p, id, addr, n), BISS_CD_OK);
    return run(&p, wait_limit, r);
}

static biss_cd_err write_regs(unsigned id, unsigned addr, const uint8_t *d, unsigned n,
                              biss_cd_result *r) {
    static biss_cd_prog p;
    ck_assert_int_eq(biss_cd_build_write(&p, id, addr, d, n), BISS_CD_OK);
    return run(&p, 10, r);
}

static void assert_bytes(const biss_cd_result *r, const uint8_t *want, unsigned n) {
    for (unsigned i = 0; i < n; i++) {
        ck_assert_uint_eq(r->byte[i].data, want[i]);
        ck_assert(r->byte[i].crc_ok);
    }
}

START_TEST(single_read_temperature) {
    biss_ctrl c;
    biss_ctrl_init(&c, 0, &sc.biss.s[0].regs, 0);
    cd_sim_add(&g.sim, &c);
    biss_cd_result r;
    ck_assert_int_eq(read_regs(0, 0x67, 1, 10, &r), BISS_CD_OK);
    ck_assert(r.rw_echo_ok);
    ck_assert_int_eq(r.byte[0].start, BISS_CD_S_IN_TIME);
    ck_assert_uint_eq(r.byte[0].data, 0x5f);
    ck_assert_uint_eq(r.byte[0].crc, biss_cd_crc4_line(0x5f, 8));
    ck_assert(r.byte[0].crc_ok);
    ck_assert_uint_eq(r.good_bytes, 1);
    ck_assert_uint_eq(g.sim.prog_frames, REG_FRAMES(1));
    ck_assert_uint_eq(c.reads, 1);
    ck_assert_int_eq(c.state, CTRL_IDLE);
}
END_TEST

/* TIDEP0022 Table 11 values, each block in one sequential access. */
START_TEST(sequential_reads_table11) {
    biss_ctrl c;
    biss_ctrl_init(&c, 0, &sc.biss.s[0].regs, 0);
    cd_sim_add(&g.sim, &c);
    biss_cd_result r;
    static const uint8_t serial[] = {0x00, 0xd9, 0x01, 0x32};
    ck_assert_int_eq(read_regs(0, 0x44, 4, 10, &r), BISS_CD_OK);
    assert_bytes(&r, serial, 4);
    ck_assert_uint_eq(r.good_bytes, 4);
    ck_assert_uint_eq(g.sim.prog_frames, REG_FRAMES(4));
    static const uint8_t ident[] = {0x46, 0x3a, 0xc0, 0x0c, 0x00, 0x01, 0x57, 0x41};
    ck_assert_int_eq(read_regs(0, 0x78, 8, 10, &r), BISS_CD_OK);
    assert_bytes(&r, ident, 8);
    ck_assert_uint_eq(r.good_bytes, 8);
    ck_assert_uint_eq(c.reads, 12);
}
END_TEST

/* Bank 2 chosen by a control-frame write to 0x40, then 64 bytes from 0x20:
 * 0x20..0x3F from bank 2, the bank register, 0x41..0x5F direct. */
START_TEST(read_64_across_bank_switch) {
    for (unsigned b = 0; b < 4; b++) {
        for (unsigned a = 0; a < 0x40; a++) {
            regfile_poke(&regs, b, (uint8_t)a, (uint8_t)(b << 6 | a));
        }
    }
    for (unsigned a = 0x41; a < 0x80; a++) {
        regfile_poke(&regs, 0, (uint8_t)a, (uint8_t)(a ^ 0xa5));
    }
    biss_ctrl c;
    biss_ctrl_init(&c, 0, &regs, 0);
    cd_sim_add(&g.sim, &c);
    biss_cd_result r;
    const uint8_t bank = 2;
    ck_assert_int_eq(write_regs(0, 0x40, &bank, 1, &r), BISS_CD_OK);
    ck_assert(r.byte[0].echo_ok);
    ck_assert_int_eq(read_regs(0, 0x20, 64, 10, &r), BISS_CD_OK);
    ck_assert_uint_eq(r.nbytes, 64);
    ck_assert_uint_eq(r.good_bytes, 64);
    uint8_t want[64];
    for (unsigned i = 0; i < 64; i++) {
        unsigned a = 0x20 + i;
        want[i] = a < 0x40 ? (uint8_t)(bank << 6 | a) : a == 0x40 ? bank : (uint8_t)(a ^ 0xa5);
    }
    assert_bytes(&r, want, 64);
    ck_assert_uint_eq(g.sim.prog_frames, REG_FRAMES(64));
    ck_assert_uint_eq(c.reads, 64);
}
END_TEST

START_TEST(write_then_read_back) {
    biss_ctrl c;
    biss_ctrl_init(&c, 5, &regs, 0);
    cd_sim_add(&g.sim, &c);
    biss_cd_result r;
    const uint8_t d[] = {0x3a, 0xc5, 0x00};
    ck_assert_int_eq(write_regs(5, 0x10, d, 3, &r), BISS_CD_OK);
    ck_assert(r.rw_echo_ok);
    for (unsigned i = 0; i < 3; i++) {
        ck_assert(r.byte[i].echo_ok);
        ck_assert_uint_eq(r.byte[i].data, d[i]);
    }
    ck_assert_uint_eq(r.good_bytes, 3);
    ck_assert_uint_eq(g.sim.prog_frames, REG_FRAMES(3));
    ck_assert_uint_eq(c.writes, 3);
    ck_assert_int_eq(read_regs(5, 0x10, 3, 10, &r), BISS_CD_OK);
    assert_bytes(&r, d, 3);
}
END_TEST

/* The model refuses the write but echoes it all the same: the line shows
 * nothing, only reading back does. */
START_TEST(write_read_only_register) {
    biss_ctrl c;
    biss_ctrl_init(&c, 0, &sc.biss.s[0].regs, 0);
    cd_sim_add(&g.sim, &c);
    biss_cd_result r;
    const uint8_t v = 0x12;
    ck_assert_int_eq(write_regs(0, 0x67, &v, 1, &r), BISS_CD_OK);
    ck_assert(r.byte[0].echo_ok);
    ck_assert_uint_eq(c.write_refused, 1);
    ck_assert_int_eq(read_regs(0, 0x67, 1, 10, &r), BISS_CD_OK);
    ck_assert_uint_ne(r.byte[0].data, v);
    ck_assert_uint_eq(r.byte[0].data, 0x5f);
}
END_TEST

START_TEST(late_start_within_wait_limit) {
    biss_ctrl c;
    biss_ctrl_init(&c, 0, &sc.biss.s[0].regs, 4);
    cd_sim_add(&g.sim, &c);
    biss_cd_result r;
    static const uint8_t serial[] = {0x00, 0xd9, 0x01, 0x32};
    ck_assert_int_eq(read_regs(0, 0x44, 4, 4, &r), BISS_CD_OK);
    assert_bytes(&r, serial, 4);
    for (unsigned i = 0; i < 4; i++) {
        ck_assert_int_eq(r.byte[i].start, BISS_CD_S_LATE);
    }
    /* each byte waits its 4 frames of processing */
    ck_assert_uint_eq(g.sim.prog_frames, REG_FRAMES(4) + 4 * 4);
    /* a late S on a write */
    const uint8_t d = 0x77;
    ck_assert_int_eq(write_regs(0, 0x10, &d, 1, &r), BISS_CD_OK);
    ck_assert_int_eq(r.byte[0].start, BISS_CD_S_LATE);
    ck_assert(r.byte[0].echo_ok);
    ck_assert_uint_eq(c.writes, 1);
}
END_TEST

START_TEST(late_start_beyond_wait_limit) {
    biss_ctrl c;
    biss_ctrl_init(&c, 0, &sc.biss.s[0].regs, 5);
    cd_sim_add(&g.sim, &c);
    biss_cd_result r;
    ck_assert_int_eq(read_regs(0, 0x44, 2, 4, &r), BISS_CD_E_NO_START);
    ck_assert(r.rw_echo_ok);
    ck_assert_int_eq(r.byte[0].start, BISS_CD_S_MISSING);
    ck_assert(!r.byte[0].answered);
    ck_assert_int_eq(r.byte[1].start, BISS_CD_S_NOT_REACHED);
    ck_assert_uint_eq(r.good_bytes, 0);
    /* the slave is still in its frame: the next program's S comes too soon */
    ck_assert_int_ne(read_regs(0, 0x44, 1, 10, &r), BISS_CD_OK);
    /* idle frames (a program of zeros) let it end its frame and re-arm */
    static biss_cd_prog idle;
    ck_assert_int_eq(biss_cd_build_idle(&idle, 32), BISS_CD_OK);
    ck_assert_int_eq(run(&idle, 0, &r), BISS_CD_OK);
    ck_assert_int_eq(read_regs(0, 0x44, 2, 5, &r), BISS_CD_OK);
    ck_assert_uint_eq(r.byte[1].data, 0xd9);
}
END_TEST

/* The second of three bytes gets one answer bit flipped on its way. */
START_TEST(corrupted_cds_bit) {
    biss_ctrl c;
    biss_ctrl_init(&c, 0, &sc.biss.s[0].regs, 0);
    cd_sim_add(&g.sim, &c);
    static biss_cd_prog p;
    ck_assert_int_eq(biss_cd_build_read(&p, 0, 0x45, 3), BISS_CD_OK);
    biss_cd_result r;
    g.sim.flip_step = p.byte[1].data + 3;
    ck_assert_int_eq(run(&p, 10, &r), BISS_CD_E_CRC);
    ck_assert_uint_eq(r.good_bytes, 1);
    ck_assert(r.byte[0].crc_ok);
    ck_assert(!r.byte[1].crc_ok);
    ck_assert_uint_eq(r.byte[1].data, 0x01 ^ 0x10);
    /* the firmware ended the control frame at byte 2's S (sent as 0) */
    ck_assert_int_eq(r.byte[2].start, BISS_CD_S_NOT_REACHED);
    ck_assert_uint_eq(c.reads, 2);
    /* a flipped CRC bit is a CRC error too */
    g.sim.flip_step = p.byte[0].crc + 2;
    ck_assert_int_eq(run(&p, 10, &r), BISS_CD_E_CRC);
    ck_assert_uint_eq(r.good_bytes, 0);
    /* a flipped echo of a write */
    static biss_cd_prog w;
    const uint8_t d[] = {0x11, 0x22};
    ck_assert_int_eq(biss_cd_build_write(&w, 0, 0x10, d, 2), BISS_CD_OK);
    g.sim.flip_step = w.byte[1].data;
    ck_assert_int_eq(run(&w, 10, &r), BISS_CD_E_ECHO);
    ck_assert_uint_eq(r.good_bytes, 1);
    ck_assert(!r.byte[1].echo_ok);
    ck_assert(r.byte[1].crc_ok == false);
}
END_TEST

START_TEST(other_id_answers_nothing) {
    biss_ctrl c;
    biss_ctrl_init(&c, 0, &sc.biss.s[0].regs, 0);
    cd_sim_add(&g.sim, &c);
    biss_cd_result r;
    ck_assert_int_eq(read_regs(3, 0x67, 1, 6, &r), BISS_CD_E_NO_ECHO);
    ck_assert(!r.rw_echo_ok);
    /* R's echo was missing: the firmware ended the frame at the byte's S */
    ck_assert_int_eq(r.byte[0].start, BISS_CD_S_NOT_REACHED);
    ck_assert_uint_eq(r.good_bytes, 0);
    ck_assert_uint_eq(c.reads, 0);
}
END_TEST

START_TEST(frame_failure_mid_program) {
    biss_ctrl c;
    biss_ctrl_init(&c, 0, &sc.biss.s[0].regs, 0);
    cd_sim_add(&g.sim, &c);
    static biss_cd_prog p;
    ck_assert_int_eq(biss_cd_build_read(&p, 0, 0x44, 4), BISS_CD_OK);
    biss_cd_result r;
    /* fails in byte 2's data: 18 frames of header and R W S, 14 per byte */
    g.sim.fail_frame = 18 + 14 * 2 + 3;
    ck_assert_int_eq(run(&p, 10, &r), BISS_CD_E_FRAME);
    ck_assert_uint_eq(r.good_bytes, 2);
    ck_assert(r.byte[1].answered);
    ck_assert(!r.byte[2].answered);
    ck_assert_int_eq(r.byte[3].start, BISS_CD_S_NOT_REACHED);
}
END_TEST

START_TEST(refused_program) {
    static biss_cd_prog p;
    ck_assert_int_eq(biss_cd_build_read(&p, 0, 0x44, 1), BISS_CD_OK);
    ck_assert_int_eq(biss_cd_shm_put(&p, 1, g.dram, sizeof g.dram), BISS_CD_OK);
    memset(g.dram + BISS_CD_STEPS, 0, 2); /* a length the firmware refuses */
    cd_sim_run(&g.sim, g.dram);
    biss_cd_answer a;
    ck_assert_int_eq(biss_cd_shm_get(g.dram, sizeof g.dram, &a), BISS_CD_OK);
    biss_cd_result r;
    ck_assert_int_eq(biss_cd_parse(&p, &a, &r), BISS_CD_E_REFUSED);
}
END_TEST

/* After a frame failed at any step of a read, the next access needs
 * BISS_CD_REARM_ZEROS frames of CDM 0 before its S (biss_cd_lead_in): the
 * slave is cancelled by the 14 zeros only if its frame is still open at the
 * 14th; where it ended on one of them it wants 14 fresh ones. Without the
 * lead-in some failure points leave the next read unanswered; with it every
 * one works, and its answers are read at the steps the lead-in moved. */
START_TEST(failure_then_lead_in) {
    biss_ctrl c;
    biss_ctrl_init(&c, 0, &sc.biss.s[0].regs, 0);
    cd_sim_add(&g.sim, &c);
    static biss_cd_prog fail, next;
    ck_assert_int_eq(biss_cd_build_read(&fail, 0, 0x44, 2), BISS_CD_OK);
    unsigned unarmed = 0;
    for (unsigned lead = 0; lead <= 1; lead++) {
        for (long k = 1; k < (long)fail.len; k++) {
            biss_cd_result r;
            g.sim.fail_frame = k;
            biss_cd_err failed = run(&fail, 10, &r);
            ck_assert_int_eq(g.sim.fail_frame == k, 1);
            g.sim.fail_frame = -1;
            /* (from the final S on, a failure costs nothing) */
            ck_assert_int_eq(failed, k < (long)fail.end ? BISS_CD_E_FRAME : BISS_CD_OK);
            ck_assert_int_eq(biss_cd_build_read(&next, 0, 0x67, 1), BISS_CD_OK);
            if (lead) {
                ck_assert_int_eq(biss_cd_lead_in(&next, BISS_CD_REARM_ZEROS), BISS_CD_OK);
            }
            biss_cd_err e = run(&next, 10, &r);
            if (!lead) {
                unarmed += e != BISS_CD_OK;
                /* (a read failing unanswered ends its frame the slave's way) */
                if (e != BISS_CD_OK) {
                    ck_assert_int_eq(run(&next, 10, &r), BISS_CD_OK);
                }
                continue;
            }
            ck_assert_msg(e == BISS_CD_OK, "failed at step %ld: next read %s", k,
                          biss_cd_strerror(e));
            ck_assert_uint_eq(r.byte[0].data, 0x5f);
            ck_assert(r.idl_answered);
            ck_assert_uint_eq(r.idl, 0x01);
            ck_assert_uint_eq(r.header_cds, 0x001);
        }
    }
    ck_assert_uint_gt(unarmed, 0);
}
END_TEST

/* The lead-in moves every field's step; the fields set afterwards count it. */
START_TEST(lead_in_moves_the_fields) {
    static biss_cd_prog p, q;
    ck_assert_int_eq(biss_cd_build_read(&p, 2, 0x10, 3), BISS_CD_OK);
    q = p;
    ck_assert_int_eq(biss_cd_lead_in(&q, 5), BISS_CD_OK);
    ck_assert_uint_eq(q.len, p.len + 5);
    ck_assert_uint_eq(q.lead, 5);
    for (unsigned i = 0; i < 5; i++) {
        ck_assert_uint_eq(q.op[i], BISS_CDOP_0);
    }
    ck_assert_mem_eq(q.op + 5, p.op, p.len);
    ck_assert_uint_eq(q.rw, p.rw + 5);
    ck_assert_uint_eq(q.idl, p.idl + 5);
    ck_assert_uint_eq(q.end, p.end + 5);
    for (unsigned i = 0; i < 3; i++) {
        ck_assert_uint_eq(q.byte[i].start, p.byte[i].start + 5);
        ck_assert_uint_eq(q.byte[i].wait, p.byte[i].wait + 5);
        ck_assert_uint_eq(q.byte[i].data, p.byte[i].data + 5);
        ck_assert_uint_eq(q.byte[i].crc, p.byte[i].crc + 5);
        ck_assert_uint_eq(q.byte[i].stop, p.byte[i].stop + 5);
    }
    ck_assert_int_eq(biss_cd_set_idl(&q, BISS_CD_IDL_AT_CTS), BISS_CD_OK);
    ck_assert_uint_eq(q.idl, 6);
    ck_assert_int_eq(biss_cd_build_command(&p, 0x01, 0, true), BISS_CD_OK);
    q = p;
    ck_assert_int_eq(biss_cd_lead_in(&q, BISS_CD_REARM_ZEROS), BISS_CD_OK);
    ck_assert_uint_eq(q.ida, p.ida + BISS_CD_REARM_ZEROS);
    ck_assert_uint_eq(biss_cd_ida_word(&q), biss_cd_ida_word(&p) + BISS_CD_REARM_ZEROS);
    ck_assert_int_eq(biss_cd_set_ida(&q, BISS_CD_IDA_AT_CRC), BISS_CD_OK);
    ck_assert_uint_eq(q.ida, p.ida + BISS_CD_REARM_ZEROS);
    ck_assert_int_eq(biss_cd_lead_in(&q, 0), BISS_CD_E_ARG);
    ck_assert_int_eq(biss_cd_lead_in(&q, BISS_CD_MAX_STEPS - q.len + 1), BISS_CD_E_TOO_LONG);
    ck_assert_int_eq(biss_cd_lead_in(&q, BISS_CD_MAX_STEPS - q.len), BISS_CD_OK);
}
END_TEST

/* Like the slaves, the firmware counts the 14 CDM 0 frames before a program
 * from the end of the last one, so programs back to back both work, the
 * second after 13 more frames of CDM 0 (the last frame's END is the first). */
START_TEST(back_to_back_waits_for_the_zeros) {
    biss_ctrl c;
    biss_ctrl_init(&c, 0, &sc.biss.s[0].regs, 0);
    cd_sim_add(&g.sim, &c);
    static biss_cd_prog p;
    ck_assert_int_eq(biss_cd_build_read(&p, 0, 0x67, 1), BISS_CD_OK);
    biss_cd_result r;
    ck_assert_int_eq(run(&p, 10, &r), BISS_CD_OK);
    unsigned long before = g.sim.frames;
    ck_assert_int_eq(run(&p, 10, &r), BISS_CD_OK);
    ck_assert_uint_eq(r.byte[0].data, 0x5f);
    ck_assert_uint_eq(g.sim.frames - before, BISS_CD_IDLE_ZEROS - 1 + g.sim.prog_frames);
}
END_TEST

/* Three slaves, IDs 0 1 2, on one CDS line. */
static biss_ctrl chain[3];

static void add_chain(void) {
    for (unsigned i = 0; i < 3; i++) {
        biss_ctrl_init(&chain[i], (uint8_t)i, &regs, 0);
        cd_sim_add(&g.sim, &chain[i]);
    }
}

static biss_cd_err command_test(uint8_t ids, unsigned cmd, bool ida_test, biss_cd_result *r) {
    static biss_cd_prog p;
    ck_assert_int_eq(biss_cd_build_command(&p, ids, cmd, ida_test), BISS_CD_OK);
    return run(&p, 0, r);
}

static biss_cd_err command(uint8_t ids, unsigned cmd, biss_cd_result *r) {
    return command_test(ids, cmd, false, r);
}

START_TEST(command_broadcast) {
    add_chain();
    biss_cd_result r;
    ck_assert_int_eq(command(0, 2, &r), BISS_CD_OK);
    ck_assert_uint_eq(r.ida, 0);
    ck_assert_uint_eq(r.ida_expected, 0);
    for (unsigned i = 0; i < 3; i++) {
        ck_assert_int_eq(chain[i].last_cmd, 2);
    }
    ck_assert_uint_eq(g.sim.prog_frames, 26 + BISS_CD_TAIL_ZEROS);
}
END_TEST

START_TEST(command_addressed) {
    add_chain();
    biss_cd_result r;
    ck_assert_int_eq(command(0x05, 1, &r), BISS_CD_OK); /* IDs 0 and 2 */
    ck_assert_uint_eq(r.ida, 0x05);
    ck_assert_int_eq(chain[0].last_cmd, 1);
    ck_assert_int_eq(chain[1].last_cmd, -1);
    ck_assert_int_eq(chain[2].last_cmd, 1);
    /* ID 6 is not in the chain: its IDA slot stays 0 */
    ck_assert_int_eq(command(0x42, 3, &r), BISS_CD_E_IDA);
    ck_assert_uint_eq(r.ida, 0x02);
    ck_assert_uint_eq(r.ida_expected, 0x42);
    ck_assert_int_eq(chain[1].last_cmd, 3);
}
END_TEST

/* With the IDA test the same mismatch withholds the command: P goes out
 * as 1, and no slave executes it. A matching IDA lets it through. */
START_TEST(command_ida_test) {
    add_chain();
    biss_cd_result r;
    ck_assert_int_eq(command_test(0x42, 3, true, &r), BISS_CD_E_WITHHELD);
    ck_assert_uint_eq(r.ida, 0x02);
    ck_assert_int_eq(chain[1].last_cmd, -1);
    ck_assert_uint_eq(chain[1].commands_dropped, 1);
    ck_assert_int_eq(command_test(0x06, 3, true, &r), BISS_CD_OK);
    ck_assert_uint_eq(r.ida, 0x06);
    ck_assert_int_eq(chain[1].last_cmd, 3);
    ck_assert_int_eq(chain[2].last_cmd, 3);
    ck_assert_int_eq(chain[0].last_cmd, -1);
    /* a broadcast expects no IDA at all */
    ck_assert_int_eq(command_test(0, 1, true, &r), BISS_CD_OK);
    ck_assert_int_eq(chain[0].last_cmd, 1);
}
END_TEST

/* A BiSS frame failing at P stops the command; one failing in the tail
 * after it does not matter. */
START_TEST(command_frame_failure) {
    add_chain();
    biss_cd_result r;
    g.sim.fail_frame = 24; /* S, 15 header, 8 IDA slots, then P */
    ck_assert_int_eq(command(0x02, 1, &r), BISS_CD_E_FRAME);
    ck_assert_uint_eq(r.ida, 0x02);
    ck_assert_int_eq(chain[1].last_cmd, -1);
    g.sim.fail_frame = 26;
    ck_assert_int_eq(command(0x02, 2, &r), BISS_CD_OK);
    ck_assert_int_eq(chain[1].last_cmd, 2);
}
END_TEST

/* The ID lock of a chain of IDs 0..2 (host/CD.md, "IDL"): read where
 * the slaves answer it, whichever of the two readings they follow, and
 * the slots that answered reported either way. A codec reading the other
 * slots than the slaves answer in shows it in header_cds. */
START_TEST(id_lock_either_slot) {
    add_chain();
    static biss_cd_prog p;
    biss_cd_result r;
    ck_assert_int_eq(biss_cd_build_read(&p, 1, 0x7e, 1), BISS_CD_OK);
    ck_assert_uint_eq(p.idl, 0); /* the default: IDL0 answers S */
    ck_assert_int_eq(run(&p, 10, &r), BISS_CD_OK);
    ck_assert(r.idl_answered);
    ck_assert_uint_eq(r.idl, 0x07);
    ck_assert_uint_eq(r.header_cds, 0x007); /* S, CTS, ID2 */
    /* slaves that answer from CTS on */
    for (unsigned i = 0; i < 3; i++) {
        chain[i].idl_at_cts = true;
    }
    ck_assert_int_eq(run(&p, 10, &r), BISS_CD_OK);
    ck_assert_uint_eq(r.header_cds, 0x00e); /* CTS, ID2, ID1 */
    ck_assert_uint_eq(r.idl, 0x07 << 1);    /* read at S: one slot off */
    ck_assert_int_eq(biss_cd_set_idl(&p, BISS_CD_IDL_AT_CTS), BISS_CD_OK);
    ck_assert_int_eq(run(&p, 10, &r), BISS_CD_OK);
    ck_assert_uint_eq(r.idl, 0x07);
    /* only a register access has an ID lock to place */
    static biss_cd_prog c;
    ck_assert_int_eq(biss_cd_build_command(&c, 0x02, 1, false), BISS_CD_OK);
    ck_assert_int_eq(biss_cd_set_idl(&c, BISS_CD_IDL_AT_CTS), BISS_CD_E_ARG);
    ck_assert_int_eq(biss_cd_set_idl(&p, (biss_cd_idl_at)7), BISS_CD_E_ARG);
}
END_TEST

/* The IDA slots (host/CD.md, "IDA"): the default reads IDA0 in the answer
 * to the last header CRC bit, where the model and the firmware's IDA test
 * put it; read one slot later the same answers show shifted, and ida_cds
 * reports the slots that answered either way. The firmware's test reads
 * the default slots only, so the other reading is refused with it. */
START_TEST(ida_either_slot) {
    add_chain();
    static biss_cd_prog p;
    biss_cd_result r;
    ck_assert_int_eq(biss_cd_build_command(&p, 0x05, 1, false), BISS_CD_OK);
    ck_assert_uint_eq(p.ida, 15);
    ck_assert_int_eq(run(&p, 0, &r), BISS_CD_OK);
    ck_assert_uint_eq(r.ida, 0x05);
    ck_assert_uint_eq(r.ida_cds, 0x005); /* the CRC step and IDA step 2 */
    ck_assert_int_eq(biss_cd_set_ida(&p, BISS_CD_IDA_AT_SLOT), BISS_CD_OK);
    ck_assert_uint_eq(p.ida, 16);
    ck_assert_int_eq(run(&p, 0, &r), BISS_CD_E_IDA);
    ck_assert_uint_eq(r.ida, 0x02); /* ID 0's answer fell before slot 0 */
    ck_assert_uint_eq(r.ida_cds, 0x005);
    ck_assert_int_eq(biss_cd_build_command(&p, 0x05, 1, true), BISS_CD_OK);
    ck_assert_int_eq(biss_cd_set_ida(&p, BISS_CD_IDA_AT_SLOT), BISS_CD_E_ARG);
    ck_assert_int_eq(biss_cd_set_ida(&p, BISS_CD_IDA_AT_CRC), BISS_CD_OK);
}
END_TEST

/* Register access to the middle slave of the chain. */
START_TEST(chain_register_access) {
    add_chain();
    regfile_poke(&regs, 0, 0x7e, 0x57);
    regfile_poke(&regs, 0, 0x7f, 0x41);
    biss_cd_result r;
    static const uint8_t want[] = {0x57, 0x41};
    ck_assert_int_eq(read_regs(1, 0x7e, 2, 10, &r), BISS_CD_OK);
    assert_bytes(&r, want, 2);
    ck_assert_uint_eq(chain[1].reads, 2);
    ck_assert_uint_eq(chain[0].reads + chain[2].reads, 0);
}
END_TEST

int main(void) {
    Suite *s = suite_create("proto_cd_sim");
    TCase *tc = tcase_create("sim");
    tcase_add_checked_fixture(tc, setup, NULL);
    tcase_add_test(tc, single_read_temperature);
    tcase_add_test(tc, sequential_reads_table11);
    tcase_add_test(tc, read_64_across_bank_switch);
    tcase_add_test(tc, write_then_read_back);
    tcase_add_test(tc, write_read_only_register);
    tcase_add_test(tc, late_start_within_wait_limit);
    tcase_add_test(tc, late_start_beyond_wait_limit);
    tcase_add_test(tc, corrupted_cds_bit);
    tcase_add_test(tc, other_id_answers_nothing);
    tcase_add_test(tc, frame_failure_mid_program);
    tcase_add_test(tc, refused_program);
    tcase_add_test(tc, back_to_back_waits_for_the_zeros);
    tcase_add_test(tc, command_broadcast);
    tcase_add_test(tc, command_addressed);
    tcase_add_test(tc, command_ida_test);
    tcase_add_test(tc, id_lock_either_slot);
    tcase_add_test(tc, ida_either_slot);
    tcase_add_test(tc, command_frame_failure);
    tcase_add_test(tc, failure_then_lead_in);
    tcase_add_test(tc, lead_in_moves_the_fields);
    tcase_add_test(tc, chain_register_access);
    suite_add_tcase(s, tc);
    return check_run(s);
}
