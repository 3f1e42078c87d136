#!/usr/bin/env bash
# pelt render -o NAME.mp4/.webm/.gif: frames piped into ffmpeg make a video
# that ffprobe reads back with the frame count and size asked for; the
# frames move; bad names and a failing ffmpeg get clear errors; without
# ffmpeg, a message saying what to install. Skips (77) without ffmpeg.
#   cli_video.sh PELT SOURCE_DIR OUT PNG_DIFF
set -u
pelt=$1 src=$2 out=$3 png_diff=$4
fails=0 passes=0
check() { if [ "$2" -eq 0 ]; then echo "ok   $1"; passes=$((passes+1)); else echo "FAIL $1: $3"; fails=$((fails+1)); fi; }
d="$out/cli_video"; rm -rf "$d"; mkdir -p "$d"

# Without ffmpeg on PATH: what to install, that PNG sequences work, no file.
err=$(PATH=/nonexistent "$pelt" render -q --size 64x48 --frames 3 -o "$d/none.mp4" 2>&1); rc=$?
[ $rc -ne 0 ] && [ $rc -lt 128 ] && grep -q "apt-get install ffmpeg" <<<"$err" &&
  grep -q -- "-o $d/none_%04d.png" <<<"$err" && [ ! -e "$d/none.mp4" ]
check no_ffmpeg_says_what_to_install $? "exit $rc: $err"

if ! command -v ffmpeg >/dev/null || ! command -v ffprobe >/dev/null; then
  echo "SKIP: ffmpeg and ffprobe are not installed (Debian package ffmpeg; scripts/setup.sh --tests installs it)"
  echo "$passes passed, $fails failed"
  [ $fails -eq 0 ] || exit 1
  exit 77
fi
# stream fields of the first video stream, as "codec,width,height,frames"
probe() {
  ffprobe -v error -count_frames -select_streams v:0 \
    -show_entries stream=codec_name,width,height,nb_read_frames -of csv=p=0 "$1" 2>&1
}

# The rain scene as the README renders it, smaller and shorter for the test
# time: 24 frames at 24 fps are the first second, while it rains.
fps=$(grep -o '"fps": *[0-9.]*' "$src/scenes/rain.json" | grep -o '[0-9.]*$')
err=$("$pelt" render "$src/scenes/rain.json" --size 320x240 --frames 24 -o "$d/rain.mp4" 2>&1); rc=$?
[ $rc -eq 0 ] && grep -q "wrote $d/rain.mp4 (24 frames at $fps fps)" <<<"$err"
check rain_mp4_runs $? "exit $rc: $err"
got=$(probe "$d/rain.mp4"); [ "$got" = "h264,320,240,24" ]
check rain_mp4_has_the_frames_and_size $? "ffprobe: $got"
rate=$(ffprobe -v error -select_streams v:0 -show_entries stream=r_frame_rate -of csv=p=0 "$d/rain.mp4")
[ "$rate" = "$fps/1" ]; check rain_mp4_has_the_scene_fps $? "r_frame_rate $rate, scene fps $fps"

# The video is the rendering: its frame 20 matches the PNG of frame 20
# within the loss of H.264, and differs from frame 0 (rain has landed).
"$pelt" render "$src/scenes/rain.json" -q --size 320x240 --frames 21 -o "$d/rain_%02d.png"
ffmpeg -v error -i "$d/rain.mp4" -vf "select=eq(n\,20)" -frames:v 1 "$d/v20.png"
ffmpeg -v error -i "$d/rain.mp4" -vf "select=eq(n\,0)" -frames:v 1 "$d/v00.png"
r=$("$png_diff" "$d/rain_20.png" "$d/v20.png" --max-mean 4 --max-frac 0.03 2>&1)
check video_frame_matches_the_png $? "$r"
# Natural tufts change a distant picture less than one crater per drop did:
# frame 20 is 0.48 off frame 0 (0.19% of pixels by more than 32), frame 1
# only 0.01 (0.003%), so these bounds sit well between the two.
r=$("$png_diff" "$d/v00.png" "$d/v20.png" --max-mean 0.2 --max-frac 0.0005 2>&1)
[ $? -eq 1 ]; check video_frames_move $? "frames 0 and 20 are nearly the same: $r"

# WebM (VP9) pads an odd size to even; GIF keeps it.
"$pelt" render -q --size 65x49 --frames 5 --turntable 90 -o "$d/odd.webm"
got=$(probe "$d/odd.webm"); [ "$got" = "vp9,66,50,5" ]; check webm_odd_size_padded $? "ffprobe: $got"
"$pelt" render -q --size 65x49 --frames 4 --turntable 90 -o "$d/spin.GIF"
got=$(probe "$d/spin.GIF"); [ "$got" = "gif,65,49,4" ]; check gif_any_case $? "ffprobe: $got"

# On a terminal the progress line has frames, fps and time left or taken;
# without one (every run above) stderr has only the final line. script(1)
# (util-linux, in every Debian) gives pelt a terminal.
tty=$(script -qec "'$pelt' render --size 64x48 --frames 6 -o '$d/tty.mp4'" /dev/null 2>&1 | tr '\r' '\n')
grep -qE '^\[#+ *\] 3/6 +[0-9.]+ fps +[0-9]+:[0-9]{2} left' <<<"$tty" &&
  grep -qE '^\[#+\] 6/6 +[0-9.]+ fps +[0-9]+:[0-9]{2} total' <<<"$tty"
check progress_on_a_terminal $? "$tty"

# Bad names: a frame pattern, an unwritable directory; no crash, no file.
err=$("$pelt" render -q --size 64x48 -o "$d/x_%04d.mp4" 2>&1); rc=$?
[ $rc -eq 2 ] && grep -q -- "-o '$d/x_%04d.mp4'" <<<"$err"; check pattern_video_refused $? "exit $rc: $err"
err=$("$pelt" render -q --size 64x48 -o "$d/no_dir/x.mp4" 2>&1); rc=$?
[ $rc -eq 1 ] && grep -q "cannot write '$d/no_dir/x.mp4'" <<<"$err"; check unwritable_video $? "exit $rc: $err"

# An ffmpeg that fails: its status is reported, pelt is not killed by
# SIGPIPE and leaves no half-written file.
mkdir -p "$d/fake"
printf '#!/bin/sh\necho "fake ffmpeg: cannot encode" >&2\nexit 3\n' >"$d/fake/ffmpeg"
chmod +x "$d/fake/ffmpeg"
err=$(PATH="$d/fake:$PATH" "$pelt" render -q --size 64x48 --frames 20 -o "$d/fail.mp4" 2>&1); rc=$?
[ $rc -eq 1 ] && grep -q "ffmpeg failed writing '$d/fail.mp4' (exit status 3" <<<"$err" && [ ! -e "$d/fail.mp4" ]
check failing_ffmpeg_reported $? "exit $rc: $err"

echo "$passes passed, $fails failed"
[ $fails -eq 0 ]
