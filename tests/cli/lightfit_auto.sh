#!/usr/bin/env bash
# fit-light --lights auto: a map of three well-separated Gaussian lights (no sky) gives K = 3
# (the fewest lights within max(1 %, 1.25 x the best L1) of K = 1..8; docs/lightfit.md "How many
# lights"), the table has a row for every K, the file three lights; auto:2 stops at 2; a bad
# KMAX is refused.
set -u
cli=$1
. "$(dirname "$0")/checks.sh"
L=-0.5,0.3,0.01,0.006,20,1,1,1,1:0.45,0.25,0.02,0.02,0,0.7,1,1,1:0.1,-0.45,0.004,0.002,-60,1.5,1,1,1
"$cli" make-env --lights $L --size 256x128 -o "$dir/env.exr" 2> /dev/null
"$cli" fit-light "$dir/env.exr" --lights auto -o "$dir/l.json" > "$dir/out" 2> "$dir/err"; rc=$?
expect '[ $rc -eq 0 ] && grep -q "auto: K = 3," "$dir/err" && [ "$(grep -c "\"mean\"" "$dir/l.json")" -eq 3 ] && [ "$(tail -n +2 "$dir/out" | wc -l)" -eq 8 ]'
"$cli" fit-light "$dir/env.exr" --lights auto:2 -o "$dir/l2.json" > /dev/null 2> "$dir/err"; rc=$?
expect '[ $rc -eq 0 ] && grep -q "auto: K = 2," "$dir/err"'
"$cli" fit-light "$dir/env.exr" --lights auto:99 -o "$dir/l3.json" > /dev/null 2> "$dir/err"; rc=$?
expect '[ $rc -eq 2 ] && grep -q "expected auto or auto:KMAX with KMAX in 1..32" "$dir/err" && [ ! -e "$dir/l3.json" ]'
finish cli_lightfit_auto
