#!/usr/bin/env bash
# Numbers printed and parsed by the CLI do not depend on the caller's locale: under a locale
# whose decimal separator is ',' (de_DE.UTF-8 and the like, when one is installed) every command
# below prints byte for byte what it prints under LC_ALL=C, and reads "0.5" as one half. The CLI
# never calls setlocale; this fails if it ever does (printf would write "0,5", strtod stop at '.').
# Without a comma locale installed, one is compiled into the test's scratch directory with
# localedef (sources from Debian's `locales` package, installed by scripts/deps.sh) and used
# through LOCPATH; only if that fails too is the test reported skipped (77).
set -u
cli=$1
loc=
for l in $(locale -a 2>/dev/null); do
  if [ "$(LC_ALL=$l locale decimal_point 2>/dev/null)" = "," ]; then loc=$l; break; fi
done
if [ -z "$loc" ]; then
  locdir=$(mktemp -d "${TMPDIR:-/tmp}/icshadow-locale.XXXXXX") || { echo "mktemp -d failed"; exit 1; }
  trap 'rm -rf "$locdir"' EXIT
  if localedef -i de_DE -f UTF-8 "$locdir/de_DE.UTF-8" >/dev/null 2>&1 &&
     [ "$(LOCPATH=$locdir LC_ALL=de_DE.UTF-8 locale decimal_point 2>/dev/null)" = "," ]; then
    export LOCPATH=$locdir
    loc=de_DE.UTF-8
  fi
fi
if [ -z "$loc" ]; then
  echo "SKIPPED: no locale with a comma decimal separator, and localedef -i de_DE -f UTF-8 failed (Debian package 'locales' missing?)"
  exit 77
fi
echo "comparing LC_ALL=C with LC_ALL=$loc${LOCPATH:+ (compiled into $LOCPATH)}"
fail=0 pass=0
same() { # name, stdin text, then the command's arguments
  local name=$1 input=$2; shift 2
  local c l rc_c rc_l
  c=$(printf '%s' "$input" | LC_ALL=C "$cli" "$@" 2>&1); rc_c=$?
  l=$(printf '%s' "$input" | LC_ALL=$loc "$cli" "$@" 2>&1); rc_l=$?
  if [ "$rc_c" -ne 0 ] || [ "$rc_l" -ne "$rc_c" ] || [ "$c" != "$l" ] || [ -z "$c" ]; then
    echo "FAILED $name under $loc (exit $rc_l, C: $rc_c):"; echo "  C:    $c" | head -3; echo "  $loc: $l" | head -3
    fail=$((fail + 1))
  else
    pass=$((pass + 1))
  fi
}
same eval "0.5
0.25
" eval ellipe
same isoline "" isoline --light gauss:0.3,2 --level 0.5 --distance 2 --model correct
same kernel "" kernel ellipse --varx 0.8 --vary 0.2 --angle 30 --samples 3 --offset 0.1
same iterate "" iterate --kernel dirac --var 0.25 --steps 1 --width 6
same kernel_table "" kernel-table --no-timing --iterations 10
same lut "" lut --size 8 --lang c
# and the value is the one meant: 0.5 read as one half, printed with a '.'
out=$(LC_ALL=$loc "$cli" isoline --light box:-1,3 --level 0.25 --distance 0.5 --model correct)
if [ "$out" = "-1" ]; then pass=$((pass + 1)); else echo "FAILED: --distance 0.5 under $loc gave '$out', expected -1"; fail=$((fail + 1)); fi
echo "locale_numbers ($loc): $pass passed, $fail failed"
exit $((fail > 0))
