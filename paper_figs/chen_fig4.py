#!/usr/bin/env python3
"""Reproduce Chen, Baran, Durand, Jarosz 2011, Fig. 4, from the icshadow CLI.

One row of the epipolar-rectified shadow map of libicshadow's height-field scene (64 depth
samples), its 1D min-max mipmap, and the traversal of one camera ray (the ray with the most lit
runs in the scene). Data: `icshadow bench minmax --samples 64 --fig4-csv FILE`.
Top:    the row (light depth of the occluder per light ray, a 1D height field), the ray's
        line h(gamma), its lit runs (sample lit iff S > h, Chen Eq. 6).
Middle: the min-max mipmap: per level (root on top), each node's [min, max] drawn as a bar.
Bottom: the traversal: nodes fully lit (white), fully shadowed (black), partial (grey, the
        traversal descends), not visited (hatched).
The script checks the C traversal independently: the lit runs it reports must equal the runs of
samples with S > h computed here in numpy, and every node's [min, max] must be the extremes of
its samples. Writes chen_fig4.csv (the CLI's data) and chen_fig4.png into --out.
"""
import csv
import os
import sys

import numpy as np

import matplotlib

matplotlib.use("Agg")
import matplotlib.patches as mpatches  # noqa: E402
import matplotlib.pyplot as plt  # noqa: E402

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "lib"))
from figutil import parse_args, run_cli, save_fig  # noqa: E402


def main():
    args = parse_args(__doc__)
    csv_path = os.path.join(args.out, "chen_fig4.csv")
    run_cli(args.cli, ["bench", "minmax", "--samples", "64", "--rows", "64", "--rays", "64", "--fig4-csv", csv_path])

    samples, nodes, runs, ray = [], [], [], None
    with open(csv_path, newline="") as f:
        for r in csv.DictReader(f):
            if r["kind"] == "sample":
                samples.append(float(r["lo"]))
            elif r["kind"] == "node":
                # %.9g round-trips a float exactly when read back as float32
                nodes.append((int(r["index"]), int(r["level"]), int(r["g0"]), int(r["g1"]),
                              float(np.float32(r["lo"])), float(np.float32(r["hi"])), int(r["class"])))
            elif r["kind"] == "run":
                runs.append((int(r["g0"]), int(r["g1"])))
            elif r["kind"] == "ray":
                ray = (int(r["index"]), float(r["lo"]), float(r["hi"]), int(r["g1"]))
    S = np.array(samples, dtype=np.float32).astype(np.float64)
    d = len(S)
    row, beta0, slope, gend = ray
    g = np.arange(d)
    h = beta0 + slope * g.astype(np.float64)

    # independent check of the traversal and of the tree
    lit = (S > h) & (g < gend)
    ref, start = [], None
    for i in range(d + 1):
        on = i < d and lit[i]
        if on and start is None:
            start = i
        if not on and start is not None:
            ref.append((start, i))
            start = None
    if ref != runs:
        sys.exit("chen_fig4: traversal runs %s differ from the per-sample test %s" % (runs, ref))
    for k, lvl, g0, g1, lo, hi, cls in nodes:
        seg = S[g0:g1]
        if seg.min() != lo or seg.max() != hi:
            sys.exit("chen_fig4: node %d [%g, %g] is not the min/max of its samples" % (k, lo, hi))
    print("chen_fig4: row %d, %d samples, %d lit runs, %d nodes; runs equal the per-sample test"
          % (row, d, len(runs), len(nodes)))

    levels = max(n[1] for n in nodes) + 1
    fig, ax = plt.subplots(3, 1, figsize=(9, 9), sharex=True,
                           gridspec_kw={"height_ratios": [2.2, 2.2, 1.4]})
    ax[0].step(np.arange(d + 1), np.append(S, S[-1]), where="post", color="k", lw=1.2,
               label="rectified shadow map row S[gamma]")
    ax[0].plot([0, gend], [beta0, beta0 + slope * gend], "r-", lw=1.2, label="camera ray h(gamma)")
    for a, b in runs:
        ax[0].plot([a, b], [beta0 + slope * a, beta0 + slope * b], color="gold", lw=5, alpha=0.8,
                   solid_capstyle="butt")
    ax[0].axvline(gend, color="r", ls=":", lw=1)
    ax[0].plot([], [], color="gold", lw=5, label="lit runs (S > h)")
    ax[0].set_ylabel("light depth")
    ax[0].set_title("Chen et al. 2011, Fig. 4: a rectified row, its min-max mipmap, one ray's traversal")
    ax[0].legend(loc="best", fontsize=8)

    cmap = plt.get_cmap("viridis")
    lo_all, hi_all = S.min(), S.max()
    for k, lvl, g0, g1, lo, hi, cls in nodes:
        y = levels - 1 - lvl
        c0 = (lo - lo_all) / (hi_all - lo_all + 1e-30)
        c1 = (hi - lo_all) / (hi_all - lo_all + 1e-30)
        ax[1].add_patch(mpatches.Rectangle((g0, y), g1 - g0, 0.5, facecolor=cmap(c1), edgecolor="w", lw=0.3))
        ax[1].add_patch(mpatches.Rectangle((g0, y + 0.5), g1 - g0, 0.5, facecolor=cmap(c0), edgecolor="w", lw=0.3))
    ax[1].set_ylim(0, levels)
    ax[1].set_yticks(np.arange(levels) + 0.5)
    ax[1].set_yticklabels(["level %d" % (levels - 1 - i) for i in range(levels)], fontsize=7)
    ax[1].set_ylabel("min (upper) / max (lower)")
    sm = plt.cm.ScalarMappable(cmap=cmap, norm=plt.Normalize(lo_all, hi_all))
    fig.colorbar(sm, ax=ax[1], pad=0.01, label="light depth")

    face = {0: "none", 1: "white", 2: "black", 3: "0.6"}
    for k, lvl, g0, g1, lo, hi, cls in nodes:
        y = levels - 1 - lvl
        ax[2].add_patch(mpatches.Rectangle((g0, y), g1 - g0, 1, facecolor=face[cls], edgecolor="0.3",
                                           lw=0.4, hatch="//" if cls == 0 else None))
    ax[2].set_ylim(0, levels)
    ax[2].set_yticks([])
    ax[2].set_xlim(0, d)
    ax[2].set_xlabel("gamma (light ray index in the epipolar row)")
    ax[2].legend(handles=[mpatches.Patch(facecolor="white", edgecolor="k", label="fully lit"),
                          mpatches.Patch(facecolor="black", label="fully shadowed"),
                          mpatches.Patch(facecolor="0.6", label="partial: descend"),
                          mpatches.Patch(facecolor="none", edgecolor="k", hatch="//", label="not visited")],
                 loc="upper center", bbox_to_anchor=(0.5, -0.35), ncol=4, fontsize=8)
    fig.colorbar(sm, ax=ax[2], pad=0.01).remove()
    fig.colorbar(sm, ax=ax[0], pad=0.01).remove()
    fig.tight_layout()
    png = os.path.join(args.out, "chen_fig4.png")
    save_fig(fig, png, 130)
    print("chen_fig4: wrote %s and %s" % (csv_path, png))


if __name__ == "__main__":
    main()
