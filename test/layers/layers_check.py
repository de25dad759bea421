#!/usr/bin/env python3
"""The layers keep their order (docs/ARCHITECTURE.md, "Layers").

Bottom up: include/ and common/; emulator/isa and proto/; the rest of the
emulator, line, assembler and core before the slave models before the
bench, and the firmware (pru_fw/, pru_slave/) beside them; then the host:
host/lib, the backends, discovery (probe), bissctl; applications
(examples/) last. A file may include its own layer's files and any lower
layer's, never a higher one's:

 - every #include of every C source and header and every firmware source
   (.p, .hp; pasm's preprocessor) outside test/, resolved to the file of
   the tree it names (relative to the includer, else by the path it
   writes), must not run back up;
 - no CMake file of a layer names a folder above it (proto/ exports no
   host/ path; pru_fw/ builds with nothing of host/);
 - every source file outside test/ is in a layer (a new folder is placed
   here, and in the document, before it can hold code).

Tests may include anything: they are no layer.

usage: layers_check.py --source DIR [--plant FILE:LINE ...]
       layers_check.py --source DIR --self-test

--plant adds LINE to FILE (as read, nothing is written) before the check:
the self-test plants includes and a CMake path that run back up, one at a
time, and requires each to be found and named, and the tree as it is to
pass.
"""

import argparse
import os
import posixpath
import re
import sys

# Bottom up; a path belongs to the layer of its longest matching prefix.
LAYERS = [
    ("contract and helpers", ["include/", "common/"]),
    ("instruction list and protocol", ["emulator/isa/", "proto/"]),
    ("emulator parts and firmware",
     ["emulator/line/", "emulator/asm/", "emulator/core/", "pru_fw/", "pru_slave/"]),
    ("slave models", ["emulator/slave/"]),
    ("bench", ["emulator/bench/", "emulator/speed/", "emulator/CMakeLists.txt"]),
    ("libbiss core", ["host/lib/", "host/include/libbiss.h"]),
    ("backends", ["host/backend/", "host/include/libbiss-emu.h"]),
    ("discovery", ["host/probe/", "host/include/biss_probe.h"]),
    ("bissctl", ["host/bissctl/", "host/bench/", "host/CMakeLists.txt", "host/libbiss"]),
    ("applications and integrations", ["examples/", "integrations/"]),
]
SOURCE_EXT = (".c", ".h", ".p", ".hp")
CMAKE_NAMES = ("CMakeLists.txt",)
CMAKE_EXT = (".cmake",)
SKIP_TOP = ("test", "build", "cmake", "docs", "man", "packaging", "scripts", "boards")

INCLUDE = re.compile(r'^\s*#\s*include\s*([<"])([^>"]+)[>"]')
# a CMake path into the tree: ${PROJECT_SOURCE_DIR}/x, ${CMAKE_SOURCE_DIR}/x,
# ${_src}/x (pru_fw/tools/pru_elf.cmake), ${top}/x
CMAKE_PATH = re.compile(r'\$\{(?:PROJECT_SOURCE_DIR|CMAKE_SOURCE_DIR|_src|top)\}/([A-Za-z0-9_./-]+)')


def layer_of(rel):
    best, rank = "", None
    for i, (_, prefixes) in enumerate(LAYERS):
        for p in prefixes:
            if rel.startswith(p) and len(p) > len(best):
                best, rank = p, i
    return rank


def folder_layer(d):
    """A folder a build file names: the highest layer reachable in it."""
    d = d.rstrip("/") + "/"
    ranks = [i for i, (_, prefixes) in enumerate(LAYERS) for p in prefixes
             if p.startswith(d) or d.startswith(p)]
    return max(ranks) if ranks else None


def skipped(rel):
    top = rel.split("/")[0]
    return top in SKIP_TOP or top.startswith("build")


def tree_files(src):
    files = []
    for d, dirs, names in os.walk(src):
        rel_d = os.path.relpath(d, src).replace(os.sep, "/")
        rel_d = "" if rel_d == "." else rel_d + "/"
        dirs[:] = sorted(x for x in dirs
                         if not x.startswith(".") and not (rel_d == "" and skipped(x)))
        for n in sorted(names):
            files.append(rel_d + n)
    return files


def resolve(includer, name, by_path):
    """The tree file an include names, or None (a system header)."""
    here = posixpath.normpath(posixpath.join(posixpath.dirname(includer), name))
    if here in by_path:
        return here
    hits = [f for f in by_path if f == name or f.endswith("/" + name)]
    return hits[0] if len(hits) == 1 else (sorted(hits) if hits else None)


def check(src, plants):
    files = tree_files(src)
    text = {}
    for f in files:
        if f.endswith(SOURCE_EXT) or os.path.basename(f) in CMAKE_NAMES or f.endswith(CMAKE_EXT):
            with open(os.path.join(src, f), encoding="utf-8", errors="replace") as fh:
                text[f] = fh.read()
    for f, line in plants:
        text[f] = text.get(f, "") + "\n" + line + "\n"
    problems = []
    files_set = set(files) | set(text)
    sources = {f: t for f, t in text.items() if f.endswith(SOURCE_EXT)}
    for f in sorted(text):
        rank = layer_of(f)
        is_cmake = not f.endswith(SOURCE_EXT)
        if rank is None:
            if not is_cmake and not skipped(f):
                problems.append("%s: in no layer (place its folder in %s and in "
                                "docs/ARCHITECTURE.md)" % (f, os.path.basename(__file__)))
            continue
        for n, line in enumerate(text[f].split("\n"), 1):
            if is_cmake:
                targets = [(posixpath.normpath(m.group(1)), m.group(0))
                           for m in CMAKE_PATH.finditer(line)]
            else:
                m = INCLUDE.match(line)
                if not m:
                    continue
                to = resolve(f, m.group(2), sources)
                if to is None:
                    continue
                if isinstance(to, list):
                    problems.append("%s:%d: %s names %s: which one?" %
                                    (f, n, m.group(0).strip(), ", ".join(to)))
                    continue
                targets = [(to, m.group(0).strip())]
            for to, what in targets:
                r = layer_of(to) if to in files_set else folder_layer(to)
                if r is not None and r > rank:
                    problems.append("%s:%d: %s runs back up: %s (%s) is above %s (%s)" %
                                    (f, n, what, to, LAYERS[r][0], f, LAYERS[rank][0]))
    return problems


# Includes and paths that run back up, planted one at a time: each must be
# found, and named by the file it is planted in.
PLANTS = [
    ("proto/biss_proto.h", '#include "libbiss.h"'),
    ("include/biss/biss_types.h", '#include "biss_priv.h"'),
    ("include/biss/biss_shm.h", '#include "../../host/include/libbiss.h"'),
    ("common/read_file.c", '#include "biss_proto.h"'),
    ("emulator/core/core.c", '#include "bench.h"'),
    ("emulator/slave/biss_slave.c", '#include "libbiss-emu.h"'),
    ("pru_fw/tools/pru_elf.c", '#include "biss_oserr.h"'),
    ("pru_fw/biss_master.p", '#include "../host/lib/biss_priv.h"'),
    ("host/lib/biss_io.c", '#include "bissctl.h"'),
    ("host/backend/backend_linux.c", '#include "biss_probe_priv.h"'),
    ("proto/CMakeLists.txt",
     "target_include_directories(biss_proto PUBLIC ${PROJECT_SOURCE_DIR}/host/include)"),
    ("pru_fw/tools/pru_elf.cmake", "target_sources(pru-elf PRIVATE ${_src}/host/lib/biss_io.c)"),
]


def self_test(src):
    ok = True
    base = check(src, [])
    if base:
        print("FAIL: the tree as it is:\n  " + "\n  ".join(base))
        ok = False
    for f, line in PLANTS:
        found = [p for p in check(src, [(f, line)]) if p not in base]
        if len(found) == 1 and found[0].startswith(f + ":") and "runs back up" in found[0]:
            print("found: " + found[0])
        else:
            print("FAIL: planted in %s, not found as one upward include: %r -> %r" %
                  (f, line, found))
            ok = False
    # and a file in a folder no layer holds
    found = [p for p in check(src, [("newpart/x.c", "int x;")]) if p not in base]
    if len(found) == 1 and "in no layer" in found[0]:
        print("found: " + found[0])
    else:
        print("FAIL: a file in no layer not found: %r" % found)
        ok = False
    print("layers self-test: %s" % ("ok" if ok else "FAILED"))
    return 0 if ok else 1


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--source", required=True)
    ap.add_argument("--plant", action="append", default=[], metavar="FILE:LINE")
    ap.add_argument("--self-test", action="store_true")
    a = ap.parse_args()
    if a.self_test:
        return self_test(a.source)
    plants = [tuple(p.split(":", 1)) for p in a.plant]
    problems = check(a.source, plants)
    for p in problems:
        print("FAIL: " + p)
    print("layers: %s" % ("%d include(s) or path(s) out of order" % len(problems)
                          if problems else "every include and build path runs down"))
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
