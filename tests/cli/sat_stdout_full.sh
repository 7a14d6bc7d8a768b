#!/usr/bin/env bash
# `icshadow bench sat2d|sat3d` with stdout on a full device (/dev/full): every output path
# (benchmark CSV, --lights, --chirp-csv -, --help) must report the write error on stderr and exit
# 1, not 0 as if the CSV had been written.
set -u
cli=$1
fail=0 pass=0
check() { # name, then the command's arguments
  local name=$1
  shift
  local err rc
  err=$("$cli" "$@" 2>&1 >/dev/full)
  rc=$?
  if [ "$rc" -eq 1 ] && printf '%s' "$err" | grep -q "cannot write stdout"; then
    pass=$((pass + 1))
  else
    echo "FAILED: $name: exit $rc, stderr: $err"
    fail=$((fail + 1))
  fi
}
check sat2d bench sat2d --width 16 --height 8 --reps 1 --boxes 2
check sat3d bench sat3d --size 8 --modes float --reps 1 --boxes 2
check chirp bench sat2d --chirp-csv -
check help bench sat3d --help
check lights bench sat3d --lights
echo "cli_sat_stdout_full: $pass passed, $fail failed"
[ "$fail" -eq 0 ]
