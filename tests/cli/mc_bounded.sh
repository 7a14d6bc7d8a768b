#!/usr/bin/env bash
# The Monte-Carlo reference's work is bounded before it starts and --time is a hard stop
# (issue: extinction 1e7 at 16 x 16 and 1 spp never finished; extinction 1e308 with detail
# ignored --time 2): the default scene with its fBm smoke made dense.
# - 1e7 at 16 x 16, 1 spp, no --time: refused at once with the estimate and the knobs;
# - 1e60 (steps finer than double precision): refused at once, even with --time (1e308 is now
#   refused by the scene reader, over ICS_SCENE_MAX_EXTINCTION: checked too);
# - 1e7 with --time 1 at 16 x 16: exit 2 when no pass of every pixel has finished, or exit 0
#   with the samples finished, within a few seconds either way (never a hang);
# - the default scene with --time stops with samples taken and a finite noise.
# Each command runs under `timeout`: a hang fails the check instead of the suite.
set -u
cli=$1
. "$(dirname "$0")/checks.sh"
"$cli" plan --print-scene -o "$dir/s.json"
for e in 1e7 1e60 1e308; do
  sed "s/\"extinction\": 14,/\"extinction\": $e,/" "$dir/s.json" > "$dir/e$e.json"
done
expect 'grep -q "\"extinction\": 1e7," "$dir/e1e7.json"'
timeout 60 "$cli" render "$dir/e1e7.json" --backend mc --spp 1 --resolution 16x16 -o "$dir/a.exr" > "$dir/out" 2> "$dir/err"; rc=$?
expect '[ $rc -eq 2 ] && grep -q "mc: up to .* volume tracking steps .* above the budget .* give --time S" "$dir/err" && [ ! -e "$dir/a.exr" ] && [ ! -s "$dir/out" ]'
timeout 60 "$cli" render "$dir/e1e60.json" --backend mc --time 2 --resolution 16x16 -o "$dir/b.exr" > /dev/null 2> "$dir/err"; rc=$?
expect '[ $rc -eq 2 ] && grep -q "cannot advance a position in double precision" "$dir/err" && [ ! -e "$dir/b.exr" ]'
timeout 60 "$cli" render "$dir/e1e308.json" --backend mc --time 2 --resolution 16x16 -o "$dir/b.exr" > /dev/null 2> "$dir/err"; rc=$?
expect '[ $rc -eq 2 ] && grep -q "materials.smoke: its extinction reaches 1.*e+308 per world unit" "$dir/err" && [ ! -e "$dir/b.exr" ]'
start=$(date +%s)
timeout 60 "$cli" render "$dir/e1e7.json" --backend mc --time 1 --resolution 16x16 -o "$dir/c.exr" > "$dir/out" 2> "$dir/err"; rc=$?
took=$(( $(date +%s) - start ))
expect '{ [ $rc -eq 2 ] && grep -q "no sample of every pixel finished within --time 1 s" "$dir/err" && [ ! -e "$dir/c.exr" ]; } || { [ $rc -eq 0 ] && grep -q "\"spp\": [1-9]" "$dir/out"; }'
expect '[ $took -lt 30 ]'
timeout 60 "$cli" render --backend mc --time 0.5 --resolution 32x24 -o "$dir/d.exr" > "$dir/out" 2> "$dir/err"; rc=$?
expect '[ $rc -eq 0 ] && grep -q "\"spp\": [1-9][0-9]*, \"noise\": [0-9]" "$dir/out"'
finish cli_mc_bounded
