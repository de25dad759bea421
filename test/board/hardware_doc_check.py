#!/usr/bin/env python3
"""docs/hardware.md against the build it describes: what the guide shows as
output is what the build prints today.

- The readelf excerpt (program headers of biss_master.elf) is readelf's
  output for the built ELF, and the dmesg excerpt's image size its size.
- Each block after a "<!-- emulator output: bissctl ARGS -->" line is what
  the build's bissctl prints for ARGS (the emulator is deterministic); after
  "<!-- emulator output: biss-sim ARGS -->" what biss-sim prints, less its
  "PRU cycles" line (it gives the host's time).
- The scope table after "<!-- scope: biss-sim ARGS -->" holds what the
  emulator's VCD of MA at the master pin shows for ARGS: MA period, idle
  level, clocks per frame, the burst, the gap and the frame period (the
  training frame, frame 1, left out).

usage: hardware_doc_check.py HARDWARE_MD BISS_MASTER_ELF BISSCTL BISS_SIM
"""
import os
import re
import shlex
import shutil
import subprocess
import sys
import tempfile
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "common"))
from checks import check, finish  # noqa: E402

doc_path, elf, bissctl, biss_sim = sys.argv[1:5]
with open(doc_path) as f:
    doc = f.read()


def block_after(marker_at):
    """The fenced block that follows the text position marker_at."""
    m = re.compile(r"```[a-z]*\n(.*?)```", re.S).search(doc, marker_at)
    return m.group(1) if m else None


# readelf -l: the LOAD lines of the guide's excerpt are readelf's
readelf = shutil.which("readelf")
check(readelf is not None, "readelf on PATH (Debian: binutils)")
if readelf:
    out = subprocess.run([readelf, "-l", "-W", elf], capture_output=True, text=True).stdout
    got = [" ".join(l.split()) for l in out.splitlines() if l.strip().startswith("LOAD")]
    at = doc.find("readelf -l")
    shown = []
    m = re.search(r"(  Type +Offset.*?)\n\n", doc[at:], re.S) if at >= 0 else None
    if m:
        shown = [" ".join(l.split()) for l in m.group(1).splitlines()
                 if l.strip().startswith("LOAD")]
    check(shown and shown == got, "hardware.md readelf excerpt %r, readelf says %r" % (shown, got))

# the size remoteproc reports when it boots the ELF (the dmesg excerpt)
m = re.search(r"Booting fw image \S+, size (\d+)", doc)
check(m is not None and int(m.group(1)) == os.path.getsize(elf),
      "hardware.md: Booting fw image size %s, biss_master.elf has %d bytes" % (
          m.group(1) if m else None, os.path.getsize(elf)))

# bissctl's output on the emulator, as shown
blocks = 0
for m in re.finditer(r"<!-- emulator output: bissctl (.*?) -->", doc):
    blocks += 1
    args = shlex.split(m.group(1))
    shown = block_after(m.end())
    r = subprocess.run([bissctl, *args], capture_output=True, text=True, timeout=120)
    check(r.returncode == 0 and shown is not None and r.stdout == shown,
          "hardware.md shows for bissctl %s:\n%s\nit prints:\n%s%s" % (
              m.group(1), shown, r.stdout, r.stderr))
check(blocks >= 1, "hardware.md has an emulator output block")

# biss-sim's output, as shown, but for the line that gives the host's time
sims = 0
for m in re.finditer(r"<!-- emulator output: biss-sim (.*?) -->", doc):
    sims += 1
    args = shlex.split(m.group(1))
    shown = block_after(m.end())
    r = subprocess.run([biss_sim, *args], capture_output=True, text=True, timeout=120)
    got = "".join(l for l in r.stdout.splitlines(True) if not l.startswith("PRU cycles "))
    check(r.returncode == 0 and shown is not None and got == shown,
          "hardware.md shows for biss-sim %s:\n%s\nit prints:\n%s%s" % (
              m.group(1), shown, got, r.stderr))
check(sims >= 1, "hardware.md has a biss-sim output block (the one-board loop, emulated)")


def ma_bursts(vcd):
    """MA at the master pin as frames: lists of (time ns, level), a new one
    after more than four MA periods without an edge."""
    ids, t, edges = {}, 0, []
    with open(vcd) as f:
        for line in f:
            line = line.strip()
            if line.startswith("$var"):
                p = line.split()
                ids[p[3]] = p[4]
            elif line.startswith("#"):
                t = int(line[1:])
            elif line[:1] in "01" and ids.get(line[1:]) == "MA_master":
                edges.append((t, int(line[0])))
    return edges


def us(ns):
    return "%.3f us" % (ns / 1000.0)


m = re.search(r"<!-- scope: biss-sim (.*?) -->", doc)
check(m is not None, "hardware.md has a scope table")
if m:
    with tempfile.TemporaryDirectory() as tmp:
        vcd = os.path.join(tmp, "ma.vcd")
        r = subprocess.run([biss_sim, *shlex.split(m.group(1)), "--vcd", vcd],
                           capture_output=True, text=True, timeout=300)
        check(r.returncode == 0, "biss-sim %s: %s" % (m.group(1), r.stderr))
        half = re.search(r"MA half period\s+(\d+) \.\. (\d+) cycles", r.stdout)
        edges = ma_bursts(vcd) if r.returncode == 0 else []
    falls = [t for t, v in edges if v == 0]
    frames, cur = [], []
    for t, v in edges:
        if v == 0 and cur and t - cur[-1][0] > 4 * 2 * 5 * int(half.group(1)):
            frames.append(cur)
            cur = []
        if v == 0 or cur:
            cur.append((t, v))
    frames.append(cur)
    data = frames[1:-1]  # no training frame, no frame cut off by the end
    clocks = {sum(1 for _, v in f if v == 0) for f in data}
    bursts = {f[-1][0] - f[0][0] for f in data}
    gaps = [b[0][0] - a[-1][0] for a, b in zip(frames[1:], frames[2:])]
    periods = [b[0][0] - a[0][0] for a, b in zip(frames[1:], frames[2:])]
    levels = {v for t, v in edges if t < falls[0]} if falls else set()
    between = {a[-1][1] for a in frames[:-1]}
    h = int(half.group(1)) if half else 0
    table = {
        "half period H": "%d PRU cycles" % h,
        "MA period": us(2 * h * 5),
        "idle level": "high" if levels == {1} and between == {1} else "?",
        "MA clocks (falling edges) per frame": ",".join(str(c) for c in sorted(clocks)),
        "burst: first falling to last rising edge": ",".join(us(b) for b in sorted(bursts)),
        "MA high between frames": "%s .. %s" % (us(min(gaps)), us(max(gaps))) if gaps else "?",
        "frame period": "%s .. %s" % (us(min(periods)), us(max(periods))) if periods else "?",
    }
    for name, value in table.items():
        row = re.search(r"^\| %s \| ([^|]*) \|$" % re.escape(name), doc[m.end():], re.M)
        check(row is not None and row.group(1).strip() == value,
              "hardware.md scope row %r: %r, the emulator: %r" % (
                  name, row.group(1).strip() if row else None, value))
finish("hardware.md")
