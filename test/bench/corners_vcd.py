#!/usr/bin/env python3
"""The corners of the envelope at the pins (issue 23, "Done when"):

1. MA is high for at least one half period before every frame's first
   falling edge, at the master's pin, after any kind of frame and under
   every trigger. Checked on the VCD biss-sim writes (1 ps) while an
   8-byte register read runs (its frames end with CDM = 1, MA low through
   the slave's timeout), at every rate/length pair of TIDEP0022's Table 5
   and at 2 m, by a decoder written from the protocol alone: BiSS-C
   frames are separated by the slave's timeout, during which MA stands
   still and at whose end SL rises (iC-MB4 datasheet, "BiSS C Frame": the
   last slave drives SL high in the timeout state; the master may start
   the next frame once it sees that). So a frame's first falling edge is
   the first MA fall after an interval in which MA did not move for more
   than half a period and SL rose at the master; the MA high phase before
   it runs from MA's last rise. iC-MB4 gives each MA phase 50 % of the
   period (items I302/I303): none may be shorter than H.

2. A two-PRU run whose IEP period is the free-run frame period plus 10
   cycles (the goal for the shortest exact period) reads every period on
   both PRUs: no period skipped (the follower silently reading at half
   rate), every frame the same time after its period's start.
"""
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
tmp = tempfile.mkdtemp()


def edges(vcd, name):
    return [(int(t), v) for t, v in vcd[("bench", name)]]


def first_falls(ma, sl, half_ps):
    """(fall time, MA high before it) of every frame that follows a slave
    timeout: the first MA fall after a still interval of MA (longer than
    half a period) in which SL rose at the master."""
    sl_rises = [t for t, v in sl if v == "1"]
    out, last_rise, armed = [], None, False
    for k, (t, v) in enumerate(ma):
        if k > 0 and t - ma[k - 1][0] > half_ps:
            i = bisect.bisect_right(sl_rises, ma[k - 1][0])
            armed = armed or (i < len(sl_rises) and sl_rises[i] < t)
        if v == "1":
            last_rise = t
        elif armed and last_rise is not None:
            out.append((t, t - last_rise))
            armed = False
    return out


def run(*args):
    vcd = os.path.join(tmp, "run.vcd")
    r = subprocess.run([SIM, *map(str, args), "--vcd", vcd, "--vcd-timescale", "1ps"],
                       capture_output=True, text=True, timeout=600)
    return r, read_vcd(vcd)[1] if os.path.exists(vcd) else None


PAIRS = [(10000000, 10), (5000000, 25), (2000000, 60), (1000000, 100), (10000000, 2), (1000000, 2)]
for freq, cable in PAIRS:
    half_ps = int(100e6 / freq) * 5000
    for trig in ("free", "host", "iep"):
        name = "%g MHz on %d m, %s" % (freq / 1e6, cable, trig)
        r, vcd = run("--freq", freq, "--cable-m", cable, "--trigger", trig, "--frames", 200,
                     "--reg-read", "0:0x78:8")
        if not check(vcd is not None, "%s: no VCD (%d %s)" % (name, r.returncode, r.stderr)):
            continue
        falls = first_falls(edges(vcd, "MA_master"), edges(vcd, "SL_master"), half_ps)
        check(len(falls) >= 150, "%s: %d frames found in the VCD" % (name, len(falls)))
        short = [(t, h) for t, h in falls if h < half_ps]
        check(not short, "%s: %d frames begin after an MA high phase shorter than H = %d ns, "
              "the first at %.3f us: %.1f ns" % (name, len(short), half_ps // 1000,
                                                 short[0][0] / 1e6 if short else 0,
                                                 short[0][1] / 1e3 if short else 0))

# every IEP period read on both PRUs at the free-run period + 10 cycles
for profile, freq, cable in [("tidep0022-test-encoder", 10000000, 10),
                             ("hengstler-ad38", 2000000, 10)]:
    r = subprocess.run([SIM, "--profile", profile, "--freq", str(freq), "--cable-m", str(cable),
                        "--frames", "200", "--json"], capture_output=True, text=True)
    free = json.loads(r.stdout)["frame_period_ns"]["mean"] / 5.0
    period = int(free) + 10
    r = subprocess.run([SIM, "--profile", profile, "--pru1-profile", profile, "--freq", str(freq),
                        "--cable-m", str(cable), "--iep-period-ns", str(5 * period),
                        "--settle-frames", "300", "--frames", "200", "--json"],
                       capture_output=True, text=True, timeout=600)
    name = "%s at %g MHz, IEP period %d cycles (free-run %.0f)" % (profile, freq / 1e6, period, free)
    try:
        j = json.loads(r.stdout)
    except ValueError:
        check(False, "%s: no result (%d %s)" % (name, r.returncode, r.stderr))
        continue
    for pru in ("pru0", "pru1"):
        i = (j[pru].get("frame_starts") or {}).get("iep") or {}
        t = i.get("trigger_to_first_fall_cycles") or {}
        check(j[pru]["frames"] == 200 and i.get("skipped_periods") == 0
              and i.get("periods") == i.get("frames") and t.get("min") == t.get("max"),
              "%s: %s read %s frames in %s periods, %s skipped, trigger to first fall %s" %
              (name, pru, i.get("frames"), i.get("periods"), i.get("skipped_periods"), t))
finish("corners at the pins")
