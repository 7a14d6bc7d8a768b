#!/usr/bin/env python3
"""Patel et al. 2013, Fig. 15/20: a fence (poles and a bar) casting its shadow on a wall behind it
under lights of increasing variance — 0 (a point light), then 0.002 and 0.008 in light-plane
units (tan^2) — rendered by the slab renderer beside the Monte-Carlo reference. Patel's
zero-variance shadow is over-blurred (their Fig. 20 limitation: filtered taps blur a hard
shadow); here a zero-variance light propagates by integer shifts, so its shadow should be as
hard as the reference's.

Commands: `icshadow render SCENE --backend mc --spp 256 --aov stderr -o REF.exr --png REF.png`,
then `icshadow render SCENE --compare REF.exr --png SLAB.png`, per variance. The scene
(scenes/patel_fig20.json, there at variance 0.002): a fence of 7 poles (0.12 x 1.2 x 0.12,
spacing 0.45) with a bar across their tops, 0.6 in front of a white wall, orthographic,
160 x 120, slab spacing 0.01, light mean (0.35, 0.25). Also the fraction of
pixels where the two 8-bit previews (decoded to linear) differ by more than 0.5: for the point
light, the hard shadow's pixels on the wrong side of an edge.
Writes patel_fig20.png and patel_fig20.csv (variance, rmse, rmse beyond the reference's noise,
max error, that fraction, ms of each).
"""
import json
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

VARIANCES = (0.0, 0.002, 0.008)


def scene(var):
    """scenes/patel_fig20.json (variance 0.002) with the light's covariance var I."""
    s = load_scene("patel_fig20")
    s["lights"][0]["cov"] = [[var, 0], [0, var]]
    return s


def linear(png):
    v = mpimg.imread(png)[:, :, 0].astype(np.float64)
    return np.where(v <= 0.04045, v / 12.92, ((v + 0.055) / 1.055) ** 2.4)


def off_fraction(a, b):
    """The fraction of pixels where the two previews differ by more than 0.5 (a hard shadow one
    pixel off)."""
    return float(np.mean(np.abs(a - b) > 0.5))


def main():
    args = parse_args(__doc__)
    tmp = tempfile.mkdtemp(prefix="fig20")
    rows, panels = [], []
    for k, var in enumerate(VARIANCES):
        sf = os.path.join(tmp, f"s{k}.json")
        with open(sf, "w") as f:
            json.dump(scene(var), f)
        ref, ref_png, png = (os.path.join(tmp, n) for n in (f"ref{k}.exr", f"ref{k}.png", f"slab{k}.png"))
        mc = json.loads(run_cli(args.cli, ["render", sf, "--backend", "mc", "--spp", "256", "--aov", "stderr",
                                           "-o", ref, "--png", ref_png]))
        sl = json.loads(run_cli(args.cli, ["render", sf, "--compare", ref, "--png", png]))
        c = sl["compare"]
        v_slab, v_ref = linear(png), linear(ref_png)
        off = off_fraction(v_slab, v_ref)
        rows.append([var, c["rmse"], c["rmse_beyond_noise"], c["max_error"], off,
                     sl["ms_plan"] + sl["ms_render"], mc["ms_render"]])
        panels.append((var, v_slab, v_ref, c, off))
        print(f"variance {var:g}: slab vs reference rmse {c['rmse']:.4f} (beyond noise {c['rmse_beyond_noise']:.4f}), "
              f"max {c['max_error']:.3f}, {100 * off:.2f} % of pixels off by > 0.5; "
              f"{sl['ms_plan'] + sl['ms_render']:.0f} ms vs {mc['ms_render']:.0f} ms")
    write_csv(os.path.join(args.out, "patel_fig20.csv"),
              ["variance", "rmse", "rmse_beyond_noise", "max_error", "off_fraction", "ms_slab",
               "ms_reference"], rows)
    fig, ax = plt.subplots(2, len(VARIANCES), figsize=(4 * len(VARIANCES), 6.2))
    for k, (var, vs, vr, c, off) in enumerate(panels):
        ax[0][k].imshow(vs, cmap="gray", vmin=0, vmax=1)
        ax[0][k].set_title(f"slab, variance {var:g}: rmse {c['rmse']:.3f}, {100 * off:.1f} % off by > 0.5",
                           fontsize=8)
        ax[1][k].imshow(vr, cmap="gray", vmin=0, vmax=1)
        ax[1][k].set_title("Monte-Carlo reference (256 spp)", fontsize=8)
        for r in (0, 1):
            ax[r][k].set_xticks([]), ax[r][k].set_yticks([])
    fig.suptitle("Patel Fig. 15/20: a fence's shadow under lights of increasing variance", fontsize=9)
    fig.tight_layout()
    save_fig(fig, os.path.join(args.out, "patel_fig20.png"), 100)


if __name__ == "__main__":
    main()
