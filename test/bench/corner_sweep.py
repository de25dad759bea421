#!/usr/bin/env python3
"""Random corners of the envelope, against the real firmware image on the
emulator: each case draws a rate (every one `bissctl rates` lists, 10 MHz
to 125 kHz), a cable up to the longest TIDEP0022 Table 5 gives the rate
(proto/biss_line.c), a chain of 1 to 8 slaves of 1 to 62 position bits
(with nE, nW: up to 64 data bits) and a CRC of 3, 5, 6 or 16 bits, a
timeout (fixed 20 us; fixed and short, down to iC-MB4's 55 % of the MA
period; adaptive with the AD38's 650 ns floor), a processing time, a
trigger (free, host, IEP), a frame kind (positions only; a register read
or write, or a command, of a random slave through control frames) and a
place (PRU0; PRU1; an AM437x PRU-ICSS; two PRUs, the second encoder
following the first's IEP; the encoder firmware on PRU1 as the slave).

Every case must run every frame valid, each position the one the encoder
model sent, every MA half period H, MA high for at least H before every
frame's first falling edge, nothing refused or flagged, the control
frames' result ok; on two PRUs the same for PRU1; with the encoder
firmware, its SL the model's at every rising MA edge (biss-sim's exit 0).

The cases are the same on every run (a fixed seed), so a failure names a
case that can be run again from its printed command line.

usage: corner_sweep.py BISS_SIM WORKDIR [CASES [SEED]]
"""
import json
import os
import random
import subprocess
import sys

sim, work = sys.argv[1], sys.argv[2]
n_cases = int(sys.argv[3]) if len(sys.argv) > 3 else 400
seed = int(sys.argv[4]) if len(sys.argv) > 4 else 2026
FRAMES = 12
RATES = [10000000, 6250000, 5000000, 4000000, 3125000, 2500000, 2000000, 1562500, 1250000,
         1000000, 800000, 781250, 625000, 500000, 400000, 390625, 312500, 250000, 200000,
         160000, 156250, 125000]
POLYS = ["0x0B", "0x25", "0x43", "0x190D9"]  # CRC3, CRC5, CRC6, CRC16
PLACES = ["pru0", "pru0", "pru1", "am437x", "pair", "encoder"]


def cable_max(f):
    """TIDEP0022 Table 5 (proto/biss_line.c)."""
    return 10 if f > 5000000 else 25 if f > 2000000 else 60 if f > 1000000 else 100


def draw(rng, case):
    f = rng.choice(RATES)
    m = rng.choice([0, 2, cable_max(f), round(rng.uniform(0, cable_max(f)), 2)])
    n = rng.choice([1, 1, 2, 3, 8, rng.randint(1, 8)])
    slaves = []
    for i in range(n):
        slaves.append({"position_bits": rng.randint(1, 62), "crc_poly": rng.choice(POLYS),
                       "id": i, "counts_per_frame": rng.randint(-1000, 1000),
                       "registers": {"0x78": "0x%02X" % (0x41 + i)}})
    period_ns = 1e9 / f
    kind = rng.choice(["fixed", "short", "adaptive"])
    timeout = ({"mode": "fixed", "ns": 20000} if kind == "fixed" else
               {"mode": "fixed", "ns": max(650, int(period_ns * rng.uniform(0.56, 2.0)) + 1)}
               if kind == "short" else {"mode": "adaptive", "factor": 1.5, "min_ns": 650})
    # processing times as datasheets give them (the AD38's 2.3-2.5 us), in
    # 100 ns steps: the encoder firmware meets one to within a cycle and a
    # half of an MA rise (pru_slave/README.md), the model to the picosecond
    busy = rng.choice([0, 0, 2400, 100 * rng.randint(0, 200)])
    scenario = {"profile": "generic",
                "biss": {"busy_ns": busy, "timeout": timeout, "slaves": slaves}}
    path = os.path.join(work, "corner_%d.json" % case)
    with open(path, "w") as fh:
        json.dump(scenario, fh)
    args = ["--scenario", path, "--freq", str(f), "--cable-m", str(m), "--frames", str(FRAMES),
            "--max-ms", "5000"]
    trigger = rng.choice(["free", "host", "iep"])
    op = rng.choice(["none", "none", "read", "write", "command"])
    place = rng.choice(PLACES)
    target = rng.randint(0, n - 1)
    if place == "pair":  # two PRUs: PRU0 on the IEP, PRU1 following; no control frames
        args += ["--pru1-profile", rng.choice(["tidep0022-test-encoder", "hengstler-ad38"])]
        op = "none"
    else:
        args += ["--trigger", trigger]
        args += {"pru0": [], "pru1": ["--pru", "1"], "encoder": ["--encoder"],
                 "am437x": ["--soc", rng.choice(["am437x-icss0", "am437x-icss1"])]}[place]
    if op == "read":
        args += ["--reg-read", "%d:0x78:1" % target]
    elif op == "write":
        args += ["--reg-write", "%d:0x70:%02x,%02x" % (target, rng.randint(0, 255),
                                                       rng.randint(0, 255))]
    elif op == "command":
        args += ["--command", "%x:%d" % (1 << target, rng.randint(0, 1))]
    return args, op, f, target


def problems(rc, j, op, f, target):
    bad = {}
    if rc:
        bad["exit"] = rc
    parts = [("", j)]
    if "pru0" in j:
        parts = [("pru0.", j["pru0"]), ("pru1.", j["pru1"])]
    for name, p in parts:
        fw = p["firmware"]
        for k in ("no_slave", "processing_errors", "ack_jumps", "off_grid"):
            if fw[k]:
                bad[name + k] = fw[k]
        for k in ("crc_errors", "position_mismatches"):
            if p[k]:
                bad[name + k] = p[k]
        if p["frames"] < FRAMES:
            bad[name + "frames"] = p["frames"]
        half = p["ma_half_period_cycles"]
        if half["min"] != half["max"] or half["min"] != 100000000 // f:
            bad[name + "ma_half_period_cycles"] = half
        if p["frame_starts"]["ma_high_shorter_than_half"]:
            bad[name + "ma_high"] = p["frame_starts"]
    if op != "none":
        cd = j["control"]
        if cd["result"] != "ok" or (op == "read" and cd["bytes"] != [0x41 + target]):
            bad["control"] = cd
    return bad


rng = random.Random(seed)
failures = []
for case in range(n_cases):
    args, op, f, target = draw(rng, case)
    r = subprocess.run([sim, "--json"] + args, capture_output=True, text=True)
    try:
        j = json.loads(r.stdout)
    except ValueError:
        failures.append("%s: exit %d, %s" % (" ".join(args), r.returncode, r.stderr.strip()))
        continue
    bad = problems(r.returncode, j, op, f, target)
    if bad:
        failures.append("%s: %s %s" % (" ".join(args), json.dumps(bad)[:600], r.stderr.strip()))

for f in failures:
    print("FAIL: biss-sim", f)
print("corner_sweep: %d cases (seed %d), %d failure(s)" % (n_cases, seed, len(failures)))
sys.exit(1 if failures else 0)
