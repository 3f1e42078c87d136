#!/usr/bin/env bash
# Renders every picture under docs/images/ into OUTDIR with the commands the
# docs give for it (docs/gallery.md, docs/gallery-dynamics.md, docs/gallery-grooming.md,
# docs/gallery-fins.md, docs/gallery-papers.md, docs/atlas.md, docs/lod.md;
# README.md only shows pictures of the galleries), so that the result can be
# compared with the committed pictures by scripts/docs-images-compare.sh.
#
#   scripts/docs-images.sh OUTDIR [PELT_BINARY]
#
# PELT_BINARY defaults to build/pelt of this checkout (a Release build, as the
# docs say: scripts/demo.sh). Environment:
#   PELT_SOURCE_DIR  tree whose scenes/ and tests/data/ the commands read
#                    (default: the checkout this script is in)
#   CGAL_ARCHIVE     Debian libcgal-demo's mesh archive
#                    (default /usr/share/doc/libcgal-dev/data.tar.gz, as tests/support/corpus.h)
#   DOCS_IMAGES      space-separated subset of picture groups to render (default all):
#                    default bunny_dry elephant bunny_combed elephant_combed
#                    atlas_elephant atlas_bunny whirl bunny_wet bunny_rain word_in_water
#                    wind_square turntable curl groom_torus groom_bunny groom_maps
#                    fins_torus fins_bunny inter_shadow lod shadows animation papers
#
# Each command runs in its own fresh working directory (symlinks to the source
# tree's top-level entries, an empty docs/images/) with its own empty
# XDG_CACHE_HOME, so the relative paths of the docs work, nothing is written
# into the source tree and no atlas cache is shared between commands; pelt atlas
# gets --no-cache as in docs/atlas.md. Each command's output goes to
# OUTDIR/log/GROUP.log; OUTDIR must not hold PNGs already. Pictures that need
# the CGAL meshes are skipped, with a message, when the archive is absent.
# Exits non-zero if any command failed.
#
# The docs' commands below are copied verbatim: unquoted $M, $COMMON and [..] values.
# shellcheck disable=SC2086,SC2102
set -euo pipefail

if [ $# -lt 1 ] || [ $# -gt 2 ] || [ "${1:-}" = -h ] || [ "${1:-}" = --help ]; then
  echo "usage: $0 OUTDIR [PELT_BINARY]" >&2
  exit 2
fi

here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
ROOT="$(cd "${PELT_SOURCE_DIR:-$here}" && pwd)"
mkdir -p "$1"
OUT="$(cd "$1" && pwd)"
if [ -n "$(find "$OUT" -maxdepth 1 -name '*.png' -print -quit)" ]; then
  echo "docs-images: $OUT already holds PNGs; give a new or empty OUTDIR so no stale picture is compared" >&2
  exit 2
fi
PELT="${2:-$ROOT/build/pelt}"
case "$PELT" in /*) ;; *) PELT="$PWD/$PELT" ;; esac
CGAL_ARCHIVE="${CGAL_ARCHIVE:-/usr/share/doc/libcgal-dev/data.tar.gz}"

if [ ! -f "$ROOT/scenes/word-in-water.json" ]; then
  echo "docs-images: $ROOT has no scenes/word-in-water.json; set PELT_SOURCE_DIR to the pelt source tree" >&2
  exit 2
fi
if [ ! -x "$PELT" ]; then
  echo "docs-images: no pelt binary at $PELT (build it: cmake -S . -B build -DCMAKE_BUILD_TYPE=Release && cmake --build build)" >&2
  exit 2
fi

TMP="$(mktemp -d "${TMPDIR:-/tmp}/docs-images.XXXXXX")"
trap 'rm -rf "$TMP"' EXIT
mkdir -p "$OUT/log"

# The docs write `pelt` for the binary.
pelt() { "$PELT" "$@"; }

# Meshes from Debian's libcgal-demo, extracted as docs/gallery.md does.
have_cgal=0
if [ -f "$CGAL_ARCHIVE" ]; then
  mkdir -p "$TMP/cgal"
  tar xzf "$CGAL_ARCHIVE" -C "$TMP/cgal" data/meshes/bunny00.off data/meshes/elephant.off \
    data/meshes/cow.off data/meshes/lion-head.off data/meshes/bear.off
  have_cgal=1
fi
M="$TMP/cgal/data/meshes"

# A fresh working directory and atlas cache for one command; prints its path.
fresh() {
  local w
  w="$(mktemp -d "$TMP/work.XXXXXX")"
  local e
  # Not docs/ (made empty below) and no top-level picture: a command without
  # -o writes pelt.png here, and must not write through a link into the tree.
  for e in "$ROOT"/*; do
    case "$(basename "$e")" in docs|*.png) ;; *) ln -s "$e" "$w/" ;; esac
  done
  mkdir -p "$w/docs/images" "$w/.cache"
  echo "$w"
}

# collect FILE NAME: the command's output FILE becomes OUTDIR/NAME.
collect() {
  if [ ! -f "$1" ]; then
    echo "docs-images: the command did not write $1" >&2
    return 1
  fi
  cp "$1" "$OUT/$2"
}

# ---- The pictures. Commands are copied from the docs; only `collect` is added.

# docs/gallery.md, "The default scene"; also README.md.
img_default() {
  pelt render -o docs/images/default.png
  collect docs/images/default.png default.png
}

# docs/gallery.md, "Real meshes without uvs" (no -o: pelt writes pelt.png).
img_bunny_dry() {
  pelt render --mesh $M/bunny00.off --size 640x480
  collect pelt.png bunny_dry.png
}
img_elephant() {
  pelt render --mesh $M/elephant.off --size 640x480
  collect pelt.png elephant.png
}

# docs/gallery.md, "Combed along the direction field"; also README.md.
img_bunny_combed() {
  pelt render --mesh $M/bunny00.off --size 640x480 --set fur.slant=40
  collect pelt.png bunny_combed.png
}
img_elephant_combed() {
  pelt render --mesh $M/elephant.off --size 640x480 --set fur.slant=40
  collect pelt.png elephant_combed.png
}

# docs/atlas.md, "pelt atlas" gallery (docs/gallery.md shows the same picture
# with `pelt atlas $M/elephant.off --size 768`, which differs only by the cache).
img_atlas_elephant() {
  pelt atlas $M/elephant.off -o docs/images/atlas_elephant.png --size 768 --no-cache
  collect docs/images/atlas_elephant.png atlas_elephant.png
}
img_atlas_bunny() {
  pelt atlas $M/bunny00.off  -o docs/images/atlas_bunny.png    --size 768 --no-cache
  collect docs/images/atlas_bunny.png atlas_bunny.png
}

# docs/gallery.md, the whirl (no -o: pelt.png).
img_whirl() {
  pelt render --mesh tests/data/meshes/swirl_colors.ply --set atlas.direction_from=vertex-colors \
      --set fur.slant=50 --set atlas.mode=patches --pitch 70 --yaw 0 --size 480x360
  collect pelt.png whirl.png
}

# docs/gallery.md, "Wet fur"; also README.md.
img_bunny_wet() {
  pelt render --mesh $M/bunny00.off --size 640x480 --set wetness.drops.count=300 \
      --set 'wetness.drops.radius=[0.012,0.02]' -o bunny_wet.png --mask-out bunny_wet_mask.png
  collect bunny_wet.png bunny_wet.png
  collect bunny_wet_mask.png bunny_wet_mask.png
}
img_bunny_rain() {
  pelt render --mesh $M/bunny00.off --size 640x480 --rain 300 --frames 2 --fps 1 \
      --set 'wetness.rain.radius=[0.012,0.02]' -o rain_%d.png    # rain_1.png
  collect rain_1.png bunny_rain.png
}
img_word_in_water() {
  pelt render scenes/word-in-water.json --size 640x480 -o word.png --mask-out word_mask.png
  collect word.png word_in_water.png
  collect word_mask.png word_in_water_mask.png
}

# docs/gallery-dynamics.md, "Wind".
img_wind_square() {
  COMMON="scenes/wind-square.json --frames 1 --set fur.density=800 --set fur.strand_radius=2.5 \
    --set fur.length=0.3 --set fur.layers=32 --pitch 12 --distance 2.6 --light 0.3,0.8,1 \
    --set light.color=[2.2,2.1,2] --set light.ambient=0.4 --size 480x360"
  pelt render $COMMON --wind 0,0,0 -o wind_square_calm.png
  pelt render $COMMON --wind 20,0,0 -o wind_square.png
  collect wind_square_calm.png wind_square_calm.png
  collect wind_square.png wind_square.png
}

# docs/gallery-dynamics.md, "Inertia: a fast turntable".
img_turntable() {
  pelt render scenes/turntable.json --frames 13 --turntable 540 --set fur.length=0.2 \
    --set light.color=[1.8,1.75,1.7] --size 480x360 -o turn_%02d.png
  # turntable_0/1/2.png = turn_00/06/12.png
  collect turn_00.png turntable_0.png
  collect turn_06.png turntable_1.png
  collect turn_12.png turntable_2.png
}

# docs/gallery-dynamics.md, "The curl looks of Silva et al. Fig. 7".
img_curl() {
  for NAME in straight wavy few-large-curls many-small-curls; do
    pelt render --mesh square --set fur.preset=$NAME --set fur.density=500 \
      --set fur.strand_radius=2.5 --set fur.length=0.3 --set fur.layers=48 --set fur.taper=0.3 \
      --gravity 0,0,0 --yaw 0 --pitch 12 --distance 2.2 --light 0.3,0.8,1 \
      --set light.color=[2.2,2.1,2] --set light.ambient=0.4 --size 480x360 -o curl_$NAME.png
    pelt render --mesh square --set fur.preset=$NAME --set fur.curl_phase=coherent --set fur.density=500 \
      --set fur.strand_radius=2.5 --set fur.length=0.3 --set fur.layers=48 --set fur.taper=0.3 \
      --gravity 0,0,0 --yaw 0 --pitch 12 --distance 2.2 --light 0.3,0.8,1 \
      --set light.color=[2.2,2.1,2] --set light.ambient=0.4 --size 480x360 -o curl_coherent_$NAME.png
    pelt compare --mesh square --set fur.preset=$NAME --set fur.density=500 \
      --set fur.strand_radius=2.5 --set fur.length=0.3 --set fur.layers=48 --set fur.taper=0.3 \
      --gravity 0,0,0 --yaw 0 --pitch 12 --distance 2.2 --light 0.3,0.8,1 \
      --set light.color=[2.2,2.1,2] --set light.ambient=0.4 --size 480x360 -o curl_${NAME}_compare.png
  done
  for NAME in straight wavy few-large-curls many-small-curls; do
    collect curl_$NAME.png curl_$NAME.png
    collect curl_coherent_$NAME.png curl_coherent_$NAME.png
    collect curl_${NAME}_compare.png curl_${NAME}_compare.png
  done
}

# docs/gallery-grooming.md, Lengyel Fig. 4 h, i, k, l by scripted strokes.
img_groom_torus() {
  pelt render --size 480x360 -o groom_torus_h.png \
    --set 'strokes=[{"tool":"length","at":[0,0,0],"radius":10,"amount":1}]'
  pelt render --size 480x360 -o groom_torus_i.png \
    --set 'strokes=[{"tool":"comb","at":[0,0,0],"radius":10,"delta":[0.09,0,0]}]'
  pelt render --size 480x360 -o groom_torus_k.png \
    --set 'strokes=[{"tool":"color","pixel":[250,250],"radius":0.35,"color":[0.2,0.5,1],"strength":0.6}]'
  pelt render --size 480x360 -o groom_torus_l.png \
    --set 'strokes=[{"tool":"comb","pixel":[250,250],"radius":0.35,"drag":[40,0]}]'
  for F in h i k l; do collect groom_torus_$F.png groom_torus_$F.png; done
}
img_groom_bunny() {
  B="--mesh $M/bunny00.off --size 480x360"
  pelt render $B -o groom_bunny_h.png --set 'strokes=[{"tool":"length","at":[0,0,0],"radius":10,"amount":1}]'
  pelt render $B -o groom_bunny_i.png --set 'strokes=[{"tool":"comb","at":[0,0,0],"radius":10,"delta":[0,-0.025,0]}]'
  pelt render $B -o groom_bunny_k.png \
    --set 'strokes=[{"tool":"color","pixel":[250,235],"radius":0.12,"color":[0.2,0.5,1],"strength":0.6}]'
  pelt render $B -o groom_bunny_l.png --set 'strokes=[{"tool":"comb","pixel":[250,235],"radius":0.12,"drag":[60,-20]}]'
  pelt render $B -o groom_bunny_paint.png --set 'strokes=[
      {"tool":"density","pixel":[106,158],"radius":0.1,"amount":0},
      {"tool":"color","pixel":[235,70],"radius":0.2,"color":[0.95,0.95,0.92]},
      {"tool":"color","pixel":[270,200],"radius":0.25,"color":[0.06,0.05,0.04]}]'
  for F in h i k l paint; do collect groom_bunny_$F.png groom_bunny_$F.png; done
}

# docs/gallery-grooming.md, maps and vertex colours.
img_groom_maps() {
  pelt render scenes/groom-stripes.json --size 480x360 -o groom_stripes.png
  pelt render scenes/groom-bald.json --size 480x360 -o groom_bald.png
  pelt render scenes/groom-flow.json --size 480x360 -o groom_flow.png
  pelt render --mesh tests/data/meshes/swirl_colors.ply --set fur.vertex_colors=hair \
    --pitch 70 --yaw 0 --size 480x360 -o groom_vertex_colors.png
  for F in stripes bald flow vertex_colors; do collect groom_$F.png groom_$F.png; done
}

# docs/gallery-fins.md: Lengyel Fig. 4 a-e, Kenwright Fig. 1/3, the table.
img_fins_torus() {
  pelt render --size 480x360 --set draw.shells=false --no-fins -o fins_torus_a.png
  pelt render --size 480x360 --set draw.shells=false --set draw.outline_hairs=false -o fins_torus_b.png
  pelt render --size 480x360 --no-fins -o fins_torus_c.png
  pelt render --size 480x360 -o fins_torus_d.png
  pelt render --size 480x360 --set draw.shells=false --set draw.fins_unfaded=true -o fins_torus_e.png
  pelt render --size 480x360 --set draw.outline_hairs=false -o fins_torus_f.png
  for F in a b c d e f; do collect fins_torus_$F.png fins_torus_$F.png; done
}
img_fins_bunny() {
  B="--mesh $M/bunny00.off --size 480x360"
  pelt render $B --set draw.shells=false --set draw.fins=false -o fins_bunny_a.png
  pelt render $B --set draw.shells=false --set draw.outline_hairs=false -o fins_bunny_b.png
  pelt render $B --no-fins -o fins_bunny_c.png
  pelt render $B -o fins_bunny_d.png
  pelt render $B --set draw.shells=false --set draw.fins_unfaded=true -o fins_bunny_e.png
  pelt render $B --set draw.outline_hairs=false -o fins_bunny_f.png
  for F in a b c d e f; do collect fins_bunny_$F.png fins_bunny_$F.png; done
}
img_inter_shadow() {
  K="--set fur.color=[0.6,0.45,0.3] --set fur.tip_color=[0.6,0.45,0.3] --set fur.specular=[0,0,0] --size 480x360"
  pelt render --mesh square $K --pitch 50 --distance 1.6 -o kenwright_off.png
  pelt render --mesh square $K --pitch 50 --distance 1.6 --inter-shadow -o kenwright_on.png
  pelt render $K --distance 2.4 -o kenwright_torus_off.png
  pelt render $K --distance 2.4 --inter-shadow -o kenwright_torus_on.png
  pelt render --mesh $M/bunny00.off $K -o kenwright_bunny_off.png
  pelt render --mesh $M/bunny00.off $K --inter-shadow -o kenwright_bunny_on.png
  pelt render --size 480x360 --shading lengyel-table -o lengyel_table.png
  for F in kenwright_off kenwright_on kenwright_torus_off kenwright_torus_on kenwright_bunny_off \
           kenwright_bunny_on lengyel_table; do collect $F.png $F.png; done
}
img_lod() {
  for K in 0 1 2; do
    pelt render --size 480x360 --distance 6 --set fur.lod=fixed --set fur.lod_shell_level=$K -o lod_shells_$K.png
    collect lod_shells_$K.png lod_shells_$K.png
  done
  pelt render --mesh $M/bunny00.off --size 480x360 --set fur.lod=off -o lod_bunny_off.png
  pelt render --mesh $M/bunny00.off --size 480x360 -o lod_bunny_auto.png
  collect lod_bunny_off.png lod_bunny_off.png
  collect lod_bunny_auto.png lod_bunny_auto.png
}
img_shadows() {
  pelt render scenes/shadows-sphere-box.json --size 480x360 -o shadows_sphere_box_on.png
  pelt render scenes/shadows-sphere-box.json --size 480x360 --no-shadows -o shadows_sphere_box_off.png
  B="--mesh $M/bunny00.off --size 480x360 --ground --set light.direction=[-0.45,1,-0.05]"
  pelt render $B --shadows -o shadows_bunny_on.png
  pelt render $B -o shadows_bunny_off.png
  E="--mesh $M/elephant.off --size 480x360 --ground --set light.direction=[-1,0.8,0.5] --set fur.length=0.03"
  pelt render $E --shadows -o shadows_elephant_on.png
  pelt render $E -o shadows_elephant_off.png
  for F in sphere_box bunny elephant; do
    collect shadows_${F}_on.png shadows_${F}_on.png
    collect shadows_${F}_off.png shadows_${F}_off.png
  done
}
img_animation() {
  A=/usr/share/assimp/models
  pelt render --mesh $A/X/BCN_Epileptic.X --animation Epileptisch --frames 8 --fps 2.4 --size 240x320 \
      --set 'camera.target=[0,-0.1,0]' --distance 3.6 -o bcn_%02d.png
  ffmpeg -loglevel error -y -i bcn_%02d.png -vf tile=4x2 anim_bcn_sheet.png
  pelt render --mesh $A/glTF2/simple_skin/simple_skin.gltf --animation 0 --frames 6 --fps 1.2 --size 200x240 \
      --set 'camera.target=[0,1,0]' --distance 4.5 -o skin_%02d.png
  ffmpeg -loglevel error -y -i skin_%02d.png -vf tile=6x1 anim_simple_skin_sheet.png
  pelt render --mesh $A/FBX/spider.fbx --size 480x360 -o anim_spider.png
  for F in anim_bcn_sheet anim_simple_skin_sheet anim_spider; do collect $F.png $F.png; done
}

# docs/gallery-papers.md: the papers' figures (Silva Fig. 1, 11, 12, 13;
# Lengyel Fig. 5); Silva Fig. 7 is the curl group's.
img_papers() {
  W="--drops 400 --set wetness.drops.radius=[0.02,0.04]"
  pelt render --mesh $M/bunny00.off --size 480x360 -o papers_fig1a.png
  pelt render --mesh $M/bunny00.off --size 480x360 --set fur.preset=many-small-curls --set fur.length=0.06 \
    -o papers_fig1b.png
  pelt render --mesh $M/cow.off --size 480x360 -o papers_fig1c.png
  pelt render --mesh $M/cow.off --size 480x360 $W -o papers_fig1d.png
  # Fig. 11: a partly wet bunny, dry and wet fur side by side, and its mask.
  P="--drops 60 --set wetness.drops.radius=[0.03,0.06]"
  pelt render --mesh $M/bunny00.off --size 480x360 $P -o papers_fig11b.png --mask-out papers_fig11b_mask.png
  pelt render --mesh $M/bunny00.off --size 480x360 $P --set wetness.clumps=droplet -o papers_fig11b_alg1.png
  L="--mesh $M/lion-head.off --size 480x360 --yaw 30 --pitch 12 --distance 2.1 --set fur.length=0.02"
  pelt render $L -o papers_fig12a.png
  pelt render $L --drops 300 --set wetness.drops.radius=[0.015,0.03] -o papers_fig12b.png
  C13="--mesh $M/bunny00.off --size 480x360 --yaw 30 --pitch 25 --distance 0.55
       --set camera.target=[0.05,0.05,0.1] --set fur.layers=32"
  pelt render $C13 $W -o papers_fig13.png
  pelt render $C13 $W --set wetness.lie=40 -o papers_fig13_lie.png
  # The figures beside the strand reference: shells | strands | difference.
  pelt compare --mesh $M/bunny00.off --size 480x360 -o papers_fig1a_compare.png
  pelt compare --mesh $M/bunny00.off --size 480x360 --set fur.preset=many-small-curls --set fur.length=0.06 \
    -o papers_fig1b_compare.png
  pelt compare --mesh $M/cow.off --size 480x360 -o papers_fig1c_compare.png
  pelt compare --mesh $M/cow.off --size 480x360 $W -o papers_fig1d_compare.png
  pelt compare --mesh $M/bunny00.off --size 480x360 $P -o papers_fig11b_compare.png
  pelt compare $L --drops 300 --set wetness.drops.radius=[0.015,0.03] -o papers_fig12b_compare.png
  pelt compare $C13 $W -o papers_fig13_compare.png
  B="--mesh $M/bear.off --size 480x360 --set fur.strand_curl=6 --set fur.strand_curl_turns=3 --set fur.layers=32"
  pelt render $B -o papers_lengyel_fig5.png
  pelt render $B --yaw 30 --pitch 20 --distance 1.0 --set camera.target=[0,0.3,0.2] -o papers_lengyel_fig5_closeup.png
  for F in fig1a fig1b fig1c fig1d fig11b fig11b_mask fig11b_alg1 fig12a fig12b fig13 fig13_lie lengyel_fig5 \
           lengyel_fig5_closeup fig1a_compare fig1b_compare fig1c_compare fig1d_compare fig11b_compare \
           fig12b_compare fig13_compare; do
    collect papers_$F.png papers_$F.png
  done
}

# ---- Running them.

all="default bunny_dry elephant bunny_combed elephant_combed atlas_elephant atlas_bunny whirl
     bunny_wet bunny_rain word_in_water wind_square turntable curl groom_torus groom_bunny groom_maps
     fins_torus fins_bunny inter_shadow lod shadows animation papers"
needs_cgal=" bunny_dry elephant bunny_combed elephant_combed atlas_elephant atlas_bunny bunny_wet bunny_rain groom_bunny fins_bunny inter_shadow lod shadows papers "
groups="${DOCS_IMAGES:-$all}"

now() { date +%s.%N; }
elapsed() { awk -v a="$1" -v b="$2" 'BEGIN { printf "%.2f", b - a }'; }
echo "docs-images: $PELT -> $OUT (sources: $ROOT)"
failed=()
skipped=()
start="$(now)"
for g in $groups; do
  if ! declare -F "img_$g" >/dev/null; then
    echo "docs-images: unknown picture group '$g' (known: $(tr -s ' \n' ' ' <<<"$all"))" >&2
    exit 2
  fi
  if [ "$g" = animation ] && [ ! -f /usr/share/assimp/models/X/BCN_Epileptic.X ]; then
    echo "  skip $g: needs Debian's assimp-testmodels (scripts/setup.sh --tests installs it)"
    skipped+=("$g")
    continue
  fi
  if [ "$have_cgal" = 0 ] && [[ "$needs_cgal" == *" $g "* ]]; then
    echo "  skip $g: needs Debian's libcgal-demo mesh archive $CGAL_ARCHIVE (scripts/setup.sh --tests installs it)"
    skipped+=("$g")
    continue
  fi
  t0="$(now)"
  leaks=""
  for attempt in 1 2 3; do
    w="$(fresh)"
    # A background subshell keeps `set -e` working inside it; `wait` gives its status.
    # set -f: the docs' unquoted [..] values (light.color=[2.2,2.1,2]) stay literal.
    ( set -f; cd "$w"; export XDG_CACHE_HOME="$w/.cache"
      [ -z "$leaks" ] || export ASAN_OPTIONS="${ASAN_OPTIONS:+$ASAN_OPTIONS:}detect_leaks=0"
      "img_$g" ) >"$OUT/log/$g.log" 2>&1 &
    rc=0
    wait $! || rc=$?
    rm -rf "$w"
    # In a sanitizer build, LeakSanitizer's own thread-stopping tracer
    # crashes at exit now and then on a loaded machine ("Tracer caught
    # signal 11 ... LeakSanitizer has encountered a fatal error", a known
    # sanitizer flake, not a leak: a leak reads "detected memory leaks").
    # Such a group runs again; after two such crashes, once more with the
    # leak check off (the cli tests check the same code for leaks), and it
    # says so either way.
    if [ "$rc" != 0 ] && [ "$attempt" != 3 ] &&
       grep -q 'LeakSanitizer has encountered a fatal error' "$OUT/log/$g.log"; then
      if [ "$attempt" = 2 ]; then
        leaks=off
        printf '  %-16s LeakSanitizer crashed at exit twice (not a leak); once more without the leak check\n' "$g"
      else
        printf '  %-16s LeakSanitizer crashed at exit (not a leak); running it again\n' "$g"
      fi
      continue
    fi
    break
  done
  t1="$(now)"
  if [ "$rc" = 0 ]; then
    printf '  %-16s %7.2f s\n' "$g" "$(elapsed "$t0" "$t1")"
  else
    printf '  %-16s FAILED (exit %s), see %s\n' "$g" "$rc" "$OUT/log/$g.log"
    tail -n 5 "$OUT/log/$g.log" | sed 's/^/      /'
    failed+=("$g")
  fi
done
end="$(now)"
printf 'docs-images: %d PNGs in %s, %.1f s' "$(find "$OUT" -maxdepth 1 -name '*.png' | wc -l)" "$OUT" "$(elapsed "$start" "$end")"
[ ${#skipped[@]} -eq 0 ] || printf ', skipped: %s' "${skipped[*]}"
echo
if [ ${#failed[@]} -ne 0 ]; then
  echo "docs-images: FAILED: ${failed[*]}" >&2
  exit 1
fi
