#!/usr/bin/env bash
# pelt compare: every figure on its named line and in range, the side by
# side picture three pictures wide, the stripe figures follow --fur-px, and
# bad arguments answer with a message that names them and a non-zero exit.
set -u
pelt=$1 data=$2 out=$3
fails=0 passes=0
check() { if [ "$2" -eq 0 ]; then echo "ok   $1"; passes=$((passes+1)); else echo "FAIL $1: $3"; fails=$((fails+1)); fi; }
png_size() { od -An -tu1 -j16 -N8 "$1" | awk '{print $1*16777216+$2*65536+$3*256+$4 "x" $5*16777216+$6*65536+$7*256+$8}'; }
field() { awk -v k="$1" '$1 == k { $1 = ""; sub(/^ /, ""); print }' <<<"$2"; }

d="$out/cli_compare"; rm -rf "$d"; mkdir -p "$d"
# A grazing view of the torus: the rim fills the picture.
view="--size 160x120 --pitch 5 --distance 3"
res=$("$pelt" compare $view -o "$d/side.png" 2>"$d/err.txt"); rc=$?
if [ $rc -ne 0 ] && grep -qi "context\|EGL" "$d/err.txt"; then
  echo "SKIPPED: no OpenGL context: $(cat "$d/err.txt")"; exit 77
fi
check compare_runs $rc "exit $rc: $(cat "$d/err.txt")"
missing=""
for k in reference ssim mae silhouette_px silhouette_shells silhouette_strands stripe_energy_ratio \
         luminance_shells luminance_strands fur_px; do
  [ -n "$(field $k "$res")" ] || missing="$missing $k"
done
[ -z "$missing" ]; check every_figure_on_its_line $? "missing:$missing in: $res"
awk -v s="$(field ssim "$res")" -v m="$(field mae "$res")" \
  'BEGIN { exit !(s > 0 && s < 1 && m > 0 && m < 255) }'
check ssim_and_mae_in_range $? "ssim $(field ssim "$res"), mae $(field mae "$res")"
[ "$(field silhouette_px "$res")" = "1 2 4 8 16 32" ]
check silhouette_bands_1_to_32 $? "got '$(field silhouette_px "$res")'"
awk -v a="$(field silhouette_shells "$res")" 'BEGIN { n = split(a, v, " "); exit !(n == 6 && v[1] > 0.5 && v[1] <= 1) }'
check fur_covers_the_first_pixel $? "silhouette_shells '$(field silhouette_shells "$res")'"
awk -v l="$(field luminance_shells "$res")" 'BEGIN { exit !(l > 0 && l < 255) }'
check luminance_in_range $? "luminance_shells $(field luminance_shells "$res")"
[ "$(png_size "$d/side.png")" = "480x120" ]; check side_picture_is_three_wide $? "got $(png_size "$d/side.png")"

res2=$("$pelt" compare $view --fur-px 40 2>/dev/null); rc=$?
[ $rc -eq 0 ] && [ "$(field fur_px "$res2")" = "40.00" ] && [ "$(field stripe_frequency "$res2")" = "0.8000" ] &&
  [ "$(field ssim "$res2")" = "$(field ssim "$res")" ]
check fur_px_sets_the_stripe_frequency $? "exit $rc: $res2"
[ ! -e "$d/pelt.png" ] && [ ! -e pelt.png ]; check no_picture_without_o $? "a picture was written"

bad() { # name, expected text in the message, args...
  local name=$1 want=$2; shift 2
  local err; err=$("$pelt" compare "$@" 2>&1 >/dev/null); local rc=$?
  [ $rc -ne 0 ] && grep -q -- "$want" <<<"$err"; check "$name" $? "exit $rc, '$err'"
}
bad unknown_flag_is_named "--bogus" --bogus
bad fur_px_needs_a_number "--fur-px 'abc'" --fur-px abc
bad fur_px_must_be_positive "--fur-px '-3'" --fur-px -3
bad fur_px_needs_a_value "--fur-px needs a value" --fur-px
bad frame_pattern_is_refused "not a frame pattern" -o "$d/x_%04d.png"
bad ground_is_refused "ground.enabled" --ground
bad missing_scene_is_named "no_such_scene.json" "$d/no_such_scene.json"
bad tiny_picture_is_refused "22x22" --size 20x20
bad unwritable_output_is_named "cannot write" --size 64x48 -o "$d/no/such/dir/side.png"

echo "$passes passed, $fails failed"
[ $fails -eq 0 ]
