#!/usr/bin/env python3
"""The bit-grid check (pru_fw/biss_periods.hp GRID_CHECK, BISS_RF_OFF_GRID)
against the real firmware image on the emulator:

1. Clean lines: no frame is refused, at every rate where the check runs
   (H >= 16: 6.25 MHz and below) and at 10 MHz, on the encoders of the
   profiles (20 us and the AD38's 650 ns timeout, a 3-word chain) and the
   cable lengths TIDEP0022 Table 5 allows the rate; and at the corners:
   IEP and host triggers, 8-slave chains, register reads (CDM = 1) on the
   longest cables, none refused, marginal or warned.
2. Both lines glitched (test/scenarios/noise-both-30khz-jitter.json) at
   5 and 2 MHz: frames are refused for the grid, and every wrong word
   still published as valid is, by the bench's own look at SL at the
   master (emulator/bench/wrong_frame.c), a clean frame on the wire, one
   whose only edges off the grid were a pulse between two of the master's
   sample instants (its samples a clean frame), or, at most 2 in these
   20,000 frames, one with an edge off the grid that the samples saw: the
   window (2 samples before the sample point, 1 after) leaves a band of
   about one and a half to two and a half samples beside the grid, and of
   the last bits, read from the last switch period's snapshot, only the
   first is checked (pru_fw/README.md, "Bit grid": 4 such in 3 x 10^5
   frames at 1, 2 and 5 MHz; with no check the CRC6 passes about 1 in 64
   of the frames the check refuses here with a wrong word, some 15 and 25);
   none a misread
   clean frame. At 10 MHz
   (H = 10, no room: the check does not run) no frame is ever refused for
   it.

usage: bit_grid.py BISS_SIM
"""
import json
import os
import subprocess
import sys

sim = sys.argv[1]
failures = []


def run(args):
    r = subprocess.run([sim, "--json"] + args, capture_output=True, text=True)
    if r.returncode != 0:
        failures.append("%s exited %d: %s" % (" ".join(args), r.returncode, r.stderr.strip()))
        return None
    return json.loads(r.stdout)


CLEAN = [
    ("tidep0022-test-encoder", 10000000, [2, 10]),
    ("tidep0022-test-encoder", 6250000, [0, 10]),
    ("tidep0022-test-encoder", 5000000, [2, 25]),
    ("tidep0022-test-encoder", 2000000, [2, 60]),
    ("tidep0022-test-encoder", 1000000, [0, 100]),
    ("hengstler-ad38", 6250000, [2]),
    ("hengstler-ad38", 5000000, [25]),
    ("hengstler-ad38", 2000000, [2, 60]),
    ("hengstler-ad38", 1000000, [100]),
    ("posital-kit-layout-biss-c", 5000000, [10]),
    ("ssi", 1000000, [10]),
]
for profile, freq, cables in CLEAN:
    for m in cables:
        args = ["--profile", profile, "--freq", str(freq), "--cable-m", str(m), "--frames", "2000"]
        j = run(args)
        if j is None:
            continue
        f = j["firmware"]
        if f["off_grid"] != 0 or j["crc_errors"] != 0:
            failures.append("%s: %d frames refused off the grid, %d CRC errors on a clean line"
                            % (" ".join(args), f["off_grid"], j["crc_errors"]))

# the envelope's corners where the check runs: the IEP and host triggers,
# 8-slave chains (650 ns and 20 us timeouts) at the shortest checked tail
# (6.25 MHz) and on the longest cable, control frames (CDM = 1) reading
# registers on the longest cable a rate allows
SCEN = os.path.join(os.path.dirname(os.path.abspath(sys.argv[2])) if len(sys.argv) > 2
                    else "test/scenarios")
CORNERS = [
    ["--trigger", "iep", "--freq", "5000000", "--cable-m", "25"],
    ["--profile", "hengstler-ad38", "--trigger", "iep", "--freq", "2000000", "--cable-m", "60"],
    ["--trigger", "host", "--freq", "1000000", "--cable-m", "100"],
    ["--scenario", os.path.join(SCEN, "chain8-650ns.json"), "--freq", "6250000", "--cable-m", "2"],
    ["--scenario", os.path.join(SCEN, "chain8-20us.json"), "--freq", "1000000", "--cable-m", "100"],
    ["--freq", "5000000", "--cable-m", "25", "--reg-read", "0:0x78:8"],
    ["--freq", "1000000", "--cable-m", "100", "--reg-read", "0:0x44:8"],
]
for args in CORNERS:
    j = run(args + ["--frames", "2000"])
    if j is None:
        continue
    f, k = j["firmware"], j["link"]
    if f["off_grid"] or j["crc_errors"] or k["marginal_frames"] or k["warning_frames"]:
        failures.append("%s: %d refused off the grid, %d CRC errors, %d marginal, %d warned"
                        % (" ".join(args), f["off_grid"], j["crc_errors"], k["marginal_frames"],
                           k["warning_frames"]))

NOISE = "test/scenarios/noise-both-30khz-jitter.json"
for freq in (5000000, 2000000, 10000000):
    args = ["--scenario", sys.argv[2] if len(sys.argv) > 2 else NOISE, "--freq", str(freq),
            "--frames", "20000", "--max-ms", "2000"]
    j = run(args)
    if j is None:
        continue
    f, w = j["firmware"], j["wrong_frames"]
    if freq == 10000000:
        if f["off_grid"] != 0:
            failures.append("%s: %d frames refused for the grid where it does not run"
                            % (" ".join(args), f["off_grid"]))
        continue
    if f["off_grid"] == 0:
        failures.append("%s: no frame refused for the grid under glitches" % " ".join(args))
    if w["off_grid"] > 2 or w["other"] != 0:
        failures.append("%s: wrong but valid: %d with an edge off the grid the samples saw "
                        "(at most 2), %d other" % (" ".join(args), w["off_grid"], w["other"]))
    print("%d MHz: %d published, %d CRC errors, %d refused off the grid (%d of them right), "
          "%d wrong but valid: %d clean on the wire, %d a pulse between samples, %d off the grid"
          % (freq // 1000000, f["publications"], j["crc_errors"], f["off_grid"],
             f["off_grid_good_lost"], j["position_mismatches"], w["valid_on_the_wire"],
             w["between_samples"], w["off_grid"]))

for msg in failures:
    print("FAIL:", msg)
sys.exit(1 if failures else 0)
