#!/usr/bin/env bash
# Sets up, builds and runs every test twice: a normal build and an
# AddressSanitizer+UndefinedBehaviorSanitizer build.
#   scripts/test.sh            both builds
#   scripts/test.sh --quick    normal build only
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh

jobs=$(nproc 2>/dev/null || echo 2)
run() { # build-dir, extra cmake args...
    local dir=$1; shift
    cmake -S . -B "$dir" -DCMAKE_BUILD_TYPE=RelWithDebInfo "$@" >/dev/null
    cmake --build "$dir" -j "$jobs"
    ctest --test-dir "$dir" --output-on-failure -j "$jobs"
}

run build
if [ "${1:-}" != "--quick" ]; then
    run build-sanitize -DBISS_SANITIZE=ON
fi
