#!/usr/bin/env bash
# Installs the Debian packages pelt needs, only those that are missing.
#   scripts/setup.sh          build and render
#   scripts/setup.sh --tests  also what the tests use: Debian's libcgal-demo meshes,
#                             ffmpeg (video output), man-db (the manual page) and
#                             dpkg-dev and file (the .deb: dpkg-deb, dpkg-shlibdeps),
#                             xvfb and xauth (pelt view in a window, tests/cli/cli_view.sh),
#                             python3 (scripts/subdivide-off.py, tests/cli/cli_lod_elephant.sh)
set -euo pipefail

packages=(build-essential cmake pkg-config
          libepoxy-dev libegl-dev libegl-mesa0 libgl1-mesa-dri libgbm1
          libglfw3-dev libassimp-dev libstb-dev libcjson-dev libmeshoptimizer-dev)
if [ "${1:-}" = "--tests" ]; then
  packages+=(libcgal-demo assimp-testmodels ffmpeg man-db dpkg-dev file xvfb xauth python3)
fi

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done
if [ ${#missing[@]} -eq 0 ]; then
  exit 0
fi

echo "setup: installing ${missing[*]}" >&2
sudo=""
if [ "$(id -u)" != 0 ]; then sudo="sudo"; fi
export DEBIAN_FRONTEND=noninteractive
$sudo apt-get update -qq
$sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
