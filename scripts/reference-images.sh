#!/usr/bin/env bash
# The strand-reference baseline of docs/reference.md: runs `pelt compare`
# on every scene of scenes/reference/, writes each side-by-side picture
# (shells | strands | difference x4) to OUTDIR/NAME.png and prints the
# figures as the rows of a Markdown table.
#
#   scripts/reference-images.sh OUTDIR [PELT_BINARY] [SET]
#
# PELT_BINARY defaults to build/pelt of this checkout. SET is `reference`
# (default: scenes/reference/, docs/reference.md), `high-quality` (the same
# scenes drawn with --high-quality) or `wet` (the wet close-up and the
# partly wet creature of scenes/wet/ beside the curly hair:
# docs/gallery-papers.md). The creature scenes render the Stanford bunny
# of Debian's libcgal-demo (CGAL_ARCHIVE, default
# /usr/share/doc/libcgal-dev/data.tar.gz); without it their rows are skipped.
set -euo pipefail

if [ $# -lt 1 ] || [ $# -gt 3 ] || [ "${1:-}" = -h ] || [ "${1:-}" = --help ]; then
  echo "usage: $0 OUTDIR [PELT_BINARY] [reference|high-quality|wet]" >&2
  exit 2
fi
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
out=$1
pelt=${2:-$here/build/pelt}
set_name=${3:-reference}
flags=()
case "$set_name" in
  reference|high-quality)
    scenes="reference/torus reference/torus-rim reference/creature reference/long-hair reference/combed
            reference/curly reference/shadowed reference/distant"
    [ "$set_name" = high-quality ] && flags=(--high-quality) ;;
  wet) scenes="wet/wet-closeup wet/wet-creature reference/curly" ;;
  *) echo "$0: unknown set '$set_name' (reference, high-quality or wet)" >&2; exit 2 ;;
esac
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
for path in $scenes; do
  scene=${path#*/}
  args=("$here/scenes/$path.json")
  if [ "${scene%creature}" != "$scene" ]; then
    if [ -z "$M" ]; then
      echo "reference-images: no $archive, skipping $scene" >&2
      continue
    fi
    args+=(--mesh "$M/bunny00.off")
  fi
  res=$("$pelt" compare "${args[@]}" ${flags[@]+"${flags[@]}"} -q -o "$out/$scene.png")
  printf '| %s | %s | %s | %s / %s | %s | %s / %s |\n' "$scene" \
    "$(field ssim "$res")" "$(field mae "$res")" \
    "$(field silhouette_shells "$res")" "$(field silhouette_strands "$res")" \
    "$(field stripe_energy_ratio "$res")" \
    "$(field luminance_shells "$res")" "$(field luminance_strands "$res")"
done
