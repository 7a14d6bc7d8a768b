#!/usr/bin/env python3
"""Patel et al. 2013, Fig. 21: a white sphere under one distant light at 0, 22.5, 45 and 67.5
degrees from the view direction: Lambertian shading, and the slab renderer's "shading from
slicing" for a point light, an isotropic light and a line light rotated 45 degrees, each beside
the Monte-Carlo reference of the same scene (the model's exact value).

The scene (scenes/patel_fig21.json, there at 45 degrees under the isotropic light: orthographic,
96 x 96, a unit sphere, slab spacing 0.01, d1 = 1, black background) is rendered by
`icshadow render --backend mc --spp 256 -o REF.exr` and then by the slab renderer with
`--compare REF.exr` (RMSE, max error, times from its summary). The light's tilt_deg (a, 0), mean
(tan a, 0) on the light plane; covariances 0, 0.04 I and the line light diag(0.04, 0) rotated 45
degrees.
Lambert: max(0, n . w) at each pixel's sphere normal n (computed here, analytically), compared
with the slab renderer's and the reference's 8-bit sRGB previews decoded to linear (quantisation
below 0.004). What to see: the reference is the model's exact visibility, a terminator (hard for
the point light, blurred by the light's spread); the slab renderer darkens every tilted part of
the sphere (a sliced surface shadows itself), which Patel compares with Lambert; at 0 degrees
with the point light all three are white.
Writes patel_fig21.png and patel_fig21.csv (angle, light, rmse and max error against the
reference, rmse of each against Lambert, ms of each).
"""
import json
import math
import os
import sys
import tempfile

import numpy as np

import matplotlib

matplotlib.use("Agg")
import matplotlib.image as mpimg  # noqa: E402
import matplotlib.pyplot as plt  # noqa: E402

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "lib"))
from figutil import load_scene, parse_args, run_cli, save_fig, write_csv  # noqa: E402

ANGLES = (0.0, 22.5, 45.0, 67.5)
LIGHTS = (("point", [[0, 0], [0, 0]]),
          ("isotropic 0.04", [[0.04, 0], [0, 0.04]]),
          ("line 0.04 at 45 deg", [[0.02, 0.02], [0.02, 0.02]]))
SCENE = load_scene("patel_fig21")             # the figure's main configuration: 45 deg, isotropic 0.04
RES = SCENE["camera"]["resolution"][0]
HEIGHT = SCENE["camera"]["height"]


def scene(angle, cov):
    """scenes/patel_fig21.json with the light at angle degrees from the view direction (x tilt)
    and covariance cov."""
    s = load_scene("patel_fig21")
    s["lights"] = [{"tilt_deg": [angle, 0], "cov": cov}]
    return s


def lambert(angle):
    h = HEIGHT / RES
    c = -HEIGHT / 2 + (np.arange(RES) + 0.5) * h
    x, y = np.meshgrid(c, -c)
    r2 = x * x + y * y
    z = np.sqrt(np.maximum(1 - r2, 0))
    a = math.radians(angle)
    return np.where(r2 < 1, np.maximum(0, x * math.sin(a) + z * math.cos(a)), 0.0), r2 < 1


def linear(png):
    v = mpimg.imread(png)[:, :, 0].astype(np.float64)
    return np.where(v <= 0.04045, v / 12.92, ((v + 0.055) / 1.055) ** 2.4)


def main():
    args = parse_args(__doc__)
    tmp = tempfile.mkdtemp(prefix="fig21")
    rows, panels = [], {}
    for ai, angle in enumerate(ANGLES):
        lam, inside = lambert(angle)
        panels[("Lambert", ai)] = lam
        for li, (lname, cov) in enumerate(LIGHTS):
            sf = os.path.join(tmp, f"s{ai}{li}.json")
            with open(sf, "w") as f:
                json.dump(scene(angle, cov), f)
            ref, ref_png, png = (os.path.join(tmp, f"{n}{ai}{li}.{e}") for n, e in
                                 (("ref", "exr"), ("ref", "png"), ("slab", "png")))
            mc = json.loads(run_cli(args.cli, ["render", sf, "--backend", "mc", "--spp", "256", "--aov", "stderr", "-o", ref,
                                               "--png", ref_png]))
            sl = json.loads(run_cli(args.cli, ["render", sf, "--compare", ref, "--png", png]))
            c = sl["compare"]
            v_slab, v_ref = linear(png), linear(ref_png)
            panels[("slab " + lname, ai)], panels[("reference " + lname, ai)] = v_slab, v_ref
            rl = lambda v: float(np.sqrt(np.mean((v - lam)[inside] ** 2)))
            rows.append([angle, lname, c["rmse"], c["rmse_beyond_noise"], c["max_error"],
                         c["reference_noise"], rl(v_slab), rl(v_ref), sl["ms_plan"] + sl["ms_render"],
                         mc["ms_render"]])
            print(f"{angle:5.1f} deg, {lname:20s}: slab vs reference rmse {c['rmse']:.4f} "
                  f"(beyond noise {c['rmse_beyond_noise']:.4f}), max {c['max_error']:.3f}; "
                  f"vs Lambert: slab {rl(v_slab):.4f}, reference {rl(v_ref):.4f}; "
                  f"{sl['ms_plan'] + sl['ms_render']:.0f} ms vs {mc['ms_render']:.0f} ms")
    write_csv(os.path.join(args.out, "patel_fig21.csv"),
              ["angle_deg", "light", "rmse_slab_vs_reference", "rmse_beyond_noise", "max_error",
               "reference_noise", "rmse_slab_vs_lambert", "rmse_reference_vs_lambert", "ms_slab",
               "ms_reference"], rows)
    names = ["Lambert"] + [f"{k} {n}" for n, _ in LIGHTS for k in ("slab", "reference")]
    fig, ax = plt.subplots(len(names), len(ANGLES), figsize=(1.9 * len(ANGLES) + 1.6, 1.9 * len(names)))
    for r, name in enumerate(names):
        for ai, angle in enumerate(ANGLES):
            ax[r][ai].imshow(panels[(name, ai)], cmap="gray", vmin=0, vmax=1)
            ax[r][ai].set_xticks([]), ax[r][ai].set_yticks([])
            if r == 0:
                ax[r][ai].set_title(f"{angle:g} deg", fontsize=9)
            if name.startswith("slab"):
                row = next(x for x in rows if x[0] == angle and name.endswith(x[1]))
                ax[r][ai].set_xlabel(f"rmse {row[2]:.3f} vs ref", fontsize=7)
        ax[r][0].set_ylabel(name.replace(" 0.04", "\n0.04"), fontsize=8)
    fig.suptitle("Patel Fig. 21: shading from slicing (slab) against the exact visibility (reference) "
                 "and Lambert", fontsize=9)
    fig.tight_layout()
    save_fig(fig, os.path.join(args.out, "patel_fig21.png"), 100)


if __name__ == "__main__":
    main()
