#!/usr/bin/env bash
# pelt atlas: draws a PNG of the patches, prints statistics, reuses its
# cache on a second run, and fails clearly on bad input.
set -u
pelt=$1 data=$2 out=$3
fails=0 passes=0
check() { # NAME CONDITION-EXIT-STATUS MESSAGE
  if [ "$2" -eq 0 ]; then echo "ok   $1"; passes=$((passes+1)); else echo "FAIL $1: $3"; fails=$((fails+1)); fi
}
is_png() { [ "$(head -c 8 "$1" | od -An -tx1 | tr -d ' \n')" = "89504e470d0a1a0a" ] && [ "$(stat -c %s "$1")" -gt 1000 ]; }

cache="$out/atlas_cache_test"
rm -rf "$cache" "$out/atlas_tetra.png" "$out/atlas_sphere.png"
o=$("$pelt" atlas "$data/meshes/tetra.off" -o "$out/atlas_tetra.png" --size 256 --cache-dir "$cache" 2>&1); rc=$?
check tetra_runs $rc "exit $rc: $o"
is_png "$out/atlas_tetra.png"; check tetra_png $? "no PNG written"
grep -q "patches" <<<"$o"; check tetra_prints_patches $? "$o"
grep -q "warning: .*no uvs" <<<"$o"; check tetra_warns_no_uvs $? "$o"

o=$("$pelt" atlas sphere --mode patches -o "$out/atlas_sphere.png" --size 256 --cache-dir "$cache" 2>&1); rc=$?
check sphere_patches_runs $rc "exit $rc: $o"
is_png "$out/atlas_sphere.png"; check sphere_png $? "no PNG written"
grep -q "cache *miss" <<<"$o"; check first_run_builds $? "$o"
o=$("$pelt" atlas sphere --mode patches -o "$out/atlas_sphere.png" --size 256 --cache-dir "$cache" 2>&1)
grep -q "cache *hit" <<<"$o"; check second_run_hits_cache $? "$o"

o=$("$pelt" atlas "$out/no_such.off" 2>&1); rc=$?
[ $rc -ne 0 ] && [ $rc -lt 128 ] && grep -q "no_such.off" <<<"$o"; check missing_mesh $? "exit $rc: $o"
o=$("$pelt" atlas sphere --mode bogus 2>&1); rc=$?
[ $rc -ne 0 ] && [ $rc -lt 128 ] && grep -q -- "--mode" <<<"$o"; check bad_mode $? "exit $rc: $o"
o=$("$pelt" atlas "$data/meshes/bad_nan.off" 2>&1); rc=$?
[ $rc -ne 0 ] && [ $rc -lt 128 ] && grep -q "bad_nan.off" <<<"$o"; check corrupt_mesh $? "exit $rc: $o"

echo "$passes passed, $fails failed"
[ $fails -eq 0 ]
