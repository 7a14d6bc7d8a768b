#!/usr/bin/env python3
"""Reproduce Eisemann & Decoret 2006, Fig. 3 (combining slices: maximum vs sum vs product) from the
icshadow CLI.

The scene (`--scene`, default foliage: small cubes scattered in a canopy, like the paper's tree)
lies between a square light and a receiver plane; `icshadow bench occtex --fig3-csv` slices it,
prefilters the occlusion textures (SAT by default, so only the combination differs) and writes the
occlusion on the receiver plane for the three combinations and the brute-force reference.
Panels: brute force, max, clamped sum, product (1 - prod(1 - O_k), their Eq. 5), and the
difference of each to the brute force. The paper's claim: the sum is too dark, the max too
bright, the product in between; the script checks max <= product <= sum at every receiver (an
identity for values in [0, 1]) and prints the measured mean error and bias of each.
Writes eisemann_fig3_occtex.csv (from the CLI), eisemann_fig3_summary.csv and eisemann_fig3.png
into --out.
"""
import argparse
import csv
import os
import subprocess
import sys

import numpy as np

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--cli", default="build/bin/icshadow", help="path to the icshadow binary")
    ap.add_argument("--out", default="out/figs", help="output folder")
    ap.add_argument("--scene", default="foliage", help="foliage, plates or blocks")
    ap.add_argument("--size", type=int, default=256, help="texture side")
    ap.add_argument("--slices", type=int, default=8, help="number of slices")
    ap.add_argument("--receivers", type=int, default=128, help="R x R receivers")
    ap.add_argument("--prefilter", default="sat", help="mipmap, nbuffers or sat")
    args = ap.parse_args()
    os.makedirs(args.out, exist_ok=True)

    data_csv = os.path.join(args.out, "eisemann_fig3_occtex.csv")
    cmd = [args.cli, "bench", "occtex", "--scene", args.scene, "--sizes", str(args.size),
           "--slices", str(args.slices), "--receivers", str(args.receivers),
           "--fig3-prefilter", args.prefilter, "--fig3-csv", data_csv]
    res = subprocess.run(cmd, capture_output=True, text=True)
    if res.returncode != 0:
        sys.exit("fig3: %s failed: %s" % (" ".join(cmd), res.stderr.strip()))

    d = np.genfromtxt(data_csv, delimiter=",", names=True)
    R = args.receivers
    if d.shape[0] != R * R:
        sys.exit("fig3: expected %d rows in %s, got %d" % (R * R, data_csv, d.shape[0]))
    grid = {k: d[k].reshape(R, R) for k in ("exact", "max", "sum", "product")}
    viol = int(np.sum((d["max"] > d["product"] + 1e-12) | (d["product"] > d["sum"] + 1e-12)))
    if viol:
        sys.exit("fig3: max <= product <= sum fails at %d receivers" % viol)

    rows = []
    for k in ("max", "sum", "product"):
        e = d[k] - d["exact"]
        rows.append((k, float(np.mean(np.abs(e))), float(np.max(np.abs(e))), float(np.mean(e))))
        print("fig3: %-7s mean |error| %.4f  max |error| %.4f  bias %+.4f" % rows[-1])
    tmp = os.path.join(args.out, "eisemann_fig3_summary.csv.tmp")
    with open(tmp, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["combination", "mean_abs_err", "max_abs_err", "mean_signed_err"])
        for r in rows:
            w.writerow([r[0]] + ["%.17g" % v for v in r[1:]])
    os.replace(tmp, os.path.join(args.out, "eisemann_fig3_summary.csv"))

    ext = [-1.2, 1.2, -1.2, 1.2]
    fig, ax = plt.subplots(2, 4, figsize=(14, 7))
    titles = {"exact": "brute force", "max": "maximum", "sum": "sum (clamped)", "product": "product (Eq. 5)"}
    for i, k in enumerate(("exact", "max", "sum", "product")):
        # shown as lit fraction (1 - occlusion), as the paper shows shadows
        ax[0, i].imshow(1 - grid[k], origin="lower", extent=ext, cmap="gray", vmin=0, vmax=1)
        ax[0, i].set_title(titles[k])
        ax[0, i].set_xticks([])
        ax[0, i].set_yticks([])
    ax[1, 0].plot(np.linspace(-1.2, 1.2, R), 1 - grid["exact"][R // 2], "k-", label="brute force")
    for k, c in (("max", "tab:blue"), ("sum", "tab:red"), ("product", "tab:green")):
        ax[1, 0].plot(np.linspace(-1.2, 1.2, R), 1 - grid[k][R // 2], color=c, label=k)
    ax[1, 0].set_title("lit fraction along y = 0")
    ax[1, 0].legend(fontsize=7)
    for i, k in enumerate(("max", "sum", "product")):
        im = ax[1, i + 1].imshow(grid[k] - grid["exact"], origin="lower", extent=ext, cmap="RdBu_r", vmin=-0.5, vmax=0.5)
        ax[1, i + 1].set_title("%s - brute force (occlusion)" % k, fontsize=9)
        ax[1, i + 1].set_xticks([])
        ax[1, i + 1].set_yticks([])
    fig.colorbar(im, ax=ax[1, 1:].tolist(), shrink=0.8)
    fig.suptitle("Eisemann & Decoret 2006, Fig. 3: %s scene, %d slices, %d^2 %s" %
                 (args.scene, args.slices, args.size, args.prefilter))
    png = os.path.join(args.out, "eisemann_fig3.png")
    fig.savefig(png + ".tmp.png", dpi=110)
    os.replace(png + ".tmp.png", png)
    print("fig3: wrote %s" % png)


if __name__ == "__main__":
    main()
