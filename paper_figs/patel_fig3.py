#!/usr/bin/env python3
"""Reproduce Patel et al. 2013, Fig. 3 from the icshadow CLI: 100 steps of iterative
convolution of a Heaviside edge with three members of one kernel equivalence class.

Class: mean 0, variance 30.25 px^2 (sigma = 5.5 px: the paper's Dirac kernel of width 11).
Columns: top-hat (box width sqrt(12) sigma = 19.05 px, exact variance on the interpolated grid),
Dirac (taps at -+5.5 px, 2 samples), stochastic Dirac (taps at -+(rho + u), u ~ U(-1, 1),
rho = sqrt(sigma^2 - 1/3): width 2 sigma +- 2, 2 samples).
Row 1: the evolution image, x across, step 0..100 down (like the paper); the black rectangle is
        zoomed in row 2 (the first 20 steps near the edge, where the Dirac staircase shows).
Row 3: the profile after 100 steps with the Gaussian cdf of the same moments (dashed) and, in the
        inset, the difference profile - Gaussian at step 100 (same scale in all three columns);
        the grey curve is step 10, where the Dirac staircase is plain.
Every number comes from `icshadow iterate` (the library's convolution engine); the Gaussian
reference is the CLI's gauss_cdf column (same moments as applied, plus the grid's 1/12 px^2).
Writes patel_fig3_profiles.csv (kernel, steps, x, value, gauss_cdf at steps 1, 2, 5, 10, 20, 50, 100),
patel_fig3_summary.csv (kernel, steps, max |value - gauss_cdf|, ripple = max |second difference|)
and patel_fig3.png into --out.
"""
import csv
import io
import os
import sys

import numpy as np

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.patches import Rectangle  # noqa: E402

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "lib"))
from figutil import parse_args, run_cli, save_fig, write_csv  # noqa: E402

VAR = 30.25
STEPS = 100
SEED = 1
KERNELS = [("tophat", "top-hat (width %.2f, %s taps)"),
           ("dirac", "Dirac (width 11, 2 taps)"),
           ("stochastic-dirac", "stochastic Dirac (width 11 $\\pm$ 2, 2 taps)")]
CSV_STEPS = [1, 2, 5, 10, 20, 50, 100]
ZOOM_X = (-40.0, 40.0)
ZOOM_STEPS = (0, 20)


def iterate(cli, kernel):
    """steps x profile arrays from `icshadow iterate` for steps 0..STEPS."""
    out = run_cli(cli, ["iterate", "--kernel", kernel, "--var", repr(VAR), "--steps", "0:%d" % STEPS,
                        "--seed", str(SEED)])
    d = np.genfromtxt(io.StringIO(out), delimiter=",", names=True)
    steps = np.unique(d["steps"]).astype(int)
    x = d["x"][d["steps"] == steps[0]]
    val = d["value"].reshape(len(steps), len(x))
    gauss = d["gauss_cdf"].reshape(len(steps), len(x))
    return steps, x, val, gauss


def kernel_table(cli):
    out = run_cli(cli, ["kernel-table", "--var", repr(VAR), "--no-timing", "--iterations", "1000"])
    return {r["member"]: r for r in csv.DictReader(io.StringIO(out))}


def main():
    args = parse_args(__doc__)

    table = kernel_table(args.cli)
    runs = {k: iterate(args.cli, k) for k, _ in KERNELS}

    prof_rows, summ_rows = [], []
    for k, _ in KERNELS:
        steps, x, val, gauss = runs[k]
        # sanity of what the engine produced: monotone profiles between 0 and 1
        if np.any(val < -1e-12) or np.any(val > 1 + 1e-12):
            sys.exit("patel_fig3: %s profile leaves [0, 1]" % k)
        for s in CSV_STEPS:
            i = int(np.nonzero(steps == s)[0][0])
            prof_rows += [[k, s, xx, v, g] for xx, v, g in zip(x, val[i], gauss[i])]
        for s in (1, 10, 100):
            i = int(np.nonzero(steps == s)[0][0])
            err = float(np.max(np.abs(val[i] - gauss[i])))
            ripple = float(np.max(np.abs(np.diff(val[i], 2))))
            summ_rows.append([k, s, "%.6g" % err, "%.6g" % ripple])
            print("patel_fig3: %-16s step %3d  max|r - Phi| = %.3g  max|2nd difference| = %.3g" % (k, s, err, ripple))
    write_csv(os.path.join(args.out, "patel_fig3_profiles.csv"), ["kernel", "steps", "x", "value", "gauss_cdf"], prof_rows)
    write_csv(os.path.join(args.out, "patel_fig3_summary.csv"), ["kernel", "steps", "max_abs_err_vs_gauss", "max_abs_second_difference"], summ_rows)

    ylim = 1.15 * max(float(np.max(np.abs(r[2][-1] - r[3][-1]))) for r in runs.values())
    fig, ax = plt.subplots(3, 3, figsize=(13, 10.5), gridspec_kw={"height_ratios": [1.1, 1.1, 1.2]})
    for c, (k, title) in enumerate(KERNELS):
        steps, x, val, gauss = runs[k]
        if k == "tophat":
            title = title % (np.sqrt(12 * VAR), table["tophat"]["taps"])
        xr = (-150, 150)
        sel = (x >= xr[0]) & (x <= xr[1])
        a = ax[0, c]
        a.imshow(val[:, sel], cmap="gray_r", vmin=0, vmax=1, aspect="auto", interpolation="nearest",
                 extent=(x[sel][0] - 0.5, x[sel][-1] + 0.5, steps[-1] + 0.5, steps[0] - 0.5))
        a.add_patch(Rectangle((ZOOM_X[0], ZOOM_STEPS[0] - 0.5), ZOOM_X[1] - ZOOM_X[0], ZOOM_STEPS[1] - ZOOM_STEPS[0] + 1,
                              fill=False, ec="red", lw=1.5))
        a.set_title(title, fontsize=10)
        a.set_xlabel("x (px)")
        if c == 0:
            a.set_ylabel("step n (shadow value: white 0, black 1)")

        zs = (x >= ZOOM_X[0]) & (x <= ZOOM_X[1])
        a = ax[1, c]
        a.imshow(val[ZOOM_STEPS[0]:ZOOM_STEPS[1] + 1][:, zs], cmap="gray_r", vmin=0, vmax=1, aspect="auto",
                 interpolation="nearest",
                 extent=(x[zs][0] - 0.5, x[zs][-1] + 0.5, ZOOM_STEPS[1] + 0.5, ZOOM_STEPS[0] - 0.5))
        a.set_title("zoom: steps %d-%d, |x| <= %g" % (ZOOM_STEPS[0], ZOOM_STEPS[1], ZOOM_X[1]), fontsize=9)
        a.set_xlabel("x (px)")
        if c == 0:
            a.set_ylabel("step n")

        a = ax[2, c]
        i100 = int(np.nonzero(steps == 100)[0][0])
        i10 = int(np.nonzero(steps == 10)[0][0])
        a.plot(x, val[i100], "k-", lw=1.5, label="iterated, n = 100")
        a.plot(x, gauss[i100], "r--", lw=1.0, label="Gaussian cdf, same moments")
        a.plot(x, val[i10], "-", color="0.55", lw=1.0, label="iterated, n = 10")
        a.set_xlim(-200, 200)
        a.set_xlabel("x (px)")
        a.set_ylim(-0.02, 1.02)
        if c == 0:
            a.set_ylabel("shadow value")
        a.legend(loc="upper left", fontsize=7, frameon=False)
        ins = a.inset_axes([0.55, 0.1, 0.42, 0.38])
        ins.plot(x, val[i100] - gauss[i100], "k-", lw=0.8)
        ins.axhline(0, color="r", lw=0.5)
        ins.set_xlim(-150, 150)
        ins.set_ylim(-ylim, ylim)
        ins.set_title("n = 100: value $-$ Gaussian", fontsize=7)
        ins.tick_params(labelsize=6)
        ins.ticklabel_format(axis="y", style="sci", scilimits=(-2, 2))
        ins.yaxis.get_offset_text().set_fontsize(6)

    fig.suptitle("Patel et al. 2013, Fig. 3: 100 steps on a Heaviside edge, class mean 0, variance %g px$^2$ "
                 "(icshadow iterate)" % VAR, fontsize=11)
    fig.tight_layout()
    png = os.path.join(args.out, "patel_fig3.png")
    save_fig(fig, png, 110)
    print("patel_fig3: wrote %s, patel_fig3_profiles.csv, patel_fig3_summary.csv" % png)


if __name__ == "__main__":
    main()
