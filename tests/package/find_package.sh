#!/usr/bin/env bash
# examples/minimal.c built against an installed pelt, as users build it:
#   find_package.sh cmake      PREFIX SOURCE_DIR OUT   find_package(pelt CONFIG REQUIRED)
#   find_package.sh pkg-config PREFIX SOURCE_DIR OUT   cc ... $(pkg-config --cflags --libs pelt)
# Each program must run and draw; the shared one must load libpelt.so from
# PREFIX, the static one must not need it; a version pelt is not must fail.
set -u
mode=$1 prefix=$2 src=$3 out=$4
fails=0 passes=0
check() { if [ "$2" -eq 0 ]; then echo "ok   $1"; passes=$((passes+1)); else echo "FAIL $1: $3"; fails=$((fails+1)); fi; }
needed() { readelf -d "$1" 2>/dev/null | sed -n 's/.*(NEEDED).*\[\(.*\)\]/\1/p' | tr '\n' ' '; }
example=$src/examples/minimal.c
version=$(sed -n 's/^project(pelt VERSION \([0-9.]*\).*/\1/p' "$src/CMakeLists.txt")

# The program draws 30 frames into a headless context and says so.
runs() {
  local name=$1 exe=$2 log
  log=$("$exe" 2>&1); local rc=$?
  [ $rc -eq 0 ] && grep -q "drew 30 frames" <<<"$log"
  check "${name}_runs" $? "exit $rc: $log"
}

case $mode in
cmake)
  d="$out/consumer"; rm -rf "$d"
  cmake -S "$src/tests/package/consumer" -B "$d" -DCMAKE_PREFIX_PATH="$prefix" \
        -DPELT_EXAMPLE="$example" >"$out/consumer-configure.log" 2>&1
  check configure_finds_pelt $? "$(tail -20 "$out/consumer-configure.log")"
  found=$(sed -n 's/^-- found pelt \([^ ]*\) in \(.*\)/\1 \2/p' "$out/consumer-configure.log")
  case "$found" in "$version $prefix"/*) r=0 ;; *) r=1 ;; esac
  check found_this_version_in_the_prefix $r "found '$found', wanted $version under $prefix"
  cmake --build "$d" -j2 >"$out/consumer-build.log" 2>&1
  check consumer_builds $? "$(tail -20 "$out/consumer-build.log")"
  for t in shared static layers; do runs "minimal_$t" "$d/minimal_$t"; done
  grep -q "libpelt.so.0" <<<"$(needed "$d/minimal_shared")"
  check shared_links_libpelt_so $? "NEEDED: $(needed "$d/minimal_shared")"
  ! grep -q "libpelt" <<<"$(needed "$d/minimal_static")"
  check static_needs_no_libpelt_so $? "NEEDED: $(needed "$d/minimal_static")"
  lib=$(LD_TRACE_LOADED_OBJECTS=1 "$d/minimal_shared" 2>/dev/null | sed -n 's/.*libpelt.so.0 => \([^ ]*\).*/\1/p')
  case "$lib" in "$prefix"/*) r=0 ;; *) r=1 ;; esac
  check shared_loads_the_installed_library $r "libpelt.so.0 => '$lib'"
  # Asked for a version this is not, find_package must refuse.
  cmake -S "$src/tests/package/consumer" -B "$out/consumer-99" -DCMAKE_PREFIX_PATH="$prefix" \
        -DPELT_EXAMPLE="$example" -DPELT_WANTED=99.0 >"$out/consumer-99.log" 2>&1; rc=$?
  [ $rc -ne 0 ] && grep -q "version: $version" "$out/consumer-99.log"
  check version_99_is_refused $? "exit $rc"
  rm -rf "$out/consumer-99"
  ;;
pkg-config)
  pc=$(find "$prefix" -name pelt.pc -path '*/pkgconfig/*' | head -1)
  [ -n "$pc" ]; check pc_file_installed $? "no pelt.pc under $prefix"
  export PKG_CONFIG_PATH=$(dirname "$pc")
  [ "$(pkg-config --modversion pelt 2>&1)" = "$version" ]
  check pc_version $? "pkg-config --modversion pelt: $(pkg-config --modversion pelt 2>&1)"
  flags=$(pkg-config --cflags --libs pelt 2>&1); check pc_flags $? "$flags"
  libdir=$(pkg-config --variable=libdir pelt)
  case "$(cd "$libdir" 2>/dev/null && pwd -P)" in "$(cd "$prefix" && pwd -P)"/*) r=0 ;; *) r=1 ;; esac
  check pc_points_into_the_prefix $r "libdir=$libdir"
  # shellcheck disable=SC2086
  cc -std=c11 "$example" -o "$out/minimal_pc" $flags -Wl,-rpath,"$libdir" >"$out/pc-build.log" 2>&1
  check pc_builds $? "$(cat "$out/pc-build.log")"
  runs minimal_pc "$out/minimal_pc"
  ;;
*) echo "usage: find_package.sh cmake|pkg-config PREFIX SOURCE_DIR OUT" >&2; exit 2 ;;
esac
echo "$passes passed, $fails failed"
[ $fails -eq 0 ]
