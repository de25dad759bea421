#!/usr/bin/env python3
"""The board flow of docs/hardware.md on a stand-in board: a sysfs tree
with PRU0's remoteproc instance and the pruss driver, /lib/firmware with
biss_master.elf installed by its own name, and a file standing in
for /dev/mem. A "kernel" thread plays pru_rproc and the firmware's
start-up: on "start" it loads the ELF's data segment (read with
pyelftools from the real biss_master.elf) into data RAM and sets the
magic; it acknowledges configurations; on "stop" the instance goes
offline. Run with the PC's bissctl and, when given, the ARM build under
qemu-arm (scripts/cross-bissctl.sh, staged in <build>/arm-root).

usage: board_flow.py BISSCTL BISS_MASTER_ELF BISS_MASTER_BIN [ARM_BISSCTL]
"""
import os
import shutil
import struct
import subprocess
import sys
import tempfile
import threading
import time

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "common"))
from checks import check, finish, use_debian_pyelftools  # noqa: E402

use_debian_pyelftools()
from elftools.elf.elffile import ELFFile  # noqa: E402



ctl, elf_path, bin_path = sys.argv[1:4]
arm = sys.argv[4] if len(sys.argv) > 4 else None
BASE = 0x4A300000
MAGIC, CFG_SEQ, ST_CFG_ACK, ST_CFG_ERROR, ST_STATE = 0x80, 0x00, 0x8C, 0x90, 0x94

with open(elf_path, "rb") as f:
    e = ELFFile(f)
    data_segs = [(s["p_paddr"], s.data()) for s in e.iter_segments()
                 if s["p_type"] == "PT_LOAD" and not s["p_flags"] & 1]


class Board:
    def __init__(self, root):
        self.root = root
        self.rp = os.path.join(root, "sys/class/remoteproc/remoteproc1")
        os.makedirs(self.rp)
        os.makedirs(os.path.join(root, "sys/bus/platform/drivers/pruss/4a300000.pruss"))
        self.put("name", "4a334000.pru\n")
        self.put("state", "offline\n")
        self.put("firmware", "am335x-pru0-fw\n")
        fw = os.path.join(root, "lib/firmware")
        os.makedirs(fw)
        shutil.copy(elf_path, os.path.join(fw, "biss_master.elf"))
        self.mem = os.path.join(root, "mem")
        with open(self.mem, "wb") as m:
            m.truncate(BASE + 0x80000)
        self.states = []
        self.stop_flag = False
        self.thread = threading.Thread(target=self.kernel)
        self.thread.start()

    def put(self, attr, text):
        tmp = os.path.join(self.rp, attr + ".k")
        with open(tmp, "w") as f:
            f.write(text)
        os.replace(tmp, os.path.join(self.rp, attr))

    def get(self, attr):
        with open(os.path.join(self.rp, attr)) as f:
            return f.read()

    def w32(self, off, v):
        with open(self.mem, "r+b") as f:
            f.seek(BASE + off)
            f.write(struct.pack("<I", v))

    def r32(self, off):
        with open(self.mem, "rb") as f:
            f.seek(BASE + off)
            return struct.unpack("<I", f.read(4))[0]

    def kernel(self):
        running = False
        while not self.stop_flag:
            state = self.get("state").strip()
            if state == "start":
                self.states.append("start:" + self.get("firmware").strip())
                with open(self.mem, "r+b") as f:   # pru_rproc: the data segments
                    for addr, blob in data_segs:
                        f.seek(BASE + addr)
                        f.write(blob)
                self.w32(ST_CFG_ACK, 0xFFFFFFFF)
                self.w32(MAGIC, 0x42695353)        # the firmware's start-up
                self.put("state", "running\n")
                running = True
            elif state == "stop":
                self.states.append("stop")
                self.w32(MAGIC, 0)
                self.put("state", "offline\n")
                running = False
            if running:                            # the firmware acks configurations
                seq = self.r32(CFG_SEQ)
                if seq and seq != self.r32(ST_CFG_ACK):
                    self.w32(ST_CFG_ERROR, 0)
                    self.w32(ST_STATE, 1)
                    self.w32(ST_CFG_ACK, seq)
            time.sleep(0.0005)

    def close(self):
        self.stop_flag = True
        self.thread.join()


def settle(b, state):
    """The stand-in kernel answers within a poll or two."""
    for _ in range(2000):
        if b.get("state") == state:
            return
        time.sleep(0.001)


def flow(cmd, label):
    with tempfile.TemporaryDirectory() as root:
        b = Board(root)
        env = dict(os.environ, BISS_LOCK_DIR=root)
        tree = ["--target", "am335x", "--sysfs", os.path.join(root, "sys"), "--devmem", b.mem,
                "--firmware-dir", os.path.join(root, "lib/firmware"), "--firmware", bin_path,
                "--timeout-ms", "2000"]
        try:
            # load through remoteproc, configure, run; the handle stops what it started
            r = subprocess.run([*cmd, *tree, "--slave", "14,6,0x43,0,0", "--freq", "10000000",
                                "run", "--ms", "20"], capture_output=True, text=True, timeout=120)
            check(r.returncode == 0 and "frames=" in r.stdout,
                  "%s run: %d %r %r" % (label, r.returncode, r.stdout, r.stderr))
            settle(b, "offline\n")
            # by the ELF's own name: the kernel's (am335x-pru0-fw) may be another's
            check(b.states == ["start:biss_master.elf", "stop"], "%s states %r" % (label, b.states))
            check(b.r32(0x04) & 0xffff == 10, "%s: CFG_HALF %d" % (label, b.r32(0x04) & 0xffff))
            # started by someone else: stats attaches and leaves it running
            b.put("state", "start")
            settle(b, "running\n")
            r = subprocess.run([*cmd, *tree, "stats"], capture_output=True, text=True, timeout=120)
            check(r.returncode == 0 and r.stdout.startswith("frames="),
                  "%s stats: %r %r" % (label, r.stdout, r.stderr))
            r = subprocess.run([*cmd, *tree, "info"], capture_output=True, text=True, timeout=120)
            check(r.returncode == 0 and "(attached)" in r.stdout and "shm_version=1" in r.stdout
                  and "pru=enabled" in r.stdout, "%s info: %r %r" % (label, r.stdout, r.stderr))
            check(b.get("state") == "running\n", "%s: still running" % label)
            # stop halts it through sysfs
            r = subprocess.run([*cmd, *tree, "stop"], capture_output=True, text=True, timeout=120)
            settle(b, "offline\n")
            check(r.returncode == 0 and b.get("state") == "offline\n",
                  "%s stop: %r %r" % (label, r.stderr, b.get("state")))
            # another image than the installed ELF's: a specific error
            other = os.path.join(root, "other.bin")
            with open(other, "wb") as f:
                f.write(b"\0\0\0\0")
            b.put("state", "start")
            settle(b, "running\n")
            r = subprocess.run([*cmd, *tree, "--firmware", other, "stats"], capture_output=True,
                               text=True, timeout=120)
            check(r.returncode == 1 and "CRC-32" in r.stderr, "%s other image: %r" % (label,
                                                                                r.stderr))
        finally:
            b.close()


flow([ctl], "pc")
if arm:
    qemu = shutil.which("qemu-arm")
    check(qemu is not None, "qemu-arm on PATH (Debian: qemu-user)")
    if qemu:
        flow([qemu, arm], "arm")
finish("board flow")
