#!/usr/bin/env bash
# The soak: a long animation (rain, drying, gusts, a turntable, comb
# strokes, droplets by ray) on a tiny image, checking that no strand, groom
# or mask value becomes NaN or infinite, that GL raises no error and that
# resident memory stays flat after the warm-up. Prints RSS at the start
# and the end and steps per second.
#   scripts/soak.sh [STEPS [SIZE]]   default 100000 steps at 32 x 24
# A plain optimised build (build-soak), so the memory is pelt's and Mesa's,
# not a sanitizer's; CTest runs 1,000 steps under ASan and UBSan
# (soak_short). LP_NUM_THREADS=1 keeps llvmpipe on one core.
set -euo pipefail
cd "$(dirname "$0")/.."
steps=${1:-100000}
size=${2:-32}
scripts/setup.sh
cmake -S . -B build-soak -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
cmake --build build-soak -j2 --target pelt_soak >/dev/null
LP_NUM_THREADS=${LP_NUM_THREADS:-1} build-soak/tests/pelt_soak "$steps" "$size"
