#!/usr/bin/env bash
# Sets up, builds, and renders the default scene (the paper's Table 1
# torus: 9,360 triangles, 16 layers, 800x600) to pelt.png.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build -j"$(nproc)" >/dev/null
./build/pelt render -o pelt.png "$@"
