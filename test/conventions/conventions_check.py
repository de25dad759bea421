#!/usr/bin/env python3
"""The tools' one convention (README "Conventions"), tool by tool: a bad
option and a bad value exit 2 with "tool: message" and "Try 'tool --help'
for more information." on stderr and nothing else; an error while running
exits 1 with "tool: ..."; --help exits 0 on stdout; one default MA rate
(bissctl, libbiss, biss-sim); info and stats on the emulator count frames
that ran.
  conventions_check.py PRUASM PRU_RUN PRU_ELF BISS_SIM BISSCTL"""
import os
import re
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "common"))
from checks import check, finish  # noqa: E402

if len(sys.argv) != 6:
    sys.exit(__doc__)
PRUASM, PRU_RUN, PRU_ELF, BISS_SIM, BISSCTL = sys.argv[1:]
TOOLS = {"pruasm": PRUASM, "pru-run": PRU_RUN, "pru-elf": PRU_ELF, "biss-sim": BISS_SIM,
         "bissctl": BISSCTL}
tmp = tempfile.mkdtemp()


def run(tool, *args):
    return subprocess.run([TOOLS[tool], *args], capture_output=True, text=True, timeout=120,
                          cwd=tmp)


def usage_error(tool, args, message, help_for=None):
    """exit 2; stderr exactly the message and the way to the help; stdout
    empty (pruasm prints pasm's banner there first)."""
    r = run(tool, *args)
    want = "%s: %s\nTry '%s --help' for more information.\n" % (tool, message, help_for or tool)
    check(r.returncode == 2 and r.stderr == want
          and (r.stdout == "" or tool == "pruasm" and "Error" not in r.stdout),
          "%s %s: exit %d, %r (want 2, %r)" % (tool, " ".join(args), r.returncode, r.stderr, want))


# an unknown option, each tool
usage_error("pruasm", ["-q", "x.p"], "unknown option '-q'")
usage_error("pruasm", ["--bogus", "x.p"], "unknown option '--bogus'")
usage_error("pru-run", ["--bogus", "x.bin"], "unknown option '--bogus' (or an ambiguous abbreviation)")
usage_error("pru-elf", ["--bogus", "a.bin", "a.elf"], "unknown option '--bogus'")
usage_error("biss-sim", ["--bogus"], "unknown option '--bogus'")
usage_error("bissctl", ["--bogus", "info"], "unknown option '--bogus'")
# a value missing
usage_error("pru-run", ["x.bin", "--max-cycles"], "option '--max-cycles' needs a value")
usage_error("biss-sim", ["--frames"], "option '--frames' needs a value")
usage_error("bissctl", ["info", "--freq"], "option '--freq' needs a value")
# a bad value: "--option 'VALUE': expected WHAT"
usage_error("pru-run", ["--soc", "am999", "x.bin"],
            "--soc 'am999': expected am335x, am437x-icss0 or am437x-icss1")
usage_error("biss-sim", ["--trigger", "sometimes"], "--trigger 'sometimes': expected free, host or iep")
usage_error("biss-sim", ["--cable-m", "-1"], "--cable-m '-1': expected metres, 0..1000")
usage_error("bissctl", ["--cable-m", "-1", "info"], "--cable-m '-1': expected metres, 0..1000")
usage_error("bissctl", ["--trigger", "sometimes", "info"],
            "--trigger 'sometimes': expected host, iep or free")
usage_error("pruasm", ["-V9", "x.p"], "-V: expected a core version, 1..3")
# arguments: too few, too many; bissctl's help once the command is known
usage_error("pruasm", [], "no InFile given")
usage_error("pru-run", [], "no IMAGE.bin given")
usage_error("pru-elf", ["a.bin"], "expected IMAGE.bin OUT.elf, not 1 arguments")
usage_error("bissctl", [], "no command given")
usage_error("bissctl", ["frobnicate"], "unknown command 'frobnicate'")
usage_error("bissctl", ["reg-read"], "reg-read needs a register address 0x00..0x7f",
            help_for="bissctl reg-read")
usage_error("bissctl", ["command", "0", "0"],
            "command 0x00 0 to every slave (broadcast) switches the data channels of every "
            "slave off: that changes how an encoder works; --force sends it",
            help_for="bissctl command")

# an error while running: exit 1, "tool: ..." (pruasm: pasm's words), no
# way to the help (the command line was right)
missing = os.path.join(tmp, "missing")
for tool, args, words in [
        ("pruasm", ["-b", missing + ".p"], "Fatal Error: Can't open source file '%s.p'" % missing),
        ("pru-run", [missing + ".bin"], "pru-run: cannot open %s.bin: No such file" % missing),
        ("pru-elf", [missing + ".bin", os.path.join(tmp, "o.elf")], "pru-elf: %s.bin" % missing),
        ("biss-sim", ["--scenario", missing + ".json"], "biss-sim: "),
        ("bissctl", ["--target", "am335x", "--loader", "devmem", "--devmem", missing, "--attach",
                     "stats"], "bissctl: open: the PRU-ICSS memory cannot be opened or mapped: " + missing)]:
    r = run(tool, *args)
    check(r.returncode == 1 and r.stderr.startswith(words) and "Try '" not in r.stderr,
          "%s %s: exit %d, %r (want 1, %r)" % (tool, " ".join(args), r.returncode, r.stderr, words))

# --help: stdout, exit 0, a usage line; --version: "tool VERSION"
for tool in TOOLS:
    r = run(tool, "--help")
    check(r.returncode == 0 and re.search(r"^[Uu]sage: ", r.stdout, re.M) and r.stderr == "",
          "%s --help: exit %d, %r" % (tool, r.returncode, r.stderr))
    check("exit status" in r.stdout.lower(), "%s --help lists its exit status" % tool)
    r = run(tool, "--version")
    check(r.returncode == 0 and r.stdout.startswith(tool + " "), "%s --version: %r" % (tool, r.stdout))

# one default MA rate: biss-sim runs at the rate bissctl configures, and
# both help texts name it
r = run("biss-sim", "--frames", "3", "--json")
sim_hz = re.search(r'"freq_hz":\s*(\d+)', r.stdout)
r = run("bissctl", "--target", "emu", "info", "--ms", "1")
ctl_hz = re.search(r"^freq_hz=(\d+) ", r.stdout, re.M)
check(sim_hz and ctl_hz and sim_hz.group(1) == ctl_hz.group(1) == "1000000",
      "default rate: biss-sim %s, bissctl %s" % (sim_hz and sim_hz.group(1), ctl_hz and ctl_hz.group(1)))
check("(default 1000000" in run("biss-sim", "--help").stdout
      and "(default 1000000)" in run("bissctl", "--help").stdout, "both helps name 1000000")

# info and stats on the emulator: the master ran before they count, and
# they say for how long; more time, more frames
for cmd in ("info", "stats"):
    counts = {}
    for ms in ("2", "20"):
        r = run("bissctl", "--target", "emu", cmd, "--ms", ms)
        m = re.search(r"^frames=(\d+) crc_errors=0 no_slave=0 proc_errors=0 training=1 off_grid=0$", r.stdout, re.M)
        counts[ms] = int(m.group(1)) if m else 0
        check(r.returncode == 0 and m and counts[ms] > 1 and
              ("emulated: counts after %s ms of simulated time" % ms) in r.stdout,
              "%s --ms %s on the emulator: %d %r %r" % (cmd, ms, r.returncode, r.stdout, r.stderr))
    # 1 MHz, the default encoder: a frame every 45.1 us (biss-sim --freq 1000000)
    check(counts["2"] < counts["20"] and 400 <= counts["20"] <= 460,
          "%s: frames after 2 and 20 ms: %r" % (cmd, counts))
r = run("bissctl", "--target", "emu", "info")
m = re.search(r"publications=(\d+)", r.stdout)
check(m and int(m.group(1)) > 2000, "info, default --ms 100: %r" % r.stdout)

finish("tool conventions")
