#!/usr/bin/env bash
# mesh_reader_orphan.sh CLI SHIM — the mesh reader's child dies with its parent: with
# ICS_FAULT=assimp-hang the shim (tests/fault/fault_shim.c, by LD_PRELOAD) makes Assimp's import
# never return, as a reader stuck on a malformed file would; `icshadow plan` is killed with
# SIGTERM while its child waits; the child must be gone (or a zombie waiting to be reaped)
# within 5 s. Before the fix the child, reparented to PID 1, stayed for ever. Medium: an ASan
# binary cannot take an LD_PRELOAD library before its runtime.
set -u
cli=$1 shim=$2
. "$(dirname "$0")/checks.sh"
cd "$dir" || exit 1
"$cli" plan --print-scene -o s.json
printf 'ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n' > tri.ply
python3 -c 'import json; s = json.load(open("s.json")); s["objects"].append({"shape": "mesh", "file": "tri.ply", "material": s["objects"][0]["material"]}); json.dump(s, open("m.json", "w"))'
"$cli" plan m.json > /dev/null 2> err
expect '[ $? -eq 0 ]'
LD_PRELOAD=$shim ICS_FAULT=assimp-hang "$cli" plan m.json > /dev/null 2> err & parent=$!
child=
for i in $(seq 1 100); do
  child=$(pgrep -P $parent | head -1)
  [ -n "$child" ] && break
  sleep 0.1
done
sleep 0.3
kill -TERM $parent
wait $parent 2> /dev/null
gone=0
for i in $(seq 1 50); do # gone, or dead and not yet reaped (a zombie: state Z or X)
  state=$(sed 's/^.*) //' "/proc/$child/stat" 2> /dev/null | cut -c1)
  case "$state" in "" | Z | X) gone=1; break ;; esac
  sleep 0.1
done
[ $gone -eq 1 ] || kill -KILL "$child" 2> /dev/null
expect '[ -n "$child" ] && [ $gone -eq 1 ]'
finish cli_mesh_reader_orphan
