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
# a second run from the start, its first frames one by one (frame 1, the
# first, is the training frame). Its figures are those frames'; biss-sim's
# above are its last frame's, and the firmware measures to 1/8 bit and
# averages 4 frames, so the two may differ by a step: the run says so.
if [ "$#" -eq 0 ]; then
    echo
    echo "a second run from the start, through libbiss: its frames 1..6 (build/host/bissctl read -n 6)."
    echo "The line delay above is biss-sim's last frame's; measured to 1/8 bit (12.5 ns at 10 MHz) and"
    echo "averaged over 4 frames, an early frame's may be a step off. lag=N: a bit is read N MA periods"
    echo "after the clock that made it, at sample_point/8 of the bit."
    build/host/bissctl --profile tidep0022-test-encoder --freq 10000000 --cable-m 10 read -n 6
fi
