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

The sysfs tree has what a board's has: the instance under its PRU's
platform device with a "device" link to it, /sys/class/remoteproc/remoteprocN
linking there, its "name" attribute on 5.10 and newer only (Linux 5.4's
sysfs-class-remoteproc ABI), the pruss driver's link to the bound PRU-ICSS,
and the device tree's root compatible and chosen/overlays entry under
firmware/devicetree/base. While configured, the stand-in firmware publishes
a frame a millisecond the way biss_shm.h's protocol has it (fill the slot
after ST_BUF's in the ring, name it, bump ST_SEQ), so "bissctl read" has frames.

Then the master that keeps running: "bissctl start" leaves it running after
it exits, "read" and "info" attach to it without restarting or
reconfiguring it, "stop" stops it (and a second stop is no error); the same
through the systemd unit's ExecStart and ExecStop lines as parsed from the
configured unit file (the installed paths replaced by the build's bissctl
and the test's configuration directory), with the default configuration
file, on a 4.19-like tree whose instance has no name. systemd-analyze
verifies the unit. And the default target: a TI compatible picks the
hardware (AM335x; AM437x: ICSS0), none says "emulated".

usage: board_flow.py BISSCTL BISS_MASTER_ELF BISS_MASTER_BIN UNIT CONFIG [ARM_BISSCTL]
"""
import os
import re
import shlex
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

# the contract's version, as biss_shm.h has it
with open(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "include", "biss",
                       "biss_shm.h"), encoding="utf-8") as _f:
    SHM_VERSION = int(re.search(r"^#define BISS_SHM_VERSION\s+(\d+)", _f.read(), re.M).group(1))



ctl, elf_path, bin_path, unit_path, conf_path = sys.argv[1:6]
arm = sys.argv[6] if len(sys.argv) > 6 else None
BASE = 0x4A300000
MAGIC, CFG_SEQ, ST_CFG_ACK, ST_CFG_ERROR, ST_STATE = 0x80, 0x00, 0x8C, 0x90, 0x94
# include/biss/biss_shm.h: configuration, status and result offsets
CFG_HALF, CFG_NSLAVES = 0x04, 0x06
ST_SEQ, ST_BUF, ST_FRAMES = 0x84, 0x88, 0x98
RING0, RING_END, R_SLAVE_SIZE = 0x480, 0xFE0, 16
R_FRAME, R_FLAGS, R_TIMESTAMP, R_NSLAVES = 0x00, 0x04, 0x08, 0x0F
R_DELAY_RAW, R_DELAY_AVG, R_SAMPLE_POINT, R_HALF, R_SLAVE0 = 0x10, 0x12, 0x14, 0x16, 0x20
RF_VALID, RF_SMA = 0x01, 0x20
RS_CRC_OK, RS_NE, RS_NW = 0x01, 0x02, 0x04
# the device tree's root compatible of a BeagleBone Black (BeagleBoard-
# DeviceTrees v5.10.x-ti src/arm/am335x-boneblack.dts) and of the AM437x IDK
# (mainline arch/arm/boot/dts/ti/omap/am437x-idk-evm.dts)
BBB_COMPATIBLE = b"ti,am335x-bone-black\0ti,am335x-bone\0ti,am33xx\0"
IDK_COMPATIBLE = b"ti,am437x-idk-evm\0ti,am4372\0ti,am43\0"
# where the PRU-ICSS's devices are (platform device names from
# of_device_make_bus_id: "<address>.<node name>"): 5.10-ti's
# target-module@300000 / pruss@0 / pru@34000, 4.19-ti's
# pruss-soc-bus@4a326004 / pruss@4a300000 / pru@4a334000
PRUSS_510 = ("platform/ocp/4a000000.interconnect/4a000000.interconnect:segment@0/"
             "4a326000.target-module/4a300000.pruss")
PRUSS_419 = "platform/ocp/4a326004.pruss-soc-bus/4a300000.pruss"

with open(elf_path, "rb") as f:
    e = ELFFile(f)
    data_segs = [(s["p_paddr"], s.data()) for s in e.iter_segments()
                 if s["p_type"] == "PT_LOAD" and not s["p_flags"] & 1]


class Board:
    def __init__(self, root, named=True):
        """named: the instance has a "name" attribute (5.10 and newer),
        else not (4.19)."""
        self.root = root
        sys_dir = os.path.join(root, "sys")
        pruss = os.path.join(sys_dir, "devices", PRUSS_510 if named else PRUSS_419)
        self.rp = os.path.join(pruss, "4a334000.pru/remoteproc/remoteproc1")
        os.makedirs(self.rp)
        os.symlink("../../../4a334000.pru", os.path.join(self.rp, "device"))
        os.makedirs(os.path.join(sys_dir, "class/remoteproc"))
        os.symlink(os.path.relpath(self.rp, os.path.join(sys_dir, "class/remoteproc")),
                   os.path.join(sys_dir, "class/remoteproc/remoteproc1"))
        drv = os.path.join(sys_dir, "bus/platform/drivers/pruss")
        os.makedirs(drv)
        os.symlink(os.path.relpath(pruss, drv), os.path.join(drv, "4a300000.pruss"))
        dt = os.path.join(sys_dir, "firmware/devicetree/base")
        os.makedirs(os.path.join(dt, "chosen/overlays"))
        with open(os.path.join(dt, "compatible"), "wb") as f:
            f.write(BBB_COMPATIBLE)
        with open(os.path.join(dt, "chosen/overlays/BB-BISS-PRU0-00A0"), "w") as f:
            f.write("BiSS-C master, PRU0: MA P9_29, SL P9_31\0")
        if named:
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
        self.frames = 0
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

    def publish(self):
        """One frame of TIDEP0022's test encoder (14 data bits: a 12-bit
        position counting up, nE and nW high, CRC good) into the ring's
        slot after the newest (its stride: the header and the slaves;
        back to the first where a slot no longer fits), numbered as its
        publication, then ST_BUF, then ST_SEQ (biss_shm.h)."""
        self.frames += 1
        nslaves = self.r32(CFG_NSLAVES) & 0xFF
        stride = R_SLAVE0 + nslaves * R_SLAVE_SIZE
        seq = self.r32(ST_SEQ) + 1
        at = RING0 + (seq - 1) % ((RING_END - RING0) // stride) * stride
        half = self.r32(CFG_HALF) & 0xFFFF
        data = ((self.frames & 0xFFF) << 2) | 0x3
        rec = bytearray(stride)
        struct.pack_into("<III", rec, R_FRAME, seq, RF_VALID | RF_SMA, self.frames * 200000)
        rec[R_NSLAVES] = nslaves
        struct.pack_into("<HHBxH", rec, R_DELAY_RAW, 30, 30, 4, half)
        struct.pack_into("<IIII", rec, R_SLAVE0, data, 0, 0, RS_CRC_OK | RS_NE | RS_NW)
        with open(self.mem, "r+b") as f:
            f.seek(BASE + at)
            f.write(rec)
        self.w32(ST_FRAMES, seq)
        self.w32(ST_BUF, at)
        self.w32(ST_SEQ, seq)

    def kernel(self):
        running = False
        last = 0.0
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
                if seq and seq == self.r32(ST_CFG_ACK) and time.monotonic() - last > 0.001:
                    self.publish()
                    last = time.monotonic()
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
            check(r.returncode == 0 and "(attached)" in r.stdout and ("shm_version=%d" % SHM_VERSION) in r.stdout
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


def bissctl(cmd, args, env):
    return subprocess.run([*cmd, *args], capture_output=True, text=True, timeout=120, env=env)


def attached_reads(b, cmd, label, where, env):
    """read and info with no --target (the stand-in's TI compatible picks
    the AM335x) and no configuration: they attach to the running master,
    neither restarting nor reconfiguring it."""
    states, cfg_seq = list(b.states), b.r32(CFG_SEQ)
    r = bissctl(cmd, [*where, "read", "-n", "3"], env)
    lines = r.stdout.splitlines()
    # three frames, then the link's counts over the frames read (proto/biss_link.c)
    check(r.returncode == 0 and len(lines) == 4 and all(" valid s0.pos=" in l for l in lines[:3])
          and lines[3].startswith("link: ") and " marginal=0 off_grid=0 " in lines[3],
          "%s attached read: %r %r" % (label, r.stdout, r.stderr))
    check("emulated" not in r.stdout, "%s: the hardware read says emulated" % label)
    r = bissctl(cmd, [*where, "info"], env)
    check(r.returncode == 0 and r.stdout.startswith("target=am335x ") and "(attached)" in r.stdout
          and "freq_hz=1000000 slaves=1" in r.stdout,
          "%s attached info: %r %r" % (label, r.stdout, r.stderr))
    check(b.states == states and b.r32(CFG_SEQ) == cfg_seq and b.get("state") == "running\n",
          "%s: the readers restarted or reconfigured it: %r CFG_SEQ %d" % (
              label, b.states, b.r32(CFG_SEQ)))


def keep_running_flow(cmd, label):
    """bissctl start leaves the master running after it exits; read attaches;
    stop stops it; a second stop is no error."""
    with tempfile.TemporaryDirectory() as root:
        b = Board(root)
        env = dict(os.environ, BISS_LOCK_DIR=root)
        where = ["--sysfs", os.path.join(root, "sys"), "--devmem", b.mem,
                 "--firmware-dir", os.path.join(root, "lib/firmware"), "--firmware", bin_path,
                 "--timeout-ms", "2000"]
        try:
            r = bissctl(cmd, [*where, "--slave", "14,6,0x43,0,0", "--freq", "1000000", "start"],
                        env)
            check(r.returncode == 0 and r.stdout.startswith("started: target=am335x pru=0 ")
                  and "keeps running" in r.stdout,
                  "%s start: %d %r %r" % (label, r.returncode, r.stdout, r.stderr))
            time.sleep(0.05)  # long enough for a stop the exit might have sent
            check(b.states == ["start:biss_master.elf"] and b.get("state") == "running\n",
                  "%s: running after start exited: %r %r" % (label, b.states, b.get("state")))
            check(b.r32(CFG_HALF) & 0xFFFF == 100, "%s: CFG_HALF %d" % (label, b.r32(CFG_HALF)))
            attached_reads(b, cmd, label, where, env)
            r = bissctl(cmd, [*where, "stop"], env)
            settle(b, "offline\n")
            check(r.returncode == 0 and r.stdout == "stopped: target=am335x pru=0\n"
                  and b.states == ["start:biss_master.elf", "stop"],
                  "%s stop: %r %r %r" % (label, r.stdout, r.stderr, b.states))
            r = bissctl(cmd, [*where, "stop"], env)
            check(r.returncode == 0 and r.stdout.startswith("stopped: nothing was running")
                  and b.states == ["start:biss_master.elf", "stop"],
                  "%s second stop: %d %r %r" % (label, r.returncode, r.stdout, r.stderr))
        finally:
            b.close()


def unit_lines(path):
    """ExecStart and ExecStop of the unit file, as word lists (systemd's
    quoting is the shell's for these lines), for instance pru0."""
    lines = {}
    with open(path) as f:
        for line in f:
            key, _, value = line.strip().partition("=")
            if key in ("ExecStart", "ExecStop", "Type", "RemainAfterExit"):
                lines[key] = value.replace("%i", "pru0")
    return lines


def service_flow(cmd, label):
    """The unit's ExecStart and ExecStop, with the default configuration,
    on a 4.19-like tree (no "name" attribute): started at "boot", readable,
    stopped by systemctl stop."""
    unit = unit_lines(unit_path)
    check(unit.get("Type") == "oneshot" and unit.get("RemainAfterExit") == "yes",
          "unit: Type=oneshot, RemainAfterExit=yes: %r" % unit)
    start, stop = shlex.split(unit["ExecStart"]), shlex.split(unit["ExecStop"])
    conf_at = start.index("--config") + 1
    installed_dir = os.path.dirname(start[conf_at])
    with tempfile.TemporaryDirectory() as root:
        b = Board(root, named=False)
        env = dict(os.environ, BISS_LOCK_DIR=root)
        etc = os.path.join(root, "etc/biss")
        os.makedirs(etc)
        # the default configuration as installed, and where the stand-in
        # board is (a real board needs none of these lines)
        with open(conf_path) as f:
            conf = f.read()
        with open(os.path.join(etc, "pru0.conf"), "w") as f:
            f.write(conf + "\n# the stand-in board\nsysfs = %s\ndevmem = %s\n"
                    "firmware-dir = %s\nfirmware = %s\ntimeout-ms = 2000\n" % (
                        os.path.join(root, "sys"), b.mem, os.path.join(root, "lib/firmware"),
                        bin_path))

        def run_unit(words):
            # the unit's own words: its bissctl is the build's, its
            # configuration directory the test's
            args = [w.replace(installed_dir, etc) for w in words[1:]]
            check(os.path.basename(words[0]) == "bissctl", "%s: unit runs %s" % (label, words[0]))
            return bissctl(cmd, args, env)

        where = ["--sysfs", os.path.join(root, "sys"), "--devmem", b.mem,
                 "--firmware", bin_path]
        try:
            r = run_unit(start)
            check(r.returncode == 0 and r.stdout.startswith("started: target=am335x pru=0 ")
                  and "freq_hz=1000000 slaves=1 trigger=free" in r.stdout,
                  "%s ExecStart: %d %r %r" % (label, r.returncode, r.stdout, r.stderr))
            time.sleep(0.05)
            check(b.states == ["start:biss_master.elf"] and b.get("state") == "running\n",
                  "%s: running after ExecStart: %r" % (label, b.states))
            attached_reads(b, cmd, label + " (unit)", where, env)
            r = run_unit(stop)
            settle(b, "offline\n")
            check(r.returncode == 0 and b.states == ["start:biss_master.elf", "stop"],
                  "%s ExecStop: %r %r %r" % (label, r.stdout, r.stderr, b.states))
            r = run_unit(stop)
            check(r.returncode == 0, "%s ExecStop again: %r" % (label, r.stderr))
            # a bad line in the configuration: ExecStart fails naming it
            with open(os.path.join(etc, "pru0.conf"), "a") as f:
                f.write("freq = fast\n")
            with open(os.path.join(etc, "pru0.conf")) as f:
                n = len(f.read().splitlines())  # the bad line is the last
            r = run_unit(start)
            check(r.returncode == 2 and ("pru0.conf:%d: --freq 'fast'" % n) in r.stderr
                  and b.states == ["start:biss_master.elf", "stop"],
                  "%s bad configuration: %d %r" % (label, r.returncode, r.stderr))
        finally:
            b.close()


def default_target(cmd, label):
    """No --target: a TI compatible picks the hardware, none the emulator
    (and then it says "emulated")."""
    with tempfile.TemporaryDirectory() as root:
        dt = os.path.join(root, "sys/firmware/devicetree/base")
        os.makedirs(dt)
        with open(os.path.join(dt, "compatible"), "wb") as f:
            f.write(IDK_COMPATIBLE)
        drv = os.path.join(root, "sys/bus/platform/drivers/pruss/54440000.pruss")
        os.makedirs(drv)
        os.makedirs(os.path.join(root, "sys/class/remoteproc"))
        mem = os.path.join(root, "mem")
        with open(mem, "wb") as f:
            f.truncate(0x54440000 + 0x40000)
        env = dict(os.environ, BISS_LOCK_DIR=root)
        r = bissctl(cmd, ["--sysfs", os.path.join(root, "sys"), "--devmem", mem, "stats"], env)
        # AM437x: ICSS0's PRU0 (IRAM 0x54474000) looked for, on the hardware
        check(r.returncode == 1 and "no remoteproc instance of 54474000.pru" in r.stderr
              and "emulated" not in r.stdout,
              "%s AM437x default: %d %r %r" % (label, r.returncode, r.stdout, r.stderr))
        os.remove(os.path.join(dt, "compatible"))
        r = bissctl(cmd, ["--sysfs", os.path.join(root, "sys"), "--freq", "10000000", "read"],
                    env)
        check(r.returncode == 0 and r.stdout.startswith("emulated: target emu, no board"),
              "%s no compatible: %r %r" % (label, r.stdout, r.stderr))
        with open(os.path.join(dt, "compatible"), "wb") as f:
            f.write(b"raspberrypi,4-model-b\0brcm,bcm2711\0")
        r = bissctl(cmd, ["--sysfs", os.path.join(root, "sys"), "--freq", "10000000", "read",
                          "--json"], env)
        check(r.returncode == 0 and r.stdout.startswith(
            '{\n  "target": "emu",\n  "emulated": true,'),
            "%s another SoC: %r %r" % (label, r.stdout[:80], r.stderr))


def verify_unit():
    """systemd-analyze verify (Debian: systemd): the configured unit with
    the build's bissctl in place of the installed one (verify checks that
    the command exists)."""
    tool = shutil.which("systemd-analyze")
    if not check(tool is not None, "systemd-analyze on PATH (Debian: systemd)"):
        return
    with tempfile.TemporaryDirectory() as d:
        unit = unit_lines(unit_path)
        installed = shlex.split(unit["ExecStart"])[0]
        with open(unit_path) as f:
            text = f.read().replace(installed, os.path.abspath(ctl))
        with open(os.path.join(d, "biss-master@.service"), "w") as f:
            f.write(text)
        r = subprocess.run([tool, "verify", "--man=no", os.path.join(d, "biss-master@pru0.service")],
                           capture_output=True, text=True, timeout=120)
        check(r.returncode == 0 and r.stdout == "" and r.stderr == "",
              "systemd-analyze verify: %d %r %r" % (r.returncode, r.stdout, r.stderr))


verify_unit()
runners = [([ctl], "pc")]
if arm:
    qemu = shutil.which("qemu-arm")
    check(qemu is not None, "qemu-arm on PATH (Debian: qemu-user)")
    if qemu:
        runners.append(([qemu, arm], "arm"))
for runner, label in runners:
    flow(runner, label)
    keep_running_flow(runner, label)
    service_flow(runner, label)
    default_target(runner, label)
finish("board flow")
