#!/usr/bin/env bash
# `icshadow bench minmax|occtex|slab` with stdout on a full device (/dev/full): exit status 1 and a
# message naming stdout and the reason (strerror), not a silent failure.
set -u
cli=$1
if [ ! -w /dev/full ]; then echo "no writable /dev/full: cannot run"; exit 1; fi
fail=0
errf="${TMPDIR:-/tmp}/bench_full_err.$$"
check() { # name, then the command's arguments
  local name=$1; shift
  "$cli" "$@" >/dev/full 2>"$errf"
  local rc=$?
  local err; err=$(cat "$errf")
  if [ "$rc" -ne 1 ]; then echo "FAILED $name: exit status $rc, expected 1"; fail=1; fi
  if ! echo "$err" | grep -q "cannot write stdout: No space left on device"; then
    echo "FAILED $name: stderr '$err'"; fail=1
  fi
}
check minmax bench minmax --samples 32 --rows 2 --rays 2 --reps 1
check minmax_svd bench minmax --samples 32 --rows 2 --rays 2 --svd-table
check occtex bench occtex --sizes 8 --slices 1 --scene plates --receivers 2 --light-samples 2 --reps 1
check slab bench slab --sizes 16 --slabs 1 --reps 1 --threads 1 --kernels ellipse2,gauss19
rm -f "$errf"
[ $fail -eq 0 ] && echo "bench_stdout_full: 4 passed"
exit $fail
