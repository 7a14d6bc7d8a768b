#!/usr/bin/env python3
"""Reproduce Patel et al. 2013, Table I ("Equivalent Kernels") from the icshadow CLI.

`icshadow kernel-table` builds every 1D member of the class (mean 0, variance sigma^2 =
30.25 px^2, sigma = 5.5 px) with the library and measures its taps: mean, variance (averaged over
10000 iterations for the stochastic Dirac, with its range), width (largest minus smallest tap),
samples (taps), the integer taps the engine applies after splitting off-grid taps for linear
interpolation, the variance that splitting adds per step, and the engine's time per pixel and
step. Next to them: the paper's entries (width sqrt(12) sigma, 2 sigma, 2 sigma +- 2; samples
sqrt(12) sigma, 2, 2) evaluated at sigma = 5.5.
Writes patel_table1.csv (the CLI's CSV as is), patel_table1.md (Markdown) and patel_table1.png into --out.
"""
import argparse
import csv
import io
import math
import os
import subprocess
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

VAR = 30.25
SIG = math.sqrt(VAR)
PAPER = {  # Table I of the paper at sigma = 5.5: (width, samples)
    "tophat": ("sqrt(12) s = %.2f" % (math.sqrt(12) * SIG), "sqrt(12) s = %.2f" % (math.sqrt(12) * SIG)),
    "dirac": ("2 s = %g" % (2 * SIG), "2"),
    "stochastic-dirac": ("2 s +- 2 = %g +- 2" % (2 * SIG), "2"),
}


def run_cli(cli, args):
    res = subprocess.run([cli] + args, capture_output=True, text=True)
    if res.returncode != 0:
        sys.exit("icshadow %s failed (exit %d): %s" % (" ".join(args), res.returncode, res.stderr.strip()))
    return res.stdout


def g(v, digits=6):
    return "%.*g" % (digits, float(v))


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--cli", default="build/bin/icshadow", help="path to the icshadow binary")
    ap.add_argument("--out", default="out/figs", help="output folder")
    args = ap.parse_args()
    os.makedirs(args.out, exist_ok=True)

    text = run_cli(args.cli, ["kernel-table", "--var", repr(VAR), "--iterations", "10000", "--seed", "1"])
    rows = list(csv.DictReader(io.StringIO(text)))
    if [r["member"] for r in rows][:5] != ["dirac", "tophat", "tophat-raw", "stochastic-dirac", "gauss"]:
        sys.exit("patel_table1: unexpected members in the kernel-table output")
    for r in rows:  # the class members must reproduce the class: mean 0, variance sigma^2
        if r["member"] == "tophat-raw":
            continue
        if abs(float(r["mean"])) > 1e-9 or abs(float(r["var"]) / VAR - 1) > (2e-2 if r["member"] == "stochastic-dirac" else 1e-12):
            sys.exit("patel_table1: %s does not have the class moments: mean %s var %s" % (r["member"], r["mean"], r["var"]))

    tmp = os.path.join(args.out, "patel_table1.csv.tmp")
    with open(tmp, "w") as f:
        f.write(text)
    os.replace(tmp, os.path.join(args.out, "patel_table1.csv"))

    header = ["kernel", "mean", "variance", "var range", "width (taps)", "samples", "applied taps",
              "interp. var/step", "ns/px/step", "paper width", "paper samples"]
    body = []
    for r in rows:
        stoch = int(r["iterations"]) > 1
        vr = "%s .. %s" % (g(r["var_min"], 4), g(r["var_max"], 4)) if stoch else "-"
        wd = "%s .. %s" % (g(r["width_min"], 4), g(r["width_max"], 4)) if stoch else g(r["width_min"])
        pw, ps = PAPER.get(r["member"], ("-", "-"))
        body.append([r["member"], g(r["mean"], 3), g(r["var"], 8) + (" (mean of %s)" % r["iterations"] if stoch else ""),
                     vr, wd, r["taps"], r["applied_taps"], g(r["interp_var"], 4), r["ns_per_px_step"], pw, ps])

    md = ["# Table I (Patel et al. 2013) measured: kernel members of the class mean 0, variance %g px^2" % VAR, "",
          "Made by `paper_figs/patel_table1.py` from `icshadow kernel-table --var %g --iterations 10000 --seed 1`." % VAR,
          "tophat-raw (box of width sqrt(12) sigma on the interpolated grid) is not in the class: shown for comparison.",
          "ns/px/step is a timing on this machine (best of repeated runs on a 65536-pixel line).", "",
          "| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    md += ["| " + " | ".join(b) + " |" for b in body]
    tmp = os.path.join(args.out, "patel_table1.md.tmp")
    with open(tmp, "w") as f:
        f.write("\n".join(md) + "\n")
    os.replace(tmp, os.path.join(args.out, "patel_table1.md"))

    fig, ax = plt.subplots(figsize=(15, 2.6))
    ax.axis("off")
    t = ax.table(cellText=body, colLabels=header, loc="center", cellLoc="center")
    t.auto_set_font_size(False)
    t.set_fontsize(8)
    t.auto_set_column_width(list(range(len(header))))
    t.scale(1, 1.5)
    ax.set_title("Patel et al. 2013, Table I measured (icshadow kernel-table): class mean 0, variance %g px$^2$ "
                 "($\\sigma$ = %g px)" % (VAR, SIG), fontsize=10)
    fig.tight_layout()
    tmp = os.path.join(args.out, ".patel_table1.tmp.png")
    fig.savefig(tmp, dpi=120)
    os.replace(tmp, os.path.join(args.out, "patel_table1.png"))
    for b in body:
        print("patel_table1: " + " | ".join(b))
    print("patel_table1: wrote patel_table1.csv, patel_table1.md, patel_table1.png in %s" % args.out)


if __name__ == "__main__":
    main()
