#!/usr/bin/env bash
# Installs the built project into a temporary prefix, then builds and runs a consumer program
# against it both ways: pkg-config (shared, and static) and CMake's find_package(icshadow); and
# as a consumer of the core alone sees it, on a machine view without OpenEXR (pkg-config limited
# to the prefix, CMake with OpenEXR disabled): flags without OpenEXR's, no OpenEXR looked for.
# Shared consumers find the library at run time through the RUNPATH README gives them
# (-Wl,-rpath,$(pkg-config --variable=libdir icshadow); CMake sets it in the build tree).
# usage: run.sh BUILD_DIR SOURCE_DIR C_COMPILER
set -euo pipefail
build=$1 src=$2 cc=$3
tmp=$(mktemp -d)
case $tmp in
  *[][*?]*)
    # CMake's generated icshadowTargets.cmake globs its own directory, so find_package fails
    # from a prefix whose path holds '[', '*' or '?' (a CMake limitation, not ours): under such
    # a build path the prefix goes to /tmp
    rmdir "$tmp"
    tmp=$(mktemp -d /tmp/icshadow-install.XXXXXX) ;;
esac
trap 'rm -rf "$tmp"' EXIT
prefix=$tmp/prefix
cmake --install "$build" --prefix "$prefix" >/dev/null
test -x "$prefix/bin/icshadow" && test -f "$prefix/include/icshadow.h"
pc=$(dirname "$(find "$prefix" -name icshadow.pc | head -1)")
# pkg-config's words, as a shell would read them: it escapes blanks (and [ ]) in paths with '\',
# which plain $(...) splitting kept (the prefix under a build path with blanks broke the flags);
# read without -r undoes the escapes
pcwords() { local out; out=$(PKG_CONFIG_PATH=$pc pkg-config "$@" icshadow) && read -a words <<< "$out"; }
pcwords --variable=libdir; libdir=${words[*]}

echo "== pkg-config, shared"
pcwords --cflags --libs
"$cc" -std=c11 "$src/tests/install/consumer.c" -o "$tmp/c_shared" "${words[@]}" -Wl,-rpath,"$libdir"
"$tmp/c_shared"
echo "== pkg-config, shared, a machine view without OpenEXR's .pc"
out=$(PKG_CONFIG_LIBDIR=$pc pkg-config --cflags --libs icshadow) ||
  { echo "pkg-config --cflags --libs icshadow fails without OpenEXR's .pc"; exit 1; }
case "$out" in *OpenEXR*|*Imath*|*pthread*) echo "a core consumer gets OpenEXR's flags: $out"; exit 1 ;; esac
echo "flags: $out"
echo "== pkg-config, static"
pcwords --cflags; cflags=("${words[@]}")
pcwords --static --libs-only-l
libs=()
for w in "${words[@]}"; do [ "$w" = -licshadow ] || libs+=("$w"); done
"$cc" -std=c11 "$src/tests/install/consumer.c" -o "$tmp/c_static" \
  "${cflags[@]}" "$libdir/libicshadow.a" "${libs[@]}"
"$tmp/c_static"
echo "== find_package(icshadow), shared only, OpenEXR disabled"
log=$(cmake --no-warn-unused-cli -S "$src/tests/install" -B "$tmp/cm_core" -DCMAKE_PREFIX_PATH="$prefix" \
  -DCMAKE_C_COMPILER="$cc" -DICS_CONSUMER_STATIC=OFF -DCMAKE_DISABLE_FIND_PACKAGE_OpenEXR=ON 2>&1) ||
  { echo "$log"; echo "find_package(icshadow) needs OpenEXR for the shared library"; exit 1; }
case "$log" in *Imath*|*OpenEXR*) echo "$log"; echo "a core consumer's CMake run mentions OpenEXR"; exit 1 ;; esac
cmake --build "$tmp/cm_core" >/dev/null
"$tmp/cm_core/consumer_shared"
echo "== find_package(icshadow COMPONENTS static)"
cmake -S "$src/tests/install" -B "$tmp/cm" -DCMAKE_PREFIX_PATH="$prefix" -DCMAKE_C_COMPILER="$cc" >/dev/null
cmake --build "$tmp/cm" >/dev/null
"$tmp/cm/consumer_shared"
"$tmp/cm/consumer_static"
echo "install test: 6 passed, 0 failed"
