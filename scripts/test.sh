#!/usr/bin/env bash
# Sets up, builds with -Werror under AddressSanitizer and
# UndefinedBehaviorSanitizer, and runs every test with CTest.
# Setup installs everything the tests need (Mesa for a GL context, the CGAL
# corpus), so here a skipped test is a failure: without this command's
# setup, run ctest yourself and read its SKIPPED lines.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh --tests
cmake -S . -B build-test -DCMAKE_BUILD_TYPE=RelWithDebInfo -DPELT_WERROR=ON -DPELT_SANITIZE=ON >/dev/null
cmake --build build-test -j"$(nproc)"
cd build-test
log=$(mktemp)
trap 'rm -f "$log"' EXIT
ctest --output-on-failure -j"$(nproc)" "$@" | tee "$log"
if grep -q '\*\*\*Skipped' "$log"; then
  echo "test.sh: tests were skipped although setup installed what they need:" >&2
  grep '\*\*\*Skipped' "$log" >&2
  exit 1
fi
