#!/usr/bin/env python3
"""The slab renderer's error by effect (docs/results.md "Error by effect"): for the default scene,
an opaque sphere over a white floor under a narrow light, the same over an opaque box (one
solid's shadow on another), two planes alone whose exact visibility is known, and the scenes of
Patel's Fig. 18, 19, 20 and 21 (built by paper_figs/patel_fig*.py), the Monte-Carlo reference (`icshadow render
--backend mc --spp N --aov stderr`), then the slab renderer under each model (render.model:
patel, solid, surface, blocker; each adds one step) with `--compare REF.exr`: RMSE beyond the reference's
noise, max error, and the frame time (plan with its geometry pass plus render; the median of
--reps renders, the models interleaved round by round). Writes error_by_effect.csv,
error_by_effect.md (the table), per scene and model the render minus the reference (x4, red
brighter, blue darker: `--diff-png`) as error_by_effect_SCENE_MODEL.png, and the default scene's
side by side as error_by_effect_default.png into --out.

usage: error_by_effect.py [--cli build/bin/icshadow] [--out out/analysis] [--reps 3]
"""
import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "paper_figs"))

import patel_fig18  # noqa: E402
import patel_fig19  # noqa: E402
import patel_fig20  # noqa: E402
import patel_fig21  # noqa: E402

MODELS = ("patel", "solid", "surface", "blocker")

SPHERE = {
    "camera": {"projection": "orthographic", "eye": [0, 1.2, 3], "target": [0, 0, 0], "up": [0, 1, 0],
               "height": 3, "resolution": [160, 120]},
    "render": {"slab_spacing": 0.02, "d1": 1.0, "seed": 1},
    "lights": [{"mean": [0.6, 0.55], "var": [0.004, 0.004], "color": [1, 1, 1], "weight": 1}],
    "materials": {"white": {"color": [1, 1, 1]}, "grey": {"color": [0.8, 0.8, 0.8]}},
    "objects": [{"shape": "sphere", "center": [0, 0.1, 0], "radius": 0.5, "material": "grey"},
                {"shape": "rect", "center": [0, -0.4, 0], "normal": [0, 1, 0], "size": [6, 6],
                 "material": "white"}],
}

# a solid's shadow on another solid: a sphere over the top of an opaque box
SPHERE_ON_BOX = {
    "camera": {"projection": "orthographic", "eye": [0, 1.2, 3], "target": [0, 0, 0], "up": [0, 1, 0],
               "height": 3, "resolution": [160, 120]},
    "render": {"slab_spacing": 0.02, "d1": 1.0, "seed": 1},
    "lights": [{"mean": [0.3, 0.6], "var": [0.01, 0.01], "color": [1, 1, 1], "weight": 1}],
    "materials": {"white": {"color": [1, 1, 1]}, "grey": {"color": [0.8, 0.8, 0.8]}},
    "objects": [{"shape": "sphere", "center": [0, 0.5, 0.2], "radius": 0.3, "material": "grey"},
                {"shape": "box", "center": [0, -0.3, 0], "size": [2.5, 0.6, 2.5], "material": "white"}],
}

# an open surface alone: a floor under a broad light at 45 deg elevation from the side (its exact
# visibility, the light's share above the floor, 0.9617), and a plane whose light lies partly
# below its horizon (exact Phi(-0.5) = 0.3085; test_render_model holds both to the closed form)
def plane(eye, center, normal, mean, var):
    return {
        "camera": {"projection": "orthographic", "eye": eye, "target": [0, 0, 0], "up": [0, 1, 0],
                   "height": 3, "resolution": [96, 72]},
        "render": {"slab_spacing": 0.02, "d1": 1.0, "seed": 5},
        "lights": [{"mean": mean, "var": [var, var], "color": [1, 1, 1], "weight": 1}],
        "materials": {"white": {"color": [1, 1, 1]}},
        "objects": [{"shape": "rect", "center": center, "normal": normal, "size": [20, 20],
                     "material": "white"}],
    }


# name, scene (None: the embedded default scene at e = 0.015, the spacing Patel's model ships
# with; it ships with 0.045 under render.model auto), reference samples per pixel
SCENES = (
    ("default scene (320 x 240, e = 0.015)", None, 1024),
    ("opaque sphere over a floor, narrow light", SPHERE, 1024),
    ("opaque sphere over an opaque box", SPHERE_ON_BOX, 1024),
    ("a floor under a light at 45 deg from the side (exact 0.9617)",
     plane([0, 1.2, 3], [0, -1, 0], [0, 1, 0], [0.8, 0.72], 0.4), 1024),
    ("a plane with its light partly below its horizon (exact 0.3085)",
     plane([0, 0, 2], [0, 0, 0], [0, 0.8, 0.6], [0, -0.8], 0.01), 1024),
    ("Fig. 18: two boxes over a wall with a 45 deg part", patel_fig18.scene(True, 1.0), 256),
    ("Fig. 19: smoke (e = 0.01)", patel_fig19.scene(0.01, False), 256),
    ("Fig. 20: fence, light variance 0.002", patel_fig20.scene(0.002), 256),
    ("Fig. 21: sphere at 45 deg, point light", patel_fig21.scene(45.0, [[0, 0], [0, 0]]), 256),
    ("Fig. 21: sphere at 45 deg, isotropic 0.04", patel_fig21.scene(45.0, [[0.04, 0], [0, 0.04]]), 256),
)


def run(cli, args):
    p = subprocess.run([cli] + args, capture_output=True, text=True)
    if p.returncode != 0:
        sys.exit(f"error_by_effect.py: icshadow {' '.join(args)}: {p.stderr.strip()}")
    return json.loads(p.stdout.strip().splitlines()[-1])


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--cli", default=os.path.join(HERE, "..", "build", "bin", "icshadow"))
    ap.add_argument("--out", default=os.path.join(HERE, "..", "out", "analysis"))
    ap.add_argument("--reps", type=int, default=3)
    a = ap.parse_args()
    os.makedirs(a.out, exist_ok=True)
    tmp = tempfile.mkdtemp(prefix="error_by_effect")
    rows = []
    for si, (name, scene, spp) in enumerate(SCENES):
        args = ["--slab-spacing", "0.015"]
        if scene is not None:
            path = os.path.join(tmp, f"scene{si}.json")
            with open(path, "w") as f:
                json.dump(scene, f)
            args = [path]
        ref = os.path.join(tmp, f"ref{si}.exr")
        mc = run(a.cli, ["render"] + args + ["--backend", "mc", "--spp", str(spp), "--seed", "1001",
                                             "--aov", "stderr", "-o", ref])
        times = {m: [] for m in MODELS}
        last = {}
        for rep in range(a.reps):
            for m in MODELS:
                diff = ["--diff-png", os.path.join(a.out, f"error_by_effect_{si}_{m}.png")] if rep == 0 else []
                s = run(a.cli, ["render"] + args + ["--model", m, "--compare", ref] + diff)
                times[m].append(s["ms_plan"] + s["ms_render"])
                last[m] = s
        for m in MODELS:
            c = last[m]["compare"]
            ms = statistics.median(times[m])
            rows.append({"scene": name, "model": m, "rmse_beyond_noise": c["rmse_beyond_noise"],
                         "max_error": c["max_error"], "reference_noise": c["reference_noise"],
                         "ms_frame": ms, "ms_min": min(times[m]), "ms_max": max(times[m]),
                         "ref_spp": spp, "ref_ms": mc["ms_render"]})
            print(f"{name:45s} {m:8s} rmse beyond noise {c['rmse_beyond_noise']:.4f}, "
                  f"max {c['max_error']:.3f}, {ms:.0f} ms", flush=True)
    fields = list(rows[0].keys())
    with open(os.path.join(a.out, "error_by_effect.csv"), "w") as f:
        f.write(",".join(fields) + "\n")
        for r in rows:
            f.write(",".join(str(r[k]) for k in fields) + "\n")
    with open(os.path.join(a.out, "error_by_effect.md"), "w") as f:
        f.write("| scene | model | RMSE beyond noise | max error | frame ms (median [min, max]) |\n")
        f.write("|---|---|---|---|---|\n")
        for r in rows:
            f.write(f"| {r['scene']} | {r['model']} | {r['rmse_beyond_noise']:.4f} | "
                    f"{r['max_error']:.3f} | {r['ms_frame']:.0f} [{r['ms_min']:.0f}, {r['ms_max']:.0f}] |\n")
    figure(a.out, [r for r in rows if r["scene"] == SCENES[0][0]])
    print(f"wrote {a.out}/error_by_effect.csv and .md")


def figure(out, rows):
    """error_by_effect_default.png: the default scene's difference images, one per model, side by
    side with their RMSE beyond noise (matplotlib; left out without it)."""
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.image as mpimg
        import matplotlib.pyplot as plt
    except ImportError:
        print("error_by_effect.py: matplotlib not installed: no figure", file=sys.stderr)
        return
    fig, axes = plt.subplots(1, len(rows), figsize=(3.2 * len(rows), 2.9))
    for ax, r in zip(axes, rows):
        ax.imshow(mpimg.imread(os.path.join(out, f"error_by_effect_0_{r['model']}.png")))
        ax.set_title(f"{r['model']}: RMSE {r['rmse_beyond_noise']:.4f}, {r['ms_frame']:.0f} ms", fontsize=9)
        ax.axis("off")
    fig.suptitle("default scene, render minus Monte-Carlo reference (x4; red brighter, blue darker)",
                 fontsize=10)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "error_by_effect_default.png"), dpi=110)
    plt.close(fig)


if __name__ == "__main__":
    main()
