#!/usr/bin/env bash
# The main job: set up, build, and run the PRU image against the default
# simulated encoder (TIDEP0022 test encoder, 10 MHz, 10 m cable), printing
# timing and writing a VCD and an SVG scope view of one frame.
# Extra arguments go to biss-sim (see: build/emulator/bench/biss-sim --help).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh

jobs=$(nproc 2>/dev/null || echo 2)
cmake -S . -B build -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
cmake --build build -j "$jobs" >/dev/null

build/emulator/bench/biss-sim --profile tidep0022-test-encoder --freq 10000000 --cable-m 10 \
    --frames 1000 --vcd build/demo.vcd --svg build/demo.svg "$@"

# The same firmware and encoder through libbiss, as a host program reads it:
# the first frames one by one (the first is the training frame).
if [ "$#" -eq 0 ]; then
    echo
    echo "first frames through libbiss (build/host/bissctl read -n 6):"
    build/host/bissctl --profile tidep0022-test-encoder --freq 10000000 --cable-m 10 read -n 6
fi
