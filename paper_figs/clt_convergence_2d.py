#!/usr/bin/env python3
"""CLT convergence of the 2D kernel members (docs/theory.md, "CLT convergence of 2D members").

Runs `icshadow clt --kernel K2 --cov 16,8,30 --steps 8,16,32,64,128` with an edge at 0, 30, 60
and 120 degrees and with the corner occluder, for the elliptical kernel with N = 2, 3, 8
samples under three offset schedules (fixed offset 0, golden-ratio rotation, random offset per
step = the kernel member), the Poisson-disk member (N = 8) and the 2D truncated Gaussian (5 x 5).
The class (16, 8) px^2 rotated 30 degrees puts the ellipse's major axis at 30 degrees: edge 30 =
along the major axis, 120 = across it.

sup_error is measured against the class Gaussian, sup_error_realized against the Gaussian with the
summed moments of the integer taps actually applied. A point is resolved only when its
discretisation estimate (2x finer grid) is below a tenth of the error it is compared with;
rates are least-squares slopes of log error vs log n over the resolved points with n >= 16
(nan with fewer than 2). Writes clt_convergence_2d.csv (every point), clt_convergence_2d.md (the
table of docs/theory.md) and clt_convergence_2d.png into --out.
"""
import concurrent.futures
import csv
import io
import math
import os
import sys

import numpy as np

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "lib"))
from figutil import arg_parser, parse_args, run_cli, save_fig, write_csv, write_text  # noqa: E402

MEMBERS = [  # (label, extra CLI arguments)
    ("ellipse N=2 fixed", ["--kernel", "ellipse", "--samples", "2", "--offsets", "fixed"]),
    ("ellipse N=2 golden", ["--kernel", "ellipse", "--samples", "2", "--offsets", "golden"]),
    ("ellipse N=2 random", ["--kernel", "ellipse", "--samples", "2"]),
    ("ellipse N=3 fixed", ["--kernel", "ellipse", "--samples", "3", "--offsets", "fixed"]),
    ("ellipse N=3 golden", ["--kernel", "ellipse", "--samples", "3", "--offsets", "golden"]),
    ("ellipse N=3 random", ["--kernel", "ellipse", "--samples", "3"]),
    ("ellipse N=8 fixed", ["--kernel", "ellipse", "--samples", "8", "--offsets", "fixed"]),
    ("ellipse N=8 golden", ["--kernel", "ellipse", "--samples", "8", "--offsets", "golden"]),
    ("ellipse N=8 random", ["--kernel", "ellipse", "--samples", "8"]),
    ("poisson N=8", ["--kernel", "poisson"]),
    ("gauss 5x5", ["--kernel", "gauss"]),
]
GEOMS = [("edge 0", ["--edge-angle", "0"]), ("edge 30", ["--edge-angle", "30"]),
         ("edge 60", ["--edge-angle", "60"]), ("edge 120", ["--edge-angle", "120"]),
         ("corner", ["--corner"])]


def fit(n, e, ok):
    m = ok & (n >= 16) & (e > 0)
    if m.sum() < 2:
        return float("nan"), float("nan")
    x, y = np.log(n[m]), np.log(e[m])
    r = np.polyfit(x, y, 1)[0]
    last = np.nonzero(m)[0][-1]
    return r, e[last] * n[last] ** (-r)


def main():
    ap = arg_parser(__doc__)
    ap.add_argument("--cov", default="16,8,30", help="class VX,VY,ANGLE (px^2, degrees)")
    ap.add_argument("--steps", default="8,16,32,64,128")
    args = parse_args(ap)
    rows, table = [], []
    data = {}
    # the 55 runs are independent single-threaded processes: run them on every core (the CPU-time
    # column is per process, so it does not depend on this)
    with concurrent.futures.ThreadPoolExecutor(max_workers=os.cpu_count() or 1) as pool:
        futures = {(label, gname): pool.submit(run_cli, args.cli, ["clt", "--cov", args.cov, "--steps",
                                                                  args.steps] + margs + gargs)
                   for label, margs in MEMBERS for gname, gargs in GEOMS}
        # progress: the runs take minutes together on two cores
        for done, _ in enumerate(concurrent.futures.as_completed(futures.values()), 1):
            print("clt_convergence_2d: %d of %d runs done" % (done, len(futures)), file=sys.stderr,
                  flush=True)
    for label, margs in MEMBERS:
        for gname, gargs in GEOMS:
            out = futures[(label, gname)].result()
            rr = list(csv.DictReader(io.StringIO(out)))
            d = {c: np.array([float(r[c]) for r in rr]) for c in rr[0]}
            n, e, er, de = d["steps"], d["sup_error"], d["sup_error_realized"], d["disc_error"]
            ok, okr = de < e / 10, de < er / 10
            rc, cc = fit(n, e, ok)
            rr_, cr = fit(n, er, okr)
            sel = (n >= 16)
            worst = float(np.max(de[sel] / np.minimum(e[sel], er[sel])))
            data[(label, gname)] = (n, e, er, ok, okr)
            for i in range(len(n)):
                rows.append([label, gname, int(n[i]), e[i], er[i], de[i], int(ok[i]), int(okr[i]),
                             d["taps_x_steps"][i], d["seconds"][i]])
            table.append((label, gname, rc, cc, rr_, cr, e[-1], er[-1], de[-1], worst,
                          d["taps_x_steps"][-1], d["seconds"][-1], int(ok[sel].sum()), int(okr[sel].sum()),
                          int(sel.sum())))
            print("%-20s %-9s class rate %7.3f  realised rate %7.3f  err(n=%d) %.3g / %.3g  disc %.2g" %
                  (label, gname, rc, rr_, n[-1], e[-1], er[-1], de[-1]), flush=True)
    write_csv(os.path.join(args.out, "clt_convergence_2d.csv"),
              ["member", "occluder", "steps", "sup_error", "sup_error_realized", "disc_error",
               "resolved", "resolved_realized", "taps_x_steps", "seconds"], rows)

    def f(v, fmt):
        return "—" if not np.isfinite(v) else fmt % v
    lines = ["| member | occluder | rate (class) | C (class) | rate (realised) | C (realised) | "
             "err class / realised at n = %s | disc at n = %s | worst disc / err (n >= 16) | "
             "taps x n | CPU s | resolved (class, realised) |" % (args.steps.split(",")[-1], args.steps.split(",")[-1]),
             "|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for (label, g, rc, cc, rr_, cr, e, er, de, worst, cost, secs, k1, k2, kt) in table:
        lines.append("| %s | %s | %s | %s | %s | %s | %.2e / %.2e | %.1e | %.2g | %d | %.2f | %d, %d of %d |" % (
            label, g, f(rc, "%.2f"), f(cc, "%.3g"), f(rr_, "%.2f"), f(cr, "%.3g"), e, er, de, worst,
            cost, secs, k1, k2, kt))
    write_text(os.path.join(args.out, "clt_convergence_2d.md"), "\n".join(lines) + "\n")

    # one panel per occluder (2 x 3, the sixth holds the legend); colour = the member's sample
    # count, line and marker = the offset schedule, so no two curves share a style
    fig, axs = plt.subplots(2, 3, figsize=(13, 8), sharey=True)
    axs = axs.ravel()
    colours = {"N=2": "tab:blue", "N=3": "tab:orange", "N=8": "tab:green", "poisson": "tab:purple",
               "gauss": "tab:brown"}
    styles = {"fixed": ("-", "o"), "golden": ("--", "s"), "random": ("-.", "^")}
    for j, (gname, _) in enumerate(GEOMS):
        ax = axs[j]
        for label, _ in MEMBERS:
            n, e, er, ok, okr = data[(label, gname)]
            words = label.split()
            c = colours[words[1] if words[0] == "ellipse" else words[0]]
            ls, mk = styles.get(words[-1], ("-", "D"))
            ax.loglog(n, er, ls, color=c, lw=1.2, label=label)
            ax.loglog(n[okr], er[okr], mk, color=c, ms=5)
            ax.loglog(n[~okr], er[~okr], mk, mfc="none", color="0.6", ms=5)
        n0 = np.array([8.0, 128.0])
        ax.loglog(n0, 3e-2 * (n0 / 8) ** -0.5, "k:", lw=1, label=r"$n^{-1/2}$")
        ax.loglog(n0, 3e-3 * (n0 / 8) ** -1.0, "k", lw=0.8, alpha=0.5, label=r"$n^{-1}$")
        ax.set_title("%s (vs realised moments)" % gname)
        ax.set_xlabel("steps n")
        ax.grid(True, which="major", alpha=0.3)
        if j % 3 == 0:
            ax.set_ylabel("sup error")
    handles, labels = axs[0].get_legend_handles_labels()
    axs[-1].axis("off")
    axs[-1].legend(handles, labels, loc="center", fontsize=9, frameon=False,
                   title="filled: resolved (disc < err/10)\ngrey open: unresolved")
    fig.suptitle("2D members, class (%s) px$^2$, degrees" % args.cov.replace(",", ", "))
    fig.tight_layout()
    save_fig(fig, os.path.join(args.out, "clt_convergence_2d.png"), 120)


if __name__ == "__main__":
    main()
