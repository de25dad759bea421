#!/usr/bin/env python3
"""bissctl record as a user runs it on the emulator (10 MHz, the default
encoder): every frame into CSV and into .npy, which numpy loads (the
user's tool, not a reader of ours); the two files of one run hold the same
frames; seq runs from the configuration's first frame without a gap; 10^6
frames read every ms, none lost; a host polling every 2 ms (the ring keeps
59 frames, 2 ms bring 88) loses frames, says how many, exits 1, and the
count is the file's gaps; the
AD38's chain, whose frames fill the ring in 0.5 ms, polled every 0.25 ms
loses none; bad command lines and files are refused by name."""
import csv
import os
import re
import subprocess
import sys
import tempfile

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "common"))
from checks import check, finish  # noqa: E402

CTL = sys.argv[1]
BASE = ["--target", "emu", "--freq", "10000000"]
COLUMNS = ["seq", "timestamp", "flags", "valid", "link_eye", "link_warning", "s0_position",
           "s0_data", "s0_error", "s0_warning", "s0_crc_ok"]


def record(path, *extra):
    r = subprocess.run([CTL, *BASE, "record", *extra, path], capture_output=True, text=True,
                       timeout=300)
    m = re.search(r"^recorded=(\d+) lost=(\d+) first_seq=(\d+) last_seq=(\d+) ", r.stdout, re.M)
    summary = {k: int(v) for k, v in zip(("recorded", "lost", "first", "last"), m.groups())} \
        if m else None
    return r, summary


with tempfile.TemporaryDirectory() as tmp:
    npy, csv_path = os.path.join(tmp, "frames.npy"), os.path.join(tmp, "frames.csv")
    # half a second: some 22 000 frames, read every ms, none lost
    r, s = record(npy, "--seconds", "0.5")
    check(r.returncode == 0 and s and s["lost"] == 0, "npy record: %r %r" % (r.stdout, r.stderr))
    a = np.load(npy)
    check(list(a.dtype.names) == COLUMNS, "npy columns: %r" % (a.dtype.names,))
    check(s and len(a) == s["recorded"] > 20000, "npy rows %d, recorded %r" % (len(a), s))
    seq = a["seq"].astype(np.int64)
    check(seq[0] == 1 and bool(np.all(np.diff(seq) == 1)) and s and seq[-1] == s["last"],
          "npy seq from 1 without a gap: %r .. %r" % (seq[:3], seq[-3:]))
    check(a["flags"][0] == 0x10 and a["valid"][0] == 0, "the first frame is the training frame")
    check(bool(np.all(a["valid"][1:] == 1)) and bool(np.all(a["s0_crc_ok"][1:] == 1)),
          "every later frame valid, CRC right")
    ts = a["timestamp"].astype(np.int64)
    check(bool(np.all(np.diff(ts) > 0)), "timestamps rise frame by frame")
    # the same run as CSV: the same frames (the emulator is deterministic)
    r, s2 = record(csv_path, "--seconds", "0.5")
    check(r.returncode == 0 and s2 == s, "csv record: %r %r" % (r.stdout, r.stderr))
    with open(csv_path, newline="") as f:
        rows = list(csv.DictReader(f))
    check(rows and list(rows[0].keys()) == COLUMNS, "csv header: %r" % (rows[:1],))
    same = len(rows) == len(a) and all(
        int(row["seq"]) == int(x["seq"]) and int(row["timestamp"]) == int(x["timestamp"]) and
        int(row["flags"], 16) == int(x["flags"]) and int(row["s0_position"]) == int(x["s0_position"])
        and int(row["s0_data"], 16) == int(x["s0_data"]) for row, x in zip(rows, a))
    check(same, "csv and npy of one run hold the same frames")
    # 10^6 frames (23 s at 10 MHz, 22.7 us a frame), read every ms: none
    # lost, seq without a gap, and the encoder model's motion in every step
    # (it turns at a constant speed: its 12-bit position moves k or k + 1
    # counts a frame period; test_host_ring compares each position with the
    # model's own record of that frame)
    million = os.path.join(tmp, "million.npy")
    r, s3 = record(million, "--seconds", "23")
    m = np.load(million)
    mseq = m["seq"].astype(np.int64)
    check(r.returncode == 0 and s3 and s3["lost"] == 0 and len(m) == s3["recorded"] >= 1000000,
          "10^6 frames: %r %r" % (r.stdout, r.stderr[-300:]))
    check(mseq[0] == 1 and bool(np.all(np.diff(mseq) == 1)), "10^6 frames: seq without a gap")
    msteps = np.diff(m["s0_position"][1:].astype(np.int64)) % 4096
    check(bool(np.all(m["valid"][1:] == 1)) and msteps.max() - msteps.min() <= 1 and
          msteps.min() > 0, "10^6 frames: every one valid, the model's steady motion: %r..%r" %
          (msteps.min(), msteps.max()))
    os.remove(million)
    # --format wins over the extension
    other = os.path.join(tmp, "frames.dat")
    r, _ = record(other, "--seconds", "0.01", "--format", "npy")
    with open(other, "rb") as f:
        check(r.returncode == 0 and f.read(6) == b"\x93NUMPY", "--format npy: %r" % r.stderr)
    # an overrun: polled every 2 ms, frames lost, counted, exit status 1
    lossy = os.path.join(tmp, "lossy.npy")
    r, s = record(lossy, "--seconds", "0.1", "--poll-ms", "2")
    b = np.load(lossy)
    bseq = b["seq"].astype(np.int64)
    gaps = int(bseq[-1] - bseq[0] + 1 - len(b)) + int(bseq[0]) - 1  # before the first and between
    check(r.returncode == 1 and s and s["lost"] > 0 and s["lost"] == gaps and s["first"] == 1,
          "overrun: lost %r, the file's gaps %d: %r" % (s, gaps, r.stderr))
    check("frames lost" in r.stderr and str(s["lost"] if s else "?") in r.stderr,
          "overrun reported: %r" % r.stderr)
    check(bool(np.all(np.diff(bseq) >= 1)), "overrun: seq still rising")
    # the AD38's three slaves at 10 MHz: the ring keeps 0.5 ms (34 frames of
    # 14.2 us); polled every 0.25 ms none is lost, every 1 ms most are
    ad38 = ["--profile", "hengstler-ad38", "--cable-m", "5"]
    fast = os.path.join(tmp, "ad38.npy")
    r, s = record(fast, *ad38, "--seconds", "0.05", "--poll-ms", "0.25")
    c = np.load(fast)
    cseq = c["seq"].astype(np.int64)
    check(r.returncode == 0 and s and s["lost"] == 0 and "poll_ms=0.25 " in r.stdout and
          len(c) == s["recorded"] > 3000 and bool(np.all(np.diff(cseq) == 1)),
          "AD38 every 0.25 ms: %r %r" % (r.stdout, r.stderr))
    r, s = record(fast, *ad38, "--seconds", "0.05")
    check(r.returncode == 1 and s and s["lost"] > s["recorded"], "AD38 every 1 ms: %r" % (s,))
    # refusals
    r = subprocess.run([CTL, *BASE, "record"], capture_output=True, text=True)
    check(r.returncode == 2 and "record needs one FILE" in r.stderr, "no file: %r" % r.stderr)
    r = subprocess.run([CTL, *BASE, "record", "--format", "hdf5", npy], capture_output=True,
                       text=True)
    check(r.returncode == 2 and "--format 'hdf5'" in r.stderr, "bad format: %r" % r.stderr)
    for bad_poll in ("0", "0.001", "60001", "1ms"):
        r = subprocess.run([CTL, *BASE, "record", "--poll-ms", bad_poll, npy],
                           capture_output=True, text=True)
        check(r.returncode == 2 and "--poll-ms '%s'" % bad_poll in r.stderr,
              "bad poll %s: %r" % (bad_poll, r.stderr))
    bad = os.path.join(tmp, "no-such-dir", "x.csv")
    r = subprocess.run([CTL, *BASE, "record", "--seconds", "0.01", bad], capture_output=True,
                       text=True)
    check(r.returncode == 1 and bad in r.stderr and "No such file or directory" in r.stderr,
          "unwritable file: %r" % r.stderr)
    r = subprocess.run([CTL, "record", "--help"], capture_output=True, text=True)
    check(r.returncode == 0 and "--poll-ms" in r.stdout and "exit status 1" in r.stdout,
          "record --help: %r" % r.stdout)
finish("bissctl record")
