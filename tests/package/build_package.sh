#!/usr/bin/env bash
# Fixture of the package tests: pelt built as a user or Debian would build
# it (Release, no sanitizers, no tests, prefix /usr) in OUT/build, and
# installed with `cmake --install --prefix OUT/prefix`.
#   build_package.sh SOURCE_DIR OUT
set -eu
src=$1 out=$2
mkdir -p "$out"
rm -rf "$out/prefix"
# The test build's sanitizer and warning flags are CMake options there, not
# environment; clear any from the environment too so this build is plain.
unset CFLAGS LDFLAGS
cmake -S "$src" -B "$out/build" -DCMAKE_BUILD_TYPE=Release -DPELT_BUILD_TESTS=OFF \
      -DPELT_SANITIZE=OFF -DCMAKE_INSTALL_PREFIX=/usr >"$out/configure.log" 2>&1 ||
  { cat "$out/configure.log"; exit 1; }
cmake --build "$out/build" -j2 >"$out/build.log" 2>&1 || { cat "$out/build.log"; exit 1; }
cmake --install "$out/build" --prefix "$out/prefix" >"$out/install.log" 2>&1 ||
  { cat "$out/install.log"; exit 1; }
echo "built and installed into $out/prefix"
