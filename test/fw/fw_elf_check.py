#!/usr/bin/env python3
"""biss_master.elf as remoteproc's pru_rproc reads it, checked with two
readers that share no code with the writer: pyelftools and binutils'
readelf. The code bytes must equal biss_master.bin; the data segment must
hold the identification block (CRC-32 as zlib computes it) and an empty
version-1 resource table, at the data RAM offsets of biss_shm.h.

usage: fw_elf_check.py ELF BIN BISS_SHM_H [PRU_ELF]
"""
import os
import re
import struct
import subprocess
import sys
import tempfile
import zlib

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "common"))
from checks import check, finish, use_debian_pyelftools  # noqa: E402

use_debian_pyelftools()
from elftools.elf.elffile import ELFFile  # noqa: E402
from elftools.elf.constants import P_FLAGS



elf_path, bin_path, shm_h = sys.argv[1:4]
pru_elf = sys.argv[4] if len(sys.argv) > 4 else None
image = open(bin_path, "rb").read()
defs = dict(re.findall(r"#define\s+(BISS_\w+)\s+(0x[0-9A-Fa-f]+|\d+)", open(shm_h).read()))
ID = int(defs["BISS_ID"], 0)
RSC = int(defs["BISS_RSC_TABLE"], 0)
ID_MAGIC = int(defs["BISS_ID_MAGIC"], 0)
VERSION = int(defs["BISS_SHM_VERSION"], 0)
PRIV_END = int(defs["BISS_PRIV_END"], 0)
DRAM = int(defs["BISS_DRAM_BYTES"], 0)

# ---- pyelftools --------------------------------------------------------
with open(elf_path, "rb") as f:
    e = ELFFile(f)
    check(e.elfclass == 32 and e.little_endian, "ELF32 little-endian")
    check(e["e_machine"] == "EM_TI_PRU" or e.header.e_machine == 144,
          "machine %r" % e["e_machine"])
    check(e["e_type"] == "ET_EXEC", "type %r" % e["e_type"])
    check(e["e_entry"] == 0, "entry %#x" % e["e_entry"])
    loads = [s for s in e.iter_segments() if s["p_type"] == "PT_LOAD"]
    check(len(loads) == 2, "%d PT_LOAD segments" % len(loads))
    code = [s for s in loads if s["p_flags"] & P_FLAGS.PF_X]
    data = [s for s in loads if not s["p_flags"] & P_FLAGS.PF_X]
    check(len(code) == 1 and len(data) == 1, "one code and one data segment")
    c = code[0]
    check(c["p_paddr"] == 0 and c["p_vaddr"] == 0, "code at IRAM 0: %#x" % c["p_paddr"])
    check(c.data() == image, "code segment bytes == biss_master.bin (%d vs %d bytes)"
          % (len(c.data()), len(image)))
    check(c["p_memsz"] == len(image), "code memsz")
    d = data[0]
    # pru_rproc: a data segment's p_paddr is the PRU's own data RAM address
    check(d["p_paddr"] == ID and d["p_memsz"] == DRAM - ID, "data segment %#x+%#x"
          % (d["p_paddr"], d["p_memsz"]))
    check(d["p_paddr"] >= PRIV_END, "data segment above everything the firmware uses")
    text = e.get_section_by_name(".text")
    check(text is not None and text.data() == image, ".text == biss_master.bin")
    rsc = e.get_section_by_name(".resource_table")
    check(rsc is not None, ".resource_table present")
    if rsc is not None:
        check(rsc["sh_addr"] == RSC, ".resource_table at %#x" % rsc["sh_addr"])
        ver, num, r0, r1 = struct.unpack("<4I", rsc.data())
        check((ver, num, r0, r1) == (1, 0, 0, 0), "resource table %r" % ((ver, num, r0, r1),))
    ident = e.get_section_by_name(".biss_id")
    check(ident is not None, ".biss_id present")
    if ident is not None:
        magic, ver, crc, n = struct.unpack("<4I", ident.data())
        check(ident["sh_addr"] == ID, ".biss_id address")
        check(magic == ID_MAGIC and ver == VERSION, "id magic/version %#x %d" % (magic, ver))
        check(crc == zlib.crc32(image) and n == len(image),
              "id CRC %#x vs zlib %#x, %d bytes" % (crc, zlib.crc32(image), n))
        check(d.data() == ident.data() + rsc.data(), "data segment = id block + table")

# ---- binutils readelf --------------------------------------------------
r = subprocess.run(["readelf", "-h", "-l", "-S", "-W", elf_path], capture_output=True, text=True)
check(r.returncode == 0, "readelf exit %d: %s" % (r.returncode, r.stderr))
check(re.search(r"Machine:\s+TI PRU", r.stdout) is not None, "readelf machine")
check(re.search(r"Type:\s+EXEC", r.stdout) is not None, "readelf type")
check(re.search(r"LOAD\s+0x[0-9a-f]+ 0x00000000 0x00000000 0x%05x 0x%05x R E"
                % (len(image), len(image)), r.stdout) is not None, "readelf code segment")
check(re.search(r"LOAD\s+0x[0-9a-f]+ 0x%08x 0x%08x 0x00020 0x00020 RW" % (ID, ID),
                r.stdout) is not None, "readelf data segment")
check(r.stderr == "", "readelf warnings: %r" % r.stderr)
r = subprocess.run(["readelf", "-x", ".text", elf_path], capture_output=True, text=True)
words = []
for line in r.stdout.splitlines():
    m = re.match(r"\s+0x[0-9a-f]+ ((?:[0-9a-f]{8} ?){1,4})", line)
    if m:
        words += m.group(1).split()
dump = bytes.fromhex("".join(words))
check(dump == image, "readelf -x .text == biss_master.bin (%d bytes)" % len(dump))

# ---- the writer refuses what it cannot wrap ------------------------------
if pru_elf:
    with tempfile.TemporaryDirectory() as tmp:
        for name, content, text in [("empty.bin", b"", "4..12288 bytes"),
                                    ("odd.bin", b"\x01\x02\x03", "whole 32-bit words"),
                                    ("big.bin", b"\0" * (12 * 1024 + 4), "12288+ bytes")]:
            p = os.path.join(tmp, name)
            open(p, "wb").write(content)
            out = os.path.join(tmp, name + ".elf")
            r = subprocess.run([pru_elf, p, out], capture_output=True, text=True)
            check(r.returncode == 1 and p in r.stderr and text in r.stderr
                  and not os.path.exists(out), "%s: %d %r" % (name, r.returncode, r.stderr))
        r = subprocess.run([pru_elf, os.path.join(tmp, "none.bin"), os.path.join(tmp, "x.elf")],
                           capture_output=True, text=True)
        check(r.returncode == 1 and "No such file" in r.stderr, "missing input: %r" % r.stderr)
        # the output's mode follows the umask (0666 & ~umask)
        old = os.umask(0o022)
        out = os.path.join(tmp, "ok.elf")
        r = subprocess.run([pru_elf, bin_path, out], capture_output=True, text=True)
        os.umask(old)
        check(r.returncode == 0 and os.stat(out).st_mode & 0o777 == 0o644,
              "mode %o" % (os.stat(out).st_mode & 0o777 if os.path.exists(out) else 0))
        check(open(out, "rb").read() == open(elf_path, "rb").read(), "reproducible output")

finish("fw ELF")
