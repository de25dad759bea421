#!/usr/bin/env python3
"""biss-sim as a user runs it: every profile with JSON and VCD output,
the architecture's JSON keys, exact MA timing, and clear errors."""
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


def run(*args):
    return subprocess.run([SIM, *args], capture_output=True, text=True, timeout=120)


tmp = tempfile.mkdtemp()
profiles = run("--list-profiles").stdout.split()
check(len(profiles) >= 5, "at least five profiles listed: %r" % profiles)
for p in ["tidep0022-test-encoder", "posital-kit-layout-biss-c", "hengstler-ad38", "generic", "ssi"]:
    check(p in profiles, "profile %s listed" % p)

KEYS = ["frames", "crc_errors", "position_mismatches", "line_delay_ns", "frame_period_ns",
        "ma_half_period_cycles", "pru_cycles", "host_seconds", "slaves"]
CLOCK_IMAGE = os.path.join(os.path.dirname(__file__), "clock_frames.p")
# every profile with the firmware; and, once, the bench's clocking image,
# which decodes nothing
runs = [(p, True) for p in profiles] + [("generic", False)]
for profile, firmware in runs:
    extra = [] if firmware else ["--image", CLOCK_IMAGE]
    for freq, cable in [(10e6, 2), (1e6, 100)]:
        vcd = os.path.join(tmp, "%s.vcd" % profile)
        r = run("--profile", profile, "--freq", str(int(freq)), "--cable-m", str(cable),
                "--frames", "30", "--seed", "7", "--json", "--vcd", vcd, *extra)
        name = "%s @ %g Hz, %d m" % (profile, freq, cable)
        check(r.returncode == 0, "%s: exit %d, %s" % (name, r.returncode, r.stderr))
        if r.returncode:
            continue
        j = json.loads(r.stdout)
        for k in KEYS:
            check(k in j, "%s: key %s" % (name, k))
        check(j["frames"] == 30, "%s: 30 frames, got %s" % (name, j["frames"]))
        half = 100e6 / freq
        check(j["ma_half_period_cycles"] == {"min": half, "max": half},
              "%s: half period %s" % (name, j["ma_half_period_cycles"]))
        fp = j["frame_period_ns"]
        if firmware:
            # free-running: the next frame starts when the slave's timeout ends,
            # seen on the 8x samples (H/4 cycles apart) by a 4-cycle polling loop
            jitter_ns = (100e6 / freq / 4 + 4) * 5
            check(0 < fp["min"] <= fp["mean"] <= fp["max"] <= fp["min"] + jitter_ns,
                  "%s: frame period %s" % (name, fp))
            check(j["crc_errors"] == 0 and j["position_mismatches"] == 0,
                  "%s: %s CRC errors, %s mismatches" % (name, j["crc_errors"], j["position_mismatches"]))
            check(abs(j["firmware"]["line_delay_ns"] - j["line_delay_ns"]) <= 100e6 / freq / 4 * 5,
                  "%s: firmware line delay %s vs %s" % (name, j["firmware"]["line_delay_ns"], j["line_delay_ns"]))
        else:
            check(fp["min"] == fp["max"] == fp["mean"] > 0, "%s: frame period %s" % (name, fp))
            check(j["crc_errors"] is None, "%s: nothing decoded" % name)
        check(len(j["slaves"]) >= 1, "%s: slaves reported" % name)
        # line delay: at least the cable's propagation both ways
        check(j["line_delay_ns"] > 2 * 5 * cable, "%s: line delay %s" % (name, j["line_delay_ns"]))
        scale, data = read_vcd(vcd)
        check(scale <= 1000, "%s: timescale 1 ns or finer" % name)
        names = {n for (scope, n) in data if scope == "bench"}
        check(names == {"MA_master", "SL_master", "MA_slave", "SL_slave", "frame"},
              "%s: wires %s" % (name, names))
        ma = [c for (s, n), c in data.items() if n == "MA_master"][0]
        falls = sum(1 for t, v in ma if v == "0")
        check(falls >= 30 * 10, "%s: MA clocked (%d falling edges)" % (name, falls))

# an SSI encoder has no control communication: a clear refusal
r = run("--profile", "ssi", "--frames", "3", "--reg-read", "0:0x44")
check(r.returncode == 1 and "SSI" in r.stderr, "ssi with a register read: %r" % r.stderr)

# same seed, same run
a = run("--profile", "generic", "--frames", "10", "--seed", "3", "--json").stdout
b = run("--profile", "generic", "--frames", "10", "--seed", "3", "--json").stdout
strip = lambda s: {k: v for k, v in json.loads(s).items() if k != "host_seconds"}
check(strip(a) == strip(b), "reproducible with the same seed")

# the scope view
svg = os.path.join(tmp, "frame.svg")
r = run("--frames", "5", "--svg", svg, "--svg-frame", "2")
check(r.returncode == 0 and open(svg).read().startswith("<svg"), "SVG written")
check("CDS" in open(svg).read(), "SVG names the bits")
# a frame long gone from the slave's ring of records by the end of the run
# keeps its bit names, and shows what the firmware did with it
r = run("--frames", "300", "--svg", svg, "--svg-frame", "3")
text = open(svg).read() if r.returncode == 0 else ""
check(">CDS<" in text and ">C0<" in text and ">nE<" in text, "SVG of frame 3 of 300 names the bits")
check(text.count('<circle class="mark"') == 1 + 2 + 12 + 2 + 6,
      "SVG: one sample mark per bit read (S, CDS, 12 + 2 + 6) and the legend's")
check("line delay" in text and 'marker-end="url(#head)"' in text, "SVG: the line delay arrow")
check("firmware: frame 3," in text and "slave 0 read: position" in text, "SVG: the values read")

# bad input: a clear message; the command line's exit 2 with the way to
# the help (README "Conventions"), a file that cannot be used exits 1
TRY = "\nTry 'biss-sim --help' for more information.\n"


def refused(args, words, code):
    r = run(*args)
    check(r.returncode == code and words in r.stderr and r.stderr.endswith(TRY) == (code == 2),
          "%s -> %d %r (got %d %r)" % (args, code, words, r.returncode, r.stderr))


for args, words in [(["--profile", "nope"], "biss-sim: --profile 'nope': expected a profile of --list-profiles"),
                    (["--freq", "3e6"], "whole number"),
                    (["--frames", "-5"], "biss-sim: --frames '-5': expected a positive count"),
                    (["--bogus"], "biss-sim: unknown option '--bogus'"),
                    (["--frames"], "biss-sim: option '--frames' needs a value"),
                    (["--soc", "am999"], "biss-sim: --soc 'am999': expected am335x"),
                    (["--vcd-timescale", "2ns"], "--vcd-timescale '2ns'"),
                    (["--svg-frame", "0"], "--svg-frame '0'")]:
    refused(args, words, 2)
for args, words in [(["--image", "/nonexistent.bin"], "cannot read"),
                    (["--scenario", "/nonexistent.json"], "nonexistent"),
                    (["--frames", "2", "--trace", "/nonexistent/t.txt"], "--trace: /nonexistent/t.txt"),
                    (["--frames", "2", "--trace", "/tmp"], "--trace: /tmp: not a regular file")]:
    refused(args, words, 1)
# --trace: every instruction the firmware ran, a line each (cycle, PC, the
# instruction), the first one the start-up's at cycle 0
with tempfile.TemporaryDirectory() as trace_dir:
    path = os.path.join(trace_dir, "t.txt")
    r = run("--frames", "2", "--trace", path)
    lines = open(path).read().splitlines() if os.path.exists(path) else []
    check(r.returncode == 0 and len(lines) > 1000 and lines[0].split()[:2] == ["0", "0000"]
          and any(" r31" in l for l in lines), "--trace: %d, %d lines %r" % (
              r.returncode, len(lines), lines[:1]))
check(run("--help").returncode == 0 and "--profile" in run("--help").stdout, "--help")

# options out of range: refused before the run, the value and the reason named
for args, words in [(["--max-ms", "1e10"], "--max-ms '1e10': expected ms, above 0 and at most"),
                    (["--max-ms", "0"], "--max-ms '0'"),
                    (["--freq", "20000000"], "--freq '20000000': the firmware cannot clock it: faster than"),
                    (["--freq", "100000"], "--freq '100000': the firmware cannot clock it: no exact 8x shift clock")]:
    refused(["--frames", "5", *args], words, 2)
# the bench's own clocking image may run faster than the firmware
r = run("--image", CLOCK_IMAGE, "--freq", "20000000", "--frames", "3")
check(r.returncode == 0, "--image at 20 MHz: %d %r" % (r.returncode, r.stderr))


def scenario_as(name, text):
    path = os.path.join(tmp, name)
    with open(path, "w") as f:
        f.write(text)
    return path


def scenario(text):
    return scenario_as("bad.json", text)


# scenario files: every bad value is named with the file and the JSON path
for text, words in [('{"line": {"length_m": 1e300}}', "bad.json: line.length_m: 1e+300 out of range 0..1000"),
                    ('{"biss": {"busy_ns": 9e9}}', "bad.json: biss.busy_ns: 9000000000 out of range 0..1000000"),
                    ('{"biss": {"slaves": [{"position_bits": 64, "fill_bits": 64, "life_counter_bits": 32}]}}',
                     "bad.json: biss.slaves[0].fill_bits: 64 out of range 0..63"),
                    ('{"seed": 18446744073709551615}', "bad.json: seed: a JSON number is exact only below 2^53"),
                    ('{"seed": 3} {"seed": 4}', "bad.json: text after the JSON object (at byte 12)"),
                    ('{"biss": {"slaves": [{"id": 0}, {"id": 0}]}}', "bad.json: biss.slaves[1].id: 0 is slaves[0]'s id too")]:
    r = run("--scenario", scenario(text), "--frames", "1")
    check(r.returncode == 1 and words in r.stderr, "%s -> %r (got %d %r)" % (text, words, r.returncode, r.stderr))
r = run("--scenario", tmp)
check(r.returncode == 1 and "Is a directory" in r.stderr, "a directory as scenario: %r" % r.stderr)

# a run that cannot finish: stopped at the time limit, and it says so; no
# line delay is invented when no frame was acknowledged
r = run("--scenario", scenario('{"sl_line": {"fault": "stuck_low"}}'), "--frames", "2", "--max-ms", "2")
check(r.returncode == 124 and "only 0 of 2 frames completed in 2 ms of simulated time (the --max-ms limit)" in r.stderr,
      "stuck SL: %d %r" % (r.returncode, r.stderr))
check("line delay           not measured" in r.stdout and "ns measured by the firmware" not in r.stdout,
      "stuck SL: line delay %r" % r.stdout)
r = run("--scenario", scenario('{"sl_line": {"fault": "stuck_low"}}'), "--frames", "2", "--max-ms", "2", "--json")
check(r.returncode == 124 and json.loads(r.stdout)["firmware"]["line_delay_ns"] is None,
      "stuck SL: JSON line delay %r" % r.stdout[:300])
# the longest busy and timeout the ranges allow still end, frames of 2 ms
# (at the slowest rate, whose processing limit of 1000 clocks is 10 ms)
r = run("--scenario", scenario('{"biss": {"busy_ns": 1e6, "timeout": {"ns": 1e6}}}'), "--frames", "3",
        "--freq", "97656.25")
check(r.returncode == 0, "longest busy and timeout: %d %r" % (r.returncode, r.stderr))

# strict mode: the firmware stops at the first construct of uncertain silicon
# behaviour in a clocked period (the one it keeps: MVIW, the CDS period's
# LOAD_RECORD), or with --strict-log lists them all; every other rule finds
# nothing (no LOOP, load or store there); contention leaves half periods at H
r = run("--frames", "3", "--strict")
check(r.returncode == 3 and "fault: strict rule mvi" in r.stderr and "between R30 changes" in r.stderr,
      "--strict: %d %r" % (r.returncode, r.stderr))
r = run("--frames", "3", "--strict=loop1,loop0,loopfield,dram")
check(r.returncode == 0, "--strict=loop1,loop0,loopfield,dram: %d %r" % (r.returncode, r.stderr))
r = run("--frames", "3", "--strict=mvi", "--strict-log")
check(r.returncode == 3 and r.stderr.count("biss-sim: strict: mvi") == 4 and "loop1" not in r.stderr,
      "--strict=mvi --strict-log: %d %r" % (r.returncode, r.stderr))
r = run("--freq", "10000000", "--frames", "30", "--contend", "40,1", "--json")
check(r.returncode == 0 and json.loads(r.stdout)["ma_half_period_cycles"]["min"] == 10
      and json.loads(r.stdout)["ma_half_period_cycles"]["max"] == 10
      and "PRU accesses stalled" in r.stderr, "--contend 40,1: %d %r %r" % (r.returncode, r.stdout[:200], r.stderr))
for args, words in [(["--strict=loop9"], "--strict 'loop9': expected loop1,"),
                    (["--strict-log"], "need --strict"),
                    (["--strict", "--strict-window", "0"], "--strict-window '0'"),
                    (["--contend", "0,1"], "--contend '0,1' is not"),
                    (["--contend", "40,1,often"], "pattern must be periodic or random")]:
    refused(["--frames", "3", *args], words, 2)

# two encoders on the two PRUs of one PRU-ICSS: both checked, the IEP
# frames of both starting on the same cycle; PRU1 alone
r = run("--pru1-profile", "hengstler-ad38", "--frames", "50", "--cable-m", "20", "--freq", "10000000")
check(r.returncode == 0 and r.stdout.count("0 CRC errors, 0 position mismatches") == 2
      and r.stdout.count("MA half period       10 .. 10 cycles") == 2
      and "PRU1 - PRU0 = 0 .. 0 ps" in r.stdout and "50 pairs" in r.stdout
      and "PRU1 stalled 0 times on PRU0's bank" in r.stdout,
      "--pru1-profile: %d %r %r" % (r.returncode, r.stdout, r.stderr))
r = run("--pru1-profile", "hengstler-ad38", "--iep-period-ns", "10000", "--frames", "5", "--freq", "10000000")
check(r.returncode == 5, "a period too short for PRU1's chain: %d %r" % (r.returncode, r.stdout))
r = run("--pru", "1", "--profile", "hengstler-ad38", "--frames", "30", "--json")
check(r.returncode == 0 and json.loads(r.stdout)["frames"] == 30
      and json.loads(r.stdout)["position_mismatches"] == 0, "--pru 1: %d %r" % (r.returncode, r.stderr))
# the firmware source given: assembled for the PRU it runs on (one image per PRU)
FW_SRC = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "pru_fw", "biss_master.p")
r = run("--pru", "1", "--firmware", FW_SRC, "--profile", "hengstler-ad38", "--frames", "20", "--json")
check(r.returncode == 0 and json.loads(r.stdout)["position_mismatches"] == 0
      and json.loads(r.stdout)["crc_errors"] == 0, "--pru 1 --firmware .p: %d %r" % (r.returncode, r.stderr))
r = run("--pru1-profile", "hengstler-ad38", "--firmware", FW_SRC, "--frames", "20")
check(r.returncode == 0 and r.stdout.count("0 CRC errors, 0 position mismatches") == 2,
      "pair, --firmware .p for both: %d %r %r" % (r.returncode, r.stdout, r.stderr))
# PRU0's image on PRU1: it says so (BISS_ST_PRU), and biss-sim does too
PRU0_IMAGE = os.path.join(os.path.dirname(SIM), "..", "..", "pru_fw", "biss_master.bin")
r = run("--pru", "1", "--firmware", PRU0_IMAGE, "--frames", "3")
check(r.returncode == 1 and "was assembled for PRU0, not PRU1" in r.stderr and r.stdout == "",
      "PRU0's image on PRU1: %d %r" % (r.returncode, r.stderr))
# both directions, refused from the image's words before it runs
r = run("--firmware", PRU0_IMAGE.replace(".bin", "_pru1.bin"), "--frames", "3")
check(r.returncode == 1 and "was assembled for PRU1, not PRU0" in r.stderr and r.stdout == "",
      "PRU1's image on PRU0: %d %r %r" % (r.returncode, r.stdout, r.stderr))
r = run("--pru1-profile", "generic", "--pru1-firmware", PRU0_IMAGE, "--frames", "3")
check(r.returncode == 1 and "was assembled for PRU0, not PRU1" in r.stderr and r.stdout == "",
      "pair, PRU0's image on PRU1: %d %r %r" % (r.returncode, r.stdout, r.stderr))
refused(["--frames", "3", "--pru1-profile", "generic", "--pru1-firmware", "/nonexistent.bin"],
        "cannot read image '/nonexistent.bin'", 1)
for args, words in [(["--pru", "2"], "--pru '2': expected 0 or 1"),
                    (["--pru1-profile", "nope"], "--pru1-profile 'nope'"),
                    (["--pru1-profile", "generic", "--vcd", "x.vcd"], "not with"),
                    (["--pru1-profile", "generic", "--trace", "x.txt"], "not with"),
                    (["--pru1-profile", "generic", "--trigger", "host"], "not with"),
                    (["--pru1-profile", "generic", "--iep-period-ns", "12"], "multiple of 5 ns"),
                    (["--trigger", "sometimes"], "--trigger 'sometimes': expected free, host or iep"),
                    (["--iep-period-ns", "50000"], "--iep-period-ns needs --trigger iep"),
                    (["--trigger", "iep", "--image", CLOCK_IMAGE], "--trigger needs the firmware"),
                    (["--settle-frames", "x"], "--settle-frames 'x': expected a count")]:
    refused(["--frames", "3", *args], words, 2)

# the rate against the scenario's line (proto/biss_line.c), up front: a
# warning beyond TIDEP0022 Table 5 (and, when no slave answered, why), a
# refusal for a slave timeout below 55 % of the MA period or a round trip
# the firmware never waits out; nothing within the table
T5_80 = ("10 MHz on 80 m of cable: TIDEP0022 Table 5 gives 10 MHz up to 10 m; rates that work: "
         "1 MHz, 800 kHz, 781.25 kHz")
r = run("--freq", "10000000", "--cable-m", "80", "--frames", "3", "--json")
check(r.returncode == 124 and r.stderr.startswith("biss-sim: warning: " + T5_80 + "\n")
      and "biss-sim: no slave answered: " + T5_80 + "\n" in r.stderr
      and json.loads(r.stdout)["firmware"]["no_slave"] > 0,
      "10 MHz on 80 m: %d %r" % (r.returncode, r.stderr))
for freq, cable in [(10e6, 10), (5e6, 25), (2e6, 60), (1e6, 100), (1e6, 2)]:
    r = run("--freq", str(int(freq)), "--cable-m", str(cable), "--frames", "3")
    check(r.returncode == 0 and r.stderr == "", "Table 5, %g Hz on %d m: %r" % (freq, cable, r.stderr))
r = run("--freq", "5000000", "--cable-m", "40", "--frames", "3")
check(r.returncode == 0 and r.stderr == "biss-sim: warning: 5 MHz on 40 m of cable: TIDEP0022 Table 5 "
      "gives 5 MHz up to 25 m; rates that work: 2 MHz, 1.5625 MHz, 1.25 MHz\n",
      "5 MHz on 40 m (works in the model, beyond the table): %d %r" % (r.returncode, r.stderr))
CHAIN1_650 = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "scenarios",
                          "chain1-650ns.json")
r = run("--scenario", CHAIN1_650, "--freq", "500000", "--frames", "3")
check(r.returncode == 1 and r.stdout == "" and r.stderr ==
      "biss-sim: a slave timeout of 650 ns is below 55 % of the MA period at 500 kHz (1100 ns, "
      "iC-MB4 I306): the slave may end the frame within a clock phase; rates that work: 1 MHz, "
      "1.25 MHz, 1.5625 MHz\n", "650 ns at 500 kHz: %d %r" % (r.returncode, r.stderr))
r = run("--scenario", CHAIN1_650, "--freq", "1000000", "--frames", "3")
check(r.returncode == 0 and r.stderr == "", "650 ns at 1 MHz: %r" % r.stderr)
r = run("--profile", "hengstler-ad38", "--freq", "500000", "--frames", "3")
check(r.returncode == 0 and r.stderr == "", "the AD38's adaptive timeout at 500 kHz: %r" % r.stderr)
r = run("--pru1-scenario", CHAIN1_650, "--freq", "500000", "--frames", "3")
check(r.returncode == 1 and r.stderr.startswith("biss-sim: PRU1's line: a slave timeout of 650 ns"),
      "PRU1's 650 ns at 500 kHz: %d %r" % (r.returncode, r.stderr))
r = run("--scenario", scenario('{"line": {"ns_per_m": 25, "tau_per_m2_ps": 0}}'), "--cable-m", "1000",
        "--freq", "1000000", "--frames", "3")
check(r.returncode == 1 and "a round trip of 50069 ns is beyond the 40000 ns the firmware waits for "
      "the ACK (BISS_MAX_DELAY_NS): no slave answers at any rate" in r.stderr,
      "a 50 us round trip: %d %r" % (r.returncode, r.stderr))

# both PRUs in one JSON object: each PRU's object as biss-sim --json prints
# it (its frame instruments too), how far apart the frame starts were on
# the IEP period, the bank stalls
r = run("--pru1-profile", "hengstler-ad38", "--frames", "20", "--json")
j = json.loads(r.stdout) if r.returncode == 0 else {}
fs = j.get("frame_starts") or {}
check(r.returncode == 0 and j["pru0"]["frames"] == 20 and j["pru1"]["frames"] == 20
      and j["pru1"]["profile"] == "hengstler-ad38" and j["spad_stalls"] == 0
      and fs.get("pairs") == 20 and fs.get("pru1_minus_pru0_min_ps") == 0
      and fs.get("pru1_minus_pru0_max_ps") == 0
      and j["pru0"]["frame_starts"]["iep"]["period_cycles"] * 5 == fs.get("iep_period_ns")
      and j["pru1"]["frame_starts"]["iep"]["skipped_periods"] == 0,
      "pair --json: %d %r %r" % (r.returncode, r.stdout[:300], r.stderr))
# one PRU under each trigger: every frame right, the trigger as asked
for trig in ["free", "host", "iep"]:
    r = run("--trigger", trig, "--frames", "30", "--json")
    j = json.loads(r.stdout) if r.returncode == 0 else {}
    fs = j.get("frame_starts") or {}
    check(r.returncode == 0 and j["frames"] == 30 and j["position_mismatches"] == 0
          and (fs.get("iep") is not None) == (trig == "iep")
          and (fs.get("restart_overhead_cycles") is not None) == (trig == "free"),
          "--trigger %s: %d %r %r" % (trig, r.returncode, fs, r.stderr))
r = run("--freq", "10000000", "--trigger", "iep", "--iep-period-ns", "40000", "--frames", "20", "--json")
j = json.loads(r.stdout) if r.returncode == 0 else {}
check(r.returncode == 0 and j["frame_period_ns"]["min"] == 40000 == j["frame_period_ns"]["max"]
      and j["frame_starts"]["iep"]["period_cycles"] == 8000,
      "--trigger iep --iep-period-ns 40000: %d %r" % (r.returncode, r.stderr))

# safety checks: the scenario's and the command line's, in JSON and text
SCEN = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "scenarios")
# on both PRUs each channel's checks time its frames by its own trigger
# (PRU0 owns the IEP, PRU1 follows it: both by the IEP period): a healthy
# encoder with the speed check, on either PRU, loses no frame to it
NOISE = os.path.join(SCEN, "noise-sl-10khz.json")
r = run("--scenario", NOISE, "--pru1-scenario", NOISE, "--frames", "2000", "--json",
        "--check-speed", "0,60000")
j = json.loads(r.stdout) if r.returncode == 0 else {}
for k in ("pru0", "pru1"):
    sp = (j.get(k, {}).get("safety", {}).get("max_speed") or [{}])[0]
    check(j.get(k, {}).get("trigger") == ("iep" if k == "pru0" else "iep-follow")
          and sp.get("checked", 0) >= 1900 and sp.get("jumped") == 0
          and j[k]["safety"]["misframed_good_lost"] == 0,
          "pair, speed check on %s: %d %r %r" % (k, r.returncode, j.get(k, {}).get("safety"),
                                                 r.stderr))
check(j.get("frame_starts", {}).get("pairs", 0) >= 2000 and j.get("spad_stalls") == 0,
      "pair --json: %r" % {k: j.get(k) for k in ("frame_starts", "spad_stalls")})
r = run("--scenario", os.path.join(SCEN, "safety-disagree.json"), "--frames", "400", "--json")
j = json.loads(r.stdout) if r.returncode == 0 else {}
sf = j.get("safety", {})
pair = (sf.get("pairs") or [{}])[0]
check(sf.get("first_flagged_frame") == 200 and pair.get("disagree", 0) > 190
      and pair.get("checked") == 400 and all(l["frozen"] + l["skipped"] == 0 for l in sf["life_counter"]),
      "disagreement in JSON: %r %r" % (sf, r.stderr))
r = run("--profile", "hengstler-ad38", "--freq", "5000000", "--frames", "50", "--check-life", "2")
check(r.returncode == 0 and "life counter 2       49 frames checked, 0 frozen, 0 skipped" in r.stdout,
      "healthy AD38 text: %r %r" % (r.stdout, r.stderr))
for args, words in [(["--check-life", "0"], "BISS_E_SAFETY_LIFE"),
                    (["--profile", "biss-safety-two-channel", "--check-pair", "0,0,1"], "BISS_E_SAFETY_PAIR")]:
    refused(["--frames", "3", *args], words, 1)
refused(["--frames", "3", "--check-pair", "0,1"], "--check-pair '0,1': expected", 2)

# the nE/nW check of a slave that never sets them: checked and quiet on a
# healthy encoder; a model that does set nE makes every frame misframed
# (none valid: the run ends at its time limit); refused where it cannot hold
r = run("--frames", "50", "--check-ew", "0", "--json")
sf = json.loads(r.stdout).get("safety", {}) if r.returncode == 0 else {}
check(sf.get("ew_static") == [{"slave": 0, "checked": 50, "misframed": 0}] and sf.get("misframed_frames") == 0,
      "healthy encoder, --check-ew 0: %r %r" % (sf, r.stderr))
r = run("--scenario", scenario('{"biss": {"slaves": [{"error": true}]}}'), "--check-ew", "0", "--frames", "3",
        "--max-ms", "1", "--json")
sf = json.loads(r.stdout).get("safety", {}) if r.stdout.startswith("{") else {}
ew = (sf.get("ew_static") or [{}])[0]
# (and each of those words was what the encoder sent: good frames lost)
check(r.returncode == 124 and json.loads(r.stdout)["frames"] == 0 and sf.get("misframed_frames", 0) > 20
      and ew.get("misframed") == sf.get("misframed_frames") == ew.get("checked")
      == sf.get("misframed_good_lost"), "nE set, --check-ew 0: %d %r" % (r.returncode, sf))
r = run("--scenario", scenario('{"biss": {"slaves": [{"error": true}]}}'), "--check-ew", "0", "--frames", "3",
        "--max-ms", "1")
check("misframed            " in r.stdout and "frames refused (nE/nW of a slave that never sets them, or a position beyond reach)"
      in r.stdout,
      "nE set, text: %r" % r.stdout)
NO_EW = '{"biss": {"slaves": [{"error_bit": false, "warning_bit": false}]}}'
for args, words in [(["--scenario", scenario_as("ew1.json", NO_EW), "--check-ew", "0"], "BISS_E_SAFETY_EW"),
                    (["--check-ew", "1"], "BISS_E_SAFETY_EW"),

                    (["--scenario", scenario_as("ew2.json", '{"biss": {"slaves": [{"warning": true}]}, "checks": {"ew_static": [0]}}')],
                     "ew2.json: checks.ew_static: slave 0 drives nE/nW active"),
                    (["--scenario", scenario_as("ew3.json", '{"biss": {"slaves": [{"error_bit": false}]}, "checks": {"ew_static": [0]}}')],
                     "ew3.json: checks.ew_static: slave 0 sends no nE/nW"),
                    (["--scenario", scenario_as("ew4.json", '{"checks": {"ew_static": [1]}}')],
                     "ew4.json: checks.ew_static: slave 1 is not in the chain"),
                    (["--scenario", scenario_as("ew5.json", '{"checks": {"ew_static": 0}}')],
                     "ew5.json: checks.ew_static: expected an array")]:
    refused(["--frames", "3", *args], words, 1)
refused(["--frames", "3", "--check-ew", "0,1"], "--check-ew '0,1': expected S", 2)

# the speed check: every position after the first compared and none beyond
# reach on a healthy encoder (50 000 counts/s, checked at 60 000)
TIDE = ["--profile", "tidep0022-test-encoder", "--freq", "10000000"]
r = run(*TIDE, "--frames", "50", "--check-speed", "0,60000", "--json")
sf = json.loads(r.stdout).get("safety", {}) if r.returncode == 0 else {}
check(sf.get("max_speed") == [{"slave": 0, "counts_per_s": 60000, "checked": 49, "jumped": 0, "resync": 0}]
      and sf.get("misframed_frames") == 0, "healthy encoder, --check-speed 0,60000: %r %r" % (sf, r.stderr))
# checked at 1 000 counts/s, a step of 2 counts between frames is beyond
# reach (and right: a good frame lost), and the next frame, in reach of it,
# takes it over (a resync): each jump is one frame
r = run(*TIDE, "--frames", "30", "--check-speed", "0,1000", "--json")
sf = json.loads(r.stdout).get("safety", {}) if r.stdout.startswith("{") else {}
sp = (sf.get("max_speed") or [{}])[0]
check(r.returncode == 0 and sp.get("jumped", 0) >= 3 and sp.get("resync") == sp.get("jumped")
      == sf.get("misframed_frames") == sf.get("misframed_good_lost"), "--check-speed 0,1000: %d %r" % (r.returncode, sf))
for args, words in [(["--check-speed", "1,5"], "BISS_E_SAFETY_SPEED"),

                    (["--scenario", scenario_as("sp1.json", '{"checks": {"max_speed": [{"slave": 1, "counts_per_s": 5}]}}')],
                     "sp1.json: checks.max_speed: slave 1 is not in the chain"),
                    (["--scenario", scenario_as("sp2.json", '{"checks": {"max_speed": [{"slave": 0}]}}')],
                     "sp2.json: checks.max_speed[0].counts_per_s: missing"),
                    (["--scenario", scenario_as("sp3.json", '{"checks": {"max_speed": [{"slave": 0, "counts_per_s": -1}]}}')],
                     "sp3.json: checks.max_speed[0].counts_per_s: -1 out of range"),
                    (["--scenario", scenario_as("sp4.json", '{"checks": {"max_speed": [{"slave": 0, "counts_per_s": 1, "x": 1}]}}')],
                     "sp4.json: checks.max_speed[0].x: unknown field"),
                    (["--scenario", scenario_as("sp5.json", '{"checks": {"max_speed": 5}}')],
                     "sp5.json: checks.max_speed: expected an array")]:
    refused(["--frames", "3", *args], words, 1)
refused(["--frames", "3", "--check-speed", "0"], "--check-speed '0': expected S,CPS", 2)
refused(["--frames", "3", "--check-speed", "0,0"], "--check-speed '0,0': expected S,CPS", 2)

# the one-board loop (docs/hardware.md section 14): the master on PRU0
# against the encoder firmware on PRU1, joined by two jumper wires (no
# transceivers, 0.2 m: test/scenarios/encoder-jumper.json), at every rate
# from 1 to 10 MHz: every frame good, SL the model's at every rising edge
JUMPER = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "scenarios",
                      "encoder-jumper.json")
for f in ["1000000", "2000000", "5000000", "10000000"]:
    r = run("--encoder", "--scenario", JUMPER, "--freq", f, "--frames", "500", "--json")
    j = json.loads(r.stdout) if r.returncode == 0 else {}
    e = j.get("encoder", {})
    check(j.get("frames") == 500 and j.get("crc_errors") == 0 and j.get("position_mismatches") == 0
          and e.get("sl_differ") == 0 and e.get("sl_compared", 0) > 500 * 20
          and j.get("slaves", [{}])[0].get("master_crc_ok") is True,
          "jumper loop at %s Hz: %r %r" % (f, {k: j.get(k) for k in ("frames", "crc_errors",
                                                                   "position_mismatches")},
                                           r.stderr))
# strict mode on both cores, the encoder's scope from MA's edges, a window
# of H: the AD38 chain at 10 MHz runs clean (test_e2e_encoder strict_both,
# test_slave_fw strict_timing_critical_code show the check bites)
r = run("--encoder", "--profile", "hengstler-ad38", "--freq", "10000000", "--frames", "100",
        "--strict=loop1,loop0,loopfield,dram,spad", "--strict-window", "10", "--json")
j = json.loads(r.stdout) if r.returncode == 0 else {}
check(j.get("frames") == 100 and j.get("crc_errors") == 0 and j.get("encoder", {}).get("sl_differ") == 0,
      "--encoder --strict: rc %d %r" % (r.returncode, r.stderr))
r = run("--encoder=/nonexistent.bin", "--frames", "3")
check(r.returncode == 1 and "cannot read image '/nonexistent.bin'" in r.stderr,
      "--encoder missing image: %r" % r.stderr)

finish("biss-sim")
