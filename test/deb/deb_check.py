#!/usr/bin/env python3
"""The Debian packages scripts/build-debs made (test/deb/CMakeLists.txt).

usage: deb_check.py lintian DEB_DIR
       deb_check.py files DEB_DIR ARCH EXPECTED   the packages of ARCH, and
           the arch-all ones EXPECTED names, hold exactly EXPECTED's files
       deb_check.py complete DEB_DIR BUILD_DIR    every file `cmake --install
           BUILD_DIR` puts down is in one of the build machine's packages
       deb_check.py unpacked DEB_DIR              the build machine's and the
           arch-all packages unpacked into an empty tree: bissctl reads
           positions from the emulator with the unpacked firmware, biss-sim
           runs it, and the example builds against the unpacked libbiss-dev

EXPECTED holds one "package /path" a line ('#' comments); {version} is the
package version, {multiarch} the architecture's multiarch tuple.
"""
import glob
import io
import os
import re
import subprocess
import sys
import tarfile
import tempfile

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "common"))
from checks import check, finish  # noqa: E402

SOURCE = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")


def run(*args, **kw):
    return subprocess.run(args, capture_output=True, text=True, timeout=600, **kw)


def field(deb, name):
    return run("dpkg-deb", "-f", deb, name).stdout.strip()


def debs(deb_dir, arch=None):
    """The .deb files of DEB_DIR, those of arch and all when given."""
    found = sorted(glob.glob(os.path.join(deb_dir, "*.deb")))
    return [d for d in found if arch is None or field(d, "Architecture") in (arch, "all")]


def contents(deb):
    """The files and links of a package, as absolute paths (no directories)."""
    tar = subprocess.run(["dpkg-deb", "--fsys-tarfile", deb], capture_output=True, check=True)
    with tarfile.open(fileobj=io.BytesIO(tar.stdout)) as t:
        return {"/" + os.path.normpath(m.name) for m in t.getmembers() if not m.isdir()}


def native_arch():
    return run("dpkg", "--print-architecture").stdout.strip()


def lintian(deb_dir):
    found = debs(deb_dir)
    check(len(found) >= 6, "the packages are there: %r" % found)
    r = run("lintian", "--fail-on", "error", *found)
    print(r.stdout, r.stderr, sep="")
    errors = [line for line in r.stdout.splitlines() if line.startswith("E:")]
    check(r.returncode == 0 and not errors, "lintian: exit %d, %d error(s)" % (r.returncode,
                                                                             len(errors)))
    finish("lintian")


def files(deb_dir, arch, expected_file):
    multiarch = run("dpkg-architecture", "-a", arch, "-q", "DEB_HOST_MULTIARCH").stdout.strip()
    with open(expected_file) as f:
        lines = [line.split("#")[0].split() for line in f]
    pairs = [tuple(p) for p in lines if p]
    check(all(len(p) == 2 for p in pairs), "%s: one package and one path a line" % expected_file)
    named = {p[0] for p in pairs}
    found = debs(deb_dir, arch)
    version = field(found[0], "Version") if found else "?"
    want = {(p, path.format(version=version.split("-")[0], multiarch=multiarch))
            for p, path in pairs}
    have = set()
    for d in found:
        pkg = field(d, "Package")
        if field(d, "Architecture") == arch or pkg in named:
            have |= {(pkg, path) for path in contents(d)}
    for p, path in sorted(want - have):
        check(False, "missing from %s (%s): %s" % (p, arch, path))
    for p, path in sorted(have - want):
        check(False, "in %s (%s) but not in %s: %s" % (p, arch, os.path.basename(expected_file),
                                                       path))
    check(have, "no %s packages in %s" % (arch, deb_dir))
    finish("%s packages' files" % arch)


def complete(deb_dir, build_dir):
    packaged = set()
    for d in debs(deb_dir, native_arch()):
        packaged |= contents(d)
    with tempfile.TemporaryDirectory() as root:
        r = run("cmake", "--install", build_dir, env=dict(os.environ, DESTDIR=root))
        check(r.returncode == 0, "cmake --install: %r" % r.stderr)
        installed = set()
        for d, _, names in os.walk(root):
            installed |= {"/" + os.path.relpath(os.path.join(d, n), root) for n in names}
    for path in sorted(installed - packaged):
        check(False, "installed but in no package (install() without a packaged COMPONENT, "
                     "packaging/CMakeLists.txt): %s" % path)
    for path in sorted(packaged - installed):
        check(False, "packaged but not installed: %s" % path)
    check(installed, "cmake --install put nothing down")
    finish("every installed file packaged")


def unpacked(deb_dir):
    arch = native_arch()
    with tempfile.TemporaryDirectory() as root:
        for d in debs(deb_dir, arch):
            check(run("dpkg-deb", "-x", d, root).returncode == 0, "dpkg-deb -x " + d)
        ctl = os.path.join(root, "usr", "bin", "bissctl")
        fw = os.path.join(root, "lib", "firmware", "biss_master.bin")
        r = run(ctl, "--target", "emu", "info")
        check(r.returncode == 0 and re.search(r"firmware=%s(\s|$)" % re.escape(fw), r.stdout),
              "bissctl finds the unpacked firmware: %r %r" % (r.stdout, r.stderr))
        r = run(ctl, "--target", "emu", "read", "-n", "5")
        frames = re.findall(r"^frame=(\d+) ", r.stdout, re.M)
        check(r.returncode == 0 and frames == ["1", "2", "3", "4", "5"]
              and r.stdout.count(" valid s0.pos=") == 4,
              "bissctl --target emu read -n 5: %d %r %r" % (r.returncode, r.stdout, r.stderr))
        r = run(os.path.join(root, "usr", "bin", "biss-sim"), "--frames", "20")
        check(r.returncode == 0, "biss-sim with the unpacked firmware: %r" % r.stderr)
        pc = glob.glob(os.path.join(root, "usr", "lib", "*", "pkgconfig", "libbiss.pc"))
        if check(len(pc) == 1, "libbiss.pc in the multiarch libdir: %r" % pc):
            env = dict(os.environ, PKG_CONFIG_LIBDIR=os.path.dirname(pc[0]), PKG_CONFIG_PATH="")
            flags = run("pkg-config", "--cflags", "--libs", "libbiss", env=env).stdout.split()
            exe = os.path.join(root, "read_positions")
            r = run("cc", "-std=c11", "-Wall", "-Wextra", "-Werror",
                    os.path.join(SOURCE, "examples", "read_positions.c"), "-o", exe, *flags)
            check(r.returncode == 0 and os.path.exists(exe),
                  "the example against libbiss-dev: %r %r" % (flags, r.stderr))
        # the Python module over the unpacked libbiss: it loads, speaks the
        # library's errors, and has no emulator (that is the build tree's)
        site = os.path.join(root, "usr", "lib", "python3", "dist-packages")
        libdir = os.path.dirname(pc[0]) if pc else ""
        env = dict(os.environ, PYTHONPATH=site, LD_LIBRARY_PATH=os.path.dirname(libdir),
                   PYTHONDONTWRITEBYTECODE="1")
        r = run("/usr/bin/python3", "-c", """
import biss
assert not biss.HAS_EMULATOR
assert biss.strerror(biss.lib.BISS_E_DEVMEM).startswith("the PRU-ICSS memory")
try:
    biss.open("am335x", loader="devmem", devmem="/nonexistent/mem")
except biss.BissError as e:
    print(e.name, e.detail)
""", env=env)
        check(r.returncode == 0 and r.stdout.startswith("BISS_E_DEVMEM /nonexistent/mem"),
              "python3-biss over the unpacked libbiss0: %r %r" % (r.stdout, r.stderr))
    finish("unpacked packages")


if __name__ == "__main__":
    modes = {"lintian": lintian, "files": files, "complete": complete, "unpacked": unpacked}
    if len(sys.argv) < 3 or sys.argv[1] not in modes:
        sys.exit(__doc__)
    modes[sys.argv[1]](*sys.argv[2:])
