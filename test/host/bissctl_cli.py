#!/usr/bin/env python3
"""bissctl as a user runs it: help for every command, reading frames from
the emulator, clear errors with non-zero exits, and the same subcommands
against a file standing in for /dev/mem."""
import json
import os
import re
import subprocess
import sys
import tempfile
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "common"))
from checks import check, finish  # noqa: E402
from memfile import rd, wr  # noqa: E402

# the contract's version, as biss_shm.h has it
with open(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "include", "biss",
                       "biss_shm.h"), encoding="utf-8") as _f:
    SHM_VERSION = int(re.search(r"^#define BISS_SHM_VERSION\s+(\d+)", _f.read(), re.M).group(1))

CTL = sys.argv[1]
# the first line of every output on the emulator (this machine has no TI
# device tree, so the emulator is also the default target)
EMULATED = "emulated: target emu, no board "


def run(*args, env=None):
    """bissctl with args; on the emulator, the "emulated" line checked and
    taken off stdout (read --json says it in its object)."""
    r = subprocess.run([CTL, *args], capture_output=True, text=True, timeout=120, env=env)
    target = args[args.index("--target") + 1] if "--target" in args else "emu"
    # (rates needs no target: it opens none)
    if (target == "emu" and r.stdout and "--help" not in args and "--json" not in args
            and "rates" not in args):
        first, _, rest = r.stdout.partition("\n")
        if check(first.startswith(EMULATED), "%r: no emulated line: %r" % (args, r.stdout[:120])):
            r.stdout = rest
    elif target != "emu":
        check("emulated" not in r.stdout, "%r: emulated on hardware: %r" % (args, r.stdout))
    return r


# help: the overview and each command's own, exit 0
r = run("--help")
check(r.returncode == 0 and "info" in r.stdout and "--target" in r.stdout, "--help: %r" % r.stdout)
for cmd in ["info", "read", "stats", "run", "trigger", "start", "stop", "reg-read",
            "reg-write", "command", "rates", "encoder"]:
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
                   (["--freq"], "needs a value"),
                   (["--pru", "2", "info"], "--pru")]:
    r = run(*args)
    check(r.returncode == 2 and text in r.stderr, "%r: rc %d, %r" % (args, r.returncode, r.stderr))

# read on the emulator: N lines, one frame each, numbered in order
r = run("--freq", "10000000", "--cable-m", "2", "read", "-n", "5")
check(r.returncode == 0, "read: rc %d %r" % (r.returncode, r.stderr))
lines = r.stdout.splitlines()
# five frames, then the link's counts over the four that measured an ACK
check(len(lines) == 6 and lines[5].startswith("link: frames=4 "),
      "read -n 5 printed %d lines: %r" % (len(lines), lines[5:]))
lines = lines[:5]
frames = [int(m.group(1)) for m in (re.match(r"frame=(\d+) ", l) for l in lines) if m]
check(frames == list(range(frames[0], frames[0] + 5)) if frames else False, "frames %r" % frames)
# frames count from 1, as biss-sim's --svg-frame: the first is the training frame
check(lines[0].startswith("frame=1 ") and " training " in lines[0], "first frame: %r" % lines[0])
data = [l for l in lines if " valid " in l]
check(len(data) >= 4, "at least 4 data frames: %r" % lines)
for l in data:
    check("s0.crc=ok" in l and "s0.nE=ok" in l and "s0.nW=ok" in l and "delay_ns=" in l
          and re.search(r" sample_point=[0-7] lag=\d+ eye=[34]/8 timestamp=\d+ "
                        r"\(IEP counts of 5 ns: \d+\.\d{3} us\)$", l), l)

# an explicit slave layout (the profile's own: 14 data bits, CRC6 0x43, nE/nW at 0)
r = run("--freq", "10000000", "--slave", "14,6,0x43,0,0", "read", "-n", "3")
check(r.returncode == 0 and r.stdout.count("s0.crc=ok") >= 2, "--slave read: %r %r" % (r.stdout, r.stderr))

# PRU1 of the emulated PRU-ICSS: its own line, data RAM and GPCFG
r = run("--pru", "1", "--freq", "10000000", "--profile", "hengstler-ad38", "read", "-n", "3")
check(r.returncode == 0 and r.stdout.count("s2.crc=ok") >= 2, "--pru 1 read: %r %r" % (r.stdout, r.stderr))
# each PRU its own image by default; PRU0's on PRU1 is refused (BISS_E_FW_PRU)
r = run("--pru", "1", "info")
check(r.returncode == 0 and "/pru_fw/biss_master_pru1.bin\n" in r.stdout, "--pru 1 image: %r" % r.stdout)
pru0_image = r.stdout.split("firmware=", 1)[1].split()[0].replace("_pru1.bin", ".bin")
r = run("--pru", "1", "--firmware", pru0_image, "--freq", "10000000", "read", "-n", "1")
check(r.returncode == 1 and "assembled for the other PRU" in r.stderr
      and "assembled for PRU0, not PRU1" in r.stderr,
      "PRU0's image on PRU1: %d %r" % (r.returncode, r.stderr))
# and PRU1's on PRU0, which once ran with NO_SLAVE forever: refused from
# its words before it runs
r = run("--firmware", pru0_image.replace(".bin", "_pru1.bin"), "read", "-n", "5")
check(r.returncode == 1 and "assembled for PRU1, not PRU0" in r.stderr and r.stdout == "",
      "PRU1's image on PRU0: %d %r %r" % (r.returncode, r.stdout, r.stderr))

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
CMD0_ID0 = "command 0 to ID 0: switches the data channel of each addressed slave on\n"
r = run("--freq", "10000000", "command", "1", "0")
check(r.returncode == 0 and r.stdout == CMD0_ID0 + "ids=0x01 cmd=0 ida=0x01\n", "command: %r %r" % (r.stdout, r.stderr))
# the other spellings: "reg read", "reg write", "cmd"
r = run("--freq", "10000000", "reg", "read", "0x78", "-n", "2")
check(r.returncode == 0 and r.stdout.split("\n")[:2] ==
      ["id=0 addr=0x78 value=0x46", "id=0 addr=0x79 value=0x3a"], "reg read: %r %r" % (r.stdout, r.stderr))
r = run("--freq", "10000000", "reg", "write", "0x60", "0x12")
check(r.returncode == 0 and r.stdout == "", "reg write: %r %r" % (r.stdout, r.stderr))
r = run("--freq", "10000000", "cmd", "1", "0")
check(r.returncode == 0 and r.stdout == CMD0_ID0 + "ids=0x01 cmd=0 ida=0x01\n", "cmd: %r %r" % (r.stdout, r.stderr))
# ID 1 is not there: with the IDA test the firmware withholds the command
r = run("--freq", "10000000", "command", "3", "0", "--ida-test")
check(r.returncode == 1 and r.stdout.endswith("ids=0x03 cmd=0 ida=0x01\n") and "withheld" in r.stderr,
      "command --ida-test: %r %r" % (r.stdout, r.stderr))
for args in [["command", "1", "4"], ["command", "1"], ["reg-read"], ["reg-read", "0x80"], ["reg-write", "0x60"], ["reg-write", "0x60", "0x100"],
             ["--id", "8", "reg-read", "0"], ["info", "0x33"]]:
    r = run(*args)
    check(r.returncode == 2, "%r: rc %d %r" % (args, r.returncode, r.stderr))

# the link's eye: a clean line's frames at 4/8 or 3/8 and no warning; both
# lines glitched at 5 MHz: frames refused off the grid, marginal frames, the
# warning from the first of them (--link-warn 1,100000: held to the end)
r = run("--freq", "5000000", "read", "-n", "50")
eyes = [int(x) for x in re.findall(r" eye=(\d)/8", r.stdout)]
check(r.returncode == 0 and len(eyes) == 49 and min(eyes) >= 3 and "link-warning" not in r.stdout
      and re.search(r"^link: frames=49 .* marginal=0 off_grid=0 warned=0$", r.stdout, re.M),
      "clean eye: %r" % r.stdout[-300:])
noise = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "scenarios",
                     "noise-both-30khz-jitter.json")
r = run("--scenario", noise, "--freq", "5000000", "--link-warn", "1,100000", "read", "-n", "3000")
lines = [x for x in r.stdout.splitlines() if x.startswith("frame=")]
first = next((i for i, x in enumerate(lines) if " off-grid " in x), None)
m = re.search(r"^link: frames=\d+ .* marginal=(\d+) off_grid=(\d+) warned=(\d+)$", r.stdout, re.M)
check(r.returncode == 0 and first is not None and m and int(m.group(2)) > 0
      and int(m.group(1)) >= int(m.group(2)) and "flags=0x1" in lines[first]
      and all(" link-warning" in x for x in lines[first:] if " eye=" in x),
      "noisy link: %r" % (m.group(0) if m else r.stdout[-300:]))
r = run("--link-warn", "1,0", "read")
check(r.returncode == 2 and "--link-warn '1,0'" in r.stderr, "--link-warn 1,0: %r" % r.stderr)

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
                   # even: refused as the scenario files refuse it (one rule)
                   (["--slave", "14,6,0x42,0,0", "read"], "polynomial"),
                   (["--slave", "70,6,0x43,0", "read"], "data bits"),
                   (["--profile", "nope", "info"], "unknown emulator profile"),
                   (["--firmware", "/nonexistent.bin", "info"], "firmware image cannot be read"),
                   (["--target", "am335x", "--devmem", "/nonexistent", "--slave", "14,6,0x43,0",
                     "info"], "/nonexistent: No such file or directory (errno 2)"),
                   # no PRU-ICSS memory there (its mapping was a bus error)
                   (["--target", "am335x", "--loader", "devmem", "--devmem", "/dev/zero",
                     "--slave", "14,6,0x43,0", "info"], "/dev/zero is not /dev/mem")]:
    r = run(*args)
    check(r.returncode == 1 and text in r.stderr, "%r: rc %d %r" % (args, r.returncode, r.stderr))

# a real target on a file standing in for /dev/mem, the PRU-ICSS clock on
# (CM_PER_PRU_ICSS_CLKCTRL = 2, as the pruss driver leaves it); the lock
# files in a directory of the test's own
BASE, CTRL0, CLKCTRL = 0x4A300000, 0x22000, 0x44E000E8


with tempfile.TemporaryDirectory() as tmp:
    env = dict(os.environ, BISS_LOCK_DIR=tmp)
    mem = os.path.join(tmp, "mem")
    with open(mem, "wb") as f:
        f.truncate(BASE + 0x80000)
    dm = ["--target", "am335x", "--loader", "devmem", "--devmem", mem, "--sysfs", tmp]
    # not powered: refused before the PRU-ICSS is touched, with the reason
    r = run(*dm, "--slave", "14,6,0x43,0,0", "info", env=env)
    check(r.returncode == 1 and "not powered" in r.stderr and "0x44e000e8" in r.stderr
          and "no pruss driver bound to 4a300000.pruss" in r.stderr
          and "already requested" in r.stderr and rd(mem, BASE + CTRL0) == 0,
          "unpowered: %r" % r.stderr)
    wr(mem, CLKCTRL, 2)
    # usage errors come before anything is opened or loaded
    r = run(*dm, "--timeout-ms", "20", "info", env=env)
    check(r.returncode == 2 and "--slave or --ssi" in r.stderr and "attach to" in r.stderr,
          "real target without layout: %r" % r.stderr)
    for args in [["reg-read", "0x80"], ["reg-write", "0x10"], ["command", "1", "9"]]:
        r = run(*dm, "--slave", "14,6,0x43,0,0", *args, env=env)
        check(r.returncode == 2 and rd(mem, BASE + CTRL0) == 0,
              "%r before open: %d %r" % (args, r.returncode, r.stderr))
    r = run(*dm, "--timeout-ms", "20", "run", env=env)
    check(r.returncode == 2 and rd(mem, BASE + CTRL0) == 0, "run without layout: %r" % r.stderr)
    # loads, writes, and reports that no firmware answers
    r = run(*dm, "--timeout-ms", "20", "--slave", "14,6,0x43,0,0", "--freq", "10000000", "info",
            env=env)
    check(r.returncode == 1 and "not running" in r.stderr, "file target: %r" % r.stderr)
    check(rd(mem, BASE + CTRL0) == 2 and rd(mem, BASE + 4, 2) == 10,
          "CONTROL %#x, CFG_HALF %d" % (rd(mem, BASE + CTRL0), rd(mem, BASE + 4, 2)))
    check(rd(mem, BASE + 0xFE0) == 0x44495342, "identification block written")
    # attach (the identification block checked) reads without reloading
    r = run(*dm, "--attach", "stats", env=env)
    check(r.returncode == 0 and "frames=0" in r.stdout, "attach stats: %r %r" % (r.stdout, r.stderr))
    # a read-only command attaches by itself to a firmware that runs
    wr(mem, BASE + 0x80, 0x42695353)  # the magic, as the firmware sets it
    wr(mem, BASE + 0x98, 1234)        # ST_FRAMES
    wr(mem, BASE + 0x34000, 0xdeadbeef)
    r = run(*dm, "stats", env=env)
    check(r.returncode == 0 and "frames=1234" in r.stdout and rd(mem, BASE + 0x34000) == 0xdeadbeef,
          "default attach: %r %r" % (r.stdout, r.stderr))
    r = run(*dm, "info", env=env)
    check(r.returncode == 0 and "(attached)" in r.stdout and ("shm_version=%d" % SHM_VERSION) in r.stdout,
          "default attach info: %r %r" % (r.stdout, r.stderr))
    # two processes on one PRU: the second is told who holds it
    holder = subprocess.Popen([CTL, *dm, "--slave", "14,6,0x43,0,0", "--no-configure", "--attach",
                               "run", "--ms", "3000"], env=env, stdout=subprocess.PIPE,
                              stderr=subprocess.PIPE, text=True)
    import time
    time.sleep(0.5)
    r = run(*dm, "--slave", "14,6,0x43,0,0", "--freq", "10000000", "info", env=env)
    check(r.returncode == 1 and ("pid %d" % holder.pid) in r.stderr and "in use" in r.stderr,
          "second process: %r" % r.stderr)
    # whatever its environment: one lock per PRU, on the memory file, and
    # the holder named with its command
    other_env = dict(os.environ, BISS_LOCK_DIR=os.path.join(tmp, "elsewhere"))
    r = run(*dm, "--slave", "14,6,0x43,0,0", "--freq", "10000000", "info", env=other_env)
    check(r.returncode == 1 and ("pid %d (bissctl)" % holder.pid) in r.stderr
          and "PRU0 of the PRU-ICSS at 0x4a300000" in r.stderr,
          "second process, another BISS_LOCK_DIR: %r" % r.stderr)
    r = run(*dm, "stats", env=env)  # another reader shares it
    check(r.returncode == 0 and "frames=1234" in r.stdout, "shared reader: %r" % r.stderr)
    holder.wait(timeout=30)
    # junk in data RAM is refused by name, not printed
    wr(mem, BASE + 0x00, 1)            # CFG_SEQ 1 ...
    wr(mem, BASE + 0x8C, 1)            # ... acked
    wr(mem, BASE + 0x90, 0)
    wr(mem, BASE + 0x04, 0x00080001)   # H = 1, 8 slaves: the old "freq_hz=100000000 slaves=8"
    r = run(*dm, "info", env=env)
    check(r.returncode == 1 and "bad MA half period" in r.stderr and "freq_hz" not in r.stdout,
          "junk config: %r %r" % (r.stdout, r.stderr))
    wr(mem, BASE + 0x04, 0x0001000a)   # H = 10, 1 slave
    wr(mem, BASE + 0x10, 0x000000c8)   # 200 data bits: once a shift by 200
    r = run(*dm, "--attach", "read", env=env)
    check(r.returncode == 1 and "bad slave data bits" in r.stderr, "junk slave: %r" % r.stderr)
    wr(mem, BASE + 0x10, 0x0100060e)   # 14 data bits, CRC6, nE/nW at 0
    wr(mem, BASE + 0x14, 0x00000003)   # 0x43
    wr(mem, BASE + 0x480, 1)           # a publication in the ring's first slot: 1 ...
    wr(mem, BASE + 0x484, 0x41)        # ... VALID with ACK_JUMP: never written so
    wr(mem, BASE + 0x48C, 0x01000000)  # one slave
    wr(mem, BASE + 0x494, 0x000a0307)  # H = 10, lag 3, sample point 7
    wr(mem, BASE + 0x88, 0x480)        # ST_BUF
    wr(mem, BASE + 0x84, 1)            # ST_SEQ
    r = run(*dm, "--attach", "read", env=env)
    check(r.returncode == 1 and "result flags: a combination the firmware never writes" in r.stderr
          and "pos=" not in r.stdout, "junk flags: %r %r" % (r.stdout, r.stderr))
    wr(mem, BASE + 0x484, 0x01)        # VALID ...
    wr(mem, BASE + 0x494, 0x000a03ff)  # ... with sample point 255
    r = run(*dm, "--attach", "read", env=env)
    check(r.returncode == 1 and "sample point: not 0..7" in r.stderr, "junk point: %r" % r.stderr)
    wr(mem, BASE + 0x494, 0x000a0307)
    wr(mem, BASE + 0x94, 7)            # ST_STATE
    r = run(*dm, "--attach", "stats", env=env)
    check(r.returncode == 1 and "ST_STATE" in r.stderr, "junk state: %r" % r.stderr)
    wr(mem, BASE + 0x94, 1)
    wr(mem, BASE + 0xFE4, 99)          # another BISS_SHM_VERSION
    r = run(*dm, "--attach", "stats", env=env)
    check(r.returncode == 1 and "BISS_SHM_VERSION 99" in r.stderr, "version: %r" % r.stderr)
    wr(mem, BASE + 0xFE0, 0)           # no identification block: not this firmware
    r = run(*dm, "--attach", "stats", env=env)
    check(r.returncode == 1 and "identification" in r.stderr, "no id: %r" % r.stderr)
    # stop attaches (no reload) and halts
    wr(mem, BASE + 0xFE0, 0x44495342)
    wr(mem, BASE + 0xFE4, SHM_VERSION)
    wr(mem, BASE + 0x04, 0)
    r = run(*dm, "stop", env=env)
    check(r.returncode == 0 and rd(mem, BASE + CTRL0) == 1 and rd(mem, BASE + 0x34000) == 0xdeadbeef,
          "stop: %r CONTROL %#x" % (r.stderr, rd(mem, BASE + CTRL0)))
    # remoteproc is the default loader: without an instance, a clear refusal
    r = run("--target", "am335x", "--devmem", mem, "--sysfs", tmp, "--slave", "14,6,0x43,0,0",
            "read", env=env)
    check(r.returncode == 1 and "remoteproc" in r.stderr and "--loader devmem" in r.stderr,
          "no remoteproc: %r" % r.stderr)
    r = run("--loader", "uio", "info")
    check(r.returncode == 2 and "remoteproc or devmem" in r.stderr, "bad loader: %r" % r.stderr)

# safety checks (host/README.md): a frozen life counter flagged from its frame on
# and counted, a healthy two-channel encoder flagging nothing, bad checks refused
SCEN = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "scenarios")
r = run("--scenario", os.path.join(SCEN, "safety-frozen.json"), "--freq", "5000000",
        "read", "-n", "260")
lines = r.stdout.splitlines()
frozen = [int(re.match(r"frame=(\d+) ", l).group(1)) for l in lines if " s2.life=frozen" in l]
check(r.returncode == 0 and frozen and min(frozen) == 200 and len(frozen) >= 55,
      "frozen counter: rc %d, frames %r %r" % (r.returncode, frozen[:3], r.stderr))
check(not any(" s2.life=skip" in l for l in lines), "frozen is not skip")
m = re.search(r"^safety: s2.life_checked=(\d+) s2.life_frozen=(\d+) s2.life_skipped=0$", r.stdout, re.M)
check(m and int(m.group(2)) == len(frozen), "frozen count: %r" % (lines[-1:],))
r = run("--profile", "biss-safety-two-channel", "--freq", "10000000", "--check-life", "0",
        "--check-life", "1", "--check-pair", "0,1,16,0,4", "read", "-n", "20")
check(r.returncode == 0 and r.stdout.count(" s1.life=ok") >= 18 and r.stdout.count(" pair0=ok") >= 19
      and "life=frozen" not in r.stdout and "pair0.disagree=0" in r.stdout,
      "healthy two channels: %r %r" % (r.stdout[-300:], r.stderr))
r = run("--scenario", os.path.join(SCEN, "safety-skip.json"), "--freq", "10000000", "read",
        "-n", "220", "--json")
try:
    j = json.loads(r.stdout)
except ValueError:
    j = {}
fr = j.get("frames", [])
skips = [f["frame"] for f in fr if f.get("slaves") and f["slaves"][1].get("life") == "skip"]
life = (j.get("safety") or {}).get("life_counter") or [{}, {}]
check(r.returncode == 0 and len(fr) == 220 and skips and min(skips) == 200
      and life[1].get("skipped") == len(skips) and life[0].get("skipped") == 0
      and all(p == "ok" for f in fr for p in f.get("pairs", []) if p != "-"),
      "read --json, skipping counter: rc %d %r %r" % (r.returncode, life, r.stderr))
for args, text in [(["--check-pair", "0,1", "read"], "--check-pair"),
                   (["--check-life", "9", "read"], "--check-life")]:
    r = run(*args)
    check(r.returncode == 2 and text in r.stderr, "%r: rc %d, %r" % (args, r.returncode, r.stderr))
r = run("--slave", "32,16,0x190D9,0,6", "--slave", "28,16,0x190D9,0,6", "--check-pair", "0,1,16,0,4",
        "read")
check(r.returncode == 1 and "same polynomial and start value" in r.stderr, "one CRC: %r" % r.stderr)
r = run("--check-life", "0", "read")  # the default encoder has no life counter
check(r.returncode == 1 and "life-counter check" in r.stderr, "no counter: %r" % r.stderr)

# the nE/nW check of a slave that never sets them (--check-ew): quiet on a
# healthy encoder, every frame "misframed" (not valid, no position) when the
# model does set nE, refused for a layout without nE/nW
r = run("--freq", "10000000", "--check-ew", "0", "read", "-n", "5")
check(r.returncode == 0 and r.stdout.count(" valid ") == 4 and "misframed" not in r.stdout.split("safety:")[0]
      and re.search(r"^safety: s0.ew_checked=[45] s0.misframed=0$", r.stdout, re.M),
      "healthy encoder, --check-ew 0: %r %r" % (r.stdout, r.stderr))
with tempfile.TemporaryDirectory() as d:
    sets = os.path.join(d, "sets-ne.json")
    with open(sets, "w") as f:
        f.write('{"biss": {"slaves": [{"error": true}]}}')
    r = run("--scenario", sets, "--freq", "10000000", "--check-ew", "0", "read", "-n", "5")
    check(r.returncode == 0 and r.stdout.count(" misframed ") >= 4 and "pos=" not in r.stdout
          and re.search(r"^safety: s0.ew_checked=([45]) s0.misframed=\1$", r.stdout, re.M),
          "nE set, --check-ew 0: %r %r" % (r.stdout, r.stderr))
    r = run("--scenario", sets, "--freq", "10000000", "--check-ew", "0", "read", "-n", "3", "--json")
    try:
        j = json.loads(r.stdout)
    except ValueError:
        j = {}
    states = [f["state"] for f in j.get("frames", [])]
    ew = ((j.get("safety") or {}).get("ew_static") or [{}])[0]
    check(r.returncode == 0 and states.count("misframed") >= 2 and ew.get("slave") == 0
          and ew.get("misframed") == ew.get("checked") == states.count("misframed"),
          "nE set, --json: %r %r" % (states, ew))
r = run("--slave", "14,6,0x43,0", "--check-ew", "0", "read")
check(r.returncode == 1 and "nE/nW check" in r.stderr, "no nE/nW: %r" % r.stderr)
r = run("--check-ew", "x", "read")
check(r.returncode == 2 and "--check-ew" in r.stderr, "--check-ew x: %r" % r.stderr)

# the speed check (--check-speed): quiet on the healthy encoder (50 000
# counts/s) at 60 000; at 10 counts/s a step of 2 counts in 23 us is beyond
# reach, and that frame is misframed (1.13 counts a frame: 10 frames checked
# hold a step of 2 wherever the first frame falls in the encoder's motion)
r = run("--freq", "10000000", "--check-speed", "0,60000", "read", "-n", "5")
check(r.returncode == 0 and r.stdout.count(" valid ") == 4 and r.stdout.count("s0.speed=ok") == 3
      and re.search(r"^safety: s0.pos_checked=3 s0.pos_jumped=0 s0.pos_resync=0 s0.pos_untimed=0$", r.stdout, re.M),
      "healthy encoder, --check-speed 0,60000: %r %r" % (r.stdout, r.stderr))
r = run("--freq", "10000000", "--check-speed", "0,10", "read", "-n", "12")
check(r.returncode == 0 and " misframed " in r.stdout
      and re.search(r"^safety: s0.pos_checked=10 s0.pos_jumped=[1-9] s0.pos_resync=[0-9] s0.pos_untimed=0$", r.stdout,
                    re.M),
      "--check-speed 0,10: %r %r" % (r.stdout, r.stderr))
r = run("--freq", "10000000", "--check-speed", "0,60000", "read", "-n", "3", "--json")
try:
    sp = (json.loads(r.stdout).get("safety") or {}).get("max_speed")
except ValueError:
    sp = None
check(sp == [{"slave": 0, "counts_per_s": 60000, "checked": 1, "jumped": 0, "resync": 0, "untimed": 0}], "--check-speed --json: %r" % sp)
r = run("--check-speed", "0,x", "read")
check(r.returncode == 2 and "--check-speed" in r.stderr, "--check-speed 0,x: %r" % r.stderr)
# the range the scenario files take, 1e-9..1e18 (one rule)
for spd in ["0,1e308", "0,2e18", "0,1e-10"]:
    r = run("--check-speed", spd, "read")
    check(r.returncode == 2 and "--check-speed" in r.stderr and "1e-9..1e18" in r.stderr,
          "--check-speed %s: %r" % (spd, r.stderr))
r = run("--check-speed", "1,5", "read")
check(r.returncode == 1 and "speed check" in r.stderr, "--check-speed 1,5: %r" % r.stderr)

# the rate against the line (proto/biss_line.c): TIDEP0022 Table 5 by the
# cable the user names (a warning; why no slave answered once the frames
# show it), a slave timeout below 55 % of the MA period (refused before
# anything runs), and without a length the round trip the training frame
# measured, or measured at 1 MHz when nothing answered
T5_80 = ("10 MHz on 80 m of cable: TIDEP0022 Table 5 gives 10 MHz up to 10 m; rates that work: "
         "1 MHz, 800 kHz, 781.25 kHz")
r = run("--freq", "10000000", "--cable-m", "80", "read", "-n", "2")
check(r.returncode == 0 and r.stdout.count("no-slave") == 2
      and "bissctl: warning: " + T5_80 + "\n" in r.stderr
      and "bissctl: no slave answered: " + T5_80 + "\n" in r.stderr,
      "10 MHz, 80 m: %r %r" % (r.stdout, r.stderr))
r = run("--freq", "10000000", "--cable-m", "80", "start")
check(r.returncode == 0 and "bissctl: no slave answered: " + T5_80 in r.stderr,
      "start at 10 MHz, 80 m: %d %r" % (r.returncode, r.stderr))
r = run("--freq", "5000000", "--cable-m", "25", "read", "-n", "3")
check(r.returncode == 0 and r.stderr == "" and r.stdout.count(" valid ") == 2,
      "5 MHz, 25 m (Table 5): %r %r" % (r.stdout, r.stderr))
tmp = tempfile.mkdtemp()
far = os.path.join(tmp, "80m.json")
with open(far, "w") as f:
    f.write('{"profile": "tidep0022-test-encoder", "line": {"length_m": 80}}')
r = run("--freq", "10000000", "--scenario", far, "read", "-n", "2")
m = re.search(r"no slave answered at 10 MHz; at 1 MHz the line's round trip is (\d+) ns\n"
              r"bissctl: no slave answered: 10 MHz on a line with a round trip of (\d+) ns "
              r"\(about (\d+) m of cable: 5 ns/m each way after 68 ns of transceivers\): "
              r"TIDEP0022 Table 5 gives 10 MHz up to 10 m \(a round trip up to about 168 ns\); "
              r"rates that work: 1 MHz, 800 kHz, 781.25 kHz", r.stderr)
check(r.returncode == 0 and m and m.group(1) == m.group(2) and 80 <= int(m.group(3)) <= 110,
      "80 m not named, measured at 1 MHz: %r" % r.stderr)
r = run("--scenario", far, "--freq", "1000000", "read", "-n", "3")
check(r.returncode == 0 and r.stdout.count(" valid ") == 2 and r.stderr == "",
      "80 m at 1 MHz: no word: %r %r" % (r.stdout, r.stderr))
r = run("--freq", "5000000", "--scenario", far, "read", "-n", "3")
m = re.search(r"^bissctl: warning: 5 MHz on a line with a round trip of \d+ ns \(about \d+ m of "
              r"cable.*TIDEP0022 Table 5 gives 5 MHz up to 25 m.*rates that work: 1 MHz, 800 kHz, "
              r"781.25 kHz$", r.stderr, re.M)
check(r.returncode == 0 and m, "5 MHz on 80 m, measured: %r %r" % (r.stdout, r.stderr))
r = run("--freq", "500000", "--slave-timeout-ns", "650", "read")
check(r.returncode == 1 and r.stdout == "" and r.stderr ==
      "bissctl: configuration: a slave timeout of 650 ns is below 55 % of the MA period at 500 kHz "
      "(1100 ns, iC-MB4 I306): the slave may end the frame within a clock phase; rates that work: "
      "1 MHz, 1.25 MHz, 1.5625 MHz\n", "timeout 650 ns at 500 kHz: %d %r" % (r.returncode, r.stderr))
r = run("--freq", "1000000", "--slave-timeout-ns", "550", "read")
check(r.returncode == 0 and r.stderr == "", "timeout 550 ns at 1 MHz: %r" % r.stderr)
r = run("--slave-timeout-ns", "0", "read")
check(r.returncode == 2 and "--slave-timeout-ns" in r.stderr, "timeout 0: %r" % r.stderr)
# rates: no target, what the line allows, fastest first
r = run("--cable-m", "30", "rates")
check(r.returncode == 0 and re.search(r"^rates_hz=2000000,1562500,1250000,1000000,", r.stdout, re.M),
      "rates for 30 m: %r %r" % (r.stdout, r.stderr))
r = run("--cable-m", "30", "--slave-timeout-ns", "300", "rates")
check(r.returncode == 0 and re.search(r"^rates_hz=2000000$", r.stdout, re.M),
      "rates for 30 m and a 300 ns timeout: %r" % r.stdout)
r = run("--round-trip-ns", "1046", "--freq", "10000000", "rates")
check(r.returncode == 0 and "round trip 1046 ns: about 98 m of cable" in r.stdout
      and "10 MHz: 10 MHz on a line with a round trip of 1046 ns" in r.stdout,
      "rates --round-trip-ns 1046 --freq 10 MHz: %r" % r.stdout)
r = run("--cable-m", "10", "--freq", "10000000", "rates")
check(r.returncode == 0 and "10 MHz: within TIDEP0022 Table 5 for this line" in r.stdout,
      "10 MHz on 10 m: %r" % r.stdout)
r = run("--slave-timeout-ns", "650", "--freq", "500000", "rates")
check(r.returncode == 1 and "rates that work: 1 MHz, 1.25 MHz, 1.5625 MHz" in r.stdout,
      "rates, short timeout: %d %r" % (r.returncode, r.stdout))
r = run("rates")
check(r.returncode == 2 and "rates needs --cable-m" in r.stderr, "rates alone: %r" % r.stderr)

# the emulator says so in JSON too; start on the emulator says the master
# ends with bissctl
r = run("--freq", "10000000", "read", "-n", "1", "--json")
try:
    j = json.loads(r.stdout)
except ValueError:
    j = {}
check(j.get("target") == "emu" and j.get("emulated") is True and len(j.get("frames", [])) == 1,
      "read --json on the emulator: %r" % r.stdout[:200])
r = run("--freq", "10000000", "start")
check(r.returncode == 0 and r.stdout.startswith("started: target=emu pru=0 ")
      and "ends with this bissctl" in r.stdout, "emulated start: %r %r" % (r.stdout, r.stderr))

# --config FILE: key = value lines as the long options; the command line
# wins; each error names FILE:LINE
with tempfile.TemporaryDirectory() as d:
    conf = os.path.join(d, "pru0.conf")

    def conf_with(text):
        with open(conf, "w") as f:
            f.write(text)

    conf_with("# a comment\n\n  freq = 10000000   # 10 MHz\nslave = 14,6,0x43,0,0\n"
              "slave=14,6,0x43,0,0\ntrigger = host\n")
    r = run("--config", conf, "info")
    check(r.returncode == 0 and "freq_hz=10000000 slaves=2 trigger=host" in r.stdout,
          "--config: %r %r" % (r.stdout, r.stderr))
    # the command line's options win, its --slave lines replace the file's
    r = run("--config", conf, "--freq", "5000000", "--slave", "14,6,0x43,0,0", "info")
    check(r.returncode == 0 and "freq_hz=5000000 slaves=1 trigger=host" in r.stdout,
          "--config overridden: %r %r" % (r.stdout, r.stderr))
    r = run("--freq", "5000000", "--config", conf, "info")  # wherever --config stands
    check(r.returncode == 0 and "freq_hz=5000000 slaves=2" in r.stdout,
          "--config after: %r %r" % (r.stdout, r.stderr))
    for text, line, words in [("freq = 10000000\nfreq = fast\n", 2, "--freq 'fast'"),
                              ("\n\n\nms = 5\n", 4, "'ms' is a command's option"),
                              ("slave\n", 1, "'slave' needs a value"),
                              ("slave =\n", 1, "'slave' needs a value"),
                              ("speed = 3\n", 1, "unknown key 'speed'"),
                              ("config = x\n", 1, "'config' is a command's option"),
                              ("attach = 1\n", 1, "'attach' is a command's option"),
                              ("slave = 14,6\n", 1, "--slave '14,6'")]:
        conf_with(text)
        r = run("--config", conf, "info")
        check(r.returncode == 2 and ("%s:%d: " % (conf, line)) in r.stderr and words in r.stderr,
              "--config %r: %d %r" % (text, r.returncode, r.stderr))
    conf_with("slave = 14,6,0x03,0,0\n")  # a configuration the library refuses
    r = run("--config", conf, "info")
    check(r.returncode == 1 and ("configuration in %s: " % conf) in r.stderr
          and "polynomial" in r.stderr, "--config refused: %r" % r.stderr)
    r = run("--config", os.path.join(d, "none.conf"), "info")
    check(r.returncode == 1 and "none.conf: No such file or directory (errno 2)" in r.stderr,
          "--config missing: %r" % r.stderr)

# bissctl encoder: the encoder firmware (pru_slave/) on PRU1 of a board. On
# the emulator it is refused (biss-sim --encoder runs the loop); on the file
# standing in for /dev/mem, a thread plays the firmware as its start-up and
# its configuration handshake write data RAM (include/biss/biss_slave_shm.h)
for args, text in [(["encoder"], "expected start CHAIN, status, ew"),
                   (["encoder", "go"], "expected start CHAIN, status, ew"),
                   (["encoder", "start"], "needs the chain"),
                   (["encoder", "start", "nope"], "unknown profile 'nope'"),
                   (["encoder", "start", "/nonexistent.json"], "/nonexistent.json")]:
    r = run(*args)
    check(r.returncode == 2 and text in r.stderr, "%r: rc %d %r" % (args, r.returncode, r.stderr))
r = subprocess.run([CTL, "encoder", "start", "tidep0022-test-encoder"], capture_output=True,
                   text=True, timeout=120)
check(r.returncode == 1 and "biss-sim --encoder" in r.stderr, "encoder on emu: %r" % r.stderr)

D1, IRAM1, CTRL1 = 0x2000, 0x38000, 0x24000     # PRU1's data RAM, IRAM, CONTROL
SLV_CFG_SEQ, SLV_NSLAVES, SLV_LIVE_EW = 0x000, 0x004, 0x018
SLV_MAGIC, SLV_PRU, SLV_ACK, SLV_ERR, SLV_FRAMES, SLV_MA_BIT = 0x120, 0x124, 0x128, 0x12C, 0x130, 0x13F


def play_encoder(mem, stop, slaves_seen):
    """The encoder's start-up whenever PRU1 runs without its magic (a load
    clears data RAM), then an ack for each configuration, its frames
    counted. A PRU does nothing while it is loaded, but this thread may be
    between two reads when a load clears data RAM: a sequence number read
    before the clearing and an ack read after it would ack an old
    configuration in the new image. Only this thread writes the magic (on
    its next turn), so the magic still there after both reads says that
    they saw one image."""
    import time
    magic = 0x564c5342
    while not stop.is_set():
        up = rd(mem, BASE + CTRL1) & 2
        if up and rd(mem, BASE + D1 + SLV_MAGIC) != magic:
            wr(mem, BASE + D1 + SLV_PRU, 1)
            wr(mem, BASE + D1 + SLV_MA_BIT, 1, 1)
            wr(mem, BASE + D1 + SLV_MAGIC, magic)
        seq = rd(mem, BASE + D1 + SLV_CFG_SEQ)
        ack = rd(mem, BASE + D1 + SLV_ACK)
        nslaves = rd(mem, BASE + D1 + SLV_NSLAVES, 1)
        if up and seq and seq != ack and rd(mem, BASE + D1 + SLV_MAGIC) == magic:
            slaves_seen.append(nslaves)
            wr(mem, BASE + D1 + SLV_ERR, 0)
            wr(mem, BASE + D1 + SLV_FRAMES, 4321)
            wr(mem, BASE + D1 + SLV_ACK, seq)
        time.sleep(0.001)


with tempfile.TemporaryDirectory() as tmp:
    import threading
    env = dict(os.environ, BISS_LOCK_DIR=tmp)
    mem = os.path.join(tmp, "mem")
    with open(mem, "wb") as f:
        f.truncate(BASE + 0x80000)
    wr(mem, CLKCTRL, 2)
    dm = ["--target", "am335x", "--loader", "devmem", "--devmem", mem, "--sysfs", tmp]
    # nothing answers: loaded on PRU1, enabled, and the missing magic named
    r = run(*dm, "--timeout-ms", "50", "encoder", "start", "tidep0022-test-encoder", env=env)
    check(r.returncode == 1 and "no encoder magic" in r.stderr and "PRU1" in r.stderr
          and rd(mem, BASE + CTRL1) & 2 and rd(mem, BASE + IRAM1) != 0
          and rd(mem, BASE + CTRL0) == 0, "encoder, no firmware: %r" % r.stderr)
    wr(mem, BASE + CTRL1, 1)
    stop, seen = threading.Event(), []
    t = threading.Thread(target=play_encoder, args=(mem, stop, seen))
    t.start()
    try:
        r = run(*dm, "--timeout-ms", "2000", "encoder", "start", "encoder-ad38.json", env=env)
        check(r.returncode == 2 and "encoder-ad38.json" in r.stderr, "missing file: %r" % r.stderr)
        scen = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "scenarios",
                            "encoder-ad38.json")
        r = run(*dm, "--timeout-ms", "2000", "encoder", "start", scen, env=env)
        check(r.returncode == 0 and r.stdout == "encoder running on PRU1: 3 slaves, MA in on R31 "
              "bit 1, SL out on R30 bit 0\n" and seen == [3] and rd(mem, BASE + CTRL1) & 2,
              "encoder start: %r %r %r" % (r.stdout, r.stderr, seen))
        r = run(*dm, "encoder", "status", env=env)
        check(r.returncode == 0 and r.stdout.startswith("pru=1 ma_bit=1 cfg_seq=1 cfg_error=0\n")
              and "frames=4321 " in r.stdout, "encoder status: %r %r" % (r.stdout, r.stderr))
        # a profile, as docs/hardware.md section 14 shows it (stdout and the note)
        r = run(*dm, "--timeout-ms", "2000", "encoder", "start", "tidep0022-test-encoder", env=env)
        check(r.returncode == 0 and r.stdout == "encoder running on PRU1: 1 slave, MA in on R31 bit "
              "1, SL out on R30 bit 0\n" and r.stderr == "encoder: slave 0 moves 3 counts a frame "
              "(50000 counts/s over a frame of 50.000 us)\n" and seen[-1] == 1,
              "encoder start profile: %r %r" % (r.stdout, r.stderr))
        # nE/nW live: slave 1's nE active, then both inactive
        r = run(*dm, "encoder", "ew", "1", "error", env=env)
        check(r.returncode == 0 and r.stdout == "slave 1: nE active, nW inactive\n"
              and rd(mem, BASE + D1 + SLV_LIVE_EW + 1, 1) == 0x01,
              "encoder ew: %r %r" % (r.stdout, r.stderr))
        r = run(*dm, "encoder", "ew", "1", env=env)
        check(r.returncode == 0 and rd(mem, BASE + D1 + SLV_LIVE_EW + 1, 1) == 0,
              "encoder ew clear: %r" % r.stderr)
        for args in [["ew"], ["ew", "8"], ["ew", "0", "fault"]]:
            r = run(*dm, "encoder", *args, env=env)
            check(r.returncode == 2 and "encoder ew" in r.stderr, "%r: %r" % (args, r.stderr))
        # the master's PRU0 is left alone throughout
        check(rd(mem, BASE + CTRL0) == 0, "PRU0 touched: %#x" % rd(mem, BASE + CTRL0))
        r = run(*dm, "encoder", "stop", env=env)
        check(r.returncode == 0 and r.stdout == "stopped: the encoder on PRU1\n"
              and not rd(mem, BASE + CTRL1) & 2, "encoder stop: %r %r" % (r.stdout, r.stderr))
    finally:
        stop.set()
        t.join()
    # the image for the other PRU is refused by name
    wr(mem, BASE + D1 + SLV_PRU, 0)
    r = run(*dm, "encoder", "status", env=env)
    check(r.returncode == 1 and "assembled for PRU0" in r.stderr, "encoder other PRU: %r" % r.stderr)

finish("bissctl CLI")
