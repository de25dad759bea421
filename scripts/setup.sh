#!/usr/bin/env bash
# Installs what a fresh Debian (bookworm) machine lacks to build and test the
# project (scripts/run.sh, scripts/test.sh); does nothing when everything is
# already there. scripts/fresh-machine-check proves the list on a clean root.
#   scripts/setup.sh              the project's packages
#   scripts/setup.sh PACKAGE...   those instead (scripts/fresh-machine-check's)
# When another apt or dpkg holds the package manager's lock (a board's first
# boot runs apt for minutes), it names the holder and waits for it, up to
# BISS_APT_WAIT seconds (default 900).
set -euo pipefail

packages=(
    gcc make cmake pkg-config check libcjson-dev libelf-dev binutils clang-format # the build
    python3 python3-pyelftools                    # the test scripts
    python3-cffi python3-numpy python3-pytest     # the Python module (integrations/python)
    python3-pip python3-setuptools                # ... installed from the tree by pip
    linuxcnc-uspace-dev                           # the HAL component (integrations/linuxcnc), halrun
    device-tree-compiler                          # the board overlays (dtc, fdtoverlay)
    gcc-arm-linux-gnueabihf libc6-dev-armhf-cross # the board's ARM build (crt1.o: the latter)
    qemu-user                                     # runs the ARM build on the PC
    sigrok-cli gtkwave                            # the VCD clients the tests open the bench's VCD with
    systemd                                       # systemd-analyze verifies the service unit (board_flow)
    help2man                                      # the manual pages
    dpkg-dev lintian                              # the Debian packages (scripts/build-debs, test/deb)
)
if [ $# -gt 0 ]; then
    packages=("$@")
fi

missing=()
for p in "${packages[@]}"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
    exit 0
fi

sudo=""
if [ "$(id -u)" -ne 0 ]; then
    if ! command -v sudo >/dev/null; then
        echo "setup: missing ${missing[*]}; run this as root, or install sudo" >&2
        exit 1
    fi
    sudo="sudo"
fi

# The package manager's locks and who holds them: /proc/locks lists every
# POSIX lock with its holder's PID and the file's inode.
locks=(/var/lib/dpkg/lock-frontend /var/lib/dpkg/lock /var/lib/apt/lists/lock
       /var/cache/apt/archives/lock)
lock_holder() { # prints "PID (command) holds FILE" for the first lock held
    local f dev id pid
    for f in "${locks[@]}"; do
        [ -e "$f" ] || continue
        # as /proc/locks spells it: MAJOR:MINOR:INODE, the numbers in hex
        dev=$((16#$(stat -c %D "$f")))
        id=$(printf "%02x:%02x:%s" $(((dev >> 8) & 0xfff)) $(((dev & 0xff) | ((dev >> 12) & 0xfff00))) \
            "$(stat -c %i "$f")")
        pid=$(awk -v id="$id" '$2 != "->" && $6 == id { print $5; exit }' /proc/locks 2>/dev/null)
        if [ -n "$pid" ]; then
            echo "$pid ($(tr '\0\n' '  ' <"/proc/$pid/cmdline" 2>/dev/null | cut -c1-80)) holds $f"
            return 0
        fi
    done
    return 1
}
wait_limit=${BISS_APT_WAIT:-900}
waited=0
wait_for_lock() {
    local holder said=""
    while holder=$(lock_holder); do
        if [ "$waited" -ge "$wait_limit" ]; then
            echo "setup: gave up after ${wait_limit} s: $holder; let it finish (or stop" \
                 "it if it is stuck) and run this again (BISS_APT_WAIT=seconds to wait longer)" >&2
            exit 1
        fi
        if [ "$holder" != "$said" ]; then
            echo "setup: the package manager is busy: $holder; waiting (up to" \
                 "$((wait_limit - waited)) s more)" >&2
            said=$holder
        fi
        sleep 5
        waited=$((waited + 5))
    done
}
apt() { # apt-get with the wait, and apt's own wait for the dpkg lock for any race after it
    wait_for_lock
    $sudo env DEBIAN_FRONTEND=noninteractive apt-get -o DPkg::Lock::Timeout=$((wait_limit - waited)) "$@"
}

echo "setup: installing ${missing[*]}" >&2
apt update -qq
apt install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
