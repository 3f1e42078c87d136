#!/usr/bin/env bash
# The strand reference and the shells against it: the reference converges
# (doubling its samples changes the picture by less than 1/255 on average),
# shells and strands agree on how far the fur reaches past a sphere's
# outline, hair crosses that outline in the shell picture as it does in the
# reference, the silhouette profiles agree band by band, and a grazing rim
# shows less stripe energy than 16 plain shells give it, a hair seen
# end-on covers its root's disc in the reference, fur seen along its hairs
# is about as bright as the hairs and as bright at four times the layers,
# the fins show hair tips
# along a grazing rim, curls shape the outline seen from the side as
# they shape the reference's, curls are lit hair by hair, and the fur
# on the reference torus is as sharp as its hairs, and the reference's
# hairs shade each other where the shells draw Kenwright's shadows, and
# long hair at --high-quality reads as close to its hairs as the look asks,
# and its 128 layers draw no colour speckles, and the fur in front of the
# torus's hole hides the fur of its far wall, and the CGAL bunny drawn on
# a coarse mesh level reads as close to its hairs as the look asks, and
# hairs seen from the side are whole, not chains of beads.
set -u
pelt=$1 png_diff=$2 out=$3 png_region=$4
fails=0 passes=0
check() { if [ "$2" -eq 0 ]; then echo "ok   $1"; passes=$((passes+1)); else echo "FAIL $1: $3"; fails=$((fails+1)); fi; }
field() { awk -v k="$1" '$1 == k { $1 = ""; sub(/^ /, ""); print }' <<<"$2"; }

d="$out/cli_reference"; rm -rf "$d"; mkdir -p "$d"

# Convergence, on the default torus at 200x150: the hard case, a hair is a
# small fraction of a pixel there. 4x (the default) against 8x.
"$pelt" render -q --strands --size 200x150 -o "$d/s4.png" 2>"$d/err.txt"; rc=$?
if [ $rc -ne 0 ] && grep -qi "context\|EGL" "$d/err.txt"; then
  echo "SKIPPED: no OpenGL context: $(cat "$d/err.txt")"; exit 77
fi
"$pelt" render -q --strands --strand-samples 8 --size 200x150 -o "$d/s8.png" 2>>"$d/err.txt"
res=$("$png_diff" "$d/s4.png" "$d/s8.png" --max-mean 1.0 --max-frac 0.01 --threshold 64)
check reference_converges $? "$res"
# and the supersampling matters: 1x is visibly different from 8x.
"$pelt" render -q --strands --strand-samples 1 --size 200x150 -o "$d/s1.png"
"$png_diff" "$d/s1.png" "$d/s8.png" --max-mean 1.0 >/dev/null
[ $? -ne 0 ]; check one_sample_is_not_converged $? "1x matches 8x within 1/255"

# A sphere, framed by pelt, with fur long enough to reach several pixels.
sphere="--mesh sphere --size 320x240"
res=$("$pelt" compare $sphere 2>"$d/err.txt"); rc=$?
check compare_sphere_runs $rc "exit $rc: $(cat "$d/err.txt")"
es=$(field extent_shells_px "$res") er=$(field extent_strands_px "$res")
awk -v a="$es" -v b="$er" 'BEGIN { exit !(b >= 3 && a - b <= 2 && b - a <= 2) }'
check same_outline_within_2px $? "shells reach $es px, strands $er px"
sh=$(field silhouette_shells "$res") st=$(field silhouette_strands "$res")
# Band 1 is (1, 2] px outside the skin.
awk -v a="$sh" -v b="$st" 'BEGIN { split(a, s, " "); split(b, r, " "); exit !(r[2] > 0 && s[2] >= 0.3 * r[2]) }'
check hair_crosses_the_outline $? "coverage at 2 px: shells $sh, strands $st"
# Every band up to the fur's reach: the shells' coverage within 25% of the strands'.
awk -v a="$sh" -v b="$st" -v e="$er" 'BEGIN {
  split(a, s, " "); split(b, r, " "); ok = 1
  for (k = 1; k <= 6; k++) { edge = 2 ^ (k - 1); if (edge / 2 >= e + 0) break
    if (r[k] > 0 && (s[k] < 0.75 * r[k] || s[k] > 1.25 * r[k])) ok = 0 }
  exit !ok }'
check silhouette_profile_within_25_percent $? "shells $sh, strands $st, reach $er px"

# Stripes edge-on: a sphere with long fur, whose lower rim is seen at a
# grazing angle. 16 shells (the paper's count everywhere, the same texture
# read) alias into rows there; the default (32 edge-on, the view's budget
# face-on) keeps the rim's stripe energy below theirs, and below the hairs'
# own. The hairs' texture has power at the shells' spacing too (the
# strands': 12.8), so the sharper the fur texture is read, the closer the
# shell pictures come to each other and to the hairs: with one fetch
# taking up to 2 texels of a grazing footprint's long side (before
# lod.texture_aniso) 16 shells gave 5.81 and the default 3.57 (0.61); with
# up to 4 (the default now) 8.06 and 6.51 (0.81, 0.51 of the strands').
# Read at the texture's own level (fur.texture_aniso=1), 16 shells give
# 5.81: the default's extra power is its hairs' detail, which its picture
# shows as radial streaks along the rim where the read before drew a
# smooth pale band, as the strands do (docs/reference.md). The 16 shells
# are drawn one a layer (fur.sub_shells=1): where 16 layers stand more than
# 1.4 px apart they would be sub shells, 3.69, no longer the plain shells
# this compares with. Bound: 0.85 of the 16 shells', 0.65 of the strands'.
long="--mesh sphere --size 320x240 --length 0.3"
plain=$("$pelt" compare $long --layers 16 --set fur.lod_shell_pixels=1 --set fur.sub_shells=1 2>&1) || echo "$plain"
ours=$("$pelt" compare $long 2>&1) || echo "$ours"
sp=$(field stripe_shells "$plain") so=$(field stripe_shells "$ours") ss=$(field stripe_strands "$ours")
awk -v p="$sp" -v o="$so" -v s="$ss" 'BEGIN { exit !(p > 0 && s > 0 && o >= 0 && o < 0.85 * p && o < 0.65 * s) }'
check no_stripes_edge_on $? "stripe energy: 16 shells $sp, default $so, strands $ss (bound: 0.85 of the 16 shells', 0.65 of the strands')"

# Hair seen end-on: straight down onto a square's upright hair through a
# narrow lens, every hair is seen along its length. A hair is a tube and
# covers at least the disc of its root: 3000 strands of radius 1.6 texels
# to a 256-texel tile (the defaults) cover 1 - exp(-3000 pi 1.6^2 / 256^2)
# = 31% of the skin with their root discs alone. A flat ribbon seen end-on
# covers next to nothing (13% as counted here). Counted: the pixels more
# than 40 levels from the same view with one strand to a tile (the skin);
# the bound, 0.25, leaves room for hairs as dark as the skin.
top="--mesh square --pitch 89 --yaw 0 --gravity 0,0,0 --size 120x120 --distance 8 --fov 6
  --set fur.color=[1,1,1] --set fur.tip_color=[1,1,1] --light 1,0,0.2"
"$pelt" render -q --strands $top -o "$d/top.png"
"$pelt" render -q --strands $top --set fur.density=1 -o "$d/top_skin.png"
res=$("$png_diff" "$d/top.png" "$d/top_skin.png" --threshold 40 | grep "pixels off")
covered=$(sed 's/.*= \([0-9.]*\) .*/\1/' <<<"$res")
awk -v c="$covered" 'BEGIN { exit !(c + 0 >= 0.25) }'
check hair_seen_end_on_covers_its_root $? "covered ${covered:-?} of the skin (bound 0.25): $res"

# Fur seen along its hairs: every shell shows the same cross-section of a
# hair a ray runs along, and composited as if each held other hairs the
# shells drew the fur more opaque than the hairs (luminance 82 against the
# hairs' 64 from 60 degrees above a square, 77 against 28 straight down:
# the bright tips cover the dark depth). Each shell now takes its share of
# a hair that k shells show (pelt__lod_shell_overcount). Bounds: within 15%
# of the hairs' luminance at 60 degrees, at most 2.2x straight down.
along="--mesh square --yaw 0 --gravity 0,0,0 --size 120x120 --distance 8 --fov 6"
r60=$("$pelt" compare $along --pitch 60 -q 2>&1)
l60s=$(field luminance_shells "$r60") l60h=$(field luminance_strands "$r60")
awk -v a="${l60s:-0}" -v b="${l60h:-0}" 'BEGIN { exit !(b > 0 && a <= 1.15 * b && a >= 0.85 * b) }'
check fur_seen_along_its_hairs_as_bright_as_the_hairs $? "from 60 degrees: shells $l60s, hairs $l60h (bound 15%)"
r89=$("$pelt" compare $along --pitch 89 -q 2>&1)
l89s=$(field luminance_shells "$r89") l89h=$(field luminance_strands "$r89")
awk -v a="${l89s:-0}" -v b="${l89h:-0}" 'BEGIN { exit !(b > 0 && a <= 2.2 * b) }'
check fur_seen_end_on_not_a_bright_carpet $? "straight down: shells $l89s, hairs $l89h (bound 2.2x)"
# and the same fur at four times the layers, each drawn (fur.lod fixed at
# level 0): a ray leaves a hair after a height of the fur, not after a
# count of shells, so the shells' share of a hair follows the layers
# (pelt__lod_shell_overcount_cap). With the count held at 3 shells, 128
# layers drew this view 45% brighter than 32 (68.6 against 47.2; the
# hairs 38.3). Bound: within 5%.
r32=$("$pelt" compare $along --pitch 80 --set fur.lod=fixed -q 2>&1)
r128=$("$pelt" compare $along --pitch 80 --set fur.lod=fixed --layers 128 -q 2>&1)
l32=$(field luminance_shells "$r32") l128=$(field luminance_shells "$r128")
awk -v a="${l32:-0}" -v b="${l128:-0}" 'BEGIN { exit !(a > 0 && b <= 1.05 * a && b >= 0.95 * a) }'
check more_layers_draw_the_same_fur $? "from 80 degrees: 32 layers $l32, 128 layers $l128 (bound 5%)"

# Hair tips on the outline: the torus's far rim seen nearly edge-on, where
# the fins carry the hair that stands against the sky. A fin's hair is
# foreshortened up the fin, and read at a texture read's own level (from the
# long side) its tips blurred into a soft band (outline roughness 0.55 px
# against the strands' 2.0); read at the short side's level, up to 4 texels
# of the long side to a pixel, the tips stand apart (1.0). Bound: the
# shells' outline at least 0.4 as rough as the strands'.
rim="$(cd "$(dirname "$0")/../.." && pwd)/scenes/reference/torus-rim.json"
"$pelt" compare "$rim" -o "$d/rim.png" >/dev/null 2>&1
rs=$("$png_region" --outline "$d/rim.png" 20 460 8 | sed 's/roughness=\([0-9.]*\).*/\1/')
rt=$("$png_region" --outline "$d/rim.png" 500 940 8 | sed 's/roughness=\([0-9.]*\).*/\1/')
awk -v a="${rs:-0}" -v b="${rt:-0}" 'BEGIN { exit !(b > 0 && a >= 0.4 * b) }'
check fins_show_hair_tips_on_the_outline $? "outline roughness: shells $rs px, strands $rt px (bound: 0.4 of the strands')"

# Curls on the outline (Silva Fig. 7, seen from the side): sparse, long fur
# on a square whose far edge stands against the sky. The fur texture's
# strands vary in length, so straight hair ends in a row of spikes; curls
# fold the tips over into a level fleece, and the outline's roughness falls
# with the curl (the strand reference shows it so; it does not rise). The
# shells and fins must draw each preset's outline as rough as the strands
# (within half), and straight hair's at least 1.6x as rough as either
# curl's. Fur without its curls would keep straight hair's roughness.
side="--mesh square --set fur.density=500 --set fur.strand_radius=2.5 --set fur.length=0.3 --set fur.layers=48
  --set fur.taper=0.3 --gravity 0,0,0 --yaw 0 --pitch 0 --distance 2.2 --light 0.3,0.8,1 --size 360x180"
declare -A rough_shells rough_strands
for preset in straight few-large-curls many-small-curls; do
  "$pelt" compare $side --set fur.preset=$preset -o "$d/side_$preset.png" >/dev/null 2>&1
  rough_shells[$preset]=$("$png_region" --outline "$d/side_$preset.png" 36 324 8 | sed 's/roughness=\([0-9.]*\).*/\1/')
  rough_strands[$preset]=$("$png_region" --outline "$d/side_$preset.png" 396 684 8 | sed 's/roughness=\([0-9.]*\).*/\1/')
done
ok=1 seen=""
for preset in straight few-large-curls many-small-curls; do
  a=${rough_shells[$preset]:-0} b=${rough_strands[$preset]:-0}
  seen="$seen $preset: shells $a px, strands $b px;"
  awk -v a="$a" -v b="$b" 'BEGIN { exit !(b > 0 && a >= 0.5 * b && a <= 1.5 * b) }' || ok=0
done
[ $ok -eq 1 ]; check curled_outline_follows_the_strands $? "$seen"
awk -v s="${rough_shells[straight]:-0}" -v l="${rough_shells[few-large-curls]:-0}" -v m="${rough_shells[many-small-curls]:-0}" \
  'BEGIN { exit !(l > 0 && m > 0 && s >= 1.6 * l && s >= 1.6 * m) }'
check curls_level_the_outline $? "$seen (bound: straight at least 1.6x either curl)"

# Curls lit hair by hair (Silva Fig. 7d, many small curls seen from 12
# degrees above a square): where the fur texture's read averages several
# hairs, their mean id gave every pixel one phase none of them has, and
# the ringlets' light came out in blotches; the id read at the finest
# level lights the hair the pixel shows. SSIM against the strands 0.619
# before, 0.640 after; bound 0.63. At 48 shells, as it was measured
# (fur.layers_per_turn=1; the preset's six turns take 78 by default).
fig7d="--mesh square --set fur.density=500 --set fur.strand_radius=2.5 --set fur.length=0.3 --set fur.layers=48
  --set fur.layers_per_turn=1
  --set fur.taper=0.3 --gravity 0,0,0 --yaw 0 --pitch 12 --distance 2.2 --light 0.3,0.8,1
  --set light.color=[2.2,2.1,2] --set light.ambient=0.4 --size 480x360 --set fur.preset=many-small-curls"
res=$("$pelt" compare $fig7d -q 2>&1)
ss=$(field ssim "$res")
awk -v s="${ss:-0}" 'BEGIN { exit !(s >= 0.63) }'
check curls_lit_hair_by_hair $? "SSIM against the strands $ss (bound 0.63)"

# Curly fur drawn with its shells a turn (scenes/reference/curly.json, six
# turns over the length): 32 shells give each a 67-degree arc of every
# hair, drawn flat at one height, and the helix reads as printed rings;
# 13 a turn (78 shells) draw it as the hairs' helix, and the view's
# budget keeps them where the fur is seen face-on, where a curl's step
# from shell to shell shows whole. SSIM against the strands 0.616 at 32
# (0.621 kept face-on), 0.669 at 72 halved face-on, 0.687 kept. Bounds:
# at least 0.68 (the look's own asks 0.6652: 1 - SSIM at most 60% of the
# baseline's 0.558) and 0.05 over the same fur at 32 shells.
curly="$(cd "$(dirname "$0")/../.." && pwd)/scenes/reference/curly.json"
res=$("$pelt" compare "$curly" -q 2>&1)
res32=$("$pelt" compare "$curly" --set fur.layers_per_turn=1 -q 2>&1)
ss=$(field ssim "$res") ss32=$(field ssim "$res32")
awk -v s="${ss:-0}" -v t="${ss32:-1}" 'BEGIN { exit !(s >= 0.68 && s >= t + 0.05) }'
check curls_drawn_as_helices $? "SSIM against the strands $ss, at 32 shells $ss32 (bounds: 0.68, 0.05 over 32 shells)"

# The fur as sharp as the hairs (the reference torus, 480x360): read at
# the footprint's own level, the nearest mip level's bilinear read
# filters wider than the pixel and the shells came out softer than the
# hairs (SSIM 0.922); half a level finer where the footprint is round,
# 0.930. Bound: the look's own, 1 - SSIM at most 60% of the baseline's
# 0.1256, so at least 0.9246.
torus="$(cd "$(dirname "$0")/../.." && pwd)/scenes/reference/torus.json"
res=$("$pelt" compare "$torus" -q 2>&1)
ss=$(field ssim "$res")
awk -v s="${ss:-0}" 'BEGIN { exit !(s >= 0.9246) }'
check fur_as_sharp_as_the_hairs $? "SSIM against the strands $ss (bound 0.9246)"

# The outline's grain (docs/reference.md, The outline's grain): the band
# outside the torus's outline steps from pixel to pixel along the outline
# 0.57 as much as the hairs' band does (0.52 without the outline's hairs,
# 0.55 with the read across the gap down to the outline): no smoother.
grain=$(field outline_grain_ratio "$res")
awk -v g="${grain:-0}" 'BEGIN { exit !(g >= 0.555) }'
check outline_no_smoother_than_today $? "the outline's grain $grain of the hairs' (bound 0.555)"

# The reference's hairs shade each other (shadowed.json, Kenwright's
# inter-fur shadows on the shells): its hairs drawn into the light's maps
# darken it (40.5 -> 36.2 in luminance), the same whatever the shells
# draw (32 or 16 layers: the maps hold the hairs, not the shells), and the
# shells come within 10% of it (-2.3%; -12.6% against the unshaded hairs).
shadowed="$(cd "$(dirname "$0")/../.." && pwd)/scenes/reference/shadowed.json"
on=$("$pelt" compare "$shadowed" -q 2>&1)
on16=$("$pelt" compare "$shadowed" --layers 16 -q 2>&1)
off=$("$pelt" compare "$shadowed" --set fur.inter_shadow=false -q 2>&1)
lon=$(field luminance_strands "$on") l16=$(field luminance_strands "$on16") loff=$(field luminance_strands "$off")
lsh=$(field luminance_shells "$on")
awk -v a="${lon:-0}" -v b="${l16:-0}" -v c="${loff:-0}" -v s="${lsh:-0}" \
  'BEGIN { exit !(a > 0 && a < 0.95 * c && a > 0.8 * c && (a - b) ^ 2 < (0.005 * a) ^ 2 && (s - a) ^ 2 < (0.1 * a) ^ 2) }'
check reference_hairs_shade_each_other $? \
  "strands $lon (16 shell layers: $l16; unshaded $loff), shells $lsh (bounds: 5-20% darker, the same within 0.5%, shells within 10%)"

# A grazing read, sharp across the view: the hole's walls and lip, seen at
# a grazing angle, read at the footprint's long side (fur.texture_aniso=1)
# blur their hairs across the view into a pale sheet. Four fetches along
# the footprint keep them apart (fur.texture_taps; SSIM 0.8095 -> 0.8403
# here), and so does the default's one fetch taking up to 4 texels of the
# long side to a pixel (0.8408), at the price of aliasing along the view.
# Bound: each at least 0.01 higher than the long side's level.
long_side=$("$pelt" compare "$shadowed" --set fur.texture_aniso=1 -q 2>&1)
taps=$("$pelt" compare "$shadowed" --set fur.texture_aniso=1 --set fur.texture_taps=4 -q 2>&1)
s1=$(field ssim "$long_side") s4=$(field ssim "$taps") sd=$(field ssim "$on")
awk -v a="${s1:-1}" -v b="${s4:-0}" 'BEGIN { exit !(b >= a + 0.01) }'
check fetches_along_the_footprint $? "SSIM against the strands $s4 with 4 fetches, $s1 with 1 at the long side's level (bound +0.01)"
awk -v a="${s1:-1}" -v b="${sd:-0}" 'BEGIN { exit !(b >= a + 0.01) }'
check one_fetch_sharp_across_a_grazing_view $? "SSIM against the strands $sd at the default, $s1 at the long side's level (bound +0.01)"

# Shells seen edge-on as deep as the hairs (fur.edge_depth): above the
# hole's near lip the outer shells are seen edge-on, a ray crosses each hair
# in less than one shell spacing and a shell held its cross-section once:
# see-through where the hairs' sides cover the ray. Standing for up to 16
# crossings there (the default), long hair comes closer to its hairs
# (0.8657 at depth 1 -> 0.8876) and nearer their brightness (-7.9% ->
# -4.1%). Bounds: SSIM at least 0.01 higher, luminance within 10%.
long_hair="$(cd "$(dirname "$0")/../.." && pwd)/scenes/reference/long-hair.json"
e1=$("$pelt" compare "$long_hair" --set fur.edge_depth=1 -q 2>&1)
e16=$("$pelt" compare "$long_hair" -q 2>&1)
s1=$(field ssim "$e1") s16=$(field ssim "$e16")
l16=$(field luminance_shells "$e16") lh=$(field luminance_strands "$e16")
awk -v a="${s1:-1}" -v b="${s16:-0}" -v l="${l16:-0}" -v h="${lh:-0}" \
  'BEGIN { exit !(b >= a + 0.01 && h > 0 && (l - h) ^ 2 < (0.1 * h) ^ 2) }'
check edge_on_shells_as_deep_as_the_hairs $? "SSIM $s16 at depth 16, $s1 at 1 (bound +0.01); luminance $l16 against $lh (bound 10%)"

# Close up, every layer in sub shells (fur.sub_shells, docs/lod.md): on
# the grazing close-up of the torus's rim the shells stand about 2 px
# apart seen side-on, and a texture read sharp across them showed as
# rows, so the hairs along the horizon blurred into a pale band. Drawn
# 2 shells a layer they stand within 1.4 px and read sharp, and the fins,
# whose hair across the outline the denser shells now hold, are drawn at
# half their opacity: SSIM against the hairs 0.8995 -> 0.9168 (bound
# +0.006, and at least 0.9156: 1 - SSIM within 60% of the baseline's
# 0.1406, as the look asks), brightness within 10%, no stripes (stripe
# ratio at most 1.5). Silva Fig. 7's square of long curly fur seen from
# 12 deg above likewise (many small curls, lit by the default light:
# 0.7066 -> 0.7689, bound +0.02).
rim="$(cd "$(dirname "$0")/../.." && pwd)/scenes/reference/torus-rim.json"
r1=$("$pelt" compare "$rim" --set fur.sub_shells=1 -q 2>&1)
rk=$("$pelt" compare "$rim" -q 2>&1)
s1=$(field ssim "$r1") sk=$(field ssim "$rk") st=$(field stripe_energy_ratio "$rk")
lk=$(field luminance_shells "$rk") lh=$(field luminance_strands "$rk")
awk -v a="${s1:-1}" -v b="${sk:-0}" -v l="${lk:-0}" -v h="${lh:-0}" -v st="${st:-9}" \
  'BEGIN { exit !(b >= a + 0.006 && b >= 0.9156 && h > 0 && (l - h) ^ 2 < (0.1 * h) ^ 2 && st <= 1.5) }'
check close_up_layers_in_sub_shells $? "rim SSIM $sk with sub shells, $s1 with one a layer (bounds +0.006 and 0.9156); luminance $lk against $lh; stripes $st"
square=(--mesh square --set fur.preset=many-small-curls --set fur.density=500 --set fur.strand_radius=2.5
        --set fur.length=0.3 --set fur.layers=48 --set fur.taper=0.3 --gravity 0,0,0 --yaw 0 --pitch 12
        --distance 2.2 --light 0.3,0.8,1 --size 480x360)
c1=$("$pelt" compare "${square[@]}" --set fur.sub_shells=1 -q 2>&1)
ck=$("$pelt" compare "${square[@]}" -q 2>&1)
s1=$(field ssim "$c1") sk=$(field ssim "$ck")
awk -v a="${s1:-1}" -v b="${sk:-0}" 'BEGIN { exit !(b >= a + 0.02) }'
check close_up_curls_in_sub_shells $? "many small curls from 12 deg: SSIM $sk with sub shells, $s1 with one a layer (bound +0.02)"

# Long hair at high quality (--high-quality: 128 layers, a 512 texture,
# every shell drawn, the full mesh): the shells converge with their layers
# (more_layers_draw_the_same_fur above) and long hair reads as close to its
# hairs as the look asks, 1 - SSIM at most 60% of the baseline's 0.183, so
# at least 0.8902 (0.8926; the default 32 layers 0.8609, 128 alone 0.8849,
# a 512 texture alone 0.8503), within 10% of their brightness (+1.0%).
res=$("$pelt" compare "$long_hair" --high-quality -q 2>&1)
ss=$(field ssim "$res") ls=$(field luminance_shells "$res") lh=$(field luminance_strands "$res")
awk -v s="${ss:-0}" -v a="${ls:-0}" -v b="${lh:-0}" 'BEGIN { exit !(s >= 0.8902 && b > 0 && (a - b) ^ 2 < (0.1 * b) ^ 2) }'
check long_hair_at_high_quality $? "SSIM against the strands $ss (bound 0.8902), luminance $ls against $lh (bound 10%)"

# 128 layers without colour speckles: an 8-bit colour target rounds each
# of the 128 blends, and on the distant torus the rounding added up to
# red and olive speckles (chroma noise 1.21 against the 32 layers' 0.61);
# above 32 layers pelt draws into a half-float target (0.71). Bound: at
# most 1.25x the default's.
distant="$(cd "$(dirname "$0")/../.." && pwd)/scenes/reference/distant.json"
"$pelt" render "$distant" -q -o "$d/distant.png"
"$pelt" render "$distant" --high-quality -q -o "$d/distant_hq.png"
n32=$("$png_region" --chroma "$d/distant.png" 0 0 480 360 | sed 's/.*=//')
n128=$("$png_region" --chroma "$d/distant_hq.png" 0 0 480 360 | sed 's/.*=//')
awk -v a="${n32:-0}" -v b="${n128:-99}" 'BEGIN { exit !(a > 0 && b <= 1.25 * a) }'
check many_layers_without_speckles $? "chroma noise at 128 layers $n128, at 32 $n32 (bound 1.25x)"

# Fur in front hides fur behind (docs/reference.md, The near lip): on the
# long-haired torus the near lip's hairs stand over the hole's far wall,
# whose fur is lit brighter. The shells are drawn a layer at a time, so
# without their depth the far wall's outer layers were laid over the near
# lip's hairs: the band above the lip, x 200-280, y 174-182 of the 480x360
# picture, came out 34% brighter than the hairs' (a pale pane); with it,
# 6% darker. Bound: within 15% of the hairs', and the shells blended
# without their depth more than 20% brighter (the scene still shows it;
# without the outline's hairs, which no shell depth would lay over all).
"$pelt" compare "$long_hair" -q -o "$d/lip.png" >/dev/null
"$pelt" compare "$long_hair" --set draw.shell_depth=false --set draw.outline_hairs=false -q -o "$d/lip_blended.png" >/dev/null
lip=$("$png_region" --luma "$d/lip.png" 200 174 281 182 | sed 's/.*=//')
hairs=$("$png_region" --luma "$d/lip.png" 680 174 761 182 | sed 's/.*=//')
blended=$("$png_region" --luma "$d/lip_blended.png" 200 174 281 182 | sed 's/.*=//')
awk -v a="${lip:-0}" -v b="${hairs:-0}" -v c="${blended:-0}" \
  'BEGIN { exit !(b > 0 && (a - b) ^ 2 < (0.15 * b) ^ 2 && c > 1.2 * b) }'
check near_fur_hides_the_far_fur $? "lip band $lip, the hairs' $hairs (bound 15%); blended without depth $blended (must exceed 1.2x)"

# Hairs seen from the side, not beads: Silva Fig. 7's square of long
# sparse straight hair seen from 12 degrees above its plane, where each
# shell held a dash of the hair and the next shell's lay a spacing lower
# (SSIM against the strands 0.7982); each shell now holds the hair down
# to the next (0.8325; docs/reference.md). Bound 0.82.
straight=(--mesh square --set fur.preset=straight --set fur.density=500 --set fur.strand_radius=2.5
          --set fur.length=0.3 --set fur.layers=48 --set fur.taper=0.3 --gravity 0,0,0 --yaw 0 --pitch 12
          --distance 2.2 --light 0.3,0.8,1 --set light.color=[2.2,2.1,2] --set light.ambient=0.4 --size 480x360)
res=$("$pelt" compare "${straight[@]}" -q 2>&1)
ss=$(field ssim "$res")
awk -v s="${ss:-0}" 'BEGIN { exit !(s >= 0.82) }'
check hairs_seen_from_the_side_not_beads $? "straight square from 12 deg: SSIM against the strands $ss (bound 0.82)"

# The creature of docs/reference.md (CGAL's bunny, which this framing
# draws from mesh level 2) reads as close to its hairs as the look asks:
# 1 - SSIM at most 60% of the baseline's 0.1074, so at least 0.9356
# (0.9377 with the level's normals fitted to the full mesh's; 0.9332 with
# the kept vertices' own, docs/lod.md). Needs libcgal-demo's corpus, which
# the test setup installs.
archive=${CGAL_ARCHIVE:-/usr/share/doc/libcgal-dev/data.tar.gz}
if [ -f "$archive" ]; then
  tar -xzf "$archive" -C "$d" data/meshes/bunny00.off
  creature="$(cd "$(dirname "$0")/../.." && pwd)/scenes/reference/creature.json"
  res=$("$pelt" compare "$creature" --mesh "$d/data/meshes/bunny00.off" -q 2>&1)
  ss=$(field ssim "$res")
  awk -v s="${ss:-0}" 'BEGIN { exit !(s >= 0.9356) }'
  check creature_within_the_look $? "SSIM against the strands $ss (bound 0.9356)"
  # Its outline as far out as the strands': the silhouette profile's 8 and
  # 16 px bands within 25% of theirs (0.957 / 0.935 and 0.245 / 0.250 with
  # the outline's hairs; the fin texture's quads alone put the 16 px band
  # 17% over).
  sh=$(printf '%s\n' "$res" | awk '/^silhouette_shells/ { print $5, $6 }')
  st=$(printf '%s\n' "$res" | awk '/^silhouette_strands/ { print $5, $6 }')
  echo "$sh $st" | awk '{ ok = NF == 4 && $3 > 0 && $4 > 0; for (i = 1; i <= 2; i++) { r = $i / $(i + 2); ok = ok && r >= 0.75 && r <= 1.25 } exit !ok }'
  check creature_outline_as_far_as_the_hairs $? "silhouette at 8 and 16 px: shells $sh, strands $st (within 25%)"
else
  check creature_within_the_look 1 "no $archive (libcgal-demo): scripts/setup.sh --tests installs it"
fi

echo "$passes passed, $fails failed"
[ $fails -eq 0 ]
