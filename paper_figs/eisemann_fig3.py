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
import os
import sys

import numpy as np

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "lib"))
from figutil import arg_parser, parse_args, run_cli, save_fig, write_csv  # noqa: E402


def main():
    ap = arg_parser(__doc__)
    ap.add_argument("--scene", default="foliage", help="foliage, plates or blocks")
    ap.add_argument("--size", type=int, default=256, help="texture side")
    ap.add_argument("--slices", type=int, default=8, help="number of slices")
    ap.add_argument("--receivers", type=int, default=128, help="R x R receivers")
    ap.add_argument("--prefilter", default="sat", help="mipmap, nbuffers or sat")
    args = parse_args(ap)

    data_csv = os.path.join(args.out, "eisemann_fig3_occtex.csv")
    run_cli(args.cli, ["bench", "occtex", "--scene", args.scene, "--sizes", str(args.size),
                       "--slices", str(args.slices), "--receivers", str(args.receivers),
                       "--fig3-prefilter", args.prefilter, "--fig3-csv", data_csv])

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
    write_csv(os.path.join(args.out, "eisemann_fig3_summary.csv"),
              ["combination", "mean_abs_err", "max_abs_err", "mean_signed_err"], rows)

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
    save_fig(fig, png, 110)
    print("fig3: wrote %s" % png)


if __name__ == "__main__":
    main()
