#!/usr/bin/env python3
"""How many lights `icshadow fit-light --lights auto` keeps on maps of known lights
(docs/lightfit.md "How many lights"): 24 maps drawn by `icshadow make-env` (512 x 256, default
4 x 4 supersampling), each of n = 1..4 Gaussian lights at random (centres in [-0.7, 0.7]^2 on the
plane and at least 0.35 apart, variances 0.003-0.05 per axis, any angle, weights 0.3-2, colours
0.2-1 per channel); the first 12 without a sky, the other 12 with a sky of (0.02, 0.03, 0.05).
Each map is fitted with `fit-light --lights auto:KMAX` (defaults otherwise: max-samples 32768,
seed 1). Then Fig. 14 case B (paper_figs/lightfit_fig14.py's map: three lights over a dim sky)
with --sweep. The maps depend on --seed only (Python's random.Random), so a run is reproducible;
the fits are deterministic for a given seed.

Writes into --out: lightfit_auto_sweep.csv (one row per map: its lights, the K chosen, K - n,
the L1 of the fit kept, the L1, seconds and EM iterations of every K = 1..KMAX), and
lightfit_auto_sweep.md (the summary tables and case B). Prints them. --ratios: the K - n that
the rule with another ratio than the CLI's 2 would choose from the same fits.

The sky's share of the kept energy is the weight of the one-Gaussian fit of the sky alone (a
map of the sky only) over that plus the lights' luminance powers. With --lib (a shared
libicshadow), also a reference for K = n + j: the L1 of the map's own lights plus the j-Gaussian
fit of the sky alone (j = 1, 2), by ics_lightfit_errors through ctypes: what a fit that finds
every light and fits the sky as well as on its own scores (a joint fit can do slightly better,
its sky components also taking up what the lights' Gaussians miss).

usage: lightfit_auto_sweep.py [--cli build/bin/icshadow] [--lib build/lib/libicshadow.so]
                              [--out out/analysis] [--seed 2023] [--kmax 8] [--maps 12]
                              [--ratios 1.25,1.5]
"""
import argparse
import csv
import ctypes
import json
import os
import random
import re
import subprocess
import sys
import tempfile

SKY = "0.02,0.03,0.05"
SIZE = "512x256"
# paper_figs/lightfit_fig14.py's map (Fig. 14-like lights; the Makefile's DEMO_LIGHTS too)
FIG14 = ("-0.55,0.35,0.08,0.08,0,1,0.2,1,0.2"
         ":0.6,0.3,0.32,0.32,0,2,1,0.2,0.1"
         ":0.05,-0.6,0.3,0.002,-70,1,0.15,0.25,1")


def draw_lights(rng, n):
    """n lights as make-env SPEC fields, centres at least 0.35 apart."""
    lights = []
    while len(lights) < n:
        mx, my = rng.uniform(-0.7, 0.7), rng.uniform(-0.7, 0.7)
        if any((mx - l[0]) ** 2 + (my - l[1]) ** 2 < 0.35 ** 2 for l in lights):
            continue
        lights.append((mx, my, rng.uniform(0.003, 0.05), rng.uniform(0.003, 0.05),
                       rng.uniform(-90, 90), rng.uniform(0.3, 2),
                       rng.uniform(0.2, 1), rng.uniform(0.2, 1), rng.uniform(0.2, 1)))
    return ":".join(",".join("%.4f" % v for v in l) for l in lights)


def run(cmd):
    p = subprocess.run(cmd, capture_output=True, text=True)
    if p.returncode != 0:
        sys.exit("failed (%d): %s\n%s" % (p.returncode, " ".join(cmd), p.stderr))
    return p.stdout, p.stderr


def fit_table(cli, env, lights_arg, out_json, sweep=False):
    """The fit-light CSV table as {k: row dict}, and the auto choice (or None)."""
    cmd = [cli, "fit-light", env, "--lights", lights_arg, "-o", out_json]
    if sweep:
        cmd.append("--sweep")
    out, err = run(cmd)
    rows = {int(r["k"]): r for r in csv.DictReader(out.splitlines())}
    m = re.search(r"--lights auto: K = (\d+),", err)
    return rows, int(m.group(1)) if m else None


class Light(ctypes.Structure):
    _fields_ = [("mean", ctypes.c_double * 2), ("cov", ctypes.c_double * 3),
                ("color", ctypes.c_double * 3), ("weight", ctypes.c_double)]


class Report(ctypes.Structure):  # icshadow/lightfit.h ics_lightfit_report
    _fields_ = [("k_fit", ctypes.c_int), ("iterations", ctypes.c_int), ("samples", ctypes.c_int),
                ("pixels", ctypes.c_int)] + [(f, ctypes.c_double) for f in (
                    "energy_total", "energy_front", "energy_cutoff", "energy_kept", "cutoff_loss",
                    "loglik", "l1", "l2", "edge")] + [("converged", ctypes.c_int)]


class Reference:
    """L1 of given lights against a map, by the library's ics_lightfit_errors (the reference)."""

    def __init__(self, path):
        self.lib = ctypes.CDLL(path)
        self.lib.ics_exr_read.argtypes = [ctypes.c_char_p, ctypes.POINTER(ctypes.c_void_p),
                                          ctypes.c_char_p, ctypes.c_size_t]
        self.lib.ics_image_destroy.argtypes = [ctypes.c_void_p]
        self.lib.ics_lightfit_errors.argtypes = [ctypes.c_void_p, ctypes.c_double,
                                                 ctypes.POINTER(Light), ctypes.c_int,
                                                 ctypes.POINTER(Report)]
        self.lib.ics_light_cov_from_eig.argtypes = [ctypes.c_double] * 3 + [ctypes.c_double * 3]

    def spec_lights(self, spec):
        """make-env SPEC lights as fitted lights (weight = luminance power)."""
        out = []
        for f in spec.split(":"):
            mx, my, vx, vy, ang, w, r, g, b = (float(v) for v in f.split(","))
            cov = (ctypes.c_double * 3)()
            self.lib.ics_light_cov_from_eig(vx, vy, ang, cov)
            out.append(((mx, my), tuple(cov), w * (0.2126 * r + 0.7152 * g + 0.0722 * b)))
        return out

    def l1(self, env, lights):
        img, msg = ctypes.c_void_p(), ctypes.create_string_buffer(512)
        if self.lib.ics_exr_read(env.encode(), ctypes.byref(img), msg, 512):
            sys.exit("cannot read %s: %s" % (env, msg.value.decode()))
        arr = (Light * len(lights))()
        for i, (m, c, w) in enumerate(lights):
            arr[i].mean[:] = m
            arr[i].cov[:] = c
            arr[i].color[:] = (1, 1, 1)
            arr[i].weight = w
        rep = Report()
        st = self.lib.ics_lightfit_errors(img, 80.0, arr, len(lights), ctypes.byref(rep))
        self.lib.ics_image_destroy(img)
        if st:
            sys.exit("ics_lightfit_errors failed (%d)" % st)
        return rep.l1


def sky_gaussians(cli, tmp, k):
    """fit-light's k Gaussians for the sky alone, as (mean, cov, weight)."""
    env, lj = os.path.join(tmp, "sky.exr"), os.path.join(tmp, "sky.json")
    run([cli, "make-env", "--sky", SKY, "--size", SIZE, "-o", env])
    run([cli, "fit-light", env, "--lights", str(k), "-o", lj])
    with open(lj) as f:
        ls = json.load(f)["lights"]
    return [(tuple(l["mean"]), (l["cov"][0][0], l["cov"][0][1], l["cov"][1][1]), l["weight"])
            for l in ls]


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--cli", default="build/bin/icshadow")
    ap.add_argument("--lib", default=None, help="libicshadow.so: also the reference L1")
    ap.add_argument("--out", default="out/analysis")
    ap.add_argument("--seed", type=int, default=2023)
    ap.add_argument("--kmax", type=int, default=8)
    ap.add_argument("--maps", type=int, default=12, help="maps per group (without / with a sky)")
    ap.add_argument("--ratios", default="1.25,1.5",
                    help="also the K - n that the rule 'fewest K with L1 <= max(1 %%, RATIO x the "
                         "best)' would give with these ratios (the CLI's is 2)")
    a = ap.parse_args()
    os.makedirs(a.out, exist_ok=True)
    rng = random.Random(a.seed)
    results = []
    oracle = Reference(a.lib) if a.lib else None
    with tempfile.TemporaryDirectory() as tmp:
        env, lj = os.path.join(tmp, "env.exr"), os.path.join(tmp, "l.json")
        skyg = [[], sky_gaussians(a.cli, tmp, 1), sky_gaussians(a.cli, tmp, 2)]
        sky_kept = skyg[1][0][2]  # the sky's kept energy (the weights add up to it)
        for group, sky in (("no sky", None), ("sky", SKY)):
            for m in range(a.maps):
                n = 1 + m % 4
                spec = draw_lights(rng, n)
                cmd = [a.cli, "make-env", "--lights", spec, "--size", SIZE, "-o", env]
                if sky:
                    cmd += ["--sky", sky]
                run(cmd)
                rows, kc = fit_table(a.cli, env, "auto:%d" % a.kmax, lj)
                l1 = {k: float(r["l1"]) for k, r in rows.items()}
                res = {"group": group, "map": m, "n": n, "k_auto": kc, "k_minus_n": kc - n,
                       "l1_auto": l1[kc], "l1_n": l1.get(n), "l1_n1": l1.get(n + 1),
                       "l1_best": min(l1.values()),
                       "l1": ";".join("%.5g" % l1[k] for k in sorted(l1)),
                       "seconds": ";".join("%.3f" % float(rows[k]["seconds"]) for k in sorted(rows)),
                       "iterations": ";".join(rows[k]["iterations"] for k in sorted(rows)),
                       "spec": spec}
                # the sky's share of the kept energy (the lights' cut-off losses neglected)
                own_w = sum(float(f[5]) * (0.2126 * float(f[6]) + 0.7152 * float(f[7]) +
                                           0.0722 * float(f[8]))
                            for f in (l.split(",") for l in spec.split(":")))
                res["sky_share"] = sky_kept / (sky_kept + own_w) if sky else 0.0
                if oracle:
                    own = oracle.spec_lights(spec)
                    for j in range(3):
                        res["oracle_n%d" % j] = (oracle.l1(env, own + skyg[j]) if sky or j == 0
                                                 else None)
                results.append(res)
                print("%-6s map %2d n=%d: K=%d (K-n=%+d) L1 %.4g; L1 at K = 1..: %s%s"
                      % (group, m, n, kc, kc - n, l1[kc], res["l1"],
                         "; reference at n, n+1, n+2: %s" % ", ".join(
                             "%.4g" % res["oracle_n%d" % j] for j in range(3)
                             if res["oracle_n%d" % j] is not None) if oracle else ""), flush=True)
        run([a.cli, "make-env", "--lights", FIG14, "--sky", SKY, "--size", SIZE, "-o", env])
        fig14, _ = fit_table(a.cli, env, str(a.kmax), lj, sweep=True)

    with open(os.path.join(a.out, "lightfit_auto_sweep.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(results[0].keys()))
        w.writeheader()
        w.writerows(results)
    pct = lambda v: "%.3g" % (100 * v)  # noqa: E731
    lines = ["`%s` (seed %d, KMAX %d)" % (os.path.basename(a.cli), a.seed, a.kmax), "",
             "| maps | K chosen - n | L1 of the fit kept, % |", "|---|---|---|"]
    for group in ("no sky", "sky"):
        rs = [r for r in results if r["group"] == group]
        lines.append("| %d %s | %s | %s – %s |" % (
            len(rs), group, ", ".join("%d" % r["k_minus_n"] for r in rs),
            pct(min(r["l1_auto"] for r in rs)), pct(max(r["l1_auto"] for r in rs))))
    for ratio in [float(v) for v in a.ratios.split(",") if v]:
        lines += ["", "With the ratio %g in place of 2 (from the same fits):" % ratio, ""]
        for group in ("no sky", "sky"):
            ks = []
            for r in (r for r in results if r["group"] == group):
                l1 = [float(v) for v in r["l1"].split(";")]
                lim = max(0.01, ratio * min(l1))
                ks.append(next(k + 1 for k, v in enumerate(l1) if v <= lim) - r["n"])
            lines.append("- %s: K - n = %s" % (group, ", ".join("%d" % k for k in ks)))
    lines += ["", "Sky maps, L1 in % at K = n + 1 and n + 2 (reference: the map's lights plus the 1- "
              "or 2-Gaussian fit of the sky alone):", "",
              "| map | n | sky share, % | K chosen | L1 at n + 1 | reference | L1 at n + 2 | "
              "reference |",
              "|---|---|---|---|---|---|---|---|"]
    for r in results:
        if r["group"] != "sky":
            continue
        l1 = [float(v) for v in r["l1"].split(";")]
        n = r["n"]
        lines.append("| %d | %d | %.3g | %d | %s | %s | %s | %s |" % (
            r["map"], n, 100 * r["sky_share"], r["k_auto"], pct(l1[n]) if n < len(l1) else "",
            pct(r["oracle_n1"]) if oracle else "", pct(l1[n + 1]) if n + 1 < len(l1) else "",
            pct(r["oracle_n2"]) if oracle else ""))
    lines += ["", "Fig. 14 case B (512 x 256, --sweep):", "",
              "| K | L1 | L2 | edge | s | EM iterations |", "|---|---|---|---|---|---|"]
    for k in sorted(fig14):
        r = fig14[k]
        lines.append("| %d | %.3g | %.3g | %.2g | %.2f | %s |" % (
            k, float(r["l1"]), float(r["l2"]), float(r["edge"]), float(r["seconds"]), r["iterations"]))
    text = "\n".join(lines) + "\n"
    with open(os.path.join(a.out, "lightfit_auto_sweep.md"), "w") as f:
        f.write(text)
    print(text)


if __name__ == "__main__":
    main()
