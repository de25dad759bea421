#!/usr/bin/env python3
"""The work after a frame against BISS_POST_MIN_CYCLES (include/biss/biss_shm.h),
from the real firmware's instruction trace on the emulator (biss-sim --trace).

The idle polls after a frame take SL's newest samples all high for the end
of the slave's timeout; the firmware cuts the last period's tails only
where 5 samples fit in the cycles from the frame's last R31 read to the
first poll's read, and counts on at least BISS_POST_MIN_CYCLES of them
(pru_fw/biss_master.p, POST_MIN; test/bench/long_lines.py shows what
happened without). Here every frame's count is measured, on the paths
after a frame: free-running (FE_START), IEP (IEP_START), the host's
trigger and control frames (FE_SLOW), SSI, an 8-slave chain at 10 MHz,
and both lines glitched (frames refused for an ACK jump or an edge off
the grid, whose paths differ) with the host's trigger; the least of them
must not be below BISS_POST_MIN_CYCLES, and each kind of path must show.

usage: post_frame.py BISS_SIM PRUASM SOURCE_DIR
"""
import json
import os
import re
import subprocess
import sys
import tempfile

sim, pruasm, src = sys.argv[1:4]
shm = open(os.path.join(src, "include", "biss", "biss_shm.h")).read()
POST_MIN = int(re.search(r"#define BISS_POST_MIN_CYCLES\s+(\d+)", shm).group(1))
failures = []

tmp = tempfile.mkdtemp()
base = os.path.join(tmp, "fw")
r = subprocess.run([pruasm, "-bl", "-DPRU_NUM=0", os.path.join(src, "pru_fw", "biss_master.p"),
                    base], capture_output=True, text=True)
if r.returncode:
    sys.exit("pruasm: %s%s" % (r.stdout, r.stderr))
labels = {}
for line in open(base + ".lst"):
    m = re.match(r"\S+\(\s*\d+\) : 0x([0-9a-f]+) = Label\s*: (\w+):", line)
    if m:
        labels.setdefault(m.group(2), int(m.group(1), 16))
FRAME_END = labels["FRAME_END"]
# where the first poll after a frame reads SL, by path
POLLS = {labels[n]: n for n in ("FE_POLL", "IEP_POLL", "SLAVE_IDLE_POLL")}


def after_frames(args):
    """(cycles from the last R31 read to the first after FRAME_END, the
    label of that read's poll) for every frame of a run."""
    trace = os.path.join(tmp, "trace.txt")
    r = subprocess.run([sim, "--firmware", base + ".bin", "--trace", trace, "--json"] + args,
                       capture_output=True, text=True)
    if r.returncode:
        failures.append("biss-sim %s: exit %d: %s" % (" ".join(args), r.returncode, r.stderr))
        return []
    fw = json.loads(r.stdout)["firmware"]
    if "noise" in " ".join(args) and not (fw["ack_jumps"] and fw["off_grid"]):
        failures.append("biss-sim %s: no frame refused for an ACK jump (%d) or off the grid (%d)"
                        % (" ".join(args), fw["ack_jumps"], fw["off_grid"]))
    out, last_read, pending = [], None, None
    with open(trace) as f:
        for line in f:
            p = line.split(None, 2)
            if len(p) < 3 or not p[0].isdigit():
                continue  # the fast-forward's notes
            cycle, pc = int(p[0]), int(p[1], 16)
            if pc == FRAME_END:
                pending = last_read
            if "r31" in p[2].split("  ")[0]:
                if pending is not None:
                    out.append((cycle - pending, POLLS.get(pc, "0x%x" % pc)))
                    pending = None
                last_read = cycle
    os.remove(trace)
    return out


RUNS = [
    ["--freq", "1000000", "--frames", "20"],
    ["--freq", "1000000", "--frames", "20", "--trigger", "iep"],
    ["--freq", "1000000", "--frames", "20", "--trigger", "host"],
    ["--freq", "1000000", "--frames", "40", "--reg-read", "0:0x44:2"],
    ["--profile", "ssi", "--freq", "1000000", "--frames", "20"],
    ["--scenario", os.path.join(src, "test", "scenarios", "chain8-650ns.json"),
     "--freq", "10000000", "--frames", "20"],
    ["--scenario", os.path.join(src, "test", "scenarios", "noise-both-30khz-jitter.json"),
     "--freq", "1000000", "--frames", "400", "--trigger", "host", "--max-ms", "2000"],
]
least = None
polls = set()
for args in RUNS:
    got = after_frames(args)
    if not got:
        failures.append("biss-sim %s: no frame measured" % " ".join(args))
        continue
    n, poll = min(got)
    polls |= {p for _, p in got}
    print("%-90s %4d frames, least %d cycles (%s)" % (" ".join(args)[-90:], len(got), n, poll))
    least = n if least is None else min(least, n)
    if n < POST_MIN:
        failures.append("biss-sim %s: %d cycles from the last R31 read to the first poll's (%s), "
                        "under BISS_POST_MIN_CYCLES = %d" % (" ".join(args), n, poll, POST_MIN))
for name in POLLS.values():
    if name not in polls:
        failures.append("no frame ended in %s" % name)
for f in failures:
    print("FAIL:", f)
print("post_frame: least %s cycles (BISS_POST_MIN_CYCLES %d), %d failure(s)"
      % (least, POST_MIN, len(failures)))
sys.exit(1 if failures else 0)
