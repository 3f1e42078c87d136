#!/usr/bin/env bash
# The Debian packages: `cpack -G DEB` in the package fixture's build tree
# (tests/package/build_package.sh), then checks of what a user installs:
# names, Depends, files only under /usr; `dpkg -x` of all three into a
# scratch root, where pelt --help, a render, the manual page, the bash
# completion and find_package(pelt) against root/usr must all work.
#   deb.sh BUILD_DIR SOURCE_DIR OUT
set -u
build=$1 src=$2 out=$3
missing=""
for tool in dpkg-deb dpkg-shlibdeps file readelf; do
  command -v $tool >/dev/null 2>&1 || missing="$missing $tool"
done
if [ -n "$missing" ]; then
  echo "SKIP: the .deb test needs$missing (Debian packages dpkg, dpkg-dev, file, binutils;"
  echo "      scripts/setup.sh --tests installs them)"
  exit 77
fi
fails=0 passes=0
check() { if [ "$2" -eq 0 ]; then echo "ok   $1"; passes=$((passes+1)); else echo "FAIL $1: $3"; fails=$((fails+1)); fi; }
version=$(sed -n 's/^project(pelt VERSION \([0-9.]*\).*/\1/p' "$src/CMakeLists.txt")
major=${version%%.*}

rm -f "$build"/*.deb
(cd "$build" && cpack -G DEB) >"$out/cpack.log" 2>&1
check cpack_runs $? "$(tail -20 "$out/cpack.log")"
deb() { ls "$build/$1"_"$version"-*_*.deb 2>/dev/null | head -1; }
lib=$(deb "libpelt$major") cli=$(deb pelt) dev=$(deb libpelt-dev)
[ -n "$lib" ] && [ -n "$cli" ] && [ -n "$dev" ]
check three_packages $? "got: $(cd "$build" && ls *.deb 2>/dev/null | tr '\n' ' ')"
[ -n "$lib" ] && [ -n "$cli" ] && [ -n "$dev" ] || { echo "$passes passed, $fails failed"; exit 1; }
for d in "$lib" "$cli" "$dev"; do
  echo "  $(basename "$d"): $(stat -c %s "$d") bytes; Depends: $(dpkg-deb -f "$d" Depends)"
done

# Depends: what the binaries link (from dpkg-shlibdeps) and what libepoxy
# loads at run time; never a sanitizer runtime.
for d in "$lib" "$cli"; do
  dep=$(dpkg-deb -f "$d" Depends)
  ok=0
  for p in libc6 libepoxy0 libassimp5 libcjson1 libegl1 libgl1; do grep -q "\b$p\b" <<<"$dep" || ok=1; done
  grep -qE "libasan|libubsan" <<<"$dep" && ok=1
  check "depends_$(dpkg-deb -f "$d" Package)" $ok "$dep"
done
# pelt view loads GLFW at run time (dlopen), so the command's package names it.
dep=$(dpkg-deb -f "$cli" Depends)
grep -q "\blibglfw3\b" <<<"$dep"; check depends_pelt_glfw_for_view $? "$dep"
dep=$(dpkg-deb -f "$dev" Depends)
grep -q "libpelt$major (= $version-" <<<"$dep" && grep -q "libassimp-dev" <<<"$dep" && grep -q "libepoxy-dev" <<<"$dep"
check depends_libpelt_dev $? "$dep"
bad=$(for d in "$lib" "$cli" "$dev"; do dpkg-deb -c "$d"; done | awk '{print $6}' | grep -v '^\./usr/' | grep -v '^\./$')
[ -z "$bad" ]; check files_only_under_usr $? "$bad"

root="$out/root"; rm -rf "$root"; mkdir -p "$root"
for d in "$lib" "$cli" "$dev"; do dpkg -x "$d" "$root" || check "dpkg_x_$(basename "$d")" 1 "dpkg -x failed"; done
pelt="$root/usr/bin/pelt"
log=$("$pelt" --help 2>&1); rc=$?
[ $rc -eq 0 ] && grep -q "usage: pelt COMMAND" <<<"$log"
check installed_pelt_help $? "exit $rc: $log"
[ "$("$pelt" --version 2>&1)" = "pelt $version" ]; check installed_pelt_version $? "$("$pelt" --version 2>&1)"
log=$("$pelt" render -q --size 64x48 -o "$out/deb_render.png" 2>&1); rc=$?
[ $rc -eq 0 ] && [ -s "$out/deb_render.png" ]; check installed_pelt_renders $? "exit $rc: $log"
man1=$(ls "$root"/usr/share/man/man1/pelt.1* 2>/dev/null | head -1)
[ -n "$man1" ] && zcat -f "$man1" | grep -q '^\.SH "RENDER, BENCH AND COMPARE FLAGS"'
check manual_page_installed $? "no pelt.1 in usr/share/man/man1"
comp="$root/usr/share/bash-completion/completions/pelt"
[ -f "$comp" ] && bash -n "$comp" && grep -q "complete -F _pelt pelt" "$comp"
check completion_installed $? "no valid $comp"

# The development package is usable where it was unpacked.
mkdir -p "$out/deb-consumer"
bash "$src/tests/package/find_package.sh" cmake "$root/usr" "$src" "$out/deb-consumer" \
  >"$out/deb-find-package.log" 2>&1
check find_package_in_unpacked_dev_package $? "$(grep -E 'FAIL' "$out/deb-find-package.log")"

echo "$passes passed, $fails failed"
[ $fails -eq 0 ]
