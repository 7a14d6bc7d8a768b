#!/usr/bin/env python3
"""Patel et al. 2013, Fig. 14 (a)/(b) as a scene: a black disk over a white plane under three
coloured Gaussian lights like Fig. 14's (a small green one, a broad red one, a thin blue line light
rotated 70 degrees clockwise; the variances of paper_figs/lightfit_fig14.py, in light-plane
units; the scene is scenes/patel_fig14.json), rendered by the slab renderer and by the
Monte-Carlo reference.

Commands: `icshadow render SCENE --backend mc --spp 512 -o REF.exr --png REF.png`, then
`icshadow render SCENE --compare REF.exr --png SLAB.png --diff-png DIFF.png` for the default
2-sample ellipse and for the 19 x 19 Gaussian (the error and the times come from the summary).
Left: the three lights on the virtual light plane (their density, drawn here in numpy from the
same parameters, and 1- and 2-sigma ellipses): the map the scene's lights project to. Then the
slab render, the reference and their difference (x4, red: the render brighter). What to see:
each light's shadow displaced by -d mean from the disk (d = 1) and blurred by its own covariance
(the blue one along its 70-degree axis), the colours where one light is blocked and the others
are not; the slab renderer's shadows agree with the reference up to the kernel's discretisation.
Writes patel_fig14_scene.png and patel_fig14_scene.csv (kernel, rmse, rmse beyond the
reference's noise, max error, psnr, ms of the slab render and of the reference).
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
from matplotlib.patches import Ellipse  # noqa: E402

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "lib"))
from figutil import load_scene, parse_args, run_cli, save_fig, write_csv  # noqa: E402


def scene():
    """scenes/patel_fig14.json (its light weights are Fig. 14's 1, 2, 1 over 4)."""
    return load_scene("patel_fig14")


def lights():
    """(mean, variances along the light's axes, angle (deg, counter-clockwise), weight, colour) of
    each of the scene's lights."""
    return [(l["mean"], l["var"], l.get("angle_deg", 0), l.get("weight", 1), l.get("color", [1, 1, 1]))
            for l in scene()["lights"]]


def cov(v, a):
    c, s = math.cos(math.radians(a)), math.sin(math.radians(a))
    R = np.array([[c, -s], [s, c]])
    return R @ np.diag(v) @ R.T


def plane_density(ax):
    g = np.linspace(-2, 2, 241)
    x, y = np.meshgrid(g, -g)
    img = np.zeros(x.shape + (3,))
    for m, v, a, w, col in lights():
        S = cov(v, a)
        Si = np.linalg.inv(S)
        dx, dy = x - m[0], y - m[1]
        q = Si[0, 0] * dx * dx + 2 * Si[0, 1] * dx * dy + Si[1, 1] * dy * dy
        dens = w * np.exp(-0.5 * q) / (2 * math.pi * math.sqrt(np.linalg.det(S)))
        img += dens[:, :, None] * np.array(col)[None, None, :]
    # the file's weights are Fig. 14's over 4: 1 - exp(-(4 img) / 2) shades Fig. 14's weights
    ax.imshow(1 - np.exp(-2 * img), extent=(-2, 2, -2, 2))
    for m, v, a, w, col in lights():
        for k in (1, 2):
            ax.add_patch(Ellipse(m, 2 * k * math.sqrt(v[0]), 2 * k * math.sqrt(v[1]), angle=a, fill=False,
                                 ec="white", lw=0.8, ls="-" if k == 1 else "--"))
    ax.set_title("the lights on the light plane\n(1 and 2 sigma)", fontsize=8)
    ax.set_xlabel("x = tan wx", fontsize=7), ax.set_ylabel("y = tan wy", fontsize=7)
    ax.tick_params(labelsize=6)


def main():
    args = parse_args(__doc__)
    tmp = tempfile.mkdtemp(prefix="fig14s")
    sf = os.path.join(tmp, "scene.json")
    with open(sf, "w") as f:
        json.dump(scene(), f)
    ref, ref_png = os.path.join(tmp, "ref.exr"), os.path.join(tmp, "ref.png")
    mc = json.loads(run_cli(args.cli, ["render", sf, "--backend", "mc", "--spp", "512", "--aov", "stderr", "-o", ref,
                                       "--png", ref_png]))
    rows, pngs = [], {}
    for kernel, samples, comp in (("ellipse", 2, "expected"), ("gauss", 19, "nonneg")):
        png, diff = os.path.join(tmp, f"{kernel}.png"), os.path.join(tmp, f"{kernel}_diff.png")
        s = json.loads(run_cli(args.cli, ["render", sf, "--kernel", kernel, "--samples", str(samples),
                                          "--compensate", comp, "--compare", ref, "--png", png,
                                          "--diff-png", diff]))
        c = s["compare"]
        rows.append([f"{kernel}{samples} {comp}", c["rmse"], c["rmse_beyond_noise"], c["max_error"], c["psnr_db"],
                     s["ms_plan"] + s["ms_render"], mc["ms_render"], c["reference_noise"]])
        pngs[kernel] = (png, diff, c, s["ms_plan"] + s["ms_render"])
        print(f"{kernel}{samples} {comp}: rmse {c['rmse']:.4f} (beyond the reference's noise "
              f"{c['rmse_beyond_noise']:.4f}), max {c['max_error']:.3f}, psnr {c['psnr_db']:.1f} dB; "
              f"{s['ms_plan'] + s['ms_render']:.0f} ms vs the reference's {mc['ms_render']:.0f} ms (512 spp)")
    write_csv(os.path.join(args.out, "patel_fig14_scene.csv"),
              ["kernel", "rmse", "rmse_beyond_noise", "max_error", "psnr_db", "ms_slab", "ms_reference",
               "reference_noise"], rows)
    fig, ax = plt.subplots(1, 4, figsize=(13, 3.6))
    plane_density(ax[0])
    png, diff, c, ms = pngs["ellipse"]
    for k, (img, title) in enumerate(((png, f"slab renderer, ellipse2 ({ms:.0f} ms)"),
                                      (ref_png, f"Monte-Carlo reference, 512 spp ({mc['ms_render'] / 1e3:.1f} s)"),
                                      (diff, f"difference x4: rmse {c['rmse']:.4f}, max {c['max_error']:.2f}"))):
        ax[k + 1].imshow(mpimg.imread(img))
        ax[k + 1].set_title(title, fontsize=8)
        ax[k + 1].axis("off")
    fig.suptitle("Patel Fig. 14 as a scene: a disk over a plane under three coloured Gaussian lights", fontsize=9)
    fig.tight_layout()
    save_fig(fig, os.path.join(args.out, "patel_fig14_scene.png"), 100)


if __name__ == "__main__":
    main()
