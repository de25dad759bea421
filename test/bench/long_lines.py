#!/usr/bin/env python3
"""Slow rates on long lines, against the real firmware image on the
emulator: the frame after a frame waits for the slave's timeout to end.

iC-MB4's datasheet: "The data transmission is followed by a timeout which
is terminated and signaled to the BiSS master by a rising edge. As soon as
the timeout is detected by the BiSS master it can start a new BiSS frame."
The firmware's polls for it (FE_POLL, IEP_POLL, SLAVE_IDLE) look at the
newest samples of SL being high, which a last bit of 1 shows too until
the samples reach past that bit's end. At a slow rate on a long line the
last bit is read with few newer samples, and the work after the frame
used to be shorter than the rest of that bit: at 200 kHz on 200-290 m,
250 kHz on 200-240 m, 400 kHz on 150-160 m and 125 kHz from 290 m, a
free-running master started its next frame inside the slave's timeout
(processing errors, ACK jumps, a register read that never finished).
Above H = BISS_CUT_MAX_HALF the last period now keeps its tails
(pru_fw/biss_master.p, POST_MIN).

Every rate from the last one that cuts its tails (781.25 kHz, H = 128)
down to 125 kHz, three BiSS-C profiles, cables every 10 m up to some 40 m
short of where the cable model's low-pass swallows the MA clock (NO_SLAVE
from there), free-running and IEP-triggered: every frame valid, none
refused or lost; and at the worst corner a register read (CDM = 1 frames,
whose MA rises only when the timeout is seen to end) completes.

An 8-slave chain (test/scenarios/chain8-20us.json: the longest path after
the frame) the same, every 50 m.

usage: long_lines.py BISS_SIM SCENARIO_DIR
"""
import json
import os
import subprocess
import sys

sim, scenarios = sys.argv[1:3]
FRAMES = 40
# rate: the longest cable tested (the model's MA clock is swallowed some
# 40 m further on for the AD38, the shortest of the three)
RATES = {781250: 160, 625000: 180, 400000: 230, 250000: 300, 200000: 340, 125000: 400}
PROFILES = [(["--profile", p], 10) for p in
            ("tidep0022-test-encoder", "hengstler-ad38", "posital-kit-layout-biss-c")]
PROFILES.append((["--scenario", os.path.join(scenarios, "chain8-20us.json")], 50))
failures = []
runs = 0


def run(args):
    global runs
    runs += 1
    r = subprocess.run([sim, "--json", "--max-ms", "1000"] + args, capture_output=True, text=True)
    try:
        return r.returncode, json.loads(r.stdout)
    except ValueError:
        failures.append("%s exited %d: %s" % (" ".join(args), r.returncode, r.stderr.strip()))
        return r.returncode, None


for encoder, step in PROFILES:
    for freq, longest in RATES.items():
        for m in range(0, longest + 1, step):
            for trigger in ("free", "iep"):
                args = encoder + ["--freq", str(freq), "--cable-m", str(m),
                                  "--frames", str(FRAMES), "--trigger", trigger]
                rc, j = run(args)
                if j is None:
                    continue
                f = j["firmware"]
                bad = {k: f[k] for k in ("no_slave", "processing_errors", "ack_jumps", "off_grid")
                       if f[k]}
                if rc or j["frames"] < FRAMES or bad or j["crc_errors"] or j["position_mismatches"]:
                    failures.append("%s: exit %d, %d of %d frames, %s, %d CRC errors, %d mismatches"
                                    % (" ".join(args), rc, j["frames"], FRAMES, bad,
                                       j["crc_errors"], j["position_mismatches"]))

# a register read where the free-running master used to start inside the timeout
for m in (200, 250):
    args = ["--freq", "200000", "--cable-m", str(m), "--frames", "100", "--reg-read", "0:0x44:4"]
    rc, j = run(args)
    if j is not None and (rc or (j.get("control") or {}).get("result") != "ok"):
        failures.append("%s: exit %d, control %s" % (" ".join(args), rc, j.get("control")))

for f in failures:
    print("FAIL:", f)
print("long_lines: %d runs, %d failure(s)" % (runs, len(failures)))
sys.exit(1 if failures else 0)
