#!/usr/bin/env python3
"""Every fast path of the emulator changes nothing but speed: biss-sim runs
with all of them, without each one and without any write the same VCD
(1 ps, every edge exact) and the same results, and each fast path does skip
work where it applies."""
import json
import os
import subprocess
import sys
import tempfile

SIM = sys.argv[1]
failures = 0


def check(cond, what):
    global failures
    if not cond:
        failures += 1
        print("FAIL:", what)


tmp = tempfile.mkdtemp()


def run(name, args, off):
    vcd = os.path.join(tmp, "%s-%s.vcd" % (name, "-".join(off) or "all"))
    cmd = [SIM, *args, "--json", "--vcd", vcd, "--vcd-timescale", "1ps"]
    for p in off:
        cmd += ["--no-fast-path", p]
    r = subprocess.run(cmd, capture_output=True, text=True, timeout=300)
    if r.returncode:
        print("FAIL: %s exited %d: %s" % (" ".join(cmd), r.returncode, r.stderr))
        sys.exit(1)
    j = json.loads(r.stdout)
    del j["host_seconds"]
    skipped = j.pop("skipped_iterations")
    return j, open(vcd, "rb").read(), skipped


# (name, arguments, whether the frames have idle time to skip: the chain's
# adaptive timeout is 1.5 MA periods, so its firmware never waits long)
cases = [
    ("default-10MHz", ["--frames", "200"], True),
    ("default-1MHz-100m", ["--frames", "100", "--freq", "1000000", "--cable-m", "100"], True),
    ("chain-2MHz", ["--profile", "hengstler-ad38", "--freq", "2000000", "--frames", "60"], False),
    ("ssi", ["--profile", "ssi", "--frames", "100"], True),
    ("register-read", ["--frames", "60", "--reg-read", "0:0x78:4"], True),
]
for name, args, idle in cases:
    ref, ref_vcd, ref_skip = run(name, args, [])
    for off in (["ff-counted"], ["ff-r31-bits"], ["ff"]):
        j, vcd, skip = run(name, args, off)
        what = "%s without %s" % (name, off[0])
        check(j == ref, "%s: other results: %s vs %s" % (what, j, ref))
        check(vcd == ref_vcd, "%s: another VCD" % what)
        check(skip < ref_skip or not idle,
              "%s: the fast path skipped nothing (%d vs %d)" % (what, skip, ref_skip))
        if off == ["ff"]:
            check(skip == 0, "%s: still skipped %d" % (what, skip))

print("%d failed" % failures if failures else "all fast-path checks passed")
sys.exit(1 if failures else 0)
