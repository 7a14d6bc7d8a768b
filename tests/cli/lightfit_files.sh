#!/usr/bin/env bash
# make-env / fit-light output files: a failing run leaves an existing -o file exactly as it was
# (and no temporary siblings); fit-light with the same --seed writes a byte-identical lights
# file when EM resamples (--max-samples 2000 < the 14168 kept pixels of a 384 x 192 map), and a
# different seed a different one.
set -u
cli=$1
. "$(dirname "$0")/checks.sh"
M3="0.35,0.25,0.004,0.004,0,1,0.2,1,0.2:-0.45,-0.05,0.02,0.012,20,2,1,0.25,0.15:0.15,-0.55,0.012,0.0012,-70,1.5,0.2,0.3,1"

"$cli" make-env --lights "$M3" --size 384x192 -o "$dir/m3.exr"; rc=$?
expect '[ $rc -eq 0 ] && [ -s "$dir/m3.exr" ]'

# failing runs leave an existing output untouched
echo keep > "$dir/keep.json"
"$cli" fit-light "$dir/missing.exr" --lights 2 -o "$dir/keep.json" 2> /dev/null; rc=$?
expect '[ $rc -eq 2 ] && [ "$(cat "$dir/keep.json")" = keep ]'
"$cli" fit-light "$dir/m3.exr" --lights 2 --seed -1 -o "$dir/keep.json" 2> /dev/null; rc=$?
expect '[ $rc -eq 2 ] && [ "$(cat "$dir/keep.json")" = keep ]'
echo keep > "$dir/keep.exr"
"$cli" make-env --lights 0,0,0.01,0.01:0.3,0,0.01,0.01,0,1e38 --size 64x32 -o "$dir/keep.exr" 2> /dev/null; rc=$?
expect '[ $rc -eq 2 ] && [ "$(cat "$dir/keep.exr")" = keep ]'
expect '[ -z "$(ls "$dir" | grep tmp)" ]'

# seed reproducibility through the CLI
for s in 7 7 8; do
  "$cli" fit-light "$dir/m3.exr" --lights 3 --max-samples 2000 --seed $s -o "$dir/s$s.$((n = ${n:-0} + 1)).json" > "$dir/table$n" 2> /dev/null
  expect '[ $? -eq 0 ]'
done
# EM ran on at most 2000 resampled pixels (samples column), not on all 14168
expect 'awk -F, '"'"'NR == 2 { ok = $1 == 3 && $8 > 0 && $8 <= 2000 } END { exit !ok }'"'"' "$dir/table1"'
expect 'cmp -s "$dir/s7.1.json" "$dir/s7.2.json"'
expect '! cmp -s "$dir/s7.1.json" "$dir/s8.3.json"'

finish cli_lightfit_files
