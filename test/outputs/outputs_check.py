"""outputs_check.py - every tool that writes a file writes it safely
(common/safe_file.h): pru-elf, pruasm, biss-sim's VCD and SVG and
bissctl's probe scenario, each against

  - a new name and an existing file: written, nothing else left beside it;
  - the name OUT.tmp planted as a link to a victim: the victim untouched
    (pru-elf once wrote OUT.tmp and renamed it over OUT);
  - a symbolic link to a file: the file replaced, the link kept;
  - a UNIX socket and a directory: refused, left as they were;
  - a device that refuses the write (/dev/full, 1:7; as root a private
    node of its own, since root may rename over /dev/full): an error, the
    node still that device;
  - a FIFO with a reader: written in place (pru-elf's libelf needs to seek:
    an error), still a FIFO.

  outputs_check.py PRU_ELF PRUASM BISS_SIM BISSCTL IMAGE
"""
import os
import socket
import stat
import subprocess
import sys
import tempfile
import threading

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "common"))
from checks import check, finish  # noqa: E402

PRU_ELF, PRUASM, SIM, CTL, IMAGE = sys.argv[1:6]


def writers(tmp):
    """Each tool as a function of its output path: (name, run, seekable)."""
    src = os.path.join(tmp, "prog.p")
    with open(src, "w") as f:
        f.write("ldi r1, 1\nhalt\n")

    def pru_elf(out):
        return subprocess.run([PRU_ELF, IMAGE, out], capture_output=True, text=True)

    def pruasm(out):
        base = out[:-4] if out.endswith(".bin") else out
        return subprocess.run([PRUASM, "-V3", "-b", src, base], capture_output=True, text=True,
                              cwd=tmp)

    def vcd(out):
        return subprocess.run([SIM, "--frames", "3", "--vcd", out], capture_output=True, text=True)

    def svg(out):
        return subprocess.run([SIM, "--frames", "3", "--svg", out], capture_output=True, text=True)

    def scenario(out):
        return subprocess.run([CTL, "--freq", "10000000", "probe", "-n", "40", out],
                              capture_output=True, text=True)

    # (name, run, output suffix, writes through a pipe)
    return [("pru-elf", pru_elf, ".elf", False), ("pruasm", pruasm, ".bin", True),
            ("biss-sim --vcd", vcd, ".vcd", True), ("biss-sim --svg", svg, ".svg", True),
            ("bissctl probe", scenario, ".json", True)]


def kind(path):
    st = os.lstat(path)
    return stat.S_IFMT(st.st_mode), st.st_rdev


with tempfile.TemporaryDirectory() as tmp:
    for name, run, ext, piped in writers(tmp):
        d = tempfile.mkdtemp(dir=tmp)
        out = os.path.join(d, "out" + ext)
        # new, then replaced; nothing left beside it
        for n in range(2):
            r = run(out)
            check(r.returncode == 0 and os.path.isfile(out) and os.path.getsize(out) > 0,
                  "%s: write %d: %d %r" % (name, n, r.returncode, r.stderr[-300:]))
        check(sorted(os.listdir(d)) == ["out" + ext], "%s: left %r" % (name, os.listdir(d)))
        # OUT.tmp planted as a link to a victim
        victim = os.path.join(d, "victim")
        with open(victim, "w") as f:
            f.write("keep\n")
        os.symlink(victim, out + ".tmp")
        r = run(out)
        check(r.returncode == 0 and open(victim, "rb").read() == b"keep\n",
              "%s: OUT.tmp followed: %r" % (name, r.stderr[-300:]))
        # a link to a file: the file replaced, the link kept
        real, link = os.path.join(d, "real" + ext), os.path.join(d, "link" + ext)
        with open(real, "w") as f:
            f.write("old\n")
        os.symlink(real, link)
        r = run(link)
        check(r.returncode == 0 and os.path.islink(link) and open(real, "rb").read() != b"old\n",
              "%s: through a link: %r" % (name, r.stderr[-300:]))
        # a socket and a directory: refused, left as they were
        sock = os.path.join(d, "sock" + ext)
        s = socket.socket(socket.AF_UNIX)
        s.bind(sock)
        sub = os.path.join(d, "sub" + ext)
        os.mkdir(sub)
        for what, path, mode in [("socket", sock, stat.S_IFSOCK), ("directory", sub, stat.S_IFDIR)]:
            r = run(path)
            check(r.returncode != 0 and kind(path)[0] == mode and
                  ("not a regular file" in r.stderr or "Is a directory" in r.stderr),
                  "%s: over a %s: %d %r" % (name, what, r.returncode, r.stderr[-300:]))
        s.close()
        # a device that refuses the write: an error, still that device
        full = "/dev/full"
        if os.geteuid() == 0:
            full = os.path.join(d, "full" + ext)
            os.mknod(full, 0o666 | stat.S_IFCHR, os.makedev(1, 7))
        before = kind(full)
        r = run(full)
        check(r.returncode != 0 and kind(full) == before and before[0] == stat.S_IFCHR,
              "%s: over /dev/full: %d %r" % (name, r.returncode, r.stderr[-300:]))
        # a FIFO with a reader: in place
        fifo = os.path.join(d, "fifo" + ext)
        os.mkfifo(fifo)
        got = []
        reader = threading.Thread(target=lambda: got.append(open(fifo, "rb").read()), daemon=True)
        reader.start()
        r = run(fifo)
        try:  # a reader still waiting for a writer (the tool never opened it)
            os.close(os.open(fifo, os.O_WRONLY | os.O_NONBLOCK))
        except OSError:
            pass  # ENXIO: the reader is gone, it saw the tool's end
        reader.join(timeout=60)
        check(kind(fifo)[0] == stat.S_IFIFO and (r.returncode == 0) == piped and
              (not piped or (got and len(got[0]) > 0)),
              "%s: into a FIFO: %d %r" % (name, r.returncode, r.stderr[-300:]))

finish("outputs")
