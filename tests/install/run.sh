#!/usr/bin/env bash
# Installs the built project into a temporary prefix, then builds and runs a consumer program
# against it both ways: pkg-config (shared, and static) and CMake's find_package(icshadow); and
# as a consumer of the core alone sees it, on a machine view without OpenEXR (pkg-config limited
# to the prefix, CMake with OpenEXR disabled): flags without OpenEXR's, no OpenEXR looked for.
# Shared consumers find the library at run time through the RUNPATH README gives them
# (-Wl,-rpath,$(pkg-config --variable=libdir icshadow); CMake sets it in the build tree).
# A program that builds a summed-area table on an OpenCL device against the installed
# libicshadow_cl, through pkg-config icshadow-cl and find_package(icshadow COMPONENTS cl) (where
# this machine has no OpenCL device it checks the link).
# Where the renderer was built, also a program that renders the default scene to an EXR against
# the installed libicshadow_render, through pkg-config icshadow-render and through
# find_package(icshadow COMPONENTS render).
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
echo "== pkg-config icshadow-cl, a summed-area table on an OpenCL device"
out=$(PKG_CONFIG_PATH=$pc pkg-config --cflags --libs icshadow-cl) && read -a words <<< "$out"
case "$out" in *render*|*jansson*) echo "libicshadow_cl's flags name the renderer: $out"; exit 1 ;; esac
"$cc" -std=c11 "$src/tests/install/consumer_cl.c" -o "$tmp/c_cl" "${words[@]}" -Wl,-rpath,"$libdir"
"$tmp/c_cl"
echo "== find_package(icshadow COMPONENTS cl)"
cmake -S "$src/tests/install" -B "$tmp/cm_cl" -DCMAKE_PREFIX_PATH="$prefix" -DCMAKE_C_COMPILER="$cc" \
  -DICS_CONSUMER_STATIC=OFF -DICS_CONSUMER_CL=ON >/dev/null
cmake --build "$tmp/cm_cl" >/dev/null
"$tmp/cm_cl/consumer_cl"
n=8
if [ -f "$prefix/include/icshadow/render.h" ]; then
  # the renderer, from C, with only the installed tree (README "Rendering from C")
  echo "== pkg-config icshadow-render, a render of the default scene to an EXR"
  out=$(PKG_CONFIG_PATH=$pc pkg-config --cflags --libs icshadow-render) && read -a words <<< "$out"
  "$cc" -std=c11 "$src/tests/install/consumer_render.c" -o "$tmp/c_render" "${words[@]}" -Wl,-rpath,"$libdir"
  "$tmp/c_render" "$tmp/pc.exr"
  test -s "$tmp/pc.exr"
  echo "== find_package(icshadow COMPONENTS render)"
  cmake -S "$src/tests/install" -B "$tmp/cm_render" -DCMAKE_PREFIX_PATH="$prefix" -DCMAKE_C_COMPILER="$cc" \
    -DICS_CONSUMER_STATIC=OFF -DICS_CONSUMER_RENDER=ON >/dev/null
  cmake --build "$tmp/cm_render" >/dev/null
  "$tmp/cm_render/consumer_render" "$tmp/cm.exr"
  test -s "$tmp/cm.exr"
  cmp "$tmp/pc.exr" "$tmp/cm.exr"
  echo "== a program of the renderer's alone, linked --as-needed: libicshadow found beside it"
  printf '#include <icshadow/render.h>\nint main(void) { return ics_backend_count() > 0 ? 0 : 1; }\n' > "$tmp/only.c"
  "$cc" -std=c11 "$tmp/only.c" -o "$tmp/c_only" -Wl,--as-needed "${words[@]}" -Wl,-rpath,"$libdir"
  "$tmp/c_only"
  echo "== the modules, installed beside the library and loaded from there"
  mods=$(ls "$libdir"/icshadow/icshadow-*.so 2>/dev/null | wc -l)
  built=$(ls "$build"/lib/icshadow/icshadow-*.so 2>/dev/null | wc -l)
  [ "$mods" -eq "$built" ] || { echo "$mods modules installed in $libdir/icshadow, $built built"; exit 1; }
  if [ "$built" -gt 0 ]; then
    loaded=$(LD_DEBUG=files "$prefix/bin/icshadow" render --backends 2>&1 >/dev/null |
      grep -Eo "file=[^ ]*icshadow-[a-z]+\.so" | sort -u | sed 's/file=//')
    echo "$loaded"
    real_libdir=$(realpath "$libdir")
    echo "$loaded" | grep -v -q "^$real_libdir/icshadow/" &&
      { echo "the installed icshadow loaded a module from outside $real_libdir/icshadow"; exit 1; }
    [ "$(echo "$loaded" | grep -c .)" -eq "$built" ] ||
      { echo "the installed icshadow loaded $(echo "$loaded" | grep -c .) of $built modules"; exit 1; }
  fi
  n=12
fi
echo "install test: $n passed, 0 failed"
