#!/usr/bin/env bash
# pelt view in a real window under Xvfb (Debian xvfb): without a display it
# says so; the window's pixels equal render's; a scripted click wets the fur
# under the cursor and nowhere else; a comb stroke leans the hair along the
# stroke under the brush only; the hair dryer brings the dry picture back; a
# corrupt mesh dropped on the window leaves it running with render's message
# in the HUD; a groom saved from the window renders the same in render; the
# scene reloads when its file changes. Skips (77) without Xvfb.
#   cli_view.sh PELT PNG_DIFF PNG_REGION DATA_DIR OUT_DIR
set -u
pelt=$1 png_diff=$2 region=$3 data=$4 out=$5
fails=0 passes=0
check() { if [ "$2" -eq 0 ]; then echo "ok   $1"; passes=$((passes+1)); else echo "FAIL $1: $3"; fails=$((fails+1)); fi; }
# value KEY "k1=v1 k2=v2": v of KEY
value() { tr ' ' '\n' <<<"$2" | sed -n "s/^$1=//p"; }
# awk-true: cond A OP B on decimals
is() { awk -v a="$1" -v b="$3" "BEGIN { exit !(a $2 b) }"; }

d="$out/cli_view"; rm -rf "$d"; mkdir -p "$d"

# Without a display: a clear message and a non-zero exit, before any work.
err=$(env -u DISPLAY -u WAYLAND_DISPLAY "$pelt" view 2>&1); rc=$?
[ $rc -ne 0 ] && grep -q "no display" <<<"$err"; check no_display_says_so $? "exit $rc: $err"

if ! command -v Xvfb >/dev/null; then
  echo "SKIP: Xvfb is not installed (Debian package xvfb; scripts/setup.sh --tests installs it)"
  [ $fails -eq 0 ] || exit 1
  exit 77
fi
# One X server for every run; -displayfd says which display it took.
Xvfb -displayfd 3 -screen 0 1024x768x24 -nolisten tcp 3>"$d/display" 2>"$d/xvfb.log" &
xpid=$!
trap 'kill $xpid 2>/dev/null; wait $xpid 2>/dev/null' EXIT
for _ in $(seq 100); do [ -s "$d/display" ] && break; sleep 0.1; done
if [ ! -s "$d/display" ]; then
  echo "FAIL xvfb_starts: $(cat "$d/xvfb.log")"
  exit 1
fi
export DISPLAY=":$(head -1 "$d/display")"
echo "Xvfb on $DISPLAY"

size=320x240
# Single-sampled: MSAA resolves the window's framebuffer and render's a little
# differently (0.7 levels), more than the key tests' 0.4 below.
# LeakSanitizer's own thread-stopping tracer crashes at exit now and then
# ("Tracer caught signal 11 ... LeakSanitizer has encountered a fatal
# error": a sanitizer flake, not a leak, which reads "detected memory
# leaks"; scripts/docs-images.sh has the same). It comes in bursts: 4 to 5
# runs in 30 of `pelt view --frames 1` here, as often before the browser
# build as after, then five in a row. A run that ends so runs again; after
# two such crashes, once more with the leak check off (every other run of
# the viewer in this test keeps it), and it says so in the test's log
# (fd 3, even inside $(...)); stderr goes where the caller sends it.
exec 3>&1
view() {
  local err tries=0 rc asan=${ASAN_OPTIONS:-}
  err=$(mktemp)
  while :; do
    ASAN_OPTIONS=$asan "$pelt" view --size $size --msaa 0 "$@" 2>"$err"; rc=$?
    if [ $rc -ne 0 ] && [ $tries -lt 2 ] &&
       grep -q 'LeakSanitizer has encountered a fatal error' "$err"; then
      tries=$((tries + 1))
      if [ $tries -eq 2 ]; then
        asan="${asan:+$asan:}detect_leaks=0"
        echo "  (LeakSanitizer's tracer crashed at exit twice, not a leak: once more without the leak check)" >&3
      else
        echo "  (LeakSanitizer's tracer crashed at exit, not a leak: running it again)" >&3
      fi
      continue
    fi
    cat "$err" >&2
    rm -f "$err"
    return $rc
  done
}
# The front of the ring at 320x240, and the brush's radius there in pixels
# (5% of the torus's diagonal, 0.2 world units, at distance 4.2, fov 40: 16 px).
cx=160 cy=180 r=16

# (i) A still: the window's pixels are render's.
"$pelt" render -q --size $size --msaa 0 -o "$d/render.png"
view --no-hud --frames 1 --screenshot-at "0:$d/still.png" 2>"$d/still.err"
check still_runs $? "$(cat "$d/still.err")"
res=$("$png_diff" "$d/render.png" "$d/still.png"); rc=$?
check still_equals_render $rc "$res"

# The dry reference of the scripted runs: fixed 1/30 s steps, no input.
printf '0.3 screenshot %s\n3.0 screenshot %s\n3.0 exit\n' "$d/dry.png" "$d/dry_3s.png" >"$d/dry.txt"
view --no-hud --script "$d/dry.txt" 2>/dev/null; check dry_reference_runs $? ""
res=$("$png_diff" "$d/render.png" "$d/dry.png"); rc=$?
check dry_fur_holds_still $rc "$res"

# (ii) A click with the water tool: a clump under the cursor, nothing elsewhere.
printf '0 key 1\n0 click %s %s\n0.3 screenshot %s\n0.3 exit\n' $cx $cy "$d/wet.png" >"$d/wet.txt"
view --no-hud --script "$d/wet.txt" 2>/dev/null; check click_runs $? ""
res=$("$region" "$d/dry.png" "$d/wet.png" $cx $cy $r); echo "  wet vs dry: $res"
is "$(value inside_frac "$res")" '>' 0.15 && is "$(value inside_mean "$res")" '>' 15
check click_wets_under_the_cursor $? "$res"
is "$(value outside_frac "$res")" '<' 0.002; check click_wets_nowhere_else $? "$res"

# (iii) A comb stroke to the right, and one to the left: the hair under the
# brush leans along the stroke (its streaks tilt from vertical towards the
# stroke), the rest stays.
printf '0 key 3\n0 drag %s %s %s %s 0.2\n0.3 screenshot %s\n0.3 exit\n' \
  $((cx - 15)) $cy $((cx + 15)) $cy "$d/comb_right.png" >"$d/comb_right.txt"
printf '0 key 3\n0 drag %s %s %s %s 0.2\n0.3 screenshot %s\n0.3 exit\n' \
  $((cx + 15)) $cy $((cx - 15)) $cy "$d/comb_left.png" >"$d/comb_left.txt"
view --no-hud --script "$d/comb_right.txt" 2>/dev/null &&
  view --no-hud --script "$d/comb_left.txt" 2>/dev/null; check comb_runs $? ""
a0=$(value axis "$("$region" --axis "$d/dry.png" $cx $cy $r)")
ar=$(value axis "$("$region" --axis "$d/comb_right.png" $cx $cy $r)")
al=$(value axis "$("$region" --axis "$d/comb_left.png" $cx $cy $r)")
echo "  hair axis (degrees, 90 = hanging down): dry $a0, combed right $ar, combed left $al"
is "$a0" '>' 75 && is "$a0" '<' 105; check dry_hair_hangs_down $? "axis $a0"
is "$ar" '<' 70 && is "$al" '>' 110; check comb_leans_along_the_stroke $? "right $ar, left $al"
res=$("$region" "$d/dry.png" "$d/comb_right.png" $cx $cy 32); echo "  combed vs dry: $res"
is "$(value outside_frac "$res")" '<' 0.005; check comb_only_under_the_brush $? "$res"

# (iv) Wet the spot, then hold the hair dryer over it: once its air has
# passed, the dry picture is back.
printf '0 key 1\n0 click %s %s\n0.2 screenshot %s\n0.2 key 2\n0.3 hold %s %s 0.8\n0.8 screenshot %s\n3.0 screenshot %s\n3.0 exit\n' \
  $cx $cy "$d/before_dryer.png" $cx $cy "$d/drying.png" "$d/dried.png" >"$d/dryer.txt"
view --no-hud --script "$d/dryer.txt" 2>/dev/null; check dryer_runs $? ""
res=$("$region" "$d/dry.png" "$d/before_dryer.png" $cx $cy $r)
is "$(value inside_mean "$res")" '>' 15; check wet_before_the_dryer $? "$res"
res=$("$region" "$d/dry.png" "$d/drying.png" $cx $cy $((2 * r))); echo "  drying vs dry: $res"
is "$(value outside_frac "$res")" '<' 0.005; check dryer_air_is_local $? "$res"
res=$("$png_diff" "$d/dry_3s.png" "$d/dried.png"); rc=$?
check dryer_brings_back_the_dry_picture $rc "$res"

# (v) A corrupt mesh dropped on the window: render's message in the HUD
# (red), on stderr, and the window keeps running (a later screenshot).
bad="$data/meshes/bad_garbage.obj"
# A second drop: a missing file whose long UTF-8 path makes a message
# longer than the HUD's text runs.
e120=$(printf 'é%.0s' $(seq 120))
printf '0.1 drop %s\n0.2 screenshot %s\n0.3 drop %s\n0.5 screenshot %s\n0.5 exit\n' "$bad" "$d/bad.png" \
  "$d/$e120/$e120/missing.obj" "$d/bad_later.png" >"$d/bad.txt"
err=$(view --script "$d/bad.txt" 2>&1); rc=$?
check bad_drop_keeps_running $rc "exit $rc: $err"
[ -f "$d/bad_later.png" ]; check bad_drop_window_still_draws $? "no screenshot after the drop"
want=$("$pelt" render -q --size 32x24 --mesh "$bad" -o "$d/x.png" 2>&1 | sed 's/^pelt render: //')
grep -qF "pelt view: $want" <<<"$err"; check bad_drop_says_what_render_says $? "render: $want
view: $err"
reds=$(value red "$("$region" --red "$d/bad.png" 0 0 320 140)")
is "$reds" '>' 200; check bad_drop_message_in_the_hud $? "$reds red pixels in the HUD"
reds=$(value red "$("$region" --red "$d/bad_later.png" 0 0 320 140)")
is "$reds" '>' 200; check bad_drop_message_stays $? "$reds red pixels in the HUD"

# (vi) A groom combed in the window and saved (Ctrl+S, --save-groom) renders
# the same in pelt render --groom.
printf '0 key 3\n0 drag %s %s %s %s 0.2\n0.3 key ctrl+s\n0.4 screenshot %s\n0.4 exit\n' \
  $((cx - 15)) $cy $((cx + 15)) $cy "$d/groomed_view.png" >"$d/groom.txt"
view --no-hud --save-groom "$d/groom.ply" --script "$d/groom.txt" 2>/dev/null
check save_groom_runs $? ""
[ -s "$d/groom.ply" ]; check groom_saved $? "no $d/groom.ply"
"$pelt" render -q --size $size --msaa 0 --groom "$d/groom.ply" -o "$d/groomed_render.png"
res=$("$png_diff" "$d/groomed_view.png" "$d/groomed_render.png"); rc=$?
check saved_groom_renders_the_same $rc "$res"
res=$("$region" "$d/dry.png" "$d/groomed_render.png" $cx $cy $r)
is "$(value inside_mean "$res")" '>' 5; check saved_groom_is_combed $? "$res"

# The camera: the wheel zooms, a right drag orbits, a middle drag pans;
# each changes the picture.
printf '0 scroll 3\n0.1 screenshot %s\n0.1 drag 100 60 160 60 0.1 right\n0.3 screenshot %s\n0.3 drag 100 60 140 60 0.1 middle\n0.5 screenshot %s\n0.5 exit\n' \
  "$d/zoom.png" "$d/orbit.png" "$d/pan.png" >"$d/camera.txt"
view --no-hud --script "$d/camera.txt" 2>/dev/null; check camera_runs $? ""
! "$png_diff" "$d/dry.png" "$d/zoom.png" >/dev/null && ! "$png_diff" "$d/zoom.png" "$d/orbit.png" >/dev/null &&
  ! "$png_diff" "$d/orbit.png" "$d/pan.png" >/dev/null
check zoom_orbit_pan_move_the_view $? "a camera move left the picture as it was"

# Keys: the towel dries a wet spot at once; screenshots go to -o; layers,
# curl presets and level of detail (on by default, L turns it off) say what they did.
printf '0 key 1\n0 click %s %s\n0.2 key t\n0.3 screenshot %s\n0.3 key p\n0.4 key up\n0.5 key c\n0.6 key l\n0.7 exit\n' \
  $cx $cy "$d/towel.png" >"$d/keys.txt"
err=$(view --no-hud -o "$d/key_shot_%d.png" --script "$d/keys.txt" 2>&1); check keys_run $? "$err"
res=$("$png_diff" "$d/dry.png" "$d/towel.png"); check towel_dries_all $? "$res"
[ -s "$d/key_shot_0.png" ]; check screenshot_key_writes_the_output $? "no $d/key_shot_0.png"
grep -q "64 layers" <<<"$err"; check layers_double $? "$err"
grep -q "curl straight" <<<"$err"; check curl_preset_cycles $? "$err"
grep -q "level of detail off" <<<"$err"; check lod_switches_off $? "$err"

# F and S switch the fins and Kenwright's inter-fur shadows: the window
# then equals render with --no-fins, and with --no-fins --inter-shadow.
# The shadows change the picture by a mean of about 0.9 levels, within
# png_diff's default tolerance: these compare at a mean of 0.4. The window
# and render draw the same settings 0.27-0.32 levels apart single-sampled
# (0.27 with fur.edge_depth 1, 0.30-0.32 since its default is 16: the
# edge-on shells are more opaque there); the switches change the picture
# by 0.9 (fins), 1.2 (inter-fur shadows) and 4.0 levels (the light's).
printf '0.1 key f\n0.1 screenshot %s\n0.2 key s\n0.2 screenshot %s\n0.2 exit\n' \
  "$d/no_fins.png" "$d/shadows.png" >"$d/passes.txt"
view --no-hud --script "$d/passes.txt" 2>/dev/null; check passes_run $? ""
"$pelt" render -q --size $size --msaa 0 --no-fins -o "$d/render_no_fins.png"
"$pelt" render -q --size $size --msaa 0 --no-fins --inter-shadow -o "$d/render_shadows.png"
! "$png_diff" "$d/render.png" "$d/render_no_fins.png" --max-mean 0.4 >/dev/null &&
  ! "$png_diff" "$d/render_no_fins.png" "$d/render_shadows.png" --max-mean 0.4 >/dev/null
check fins_and_shadows_change_the_picture $? "render's pictures with and without them are alike"
res=$("$png_diff" "$d/render_no_fins.png" "$d/no_fins.png" --max-mean 0.4); check key_f_is_no_fins $? "$res"
res=$("$png_diff" "$d/render_shadows.png" "$d/shadows.png" --max-mean 0.4); check key_s_is_inter_shadow $? "$res"

# O switches the light's shadows on (off in the default scene): the window
# then equals render with --shadows.
printf '0.1 key o\n0.1 screenshot %s\n0.1 exit\n' "$d/light.png" >"$d/light.txt"
view --no-hud --script "$d/light.txt" 2>/dev/null; check light_key_runs $? ""
"$pelt" render -q --size $size --msaa 0 --shadows -o "$d/render_light.png"
! "$png_diff" "$d/render.png" "$d/render_light.png" --max-mean 0.4 >/dev/null
check light_shadows_change_the_picture $? "render's pictures with and without them are alike"
res=$("$png_diff" "$d/render_light.png" "$d/light.png" --max-mean 0.4); check key_o_is_shadows $? "$res"

# The scene file changes on disk while the window is open: it reloads
# (polled once a second) and the new background shows.
printf '{"output": {"background": [0.1, 0.11, 0.13, 1]}}\n' >"$d/scene.json"
printf '0 screenshot %s\n4.0 screenshot %s\n4.0 exit\n' "$d/reload_0.png" "$d/reload_1.png" >"$d/reload.txt"
"$pelt" view "$d/scene.json" --size 160x120 --no-hud --script "$d/reload.txt" 2>"$d/reload.err" &
vpid=$!
for _ in $(seq 600); do [ -s "$d/reload_0.png" ] && break; sleep 0.1; done
sleep 0.2
printf '{"output": {"background": [1, 0, 0, 1]}}\n' >"$d/scene.json"
wait $vpid; rc=$?
check reload_runs $rc "$(cat "$d/reload.err")"
grep -q "reloaded" "$d/reload.err"; check reload_when_the_file_changes $? "$(cat "$d/reload.err")"
reds=$(value red "$("$region" --red "$d/reload_1.png" 0 0 20 20)")
is "$reds" '>' 300; check reloaded_scene_shows $? "$reds red pixels in the corner"

echo "$passes passed, $fails failed"
[ $fails -eq 0 ]
