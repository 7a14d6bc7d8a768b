#!/usr/bin/env bash
# An empty output file name is a usage error (exit 2, a message, nothing on stdout) for
# `icshadow bench minmax --fig4-csv ""`, `bench occtex --fig3-csv ""`, `bench sat2d --chirp-csv
# ""`, `make-env -o ""` and `fit-light -o ""` / `--plane-csv ""` (make-env and fit-light used to
# exit 1 trying to open "").
set -u
cli=$1
fail=0
errf="${TMPDIR:-/tmp}/bench_empty_err.$$"
check() { # name, expected stderr text, then the command's arguments
  local name=$1 want=$2; shift 2
  local out; out=$("$cli" "$@" 2>"$errf")
  local rc=$?
  if [ "$rc" -ne 2 ]; then echo "FAILED $name: exit status $rc, expected 2"; fail=1; fi
  if [ -n "$out" ]; then echo "FAILED $name: wrote to stdout"; fail=1; fi
  if ! grep -q -- "$want" "$errf"; then echo "FAILED $name: stderr '$(cat "$errf")'"; fail=1; fi
}
check minmax "bench minmax: --fig4-csv: empty file name" bench minmax --samples 16 --fig4-csv ""
check occtex "bench occtex: --fig3-csv: empty file name" bench occtex --sizes 8 --fig3-csv ""
check sat "bench sat2d: --chirp-csv: empty file name" bench sat2d --chirp-csv ""
check make_env "make-env: -o: empty file name" make-env --lights 0,0,0.01,0.01,0,1,1,1,1 --size 64x32 -o ""
check fit_light "fit-light: -o: empty file name" fit-light map.exr --lights 1 -o ""
check fit_light_plane "fit-light: --plane-csv: empty file name" fit-light map.exr --lights 1 -o x.json --plane-csv ""
rm -f "$errf"
[ $fail -eq 0 ] && echo "bench_empty_path: 6 passed"
exit $fail
