#!/usr/bin/env python3
"""Gaussian light fitting, in the manner of Patel et al. 2013, Fig. 14 (c)/(d), from the CLI.

A synthetic environment map holds three lights like Fig. 14's (a small green one, a broad red
one, and a thin blue one rotated 70 degrees clockwise; variances scaled by 1/10 so they stay
inside the 80-degree cut-off) over a dim uniform sky. `icshadow make-env` draws it,
`icshadow fit-light --sweep` fits K = 1..8 Gaussians and prints the error table, and
`--plane-csv` gives the map projected onto the virtual light plane (density l = L dw/dA).

Left:   the map on the light plane (tone-mapped RGB) with the fitted K = 4 Gaussians overlaid
        (1- and 2-sigma ellipses in each light's colour).
Middle: the fitted K = 4 mixture (three lights and one for the sky) evaluated here (numpy) from the lights file, same scale.
Right:  fit error against K (L1, L2 on the plane; edge-shadow error at d1) and against time.
Writes lightfit_fig14.png, lightfit_fig14_errors.csv (the CLI's table), lightfit_fig14_lights.csv
into --out. Consistency check here: the mixture's total luminance equals the kept energy of the
map summed from the plane CSV. This is not an independent check of the change of measure (the
CLI writes L (1 + r^2)^(-3/2) and this script multiplies by (1 + r^2)^(3/2), so both sides sum
Y dw, and fitted weights add up to the kept energy by construction); it checks that the kept
set and the pixel solid angles agree with the library's. The change of measure is checked in
tests/test_lightfit.c against the analytic total weight of a rendered map.
"""
import csv
import io
import json
import os
import sys
import tempfile

import numpy as np

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.patches import Ellipse  # noqa: E402

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "lib"))
from figutil import parse_args, run_cli, save_fig, write_csv  # noqa: E402

SPEC = ("-0.55,0.35,0.08,0.08,0,1,0.2,1,0.2"
        ":0.6,0.3,0.32,0.32,0,2,1,0.2,0.1"
        ":0.05,-0.6,0.3,0.002,-70,1,0.15,0.25,1")
W, H = 512, 256
KMAX = 8
KFIG = 4  # three lights and the sky


def mixture(lights, x, y):
    """RGB density of the lights at plane points (x, y)."""
    out = np.zeros(x.shape + (3,))
    for l in lights:
        (cxx, cxy), (_, cyy) = l["cov"]
        det = cxx * cyy - cxy * cxy
        dx, dy = x - l["mean"][0], y - l["mean"][1]
        q = (cyy * dx * dx - 2 * cxy * dx * dy + cxx * dy * dy) / det
        g = np.exp(-0.5 * q) / (2 * np.pi * np.sqrt(det))
        out += l["weight"] * g[..., None] * np.array(l["color"])
    return out


def ellipse(ax, l, nsig, **kw):
    c = np.array(l["cov"])
    ev, evec = np.linalg.eigh(c)
    ang = np.degrees(np.arctan2(evec[1, 1], evec[0, 1]))
    w, h = 2 * nsig * np.sqrt(np.maximum(ev[::-1], 0))
    ax.add_patch(Ellipse(l["mean"], w, h, angle=ang, fill=False, **kw))


def main():
    args = parse_args(__doc__)
    with tempfile.TemporaryDirectory() as tmp:
        env = os.path.join(tmp, "env.exr")
        run_cli(args.cli, ["make-env", "--lights", SPEC, "--sky", "0.02,0.03,0.05", "--size", "%dx%d" % (W, H), "-o", env])
        lj = os.path.join(tmp, "lights.json")
        table = run_cli(args.cli, ["fit-light", env, "--lights", str(KMAX), "--sweep", "-o", lj])
        lj4 = os.path.join(tmp, "lights%d.json" % KFIG)
        pc = os.path.join(tmp, "plane.csv")
        run_cli(args.cli, ["fit-light", env, "--lights", str(KFIG), "-o", lj4, "--plane-csv", pc])
        with open(lj4) as f:
            lights = json.load(f)["lights"]
        plane = np.genfromtxt(pc, delimiter=",", names=True)
    rows = list(csv.reader(io.StringIO(table)))
    header, rows = rows[0], rows[1:]
    write_csv(os.path.join(args.out, "lightfit_fig14_errors.csv"), header, rows)
    write_csv(os.path.join(args.out, "lightfit_fig14_lights.csv"),
              ["mx", "my", "cxx", "cxy", "cyy", "r", "g", "b", "weight"],
              [l["mean"] + [l["cov"][0][0], l["cov"][0][1], l["cov"][1][1]] + l["color"] + [l["weight"]] for l in lights])

    # consistency check (see the docstring: not independent of the change of measure): kept
    # luminance energy summed from the plane CSV (area of each pixel on the plane = its solid
    # angle * (1 + r^2)^(3/2)) against the fitted weights
    i, j = plane["i"].astype(int), plane["j"].astype(int)
    x, y = plane["x"], plane["y"]
    th0, th1 = np.pi * j / H, np.pi * (j + 1) / H
    dw = (np.cos(th0) - np.cos(th1)) * 2 * np.pi / W
    area = dw * (1 + x * x + y * y) ** 1.5
    lum = 0.2126 * plane["r"] + 0.7152 * plane["g"] + 0.0722 * plane["b"]
    kept = plane["kept"] > 0
    e_kept = float(np.sum((lum * area)[kept]))
    wsum = sum(l["weight"] for l in lights)
    print("kept energy from the plane CSV %.6g, sum of fitted weights %.6g (rel %.2g)"
          % (e_kept, wsum, abs(wsum / e_kept - 1)))
    if abs(wsum / e_kept - 1) > 1e-6:
        sys.exit("fitted weights do not add up to the map's kept energy")

    # the half map behind the viewer is a rectangle of pixels
    i0, j0 = i.min(), j.min()
    nx, ny = i.max() - i0 + 1, j.max() - j0 + 1
    rgb = np.full((ny, nx, 3), np.nan)
    for c, name in enumerate("rgb"):
        rgb[j - j0, i - i0, c] = plane[name]

    # the plane image: every point of a regular grid on [-2, 2]^2 looks up the map pixel of its
    # direction (nearest pixel; x = tan(phi), theta = acos(y / sqrt(1 + x^2 + y^2)))
    n = 600
    gx, gy = np.meshgrid(np.linspace(-2, 2, n), np.linspace(2, -2, n))
    norm = np.sqrt(1 + gx * gx + gy * gy)
    pi_ = np.clip(np.floor((np.arctan(gx) + np.pi) / (2 * np.pi) * W).astype(int) - i0, 0, nx - 1)
    pj_ = np.clip(np.floor(np.arccos(gy / norm) / np.pi * H).astype(int) - j0, 0, ny - 1)
    img_map = rgb[pj_, pi_]
    img_fit = mixture(lights, gx, gy)
    scale = np.nanpercentile(img_map, 99.5)
    tone = lambda a: np.clip(np.nan_to_num(a) / scale, 0, 1) ** (1 / 2.2)  # noqa: E731

    fig, axs = plt.subplots(1, 3, figsize=(16, 5.2))
    for ax, img, title in ((axs[0], img_map, "map on the light plane, fitted K = %d overlaid" % KFIG),
                           (axs[1], img_fit, "fitted mixture (K = %d, from the lights file)" % KFIG)):
        ax.imshow(tone(img), extent=(-2, 2, -2, 2), interpolation="bilinear")
        ax.set_xlabel("x = tan(x-tilt)")
        ax.set_ylabel("y = tan(y-tilt)")
        ax.set_title(title, fontsize=10)
    for l in lights:
        col = np.clip(np.array(l["color"]) / max(l["color"]), 0, 1)
        for s in (1, 2):
            ellipse(axs[0], l, s, edgecolor="white", lw=1.2, ls="-" if s == 1 else "--")
        axs[0].plot(*l["mean"], "+", color=col, ms=10, mew=2)
    axs[0].set_xlim(-2, 2)
    axs[0].set_ylim(-2, 2)
    k = np.array([int(r[0]) for r in rows])
    l1 = np.array([float(r[2]) for r in rows])
    l2 = np.array([float(r[3]) for r in rows])
    edge = np.array([float(r[4]) for r in rows])
    secs = np.array([float(r[5]) for r in rows])
    ax = axs[2]
    ax.semilogy(k, l1, "o-", label="L1 (plane)")
    ax.semilogy(k, l2, "s-", label="L2 (plane)")
    ax.semilogy(k, edge, "^-", label="edge shadow at d1 (sup)")
    ax.set_xlabel("K (Gaussian lights)")
    ax.set_ylabel("relative error")
    ax.grid(True, which="both", alpha=0.3)
    for kk, s_, e_ in zip(k, secs, l1):  # centred above each point, inside the axes
        ax.annotate("%.2fs" % s_, (kk, e_), textcoords="offset points", xytext=(0, 6), fontsize=7,
                    ha="center")
    ax.set_xlim(min(k) - 0.5, max(k) + 0.5)
    ax.legend(fontsize=8)
    ax.set_title("fit error against K (labels: fit time)", fontsize=10)
    fig.tight_layout()
    png = os.path.join(args.out, "lightfit_fig14.png")
    save_fig(fig, png, 110)
    print("wrote", png)
    print(table, end="")


if __name__ == "__main__":
    main()
