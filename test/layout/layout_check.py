#!/usr/bin/env python3
"""The shared-memory layout is written in one place.

include/biss/biss_shm.h gives every data-RAM offset; the firmware
assembles from it, and on the host side only proto/ (the protocol layer)
turns offsets into transfers. This test shows both halves:

1. No C source outside proto/, include/biss/ and pru_fw/ names a data-RAM
   offset of the header, except the files listed in ALLOWED (each with its
   reason: test stand-ins that play the firmware's side, the bench's store
   watch). A stale entry (nothing left to allow) fails too.
2. A layout change is one change to the header: proto and a driver that
   plays the firmware from the header's macros (layout_roundtrip.c) are
   built with the project's header and with one whose status block has
   moved 0x20 bytes down; both builds must agree with themselves, and the
   move must have taken.

usage: layout_check.py --source DIR --cc CC
"""
import argparse
import os
import re
import subprocess
import sys
import tempfile

# file (relative to the source) -> (offset names it may use or "*", why)
ALLOWED = {
    "test/host/fake_backend.c": ("*", "a fake firmware for libbiss's unit tests"),
    "test/host/test_host_cd.c": ("*", "checks the words libbiss wrote, as the firmware reads them"),
    "test/proto/test_proto_encode.c": ("*", "checks proto's encoding byte by byte against the header"),
    "test/host/test_host_linux.c": ("*", "a stand-in /dev/mem file with a fake firmware thread"),
    "test/host/test_host_rproc.c": ("*", "a stand-in remoteproc firmware writes its words"),
    "test/host/test_host_seqlock.c": ("*", "checks the words libbiss wrote, as the firmware reads them"),
    "test/proto/cd_sim.c": ("*", "a model of the firmware's control-communication engine"),
    "test/proto/test_proto_cd_build.c": ("*", "checks the codec's data RAM image against the header"),
    "test/proto/test_proto_cd_sim.c": ("*", "drives the engine model's image as the firmware would see it"),
    "test/layout/layout_roundtrip.c": ("*", "plays the firmware's side from the header's macros"),
    "test/host/test_host_ring.c": ({"BISS_ST_BUF"},
                                   "the store watch on the newest slot's pointer: the encoder "
                                   "model's side of each frame, as fw_check.c's on ST_SEQ"),
    "test/host/test_host_wrap.c": ({"BISS_ST_MAGIC", "BISS_ST_SEQ", "BISS_ST_FRAMES",
                                    "BISS_CD_CMD", "BISS_ST_CD_SEQ"},
                                   "sets the firmware's counters near their limits, as "
                                   "days of running would leave them"),
    "emulator/bench/fw_check.c": ({"BISS_ST_SEQ"},
                                  "the store watch on the publication counter: what the "
                                  "bench watches, not a transfer"),
    "host/lib/biss_open.c": ({"BISS_ID"}, "names the block's address in an error message"),
    "host/bench/biss_read_cost.c": ("*", "a stand-in of the firmware's PUBLISH between the "
                                    "timed ring reads (pru_fw/results.p)"),
}
# (test/golden/pasm/fw: a frozen copy of pru_fw/ and the header, for pasm's record)
EXEMPT_DIRS = ("proto/", "include/biss/", "pru_fw/", "test/golden/pasm/fw/", "build")
SCANNED_DIRS = ("host", "common", "emulator", "test", "examples", "boards")

# status block, moved for the second build
STATUS = ("PRU", "MAGIC", "SEQ", "BUF", "CFG_ACK", "CFG_ERROR", "STATE", "FRAMES", "CRC_ERRORS",
          "NO_SLAVE", "PROC_ERRORS", "TRAINING", "END")
MOVE = 0x20


def layout_names(header):
    """Offset macros of the header: configuration, commands, status,
    control communication, results, identification, private area."""
    names = set()
    for m in re.finditer(r"^#define\s+(BISS_\w+)\s+(0x[0-9A-Fa-f]+|\d+)", header, re.M):
        n = m.group(1)
        if re.match(r"BISS_(CFG_|ST_|CD_|R_|RING0$|RING_END$|CMD_|ID$|ID_END$|RSC_TABLE$|"
                    r"PRIV$|PRIV_END$)", n) and n not in ("BISS_CD_MAX_STEPS",):
            names.add(n)
    return names


def code_only(text):
    """C text without comments and string literals."""
    text = re.sub(r"/\*.*?\*/", " ", text, flags=re.S)
    text = re.sub(r"//[^\n]*", " ", text)
    return re.sub(r'"(\\.|[^"\\\n])*"', '""', text)


def check_users(src, names):
    bad, used_allow = [], set()
    pattern = re.compile(r"\b(" + "|".join(sorted(names, key=len, reverse=True)) + r")\b")
    for top in SCANNED_DIRS:
        for root, _, files in os.walk(os.path.join(src, top)):
            for f in files:
                if not f.endswith((".c", ".h")):
                    continue
                path = os.path.join(root, f)
                rel = os.path.relpath(path, src)
                if rel.startswith(EXEMPT_DIRS):
                    continue
                with open(path, encoding="utf-8") as fh:
                    code = code_only(fh.read())
                for m in pattern.finditer(code):
                    line = code.count("\n", 0, m.start()) + 1
                    allow = ALLOWED.get(rel)
                    if allow and (allow[0] == "*" or m.group(1) in allow[0]):
                        used_allow.add(rel)
                        continue
                    bad.append("%s:%d: %s" % (rel, line, m.group(1)))
    stale = sorted(set(ALLOWED) - used_allow)
    return bad, stale


def moved_header(header):
    out = header
    for s in STATUS:
        name = "BISS_ST_" + s
        m = re.search(r"^#define\s+%s\s+(0x[0-9A-Fa-f]+)" % name, out, re.M)
        if not m:
            sys.exit("layout_check: %s not in the header" % name)
        new = "0x%03X" % (int(m.group(1), 16) - MOVE)
        out = out[:m.start(1)] + new + out[m.end(1):]
    return out


def build_and_run(src, cc, include_dir, out):
    proto = os.path.join(src, "proto")
    sources = sorted(os.path.join(proto, f) for f in os.listdir(proto) if f.endswith(".c"))
    cmd = cc.split() + ["-std=c11", "-Wall", "-Wextra", "-Werror", "-D_POSIX_C_SOURCE=200809L",
                        "-I", include_dir, "-I", proto, "-I", os.path.join(src, "include"),
                        "-I", os.path.join(src, "host", "include"),
                        "-I", os.path.join(src, "emulator", "isa"),
                        os.path.join(src, "test", "layout", "layout_roundtrip.c")] + sources + [
                        os.path.join(src, "emulator", "isa", "pru_isa.c"),  # biss_image_pru.c
                        "-o", out]
    r = subprocess.run(cmd, capture_output=True, text=True)
    if r.returncode:
        return None, "build failed: %s\n%s" % (" ".join(cmd), r.stderr)
    r = subprocess.run([out], capture_output=True, text=True)
    return r.returncode, r.stdout + r.stderr


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--source", required=True)
    ap.add_argument("--cc", default="cc")
    a = ap.parse_args()
    with open(os.path.join(a.source, "include", "biss", "biss_shm.h"), encoding="utf-8") as f:
        header = f.read()
    names = layout_names(header)
    failed = False
    if len(names) < 50 or "BISS_R_S_DATA_LO" not in names or "BISS_CFG_SEQ" not in names:
        print("FAIL: only %d offset names read from the header" % len(names))
        failed = True
    bad, stale = check_users(a.source, names)
    for b in bad:
        print("FAIL: offset outside proto/: " + b)
    for s in stale:
        print("FAIL: ALLOWED names %s, which uses no offset any more" % s)
    failed |= bool(bad or stale)
    print("%d offset names; users outside proto/: %d allowed files, %d others" %
          (len(names), len(ALLOWED) - len(stale), len(bad)))

    with tempfile.TemporaryDirectory() as tmp:
        runs = {}
        for label, text in (("project", header), ("moved", moved_header(header))):
            inc = os.path.join(tmp, label)
            os.makedirs(os.path.join(inc, "biss"))
            with open(os.path.join(inc, "biss", "biss_shm.h"), "w", encoding="utf-8") as f:
                f.write(text)
            # the struct view comes along unchanged: it is derived from the macros
            with open(os.path.join(a.source, "include", "biss", "biss_shm_struct.h"),
                      encoding="utf-8") as f:
                struct_view = f.read()
            with open(os.path.join(inc, "biss", "biss_shm_struct.h"), "w", encoding="utf-8") as f:
                f.write(struct_view)
            rc, out = build_and_run(a.source, a.cc, inc, os.path.join(tmp, label + ".bin"))
            runs[label] = out
            print("--- %s header ---\n%s" % (label, out.strip()))
            if rc != 0 or not out.strip().endswith("ok"):
                print("FAIL: proto does not follow the %s header" % label)
                failed = True
        magic = {k: re.search(r"BISS_ST_MAGIC (0x[0-9a-f]+)", v) for k, v in runs.items()}
        if not all(magic.values()) or \
                int(magic["project"].group(1), 16) - int(magic["moved"].group(1), 16) != MOVE:
            print("FAIL: the moved header did not move the status block")
            failed = True
    print("FAIL" if failed else "PASS")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
