#!/usr/bin/env bash
# Builds the libFuzzer targets of tests/fuzz with clang under AddressSanitizer
# and UndefinedBehaviorSanitizer and runs them.
#   scripts/fuzz.sh                    every target, 60 seconds each
#   scripts/fuzz.sh fuzz_scene 300     one target, 300 seconds
#   scripts/fuzz.sh all 90             every target, 90 seconds each
# Each run starts from the target's corpus in tests/fuzz/corpus (read only;
# what libFuzzer finds goes to build-fuzz/corpus/TARGET) and writes its log
# to build-fuzz/logs/TARGET.log. A crash, leak or hang lands in
# build-fuzz/artifacts/TARGET/: fix it, then copy the file to
# tests/fuzz/crashes/TARGET/ so CTest replays it for ever.
set -euo pipefail
cd "$(dirname "$0")/.."
root=$PWD
target=${1:-all}
seconds=${2:-60}

scripts/setup.sh
need=()
for p in clang libclang-rt-14-dev; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || need+=("$p")
done
if [ ${#need[@]} -gt 0 ]; then
  echo "fuzz: installing ${need[*]}" >&2
  sudo=""
  if [ "$(id -u)" != 0 ]; then sudo="sudo"; fi
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${need[@]}" >/dev/null
fi

build=$root/build-fuzz
CC=clang cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DPELT_SANITIZE=ON \
  -DPELT_FUZZ=ON >/dev/null
# The targets are what tests/CMakeLists.txt declares with pelt_fuzz.
all=$(cmake --build "$build" --target help | sed -n 's/^\.\.\. \(fuzz_[a-z_]*\)$/\1/p' \
      | grep -v '_replay$' | sort)
if [ "$target" = all ]; then
  targets=$all
elif echo "$all" | grep -qx "$target"; then
  targets=$target
else
  echo "fuzz: no target '$target'; there are: $(echo $all)" >&2
  exit 2
fi
# shellcheck disable=SC2086
cmake --build "$build" -j2 --target $targets >/dev/null

export ASAN_OPTIONS=detect_leaks=1:allocator_may_return_null=1
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
export LSAN_OPTIONS=suppressions=$root/tests/support/lsan.supp:print_suppressions=0
status=0
printf '%-18s %8s %10s %8s %8s %s\n' target seconds execs cov ft crashes
for t in $targets; do
  mkdir -p "$build/corpus/$t" "$build/artifacts/$t" "$build/logs"
  log=$build/logs/$t.log
  start=$(date +%s)
  set +e
  (cd "$build/tests" && ./"$t" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 \
     -max_len=65536 -print_final_stats=1 -artifact_prefix="$build/artifacts/$t/" \
     "$build/corpus/$t" "$root/tests/fuzz/corpus/$t") >"$log" 2>&1
  rc=$?
  set -e
  took=$(( $(date +%s) - start ))
  execs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)
  last=$(grep -E '^#[0-9]+.*cov: ' "$log" | tail -1 || true)
  cov=$(echo "$last" | sed -n 's/.*cov: \([0-9]*\).*/\1/p')
  ft=$(echo "$last" | sed -n 's/.*ft: \([0-9]*\).*/\1/p')
  crashes=$(find "$build/artifacts/$t" -type f | wc -l)
  printf '%-18s %8s %10s %8s %8s %s\n' "$t" "$took" "${execs:-?}" "${cov:-?}" "${ft:-?}" "$crashes"
  if [ $rc -ne 0 ] || [ "$crashes" -gt 0 ]; then
    status=1
    echo "fuzz: $t stopped (exit $rc); see $log and $build/artifacts/$t/" >&2
  fi
done
exit $status
