#!/usr/bin/env python3
"""The board overlays compiled with dtc -@ and read back: every pad they
set, its offset and value, against the table below (written from TI's pad
tables, not from the overlays): the AM335x TRM's control-module pad
registers as Linux's dt-bindings/pinctrl/am33xx.h and am43xx.h encode
them, the BeagleBone Black / PocketBeagle header tables, and TIDEP0022's
Table 9 for the AM437x IDK. Also the nodes they enable and the labels they
need from the base device tree.

Then each overlay applied with fdtoverlay to stand-ins of the base trees
BeagleBoard's images boot (standins.py: 4.19-ti, 5.10-ti, 6.1-ti; the
BeagleBone Black with the universal cape on and off, the PocketBeagle; the
AM437x IDK's mainline and TI 4.19 trees), followed by the overlays U-Boot
applies after it (its HDMI overlay, 4.19's PRU remoteproc overlay): no pad
may be claimed by two enabled nodes (fdt.py walks every enabled node's
pinctrl-N groups), and the PRU-ICSS must be enabled with exactly the
overlay's pads. The two cases the guide warns about (HDMI audio or video
left on) must show exactly the pads they take.

usage: overlays_check.py BOARDS_DIR
"""
import os
import re
import shutil
import subprocess
import sys
import tempfile
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "common"))
from checks import check, finish  # noqa: E402
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import fdt  # noqa: E402
import standins  # noqa: E402



CONTROL = 0x44E10000   # control module; pinctrl-single's base is CONTROL + 0x800

# Pad value encodings. AM335x (am33xx.h): bits 2:0 mode, bit 3 pull disable,
# bit 4 pull up, bit 5 receiver (input) enable. AM437x (am43xx.h): bits 3:0
# mode, bit 16 pull disable, bit 17 pull up, bit 18 input enable.
ENC = {"am335x": dict(mode=0x7, pulldis=1 << 3, pullup=1 << 4, input=1 << 5),
       "am437x": dict(mode=0xF, pulldis=1 << 16, pullup=1 << 17, input=1 << 18)}

# board, overlay, soc, header pin, pad name, pad (control module offset),
# mode, signal, direction ("in" with pull-up, "out" without pull)
PINS = [
    ("BeagleBone Black", "BB-BISS-PRU0-00A0", "am335x", "P9_29", "mcasp0_fsx", 0x994, 5,
     "pr1_pru0_pru_r30_1 (MA)", "out"),
    ("BeagleBone Black", "BB-BISS-PRU0-00A0", "am335x", "P9_31", "mcasp0_aclkx", 0x990, 6,
     "pr1_pru0_pru_r31_0 (SL)", "in"),
    ("PocketBeagle", "PB-BISS-PRU0-00A0", "am335x", "P1_33", "mcasp0_fsx", 0x994, 5,
     "pr1_pru0_pru_r30_1 (MA)", "out"),
    ("PocketBeagle", "PB-BISS-PRU0-00A0", "am335x", "P1_36", "mcasp0_aclkx", 0x990, 6,
     "pr1_pru0_pru_r31_0 (SL)", "in"),
    # two encoders: PRU0's pins again, and PRU1's (SPRS717L Signal Descriptions,
    # PRU1 table: r31_0 on ball R1 only, r30_1 on R2 only; BeagleBone Black
    # SRM "Expansion Header P8 Pinout": R1 = P8_45 lcd_data0, R2 = P8_46
    # lcd_data1, modes 5 and 6 as below)
    ("BeagleBone Black", "BB-BISS-PRU01-00A0", "am335x", "P9_29", "mcasp0_fsx", 0x994, 5,
     "pr1_pru0_pru_r30_1 (MA0)", "out"),
    ("BeagleBone Black", "BB-BISS-PRU01-00A0", "am335x", "P9_31", "mcasp0_aclkx", 0x990, 6,
     "pr1_pru0_pru_r31_0 (SL0)", "in"),
    ("BeagleBone Black", "BB-BISS-PRU01-00A0", "am335x", "P8_46", "lcd_data1", 0x8A4, 5,
     "pr1_pru1_pru_r30_1 (MA1)", "out"),
    ("BeagleBone Black", "BB-BISS-PRU01-00A0", "am335x", "P8_45", "lcd_data0", 0x8A0, 6,
     "pr1_pru1_pru_r31_0 (SL1)", "in"),
    ("AM437x IDK", "AM437X-IDK-BISS-00A0", "am437x", "-", "mcasp0_aclkx", 0x990, 6,
     "pr0_pru0_gpi0 (SL)", "in"),
    ("AM437x IDK", "AM437X-IDK-BISS-00A0", "am437x", "-", "mcasp0_fsx", 0x994, 5,
     "pr0_pru0_gpo1 (MA)", "out"),
    ("AM437x IDK", "AM437X-IDK-BISS-00A0", "am437x", "-", "endat_en", 0xA48, 7,
     "gpio5_12 (receiver enable)", "out"),
]

# the labels each overlay needs from the base tree, and no more: none that
# one of the kernels lacks (pruss_tm is 5.10-ti and newer only)
TARGETS = {
    "BB-BISS-PRU0-00A0": {"am33xx_pinmux", "pruss", "mcasp0", "ocp"},
    "PB-BISS-PRU0-00A0": {"am33xx_pinmux", "pruss", "ocp"},
    "BB-BISS-PRU01-00A0": {"am33xx_pinmux", "pruss", "mcasp0", "ocp"},
    "AM437X-IDK-BISS-00A0": {"am43xx_pinmux", "pruss0", "gpio5"},
}
# the pin helpers each overlay must disable (the helpers of its pads)
HELPERS_OFF = {
    "BB-BISS-PRU0-00A0": {"P9_29_pinmux", "P9_31_pinmux"},
    "PB-BISS-PRU0-00A0": {"P1_33_pinmux", "P1_36_pinmux"},
    "BB-BISS-PRU01-00A0": {"P9_29_pinmux", "P9_31_pinmux", "P8_45_pinmux", "P8_46_pinmux"},
    "AM437X-IDK-BISS-00A0": set(),
}
# the PRU-ICSS node the pins hang on
PRUSS = {"BB-BISS-PRU0-00A0": "pruss", "PB-BISS-PRU0-00A0": "pruss",
         "BB-BISS-PRU01-00A0": "pruss", "AM437X-IDK-BISS-00A0": "pruss0"}

boards = sys.argv[1]
dtc = shutil.which("dtc")
check(dtc is not None, "dtc on PATH (Debian: device-tree-compiler, scripts/setup.sh)")
if dtc is None:
    sys.exit(1)

with tempfile.TemporaryDirectory() as tmp:
    for name, labels in TARGETS.items():
        src = os.path.join(boards, name + ".dts")
        dtbo = os.path.join(tmp, name + ".dtbo")
        r = subprocess.run([dtc, "-@", "-I", "dts", "-O", "dtb", "-o", dtbo, src],
                           capture_output=True, text=True)
        check(r.returncode == 0, "%s: dtc: %s" % (name, r.stderr))
        check(r.stderr == "", "%s: dtc warnings: %s" % (name, r.stderr))
        if r.returncode:
            continue
        back = subprocess.run([dtc, "-I", "dtb", "-O", "dts", dtbo], capture_output=True,
                              text=True).stdout
        cells = re.findall(r"pinctrl-single,pins = <([^>]*)>", back)
        check(len(cells) == 1, "%s: one pin group, found %d" % (name, len(cells)))
        words = [int(w, 16) for w in cells[0].split()] if cells else []
        pads = dict(zip(words[0::2], words[1::2]))
        rows = [p for p in PINS if p[1] == name]
        check(len(pads) == len(rows) and len(words) == 2 * len(rows),
              "%s: %d pads set, table has %d" % (name, len(pads), len(rows)))
        for board, _, soc, pin, pad, off, mode, signal, d in rows:
            e = ENC[soc]
            key = off - 0x800      # pinctrl-single offset
            v = pads.get(key)
            what = "%s %s %s (pad 0x%03x, 0x%08x)" % (board, pin, pad, off, CONTROL + off)
            check(v is not None, "%s: not set" % what)
            if v is None:
                continue
            check(v & e["mode"] == mode, "%s: mode %d, want %d for %s" % (what, v & e["mode"],
                                                                         mode, signal))
            if d == "in":
                check(v & e["input"] and v & e["pullup"] and not v & e["pulldis"],
                      "%s: 0x%x is not an input with pull-up" % (what, v))
            else:
                check(not v & e["input"] and v & e["pulldis"],
                      "%s: 0x%x is not an output without pull" % (what, v))
            known = e["mode"] | e["pulldis"] | e["pullup"] | e["input"]
            check(v & ~known == 0, "%s: unexpected bits 0x%x" % (what, v & ~known))
        fix = re.search(r"__fixups__ \{(.*?)\};", back, re.S)
        got = set(re.findall(r"(\w+) = ", fix.group(1))) if fix else set()
        check(got == labels, "%s: labels %s, want %s" % (name, sorted(got), sorted(labels)))
        check("__symbols__" in back, "%s: compiled with symbols (-@)" % name)
        # the PRU-ICSS switched on and nothing else; on the Black, McASP0
        # (HDMI audio) off; the helpers of its pads off
        check(len(re.findall(r'status = "okay"', back)) == 1, "%s: one node enabled" % name)
        ov = fdt.read(dtbo)
        target = {}  # label -> the fragment's __overlay__ node
        for label, refs in ov.child("__fixups__").props.items():
            for ref in refs.rstrip(b"\0").decode().split("\0"):
                target[label] = fdt.find(ov, ref.split(":")[0] + "/__overlay__")
        if "ocp" in target:
            helpers_off = {c.name for c in target["ocp"].children
                           if c.props.get("status") == b"disabled\0"}
            check(helpers_off == HELPERS_OFF[name] and len(target["ocp"].children) ==
                  len(helpers_off), "%s: helpers disabled %s, want %s"
                  % (name, sorted(helpers_off), sorted(HELPERS_OFF[name])))
        else:
            check(not HELPERS_OFF[name], "%s: no &ocp fragment" % name)
        if "mcasp0" in target:
            check(target["mcasp0"].props.get("status") == b"disabled\0",
                  "%s: McASP0 disabled" % name)
        if "gpio5" in labels:
            check(re.search(r"gpio-hog;\s*gpios = <0x0c 0x00>;\s*output-high;", back) is not None,
                  "%s: gpio5_12 hog" % name)

    # applied to the stand-in base trees, followed by what U-Boot applies
    # after uboot_overlay_addr4
    fdtoverlay = shutil.which("fdtoverlay")
    check(fdtoverlay is not None, "fdtoverlay on PATH (Debian: device-tree-compiler)")

    def compile_tree(tree, name):
        """A stand-in tree (standins.Tree) compiled with dtc -@: its path."""
        out = os.path.join(tmp, name + (".dtbo" if tree.plugin else ".dtb"))
        r = subprocess.run([dtc, "-@", "-q", "-I", "dts", "-O", "dtb", "-o", out, "-"],
                           input=tree.dts(), capture_output=True, text=True)
        check(r.returncode == 0, "%s: dtc: %s" % (name, r.stderr))
        return out

    for i, (case, base, overlay, after, want) in enumerate(standins.cases()):
        if fdtoverlay is None:
            break
        base_dtb = compile_tree(base, "base%d" % i)
        extra = [compile_tree(t, "after%d_%d" % (i, k)) for k, t in enumerate(after)]
        applied = os.path.join(tmp, "applied%d.dtb" % i)
        r = subprocess.run([fdtoverlay, "-i", base_dtb, "-o", applied,
                            os.path.join(tmp, overlay + ".dtbo")] + extra,
                           capture_output=True, text=True)
        if not check(r.returncode == 0, "%s: fdtoverlay: %s" % (case, r.stderr.strip())):
            continue
        tree = fdt.read(applied)
        doubles = fdt.double_claims(tree)
        got = {pad for (_ctl, pad) in doubles}
        check(got == want, "%s: pads claimed twice %s, want %s: %s" % (
            case, sorted(hex(p) for p in got), sorted(hex(p) for p in want),
            "; ".join("0x%03x by %s" % (pad, ", ".join(sorted(who)))
                      for (_ctl, pad), who in sorted(doubles.items()))))
        # the PRU-ICSS probes (it and its parents enabled) with the
        # overlay's pads and only those
        pruss = fdt.find(tree, standins.pruss_path(base, PRUSS[overlay]))
        check(pruss is not None and fdt.enabled(pruss), "%s: PRU-ICSS not enabled" % case)
        mine = {pad for (_ctl, pad), who in fdt.pad_claims(tree).items()
                if pruss is not None and pruss.path() in who}
        table = {p[5] - 0x800 for p in PINS if p[1] == overlay}
        check(mine == table, "%s: PRU-ICSS claims %s, want %s" % (
            case, sorted(hex(p) for p in mine), sorted(hex(p) for p in table)))

    # the config-pin recipes, run with a stand-in config-pin that logs its
    # arguments: the same header pins and PRU modes as the table, per PRU;
    # the PocketBeagle refuses PRU1 (its R31 bit 0 is not on a header)
    fake = os.path.join(tmp, "bin")
    os.mkdir(fake)
    log = os.path.join(tmp, "config-pin.log")
    with open(os.path.join(fake, "config-pin"), "w") as f:
        f.write('#!/bin/sh\necho "$*" >> "%s"\n' % log)
    os.chmod(os.path.join(fake, "config-pin"), 0o755)
    env = dict(os.environ, PATH=fake + os.pathsep + os.environ["PATH"])
    for script, args, rc, pins in [
            ("config-pin-beaglebone.sh", [], 0, [("P9_29", "pruout"), ("P9_31", "pruin")]),
            ("config-pin-beaglebone.sh", ["--pru", "0"], 0,
             [("P9_29", "pruout"), ("P9_31", "pruin")]),
            ("config-pin-beaglebone.sh", ["--pru", "1"], 0,
             [("P8_46", "pruout"), ("P8_45", "pruin")]),
            ("config-pin-beaglebone.sh", ["--pru", "2"], 2, []),
            ("config-pin-pocketbeagle.sh", [], 0, [("P1_33", "pruout"), ("P1_36", "pruin")]),
            ("config-pin-pocketbeagle.sh", ["--pru", "1"], 1, [])]:
        if os.path.exists(log):
            os.remove(log)
        r = subprocess.run(["sh", os.path.join(boards, script)] + args, env=env,
                           capture_output=True, text=True)
        what = "%s %s" % (script, " ".join(args))
        check(r.returncode == rc, "%s: exit %d, want %d (%s)" % (what, r.returncode, rc,
                                                                 r.stderr.strip()))
        calls = open(log).read().split("\n")[:-1] if os.path.exists(log) else []
        want = ["%s %s" % p for p in pins] + ["-q %s" % p for p, _ in pins]
        check(calls == want, "%s: config-pin calls %r, want %r" % (what, calls, want))
        if rc:
            check(r.stderr != "", "%s: fails without saying why" % what)
    # the PRU1 pins in the table are the ones the BeagleBone recipe sets
    pru1 = {p[3]: ("pruout" if p[8] == "out" else "pruin") for p in PINS
            if p[1] == "BB-BISS-PRU01-00A0" and "pru1" in p[7]}
    check(pru1 == {"P8_46": "pruout", "P8_45": "pruin"}, "PRU1 table rows %r" % pru1)

finish("board overlays")
