#!/usr/bin/env bash
# Outputs to targets that are not regular files, made here (never the system's): a FIFO with a
# reader gets the finished bytes (make-env, render: their EXR is written to a private temporary
# file and copied in on commit); a character device that is full (a /dev/full of our own, mknod:
# root only, skipped with the reason otherwise) makes make-env, render and lut fail with the
# cause and exit 1 — and the device node is still there afterwards. No temporary is left in
# TMPDIR (a private one here).
set -u
cli=$1
. "$(dirname "$0")/checks.sh"
mkdir "$dir/tmp"
export TMPDIR=$dir/tmp
L=0,0,0.01,0.01,0,1,1,1,1
mkfifo "$dir/fifo"
cat "$dir/fifo" > "$dir/from_fifo.exr" & reader=$!
"$cli" make-env --lights $L --size 64x32 -o "$dir/fifo" 2> "$dir/err"; rc=$?
wait $reader
expect '[ $rc -eq 0 ] && [ -p "$dir/fifo" ]'
"$cli" fit-light "$dir/from_fifo.exr" --lights 1 -o "$dir/l.json" 2>> "$dir/err"
expect '[ $? -eq 0 ] && grep -q "\"mean\"" "$dir/l.json"'
cat "$dir/fifo" > "$dir/render_fifo.exr" & reader=$!
"$cli" render --resolution 32x24 -o "$dir/fifo" > /dev/null 2>> "$dir/err"; rc=$?
wait $reader
"$cli" render --resolution 32x24 --compare "$dir/render_fifo.exr" --png "$dir/r.png" > "$dir/cmp.json" 2>> "$dir/err"
expect '[ $rc -eq 0 ] && grep -q "\"rmse\": 0," "$dir/cmp.json"'
if [ "$(id -u)" -eq 0 ]; then
  mknod "$dir/full" c 1 7
  "$cli" make-env --lights $L --size 64x32 -o "$dir/full" 2> "$dir/err"; rc=$?
  expect '[ $rc -eq 1 ] && grep -q "No space left on device" "$dir/err" && [ -c "$dir/full" ]'
  "$cli" render --resolution 32x24 -o "$dir/full" > /dev/null 2> "$dir/err"; rc=$?
  expect '[ $rc -eq 1 ] && grep -q "No space left on device" "$dir/err" && [ -c "$dir/full" ]'
  "$cli" lut --size 64 --lang glsl -o "$dir/full" 2> "$dir/err"; rc=$?
  expect '[ $rc -eq 1 ] && [ -c "$dir/full" ]'
else
  echo "SKIPPED the device checks: mknod needs root"
fi
expect '[ -z "$(ls -A "$dir/tmp")" ]'
finish cli_write_targets
