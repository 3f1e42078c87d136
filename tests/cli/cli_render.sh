#!/usr/bin/env bash
# pelt render: the image is exactly the size asked for; an animation writes
# one PNG per frame and prints no progress when stderr is not a terminal;
# the frames of a moving scene differ; --mask-out writes the mask.
set -u
pelt=$1 data=$2 out=$3
fails=0 passes=0
check() { if [ "$2" -eq 0 ]; then echo "ok   $1"; passes=$((passes+1)); else echo "FAIL $1: $3"; fails=$((fails+1)); fi; }
png_size() { od -An -tu1 -j16 -N8 "$1" | awk '{print $1*16777216+$2*65536+$3*256+$4 "x" $5*16777216+$6*65536+$7*256+$8}'; }

d="$out/cli_render"; rm -rf "$d"; mkdir -p "$d"
"$pelt" render --size 123x77 -o "$d/still.png" 2>/dev/null; check still_runs $? "non-zero exit"
[ "$(png_size "$d/still.png")" = "123x77" ]; check still_has_the_size_asked $? "got $(png_size "$d/still.png")"

err=$("$pelt" render --size 64x48 --frames 4 --fps 10 --turntable 180 --wind 20,0,0 -o "$d/f_%03d.png" 2>&1 >/dev/null)
check animation_runs $? "$err"
n=$(ls "$d"/f_*.png 2>/dev/null | wc -l); [ "$n" -eq 4 ]; check four_frames_written $? "got $n files"
[ -z "$err" ]; check no_progress_without_a_terminal $? "stderr: $err"
[ -f "$d/f_000.png" ] && [ -f "$d/f_003.png" ] && ! cmp -s "$d/f_000.png" "$d/f_003.png"
check turning_frames_differ $? "first and last frames are identical"

"$pelt" render --size 64x48 --drops 20 --set wetness.mask_size=128 --mask-out "$d/mask.png" -o "$d/wet.png" 2>/dev/null
check mask_out_runs $? "non-zero exit"
[ "$(png_size "$d/mask.png")" = "128x128" ]; check mask_has_the_mask_size $? "got $(png_size "$d/mask.png")"

"$pelt" render scenes_missing.json -o "$d/x.png" 2>/dev/null; rc=$?
[ $rc -ne 0 ]; check missing_scene_fails $? "exit $rc"

# A droplet under a pixel: the torus at (20, 25) of a 64x48 image is fur,
# the corner (0, 0) is background.
"$pelt" render --size 64x48 -o "$d/dry.png" 2>/dev/null
err=$("$pelt" render -q --size 64x48 --drop-at 20,25,0.3 -o "$d/hit.png" 2>&1); rc=$?
[ $rc -eq 0 ] && [ -z "$err" ] && ! cmp -s "$d/dry.png" "$d/hit.png"
check drop_at_a_pixel_wets_the_fur $? "exit $rc, '$err', or no change"
err=$("$pelt" render -q --size 64x48 --drop-at 0,0,0.3 -o "$d/miss.png" 2>&1); rc=$?
[ $rc -eq 0 ] && grep -q "misses" <<<"$err" && cmp -s "$d/dry.png" "$d/miss.png"
check drop_at_background_misses $? "exit $rc, '$err'"
err=$("$pelt" render --size 64x48 --drop-at 1,2 -o "$d/x.png" 2>&1); rc=$?
[ $rc -ne 0 ] && grep -q -- "--drop-at" <<<"$err"
check drop_at_needs_three_numbers $? "exit $rc, '$err'"

# Grooming: scripted strokes change the picture; saved with --save-groom
# and loaded with --set fur.groom (and the --groom flag), the groom renders
# the same picture byte for byte without the strokes.
strokes='[{"tool":"density","pixel":[20,25],"radius":0.3,"amount":0},
          {"tool":"comb","pixel":[44,26],"radius":0.4,"drag":[6,0]},
          {"tool":"color","pixel":[32,36],"radius":0.4,"color":[0.9,0.9,0.95]}]'
"$pelt" render -q --size 64x48 --set "strokes=$strokes" --save-groom "$d/strokes.groom.ply" \
  -o "$d/groomed.png" 2>/dev/null
check strokes_render $? "non-zero exit"
! cmp -s "$d/dry.png" "$d/groomed.png"; check strokes_change_the_picture $? "same as ungroomed"
"$pelt" render -q --size 64x48 --set fur.groom="$d/strokes.groom.ply" -o "$d/reloaded.png" 2>/dev/null &&
  cmp -s "$d/groomed.png" "$d/reloaded.png"
check saved_groom_renders_the_same $? "differs from the groomed picture"
"$pelt" render -q --size 64x48 --groom "$d/strokes.groom.ply" -o "$d/reloaded2.png" 2>/dev/null &&
  cmp -s "$d/groomed.png" "$d/reloaded2.png"
check groom_flag_is_the_key $? "differs from the groomed picture"

# No EGL driver at all (glvnd pointed at nothing): a clear error that says
# what is missing, and no image.
err=$(__EGL_VENDOR_LIBRARY_FILENAMES=/nonexistent.json "$pelt" render --size 64x48 -o "$d/none.png" 2>&1); rc=$?
[ $rc -ne 0 ] && [ $rc -lt 128 ] && grep -q "EGL" <<<"$err" && [ ! -e "$d/none.png" ]
check no_egl_driver_is_a_clear_error $? "exit $rc: $err"

echo "$passes passed, $fails failed"
[ $fails -eq 0 ]
