#!/usr/bin/env bash
# `icshadow isoline` with mixture lights: their SPEC holds ';', which ics_cli_test's argument
# list cannot carry, so these cases run here. Expected values: the median of
# 0.8 N(0, .25) + 0.2 N(2, .25) by bisection in Python's math.erfc, 0.15928145625928486, so the
# correct 1/2-isoline at d = 2 is -0.31856291251857; the iterated one stays at -d mean = -0.8.
set -u
cli=$1
fail=0
run() { # run EXPECTED_RC STDOUT_REGEX STDERR_REGEX args...
  local want=$1 oexp=$2 eexp=$3; shift 3
  local errf="${TMPDIR:-/tmp}/theory_mix_err.$$"
  local out; out=$("$cli" "$@" 2>"$errf"); local rc=$?
  local err; err=$(cat "$errf"); rm -f "$errf"
  if [ "$rc" -ne "$want" ]; then echo "FAILED (exit $rc, want $want): $*"; echo "$err"; fail=1; fi
  if [ -n "$oexp" ] && ! printf '%s\n' "$out" | grep -Eq "$oexp"; then echo "FAILED stdout '$out' !~ $oexp: $*"; fail=1; fi
  if [ -n "$eexp" ] && ! printf '%s\n' "$err" | grep -Eq "$eexp"; then echo "FAILED stderr '$err' !~ $eexp: $*"; fail=1; fi
  if [ "$want" -ne 0 ] && [ -n "$out" ]; then echo "FAILED: a failed run wrote to stdout: $*"; fail=1; fi
}
mix='mix:0.8,0,0.25;0.2,2,0.25'
run 0 '^-0\.318562912518[0-9]*$' '' isoline --light "$mix" --level 0.5 --distance 2 --model correct
run 0 '^-0\.(8000|7999)[0-9]*$' '' isoline --light "$mix" --level 0.5 --distance 2 --d1 1 --slab 0.03125 --model iterative --kernel tophat
# CLT model: -d mean + 0 at s = 1/2
run 0 '^-0\.8(0000000000000[0-9]*)?$' '' isoline --light "$mix" --level 0.5 --distance 2 --d1 1 --model clt
run 2 '' 'not a number at position 13 of' isoline --light 'mix:1,0,1;1,x,1' --level 0.5 --distance 1 --model correct
run 2 '' 'component variance must be > 0 at position 15' isoline --light 'mix:1,0,1;1,2,0' --level 0.5 --distance 1 --model correct
run 2 '' 'negative weight at position 11' isoline --light 'mix:1,0,1;-1,2,1' --level 0.5 --distance 1 --model correct
run 2 '' 'weights of .* sum to zero' isoline --light 'mix:0,0,1;0,2,1' --level 0.5 --distance 1 --model correct
run 2 '' 'expected 3 comma-separated numbers at position 11' isoline --light 'mix:1,0,1;1' --level 0.5 --distance 1 --model correct
# overflow: the weights' sum (2e308) and the variance ((1e308 - 0)^2) are not finite doubles
run 2 '' "weights' sum, the mixture's mean or its variance overflows" isoline --light 'mix:1e308,0,1;1e308,1,1' --level 0.3 --distance 1 --model correct
run 2 '' "weights' sum, the mixture's mean or its variance overflows" isoline --light 'mix:1,1e308,1;1,-1e308,1' --level 0.3 --distance 1 --model correct
[ "$fail" -eq 0 ] && echo "theory_mix: all passed"
exit $fail
