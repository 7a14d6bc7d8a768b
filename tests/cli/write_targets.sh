#!/usr/bin/env bash
# Outputs to targets that are not regular files, made here (never the system's): a FIFO with a
# reader gets the finished bytes (make-env, render: their EXR is written to a private temporary
# file and copied in on commit); a character device that is full (a /dev/full of our own, mknod:
# root only, skipped with the reason otherwise) makes make-env, render and lut fail with the
# cause and exit 1 — and the device node is still there afterwards. A link to nothing gets its
# file created whole or not at all. A command's outputs are committed together: a full stdout
# leaves fit-light's and render's files unwritten. A full and a read-only file system (tmpfs
# mounts of our own, root only) leave the previous file and no temporary. SIGTERM while a
# temporary is open removes it. No temporary
# is left in TMPDIR (a private one here) or beside the targets.
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
# a full file system and a read-only one, each a tmpfs of our own (root, and a kernel that lets
# us mount; skipped with the reason otherwise): the previous file is intact, no temporary is
# left, and the message names the cause
mount_why=
if [ "$(id -u)" -ne 0 ]; then
  mount_why="not root"
elif ! { mkdir "$dir/small" "$dir/ro" && trap 'umount "$dir/small" "$dir/ro" 2> /dev/null; rm -rf "$dir"' EXIT &&
         mount -t tmpfs -o size=64k tmpfs "$dir/small" 2> "$dir/mount_err" &&
         mount -t tmpfs -o size=1m tmpfs "$dir/ro" 2>> "$dir/mount_err"; }; then
  mount_why="mount: $(head -1 "$dir/mount_err")"
fi
if [ -z "$mount_why" ]; then
  "$cli" make-env --lights $L --size 16x8 -o "$dir/small/map.exr" 2> "$dir/err"
  cp "$dir/small/map.exr" "$dir/map_before.exr"
  "$cli" make-env --lights $L --size 512x256 --supersample 1 -o "$dir/small/map.exr" 2> "$dir/err"; rc=$?
  expect '[ $rc -eq 1 ] && grep -q "No space left on device" "$dir/err" && cmp -s "$dir/small/map.exr" "$dir/map_before.exr" && [ "$(ls -A "$dir/small")" = map.exr ]'
  "$cli" lut --size 4096 --lang c -o "$dir/small/big.h" 2> "$dir/err"; rc=$?
  expect '[ $rc -eq 1 ] && grep -q "cannot write .*big.h: No space left on device" "$dir/err" && [ "$(ls -A "$dir/small")" = map.exr ]'
  "$cli" render --resolution 128x96 --aov all --slab-spacing 0.5 -o "$dir/small/r.exr" > /dev/null 2> "$dir/err"; rc=$?
  expect '[ $rc -eq 1 ] && grep -q "No space left on device" "$dir/err" && [ "$(ls -A "$dir/small")" = map.exr ]'
  cp "$dir/map_before.exr" "$dir/ro/map.exr"
  if ! mount -o remount,ro "$dir/ro" 2> "$dir/mount_err"; then
    echo "SKIPPED the read-only checks: mount -o remount,ro: $(head -1 "$dir/mount_err")"
  else
  for c in "make-env --lights $L --size 16x8 -o $dir/ro/map.exr" "lut --size 64 --lang glsl -o $dir/ro/lut.glsl" \
           "render --resolution 16x12 -o $dir/ro/r.exr"; do
    $cli $c > /dev/null 2> "$dir/err"; rc=$?
    expect '[ $rc -eq 1 ] && grep -q "Read-only file system" "$dir/err" && cmp -s "$dir/ro/map.exr" "$dir/map_before.exr" && [ "$(ls -A "$dir/ro")" = map.exr ]'
  done
  fi
  umount "$dir/small" "$dir/ro"
else
  echo "SKIPPED the full and read-only file-system checks: $mount_why"
fi
# a link to nothing: the file it names is created whole, or not at all (a write past the file
# size limit, as on a full disk, leaves neither a truncated file nor a temporary; the link stays)
ln -s made.exr "$dir/dangling"
"$cli" make-env --lights $L --size 64x32 -o "$dir/dangling" 2> "$dir/err"
expect '[ $? -eq 0 ] && [ -L "$dir/dangling" ] && [ -f "$dir/made.exr" ]'
ln -s big.exr "$dir/dangling2"
( trap '' XFSZ; ulimit -f 8; "$cli" make-env --lights $L --size 512x256 --supersample 1 -o "$dir/dangling2" ) 2> "$dir/err"; rc=$?
expect '[ $rc -eq 1 ] && grep -q "File too large" "$dir/err" && [ -L "$dir/dangling2" ] && [ ! -e "$dir/big.exr" ]'
# a write past the file-size limit (as on a full disk) names its cause, not "input/output error"
( trap '' XFSZ; ulimit -f 8; "$cli" lut --size 4096 --lang c -o "$dir/big.h" ) 2> "$dir/err"; rc=$?
expect '[ $rc -eq 1 ] && grep -q "cannot write .*big.h: File too large" "$dir/err" && [ ! -e "$dir/big.h" ]'
# all or none: when stdout fails (a full one), the files of the same command are not written
"$cli" fit-light "$dir/made.exr" --lights 1 -o "$dir/none.json" --plane-csv "$dir/none.csv" > /dev/full 2> "$dir/err"; rc=$?
expect '[ $rc -eq 1 ] && grep -q "cannot write stdout: No space left on device" "$dir/err" && [ ! -e "$dir/none.json" ] && [ ! -e "$dir/none.csv" ]'
"$cli" render --resolution 32x24 -o "$dir/none.exr" --png "$dir/none.png" > /dev/full 2> "$dir/err"; rc=$?
expect '[ $rc -eq 1 ] && grep -q "cannot write stdout" "$dir/err" && [ ! -e "$dir/none.exr" ] && [ ! -e "$dir/none.png" ]'
# SIGTERM while a command holds a temporary: fit-light has written -o's temporary and waits to
# open --plane-csv, a FIFO nobody reads; the signal removes the temporary and ends the process
"$cli" make-env --lights $L --size 64x32 -o "$dir/map.exr" 2>> "$dir/err"
mkfifo "$dir/plane.fifo"
"$cli" fit-light "$dir/map.exr" --lights 1 -o "$dir/sig.json" --plane-csv "$dir/plane.fifo" > /dev/null 2>&1 &
pid=$!
for _ in $(seq 1 200); do ls "$dir" | grep -q "^sig.json.tmp" && break; sleep 0.05; done
expect 'ls "$dir" | grep -q "^sig.json.tmp"'  # the temporary exists while it waits
kill -TERM $pid; wait $pid; rc=$?
expect '[ $rc -eq 143 ] && [ -z "$(ls "$dir" | grep "^sig.json")" ]'
expect '[ -z "$(ls "$dir" | grep tmp.)" ]'
expect '[ -z "$(ls -A "$dir/tmp")" ]'
finish cli_write_targets
