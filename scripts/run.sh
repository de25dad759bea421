#!/usr/bin/env bash
# The main job: set up, build, and run the PRU image against the default
# simulated encoder (TIDEP0022 test encoder, 10 MHz, 10 m cable), printing
# timing and writing a VCD and an SVG scope view of one frame.
# Extra arguments go to biss-sim (see: build/emulator/bench/biss-sim --help).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh

# Only what this script runs: the firmware image, biss-sim and bissctl (the
# tests are scripts/test.sh's). Quiet unless something fails.
jobs=$(nproc 2>/dev/null || echo 2)
log=$(mktemp)
trap 'rm -f "$log"' EXIT
step() { # step MESSAGE COMMAND...: says what it does; shows the output if it fails
    local what=$1
    shift
    echo "run: $what" >&2
    if ! "$@" >"$log" 2>&1; then
        cat "$log" >&2
        echo "run: failed: $what" >&2
        exit 1
    fi
}
step "configuring build/ (cmake)" cmake -S . -B build -DCMAKE_BUILD_TYPE=RelWithDebInfo
step "building the firmware image, biss-sim and bissctl" \
    cmake --build build -j "$jobs" --target biss_master biss_master_pru1 biss-sim bissctl
echo "run: running 1000 frames against the default encoder" >&2

build/emulator/bench/biss-sim --profile tidep0022-test-encoder --freq 10000000 --cable-m 10 \
    --frames 1000 --vcd build/demo.vcd --svg build/demo.svg "$@"

# The same firmware and encoder through libbiss, as a host program reads it:
# the first frames one by one (frame 1, the first, is the training frame).
if [ "$#" -eq 0 ]; then
    echo
    echo "first frames through libbiss (build/host/bissctl read -n 6):"
    build/host/bissctl --profile tidep0022-test-encoder --freq 10000000 --cable-m 10 read -n 6
fi
