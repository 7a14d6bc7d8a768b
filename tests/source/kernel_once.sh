#!/bin/sh
# kernel_once.sh — the kernel source is written once (docs/architecture.md "One kernel source"):
#   - no device function is defined in two kernel files (the cl and gl programs and the shared
#     headers of gpu/kernel; GLSL's entry point main excepted, one per program);
#   - no program defines a record offset or stride of its own (gpu/kernel/device_layout.h names
#     each once).
# usage: kernel_once.sh FILE...; exit 1 naming what is written twice.
status=0
defs=$(for f in "$@"; do
  # a definition: a line at column 0 "[qualifiers] type name(" whose statement is not a
  # declaration (the line does not end in ";")
  sed -E 's/__attribute__\(\(([^()]|\([^()]*\))*\)\) ?//g' "$f" |
    sed -n -E 's/^(ICS_FN |static |inline |__kernel )*[A-Za-z_][A-Za-z0-9_]*[ *]+([A-Za-z_][A-Za-z0-9_]*)\(.*[^;]$/\2/p' |
    sort -u | sed "s|$| $(basename "$f")|"
done)
twice=$(printf '%s\n' "$defs" | awk '$1 != "main" && $1 != "" { n[$1]++; where[$1] = where[$1] " " $2 }
  END { for (k in n) if (n[k] > 1) print k ":" where[k] }')
if [ -n "$twice" ]; then
  echo "kernel_once: functions defined in more than one kernel file:"
  echo "$twice"
  status=1
fi
offsets=$(grep -nE '^[[:space:]]*#[[:space:]]*define[[:space:]]+((O|G|CAM)_[A-Z_]+|[A-Z_]*(OBJ|GEO)_STRIDE)[[:space:](]' "$@" |
  grep -v 'device_layout\.h:')
if [ -n "$offsets" ]; then
  echo "kernel_once: record offsets defined outside gpu/kernel/device_layout.h:"
  echo "$offsets"
  status=1
fi
n=$(printf '%s\n' "$defs" | grep -c .)
[ $status -eq 0 ] && echo "kernel_once: $n function definitions in $# files, each once; offsets named once"
exit $status
