#!/usr/bin/env python3
"""Reproduce Patel et al. 2013, Fig. 16 and Fig. 17 (Sec. 6, Appendix A.3-A.5) from the icshadow CLI.

Fig. 16: shadow behind a Heaviside edge (opaque for x > 0) for a light of mean zero, correct
         (left) and actually iterated (right; tophat member, e = 1/64, d1 = 1), drawn from
         isolines 0.05 .. 0.95; the 1/2-isoline in white.
Fig. 17: isolines 0.1 .. 0.9 of the correct shadow (blue, straight lines) and of the iterated
         shadow (red, square-root curves) for a Gaussian light; they meet at d = d1 (dashed).
Every position comes from `icshadow isoline` (models correct and iterative). As an independent
check, the correct isolines are compared with the closed form x = d sigma Phi^-1(s) of a
Gaussian light (math.erfc bisection here) and the iterated ones with the CLT form
x = Phi^-1(s) sqrt(d d1) sigma; the worst differences are printed.
Writes patel_fig16_isolines.csv, patel_fig16.png, patel_fig17_isolines.csv, patel_fig17.png into --out.
"""
import concurrent.futures
import math
import os
import sys

import numpy as np

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "lib"))
from figutil import parse_args, run_cli, save_fig, write_csv  # noqa: E402


def isoline(cli, light, level, dist, model, d1=None, slab=None, kernel="tophat"):
    cmd = ["isoline", "--light", light, "--level", "%.17g" % level, "--distance", "%.17g" % dist, "--model", model]
    if model != "correct":
        cmd += ["--d1", "%.17g" % d1]
    if model == "iterative":
        cmd += ["--slab", "%.17g" % slab, "--kernel", kernel]
    return float(run_cli(cli, cmd))


def isolines(cli, queries, what):
    """isoline(cli, *q) for every q, on every core (each a short process), with progress on stderr."""
    with concurrent.futures.ThreadPoolExecutor(max_workers=os.cpu_count() or 1) as pool:
        futures = {q: pool.submit(isoline, cli, *q) for q in queries}
        step = max(1, len(futures) // 10)
        for done, _ in enumerate(concurrent.futures.as_completed(futures.values()), 1):
            if done % step == 0 or done == len(futures):
                print("patel_fig16_17: %s: %d of %d isoline points" % (what, done, len(futures)),
                      file=sys.stderr, flush=True)
        return {q: f.result() for q, f in futures.items()}


def phi_inv(p):
    """Phi^-1 by bisection on math.erfc (independent of the library)."""
    lo, hi = -40.0, 40.0
    for _ in range(200):
        m = 0.5 * (lo + hi)
        if 0.5 * math.erfc(-m / math.sqrt(2)) < p:
            lo = m
        else:
            hi = m
    return 0.5 * (lo + hi)


def main():
    args = parse_args(__doc__)
    e = 1.0 / 64

    # ---- Fig. 16: light mean 0, variance 1, d1 = 1
    light, var, d1 = "gauss:0,1", 1.0, 1.0
    levels = [round(0.05 * k, 2) for k in range(1, 20)]
    # fine steps near the occluder, where every isoline leaves x = 0 (at d = 0 the shadow is the
    # occluder's own step: the plots start the lines there)
    dists = [1 / 64, 1 / 32, 1 / 16, 3 / 32] + [k / 8.0 for k in range(1, 33)]
    rows, worst_c, worst_i = [], 0.0, 0.0
    x = isolines(args.cli, [q for s in levels for d in dists
                            for q in ((light, s, d, "correct"), (light, s, d, "iterative", d1, e))],
                 "Fig. 16")
    for s in levels:
        for d in dists:
            xc = x[(light, s, d, "correct")]
            xi = x[(light, s, d, "iterative", d1, e)]
            worst_c = max(worst_c, abs(xc - d * math.sqrt(var) * phi_inv(s)))
            if d >= 1 / 8:  # the CLT form needs steps: 8 or more (one step at d = 1/64)
                worst_i = max(worst_i, abs(xi - phi_inv(s) * math.sqrt(d * d1 * var)) / math.sqrt(d * d1 * var))
            rows.append((s, d, xc, xi))
    print("fig16: correct vs closed form: max |dx| = %.3g; iterated vs CLT form (d >= 1/8): max |dx|/sigma_n = %.3g"
          % (worst_c, worst_i))
    write_csv(os.path.join(args.out, "patel_fig16_isolines.csv"), ["level", "distance", "x_correct", "x_iterative"], rows)
    a = np.array(rows)
    fig, axs = plt.subplots(1, 2, figsize=(10, 4.5), sharey=True)
    for ax, col, title in ((axs[0], 2, "correct shadow (Eq. 16)"), (axs[1], 3, "iterated shadow (tophat, e = 1/64)")):
        # shadow level as a function of (x, d): the isolines sample it densely
        step = np.linspace(-6.0, 6.0, 241)  # d = 0: the occluder's step, 0 for x < 0, 1 for x > 0
        step = step[step != 0]
        pts_x = np.concatenate([a[:, col], [-6.0] * len(dists), [6.0] * len(dists), step])
        pts_d = np.concatenate([a[:, 1], dists, dists, np.zeros_like(step)])
        pts_s = np.concatenate([a[:, 0], [0.0] * len(dists), [1.0] * len(dists), (step > 0) * 1.0])
        # the top level just above 1, so the fully shadowed region (s = 1 exactly) is filled too
        ax.tricontourf(pts_x, pts_d, pts_s, levels=np.append(np.linspace(0, 1, 21)[:-1], 1 + 1e-9),
                       cmap="gray_r")
        for s in levels:
            sel = a[:, 0] == s
            xs, ds = np.concatenate([[0.0], a[sel, col]]), np.concatenate([[0.0], a[sel, 1]])
            if abs(s - 0.5) < 1e-9:
                ax.plot(xs, ds, color="white", lw=2.0)
            elif abs(round(s * 10) - s * 10) < 1e-9:
                ax.plot(xs, ds, color=plt.cm.rainbow(s), lw=1.0)
        ax.set_xlim(-5, 5)
        ax.set_ylim(4, 0)
        ax.set_xlabel("x (edge at 0, occluder opaque for x > 0)")
        ax.set_title(title)
    axs[0].set_ylabel("distance d behind the occluder")
    fig.suptitle("Patel Fig. 16: light mean 0, variance 1, d1 = 1; isolines 0.1..0.9, 1/2 in white")
    fig.tight_layout()
    save_fig(fig, os.path.join(args.out, "patel_fig16.png"), 120)
    plt.close(fig)

    # ---- Fig. 17: Gaussian light, d1 = 2
    light, var, d1 = "gauss:0,1", 1.0, 2.0
    levels = [round(0.1 * k, 1) for k in range(1, 10)]
    rows = []
    x = isolines(args.cli, [q for s in levels for d in dists
                            for q in ((light, s, d, "correct"), (light, s, d, "iterative", d1, e),
                                      (light, s, d, "clt", d1))], "Fig. 17")
    for s in levels:
        for d in dists:
            rows.append((s, d, x[(light, s, d, "correct")], x[(light, s, d, "iterative", d1, e)],
                         x[(light, s, d, "clt", d1)]))
    write_csv(os.path.join(args.out, "patel_fig17_isolines.csv"),
              ["level", "distance", "x_correct", "x_iterative", "x_clt"], rows)
    a = np.array(rows)
    at_d1 = a[a[:, 1] == d1]
    print("fig17: at d = d1 = %g, max |x_iterative - x_correct| = %.3g" % (d1, np.max(np.abs(at_d1[:, 3] - at_d1[:, 2]))))
    fig, ax = plt.subplots(figsize=(6, 5))
    for s in levels:
        sel = a[:, 0] == s
        ds = np.concatenate([[0.0], a[sel, 1]])  # every isoline starts at the edge (d = 0, x = 0)
        ax.plot(np.concatenate([[0.0], a[sel, 2]]), ds, color="tab:blue", lw=1.2,
                label="correct" if s == levels[0] else None)
        ax.plot(np.concatenate([[0.0], a[sel, 3]]), ds, color="tab:red", lw=1.2,
                label="iterated" if s == levels[0] else None)
    ax.axhline(d1, color="k", ls="--", lw=0.8, label="d1 = %g" % d1)
    ax.set_ylim(4, 0)
    ax.set_xlabel("x")
    ax.set_ylabel("distance d")
    ax.set_title("Patel Fig. 17: isolines 0.1..0.9, Gaussian light (var 1)")
    ax.legend(loc="lower left")
    fig.tight_layout()
    save_fig(fig, os.path.join(args.out, "patel_fig17.png"), 120)
    plt.close(fig)


if __name__ == "__main__":
    main()
