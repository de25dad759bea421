#!/usr/bin/env python3
"""bissctl as a user runs it: help for every command, reading frames from
the emulator, clear errors with non-zero exits, and the same subcommands
against a file standing in for /dev/mem."""
import os
import re
import subprocess
import sys
import tempfile

CTL = sys.argv[1]
failures = 0


def check(cond, what):
    global failures
    if not cond:
        failures += 1
        print("FAIL:", what)


def run(*args, env=None):
    return subprocess.run([CTL, *args], capture_output=True, text=True, timeout=120, env=env)


# help: the overview and each command's own, exit 0
r = run("--help")
check(r.returncode == 0 and "info" in r.stdout and "--target" in r.stdout, "--help: %r" % r.stdout)
for cmd in ["info", "read", "stats", "run", "trigger", "start", "stop", "reg-read",
            "reg-write", "command"]:
    r = run(cmd, "--help")
    check(r.returncode == 0 and r.stdout.startswith("bissctl [options] " + cmd),
          "%s --help: %r" % (cmd, r.stdout[:80]))

# usage errors: exit 2, a message on stderr
for args, text in [(["frobnicate"], "unknown command"),
                   (["--bogus", "info"], "unknown option"),
                   ([], "no command"),
                   (["--target", "pi", "info"], "unknown target"),
                   (["--slave", "14,6", "info"], "--slave"),
                   (["read", "-n", "0"], "-n"),
                   (["--freq"], "needs a value")]:
    r = run(*args)
    check(r.returncode == 2 and text in r.stderr, "%r: rc %d, %r" % (args, r.returncode, r.stderr))

# read on the emulator: N lines, one frame each, numbered in order
r = run("--freq", "10000000", "--cable-m", "2", "read", "-n", "5")
check(r.returncode == 0, "read: rc %d %r" % (r.returncode, r.stderr))
lines = r.stdout.splitlines()
check(len(lines) == 5, "read -n 5 printed %d lines" % len(lines))
frames = [int(m.group(1)) for m in (re.match(r"frame=(\d+) ", l) for l in lines) if m]
check(frames == list(range(frames[0], frames[0] + 5)) if frames else False, "frames %r" % frames)
# frames count from 1, as biss-sim's --svg-frame: the first is the training frame
check(lines[0].startswith("frame=1 ") and " training " in lines[0], "first frame: %r" % lines[0])
data = [l for l in lines if " valid " in l]
check(len(data) >= 4, "at least 4 data frames: %r" % lines)
for l in data:
    check("s0.crc=ok" in l and "s0.nE=ok" in l and "s0.nW=ok" in l and "delay_ns=" in l
          and re.search(r" sample_point=[0-7] lag=\d+ timestamp=\d+ \(IEP counts of 5 ns: \d+\.\d{3} us\)$", l), l)

# an explicit slave layout (the profile's own: 14 data bits, CRC6 0x43, nE/nW at 0)
r = run("--freq", "10000000", "--slave", "14,6,0x43,0,0", "read", "-n", "3")
check(r.returncode == 0 and r.stdout.count("s0.crc=ok") >= 2, "--slave read: %r %r" % (r.stdout, r.stderr))

# host trigger: one frame per trigger
r = run("--freq", "10000000", "--trigger", "host", "trigger")
check(r.returncode == 0 and " valid " in r.stdout, "trigger: %r %r" % (r.stdout, r.stderr))
r = run("--freq", "10000000", "trigger")
check(r.returncode == 1 and "host-trigger" in r.stderr, "trigger in free-run: %r" % r.stderr)

# run and stats
r = run("--freq", "10000000", "run", "--ms", "2")
m = re.search(r"frames=(\d+) crc_errors=(\d+)", r.stdout)
check(r.returncode == 0 and m and int(m.group(1)) > 50 and m.group(2) == "0", "run: %r" % r.stdout)
r = run("--freq", "10000000", "info")
check(r.returncode == 0 and "firmware_running=yes" in r.stdout and "cfg_error=0" in r.stdout,
      "info: %r" % r.stdout)

# registers through control communication (the TIDEP0022 encoder's 0x78..)
r = run("--freq", "10000000", "reg-read", "0x78", "-n", "2")
check(r.returncode == 0 and r.stdout.splitlines() ==
      ["id=0 addr=0x78 value=0x46", "id=0 addr=0x79 value=0x3a"], "reg-read: %r %r" % (r.stdout, r.stderr))
r = run("--freq", "10000000", "reg-read", "0x78", "-n", "8", "--dump")
check(r.returncode == 0 and r.stdout == "0x78: 46 3a c0 0c 00 01 57 41" + " " * 24 + "  F:....WA\n",
      "reg-read --dump: %r %r" % (r.stdout, r.stderr))
r = run("--freq", "10000000", "reg-write", "0x60", "0x12", "0x34")
check(r.returncode == 0 and r.stdout == "", "reg-write: %r %r" % (r.stdout, r.stderr))
r = run("--freq", "10000000", "--id", "3", "reg-read", "0x78")
check(r.returncode == 1 and "no slave took" in r.stderr, "reg-read wrong id: %r" % r.stderr)
r = run("--freq", "10000000", "command", "1", "0")
check(r.returncode == 0 and r.stdout == "ids=0x01 cmd=0 ida=0x01\n", "command: %r %r" % (r.stdout, r.stderr))
# the other spellings: "reg read", "reg write", "cmd"
r = run("--freq", "10000000", "reg", "read", "0x78", "-n", "2")
check(r.returncode == 0 and r.stdout.split("\n")[:2] ==
      ["id=0 addr=0x78 value=0x46", "id=0 addr=0x79 value=0x3a"], "reg read: %r %r" % (r.stdout, r.stderr))
r = run("--freq", "10000000", "reg", "write", "0x60", "0x12")
check(r.returncode == 0 and r.stdout == "", "reg write: %r %r" % (r.stdout, r.stderr))
r = run("--freq", "10000000", "cmd", "1", "0")
check(r.returncode == 0 and r.stdout == "ids=0x01 cmd=0 ida=0x01\n", "cmd: %r %r" % (r.stdout, r.stderr))
# ID 1 is not there: with the IDA test the firmware withholds the command
r = run("--freq", "10000000", "command", "3", "1", "--ida-test")
check(r.returncode == 1 and r.stdout == "ids=0x03 cmd=1 ida=0x01\n" and "withheld" in r.stderr,
      "command --ida-test: %r %r" % (r.stdout, r.stderr))
for args in [["command", "1", "4"], ["command", "1"], ["reg-read"], ["reg-read", "0x80"], ["reg-write", "0x60"], ["reg-write", "0x60", "0x100"],
             ["--id", "8", "reg-read", "0"], ["info", "0x33"]]:
    r = run(*args)
    check(r.returncode == 2, "%r: rc %d %r" % (args, r.returncode, r.stderr))

# an SSI encoder: the layout from the profile, or given (the delay given too)
r = run("--profile", "ssi", "--freq", "2000000", "read", "-n", "3")
pos = [int(x) for x in re.findall(r"s0.pos=(\d+)", r.stdout)]
check(r.returncode == 0 and len(pos) == 3 and pos[0] < pos[2] and "valid" in r.stdout,
      "ssi read: %r %r" % (r.stdout, r.stderr))
r = run("--profile", "ssi", "--ssi", "13", "--ssi-delay-ns", "60", "--freq", "2000000", "read", "-n", "2")
check(r.returncode == 0 and r.stdout.count("valid") == 2, "ssi given: %r %r" % (r.stdout, r.stderr))
check("s0.crc=none" in r.stdout and "s0.nE=none" in r.stdout, "ssi fields: %r" % r.stdout)
r = run("--ssi", "13,grey", "read")
check(r.returncode == 2 and "BITS[,gray]" in r.stderr, "ssi bad: %r" % r.stderr)
r = run("--profile", "ssi", "--ssi", "13", "--slave", "13,0,0,0", "read")
check(r.returncode == 1 and "SSI: one slave only" in r.stderr, "ssi chain: %r" % r.stderr)

# the library's errors, in its words, exit 1
for args, text in [(["--freq", "3000000", "read"], "not 100 MHz divided by a whole number"),
                   (["--freq", "100000", "read"], "no exact 8x shift clock"),
                   (["--freq", "20000000", "read"], "out of range"),
                   (["--slave", "14,6,0x03,0,0", "read"], "polynomial"),
                   (["--slave", "70,6,0x43,0", "read"], "data bits"),
                   (["--profile", "nope", "info"], "unknown emulator profile"),
                   (["--firmware", "/nonexistent.bin", "info"], "firmware image cannot be read"),
                   (["--target", "am335x", "--devmem", "/nonexistent", "info"], "devmem")]:
    r = run(*args)
    check(r.returncode == 1 and text in r.stderr, "%r: rc %d %r" % (args, r.returncode, r.stderr))

# a real target on a file: loads, writes, and reports that no firmware answers
with tempfile.TemporaryDirectory() as tmp:
    mem = os.path.join(tmp, "mem")
    with open(mem, "wb") as f:
        f.truncate(0x4A300000 + 0x80000)
    r = run("--target", "am335x", "--devmem", mem, "--timeout-ms", "20", "info")
    check(r.returncode == 2 and "--slave or --ssi" in r.stderr, "real target without layout: %r" % r.stderr)
    r = run("--target", "am335x", "--devmem", mem, "--timeout-ms", "20",
            "--slave", "14,6,0x43,0,0", "--freq", "10000000", "info")
    check(r.returncode == 1 and "not running" in r.stderr, "file target: %r" % r.stderr)
    with open(mem, "rb") as f:
        f.seek(0x4A300000 + 0x22000)
        control = int.from_bytes(f.read(4), "little")
        f.seek(0x4A300000 + 0x4)
        half = int.from_bytes(f.read(2), "little")
    check(control == 2 and half == 10, "CONTROL %#x, CFG_HALF %d" % (control, half))
    r = run("--target", "am335x", "--devmem", mem, "--attach", "stats")
    check(r.returncode == 0 and "frames=0" in r.stdout, "attach stats: %r %r" % (r.stdout, r.stderr))
    r = run("--target", "am335x", "--devmem", mem, "--attach", "stop")
    with open(mem, "rb") as f:
        f.seek(0x4A300000 + 0x22000)
        control = int.from_bytes(f.read(4), "little")
    check(r.returncode == 0 and control == 1, "stop: CONTROL %#x" % control)

print("bissctl CLI: %d failure(s)" % failures)
sys.exit(1 if failures else 0)
