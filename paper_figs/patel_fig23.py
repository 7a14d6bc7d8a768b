#!/usr/bin/env python3
"""Reproduce Patel et al. 2013, Fig. 23 (Appendix A.7) from the icshadow CLI.

Left:   var_x(b), the x-variance of points uniform in arc length on the ellipse with radii (1, b).
Middle: V_x(t) (green) and V_y(t) (red) of the unit ellipse with radii (1 - t, t).
Right:  the map ratio V_y/V_x -> t (ratioToab).
Every curve comes from `icshadow eval`; markers on the left panel are an independent check by
periodic trapezoid quadrature of the arc-length density (numpy), so a wrong convention shows.
Writes patel_fig23_varx.csv, patel_fig23_vxvy.csv, patel_fig23_ratio_to_t.csv and patel_fig23.png into --out.
"""
import os
import sys

import numpy as np

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "lib"))
from figutil import parse_args, run_cli, save_fig, write_csv  # noqa: E402


def cli_eval(cli, func, xs):
    """Evaluate FUNC on xs through `icshadow eval` (one number per line in and out)."""
    text = "".join("%.17g\n" % x for x in xs)
    return np.array([float(v) for v in run_cli(cli, ["eval", func], stdin_text=text).split()])


def varx_quadrature(b, n=4096):
    """x-variance of the arc-length-uniform distribution on (cos th, b sin th): trapezoid rule."""
    th = (np.arange(n) + 0.5) * (2 * np.pi / n)
    ds = np.sqrt(np.sin(th) ** 2 + (b * np.cos(th)) ** 2)
    return float(np.sum(np.cos(th) ** 2 * ds) / np.sum(ds))


def main():
    args = parse_args(__doc__)

    b = np.linspace(0.0, 4.0, 401)
    varx = cli_eval(args.cli, "varx", b)
    bq = np.linspace(0.05, 4.0, 17)
    varx_q = np.array([varx_quadrature(x) for x in bq])
    varx_at_bq = cli_eval(args.cli, "varx", bq)
    worst = float(np.max(np.abs(varx_at_bq - varx_q) / varx_q))
    print("fig23: var_x(b) vs independent quadrature, max relative difference %.3g" % worst)
    if worst > 1e-9:
        sys.exit("fig23: var_x disagrees with quadrature (%.3g): wrong convention?" % worst)

    t = np.linspace(0.0, 1.0, 401)
    vx = cli_eval(args.cli, "vx", t)
    vy = cli_eval(args.cli, "vy", t)

    rat = np.logspace(-4, 4, 401)
    t_of_rat = cli_eval(args.cli, "ratio_to_t", rat)

    write_csv(os.path.join(args.out, "patel_fig23_varx.csv"), ["b", "varx"], zip(b, varx))
    write_csv(os.path.join(args.out, "patel_fig23_vxvy.csv"), ["t", "Vx", "Vy"], zip(t, vx, vy))
    write_csv(os.path.join(args.out, "patel_fig23_ratio_to_t.csv"), ["ratio", "t"], zip(rat, t_of_rat))

    fig, ax = plt.subplots(1, 3, figsize=(12, 3.6))
    ax[0].plot(b, varx, "b-", label="icshadow varx")
    ax[0].plot(bq, varx_q, "ko", ms=3, label="quadrature")
    ax[0].set_xlabel("b  (x-radius 1)")
    ax[0].set_ylabel("var_x(b)")
    ax[0].legend()
    ax[1].plot(t, vx, "g-", label="V_x(t)")
    ax[1].plot(t, vy, "r-", label="V_y(t)")
    ax[1].set_xlabel("t  (radii 1 - t, t)")
    ax[1].legend()
    ax[2].semilogx(rat, t_of_rat, "b-")
    ax[2].set_xlabel("V_y / V_x")
    ax[2].set_ylabel("t = ratioToab")
    for a in ax:
        a.grid(alpha=0.3)
    fig.suptitle("Patel et al. 2013, Fig. 23 (reproduced by icshadow eval)")
    fig.tight_layout()
    png = os.path.join(args.out, "patel_fig23.png")
    save_fig(fig, png, 110)
    print("fig23: wrote %s and 3 CSV files" % png)


if __name__ == "__main__":
    main()
