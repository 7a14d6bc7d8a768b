#!/usr/bin/env bash
# The error-against-time sweep in shards (analysis/error_vs_time.py): a small sweep (64 x 48,
# two slab members, ellipse2 at a second resolution, Monte Carlo at 4 and 16 spp; 16-spp
# references) run whole and as shards 0/3, 1/3, 2/3; the merged shards equal the whole run byte
# for byte (--no-times: the rest is a function of the inputs). Then the refusals: a shard spec
# out of range, a missing task, a task twice, a shard of another sweep (another resolution, the
# same task count), a file that is not a sweep's, a reference made for another scene — exit 2
# with the reason and no output file.
set -u
py=$1 evt=$2  # the icshadow package on PYTHONPATH (tests/python.cmake installs it)
"$py" -c "import icshadow" 2>/dev/null || {
  echo "SKIPPED: the icshadow Python package is not importable (the CTest fixture python_install builds it; it needs cffi)"
  exit 77; }
. "$(dirname "$0")/checks.sh"
sweep() {
  "$py" "$evt" --quick --resolution 64x48 --resolutions 32x24 --ref-spp 16 \
    --reps 1 --no-times --ref "$dir/ref.exr" "$@" 2>> "$dir/log"
}
sweep --csv "$dir/all.csv"; expect '[ $? -eq 0 ]'
for i in 0 1 2; do sweep --shard $i/3 --csv "$dir/s$i.csv"; expect '[ $? -eq 0 ]'; done
expect '[ "$(wc -l < "$dir/all.csv")" -eq 6 ]'  # the header and 5 tasks
"$py" "$evt" --merge "$dir/s2.csv" "$dir/s0.csv" "$dir/s1.csv" --csv "$dir/merged.csv" 2>> "$dir/log"
expect '[ $? -eq 0 ] && cmp "$dir/all.csv" "$dir/merged.csv"'

"$py" "$evt" --shard 3/3 --csv "$dir/x.csv" 2> "$dir/err"; rc=$?
expect '[ $rc -eq 2 ] && grep -q "need N >= 1 and 0 <= I < N" "$dir/err" && [ ! -e "$dir/x.csv" ]'
"$py" "$evt" --shard 0/0 --csv "$dir/x.csv" 2> "$dir/err"; rc=$?
expect '[ $rc -eq 2 ] && [ ! -e "$dir/x.csv" ]'
"$py" "$evt" --merge "$dir/s0.csv" "$dir/s1.csv" --csv "$dir/x.csv" 2> "$dir/err"; rc=$?
expect '[ $rc -eq 2 ] && grep -q "tasks missing: 2" "$dir/err" && [ ! -e "$dir/x.csv" ]'
"$py" "$evt" --merge "$dir/s0.csv" "$dir/s1.csv" "$dir/s1.csv" "$dir/s2.csv" --csv "$dir/x.csv" 2> "$dir/err"; rc=$?
expect '[ $rc -eq 2 ] && grep -q "is in two shards" "$dir/err" && [ ! -e "$dir/x.csv" ]'
"$py" "$evt" --quick --resolution 48x32 --resolutions 32x24 --ref-spp 16 --reps 1 \
  --no-times --ref "$dir/ref2.exr" --shard 0/3 --csv "$dir/o0.csv" 2>> "$dir/log"
"$py" "$evt" --merge "$dir/o0.csv" "$dir/s1.csv" "$dir/s2.csv" --csv "$dir/x.csv" 2> "$dir/err"; rc=$?
expect '[ $rc -eq 2 ] && grep -q "is from another sweep" "$dir/err" && [ ! -e "$dir/x.csv" ]'
"$py" "$evt" --quick --resolution 48x32 --resolutions 32x24 --ref-spp 16 --reps 1 \
  --no-times --ref "$dir/ref.exr" --csv "$dir/x.csv" 2> "$dir/err"; rc=$?
expect '[ $rc -eq 2 ] && grep -q "ref.exr was not made for this scene" "$dir/err" && [ ! -e "$dir/x.csv" ]'
echo "a,b" > "$dir/other.csv"
"$py" "$evt" --merge "$dir/other.csv" --csv "$dir/x.csv" 2> "$dir/err"; rc=$?
expect '[ $rc -eq 2 ] && grep -q "not a sweep" "$dir/err" && [ ! -e "$dir/x.csv" ]'
finish cli_error_vs_time_shards
