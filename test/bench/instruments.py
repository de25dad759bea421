#!/usr/bin/env python3
"""biss-sim's frame instruments (emulator/bench/INSTRUMENTS.md) against what
the VCD it writes shows, read here on their own definitions: every MA high
phase before a frame's first fall and every restart (SL rising at the
master to the next first fall) that biss-sim reports must be those of a run
of consecutive frames in the VCD (1 ps); the publication latency and the
position's age are the same with every fast path of the core off (the
store watch once saw a stale cycle there) and keep their relations; IEP
frames lie one period apart, each the same time after its period's start."""
import bisect
import json
import os
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(__file__))
from vcd_check import read_vcd  # noqa: E402
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "common"))
from checks import check, finish  # noqa: E402

SIM = sys.argv[1]
PS = 5000  # one PRU cycle
tmp = tempfile.mkdtemp()


def run(args):
    vcd = os.path.join(tmp, "run.vcd")
    r = subprocess.run([SIM, *args, "--json", "--vcd", vcd, "--vcd-timescale", "1ps"],
                       capture_output=True, text=True, timeout=300)
    if not check(r.returncode == 0, "%s: exit %d %s" % (args, r.returncode, r.stderr)):
        return None, None
    return json.loads(r.stdout), read_vcd(vcd)[1]


def first_falls(vcd, half):
    """(time, high phase) of each frame's first MA fall at the master: a
    fall whose high phase or the low phase before it is not H."""
    hp, rise, fall, out = half * PS, 0, None, []
    for t, v in vcd[("bench", "MA_master")]:
        if v == "1":
            rise = t
            continue
        if t - rise != hp or fall is None or rise - fall != hp:
            out.append((t, t - rise))
        fall = t
    return out


def restarts(vcd, falls):
    """Each first fall after SL's last rise at the master (None: SL never rose)."""
    rises = [t for t, v in vcd[("bench", "SL_master")] if v == "1"]
    out = []
    for t, _ in falls:
        i = bisect.bisect_left(rises, t) - 1
        out.append(t - rises[i] if i >= 0 else None)
    return out


def span(values):
    return {"min": min(values) / PS, "mean": sum(values) / len(values) / PS, "max": max(values) / PS}


def same_span(a, b):
    return all(abs(a[k] - b[k]) <= 1e-9 * max(1.0, abs(b[k])) for k in ("min", "mean", "max"))


def some_window(values, n, want):
    """Whether n consecutive values (None: skipped) have the span want."""
    for a in range(len(values) - n + 1):
        w = [v for v in values[a:a + n] if v is not None]
        if w and same_span(span(w), want):
            return True
    return False


cases = [
    ("default encoder 10 MHz", ["--freq", "10000000", "--frames", "100"], 10),
    ("register read (CDM = 1 frames)", ["--freq", "10000000", "--frames", "30", "--reg-read", "0:0x44:8"], 10),
    ("AD38 chain 1 MHz 100 m", ["--profile", "hengstler-ad38", "--freq", "1000000",
                                "--cable-m", "100", "--frames", "40"], 100),
    ("SSI 2 MHz", ["--profile", "ssi", "--freq", "2000000", "--frames", "40"], 50),
]
for name, args, half in cases:
    j, vcd = run(args)
    if j is None:
        continue
    fs = j["frame_starts"]
    falls = first_falls(vcd, half)
    highs = [h for _, h in falls]
    n = fs["frames"]
    check(some_window(highs, n, fs["ma_high_before_first_fall_cycles"]),
          "%s: MA high before the first fall %r is no run of %d frames in the VCD" %
          (name, fs["ma_high_before_first_fall_cycles"], n))
    check(any(sum(1 for h in highs[a:a + n] if h < half * PS) == fs["ma_high_shorter_than_half"]
              for a in range(len(highs) - n + 1)),
          "%s: %d phases shorter than H, not in the VCD" % (name, fs["ma_high_shorter_than_half"]))
    check(abs(fs["ma_high_min_of_half"] - fs["ma_high_before_first_fall_cycles"]["min"] / half) < 1e-12,
          "%s: the least high phase as a fraction of H" % name)
    rs = fs["restart_overhead_cycles"]
    check(rs is not None and some_window(restarts(vcd, falls), n, rs),
          "%s: restart %r is no run of %d frames in the VCD" % (name, rs, n))
    over = fs["restart_over_idle_filter_cycles"]
    check(all(abs(over[k] - (rs[k] - half)) < 1e-9 for k in over),
          "%s: the restart over the idle filter is the restart less H: %r %r" % (name, over, rs))
    if name.startswith("SSI"):
        continue
    # the publication: after the last bit's start, its end (2H later) and
    # half a bit (H); the position is older than the last bit
    p = j["firmware"]["publication_latency_cycles"]
    for k in ("min", "mean", "max"):
        check(abs(p["beyond_half_bit"][k] - (p["after_last_bit_start"][k] - half)) < 1e-9
              and abs(p["after_last_bit_end"][k] - (p["after_last_bit_start"][k] - 2 * half)) < 1e-9,
              "%s: latency's forms disagree: %r" % (name, p))
    age = j["firmware"]["position_age_cycles"]
    check(age["min"] > p["after_last_bit_start"]["max"], "%s: age %r, latency %r" % (name, age, p))
    # the same with every fast path of the core off: the watch's cycle is
    # the store's, not the fast loop's last sync
    slow, _ = run(args + ["--no-fast-path", "fast-loop", "--no-fast-path", "ff",
                          "--no-fast-path", "leaf-call"])
    if slow:
        check(slow["firmware"]["publication_latency_cycles"] == p
              and slow["firmware"]["position_age_cycles"] == age,
              "%s: latency/age differ without the fast paths: %r vs %r" %
              (name, slow["firmware"]["publication_latency_cycles"], p))

# IEP frames: one per period, each its start's fixed time after the
# period's start, exactly one period apart at the master pin
j, vcd = run(["--freq", "10000000", "--trigger", "iep", "--iep-period-ns", "50000", "--frames", "40"])
if j:
    iep = j["frame_starts"]["iep"]
    check(iep["period_cycles"] == 10000 and iep["frames"] == 40 and iep["periods"] == 40
          and iep["skipped_periods"] == 0 and iep["crowded_periods"] == 0
          and iep["trigger_to_first_fall_cycles"]["min"] == iep["trigger_to_first_fall_cycles"]["max"],
          "IEP 50 us: %r" % iep)
    times = [t for t, _ in first_falls(vcd, 10)][2:]
    check(all(b - a == 10000 * PS for a, b in zip(times, times[1:])),
          "IEP 50 us: first falls one period apart in the VCD")
    check(j["frame_starts"]["restart_overhead_cycles"] is None, "IEP: no restart overhead")
finish("instruments")
