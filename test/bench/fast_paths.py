#!/usr/bin/env python3
"""Every fast path of the emulator changes nothing but speed: biss-sim runs
with all of them, without each one and without any write the same VCD
(1 ps, every edge exact) and the same results, and each fast path does skip
work where it applies; with two PRUs, run ahead (run-ahead) or cycle by
cycle, the same results."""
import json
import os
import subprocess
import sys
import tempfile
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "common"))
from checks import check, finish  # noqa: E402

SIM = sys.argv[1]
SCEN = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "scenarios")


tmp = tempfile.mkdtemp()


def sim_json(args, off):
    """biss-sim's JSON with the fast paths in off turned off; a failed run
    ends the test."""
    cmd = [SIM, *args, "--json"]
    for p in off:
        cmd += ["--no-fast-path", p]
    r = subprocess.run(cmd, capture_output=True, text=True, timeout=300)
    if r.returncode:
        print("FAIL: %s exited %d: %s" % (" ".join(cmd), r.returncode, r.stderr))
        sys.exit(1)
    return json.loads(r.stdout)


def run(name, args, off):
    vcd = os.path.join(tmp, "%s-%s.vcd" % (name, "-".join(off) or "all"))
    j = sim_json([*args, "--vcd", vcd, "--vcd-timescale", "1ps"], off)
    del j["host_seconds"]
    skipped = j.pop("skipped_iterations")
    return j, open(vcd, "rb").read(), skipped


cases = [
    ("default-10MHz", ["--frames", "200"]),
    ("default-1MHz-100m", ["--frames", "100", "--freq", "1000000", "--cable-m", "100"]),
    ("chain-2MHz", ["--profile", "hengstler-ad38", "--freq", "2000000", "--frames", "60"]),
    # the AD38 chain's adaptive timeout at the top rate, and a fixed 650 ns
    # one (the slave's quick step either way)
    ("chain-10MHz", ["--scenario", os.path.join(SCEN, "encoder-ad38.json"), "--freq", "10000000",
                     "--frames", "100"]),
    ("chain8-650ns", ["--scenario", os.path.join(SCEN, "chain8-650ns.json"), "--freq", "10000000",
                      "--frames", "60"]),
    ("ssi", ["--profile", "ssi", "--frames", "100"]),
    ("register-read", ["--frames", "60", "--reg-read", "0:0x78:4"]),
    # IEP-triggered frames wait in IEP_POLL, counted down below 0
    ("iep-10MHz", ["--trigger", "iep", "--frames", "100"]),
    # the bench's clocking image: its half periods are LOOP delays (the
    # firmware's are not: docs/silicon-assumptions.md A2)
    ("image-1MHz", ["--image", os.path.join(os.path.dirname(__file__), "clock_frames.p"),
                    "--freq", "1000000", "--frames", "10"]),
    # noise on the SL line (glitches; glitches and jitter on both lines):
    # sl-reach counts the SL line's own events at their time, with jitter
    # any other event 1 ps after its own
    ("noise-sl", ["--scenario", os.path.join(SCEN, "noise-sl-100khz.json"), "--frames", "100"]),
    ("noise-jitter", ["--scenario", os.path.join(SCEN, "noise-both-30khz-jitter.json"),
                      "--frames", "100"]),
]
paths = ["ff-counted", "ff-r31-bits", "ff-loop-delay", "ff-count-loop", "ff"]
# the core's threaded execute loop (and its kinds: whole-register and
# immediate forms, R30 writes) against the general path: it skips no
# iterations, so only the results and the VCD are compared
# the line model's settled-filter step (line_dir_set_settled_fast): the
# same low-pass results without the arithmetic, so it skips nothing either;
# at 1 MHz on 100 m (tau 200 ns) the lines never settle between clock edges
# the core's leaf calls (the firmware's delay tails replayed from a memo,
# leaf.h leaf_call()): the same registers, cycles and pins, no iteration
# skipped either
# the BiSS-C slave's quick step (biss_slave_set_quick): a clocked MA edge
# in one step, the adaptive timeout's included; it skips nothing either
# the core's straight runs (predecode.c set_run(), exec.c RUN_ENTER): runs
# of register-only instructions, and the firmware's pairs and carry chain
# in them, without the checks between them, and a call of a routine that is
# one returning JMP as one with it; nothing skipped either
loops = ["fast-loop", "leaf-call", "line-settled", "slave-quick", "straight-run"]
# the link's bound on the next SL change (link_next_sl_change): it may
# change how far the core skips, so only the results and the VCD count
bounds = ["sl-reach"]
skips_less = {p: [] for p in paths}  # the cases in which the path skipped something
all_skipped = {}  # iterations skipped with every fast path on, by case
for name, args in cases:
    ref, ref_vcd, ref_skip = run(name, args, [])
    all_skipped[name] = ref_skip
    for path in paths:
        j, vcd, skip = run(name, args, [path])
        what = "%s without %s" % (name, path)
        check(j == ref, "%s: other results: %s vs %s" % (what, j, ref))
        check(vcd == ref_vcd, "%s: another VCD" % what)
        if skip < ref_skip:
            skips_less[path].append(name)
        if path == "ff":
            check(skip == 0, "%s: still skipped %d" % (what, skip))
    for path in loops:
        j, vcd, skip = run(name, args, [path])
        what = "%s without %s" % (name, path)
        check(j == ref, "%s: other results: %s vs %s" % (what, j, ref))
        check(vcd == ref_vcd, "%s: another VCD" % what)
        check(skip == ref_skip, "%s: skipped %d, not %d" % (what, skip, ref_skip))
    for path in bounds:
        j, vcd, skip = run(name, args, [path])
        what = "%s without %s" % (name, path)
        check(j == ref, "%s: other results: %s vs %s" % (what, j, ref))
        check(vcd == ref_vcd, "%s: another VCD" % what)
for path, where in skips_less.items():
    check(where, "%s skipped nothing in any case" % path)
# the default run at 10 MHz idles in a counted poll; at 1 MHz the image's
# MA half periods are mostly LOOP delays
check("default-10MHz" in skips_less["ff-counted"], "ff-counted at 10 MHz: %s" % skips_less)
check("iep-10MHz" in skips_less["ff-counted"], "ff-counted, IEP frames: %s" % skips_less)
# its poll counts a field (r1.w2): the 20 us timeout's 4-cycle turns, some
# 990 a frame, all but a few skipped
check(all_skipped["default-10MHz"] > 200 * 900,
      "default-10MHz: %d turns skipped in 200 frames" % all_skipped["default-10MHz"])
check("image-1MHz" in skips_less["ff-loop-delay"], "ff-loop-delay at 1 MHz: %s" % skips_less)
# the firmware's clocked periods at 1 MHz wait in its countdown delay
check("default-1MHz-100m" in skips_less["ff-count-loop"], "ff-count-loop at 1 MHz: %s" % skips_less)


# the slave taking a BiSS-C frame's clock edges when the core drives them
# (ma-ahead): off wherever a VCD is written, so compared on the JSON alone,
# on the clocked cases (chains, adaptive and fixed timeouts), a register
# read (control frames), noise (where it does not apply), and a run that
# halts with an edge taken ahead still on the cable (run again without it:
# test_bench checks that such a run is told apart); the same results
def run_json(args, off):
    j = sim_json(args, off)
    del j["host_seconds"]
    j.pop("skipped_iterations")
    return j


def sim_any_exit(args, off):
    """biss-sim's output and exit code, whatever the code."""
    cmd = [SIM, *args, "--json"]
    for p in off:
        cmd += ["--no-fast-path", p]
    r = subprocess.run(cmd, capture_output=True, text=True, timeout=300)
    j = json.loads(r.stdout)
    del j["host_seconds"]
    return j, r.returncode, r.stderr


ahead_cases = cases + [
    ("chain3-650ns", ["--scenario", os.path.join(SCEN, "chain3-650ns.json"), "--freq", "10000000",
                      "--frames", "100"]),
    ("chain1-650ns-5MHz", ["--scenario", os.path.join(SCEN, "chain1-650ns.json"), "--freq",
                           "5000000", "--frames", "100"]),
]
for name, args in ahead_cases:
    ref = run_json(args, ["ma-ahead"])
    on = run_json(args, [])
    check(on == ref, "%s without ma-ahead: other results" % name)
    # the bench's measurements of those edges one by one, not in batches
    check(run_json(args, ["ahead-batch"]) == on, "%s without ahead-batch: other results" % name)
    # the core's straight runs where the slave takes the edges ahead (no VCD)
    check(run_json(args, ["straight-run"]) == on, "%s without straight-run: other results" % name)
halt = ["--image", os.path.join(os.path.dirname(__file__), "halt_in_frame.src"), "--freq", "10000000",
        "--frames", "5"]
on, off = sim_any_exit(halt, []), sim_any_exit(halt, ["ma-ahead"])
check(on == off, "halted in a frame, without ma-ahead: %s vs %s" % (on, off))
check(sim_any_exit(halt, ["ahead-batch"]) == on, "halted in a frame, without ahead-batch")
check(on[0]["stop"] == "halted" and on[0]["frames"] == 4, "halted in a frame: %s" % (on,))

# two PRUs of one PRU-ICSS (no VCD with two): run ahead to each one's next
# cross-PRU event or cycle by cycle, the same results; run ahead the
# fast-forward reaches the polls it cannot reach a cycle at a time, so only
# its own count may differ (more skipped)


def run_pair(name, args, off):
    j = sim_json(args, off)
    skipped = 0
    for pru in ("pru0", "pru1"):
        del j[pru]["host_seconds"]
        skipped += j[pru].pop("skipped_iterations")
    return j, skipped


pairs = [
    ("pair-10MHz", ["--pru1-profile", "hengstler-ad38", "--frames", "100"]),
    ("pair-chain-1MHz", ["--profile", "hengstler-ad38", "--pru1-profile", "tidep0022-test-encoder",
                         "--freq", "1000000", "--frames", "40"]),
    ("pair-noise", ["--scenario", os.path.join(SCEN, "noise-both-30khz-jitter-two-pru.json"),
                    "--pru1-scenario", os.path.join(SCEN, "noise-both-30khz-jitter-two-pru.json"),
                    "--seed", "3", "--frames", "40", "--max-ms", "100"]),
]
for name, args in pairs:
    ref, ref_skip = run_pair(name, args, [])
    j, skip = run_pair(name, args, ["run-ahead"])
    check(j == ref, "%s without run-ahead: other results: %s vs %s" % (name, j, ref))
    check(ref["pru0"]["frames"] == ref["pru1"]["frames"] > 0, "%s: %s" % (name, ref))
    check(ref_skip > skip, "%s: run ahead skipped %d, cycle by cycle %d" % (name, ref_skip, skip))
    j, skip = run_pair(name, args, ["run-ahead", "ff"])
    check(j == ref and skip == 0, "%s without run-ahead and ff: %s vs %s" % (name, j, ref))
# PRU1 alone (PRU0 disabled, its time passing with PRU1's): the VCD too
ref, ref_vcd, _ = run("pru1", ["--pru", "1", "--frames", "100"], [])
j, vcd, _ = run("pru1", ["--pru", "1", "--frames", "100"], ["run-ahead"])
check(j == ref, "PRU1 alone without run-ahead: other results: %s vs %s" % (j, ref))
check(vcd == ref_vcd, "PRU1 alone without run-ahead: another VCD")

finish("fast-path")
