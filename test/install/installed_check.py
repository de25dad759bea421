#!/usr/bin/env python3
"""An installed tree as its users meet it: the files in their places (the
programs under the prefix, the firmware and overlays in the firmware
directory, /lib/firmware whatever the prefix), every tool's --version,
libbiss.so's soname and exports (no emulator symbols, no libcjson),
bissctl finding the firmware installed for it (emulator target) and
loading it through a file standing in for /dev/mem, attaching to it and
saying so when the installed image it would compare with is absent,
examples/read_positions.c built with `pkg-config --cflags --libs libbiss`
reading a position the test publishes in the stand-in's data RAM, and the
kernel-fw-names component linking the kernel's names without replacing
another firmware.

usage: installed_check.py --version V --source DIR --cc CC [--nm NM]
         --prefix PREFIX --firmware-dir DIR (--install-from BUILD_DIR | --root ROOT)
         [--run "qemu-arm -L /usr/arm-linux-gnueabihf"] [--tools "bissctl pruasm ..."]
         [--same-firmware BUILD_DIR]
PREFIX and DIR are the tree's configured (absolute) prefix and firmware
directory; the files lie under ROOT (a DESTDIR). --install-from installs
BUILD_DIR with DESTDIR set to a temporary directory first (removed after);
--root checks a tree already installed (the cross build's).
--same-firmware: the installed images must be byte-identical to BUILD_DIR's.
"""
import argparse
import os
import shlex
import shutil
import struct
import subprocess
import sys
import tempfile
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "common"))
from checks import check, finish  # noqa: E402
from memfile import rd, wr  # noqa: E402



ap = argparse.ArgumentParser()
ap.add_argument("--version", required=True)
ap.add_argument("--source", required=True)
ap.add_argument("--cc", required=True)
ap.add_argument("--nm", default="nm")
ap.add_argument("--install-from")
ap.add_argument("--root")
ap.add_argument("--prefix", required=True)
ap.add_argument("--firmware-dir", required=True)
ap.add_argument("--run", default="")
ap.add_argument("--tools", default="bissctl biss-sim pruasm pru-run pru-elf")
ap.add_argument("--same-firmware")
a = ap.parse_args()
runner = shlex.split(a.run)

BASE, CLKCTRL, IRAM = 0x4A300000, 0x44E000E8, 0x34000
CFG_SEQ, MAGIC, ST_SEQ, ST_BUF, ST_CFG_ACK, ST_CFG_ERROR, ST_STATE = (
    0x00, 0x80, 0x84, 0x88, 0x8C, 0x90, 0x94)
RING0, RF_VALID, RS_CRC_OK, R_SLAVE0 = 0x480, 0x01, 0x01, 0x20


def run(*args, **kw):
    return subprocess.run([*runner, *args], capture_output=True, text=True, timeout=120, **kw)


def under(root, path):
    return os.path.join(root, path.lstrip("/"))


def check_tree(root, tmp):
    prefix = under(root, a.prefix)
    fw = under(root, a.firmware_dir)
    pc = os.path.join(prefix, "lib", "pkgconfig", "libbiss.pc")
    if not os.path.exists(pc):  # a multiarch libdir (prefix /usr on Debian)
        found = [d for d, _, f in os.walk(prefix) if "libbiss.pc" in f]
        pc = os.path.join(found[0], "libbiss.pc") if found else pc
    if not check(os.path.exists(pc), "libbiss.pc installed"):
        return
    env = dict(os.environ, PKG_CONFIG_LIBDIR=os.path.dirname(pc), PKG_CONFIG_PATH="")
    libdir = subprocess.run(["pkg-config", "--variable=libdir", "libbiss"], env=env,
                            capture_output=True, text=True).stdout.strip()
    check(os.path.realpath(libdir) == os.path.realpath(os.path.dirname(os.path.dirname(pc))),
          "libdir %r beside the .pc" % libdir)
    for f in ["bin/" + t for t in a.tools.split()] + [
            "include/libbiss.h", "include/biss/biss_types.h", "include/biss/biss_rules.h",
            "share/doc/pru_biss/README.md",
            "share/doc/pru_biss/host/README.md"]:
        check(os.path.exists(os.path.join(prefix, f)), "installed: " + f)
    for f in ["biss_master.bin", "biss_master.elf", "biss_master_pru1.bin",
              "biss_master_pru1.elf", "biss_encoder.bin", "biss_encoder.elf",
              "biss_encoder_pru1.bin", "biss_encoder_pru1.elf", "BB-BISS-PRU0-00A0.dtbo",
              "BB-BISS-PRU01-00A0.dtbo"]:
        check(os.path.exists(os.path.join(fw, f)), "installed: %s/%s" % (a.firmware_dir, f))
    # the kernel's names are another firmware's unless asked for (kernel-fw-names)
    for f in ["am335x-pru0-fw", "am335x-pru1-fw", "am437x-pru0_0-fw", "am437x-pru0_1-fw"]:
        check(not os.path.lexists(os.path.join(fw, f)), "not installed by default: " + f)
    for f in ["libbiss.a", "libbiss.so"]:
        check(os.path.exists(os.path.join(libdir, f)), "installed: %s/%s" % (libdir, f))
    check(not os.path.exists(os.path.join(prefix, "include", "libbiss-emu.h")),
          "the emulator header is not installed")
    with open(os.path.join(prefix, "include", "libbiss.h")) as f:
        check("struct bench" not in f.read(), "libbiss.h names no bench type")

    # every tool: one project version
    for t in a.tools.split():
        r = run(os.path.join(prefix, "bin", t), "--version")
        check(r.returncode == 0 and r.stdout == "%s %s\n" % (t, a.version),
              "%s --version: %d %r %r" % (t, r.returncode, r.stdout, r.stderr))

    # the shared library: soname, needs, exports
    so = os.path.join(libdir, "libbiss.so")
    dyn = subprocess.run(["readelf", "-d", so], capture_output=True, text=True).stdout
    soname = "libbiss.so.%s" % a.version.split(".")[0]
    check("Library soname: [%s]" % soname in dyn, "SONAME %s in %r" % (soname, dyn))
    check(os.path.islink(so) and os.readlink(so) == soname, "libbiss.so -> " + soname)
    needed = [l.split("[")[1].rstrip("]") for l in dyn.splitlines() if "(NEEDED)" in l]
    check(needed and not [n for n in needed if "cjson" in n or "elf" in n or "check" in n],
          "libbiss.so needs only the C library: %r" % needed)
    syms = subprocess.run([a.nm, "-D", "--defined-only", so], capture_output=True,
                          text=True).stdout.split("\n")
    names = [l.split()[-1] for l in syms if len(l.split()) == 3 and l.split()[1] in "TDBRV"]
    check(len(names) > 40 and "biss_open" in names and "biss_read_sample" in names,
          "libbiss.so exports its API (%d symbols)" % len(names))
    emu = [n for n in names if not n.startswith("biss_") or n.startswith("biss_emu")
           or n in ("biss_config_from_emu",)]
    check(not emu, "libbiss.so exports nothing but its API, no emulator: %r" % emu[:10])
    for n in names:
        for bad in ("bench_", "pru_core", "pru_host", "scenario_", "cJSON", "link_model"):
            check(bad not in n, "emulator symbol %s exported" % n)

    # bissctl on the emulator target finds the firmware installed beside it
    ctl = os.path.join(prefix, "bin", "bissctl")
    r = run(ctl, "info")
    want = os.path.join(fw, "biss_master.bin")
    check(r.returncode == 0 and ("firmware=%s\n" % want) in r.stdout,
          "installed firmware found: %r %r" % (r.stdout, r.stderr))
    r = run(ctl, "read", "-n", "3")
    check(r.returncode == 0 and r.stdout.count("valid s0.pos=") >= 2,
          "emulator read: %r %r" % (r.stdout, r.stderr))

    # the devmem loader, on a file standing in for /dev/mem
    mem = os.path.join(tmp, "mem")
    with open(mem, "wb") as f:
        f.truncate(BASE + 0x80000)
    wr(mem, CLKCTRL, 2)  # powered, as the pruss driver leaves it
    env = dict(os.environ, BISS_LOCK_DIR=tmp)
    dm = ["--target", "am335x", "--loader", "devmem", "--devmem", mem]
    r = run(ctl, *dm, "--slave", "14,6,0x43,0,0", "--freq", "10000000", "--timeout-ms", "20",
            "info", env=env)
    check(r.returncode == 1 and "not running" in r.stderr, "devmem load: %r" % r.stderr)
    with open(want, "rb") as f:
        image = f.read()
    with open(mem, "rb") as f:
        f.seek(BASE + IRAM)
        check(f.read(len(image)) == image, "IRAM holds the installed image")
    check(rd(mem, BASE + 0x04, 2) == 10, "CFG_HALF 10 (10 MHz)")

    # the firmware's part, played here: running, configuration acked, one
    # frame published with slave 0's data word: 12-bit position, nE, nW
    seq, pos = rd(mem, BASE + CFG_SEQ), 0xA5C
    wr(mem, BASE + MAGIC, 0x42695353)
    wr(mem, BASE + ST_CFG_ACK, seq)
    wr(mem, BASE + ST_CFG_ERROR, 0)
    wr(mem, BASE + ST_STATE, 1)
    res = BASE + RING0                 # the ring's first slot
    wr(mem, res + 0x00, 1)             # frame: publication 1
    wr(mem, res + 0x04, RF_VALID)
    wr(mem, res + 0x0F, 1, 1)          # nslaves
    wr(mem, res + 0x16, 10, 2)         # half
    wr(mem, res + R_SLAVE0, pos << 2 | 3)  # data_lo: nE, nW = 1: no error, no warning
    wr(mem, res + R_SLAVE0 + 12, RS_CRC_OK)
    wr(mem, BASE + ST_BUF, RING0)
    wr(mem, BASE + ST_SEQ, 1)

    # the example, built against the installed tree with pkg-config
    flags = subprocess.run(["pkg-config", "--cflags", "--libs", "libbiss"], env=dict(
        os.environ, PKG_CONFIG_LIBDIR=os.path.dirname(pc), PKG_CONFIG_PATH=""),
        capture_output=True, text=True)
    check(flags.returncode == 0 and "-lbiss" in flags.stdout, "pkg-config: %r" % flags.stderr)
    exe = os.path.join(tmp, "read_positions")
    cc = subprocess.run([*shlex.split(a.cc), "-std=c11", "-Wall", "-Wextra", "-Werror",
                         os.path.join(a.source, "examples", "read_positions.c"), "-o", exe,
                         *shlex.split(flags.stdout), "-Wl,-rpath," + libdir],
                        capture_output=True, text=True)
    if check(cc.returncode == 0, "example build: %r" % cc.stderr):
        ldd = subprocess.run(["readelf", "-d", exe], capture_output=True, text=True).stdout
        check("[%s]" % soname in ldd, "the example links the shared libbiss")
        r = run(exe, mem, env=env)
        check(r.returncode == 0 and r.stdout == "slave 0: position %d\n" % pos,
              "example: %d %r %r" % (r.returncode, r.stdout, r.stderr))
        # a failing open: the library's words (biss_strerror) and its detail
        # (errbuf: the path, errno), as bissctl prints them
        missing = os.path.join(tmp, "no-such-mem")
        r = run(exe, missing, env=env)
        check(r.returncode == 1 and r.stdout == "" and r.stderr.startswith(
                  "read_positions: the PRU-ICSS memory cannot be opened or mapped: " + missing
                  + ": No such file or directory (errno 2)"),
              "example, missing memory file: %d %r" % (r.returncode, r.stderr))
        r = run(exe, mem, mem, env=env)
        check(r.returncode == 2 and "usage: read_positions [MEM]" in r.stderr,
              "example, two arguments: %d %r" % (r.returncode, r.stderr))

    # attaching, bissctl compares the running image (its identification
    # block, which the devmem load above wrote) with the installed one, and
    # says so when that is absent rather than skip the check in silence
    attach = [*dm, "--attach", "stats"]
    r = run(ctl, *attach, env=env)
    check(r.returncode == 0 and r.stdout.startswith("frames=") and "cannot check" not in r.stderr,
          "attached, image compared: %d %r %r" % (r.returncode, r.stdout, r.stderr))
    # absent beside the program, it is looked for in the configured firmware
    # directory itself (which a DESTDIR tree's program cannot know to be
    # outside its tree): absent there too on a machine without the package
    os.rename(want, want + ".away")
    r = run(ctl, *attach, env=env)
    os.rename(want + ".away", want)
    last = os.path.join(a.firmware_dir, "biss_master.bin")
    if os.path.exists(last):
        check(r.returncode == 0 and "cannot check" not in r.stderr or
              r.returncode == 1 and "CRC-32" in r.stderr and last in r.stderr,
              "attached, compared with %s: %d %r" % (last, r.returncode, r.stderr))
    else:
        check(r.returncode == 0 and "bissctl: cannot check the running image: %s: No such file "
              "or directory" % last in r.stderr,
              "attached, installed image absent: %d %r" % (r.returncode, r.stderr))


def kernel_names(build, tmp):
    """The kernel-fw-names component: the links, again (nothing changes),
    and never over another firmware's file."""
    root = os.path.join(tmp, "names")
    fw = under(root, a.firmware_dir)
    env = dict(os.environ, DESTDIR=root)
    cmd = ["cmake", "--install", build, "--component", "kernel-fw-names"]
    links = {"am335x-pru0-fw": "biss_master.elf", "am437x-pru0_0-fw": "biss_master.elf",
             "am335x-pru1-fw": "biss_master_pru1.elf", "am437x-pru0_1-fw": "biss_master_pru1.elf"}
    for attempt in ("first", "again"):
        os.makedirs(fw, exist_ok=True)
        r = subprocess.run(cmd, env=env, capture_output=True, text=True)
        check(r.returncode == 0, "kernel-fw-names %s: %r" % (attempt, r.stderr))
        for name, target in links.items():
            p = os.path.join(fw, name)
            check(os.path.islink(p) and os.readlink(p) == target,
                  "%s: %s -> %s" % (attempt, name, target))
    other = os.path.join(fw, "am335x-pru1-fw")
    os.remove(other)
    with open(other, "w") as f:
        f.write("another firmware\n")
    r = subprocess.run(cmd, env=env, capture_output=True, text=True)
    check(r.returncode != 0 and "another firmware has that name" in " ".join(r.stderr.split()),
          "kernel-fw-names over another firmware fails: %d %r" % (r.returncode, r.stderr))
    with open(other) as f:
        check(f.read() == "another firmware\n", "the other firmware is left as it was")


with tempfile.TemporaryDirectory() as tmp:
    root = a.root and os.path.abspath(a.root)
    if a.install_from:
        root = os.path.join(tmp, "root")
        r = subprocess.run(["cmake", "--install", a.install_from], capture_output=True, text=True,
                           env=dict(os.environ, DESTDIR=root))
        check(r.returncode == 0, "cmake --install: %r" % r.stderr)
    check_tree(root, tmp)
    if a.install_from:
        kernel_names(a.install_from, tmp)
    if a.same_firmware:
        for f in ["biss_master.bin", "biss_master.elf", "biss_master_pru1.bin",
                  "biss_master_pru1.elf"]:
            with open(os.path.join(under(root, a.firmware_dir), f), "rb") as x, \
                 open(os.path.join(a.same_firmware, "pru_fw", f), "rb") as y:
                check(x.read() == y.read(), "%s byte-identical to %s's" % (f, a.same_firmware))
finish("installed tree %s" % (a.root or "(temporary)"))
