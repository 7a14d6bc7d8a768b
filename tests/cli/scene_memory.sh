#!/usr/bin/env bash
# scene_memory.sh CLI DATA — a scene's files are read only as far as they are used and as the
# memory limit allows (issue: 254 materials of 2^28-cell grids, none used, took 3.2 GB before a
# refusal; meshes were read whatever their size):
# - grids of materials no object uses are never read (their files need not even exist);
# - a used grid over render.memory_limit_mib is refused before its file is opened;
# - meshes count too, each as it is read: the one that takes the scene over the limit is named.
set -u
cli=$1 data=$2
. "$(dirname "$0")/checks.sh"
cd "$dir" || exit 1
python3 - "$data" << 'PY'
import json, struct, sys
data = sys.argv[1]
open("small.raw", "wb").write(struct.pack("<8f", *[0.5] * 8))
mats = {f"unused{i}": {"extinction": 1, "detail": {"function": "grid", "file": f"missing{i}.raw",
                                                  "size": [4096, 4096, 16]}} for i in range(254)}
mats["used"] = {"extinction": 1, "detail": {"function": "grid", "file": "small.raw", "size": [2, 2, 2]}}
mats["white"] = {}
base = {"camera": {"eye": [0, 0, 3], "target": [0, 0, 0], "height": 2, "resolution": [16, 16]},
        "render": {"slab_spacing": 0.05, "d1": 1, "memory_limit_mib": 100},
        "lights": [{"mean": [0.1, 0.1], "var": [0.01, 0.01]}], "materials": mats,
        "objects": [{"shape": "box", "center": [0, 0, 0], "size": [1, 1, 1], "material": "used"},
                    {"shape": "rect", "center": [0, 0, -1], "normal": [0, 0, 1], "size": [3, 3],
                     "material": "white"}]}
json.dump(base, open("unused.json", "w"))
mats["used"]["detail"] = {"function": "grid", "file": "huge.raw", "size": [4096, 4096, 16]}
json.dump(base, open("huge.json", "w"))
mats["used"]["detail"] = {"function": "grid", "file": "small.raw", "size": [2, 2, 2]}
base["render"]["memory_limit_mib"] = 0.01
open("cube.ply", "wb").write(open(f"{data}/cube.ply", "rb").read())  # (in the scene's folder)
base["objects"] += [{"shape": "mesh", "file": "cube.ply", "translate": [0, 0, 0.1 * k],
                     "material": "white"} for k in range(12)]
json.dump(base, open("meshes.json", "w"))
# a PLY whose header declares 5e7 faces (its body: 4 bytes): refused from the header, unread
open("declared.ply", "w").write("ply\nformat binary_little_endian 1.0\nelement vertex 3\n"
    "property float x\nproperty float y\nproperty float z\nelement face 50000000\n"
    "property list uchar int vertex_indices\nend_header\n\0\0\0\0")
base["render"]["memory_limit_mib"] = 100
base["objects"][-1]["file"] = "declared.ply"
json.dump(base, open("declared.json", "w"))
PY
timeout 60 "$cli" plan unused.json > out 2> err; rc=$?
expect '[ $rc -eq 0 ] && grep -q "\"scene\": \"unused.json\"" out'
timeout 60 "$cli" plan huge.json > out 2> err; rc=$?
expect '[ $rc -eq 2 ] && grep -q "materials.used.detail: 1024 MiB, with the grids and meshes before it 1024 MiB, over render.memory_limit_mib = 100" err'
timeout 60 "$cli" plan meshes.json > out 2> err; rc=$?
expect '[ $rc -eq 2 ] && grep -q "objects\[[0-9]*\].file: .* MiB, with the grids and meshes before it .* over render.memory_limit_mib = 0.01" err'
timeout 60 "$cli" plan declared.json > out 2> err; rc=$?
expect '[ $rc -eq 2 ] && grep -q "objects\[13\].file: its PLY header declares 50000000 faces: at least 3624 MiB, with the grids and meshes before it .* over render.memory_limit_mib = 100" err && [ ! -s out ]'
finish cli_scene_memory
