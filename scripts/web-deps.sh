#!/usr/bin/env bash
# Build pelt's C/C++ dependencies as static WebAssembly libraries with
# Debian's Emscripten, from Debian's own source packages:
#   cJSON, meshoptimizer, assimp (importers: glTF 2 / GLB, OBJ, PLY, STL, OFF),
#   plus what assimp needs: zlib and minizip.
#
# Usage: scripts/web-deps.sh [PREFIX]        (default: build-web/deps)
#
# Result: PREFIX/include (cjson/cJSON.h, meshoptimizer.h, assimp/..., zlib.h,
#         minizip/...) and PREFIX/lib/{libassimp,libminizip,libz,libmeshoptimizer,libcjson}.a
# Work files (downloads, unpacked sources, build trees, private apt state) live in
# PREFIX/../deps-src; nothing is vendored into the repository and /etc/apt is
# never touched.
#
# Versions are pinned to the source versions of the installed native -dev
# packages, so the web build uses the same code as the native build.
# A second run with the same pins (and the same script) exits at once.
#
# Consumers (assimp is built with -fexceptions, so malformed files raise a
# catchable error instead of aborting):
#   compile: -I PREFIX/include -fexceptions
#   link:    -fexceptions -L PREFIX/lib -lassimp -lminizip -lz -lmeshoptimizer -lcjson
#            (link with em++ or emcc; -fexceptions at link time implies
#             -sDISABLE_EXCEPTION_CATCHING=0)
set -euo pipefail

t_start=$(date +%s)
step() { printf '==> %s\n' "$*"; }
die() { printf 'web-deps: error: %s\n' "$*" >&2; exit 1; }
trap 'rc=$?; [ $rc -eq 0 ] || printf "web-deps: FAILED (exit %s) during: %s\n" "$rc" "${CURRENT_STEP:-setup}" >&2' EXIT

PREFIX=${1:-build-web/deps}
mkdir -p "$PREFIX"
PREFIX=$(cd "$PREFIX" && pwd)
WORK=$(dirname "$PREFIX")/deps-src
JOBS=$(nproc)
SCRIPT_SUM=$(sha256sum "${BASH_SOURCE[0]}" | cut -d' ' -f1)

# ---------------------------------------------------------------- pins
# Source package and version of an installed binary package.
pin() {
    local bin=$1 out src ver
    out=$(dpkg-query -W -f='${source:Package} ${source:Version} ${Version}' "$bin" 2>/dev/null) \
        || die "$bin is not installed; install the native build dependencies first"
    read -r src ver binver <<<"$out"
    if [ -z "${ver:-}" ]; then
        ver=$(printf '%s' "$binver" | sed -E 's/\+b[0-9]+$//')
    fi
    [ -n "$src" ] && [ -n "$ver" ] || die "cannot determine source version of $bin"
    printf '%s=%s\n' "$src" "$ver"
}
CURRENT_STEP="pinning versions"
PIN_CJSON=$(pin libcjson-dev)
PIN_MESHOPT=$(pin libmeshoptimizer-dev)
PIN_ASSIMP=$(pin libassimp-dev)
PIN_ZLIB=$(pin zlib1g-dev)
PIN_MINIZIP=$(pin libminizip-dev)
PINS="$PIN_ZLIB $PIN_MINIZIP $PIN_CJSON $PIN_MESHOPT $PIN_ASSIMP"
STAMP_TEXT="pins: $PINS
emcc: $(emcc --version 2>/dev/null | sed -n 1p)
script: $SCRIPT_SUM"

if [ -f "$PREFIX/.stamp" ] && [ "$(cat "$PREFIX/.stamp")" = "$STAMP_TEXT" ]; then
    echo "web-deps: $PREFIX is up to date ($PINS)"
    exit 0
fi

step "pinned: $PINS"
step "prefix: $PREFIX  work: $WORK  jobs: $JOBS"

# ---------------------------------------------------------------- host tools
CURRENT_STEP="host tools"
SUDO=
[ "$(id -u)" -eq 0 ] || SUDO=sudo
need_pkgs=()
for p in dpkg-dev cmake make pkg-config libutfcpp-dev libstb-dev; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q 'install ok installed' || need_pkgs+=("$p")
done
if [ ${#need_pkgs[@]} -gt 0 ]; then
    step "installing host packages: ${need_pkgs[*]}"
    $SUDO apt-get install -y --no-install-recommends "${need_pkgs[@]}"
fi
for t in emcc em++ emcmake emconfigure emmake emar cmake dpkg-source apt-get pkg-config; do
    command -v "$t" >/dev/null || die "missing tool: $t (Debian package emscripten / cmake / dpkg-dev / pkg-config)"
done

# ---------------------------------------------------------------- sources
CURRENT_STEP="fetching Debian sources"
APTDIR=$WORK/apt
mkdir -p "$APTDIR/lists/partial" "$APTDIR/cache/archives/partial" "$APTDIR/etc" "$WORK/dl"
KEYRING=/usr/share/keyrings/debian-archive-keyring.gpg
[ -f "$KEYRING" ] || die "$KEYRING missing (package debian-archive-keyring)"
cat >"$APTDIR/etc/sources.list" <<EOF
deb-src [signed-by=$KEYRING] http://deb.debian.org/debian bookworm main
deb-src [signed-by=$KEYRING] http://deb.debian.org/debian bookworm-updates main
deb-src [signed-by=$KEYRING] http://deb.debian.org/debian-security bookworm-security main
EOF
APT_OPTS=(
    -o "Dir::Etc::SourceList=$APTDIR/etc/sources.list"
    -o "Dir::Etc::SourceParts=/dev/null"
    -o "Dir::Etc::Preferences=/dev/null"
    -o "Dir::Etc::PreferencesParts=/dev/null"
    -o "Dir::State::Lists=$APTDIR/lists"
    -o "Dir::Cache=$APTDIR/cache"
    -o "Dir::Cache::archives=$APTDIR/cache/archives"
    -o "Debug::NoLocking=1"
    -o "APT::Get::Only-Source=1"
)
[ "$(id -u)" -ne 0 ] || APT_OPTS+=(-o "APT::Sandbox::User=root")
step "apt-get update (private source lists in $APTDIR)"
apt-get "${APT_OPTS[@]}" -q update >"$APTDIR/update.log" 2>&1 \
    || { cat "$APTDIR/update.log" >&2; die "apt-get update failed (network?)"; }

SRC=$WORK/src
rm -rf "$SRC"
mkdir -p "$SRC"
# fetch_src pkg=ver -> prints unpacked directory
fetch_src() {
    local spec=$1 pkg=${1%%=*} ver=${1#*=} dsc
    dsc="${pkg}_${ver#*:}.dsc"
    step "apt-get source --download-only $spec" >&2
    (cd "$WORK/dl" && apt-get "${APT_OPTS[@]}" -q source --download-only "$spec") >"$WORK/dl/$pkg.log" 2>&1 \
        || { cat "$WORK/dl/$pkg.log" >&2; die "cannot download source $spec"; }
    [ -f "$WORK/dl/$dsc" ] || die "expected $WORK/dl/$dsc after download"
    (cd "$SRC" && dpkg-source -q -x "$WORK/dl/$dsc" "$pkg") >"$WORK/dl/$pkg.x.log" 2>&1 \
        || { cat "$WORK/dl/$pkg.x.log" >&2; die "dpkg-source -x $dsc failed"; }
    printf '%s\n' "$SRC/$pkg"
}
S_ZLIB=$(fetch_src "$PIN_ZLIB")
S_MINIZIP=$(fetch_src "$PIN_MINIZIP")
S_CJSON=$(fetch_src "$PIN_CJSON")
S_MESHOPT=$(fetch_src "$PIN_MESHOPT")
S_ASSIMP=$(fetch_src "$PIN_ASSIMP")

# ---------------------------------------------------------------- build
rm -rf "$PREFIX" "$WORK/build"
mkdir -p "$PREFIX/include" "$PREFIX/lib/pkgconfig" "$WORK/build"
B=$WORK/build
CFLAGS_WEB="-O2"

CURRENT_STEP="zlib"
step "zlib (${PIN_ZLIB#*=})"
(
    cd "$S_ZLIB"
    CFLAGS="$CFLAGS_WEB" emconfigure ./configure --static --prefix="$PREFIX"
    emmake make -j"$JOBS" libz.a
    emmake make install
) >"$B/zlib.log" 2>&1 || { tail -40 "$B/zlib.log" >&2; die "zlib build failed (log: $B/zlib.log)"; }

CURRENT_STEP="minizip"
step "minizip (${PIN_MINIZIP#*=}) - the libminizip that Debian's assimp uses instead of contrib/unzip"
(
    mkdir -p "$B/minizip" "$PREFIX/include/minizip"
    cd "$B/minizip"
    # libminizip_la_SOURCES from the package's Makefile.am
    for f in ioapi mztools unzip zip; do
        emcc $CFLAGS_WEB -I"$PREFIX/include" -c "$S_MINIZIP/$f.c" -o "$f.o"
    done
    emar rcs "$PREFIX/lib/libminizip.a" ioapi.o mztools.o unzip.o zip.o
    cp "$S_MINIZIP"/{crypt,ioapi,mztools,unzip,zip}.h "$PREFIX/include/minizip/"
    mzver=${PIN_MINIZIP#*=}; mzver=${mzver%%-*}
    sed -e "s|@prefix@|$PREFIX|" -e 's|@exec_prefix@|${prefix}|' \
        -e 's|@libdir@|${exec_prefix}/lib|' -e 's|@includedir@|${prefix}/include|' \
        -e "s|@PACKAGE_VERSION@|$mzver|" "$S_MINIZIP/minizip.pc.in" >"$PREFIX/lib/pkgconfig/minizip.pc"
) >"$B/minizip.log" 2>&1 || { tail -40 "$B/minizip.log" >&2; die "minizip build failed (log: $B/minizip.log)"; }

cmake_build() { # name srcdir [cmake args...]
    local name=$1 src=$2; shift 2
    emcmake cmake -S "$src" -B "$B/$name" -DCMAKE_BUILD_TYPE=Release \
        -DCMAKE_INSTALL_PREFIX="$PREFIX" -DCMAKE_INSTALL_LIBDIR=lib -DBUILD_SHARED_LIBS=OFF "$@"
    cmake --build "$B/$name" -j"$JOBS"
    cmake --install "$B/$name"
}

CURRENT_STEP="cJSON"
step "cJSON (${PIN_CJSON#*=})"
# cJSON's own warning flags (-std=c89 -pedantic -Werror) trip over Emscripten's math.h.
cmake_build cjson "$S_CJSON" -DENABLE_CJSON_TEST=OFF -DENABLE_CJSON_UTILS=OFF \
    -DENABLE_CUSTOM_COMPILER_FLAGS=OFF \
    -DBUILD_SHARED_AND_STATIC_LIBS=OFF -DENABLE_TARGET_EXPORT=OFF \
    -DCMAKE_C_FLAGS="$CFLAGS_WEB" >"$B/cjson.log" 2>&1 \
    || { tail -40 "$B/cjson.log" >&2; die "cJSON build failed (log: $B/cjson.log)"; }

CURRENT_STEP="meshoptimizer"
step "meshoptimizer (${PIN_MESHOPT#*=})"
cmake_build meshoptimizer "$S_MESHOPT" -DMESHOPT_BUILD_SHARED_LIBS=OFF \
    -DMESHOPT_BUILD_DEMO=OFF -DMESHOPT_BUILD_GLTFPACK=OFF \
    -DCMAKE_CXX_FLAGS="$CFLAGS_WEB" >"$B/meshoptimizer.log" 2>&1 \
    || { tail -40 "$B/meshoptimizer.log" >&2; die "meshoptimizer build failed (log: $B/meshoptimizer.log)"; }

CURRENT_STEP="assimp"
step "assimp (${PIN_ASSIMP#*=}): glTF2/GLB, OBJ, PLY, STL, OFF importers, C++ exceptions on"
# Debian's assimp source drops contrib/{unzip,utf8cpp,stb,zlib} and uses the
# system libraries (debian/patches/use-system-*.patch): minizip and zlib are
# built above; the header-only utf8cpp and stb come from libutfcpp-dev and
# libstb-dev through a directory holding only those headers.
# Debian's use-system-libdraco.patch makes draco mandatory; draco is not
# needed here (no Draco-compressed glTF), so that one packaging patch is reverted.
(cd "$S_ASSIMP" && patch -R -p1 --quiet <debian/patches/use-system-libdraco.patch) \
    || die "cannot revert debian/patches/use-system-libdraco.patch in $S_ASSIMP"
HDR=$WORK/hdr
rm -rf "$HDR"; mkdir -p "$HDR"
ln -s /usr/include/utf8cpp/utf8.h "$HDR/utf8.h"
ln -s /usr/include/utf8cpp/utf8 "$HDR/utf8"
ln -s /usr/include/stb "$HDR/stb"
[ -f "$HDR/utf8.h" ] && [ -f "$HDR/stb/stb_image.h" ] || die "utf8cpp/stb headers missing (libutfcpp-dev, libstb-dev)"
ASSIMP_CXXFLAGS="$CFLAGS_WEB -fexceptions -I$HDR -DASSIMP_BUILD_NO_GLTF1_IMPORTER"
# pkg-config must see only our prefix (never the host's /usr/include/minizip).
PKG_CONFIG_LIBDIR="$PREFIX/lib/pkgconfig" PKG_CONFIG_PATH= PKG_CONFIG_SYSROOT_DIR= \
    EM_PKG_CONFIG_PATH= cmake_build assimp "$S_ASSIMP" \
    -DASSIMP_BUILD_ALL_IMPORTERS_BY_DEFAULT=OFF \
    -DASSIMP_BUILD_GLTF_IMPORTER=ON -DASSIMP_BUILD_OBJ_IMPORTER=ON \
    -DASSIMP_BUILD_PLY_IMPORTER=ON -DASSIMP_BUILD_STL_IMPORTER=ON \
    -DASSIMP_BUILD_OFF_IMPORTER=ON \
    -DASSIMP_BUILD_ALL_EXPORTERS_BY_DEFAULT=OFF -DASSIMP_NO_EXPORT=ON \
    -DASSIMP_BUILD_TESTS=OFF -DASSIMP_BUILD_ASSIMP_TOOLS=OFF \
    -DASSIMP_BUILD_SAMPLES=OFF -DASSIMP_BUILD_DOCS=OFF \
    -DASSIMP_BUILD_DRACO=OFF -DASSIMP_BUILD_ZLIB=OFF \
    -DASSIMP_WARNINGS_AS_ERRORS=OFF -DASSIMP_INJECT_DEBUG_POSTFIX=OFF \
    -DASSIMP_INSTALL_PDB=OFF -DASSIMP_IGNORE_GIT_HASH=ON \
    -DZLIB_LIBRARY="$PREFIX/lib/libz.a" -DZLIB_INCLUDE_DIR="$PREFIX/include" \
    -DCMAKE_C_FLAGS="$CFLAGS_WEB" -DCMAKE_CXX_FLAGS="$ASSIMP_CXXFLAGS" \
    >"$B/assimp.log" 2>&1 \
    || { tail -40 "$B/assimp.log" >&2; die "assimp build failed (log: $B/assimp.log)"; }
grep -qx "UNZIP_INCLUDE_DIRS:INTERNAL=$PREFIX/include/minizip" "$B/assimp/CMakeCache.txt" \
    || die "assimp did not pick up the wasm minizip from $PREFIX (see $B/assimp/CMakeCache.txt)"
if grep -rqE --include=flags.make --include='*.rsp' --include=build.ninja \
        -e '(-I|-isystem) ?"?/usr/include' "$B/assimp"; then
    die "assimp compile flags reference host /usr/include"
fi

CURRENT_STEP="check"
for f in cjson/cJSON.h meshoptimizer.h assimp/cimport.h zlib.h; do
    [ -f "$PREFIX/include/$f" ] || die "expected $PREFIX/include/$f after build"
done
for f in libcjson.a libmeshoptimizer.a libassimp.a libminizip.a libz.a; do
    [ -f "$PREFIX/lib/$f" ] || die "expected $PREFIX/lib/$f after build"
done

printf '%s\n' "$STAMP_TEXT" >"$PREFIX/.stamp"
t_end=$(date +%s)
step "done in $((t_end - t_start)) s: $PREFIX"
echo "    compile: -I$PREFIX/include -fexceptions"
echo "    link:    -fexceptions -L$PREFIX/lib -lassimp -lminizip -lz -lmeshoptimizer -lcjson"
