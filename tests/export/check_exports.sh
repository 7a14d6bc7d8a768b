#!/usr/bin/env bash
# check_exports.sh — the shared library exports exactly what the public headers declare with
# ICS_API (icshadow/api.h), nothing private and nothing missing.
# usage: check_exports.sh NM LIBRARY INCLUDE_DIR
#   declared: every line of INCLUDE_DIR/icshadow/*.h that starts with "ICS_API": the name before
#             its first '(' (a function), else the last name before ';', '[' or '=' (data);
#   exported: `NM -D --defined-only LIBRARY`, symbol versions stripped.
# Also fails for a top-level function declaration without ICS_API (a line at column 0 that
# declares ics_*( and is not a typedef, a macro or a static inline alias), so a declaration that
# forgot the macro cannot drop out of both lists unnoticed.
set -euo pipefail
nm=$1 lib=$2 inc=$3
headers=("$inc"/icshadow/*.h)
fail=0

declared=$(sed -n 's/^ICS_API //p' "${headers[@]}" | while IFS= read -r decl; do
  if [[ $decl == *"("* ]]; then decl=${decl%%(*}; else decl=${decl%%[;[=]*}; fi
  [[ $decl =~ ([A-Za-z_][A-Za-z0-9_]*)[[:space:]]*$ ]] && echo "${BASH_REMATCH[1]}"
done | sort -u)

# (-H: the file name on every line, also where the folder holds one header)
unmarked=$(grep -H -n -E '^[A-Za-z_].*\<ics_[A-Za-z0-9_]*\(' "${headers[@]}" |
  grep -v -E '^[^:]*:[0-9]+:(ICS_API |ICS_DEPRECATED|typedef |static |#)' || true)
if [ -n "$unmarked" ]; then
  echo "declared without ICS_API:"; echo "$unmarked" | sed 's/^/  /'; fail=1
fi

# Linker-defined symbols some toolchains list as defined in every shared object.
exported=$("$nm" -D --defined-only "$lib" | awk 'NF >= 3 {sub(/@.*/, "", $3); print $3}' |
  grep -v -x -E '_init|_fini|__bss_start|_edata|_end' | sort -u)

private=$(comm -13 <(echo "$declared") <(echo "$exported"))
missing=$(comm -23 <(echo "$declared") <(echo "$exported"))
if [ -n "$private" ]; then
  echo "exported but not declared ICS_API in a public header:"; echo "$private" | sed 's/^/  /'
  fail=1
fi
if [ -n "$missing" ]; then
  echo "declared ICS_API but not exported:"; echo "$missing" | sed 's/^/  /'; fail=1
fi
ndeclared=$(echo "$declared" | grep -c . || true) nexported=$(echo "$exported" | grep -c . || true)
echo "export check: $ndeclared declared, $nexported exported"
exit $fail
