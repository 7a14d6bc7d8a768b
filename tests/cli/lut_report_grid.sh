#!/usr/bin/env bash
# lut_report_grid.sh CLI — `lut --report` measures each size on the grid its header's stamp is
# measured on: the size-16 row has the same errors and grid_points alone and in a longer --sizes
# list, and its grid_points is the header stamp's point count.
set -u
cli=$1
row() { "$cli" lut --report --sizes "$1" | awk -F, '$1 == "lut" && $2 == 16 { print $3","$4","$5","$6","$7","$8","$13 }'; }
alone=$(row 16) || exit 1
listed=$(row 8,16,64) || exit 1
stamp=$("$cli" lut --size 16 --lang c | sed -n 's/.* on \([0-9]*\) grid points.*/\1/p' | head -1)
echo "size 16 alone: $alone; in 8,16,64: $listed; header stamp: $stamp grid points"
[ -n "$alone" ] && [ "$alone" = "$listed" ] || { echo "the size-16 row depends on the --sizes list"; exit 1; }
[ "${alone##*,}" = "$stamp" ] || { echo "grid_points ${alone##*,} != the stamp's $stamp"; exit 1; }
