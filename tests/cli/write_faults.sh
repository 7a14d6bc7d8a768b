#!/usr/bin/env bash
# write_faults.sh CLI SHIM — every writer of the CLI (lut, make-env, render -o and --png, plan,
# fit-light -o and --plane-csv, bench sat2d --chirp-csv, bench minmax --fig4-csv) under a
# failing fsync and a failing rename
# (tests/fault/fault_shim.c through LD_PRELOAD): exit status 1, a message naming the output and
# the cause ("Input/output error"), the previous file intact, no temporary left beside it; and
# with the shim loaded but no fault, the same commands replace the file.
set -u
cli=$1 shim=$2
dir=$(mktemp -d "${TMPDIR:-/tmp}/write_faults.XXXXXX") || exit 2
trap 'rm -rf "$dir"' EXIT
fail=0
printf 'previous\n' > "$dir/previous"
same() { cmp -s "$1" "$dir/previous"; }
run() { # name, output file, command... (RE: the outputs a message may name; default the file's)
  local name=$1 out=$2 re=${RE:-$(basename "$2")}
  shift 2
  for fault in fsync rename; do
    printf 'previous\n' > "$out"
    err=$(LD_PRELOAD=$shim ICS_FAULT=$fault "$@" 2>&1 > /dev/null); rc=$?
    left=$(ls "$dir" | grep -c "\.tmp")
    if [ $rc -ne 1 ] || ! printf '%s' "$err" | grep -qE "($re).*Input/output error" ||
       ! same "$out" || [ "$left" -ne 0 ]; then
      echo "$name, $fault fails: exit $rc, '$err', file: $(head -c 20 "$out" | tr -dc '[:print:]'), $left temporaries"
      fail=1
    else
      echo "$name, $fault fails: exit 1, previous file intact, no temporary: $err"
    fi
  done
  LD_PRELOAD=$shim "$@" > /dev/null 2>&1 || { echo "$name without a fault: exit $?"; fail=1; }
  ! same "$out" || { echo "$name without a fault: file not replaced"; fail=1; }
}
run "lut -o" "$dir/lut.h" "$cli" lut --size 16 --lang c -o "$dir/lut.h"
run "make-env -o" "$dir/env.exr" "$cli" make-env --lights '0.2,0.1,0.05,0.05,0,1,1,1,1' --size 32x16 -o "$dir/env.exr"
run "render -o" "$dir/r.exr" "$cli" render --resolution 16x12 -o "$dir/r.exr"
run "render --png" "$dir/r.png" "$cli" render --resolution 16x12 --png "$dir/r.png"
run "plan -o" "$dir/plan.json" "$cli" plan --resolution 16x12 -o "$dir/plan.json"
"$cli" make-env --lights '0.2,0.1,0.05,0.05,0,1,1,1,1' --size 64x32 -o "$dir/in.exr" > /dev/null 2>&1
run "fit-light -o" "$dir/l.json" "$cli" fit-light "$dir/in.exr" --lights 1 -o "$dir/l.json"
# the outputs are committed together, -o's first: its failure is the one named
RE='l2.json|plane.csv' run "fit-light --plane-csv" "$dir/plane.csv" "$cli" fit-light "$dir/in.exr" --lights 1 -o "$dir/l2.json" --plane-csv "$dir/plane.csv"
rm -f "$dir/l2.json"
# the second output's own faults (ICS_FAULT_AFTER=1: -o's fsync or rename passes): an fsync
# fault commits neither; a rename fault leaves -o's file renamed (POSIX renames one file at a
# time) and the CSV's previous contents
for fault in fsync rename; do
  printf 'previous\n' > "$dir/plane.csv"
  err=$(LD_PRELOAD=$shim ICS_FAULT=$fault ICS_FAULT_AFTER=1 "$cli" fit-light "$dir/in.exr" --lights 1 \
        -o "$dir/l3.json" --plane-csv "$dir/plane.csv" 2>&1 > /dev/null); rc=$?
  want_l3=$([ $fault = rename ] && echo yes || echo no)
  have_l3=$([ -e "$dir/l3.json" ] && echo yes || echo no)
  if [ $rc -ne 1 ] || ! printf '%s' "$err" | grep -q "plane.csv: Input/output error" ||
     ! same "$dir/plane.csv" || [ "$have_l3" != "$want_l3" ] || [ "$(ls "$dir" | grep -c "\.tmp")" -ne 0 ]; then
    echo "fit-light --plane-csv, its own $fault fails: exit $rc, '$err', l3.json: $have_l3 (expected $want_l3)"
    fail=1
  else
    echo "fit-light --plane-csv, its own $fault fails: exit 1, the CSV intact, -o's file committed: $have_l3"
  fi
  rm -f "$dir/l3.json"
done
run "bench sat2d --chirp-csv" "$dir/chirp.csv" "$cli" bench sat2d --size 64 --chirp-csv "$dir/chirp.csv"
run "bench minmax --fig4-csv" "$dir/fig4.csv" "$cli" bench minmax --samples 16 --fig4-csv "$dir/fig4.csv"
exit $fail
