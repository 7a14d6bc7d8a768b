#!/usr/bin/env bash
# Installs the built project into a temporary prefix, then builds and runs a consumer program
# against it both ways: pkg-config (shared, and static) and CMake's find_package(icshadow).
# usage: run.sh BUILD_DIR SOURCE_DIR C_COMPILER
set -euo pipefail
build=$1 src=$2 cc=$3
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
prefix=$tmp/prefix
cmake --install "$build" --prefix "$prefix" >/dev/null
test -x "$prefix/bin/icshadow" && test -f "$prefix/include/icshadow.h"
pc=$(dirname "$(find "$prefix" -name icshadow.pc | head -1)")
libdir=$(PKG_CONFIG_PATH=$pc pkg-config --variable=libdir icshadow)

echo "== pkg-config, shared"
# shellcheck disable=SC2046
"$cc" -std=c11 "$src/tests/install/consumer.c" -o "$tmp/c_shared" \
  $(PKG_CONFIG_PATH=$pc pkg-config --cflags --libs icshadow) -Wl,-rpath,"$libdir"
"$tmp/c_shared"
echo "== pkg-config, static"
# shellcheck disable=SC2046
"$cc" -std=c11 "$src/tests/install/consumer.c" -o "$tmp/c_static" \
  $(PKG_CONFIG_PATH=$pc pkg-config --cflags icshadow) "$libdir/libicshadow.a" \
  $(PKG_CONFIG_PATH=$pc pkg-config --static --libs-only-l icshadow | sed 's/-licshadow//')
"$tmp/c_static"
echo "== find_package(icshadow)"
cmake -S "$src/tests/install" -B "$tmp/cm" -DCMAKE_PREFIX_PATH="$prefix" -DCMAKE_C_COMPILER="$cc" >/dev/null
cmake --build "$tmp/cm" >/dev/null
"$tmp/cm/consumer_shared"
"$tmp/cm/consumer_static"
echo "install test: 4 passed, 0 failed"
