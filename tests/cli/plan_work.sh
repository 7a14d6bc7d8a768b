#!/usr/bin/env bash
# The plan's work estimate covers every term that grows, and refuses before the work (issue:
# renders of hours or days were accepted): a 1 x 1 perspective view with 64 lights and 10^4 slabs
# (the per-slab class compensation: hours), 4096 overlapping spheres at 1024 x 1024 (the geometry
# pass: minutes before a memory refusal), 64 fBm spheres of 16 octaves at 1024 x 1024 and 5.5e4
# slabs (the detail: days). Each is refused at once with the estimate and what to change; a
# small perspective render with 4 lights still runs.
set -u
cli=$1
. "$(dirname "$0")/checks.sh"
cd "$dir" || exit 1
python3 - << 'PY'
import json, random
random.seed(3)
lights = [{"mean": [random.uniform(-0.3, 0.3), random.uniform(-0.3, 0.3)], "var": [0.01, 0.01]}
          for _ in range(64)]
floor = {"shape": "rect", "center": [0, 0, -0.3], "normal": [0, 0, 1], "size": [3, 3], "material": "m"}
persp = {"camera": {"projection": "perspective", "eye": [0, 0, 3], "target": [0, 0, 0], "fov_deg": 40,
                    "resolution": [1, 1]},
         "render": {"slab_spacing": 0.0001, "d1": 1}, "lights": lights, "materials": {"m": {}},
         "objects": [{"shape": "sphere", "center": [0, 0, 0], "radius": 0.5, "material": "m"}, floor]}
json.dump(persp, open("persp.json", "w"))
persp["lights"] = lights[:4]
persp["render"]["slab_spacing"] = 0.05
json.dump(persp, open("persp_small.json", "w"))
one = [{"mean": [0.1, 0.1], "var": [0.01, 0.01]}]
cam = {"eye": [0, 0, 3], "target": [0, 0, 0], "height": 2, "resolution": [1024, 1024]}
sph = {"camera": cam, "render": {"slab_spacing": 0.05, "d1": 1}, "lights": one, "materials": {"m": {}},
       "objects": [{"shape": "sphere", "center": [random.uniform(-0.2, 0.2), random.uniform(-0.2, 0.2),
                                                  random.uniform(-0.2, 0.2)], "radius": 0.5, "material": "m"}
                   for _ in range(4096)]}
json.dump(sph, open("spheres.json", "w"))
fbm = {"camera": cam, "render": {"slab_spacing": 0.0001, "d1": 1}, "lights": one,
       "materials": {"s": {"extinction": 1, "detail": {"function": "fbm", "octaves": 16}}},
       "objects": [{"shape": "sphere", "center": [random.uniform(-0.5, 0.5), random.uniform(-0.5, 0.5),
                                                  random.uniform(-2.5, 2.5)], "radius": 0.3, "material": "s"}
                   for _ in range(64)]}
json.dump(fbm, open("fbm.json", "w"))
PY
timeout 60 "$cli" plan persp.json > /dev/null 2> err; rc=$?
expect '[ $rc -eq 2 ] && grep -q "each compensating 256 classes of its perspective kernel per slab .* exceed the work limit" err'
timeout 60 "$cli" plan spheres.json > /dev/null 2> err; rc=$?
expect '[ $rc -eq 2 ] && grep -q "the geometry pass: .* ray-object tests exceed the limit" err'
timeout 60 "$cli" plan fbm.json > /dev/null 2> err; rc=$?
expect '[ $rc -eq 2 ] && grep -q "and the volume detail.s octaves) = .* updates exceed the work limit" err'
timeout 60 "$cli" render persp_small.json -o small.exr > /dev/null 2> err; rc=$?
expect '[ $rc -eq 0 ] && [ -s small.exr ]'
finish cli_plan_work
