#!/usr/bin/env bash
# Every command with stdout on a full device (/dev/full) or closed: exit status 1 and a message
# naming stdout and the reason on stderr. (eval and bench are covered since before; these
# exited 1 without a word, and --help / --version exited 0.)
set -u
cli=$1
if [ ! -w /dev/full ]; then echo "no writable /dev/full: cannot run"; exit 1; fi
fail=0 pass=0
check() { # name, then the command's arguments
  local name=$1 err rc
  shift
  for target in full closed; do
    if [ $target = full ]; then
      err=$("$cli" "$@" 2>&1 >/dev/full </dev/null); rc=$?
    else
      err=$("$cli" "$@" 2>&1 >&- </dev/null); rc=$?
    fi
    if [ "$rc" -eq 1 ] && printf '%s' "$err" | grep -q "cannot write stdout: "; then
      pass=$((pass + 1))
    else
      echo "FAILED: $name, stdout $target: exit $rc, stderr: $err"
      fail=$((fail + 1))
    fi
  done
}
check help --help
check version --version
check kernel kernel ellipse --varx 1 --vary 0.25
check kernel_help kernel --help
check isoline isoline --light gauss:0,1 --level 0.5 --distance 1 --model correct
check iterate iterate --kernel dirac --var 1 --steps 1 --width 4
check kernel_table kernel-table --no-timing --iterations 2
check kernel_table_2d kernel-table --dims 2 --no-timing --iterations 2
check lut_report lut --report --sizes 8
check lut_help lut --help
check make_env_help make-env --help
check fit_light_help fit-light --help
echo "cli_stdout_full: $pass passed, $fail failed"
[ "$fail" -eq 0 ]
