#!/usr/bin/env bash
# The strand-reference baseline of docs/reference.md: runs `pelt compare`
# on every scene of scenes/reference/, writes each side-by-side picture
# (shells | strands | difference x4) to OUTDIR/NAME.png and prints the
# figures as the rows of a Markdown table.
#
#   scripts/reference-images.sh OUTDIR [PELT_BINARY]
#
# PELT_BINARY defaults to build/pelt of this checkout. The creature scene
# renders the Stanford bunny of Debian's libcgal-demo (CGAL_ARCHIVE, default
# /usr/share/doc/libcgal-dev/data.tar.gz); without it that row is skipped.
set -euo pipefail

if [ $# -lt 1 ] || [ $# -gt 2 ] || [ "${1:-}" = -h ] || [ "${1:-}" = --help ]; then
  echo "usage: $0 OUTDIR [PELT_BINARY]" >&2
  exit 2
fi
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
out=$1
pelt=${2:-$here/build/pelt}
mkdir -p "$out"
tmp="$(mktemp -d "${TMPDIR:-/tmp}/reference.XXXXXX")"
trap 'rm -rf "$tmp"' EXIT
archive=${CGAL_ARCHIVE:-/usr/share/doc/libcgal-dev/data.tar.gz}
M=""
if [ -f "$archive" ]; then
  tar -xzf "$archive" -C "$tmp" data/meshes/bunny00.off
  M=$tmp/data/meshes
fi

field() { awk -v k="$1" '$1 == k { $1 = ""; sub(/^ /, ""); print }' <<<"$2"; }

echo "| scene | ssim | mae | coverage at 1 2 4 8 16 32 px: shells / strands | stripe ratio (shells/strands) | luminance shells / strands |"
echo "|---|---|---|---|---|---|"
for scene in torus torus-rim creature long-hair combed curly shadowed distant; do
  args=("$here/scenes/reference/$scene.json")
  if [ "$scene" = creature ]; then
    if [ -z "$M" ]; then
      echo "reference-images: no $archive, skipping $scene" >&2
      continue
    fi
    args+=(--mesh "$M/bunny00.off")
  fi
  res=$("$pelt" compare "${args[@]}" -q -o "$out/$scene.png")
  printf '| %s | %s | %s | %s / %s | %s | %s / %s |\n' "$scene" \
    "$(field ssim "$res")" "$(field mae "$res")" \
    "$(field silhouette_shells "$res")" "$(field silhouette_strands "$res")" \
    "$(field stripe_energy_ratio "$res")" \
    "$(field luminance_shells "$res")" "$(field luminance_strands "$res")"
done
