#!/usr/bin/env bash
# Compares the pictures rendered by scripts/docs-images.sh with the committed
# ones: every OUTDIR/*.png against the picture of the same name in docs/images/
# (or in REFDIR), with png_diff (tests/tools/png_diff.c). One line per picture; exits 1 if
# any picture differs, is missing on either side, or cannot be read.
#
#   scripts/docs-images-compare.sh OUTDIR [REFDIR]
#
# REFDIR defaults to docs/images of this checkout; give another render
# (e.g. the baseline /tmp/docs-before) to compare code before and after a change.
# Environment:
#   PNG_DIFF        a built png_diff (default: compiled from tests/tools/png_diff.c
#                   into a temporary directory with gcc)
#   PNG_DIFF_FLAGS  tolerance flags passed on, e.g. "--max-mean 4 --max-frac 0.03"
#                   (the golden-image tolerance of tests/gl/test_render.c); default:
#                   png_diff's own defaults (mean <= 1.0, at most 1% of pixels off by > 32)
#   ALLOW_MISSING=1 a picture of REFDIR that OUTDIR lacks (e.g. skipped without the
#                   CGAL archive) is reported but does not fail the comparison
set -euo pipefail

if [ $# -lt 1 ] || [ $# -gt 2 ] || [ "${1:-}" = -h ] || [ "${1:-}" = --help ]; then
  echo "usage: $0 OUTDIR [REFDIR]" >&2
  exit 2
fi

here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
OUT="$1"
REF="${2:-$here/docs/images}"
for d in "$OUT" "$REF"; do
  if [ ! -d "$d" ]; then
    echo "docs-images-compare: no directory $d" >&2
    exit 2
  fi
done

TMP="$(mktemp -d "${TMPDIR:-/tmp}/docs-compare.XXXXXX")"
trap 'rm -rf "$TMP"' EXIT

PNG_DIFF="${PNG_DIFF:-}"
if [ -z "$PNG_DIFF" ]; then
  src="$here/tests/tools/png_diff.c"
  if [ ! -f "$src" ]; then
    echo "docs-images-compare: no $src; set PNG_DIFF to a built png_diff" >&2
    exit 2
  fi
  PNG_DIFF="$TMP/png_diff"
  gcc -std=c11 -O2 -Wall -Wextra -I/usr/include/stb "$src" -o "$PNG_DIFF" -lstb -lm
fi
read -r -a flags <<<"${PNG_DIFF_FLAGS:-}"

echo "docs-images-compare: $OUT vs $REF${PNG_DIFF_FLAGS:+ ($PNG_DIFF_FLAGS)}"
printf '  %-28s %-10s %12s %14s  %s\n' picture result "mean error" "pixels off" note
n=0 bad=0 missing=0
shopt -s nullglob
for a in "$OUT"/*.png; do
  name="$(basename "$a")"
  b="$REF/$name"
  n=$((n + 1))
  if [ ! -f "$b" ]; then
    printf '  %-28s %-10s %12s %14s  %s\n' "$name" DIFFERENT - - "no $name in $REF"
    bad=$((bad + 1))
    continue
  fi
  rc=0
  report="$("$PNG_DIFF" "$a" "$b" ${flags[@]+"${flags[@]}"} 2>&1)" || rc=$?
  mean="$(sed -n 's/.*; RGB \([0-9.]*\) .*/\1/p' <<<"$report")"
  frac="$(sed -n 's/^pixels off by > [0-9.]*: [0-9]* of [0-9]* = \([0-9.]*\) .*/\1/p' <<<"$report")"
  note=""
  case "$rc" in
    0) result=same ;;
    1) result=DIFFERENT
       if grep -q '^size: .*DIFFERENT' <<<"$report"; then
         note="size: $(sed -n 's/^size: [^ ]* \([0-9x]*\), [^ ]* \([0-9x]*\):.*/rendered \1, committed \2/p' <<<"$report")"
       fi ;;
    *) result=ERROR
       note="$(tr '\n' ' ' <<<"$report")" ;;
  esac
  [ "$rc" = 0 ] || bad=$((bad + 1))
  printf '  %-28s %-10s %12s %14s  %s\n' "$name" "$result" "${mean:--}" "${frac:--}" "$note"
done
for b in "$REF"/*.png; do
  name="$(basename "$b")"
  if [ ! -f "$OUT/$name" ]; then
    printf '  %-28s %-10s %12s %14s  %s\n' "$name" MISSING - - "not rendered in $OUT"
    missing=$((missing + 1))
  fi
done
echo "docs-images-compare: $((n - bad)) of $n rendered pictures match, $bad differ, $missing not rendered"
if [ "$n" = 0 ] || [ "$bad" != 0 ] || { [ "$missing" != 0 ] && [ "${ALLOW_MISSING:-0}" != 1 ]; }; then
  exit 1
fi
