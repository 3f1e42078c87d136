#!/usr/bin/env bash
# Sets up, builds with -Werror under AddressSanitizer and
# UndefinedBehaviorSanitizer, and runs every test with CTest.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh --tests
cmake -S . -B build-test -DCMAKE_BUILD_TYPE=RelWithDebInfo -DPELT_WERROR=ON -DPELT_SANITIZE=ON >/dev/null
cmake --build build-test -j"$(nproc)"
cd build-test
ctest --output-on-failure -j"$(nproc)" "$@"
