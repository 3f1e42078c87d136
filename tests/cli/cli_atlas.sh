#!/usr/bin/env bash
# pelt atlas: writes a PNG and prints the stats; a second run with the same
# cache dir loads from the cache; bad input fails naming the file or flag.
set -u
pelt=$1 data=$2 out=$3
fails=0 passes=0
cache="$out/atlas_cache_$$"
rm -rf "$cache"

pass() { echo "ok   $1"; passes=$((passes+1)); }
fail() { echo "FAIL $1"; fails=$((fails+1)); }

# crashed RC ERR: exit >= 128 (signal) or a sanitizer report.
crashed() { [ "$1" -ge 128 ] || grep -q "Sanitizer\|runtime error" <<<"$2"; }

# png_ok FILE: starts with the 8-byte PNG signature and is over 1 KB.
png_ok() {
  [ -f "$1" ] || return 1
  [ "$(head -c 8 "$1" | od -An -tx1 | tr -d ' \n')" = "89504e470d0a1a0a" ] || return 1
  [ "$(wc -c <"$1")" -gt 1024 ]
}

# expect_atlas NAME MESH: exit 0, a PNG, "patches" on stdout; leaves stdout in $stdout.
expect_atlas() {
  local name=$1 mesh=$2 png="$out/atlas_$1.png" err rc
  rm -f "$png"
  stdout=$("$pelt" atlas "$mesh" -o "$png" --size 256 --cache-dir "$cache" 2>"$out/atlas_$1.err"); rc=$?
  err=$(cat "$out/atlas_$1.err")
  if [ $rc -ne 0 ] || crashed $rc "$err"; then fail "$name: exit $rc: $err"; return; fi
  if ! png_ok "$png"; then fail "$name: $png is not a PNG of more than 1 KB"; return; fi
  if ! grep -q "patches" <<<"$stdout"; then fail "$name: no 'patches' in: $stdout"; return; fi
  pass "$name"
}

expect_fail() {
  local name=$1 needle=$2; shift 2
  local err rc
  err=$("$@" 2>&1 >/dev/null); rc=$?
  if [ $rc -eq 0 ]; then fail "$name: exit 0"; return; fi
  if crashed $rc "$err"; then fail "$name: crashed (exit $rc): $err"; return; fi
  if ! grep -qF -- "$needle" <<<"$err"; then fail "$name: message does not name '$needle': $err"; return; fi
  pass "$name: $(head -n1 <<<"$err")"
}

expect_atlas tetra "$data/meshes/tetra.off"
# An OFF file has no uvs: the reason they were not used goes to stderr.
if grep -q "warning: .*uvs" "$out/atlas_tetra.err"; then pass tetra_warns_about_uvs; else fail "tetra_warns_about_uvs: $(cat "$out/atlas_tetra.err")"; fi
if grep -q "cache.*hit" <<<"$stdout"; then fail "tetra_first_run_not_from_cache: $stdout"; else pass tetra_first_run_not_from_cache; fi
expect_atlas tetra_again "$data/meshes/tetra.off"
if grep -q "cache.*hit" <<<"$stdout"; then pass tetra_second_run_from_cache; else fail "tetra_second_run_from_cache: $stdout"; fi

expect_atlas sphere sphere
expect_atlas sphere_again sphere
if grep -q "cache.*hit" <<<"$stdout"; then pass sphere_second_run_from_cache; else fail "sphere_second_run_from_cache: $stdout"; fi

# A cache file cut short (a crash, a full disk, another process): the atlas
# is built again with a warning naming the file, and the next run hits.
for f in "$cache"/atlas-*.bin; do
  cp "$f" "$f.whole"; head -c $(( $(wc -c <"$f.whole") / 2 )) "$f.whole" >"$f"; rm "$f.whole"
done
expect_atlas sphere_truncated_cache sphere
if grep -q "cache.*hit" <<<"$stdout"; then fail "truncated_cache_rebuilt: $stdout"; else pass truncated_cache_rebuilt; fi
if grep -q "warning: atlas cache '$cache/atlas-.*\.bin' is truncated; building the atlas again" \
     "$out/atlas_sphere_truncated_cache.err"; then pass truncated_cache_warns
else fail "truncated_cache_warns: $(cat "$out/atlas_sphere_truncated_cache.err")"; fi
expect_atlas sphere_rewritten_cache sphere
if grep -q "cache.*hit" <<<"$stdout"; then pass rewritten_cache_hits; else fail "rewritten_cache_hits: $stdout"; fi

# --no-cache never reports a hit, even with a warm cache.
stdout=$("$pelt" atlas sphere -o "$out/atlas_nocache.png" --size 64 --no-cache --cache-dir "$cache" 2>/dev/null)
if grep -q "cache.*hit" <<<"$stdout"; then fail "no_cache_rebuilds: $stdout"; else pass no_cache_rebuilds; fi

# Forced patches on the sphere: more than one patch (its own uvs are one).
stdout=$("$pelt" atlas sphere -o "$out/atlas_patches.png" --size 64 --mode patches --no-cache 2>/dev/null)
n=$(sed -n 's/^ *patches *\([0-9]*\).*/\1/p' <<<"$stdout")
if [ -n "$n" ] && [ "$n" -gt 1 ]; then pass "sphere_patch_mode_has_several_patches ($n)"; else fail "sphere_patch_mode_has_several_patches: $stdout"; fi

a="$pelt atlas"
o="-o $out/atlas_bad.png --no-cache"
expect_fail missing_mesh "no_such_mesh.off" $a "$out/no_such_mesh.off" $o
expect_fail corrupt_mesh "bad_garbage.off" $a "$data/meshes/bad_garbage.off" $o
expect_fail no_mesh "mesh" $a $o
expect_fail bad_mode "--mode" $a sphere $o --mode sideways
expect_fail bad_mode_value "sideways" $a sphere $o --mode sideways
expect_fail bad_size "--size" $a sphere $o --size 0
expect_fail bad_direction "--direction" $a sphere $o --direction 1,2
expect_fail bad_density "--density" $a sphere $o --density -1
expect_fail bad_mask_size "--mask-size" $a sphere $o --mask-size lots
expect_fail bad_seed "--seed" $a sphere $o --seed x
expect_fail missing_value "--size" $a sphere --size
expect_fail unknown_flag "--bogus" $a sphere --bogus
expect_fail unwritable_output "atlas_no_dir" $a sphere --no-cache -o "$out/atlas_no_dir/x.png"

err=$("$pelt" atlas --help 2>&1); rc=$?
if [ $rc -eq 0 ] && grep -q -- "--cache-dir" <<<"$err"; then pass help; else fail "help: exit $rc"; fi

rm -rf "$cache"
echo "$passes passed, $fails failed"
[ $fails -eq 0 ]
