#!/usr/bin/env python3
"""bissctl probe as a user runs it, and what it writes read back: an encoder
with a life counter and no nE/nW (test/host/scenarios/lc-no-ew.json) is
probed, its --slave line reads it, its scenario runs in biss-sim with the
counter checked, and probing that scenario gives the same layout again
(probe -> scenario -> biss-sim -> probe)."""
import json
import os
import re
import subprocess
import sys
import tempfile
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "common"))
from checks import check, finish  # noqa: E402

CTL, SIM = sys.argv[1], sys.argv[2]
HERE = os.path.dirname(os.path.abspath(__file__))
LC_NO_EW = os.path.join(HERE, "scenarios", "lc-no-ew.json")
FREQ = ["--freq", "10000000"]


def run(prog, *args):
    return subprocess.run([prog, *args], capture_output=True, text=True, timeout=300)


def options_line(out):
    m = re.search(r"^options: (.*)$", out, re.M)
    return m.group(1) if m else None


with tempfile.TemporaryDirectory() as tmp:
    # the encoder: 18 position bits, a 6-bit counter below them, CRC6 from 0x2A
    written = os.path.join(tmp, "probed.json")
    r = run(CTL, "--scenario", LC_NO_EW, *FREQ, "probe", written)
    check(r.returncode == 0 and "verdict: unique:" in r.stdout, "probe: %d %r" % (r.returncode, r.stdout))
    check("no nE/nW" in r.stdout and "6-bit life counter" in r.stdout, "fields: %r" % r.stdout)
    opts = options_line(r.stdout)
    check(opts == "--slave 24,6,0x43,0x2A,-,18 --check-life 0,6", "options: %r" % opts)

    # the scenario names every field: position above the counter, no nE/nW
    with open(written) as f:
        sc = json.load(f)
    s0 = sc["biss"]["slaves"][0]
    check((s0["position_bits"], s0["error_bit"], s0["warning_bit"], s0["life_counter_bits"],
           s0["crc_poly"], s0["crc_start"]) == (18, False, False, 6, "0x43", "0x2A"),
          "scenario slave: %r" % s0)

    # the --slave line reads the encoder: CRCs good, the counter advancing,
    # positions from the 18 bits above it
    r = run(CTL, "--scenario", LC_NO_EW, *FREQ, *opts.split(), "read", "-n", "12")
    frames = [l for l in r.stdout.splitlines() if " valid " in l]
    check(r.returncode == 0 and len(frames) >= 10, "read: %d %r %r" % (r.returncode, r.stdout, r.stderr))
    check(all("s0.crc=ok" in l and "s0.nE=none" in l for l in frames), "read: %r" % frames)
    check(re.search(r"safety: s0.life_checked=(\d+) s0.life_frozen=0 s0.life_skipped=0", r.stdout)
          and int(re.search(r"life_checked=(\d+)", r.stdout).group(1)) >= 9, "life: %r" % r.stdout)
    pos = [int(re.search(r"s0.pos=(\d+)", l).group(1)) for l in frames]
    data = [int(re.search(r"s0.data=0x([0-9a-f]+)", l).group(1), 16) for l in frames]
    check(all(p == d >> 6 for p, d in zip(pos, data)), "positions above the counter: %r %r" % (pos, data))

    # biss-sim runs the scenario and checks the counter it names
    r = run(SIM, "--scenario", written, "--frames", "50", "--check-life", "0,6")
    check(r.returncode == 0 and re.search(r"checked +0 CRC errors, 0 position mismatches", r.stdout)
          and re.search(r"life counter 0 +49 frames checked, 0 frozen, 0 skipped", r.stdout),
          "biss-sim: %d %r %r" % (r.returncode, r.stdout, r.stderr))

    # probing the written scenario finds the same layout
    again = os.path.join(tmp, "again.json")
    r = run(CTL, "--scenario", written, *FREQ, "probe", again)
    check(r.returncode == 0 and "verdict: unique:" in r.stdout and options_line(r.stdout) == opts,
          "round trip: %r" % r.stdout)
    with open(again) as f:
        check(json.load(f)["biss"]["slaves"][0] == s0, "round trip scenario")

# the time limit: a 547-bit chain (a second or so of search) stopped at
# 0.2 s says so and decides nothing; bad values are usage errors
LONG = os.path.join(HERE, "scenarios", "long-chain-547.json")
r = run(CTL, "--scenario", LONG, *FREQ, "probe", "--time-limit", "0.2")
check(r.returncode == 1 and "stopped at the time limit" in r.stdout
      and re.search(r"^verdict: (cannot decide|ambiguous): ", r.stdout, re.M)
      and "options:" not in r.stdout.split("verdict:")[0],
      "--time-limit 0.2: %d %r" % (r.returncode, r.stdout))
for bad in ["0", "abc", "-1", "1e9"]:
    r = run(CTL, "probe", "--time-limit", bad)
    check(r.returncode == 2 and "--time-limit" in r.stderr, "--time-limit %s: %d %r" % (bad, r.returncode, r.stderr))
r = run(CTL, "probe", "--help")
check(r.returncode == 0 and "--time-limit S" in r.stdout and "default 60" in r.stdout, "probe --help: %r" % r.stdout)

finish("probe_cli")
