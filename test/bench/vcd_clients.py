#!/usr/bin/env python3
"""The bench's VCD in the tools engineers open it with: sigrok-cli reads it
and its decoders find the MA edges and the frames (the frame wire as a chip
select), GTKWave's vcd2fst converts it and fst2vcd gives the same changes
back; the 1 ns default keeps the order of every edge a 1 ps file has."""
import os
import shutil
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(__file__))
from vcd_check import read_vcd  # noqa: E402
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "common"))
from checks import check, finish  # noqa: E402

SIM = sys.argv[1]


def run(*args):
    r = subprocess.run(list(args), capture_output=True, text=True, timeout=120)
    if r.returncode:
        print("FAIL: %s exited %d: %s" % (" ".join(args), r.returncode, r.stderr))
        sys.exit(1)
    return r.stdout


for tool in ["sigrok-cli", "vcd2fst", "fst2vcd"]:
    if not shutil.which(tool):
        print("FAIL: %s is not installed (scripts/setup.sh installs sigrok-cli and gtkwave)" % tool)
        sys.exit(1)

tmp = tempfile.mkdtemp()
vcd = os.path.join(tmp, "bench.vcd")
vcd_ps = os.path.join(tmp, "bench_ps.vcd")
# the default encoder (TIDEP0022: 12-bit position, nE, nW, CRC6) at 10 MHz
common = ["--freq", "10000000", "--frames", "20", "--seed", "5"]
run(SIM, *common, "--vcd", vcd)
run(SIM, *common, "--vcd", vcd_ps, "--vcd-timescale", "1ps")

scale, data = read_vcd(vcd)
check(scale == 1000, "default timescale 1 ns, got %g ps" % scale)
wires = {n: ch for (scope, n), ch in data.items() if scope == "bench"}
check(set(wires) == {"MA_master", "SL_master", "MA_slave", "SL_slave", "frame"},
      "wires %s" % sorted(wires))


def edges(changes):
    """Changes after the first 0 or 1 (which sets the wire, not an edge)."""
    known = [(t, v) for t, v in changes if v in "01"]
    return known[1:]


ma = edges(wires["MA_master"])
frame = edges(wires["frame"])
rises = [t for t, v in ma if v == "1"]
ups = [t for t, v in frame if v == "1"]
downs = [t for t, v in frame if v == "0"]
check(len(downs) >= 20, "frame wire: %d frames closed" % len(downs))

# sigrok-cli parses it: five logic channels at 1 GHz
show = run("sigrok-cli", "-I", "vcd", "-i", vcd, "--show")
check("Samplerate: 1000000000" in show, "sigrok sample rate: %s" % show)
for n in wires:
    check("- %s: logic" % n in show, "sigrok channel %s" % n)

# the timing decoder times every interval between MA edges at the master
timing = run("sigrok-cli", "-I", "vcd", "-i", vcd, "-P", "timing:data=MA_master",
             "-A", "timing=time").splitlines()
check(len(timing) == len(ma) - 1, "timing: %d intervals for %d MA edges" % (len(timing), len(ma)))
check(sum(1 for l in timing if l.strip() == "timing-1: 50.000 ns (20.000 MHz)") >= 20 * 40,
      "timing: MA half periods of 50 ns at 10 MHz")

# the SPI decoder with the frame wire as chip select: one transfer per
# frame, one bit per MA rise inside it
spi = ["sigrok-cli", "-I", "vcd", "-i", vcd, "-P",
       "spi:clk=MA_master:miso=SL_master:cs=frame:cs_polarity=active-high:cpol=1:cpha=1:wordsize=1"]
transfers = [l.split(":", 1)[1].split() for l in run(*spi, "-A", "spi=miso-transfer").splitlines()]
bits = run(*spi, "-A", "spi=miso-bits").splitlines()
check(len(transfers) == len(downs), "spi: %d transfers for %d frames" % (len(transfers), len(downs)))
# (the last frame may still be open when the run ends: its bits count too)
in_frames = sum(1 for a, b in zip(ups, downs + [float("inf")]) for r in rises if a <= r <= b)
closed = sum(1 for a, b in zip(ups, downs) for r in rises if a <= r <= b)
check(len(bits) == in_frames and sum(len(t) for t in transfers) == closed,
      "spi: %d bits, %d MA rises in frames" % (len(bits), in_frames))
# the training frame has two clocks; a data frame 2 to the ACK, start,
# CDS, 12 + 2 + 6 bits, and the one that starts the slave's timeout
check(len(transfers[0]) == 2, "spi: training frame of 2 clocks, got %d" % len(transfers[0]))
check(all(len(t) == 25 for t in transfers[1:]),
      "spi: data frames of 25 clocks, got %s" % sorted({len(t) for t in transfers[1:]}))

# 1 ns and 1 ps files: the same changes in the same order, within a ns or two
_, data_ps = read_vcd(vcd_ps)


def ordered(d):
    """Every change of every wire in time order (stable: file order at a tie)."""
    return sorted(((t, n, v) for (s, n), ch in d.items() for t, v in edges(ch)), key=lambda c: c[0])


ns, ps = ordered(data), ordered(data_ps)
check([c[1:] for c in ns] == [c[1:] for c in ps], "1 ns file keeps the 1 ps file's order of changes")
check(len(ns) == len(ps) and all(abs(a[0] - b[0]) <= 2000 for a, b in zip(ns, ps)),
      "1 ns file within 2 ns of the 1 ps file")
check(len({c[0] for c in ns}) == len({c[0] for c in ps}), "edges at distinct ps at distinct ns")

# GTKWave's converter takes it, and its reverse gives the same changes back
fst = os.path.join(tmp, "bench.fst")
run("vcd2fst", vcd, fst)
check(os.path.getsize(fst) > 0, "vcd2fst wrote %s" % fst)
back = os.path.join(tmp, "back.vcd")
with open(back, "w") as f:
    f.write(run("fst2vcd", fst))
_, data_back = read_vcd(back)
check({k: edges(v) for k, v in data_back.items()} == {k: edges(v) for k, v in data.items()},
      "fst2vcd gives the same changes back")

finish("VCD client")
