#!/usr/bin/env bash
# Installs what a fresh Debian (bookworm) machine lacks to build and test the
# project. Does nothing when everything is already there.
set -euo pipefail

packages=(gcc make cmake pkg-config check libcjson-dev python3 clang-format libelf-dev binutils python3-pyelftools device-tree-compiler gcc-arm-linux-gnueabihf libc6-dev-armhf-cross qemu-user)
packages+=(sigrok-cli gtkwave) # the VCD clients the tests open the bench's VCD with
packages+=(systemd) # systemd-analyze verifies the service unit (test board_flow)

missing=()
for p in "${packages[@]}"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done

if [ ${#missing[@]} -eq 0 ]; then
    exit 0
fi

echo "setup: installing ${missing[*]}" >&2
sudo=""
if [ "$(id -u)" -ne 0 ]; then
    sudo="sudo"
fi
export DEBIAN_FRONTEND=noninteractive
$sudo apt-get update -qq
$sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
