#!/usr/bin/env bash
# Installs the built project into a temporary prefix, then builds and runs a consumer program
# against it both ways: pkg-config (shared, and static) and CMake's find_package(icshadow).
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
echo "== pkg-config, static"
pcwords --cflags; cflags=("${words[@]}")
pcwords --static --libs-only-l
libs=()
for w in "${words[@]}"; do [ "$w" = -licshadow ] || libs+=("$w"); done
"$cc" -std=c11 "$src/tests/install/consumer.c" -o "$tmp/c_static" \
  "${cflags[@]}" "$libdir/libicshadow.a" "${libs[@]}"
"$tmp/c_static"
echo "== find_package(icshadow)"
cmake -S "$src/tests/install" -B "$tmp/cm" -DCMAKE_PREFIX_PATH="$prefix" -DCMAKE_C_COMPILER="$cc" >/dev/null
cmake --build "$tmp/cm" >/dev/null
"$tmp/cm/consumer_shared"
"$tmp/cm/consumer_static"
echo "install test: 4 passed, 0 failed"
