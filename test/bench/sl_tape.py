#!/usr/bin/env python3
"""biss-sim --sl-record / --sl-replay (emulator/bench/sl_tape.h): a replay
with the recording's options is the recorded run, instruction for
instruction, with no model running; anything else is told apart, and bad
tapes and options get clear errors."""
import json
import os
import struct
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "common"))
from checks import check, finish  # noqa: E402

SIM = sys.argv[1]
ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")
CHAIN = ["--scenario", os.path.join(ROOT, "test/scenarios/chain3-650ns.json"),
         "--freq", "10000000", "--frames", "300"]
tmp = tempfile.mkdtemp()


def run(*args):
    return subprocess.run([SIM, *args], capture_output=True, text=True, timeout=300)


def words(path):
    with open(path, "rb") as f:
        data = f.read()
    return data[:8], list(struct.unpack("<%dq" % (len(data) // 8 - 1), data[8:]))


def write(path, magic, w):
    with open(path, "wb") as f:
        f.write(magic + struct.pack("<%dq" % len(w), *w))


# a clocked chain recorded, then replayed
tape = os.path.join(tmp, "chain.tape")
r = run(*CHAIN, "--json", "--sl-record", tape)
check(r.returncode == 0, "record: exit %d %r" % (r.returncode, r.stderr))
rec = json.loads(r.stdout)
check(rec["frames"] == 300 and rec["crc_errors"] == 0, "record: 300 clean frames: %s" % rec["frames"])
magic, w = words(tape)
edges = w[1:-4]
check(magic == b"BISSSLT1" and w[0] in (0, 1) and w[-4] == 2**63 - 1, "tape: header and end mark")
# SL at the master: each frame's ACK, start bit and the data's changes, so
# tens of edges a frame, in time order
check(len(edges) > 300 * 10 and all(a // 2 < b // 2 for a, b in zip(edges, edges[1:])),
      "tape: %d edges, increasing" % len(edges))
check(w[-2] == rec["pru_cycles"], "tape: the run's %d cycles, got %d" % (rec["pru_cycles"], w[-2]))

r = run(*CHAIN, "--json", "--sl-replay", tape)
check(r.returncode == 0 and r.stderr == "", "replay: exit %d %r" % (r.returncode, r.stderr))
j = json.loads(r.stdout) if r.returncode == 0 else {}
check(j.get("same_run") is True and j.get("frames") == 300 and j.get("crc_errors") == 0
      and j.get("pru_cycles") == rec["pru_cycles"] and j.get("pru_instructions") == w[-3],
      "replay: the recorded run: %s" % j)
r = run(*CHAIN, "--sl-replay", tape)
check(r.returncode == 0 and "the recorded run, instruction for instruction" in r.stdout
      and "no cable or encoder model" in r.stdout, "replay, text: %r" % r.stdout)

# the fast paths change nothing a tape holds: the same tape without them
slow = os.path.join(tmp, "slow.tape")
r = run(*CHAIN, "--json", "--sl-record", slow, "--no-fast-path", "ma-ahead",
        "--no-fast-path", "slave-quick", "--no-fast-path", "line-settled")
check(r.returncode == 0 and open(slow, "rb").read() == open(tape, "rb").read(),
      "record without ma-ahead, slave-quick, line-settled: the same tape")

# other options: another run, told apart (exit 1, no claim of sameness)
r = run(*CHAIN[:2], "--freq", "5000000", "--frames", "300", "--json", "--sl-replay", tape)
j = json.loads(r.stdout) if r.stdout else {}
check(r.returncode == 1 and j.get("same_run") is False and "not the run recorded on" in r.stderr,
      "replay at 5 MHz: not the same run (exit %d, %r)" % (r.returncode, r.stderr))

# one data bit changed on the tape (a 0-1 pulse in the middle of a frame
# taken out: the same timing, other bits): not the same run
mid = len(edges) // 2
while not (edges[mid] & 1 == 0 and edges[mid + 1] - edges[mid] < 2 * 200 * 1000):
    mid += 1  # a fall followed within 200 ns by a rise: one bit low
bit = os.path.join(tmp, "bit.tape")
write(bit, magic, [w[0]] + edges[:mid] + edges[mid + 2:] + w[-4:])
r = run(*CHAIN, "--json", "--sl-replay", bit)
j = json.loads(r.stdout) if r.stdout else {}
check(r.returncode == 1 and j.get("same_run") is False,
      "one bit taken off the tape: not the same run (exit %d, %s)" % (r.returncode, j))

# the recorded end each way: instructions, cycles, and the RAMs' hash (a
# change of data bits that keeps the firmware's data-independent timing
# shows only there)
for k, what in [(-3, "instructions"), (-2, "cycles"), (-1, "RAM hash")]:
    end = list(w[-4:])
    end[k] ^= 1
    alt = os.path.join(tmp, "end.tape")
    write(alt, magic, [w[0]] + edges + end)
    r = run(*CHAIN, "--json", "--sl-replay", alt)
    j = json.loads(r.stdout) if r.stdout else {}
    check(r.returncode == 1 and j.get("same_run") is False,
          "the tape's %s changed: not the same run (exit %d)" % (what, r.returncode))

# ... as a tape of PRU1's run played on PRU0 shows: the same instructions
# and cycles, the results in the other data RAM
p1 = os.path.join(tmp, "pru1.tape")
r = run("--pru", "1", "--frames", "50", "--sl-record", p1)
r0 = run("--frames", "50", "--json", "--sl-replay", p1)
j = json.loads(r0.stdout) if r0.stdout else {}
_, w1 = words(p1)
check(r.returncode == 0 and r0.returncode == 1 and j.get("same_run") is False
      and j.get("pru_instructions") == w1[-3] and j.get("pru_cycles") == w1[-2],
      "PRU1's tape on PRU0: the same instructions and cycles, not the same run (%s)" % j)
r = run("--pru", "1", "--frames", "50", "--json", "--sl-replay", p1)
check(r.returncode == 0 and json.loads(r.stdout)["same_run"] is True, "PRU1's tape on PRU1")

# bad tapes: what is wrong, and the path
bad = os.path.join(tmp, "bad.tape")
for name, data, words_ in [
        ("not a tape", b"hello world, no tape here\n", "no header"),
        ("cut short", open(tape, "rb").read()[:1001], "cut short"),
        ("no end", open(tape, "rb").read()[:1000], "no end")]:
    with open(bad, "wb") as f:
        f.write(data)
    r = run(*CHAIN, "--sl-replay", bad)
    check(r.returncode == 1 and bad in r.stderr and words_ in r.stderr,
          "%s: exit %d %r" % (name, r.returncode, r.stderr))
write(bad, magic, [w[0]] + edges[:10] + [edges[3]] + edges[10:] + w[-4:])
r = run(*CHAIN, "--sl-replay", bad)
check(r.returncode == 1 and "edge 11 out of order" in r.stderr, "out of order: %r" % r.stderr)
r = run(*CHAIN, "--sl-replay", os.path.join(tmp, "none.tape"))
check(r.returncode == 1 and "none.tape: No such file or directory" in r.stderr,
      "missing tape: %r" % r.stderr)
r = run(*CHAIN, "--sl-record", os.path.join(tmp, "no", "dir.tape"))
check(r.returncode == 1 and "dir.tape: No such file or directory" in r.stderr,
      "tape not writable: %r" % r.stderr)

# options a tape cannot go with
for args in [["--sl-replay", tape, "--vcd", os.path.join(tmp, "x.vcd")],
             ["--sl-replay", tape, "--sl-record", bad],
             ["--sl-record", bad, "--image", os.path.join(ROOT, "test/bench/clock_frames.p")],
             ["--sl-replay", tape, "--pru1-profile", "hengstler-ad38"]]:
    r = run(*CHAIN, *args)
    check(r.returncode == 2 and "--sl-re" in r.stderr, "%s: exit %d %r" % (args, r.returncode, r.stderr))

finish("sl_tape")
