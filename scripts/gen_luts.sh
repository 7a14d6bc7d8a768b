#!/bin/sh
# gen_luts.sh — regenerate the lookup-table headers the project itself uses, or check them.
#
#   scripts/gen_luts.sh [ICSHADOW]           rewrite the checked-in files
#   scripts/gen_luts.sh --check [ICSHADOW]   regenerate into a temporary folder and diff
#                                            (exit 1 on any difference; the lut_regen test)
# ICSHADOW defaults to build/bin/icshadow. The command builds the tables from the exact
# functions (ellipse.c), never from the library's own tables, so it can always regenerate
# libicshadow/src/lut_data.c. Sizes and the reasons for them: docs/lut.md.
set -eu
root=$(cd "$(dirname "$0")/.." && pwd)
check=0
if [ "${1:-}" = "--check" ]; then
  check=1
  shift
fi
cli=${1:-$root/build/bin/icshadow}
if [ ! -x "$cli" ]; then
  echo "gen_luts.sh: no icshadow at $cli (build first, or pass its path)" >&2
  exit 2
fi
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT INT TERM
status=0
# size  language  checked-in file (relative to the repository root)
while read -r size lang file; do
  "$cli" lut --size "$size" --lang "$lang" -o "$tmp/out"
  if [ "$check" = 1 ]; then
    if diff -u "$root/$file" "$tmp/out"; then
      echo "gen_luts.sh: $file is up to date (icshadow lut --size $size --lang $lang)"
    else
      echo "gen_luts.sh: $file differs from icshadow lut --size $size --lang $lang" >&2
      status=1
    fi
  else
    mv "$tmp/out" "$root/$file"
    echo "gen_luts.sh: wrote $file"
  fi
done <<LIST
256 c-data libicshadow/src/lut_data.c
256 glsl gpu/backends/gl/icshadow_lut.glsl
256 opencl gpu/backends/cl/icshadow_lut.cl
LIST
exit $status
