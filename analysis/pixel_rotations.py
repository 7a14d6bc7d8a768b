#!/usr/bin/env python3
"""Per-pixel rotations against Monte Carlo (docs/renderer.md "The light buffers": why the default
is 2): for the embedded default scene (at e = 0.015) and every orthographic scene of scenes/, the
slab renderer under Patel's model with render.pixel_rotations K (default 1, 2, 4) and render seeds 1..S, each compared with
`--compare` to a Monte-Carlo reference of the same scene (made once per scene in --out:
`icshadow render SCENE --backend mc --spp N`; the default scene's may be given with --ref).
Prints a CSV row per scene and K: the mean, min and max RMSE over the seeds and the mean max
error. Perspective scenes are left out (they draw one rotation per slab whatever K).

usage: pixel_rotations.py [--cli build/bin/icshadow] [--out out/analysis/rotations]
                          [--ref REF.exr] [--spp 256] [--seeds 3] [--rotations 1,2,4]
"""
import argparse
import glob
import json
import os
import statistics
import subprocess
import sys


def render_json(cli, args):
    r = subprocess.run([cli, "render"] + args, capture_output=True, text=True)
    if r.returncode:
        sys.exit(f"pixel_rotations.py: icshadow render {' '.join(args)}: {r.stderr.strip()}")
    return json.loads(r.stdout) if r.stdout.strip() else {}


def default_scene(cli, out):
    """the embedded default scene (what `icshadow render` renders without a SCENE) written to a
    file, its JSON read from the renderer library (ics_scene_default_json) through ctypes"""
    path = os.path.join(out, "default.json")
    if not os.path.exists(path):
        import ctypes
        lib = os.path.join(os.path.dirname(os.path.abspath(cli)), "..", "lib", "libicshadow_render.so")
        so = ctypes.CDLL(lib)
        so.ics_scene_default_json.restype = ctypes.c_char_p
        with open(path, "wb") as f:
            f.write(so.ics_scene_default_json())
    return path


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--cli", default="build/bin/icshadow")
    ap.add_argument("--out", default="out/analysis/rotations")
    ap.add_argument("--ref", help="the default scene's reference (e.g. make error-vs-time's)")
    ap.add_argument("--spp", type=int, default=256, help="samples of the references made here")
    ap.add_argument("--seeds", type=int, default=3)
    ap.add_argument("--rotations", default="1,2,4")
    ap.add_argument("--scenes", nargs="*", help="scene files (default: the default scene and "
                    "scenes/*.json)")
    a = ap.parse_args()
    os.makedirs(a.out, exist_ok=True)
    rotations = [int(k) for k in a.rotations.split(",")]
    scenes = a.scenes or [default_scene(a.cli, a.out)] + sorted(glob.glob("scenes/*.json"))
    print("scene,rotations,seeds,rmse_mean,rmse_min,rmse_max,max_error_mean")
    for path in scenes:
        try:
            with open(path) as f:
                scene = json.load(f)
        except (OSError, ValueError) as e:
            sys.exit(f"pixel_rotations.py: {path}: {e}")
        if scene.get("camera", {}).get("projection") == "perspective":
            continue
        name = os.path.splitext(os.path.basename(path))[0]
        ref = a.ref if a.ref and name == "default" else os.path.join(a.out, f"{name}_ref.exr")
        if not os.path.exists(ref):
            render_json(a.cli, [path, "--backend", "mc", "--spp", str(a.spp), "-o", ref])
        for k in rotations:
            rmse, mx = [], []
            for seed in range(1, a.seeds + 1):
                s = json.loads(json.dumps(scene))
                # Patel's model, the default scene at its spacing (it ships with 0.045 under auto)
                s.setdefault("render", {}).update({"pixel_rotations": k, "seed": seed, "model": "patel"})
                if name == "default":
                    s["render"]["slab_spacing"] = 0.015
                # beside the scene: it may read files relative to its folder
                tmp = os.path.join(os.path.dirname(os.path.abspath(path)), f".rotations_{os.getpid()}.json")
                try:
                    with open(tmp, "w") as f:
                        json.dump(s, f)
                    c = render_json(a.cli, [tmp, "--compare", ref])["compare"]
                finally:
                    if os.path.exists(tmp):
                        os.remove(tmp)
                rmse.append(c["rmse"])
                mx.append(c["max_error"])
            print(f"{name},{k},{a.seeds},{statistics.mean(rmse):.5f},{min(rmse):.5f},"
                  f"{max(rmse):.5f},{statistics.mean(mx):.3f}", flush=True)


if __name__ == "__main__":
    main()
