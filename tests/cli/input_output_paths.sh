#!/usr/bin/env bash
# A command's outputs never replace its inputs, and no input blocks (issue: outputs overwrote
# inputs; FIFOs hung the reader; the mesh reader's child outlived a killed parent).
# - an output that is an input — the same name, "./" forms, a hard link, a symbolic link —
#   or another output of the same command: exit 2 before any work, the input intact;
# - a FIFO as the scene, a lights_file, a grid file, a mesh or the --compare reference: exit 2
#   at once with "not a regular file (a FIFO)" (each under `timeout`: a hang fails the check);
# - a PLY whose magic line is "PLY" without end_header: refused at once, as "ply" is;
# - a glTF whose buffer is a FIFO: refused at once; the buffer of a glTF is an input too (the
#   mesh reader's dying with its parent: tests/cli/mesh_reader_orphan.sh).
set -u
cli=$1
. "$(dirname "$0")/checks.sh"
cd "$dir" || exit 1
T="timeout 20"
"$cli" plan --print-scene -o s.json && cp s.json keep.json
intact() { cmp -s s.json keep.json; }
refused() { # RC FILE-OF-STDERR REGEX
  [ "$1" -eq 2 ] && grep -q -- "$3" "$2"
}
# outputs against inputs
$T "$cli" render s.json -o s.json --resolution 16x12 > out 2> err
expect 'refused $? err "-o s.json: that is the scene file (s.json); refusing to overwrite an input" && intact && [ ! -s out ]'
$T "$cli" plan s.json -o ./s.json 2> err
expect 'refused $? err "that is the scene file" && intact'
mkdir sub && ln s.json hard.json && ln -s s.json sym.json && ln -s ../s.json sub/rel.json
$T "$cli" plan s.json -o "$dir/sub/../s.json" 2> err
expect 'refused $? err "that is the scene file" && intact'
$T "$cli" render hard.json -o s.json --resolution 16x12 > /dev/null 2> err
expect 'refused $? err "that is the scene file (hard.json)" && intact'
$T "$cli" plan s.json -o sym.json 2> err
expect 'refused $? err "that is the scene file" && intact && [ -L sym.json ]'
$T "$cli" plan sub/rel.json -o s.json 2> err
expect 'refused $? err "that is the scene file" && intact'
"$cli" render s.json --resolution 16x12 -o ref.exr > /dev/null 2>&1 && cp ref.exr ref_keep.exr
$T "$cli" render s.json --resolution 16x12 --compare ref.exr -o ref.exr > /dev/null 2> err
expect 'refused $? err "-o ref.exr: that is the --compare reference" && cmp -s ref.exr ref_keep.exr'
$T "$cli" render s.json --resolution 16x12 --compare ref.exr --diff-png ref.exr > /dev/null 2> err
expect 'refused $? err "that is the --compare reference" && cmp -s ref.exr ref_keep.exr'
# the files a scene reads: its lights_file
python3 -c 'import json; s = json.load(open("s.json")); json.dump({"lights": s.pop("lights")}, open("lights.json", "w")); s["lights_file"] = "lights.json"; json.dump(s, open("lf.json", "w"))'
cp lights.json lights_keep.json
$T "$cli" render lf.json --resolution 16x12 -o lights.json > /dev/null 2> err
expect 'refused $? err "-o lights.json: that is the scene.s input" && cmp -s lights.json lights_keep.json'
$T "$cli" plan lf.json -o ./lights.json 2> err
expect 'refused $? err "that is the scene.s input" && cmp -s lights.json lights_keep.json'
# fit-light and make-env against their inputs
"$cli" make-env --lights 0,0,0.01,0.01,0,1,1,1,1 --size 32x16 -o env.exr 2> /dev/null && cp env.exr env_keep.exr
$T "$cli" fit-light env.exr --lights 1 -o env.exr 2> err
expect 'refused $? err "-o env.exr: that is the input map" && cmp -s env.exr env_keep.exr'
$T "$cli" fit-light env.exr --lights 1 -o l.json --plane-csv ./env.exr 2> err
expect 'refused $? err "that is the input map" && cmp -s env.exr env_keep.exr && [ ! -e l.json ]'
$T "$cli" make-env --lights lights.json --size 32x16 -o lights.json 2> err
expect 'refused $? err "that is the --lights file" && cmp -s lights.json lights_keep.json'
# two outputs of one command on one path; a device may take several
$T "$cli" render s.json --resolution 16x12 -o x.exr --png x.exr > out 2> err
expect 'refused $? err "-o x.exr and --png x.exr name the same file" && [ ! -e x.exr ] && [ ! -s out ]'
$T "$cli" render s.json --resolution 16x12 --compare ref.exr --png b.png --diff-png ./b.png > /dev/null 2> err
expect 'refused $? err "--png b.png and --diff-png ./b.png name the same file" && [ ! -e b.png ]'
$T "$cli" fit-light env.exr --lights 1 -o l.json --plane-csv l.json 2> err
expect 'refused $? err "name the same file" && [ ! -e l.json ]'
$T "$cli" fit-light env.exr --lights 1 -o - --plane-csv - > out 2> err
expect 'refused $? err "-o and --plane-csv both write to stdout" && [ ! -s out ]'
$T "$cli" fit-light env.exr --lights 1 -o l.json --plane-csv - > out 2> err
expect 'refused $? err "--plane-csv and the summary table both write to stdout" && [ ! -e l.json ]'
$T "$cli" render s.json --resolution 16x12 -o /dev/null --png /dev/null > out 2> err
expect '[ $? -eq 0 ] && [ -c /dev/null ] && grep -q "\"png\"" out'
# only the numbers: --compare without an output
$T "$cli" render s.json --resolution 16x12 --compare ref.exr > out 2> err
expect '[ $? -eq 0 ] && grep -q "\"rmse\": 0," out'
# FIFOs as inputs: refused at once, never opened for a blocking read
mkfifo fifo
# (the scene itself may be a pipe, /dev/stdin: read as a stream, bounded; a FIFO nobody writes
# to reads as empty at once)
$T "$cli" render fifo -o y.exr > /dev/null 2> err
expect 'refused $? err "fifo:1:0: .* expected near end of file" && [ ! -e y.exr ]'
cat s.json | $T "$cli" plan /dev/stdin > out 2> err
expect '[ $? -eq 0 ] && grep -q "\"scene\": \"/dev/stdin\"" out'
head -c 17000000 /dev/zero | tr '\0' ' ' | $T "$cli" plan /dev/stdin > out 2> err
expect 'refused $? err "refusing a too large scene file: more than the 16 MiB"'
$T "$cli" render s.json --resolution 16x12 --compare fifo > /dev/null 2> err
expect 'refused $? err "fifo: cannot open: not a regular file (a FIFO)"'
$T "$cli" fit-light fifo --lights 1 -o l.json 2> err
expect 'refused $? err "not a regular file (a FIFO)" && [ ! -e l.json ]'
python3 -c 'import json; s = json.load(open("lf.json")); s["lights_file"] = "fifo"; json.dump(s, open("lfifo.json", "w"))'
$T "$cli" plan lfifo.json 2> err > /dev/null
expect 'refused $? err "cannot open lights file: not a regular file (a FIFO) (lights_file of lfifo.json)"'
python3 - << 'PY'
import json
s = json.load(open("s.json"))
s["materials"]["grid_smoke"] = {"extinction": 1, "detail": {"function": "grid", "file": "fifo", "size": [2, 2, 2]}}
s["objects"].append({"shape": "box", "center": [0, 0, 0], "size": [1, 1, 1], "material": "grid_smoke"})
json.dump(s, open("gfifo.json", "w"))
del s["materials"]["grid_smoke"]
s["objects"][-1] = {"shape": "mesh", "file": "fifo", "material": s["objects"][0]["material"]}
json.dump(s, open("mfifo.json", "w"))
s["objects"][-1]["file"] = "magic.ply"
json.dump(s, open("magic.json", "w"))
s["objects"][-1]["file"] = "blocks.gltf"
json.dump(s, open("gltf.json", "w"))
gltf = {"asset": {"version": "2.0"}, "buffers": [{"uri": "fifo", "byteLength": 36}],
        "bufferViews": [{"buffer": 0, "byteLength": 36}],
        "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                       "min": [0, 0, 0], "max": [1, 1, 0]}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
        "nodes": [{"mesh": 0}], "scenes": [{"nodes": [0]}], "scene": 0}
json.dump(gltf, open("blocks.gltf", "w"))
PY
$T "$cli" plan gfifo.json > /dev/null 2> err
expect 'refused $? err "cannot open .*fifo.*: not a regular file (a FIFO)"'
$T "$cli" plan mfifo.json > /dev/null 2> err
expect 'refused $? err "cannot open mesh file: not a regular file (a FIFO)"'
# Assimp takes "PLY" for "ply": the end_header pre-check must too (it spun for a minute before)
printf 'PLY\nformat ascii 1.0\nelement vertex 3\nproperty float x\n' > magic.ply
$T "$cli" plan magic.json > /dev/null 2> err
expect 'refused $? err "magic.ply: a PLY header without an end_header line"'
# a glTF whose buffer is a FIFO: Assimp opens it through the reader's own file system, which
# refuses it at once (it blocked the reader until its time limit)
$T "$cli" plan gltf.json > /dev/null 2> err
expect 'refused $? err "cannot read mesh: it needs .*fifo: not a regular file (a FIFO)"'
# a file Assimp reads for a mesh (the glTF's buffer) is one of the scene's inputs
python3 -c 'import struct; open("tri.bin", "wb").write(struct.pack("<9f", 0, 0, 0, 1, 0, 0, 0, 1, 0))'
sed 's/"uri": "fifo"/"uri": "tri.bin"/' blocks.gltf > tri.gltf && sed 's/blocks.gltf/tri.gltf/' gltf.json > tri.json
cp tri.bin tri_keep.bin
$T "$cli" render tri.json --resolution 16x12 -o tri.bin > /dev/null 2> err
expect 'refused $? err "-o tri.bin: that is the scene.s input" && cmp -s tri.bin tri_keep.bin'
finish cli_input_output_paths
