#!/usr/bin/env bash
# `icshadow eval` on mixed input: good lines give results, the bad line is named on stderr by
# its number, gives nan on stdout (alignment kept), and the exit status is 2.
set -u
cli=$1
out=$(printf '0\n1\nhello\n0.5x\n-inf\n\n' | "$cli" eval ellipe 2>"${TMPDIR:-/tmp}/eval_err.$$")
rc=$?
err=$(cat "${TMPDIR:-/tmp}/eval_err.$$"); rm -f "${TMPDIR:-/tmp}/eval_err.$$"
fail=0
expect() { if ! eval "$1"; then echo "FAILED: $1"; fail=1; fi; }
expect '[ "$rc" -eq 2 ]'
expect '[ "$(echo "$out" | wc -l)" -eq 6 ]'
# E(0) = pi/2 and E(1) = 1 exactly rounded; E(-inf) = inf
expect '[ "$(echo "$out" | sed -n 1p)" = "1.5707963267948966" ]'
expect '[ "$(echo "$out" | sed -n 2p)" = "1" ]'
expect '[ "$(echo "$out" | sed -n 3p)" = "nan" ]'
expect '[ "$(echo "$out" | sed -n 5p)" = "inf" ]'
expect 'echo "$err" | grep -q "line 3: not a number"'
expect 'echo "$err" | grep -q "line 4: not a number"'
expect 'echo "$err" | grep -q "line 6: not a number"'
echo "$err"
# a NUL byte inside a line is named, not silently cut off
out=$(printf '7\0xx\n0.5\n' | "$cli" eval varx 2>"${TMPDIR:-/tmp}/eval_err.$$")
rc=$?
err=$(cat "${TMPDIR:-/tmp}/eval_err.$$"); rm -f "${TMPDIR:-/tmp}/eval_err.$$"
expect '[ "$rc" -eq 2 ] && [ "$(echo "$out" | sed -n 1p)" = "nan" ]'
expect 'echo "$err" | grep -q "line 1: contains a NUL byte"'
# stdin that cannot be read (a directory) is an error, not an empty input
"$cli" eval ellipk < / 2>/dev/null
expect '[ $? -eq 1 ]'
[ $fail -eq 0 ] && echo "cli_eval_bad_line: 12 passed, 0 failed"
exit $fail
