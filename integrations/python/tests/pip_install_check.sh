#!/bin/sh
# pip installs the module `biss` from the build tree (PYTHON TREE) into a
# scratch folder, and the installed copy, run from elsewhere, reads a valid
# position from the emulator.
set -eu
py=$1
tree=$2
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
"$py" -m pip install -q --no-deps --no-build-isolation --no-index --target "$dir/site" "$tree" \
    2>"$dir/pip.err" || { cat "$dir/pip.err" >&2; exit 1; }
test -f "$dir/site/biss/libbiss-emu.so"
cd "$dir"
PYTHONPATH="$dir/site" "$py" -c '
import biss, sys
assert biss.__file__.startswith(sys.argv[1]), biss.__file__
with biss.open("emu") as m:
    m.configure_from_emulator()
    m.start()
    s = m.wait()
    while not s.valid or s.training:
        s = m.wait(after_frame=s.frame)
    print("installed biss: frame %d position %d" % (s.frame, s.positions[0]))
' "$dir/site"
