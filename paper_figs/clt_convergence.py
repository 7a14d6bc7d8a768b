#!/usr/bin/env python3
"""CLT convergence of the actually iterated kappa^{*n} * H per kernel member (docs/theory.md).

Runs `icshadow clt --kernel K --var 36 --steps 4,8,...,1024` for dirac, tophat,
stochastic-dirac, gauss and skew, and plots the sup error against n (with the n^-1/2 and n^-1
reference slopes and the discretisation estimate dotted) and against the cost (taps x steps).
As an independent check, the printed Dirac errors are compared with the lattice staircase
phi(0) (2 sigma - 1) / (2 sigma sqrt n) derived in docs/theory.md.
Writes clt_convergence.csv and clt_convergence.png into --out.
"""
import argparse
import csv
import io
import math
import os
import subprocess
import sys

import numpy as np

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

KERNELS = ["dirac", "tophat", "stochastic-dirac", "gauss", "skew"]


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--cli", default="build/bin/icshadow", help="path to the icshadow binary")
    ap.add_argument("--out", default="out/figs", help="output folder")
    ap.add_argument("--var", type=float, default=36.0, help="class variance per step, px^2")
    args = ap.parse_args()
    os.makedirs(args.out, exist_ok=True)
    steps = [2 ** k for k in range(2, 11)]
    data = {}
    for k in KERNELS:
        cmd = [args.cli, "clt", "--kernel", k, "--var", "%.17g" % args.var, "--steps", ",".join(map(str, steps))]
        res = subprocess.run(cmd, capture_output=True, text=True)
        if res.returncode != 0:
            sys.exit("icshadow clt failed (%s): %s" % (" ".join(cmd), res.stderr.strip()))
        rows = list(csv.DictReader(io.StringIO(res.stdout)))
        data[k] = {c: np.array([float(r[c]) for r in rows]) for c in rows[0]}
    sigma = math.sqrt(args.var)
    if abs(sigma - round(sigma)) < 1e-12:
        pred = (2 * sigma - 1) / (2 * sigma) / math.sqrt(2 * math.pi) / np.sqrt(data["dirac"]["steps"])
        print("dirac vs lattice staircase: max relative difference (n >= 64) %.3g"
              % np.max(np.abs(data["dirac"]["sup_error"] / pred - 1)[data["dirac"]["steps"] >= 64]))
    tmp = os.path.join(args.out, "clt_convergence.csv.tmp")
    with open(tmp, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["kernel", "steps", "sup_error", "disc_error", "taps_x_steps", "seconds"])
        for k in KERNELS:
            d = data[k]
            for i in range(len(d["steps"])):
                w.writerow([k, int(d["steps"][i])] + ["%.17g" % d[c][i] for c in
                                                       ("sup_error", "disc_error", "taps_x_steps", "seconds")])
    os.replace(tmp, os.path.join(args.out, "clt_convergence.csv"))

    fig, axs = plt.subplots(1, 2, figsize=(11, 4.5))
    for k in KERNELS:
        d = data[k]
        line, = axs[0].loglog(d["steps"], d["sup_error"], "o-", label=k)
        axs[0].loglog(d["steps"], d["disc_error"], ":", color=line.get_color(), lw=0.8)
        axs[1].loglog(d["taps_x_steps"], d["sup_error"], "o-", color=line.get_color(), label=k)
    n = np.array(steps, float)
    axs[0].loglog(n, 0.3 / np.sqrt(n), "k--", lw=0.7, label="n^-1/2")
    axs[0].loglog(n, 0.03 / n, "k-.", lw=0.7, label="n^-1")
    axs[0].set_xlabel("steps n")
    axs[0].set_ylabel("sup |kappa^{*n} * H - Gaussian cdf|")
    axs[0].set_title("error vs n (dotted: discretisation estimate)")
    axs[0].legend(fontsize=8)
    axs[1].set_xlabel("cost: applied taps x steps")
    axs[1].set_ylabel("sup error")
    axs[1].set_title("error vs cost")
    fig.suptitle("CLT convergence per kernel member, class variance %g px^2 per step" % args.var)
    fig.tight_layout()
    fig.savefig(os.path.join(args.out, "clt_convergence.png"), dpi=120)
    plt.close(fig)


if __name__ == "__main__":
    main()
