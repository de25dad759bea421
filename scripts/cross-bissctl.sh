#!/bin/sh
# Builds bissctl for the board (ARM, hard float) without the emulator:
#   scripts/cross-bissctl.sh [OUT]        (default build-arm/bissctl)
# CC defaults to arm-linux-gnueabihf-gcc (Debian: gcc-arm-linux-gnueabihf).
# The binary is static, so it runs on any ARM Linux image and, on a PC,
# under qemu-arm. 64-bit file offsets: readdir of a sysfs (or any) directory
# must not fail with EOVERFLOW on large inode numbers.
set -eu
here=$(cd "$(dirname "$0")/.." && pwd)
out=${1:-build-arm/bissctl}
cc=${CC:-arm-linux-gnueabihf-gcc}
mkdir -p "$(dirname "$out")"
srcs=""
for f in "$here"/host/*.c; do
    case $(basename "$f") in
    backend_emu.c) ;;   # the emulator stays on the PC
    *) srcs="$srcs $f" ;;
    esac
done
# shellcheck disable=SC2086
"$cc" -std=c11 -O2 -Wall -Wextra -Werror -D_POSIX_C_SOURCE=200809L -D_FILE_OFFSET_BITS=64 -static -pthread \
    -DBISS_DEFAULT_FIRMWARE='"/lib/firmware/biss_master.bin"' \
    -I"$here/host/include" -I"$here/host" -I"$here/include" -I"$here/emulator/util" \
    $srcs "$here/emulator/util/read_file.c" -o "$out"
echo "$out"
