#!/usr/bin/env python3
"""Accuracy of icshadow's K and E next to scipy's (Cephes) on the same inputs, against mpmath.

Draws deterministic inputs in four regions (m uniform in [0, 1); m1 = 1 - m log-uniform in
[1e-300, 1e-2]; m1 log-uniform in [1e-15, 1e-2] where 1 - m1 is still exact enough for scipy's
m entry point; m = -10^u, u uniform in [-3, 6]), evaluates icshadow through `icshadow eval` and
scipy.special (ellipk, ellipkm1, ellipe), and measures the error in ulps against mpmath at 60
digits (plus as many as 1 - m1 needs). scipy's ellipe has no complementary entry point: near m = 1 it is given m = 1 - m1 as a
double, which is what a user of it can do. Writes CSV to --out (default stdout): region,
function, implementation, samples, max_ulp, worst_input.
"""
import argparse
import csv
import math
import os
import random
import subprocess
import sys

import mpmath
import scipy.special as sc

mpmath.mp.dps = 60


def ulp_err(x, ref):
    if math.isnan(x) or math.isinf(x):
        return math.inf
    if ref == 0:
        return abs(x) / 2.0**-1074
    e = int(mpmath.floor(mpmath.log(abs(ref), 2))) + 1  # |ref| in [2^(e-1), 2^e)
    ulp = mpmath.mpf(2) ** max(e - 53, -1074)
    return float(abs(mpmath.mpf(x) - ref) / ulp)


def cli_eval(cli, func, xs):
    res = subprocess.run([cli, "eval", func], input="".join("%r\n" % x for x in xs),
                         capture_output=True, text=True)
    if res.returncode != 0:
        sys.exit("icshadow eval %s failed: %s" % (func, res.stderr.strip()))
    return [float(v) for v in res.stdout.split()]


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--cli", default="build/bin/icshadow")
    ap.add_argument("--samples", type=int, default=2000)
    ap.add_argument("--out", default="-")
    args = ap.parse_args()
    rnd = random.Random(20261122)
    n = args.samples
    regions = {
        "m uniform [0,1)": ("m", [rnd.random() for _ in range(n)]),
        "m1 log-uniform [1e-300,1e-2]": ("m1", [10 ** rnd.uniform(-300, -2) for _ in range(n)]),
        "m1 log-uniform [1e-15,1e-2]": ("m1", [10 ** rnd.uniform(-15, -2) for _ in range(n)]),
        "m = -10^u, u in [-3,6]": ("m", [-(10 ** rnd.uniform(-3, 6)) for _ in range(n)]),
    }
    rows = []
    for name, (kind, xs) in regions.items():
        if kind == "m":
            ours_k, ours_e = cli_eval(args.cli, "ellipk", xs), cli_eval(args.cli, "ellipe", xs)
            sp_k = [float(sc.ellipk(x)) for x in xs]
            sp_e = [float(sc.ellipe(x)) for x in xs]
        else:
            ours_k, ours_e = cli_eval(args.cli, "ellipk_m1", xs), cli_eval(args.cli, "ellipe_m1", xs)
            sp_k = [float(sc.ellipkm1(x)) for x in xs]
            sp_e = [float(sc.ellipe(1.0 - x)) for x in xs]
        ref_k, ref_e = [], []
        for x in xs:  # enough digits that 1 - m1 keeps every bit of m1
            with mpmath.workdps(60 + (int(-math.log10(x)) if kind == "m1" else 0)):
                m = 1 - mpmath.mpf(x) if kind == "m1" else mpmath.mpf(x)
                ref_k.append(+mpmath.ellipk(m))
                ref_e.append(+mpmath.ellipe(m))
        for func, ref, impls in (("K", ref_k, (("icshadow", ours_k), ("scipy", sp_k))),
                                 ("E", ref_e, (("icshadow", ours_e), ("scipy", sp_e)))):
            for impl, vals in impls:
                errs = [ulp_err(v, r) for v, r in zip(vals, ref)]
                i = max(range(n), key=lambda j: errs[j])
                rows.append([name, func, impl, n, "%.3f" % errs[i], float.hex(xs[i])])
    out = sys.stdout if args.out == "-" else open(args.out + ".tmp", "w", newline="")
    w = csv.writer(out)
    w.writerow(["region", "function", "implementation", "samples", "max_ulp", "worst_input"])
    w.writerows(rows)
    if out is not sys.stdout:
        out.close()
        os.replace(args.out + ".tmp", args.out)


if __name__ == "__main__":
    main()
