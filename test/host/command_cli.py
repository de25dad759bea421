#!/usr/bin/env python3
"""bissctl command tells what a BiSS command does and sends one that changes
how an encoder works (switches something off, bypass, reserved, the
maker's own) only with --force; its help lists every command's effect and
the source (proto/biss_cd_cmd.c, host/CD.md "Commands")."""
import os
import subprocess
import sys
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "common"))
from checks import check, finish  # noqa: E402

CTL = sys.argv[1]
FREQ = ["--freq", "10000000"]


def run(*args):
    """bissctl's result, its stdout without the note on the emulator's first line."""
    r = subprocess.run([CTL, *args], capture_output=True, text=True, timeout=120)
    r.stdout = "".join(l for l in r.stdout.splitlines(True) if not l.startswith("emulated: "))
    return r


# the help: all eight (broadcast and addressed, 00..11), which need --force, the source
r = run("command", "--help")
check(r.returncode == 0, "command --help: %d" % r.returncode)
for line in ["broadcast (IDS 0) 0 (00): switches the data channels of every slave off [--force]",
             "broadcast (IDS 0) 1 (01): switches register and command communication of every slave on\n",
             "broadcast (IDS 0) 2 (10): switches every bus coupler to bypass [--force]",
             "broadcast (IDS 0) 3 (11): reserved [--force]",
             "addressed         0 (00): switches the data channel of each addressed slave on\n",
             "addressed         1 (01): switches register and command communication of each addressed "
             "slave off [--force]",
             "addressed         2 (10): switches the addressed bus couplers from bypass to line operation "
             "[--force]",
             "addressed         3 (11): does what each addressed slave's maker defines [--force]",
             "Source: Microchip's dsPIC33A BiSS peripheral documentation, \"Command Communication\""]:
    check(line in r.stdout, "help lacks %r" % line)

# each command that changes the encoder is refused before anything is opened
# (a bad target would fail otherwise), and named
for ids, cmd, words in [("0", "0", "switches the data channels of every slave off"),
                        ("0", "2", "switches every bus coupler to bypass"),
                        ("0", "3", "reserved"),
                        ("0x03", "1", "switches register and command communication of each addressed slave off"),
                        ("1", "2", "bypass to line operation"),
                        ("0x80", "3", "maker defines")]:
    r = run("--target", "am335x", "--devmem", "/nonexistent", "command", ids, cmd)
    check(r.returncode == 2 and words in r.stderr and "--force" in r.stderr and r.stdout == "",
          "command %s %s: %d %r %r" % (ids, cmd, r.returncode, r.stdout, r.stderr))

# with --force it goes out, its effect printed first
r = run(*FREQ, "command", "0x01", "1", "--force")
check(r.returncode == 0 and r.stdout == "command 1 to ID 0: switches register and command communication of "
      "each addressed slave off\nids=0x01 cmd=1 ida=0x01\n", "--force: %d %r %r" % (r.returncode, r.stdout, r.stderr))
# the ones that switch something on need no --force
for ids, cmd, words in [("0", "1", "every slave (broadcast): switches register and command communication of every slave on"),
                        ("0x01", "0", "ID 0: switches the data channel of each addressed slave on")]:
    r = run(*FREQ, "command", ids, cmd, "--ida-test")
    check(r.returncode == 0 and r.stdout.startswith("command %s to %s\n" % (cmd, words)),
          "command %s %s: %d %r %r" % (ids, cmd, r.returncode, r.stdout, r.stderr))

finish("command_cli")
