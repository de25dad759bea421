#!/bin/sh
# Cross-builds the host side for the board (ARM, hard float) with CMake and
# cmake/toolchain-armhf.cmake, and installs it into BUILD_DIR-prefix:
#   scripts/cross-bissctl.sh [BUILD_DIR]        (default build-arm)
# Prints the installed bissctl's path. The build directory is a cache: a
# second run only rebuilds what changed. (The prefix lies outside the build
# tree so the installed programs find their firmware as installed ones do.) Programs are linked statically
# (libbiss.so is still built and installed), so bissctl runs on any ARM
# Linux image whatever its C library and, on a PC, under qemu-arm.
# Debian: gcc-arm-linux-gnueabihf (scripts/setup.sh installs it).
set -eu
here=$(cd "$(dirname "$0")/.." && pwd)
dir=${1:-build-arm}
mkdir -p "$dir"
dir=$(cd "$dir" && pwd)
cmake -S "$here" -B "$dir" -DCMAKE_TOOLCHAIN_FILE="$here/cmake/toolchain-armhf.cmake" \
    -DBUILD_TESTING=OFF -DCMAKE_BUILD_TYPE=Release -DCMAKE_EXE_LINKER_FLAGS=-static \
    -DCMAKE_INSTALL_PREFIX="$dir-prefix" >"$dir/configure.log" ||
    { cat "$dir/configure.log" >&2; exit 1; }
cmake --build "$dir" -j "${BISS_CROSS_JOBS:-2}" >"$dir/build.log" 2>&1 ||
    { tail -40 "$dir/build.log" >&2; exit 1; }
cmake --install "$dir" >/dev/null
echo "$dir-prefix/bin/bissctl"
