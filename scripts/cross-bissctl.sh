#!/bin/sh
# Cross-builds the host side for the board (ARM, hard float) with CMake and
# cmake/toolchain-armhf.cmake, and installs it as the board will have it
# (prefix /usr/local, firmware and overlays in /lib/firmware) into the
# staging root BUILD_DIR-root:
#   scripts/cross-bissctl.sh [BUILD_DIR]        (default build-arm)
# Prints the staged bissctl's path (BUILD_DIR-root/usr/local/bin/bissctl).
# Copy the tree onto the board's / (docs/hardware.md). The build directory
# is a cache: a second run only rebuilds what changed. Programs are linked
# statically (libbiss.so is still built and installed), so bissctl runs on
# any ARM Linux image whatever its C library and, on a PC, under qemu-arm;
# the Debian packages (scripts/build-debs) link them dynamically instead.
# Debian: gcc-arm-linux-gnueabihf (scripts/setup.sh installs it).
set -eu
here=$(cd "$(dirname "$0")/.." && pwd)
dir=${1:-build-arm}
mkdir -p "$dir"
dir=$(cd "$dir" && pwd)
cmake -S "$here" -B "$dir" -DCMAKE_TOOLCHAIN_FILE="$here/cmake/toolchain-armhf.cmake" \
    -DBUILD_TESTING=OFF -DCMAKE_BUILD_TYPE=Release -DCMAKE_EXE_LINKER_FLAGS=-static \
    -DCMAKE_INSTALL_PREFIX=/usr/local -DBISS_FIRMWARE_DIR=/lib/firmware \
    >"$dir/configure.log" || { cat "$dir/configure.log" >&2; exit 1; }
cmake --build "$dir" -j "${BISS_CROSS_JOBS:-2}" >"$dir/build.log" 2>&1 ||
    { tail -40 "$dir/build.log" >&2; exit 1; }
rm -rf "$dir-root"
DESTDIR="$dir-root" cmake --install "$dir" >/dev/null
echo "$dir-root/usr/local/bin/bissctl"
