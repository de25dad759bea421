#!/usr/bin/env python3
"""The widest chain the firmware takes, against the real firmware image on
the emulator: eight slaves (BISS_MAX_SLAVES) of 64 data bits
(BISS_MAX_DATA_BITS: a 62-bit position, nE, nW) and a 16-bit CRC
(BISS_MAX_CRC_BITS) each, 640 bits a frame (test/scenarios/chain8-widest.json),
at the fastest rate (10 MHz), 1 MHz and the slowest (125 kHz: a frame of
some 5 ms), on a short cable and on the longest TIDEP0022 Table 5 gives the
rate (proto/biss_line.c: 10 m at 10 MHz, 60 m at 1 MHz, 100 m below),
free-running, host- and IEP-triggered.

Every frame must be valid, every position the one the encoder model sent,
every MA half period H, MA high for at least H before every frame's first
falling edge, and nothing refused or flagged. Each run also reads the last
slave's registers 0x78-0x7F through control frames (its CDS comes after
the other seven slaves' 560 bits): they must read "WIDEST-7", as the
scenario sets them.

usage: widest_chain.py BISS_SIM SCENARIO
"""
import json
import subprocess
import sys

sim, scenario = sys.argv[1], sys.argv[2]
FRAMES = 12
CASES = {10000000: [2, 10], 1000000: [2, 60], 125000: [2, 100]}
failures = []
runs = 0

for freq, cables in CASES.items():
    for m in cables:
        for trigger in ("free", "host", "iep"):
            args = ["--scenario", scenario, "--freq", str(freq), "--cable-m", str(m),
                    "--frames", str(FRAMES), "--trigger", trigger, "--reg-read", "7:0x78:8"]
            runs += 1
            r = subprocess.run([sim, "--json"] + args, capture_output=True, text=True)
            try:
                j = json.loads(r.stdout)
            except ValueError:
                failures.append("%s exited %d: %s" % (" ".join(args), r.returncode,
                                                      r.stderr.strip()))
                continue
            f = j["firmware"]
            bad = {k: f[k] for k in ("no_slave", "processing_errors", "ack_jumps", "off_grid")
                   if f[k]}
            if r.returncode:
                bad["exit"] = r.returncode
            for k in ("crc_errors", "position_mismatches"):
                if j[k]:
                    bad[k] = j[k]
            if j["frames"] != FRAMES or len(j["slaves"]) != 8:
                bad["frames"] = (j["frames"], len(j["slaves"]))
            half = j["ma_half_period_cycles"]
            if half["min"] != half["max"] or half["min"] != 100000000 // freq:
                bad["ma_half_period_cycles"] = half
            cd = j["control"]
            if cd["result"] != "ok" or bytes(cd["bytes"]) != b"WIDEST-7":
                bad["control"] = cd
            starts = j["frame_starts"]
            if starts["ma_high_shorter_than_half"] or starts["frames"] < FRAMES - 1:
                bad["ma_high"] = (starts["frames"], starts["ma_high_shorter_than_half"])
            if bad:
                failures.append("%s: %s" % (" ".join(args), bad))

for f in failures:
    print("FAIL:", f)
print("widest_chain: %d runs, %d failure(s)" % (runs, len(failures)))
sys.exit(1 if failures else 0)
