#!/usr/bin/env bash
# Every picture in docs/images/ renders the same from its documented command
# (scripts/docs-images.sh) within png_diff's tolerance: mean channel error
# <= 1/255-levels and at most 1% of pixels off by more than 32. The docs
# cannot drift from the code. SKIPPED (77) without the CGAL meshes.
#   docs_images.sh PELT PNG_DIFF OUTDIR
set -euo pipefail
pelt=$1 png_diff=$2 out=$3/docs-images
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
if [ ! -f "${CGAL_ARCHIVE:-/usr/share/doc/libcgal-dev/data.tar.gz}" ]; then
  echo "SKIPPED: libcgal-demo is not installed (the gallery renders its meshes)"
  exit 77
fi
rm -rf "$out"
"$here/scripts/docs-images.sh" "$out" "$pelt"
PNG_DIFF=$png_diff "$here/scripts/docs-images-compare.sh" "$out"
