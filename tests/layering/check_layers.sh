#!/usr/bin/env bash
# The layering rules of docs/architecture.md, checked:
#   check_layers.sh includes ROOT   every #include in ROOT's library folders
#                                   points down the stack (core knows no GL,
#                                   nothing above it; core's folders form a DAG)
#   check_layers.sh circles OBJ...  no two object files of a library call
#                                   each other, directly or round a loop
#                                   (from their symbols, with nm and tsort)
#   check_layers.sh self-test ROOT  both checks catch a planted violation
set -euo pipefail

# What each folder may include, as extended regular expressions over the
# quoted or bracketed include path. System headers not named here are free.
forbidden_system='^(epoxy/|EGL/|GL/|GLES|GLFW/|cjson/|assimp/)'
allowed_local() {
    case "$1" in
        core/base/*)  echo '^(pelt/(base|camera|params|compare)\.h|core/base/)' ;;
        core/mesh/*)  echo '^(pelt/(base|mesh|animation)\.h|core/(base|mesh)/)' ;;
        core/atlas/*) echo '^(pelt/(base|mesh|atlas|params)\.h|core/(base|mesh|atlas)/)' ;;
        core/wet/*)   echo '^(pelt/(base|mesh|wetness|fur)\.h|core/(base|mesh|wet)/)' ;;
        core/fur/*)   echo '^(pelt/(base|mesh|fur|groom|dynamics|wetness|shadow|params|camera)\.h|core/(base|mesh|wet|fur)/)' ;;
        gl/*)         echo '^(pelt/(base|camera|mesh|fur|dynamics|wetness|shadow|render)\.h|core/base/|core/fur/(fur_gpu|frame_plan)\.h|gl/)' ;;
        scene/*)      echo '^(pelt/|core/base/|scene/)' ;;
        platform/*)   echo '^(pelt/(base|headless|window)\.h|core/base/|platform/)' ;;
        *)            echo '.' ;;
    esac
}
system_allowed() {
    case "$1" in
        core/*|scene/*) ! [[ "$2" =~ $forbidden_system ]] || [[ "$1" == core/mesh/* && "$2" == assimp/* ]] ||
                        [[ "$1" == scene/* && "$2" == cjson/* ]] ;;
        gl/*)           [[ ! "$2" =~ ^(EGL/|GLFW/|cjson/|assimp/) ]] ;;
        *)              true ;;
    esac
}

check_includes() {
    local root=$1 bad=0 f rel line path allowed
    while IFS= read -r f; do
        rel=${f#"$root"/}
        allowed=$(allowed_local "$rel")
        while IFS= read -r line; do
            path=$(sed -E 's/^[0-9]+:[[:space:]]*#[[:space:]]*include[[:space:]]*[<"]([^>"]+)[>"].*/\1/' <<<"$line")
            if [[ "$line" =~ \" ]]; then
                if [[ "$path" == core/mesh/mesh_internal.h && "$rel" != core/mesh/* ]]; then
                    echo "$rel:${line%%:*}: includes \"$path\": the mesh's layout is core/mesh's own; use pelt/mesh.h (docs/architecture.md)"
                    bad=1
                elif [[ ! "$path" =~ $allowed ]]; then
                    echo "$rel:${line%%:*}: includes \"$path\": not allowed in ${rel%/*}/ (docs/architecture.md)"
                    bad=1
                fi
            elif ! system_allowed "$rel" "$path"; then
                echo "$rel:${line%%:*}: includes <$path>: not allowed in ${rel%/*}/ (docs/architecture.md)"
                bad=1
            fi
        done < <(grep -nE '^[[:space:]]*#[[:space:]]*include' "$f" || true)
    done < <(find "$root/core" "$root/gl" "$root/scene" "$root/platform" -name '*.[ch]' | sort)
    return $bad
}

# Edges "caller callee" between object files, from the undefined and the
# defined global symbols; tsort reports any loop.
check_circles() {
    local defs edges
    defs=$(mktemp) edges=$(mktemp)
    for o in "$@"; do
        nm -g --defined-only "$o" | awk -v o="$(basename "$o" .o)" '$2 ~ /^[TDBR]$/ {print $3, o}'
    done | sort >"$defs"
    for o in "$@"; do
        nm -u "$o" | awk '{print $2}' | sort -u | join - "$defs" | awk -v o="$(basename "$o" .o)" '$2 != o {print o, $2}'
    done | sort -u >"$edges"
    local out rc=0
    out=$( (cat "$edges"; awk '{print $2, $2}' "$defs") | tsort 2>&1 >/dev/null) || rc=1
    rm -f "$defs" "$edges"
    if [ -n "$out" ] || [ $rc -ne 0 ]; then
        echo "call circle between object files:"
        echo "$out" | sed 's/^tsort: /  /'
        return 1
    fi
}

self_test() {
    local root=$1 tmp
    tmp=$(mktemp -d)
    trap 'rm -rf "$tmp"' RETURN
    cp -r "$root/core" "$root/gl" "$root/scene" "$root/platform" "$tmp/"
    check_includes "$tmp" >/dev/null || { echo "self-test: the clean tree fails"; return 1; }
    # Each plant: a file, the line put at its top, what it stands for.
    expect_caught() {
        sed -i "1i $2" "$tmp/$1"
        if check_includes "$tmp" >"$tmp/out"; then
            echo "self-test: $3 was not caught"
            return 1
        fi
        echo "self-test: caught: $(cat "$tmp/out")"
        sed -i '1d' "$tmp/$1"
    }
    local victim
    victim=$(cd "$tmp" && find core/fur -name '*.c' | sort | head -1)
    expect_caught "$victim" '#include <epoxy/gl.h>' "a core file that includes <epoxy/gl.h>" || return 1
    expect_caught core/base/vec.c '#include "gl/gpu.h"' "core/base including gl/" || return 1
    expect_caught core/wet/mask.c '#include "core/mesh/mesh_internal.h"' \
        "core/wet including core/mesh/mesh_internal.h" || return 1
    printf 'int b(int);\nint a(int x) { return x ? b(x - 1) : 0; }\n' >"$tmp/a.c"
    printf 'int a(int);\nint b(int x) { return a(x); }\n' >"$tmp/b.c"
    printf 'int a(int);\nint c(int x) { return a(x); }\n' >"$tmp/c.c"
    cc -c "$tmp/a.c" -o "$tmp/a.o" && cc -c "$tmp/b.c" -o "$tmp/b.o" && cc -c "$tmp/c.c" -o "$tmp/c.o"
    check_circles "$tmp/a.o" "$tmp/c.o" >/dev/null || { echo "self-test: c -> a is no circle"; return 1; }
    if check_circles "$tmp/a.o" "$tmp/b.o" "$tmp/c.o" >"$tmp/out"; then
        echo "self-test: the circle a <-> b was not caught"
        return 1
    fi
    echo "self-test: caught: $(tr '\n' ' ' <"$tmp/out")"
}

case "${1:-}" in
    includes) check_includes "$2" && echo "includes: every layer points down" ;;
    circles) shift; check_circles "$@" && echo "circles: none among $# object files" ;;
    self-test) self_test "$2" ;;
    *) echo "usage: $0 includes ROOT | circles OBJ... | self-test ROOT" >&2; exit 2 ;;
esac
