#!/usr/bin/env bash
# pelt in the browser (docs/web.md): sets up and builds build-web/pelt.html,
# .js, .wasm and .data with Debian's Emscripten.
#   scripts/web.sh          build
#   scripts/web.sh --serve  build, then serve it on http://127.0.0.1:8000/pelt.html
#   scripts/web.sh --test [PELT [OUT]]
#                           build, then run the browser test (tests/web/web_test.py)
#                           against the native pelt PELT (default: a Release
#                           build/pelt, built here), pictures in OUT
#                           (default build-web/test)
# Installs what is missing (Debian packages: emscripten, the native -dev
# packages whose sources the wasm libraries are built from, dpkg-dev for
# dpkg-source, chromium-headless-shell for --test); the wasm libraries
# come from Debian's source packages (scripts/web-deps.sh).
set -euo pipefail
cd "$(dirname "$0")/.."
mode=${1:-}
test_pelt=${2:-}
test_out=${3:-build-web/test}
case "$mode" in
  ""|--serve|--test) ;;
  *) echo "usage: scripts/web.sh [--serve|--test]" >&2; exit 2 ;;
esac

t0=$(date +%s)
packages=(emscripten cmake dpkg-dev libstb-dev libcjson-dev libmeshoptimizer-dev libassimp-dev
          zlib1g-dev libminizip-dev libutfcpp-dev python3)
if [ "$mode" = --test ]; then
  # The test compares the page with the native `pelt render` of the scene.
  packages+=(chromium-headless-shell build-essential pkg-config libepoxy-dev libegl-dev libegl-mesa0
             libgl1-mesa-dri libgbm1 libglfw3-dev)
fi
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "web: installing ${missing[*]}" >&2
  sudo=""
  [ "$(id -u)" = 0 ] || sudo=sudo
  export DEBIAN_FRONTEND=noninteractive
  $sudo apt-get update -qq
  $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

# Debian's emcc runs acorn (node-acorn) from Debian's node modules, which a
# Node.js from elsewhere on the PATH does not look in.
export NODE_PATH=/usr/share/nodejs${NODE_PATH:+:$NODE_PATH}
scripts/web-deps.sh build-web/deps
emcmake cmake -S . -B build-web -DCMAKE_BUILD_TYPE=Release -DPELT_WERROR=ON \
  -DPELT_WEB_DEPS="$PWD/build-web/deps" >/dev/null
cmake --build build-web -j"$(nproc)"
echo "web: build-web/pelt.html, .js, .wasm, .data in $(( $(date +%s) - t0 )) s" >&2

case "$mode" in
  --serve)
    echo "web: http://127.0.0.1:8000/pelt.html (Ctrl+C stops)" >&2
    exec python3 -m http.server 8000 --bind 127.0.0.1 --directory build-web ;;
  --test)
    if [ -z "$test_pelt" ]; then
      cmake -S . -B build -DCMAKE_BUILD_TYPE=Release >/dev/null
      cmake --build build -j"$(nproc)" --target pelt
      test_pelt=build/pelt
    fi
    exec python3 tests/web/web_test.py --web build-web --pelt "$test_pelt" --out "$test_out" ;;
esac
