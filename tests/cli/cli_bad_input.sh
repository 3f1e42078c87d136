#!/usr/bin/env bash
# Bad input to the pelt command: every case must print a message that names
# the file or flag at fault and exit non-zero, never crash (sanitizers
# abort with their own exit codes and reports, which this catches too).
set -u
pelt=$1 data=$2 out=$3
fails=0 passes=0

# expect_fail NAME NEEDLE CMD...: non-zero exit, not a signal/sanitizer
# (exit < 128 and no sanitizer report), stderr contains NEEDLE.
expect_fail() {
  local name=$1 needle=$2; shift 2
  local err rc
  err=$("$@" 2>&1 >/dev/null); rc=$?
  if [ $rc -eq 0 ]; then
    echo "FAIL $name: exit 0"; fails=$((fails+1)); return
  fi
  if [ $rc -ge 128 ] || grep -q "Sanitizer\|runtime error" <<<"$err"; then
    echo "FAIL $name: crashed (exit $rc): $err"; fails=$((fails+1)); return
  fi
  if ! grep -qF -- "$needle" <<<"$err"; then
    echo "FAIL $name: message does not name '$needle': $err"; fails=$((fails+1)); return
  fi
  echo "ok   $name: $(head -n1 <<<"$err")"; passes=$((passes+1))
}

expect_ok() {
  local name=$1; shift
  local err rc
  err=$("$@" 2>&1 >/dev/null); rc=$?
  if [ $rc -ne 0 ]; then echo "FAIL $name: exit $rc: $err"; fails=$((fails+1)); return; fi
  echo "ok   $name"; passes=$((passes+1))
}

r="$pelt render --size 64x48 -q -o $out/cli_out.png"
expect_fail missing_mesh "no_such_mesh.obj" $r --mesh "$out/no_such_mesh.obj"
for f in "$data"/meshes/bad_*; do
  expect_fail "mesh_$(basename "$f")" "$(basename "$f")" $r --mesh "$f"
done
# Strict, never a silently partial mesh: what is wrong, where.
expect_fail ply_list_short "list 'vertex_indices' declares 4 entries but the line holds 3" \
  $r --mesh "$data/meshes/bad_list_short.ply"
expect_fail ply_list_short_binary "declares 3 entries but the file ends first" \
  $r --mesh "$data/meshes/bad_list_short_binary.ply"
expect_fail stl_truncated_binary "binary STL declares 2 triangles (184 bytes) but the file has 154 bytes" \
  $r --mesh "$data/meshes/bad_truncated_solid.stl"
expect_fail obj_two_corner_face "line 7: a face of 2 corners" $r --mesh "$data/meshes/bad_face_two_vertices.obj"
expect_fail gltf_accessor_out_of_range "out of range" $r --mesh "$data/meshes/bad_accessor_range.gltf"
expect_fail missing_scene "nope.json" $r "$out/nope.json" 
for f in "$data"/scenes/bad_*.json "$data"/scenes/empty.json "$data"/scenes/nul_byte.json; do
  [ -e "$f" ] || continue
  expect_fail "scene_$(basename "$f")" "$(basename "$f")" $pelt render "$f" --size 64x48 -q -o "$out/cli_out.png"
done
printf '{"fur": {"layers": 16,}' > "$out/truncated.json"
expect_fail scene_json_syntax "truncated.json" $pelt render "$out/truncated.json" -q -o "$out/cli_out.png"
printf '{"fur": {"lenght": 0.1}}' > "$out/typo.json"
expect_fail scene_unknown_key "fur.lenght" $pelt render "$out/typo.json" -q -o "$out/cli_out.png"
printf '{"fur": {"layers": "many"}}' > "$out/type.json"
expect_fail scene_wrong_type "fur.layers" $pelt render "$out/type.json" -q -o "$out/cli_out.png"

printf 'not a png' > "$out/corrupt.png"
expect_fail texture_missing "no_texture.png" $r --texture "$out/no_texture.png"
expect_fail texture_corrupt "corrupt.png" $r --texture "$out/corrupt.png"
expect_fail mask_image_corrupt "corrupt.png" $r --mask-image "$out/corrupt.png"
# A 16-bit PGM shorter than its header says (stb read past it; found by fuzz_image).
printf 'P5\n64 64\n65535\n\001\002' > "$out/short16.pgm"
expect_fail texture_short_pnm "short16.pgm' is truncated" $r --texture "$out/short16.pgm"
# A PGM header declaring 60000 x 60000 pixels: refused before stb allocates.
printf 'P5\n60000 60000\n255\n\001' > "$out/huge.pgm"
expect_fail texture_huge_pnm "declares 60000 x 60000 pixels" $r --texture "$out/huge.pgm"
expect_fail pattern_unknown "--pattern" $r --pattern plaid

expect_fail layers_too_many "--layers" $r --layers 300
expect_fail layers_word "--layers" $r --layers many
expect_fail layers_negative "--layers" $r --layers -3
expect_fail size_bad "--size" $r --size 800
expect_fail size_zero "--size" $r --size 0x600
expect_fail size_huge "--size" $r --size 99999x10
expect_fail seed_word "--seed" $r --seed abc
expect_fail wind_two "--wind" $r --wind 1,2
expect_fail wind_nan "--wind" $r --wind 1,nan,2
# Groom files: corrupt, truncated, foreign, for another mesh; bad strokes.
expect_ok groom_save $r --save-groom "$out/cli_torus.groom.ply"
printf 'ply\nformat ascii 1.0\nend_header\n' > "$out/ascii.groom.ply"
expect_fail groom_ascii "ascii.groom.ply" $r --groom "$out/ascii.groom.ply"
head -c 700 "$out/cli_torus.groom.ply" > "$out/truncated.groom.ply"
expect_fail groom_truncated "truncated.groom.ply" $r --groom "$out/truncated.groom.ply"
expect_fail groom_not_ply "corrupt.png" $r --set fur.groom="$out/corrupt.png"
expect_fail groom_other_mesh "does not match" $r --mesh sphere --groom "$out/cli_torus.groom.ply"
expect_fail groom_missing "no_groom.ply" $r --groom "$out/no_groom.ply"
expect_fail groom_unwritable "--save-groom" $r --save-groom "$out/cli_no_dir/g.ply"
expect_fail stroke_no_place "strokes[0]" $r --set 'strokes=[{"tool":"comb","radius":0.1}]'
expect_fail stroke_bad_tool "strokes[0].tool" $r --set 'strokes=[{"tool":"rake","radius":0.1,"at":[0,0,0]}]'
expect_fail stroke_missed "does not see the mesh" $r --set 'strokes=[{"tool":"comb","radius":0.1,"pixel":[1,1]}]'
expect_fail length_map_corrupt "corrupt.png" $r --set fur.length_map="$out/corrupt.png"
expect_fail shadow_map_too_small "shadows.map_size: expected an integer from 16 to 4096" $r --set shadows.map_size=8
expect_fail shadow_slices_too_many "shadows.slices" $r --set shadows.slices=9
expect_fail ground_size_negative "ground.size" $r --set ground.size=-1
expect_fail animation_missing "no animation 'walk': the mesh has 0 'bend'" $r --mesh "$data/skin/tube.gltf" --animation walk
expect_fail animation_on_static "no animation '0': the mesh has no animations" $r --animation 0
expect_fail skin_weights_zero "vertex 5 of mesh 'tube' has bone weights summing to 0" $r --mesh "$data/skin/tube_bad_weights.gltf"
expect_fail skin_key_nan "rotation key 1 is not a finite rotation" $r --mesh "$data/skin/tube_bad_key.gltf"
expect_fail vertex_colors_none "no vertex colours" $r --set fur.vertex_colors=hair

expect_fail unknown_flag "--bogus" $r --bogus
expect_fail missing_value "--layers" $pelt render --layers
expect_fail bad_pattern "-o" $pelt render --size 64x48 -q -o "$out/x_%s.png"
expect_fail unwritable_output "cli_no_dir" $pelt render --size 64x48 -q -o "$out/cli_no_dir/x.png"
expect_fail unknown_command "frobnicate" $pelt frobnicate
expect_fail info_missing "nothing.off" $pelt info "$out/nothing.off"

expect_ok help_main $pelt --help
for c in render bench info; do expect_ok "help_$c" $pelt $c --help; done
expect_ok good_obj $r --mesh "$data/meshes/square_uv.obj"
expect_ok good_off $r --mesh "$data/meshes/tetra.off"
expect_ok good_ply $r --mesh "$data/meshes/tetra.ply"
expect_ok good_stl $r --mesh "$data/meshes/two_facets.stl"
expect_ok good_gltf $r --mesh "$data/meshes/quad.gltf"
expect_ok good_glb $r --mesh "$data/meshes/quad.glb"
expect_ok pattern_spots $r --pattern spots
expect_ok mask_out $r --drops 5 --mask-out "$out/cli_mask.png"

echo "$passes passed, $fails failed"
[ $fails -eq 0 ]
