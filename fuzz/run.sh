#!/usr/bin/env bash
# Runs one libFuzzer harness for SECONDS from the seed corpus CORPUS (copied to a scratch folder,
# so new units do not touch the tree), with the dictionary fuzz/dict/NAME.dict where there is one
# (NAME: the corpus folder's name), and prints one summary line: executions, coverage
# (libFuzzer's cov: edges and ft: features), corpus size, and the finding if any. Exit status:
# 0 clean, 1 a crash / sanitizer report / broken invariant (the reproducer's path is printed and
# kept under $ICS_FUZZ_KEEP, default the scratch folder's parent), 2 usage.
set -u
[ $# -eq 3 ] || { echo "usage: run.sh HARNESS CORPUS SECONDS" >&2; exit 2; }
harness=$(cd "$(dirname "$1")" && pwd)/$(basename "$1") corpus=$(cd "$2" && pwd) seconds=$3
name=$(basename "$harness")
work=$(mktemp -d "${TMPDIR:-/tmp}/$name.XXXXXX") || exit 2
keep=${ICS_FUZZ_KEEP:-${TMPDIR:-/tmp}}
mkdir "$work/corpus" && cp "$corpus"/* "$work/corpus/" 2> /dev/null
cd "$work" || exit 2
dict=() d=$corpus/../../dict/$(basename "$corpus").dict
[ -f "$d" ] && dict=(-dict="$d")
"$harness" -max_total_time="$seconds" -timeout=20 -rss_limit_mb=4096 -seed=1 -print_final_stats=1 \
  "${dict[@]}" -artifact_prefix="$work/" "$work/corpus" > "$work/log" 2>&1
rc=$?
execs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$work/log" | tail -1)
cov=$(grep -o 'cov: [0-9]*' "$work/log" | tail -1 | cut -d' ' -f2)
ft=$(grep -o 'ft: [0-9]*' "$work/log" | tail -1 | cut -d' ' -f2)
units=$(ls "$work/corpus" | wc -l)
seeds=$(ls "$corpus" | wc -l)
if [ $rc -ne 0 ]; then
  tail -40 "$work/log"
  for a in "$work"/crash-* "$work"/leak-* "$work"/timeout-* "$work"/oom-* "$work"/slow-unit-*; do
    [ -e "$a" ] && cp "$a" "$keep/" && echo "$name: FINDING $(basename "$a") kept as $keep/$(basename "$a")"
  done
  echo "$name: FAILED (exit $rc) after ${execs:-?} executions in ${seconds} s"
  rm -rf "$work"
  exit 1
fi
echo "$name: ${execs:-?} executions in $seconds s, cov ${cov:-?} edges, ft ${ft:-?} features, corpus $seeds seeds -> $units units, no finding"
rm -rf "$work"
exit 0
