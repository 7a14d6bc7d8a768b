#!/usr/bin/env python3
"""error_vs_time.py — error against run time for the slab renderer's configurations and for the
Monte-Carlo reference itself, on one scene (default: the embedded default scene).

Method (docs/results.md "Error against run time"):
1. A reference: `icshadow render SCENE --backend mc --spp REF_SPP --seed 1001 --aov stderr`
   (written once, reused when present). Its own noise (RMS standard error of R, G, B) is
   reported; every comparison states `rmse_beyond_noise` = sqrt(max(rmse^2 - noise^2, 0)),
   the render's error with the reference's noise taken out (E[rmse^2] = error^2 + noise^2).
2. The configurations (kernel member, samples, compensation, slab spacing, preintegration,
   rotation runs, d1) and Monte-Carlo renders at 4..256 samples per pixel under another seed, each
   run REPS times in an interleaved order (configuration by configuration, round by round) so
   load drifts spread over all of them; `icshadow render ... --compare REF.exr` gives the error,
   the summary the time. Time is ms_plan + ms_render (the frame: plan with its geometry pass,
   then the render) for the slab renderer and ms_render for Monte Carlo (it uses no plan).
3. CSV (method, parameters, ms median / min / max, rmse, rmse_beyond_noise, max_error, psnr) and
   a log-log plot of error against time with the Pareto front marked.

Python is only the driver and the plot; all numbers come from the C tool.
"""
import argparse
import csv
import json
import math
import os
import statistics
import subprocess
import sys
import tempfile


def run(cmd):
    p = subprocess.run(cmd, capture_output=True, text=True)
    if p.returncode != 0:
        sys.exit(f"error_vs_time: {' '.join(cmd)} failed ({p.returncode}): {p.stderr.strip()}")
    return json.loads(p.stdout)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--icshadow", default="build/bin/icshadow")
    ap.add_argument("--scene", default=None, help="scene file (default: the embedded default scene)")
    ap.add_argument("--ref", default="out/error_vs_time_ref.exr", help="reference EXR (made if absent)")
    ap.add_argument("--ref-spp", type=int, default=1024)
    ap.add_argument("--reps", type=int, default=3)
    ap.add_argument("--csv", default="out/error_vs_time.csv")
    ap.add_argument("--plot", default="out/error_vs_time.png")
    ap.add_argument("--images", help="PNG: the default configuration, the reference, the difference")
    ap.add_argument("--quick", action="store_true", help="fewer configurations (a smoke run)")
    ap.add_argument("--replot", action="store_true", help="only redraw the plot from --csv")
    a = ap.parse_args()
    if a.replot:
        return replot(a)
    ics = a.icshadow
    os.makedirs(os.path.dirname(a.csv) or ".", exist_ok=True)
    tmp = tempfile.mkdtemp(prefix="evt")
    scene_text = subprocess.run([ics, "plan", "--print-scene"] if a.scene is None else ["cat", a.scene],
                                capture_output=True, text=True, check=True).stdout
    base = json.loads(scene_text)

    def scene_with(**render):
        s = json.loads(json.dumps(base))
        s["render"].update(render)
        path = os.path.join(tmp, "scene_%d.json" % abs(hash(json.dumps(render, sort_keys=True))))
        with open(path, "w") as f:
            json.dump(s, f)
        return path

    ref_png = os.path.splitext(a.ref)[0] + ".png"
    if not os.path.exists(a.ref):
        print(f"reference: mc, {a.ref_spp} spp -> {a.ref}", file=sys.stderr, flush=True)
        run([ics, "render", scene_with(), "--backend", "mc", "--spp", str(a.ref_spp), "--seed", "1001",
             "--aov", "stderr", "-o", a.ref, "--png", ref_png])
    e0 = base["render"]["slab_spacing"]
    configs = []  # (method, parameters, scene, extra args)
    members = [("ellipse", 2, "expected"), ("ellipse", 3, "expected"), ("poisson", 8, "expected"),
               ("poisson", 16, "expected"), ("gauss", 19, "nonneg"), ("gauss", 19, "signed"),
               ("tophat", 5, "nonneg"), ("ellipse", 2, "signed"), ("ellipse", 2, "integer")]
    if a.quick:
        members = members[:1] + members[4:5]
    for k, n, comp in members:
        configs.append(("slab", f"{k}{n} {comp} e={e0:g}", scene_with(),
                        ["--kernel", k, "--samples", str(n), "--compensate", comp]))
    if not a.quick:
        configs.append(("slab", f"ellipse2 expected e={e0:g} run16", scene_with(rotation_run=16), []))
        for f in (0.5, 2, 4):
            for pre in (False, True):
                configs.append(("slab", f"ellipse2 expected e={e0 * f:g}{' preint' if pre else ''}",
                                scene_with(slab_spacing=e0 * f, preintegrate=pre), []))
        configs.append(("slab", f"ellipse2 expected e={e0:g} preint", scene_with(preintegrate=True), []))
        d10 = base["render"]["d1"]
        for f in (0.25, 0.5, 2):
            configs.append(("slab", f"ellipse2 expected e={e0:g} d1={d10 * f:g}", scene_with(d1=d10 * f), []))
    for spp in ([4, 16] if a.quick else [4, 16, 64, 256]):
        configs.append(("mc", f"{spp} spp", scene_with(), ["--backend", "mc", "--spp", str(spp), "--seed", "7"]))
    times = {i: [] for i in range(len(configs))}
    result = {}
    for r in range(a.reps):
        for i, (method, params, scene, extra) in enumerate(configs):
            print(f"round {r + 1}/{a.reps}: {method} {params}", file=sys.stderr, flush=True)
            s = run([ics, "render", scene, "--compare", a.ref, "--png", os.path.join(tmp, "x.png")] + extra)
            ms = s["ms_render"] + (0 if method == "mc" else s["ms_plan"])
            times[i].append(ms)
            result[i] = s["compare"]
    ref_info = result[0]
    rows = []
    for i, (method, params, _, _) in enumerate(configs):
        c = result[i]
        t = times[i]
        rows.append({"method": method, "parameters": params, "ms": statistics.median(t), "ms_min": min(t),
                     "ms_max": max(t), "rmse": c["rmse"], "rmse_beyond_noise": c["rmse_beyond_noise"],
                     "max_error": c["max_error"], "psnr_db": c["psnr_db"],
                     "reference_spp": c.get("reference_spp"), "reference_noise": c["reference_noise"]})
    with open(a.csv, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        w.writeheader()
        for row in rows:
            w.writerow({k: (f"{v:.6g}" if isinstance(v, float) else v) for k, v in row.items()})
    print(f"reference: {a.ref}, {ref_info.get('reference_spp')} spp, noise {ref_info['reference_noise']:.3g}, "
          f"{ref_info['ms_reference']:.0f} ms")
    plot(rows, ref_info.get("reference_spp"), ref_info["reference_noise"], a.reps, a.plot)
    if a.images and os.path.exists(ref_png):
        slab_png, diff_png = os.path.join(tmp, "slab.png"), os.path.join(tmp, "diff.png")
        c = run([ics, "render", scene_with(), "--compare", a.ref, "--png", slab_png, "--diff-png", diff_png])
        images(slab_png, ref_png, diff_png, c["compare"], a.images)


def images(slab_png, ref_png, diff_png, c, path):
    """The default configuration, the reference and their difference side by side."""
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        import matplotlib.image as mpimg
    except ImportError:
        print("error_vs_time: matplotlib not installed: no images", file=sys.stderr)
        return
    fig, ax = plt.subplots(1, 3, figsize=(12, 3.4))
    titles = ("slab renderer (ellipse2, defaults)", "Monte-Carlo reference (%s spp)" % c.get("reference_spp"),
              "render - reference, x4 (red brighter, blue darker)")
    for k, (png, t) in enumerate(zip((slab_png, ref_png, diff_png), titles)):
        ax[k].imshow(mpimg.imread(png))
        ax[k].set_title(t, fontsize=9)
        ax[k].axis("off")
    x, y = c["max_at"]
    ax[2].plot([x], [y], "o", mfc="none", mec="yellow", ms=10)
    fig.suptitle("RMSE %.4f (%.4f beyond the reference's noise %.4f), max error %.2f at (%d, %d) (circled)"
                 % (c["rmse"], c["rmse_beyond_noise"], c["reference_noise"], c["max_error"], x, y), fontsize=9)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    print(f"images: {path}")


def plot(rows, ref_spp, ref_noise, reps, path):
    """The Pareto front (no other row at once faster and more accurate) and error against time."""
    for row in rows:
        row["pareto"] = not any(o["ms"] < row["ms"] and o["rmse_beyond_noise"] < row["rmse_beyond_noise"]
                                for o in rows if o is not row)
    for row in rows:
        print(f"{row['method']:4s} {row['parameters']:34s} {row['ms']:9.1f} ms [{row['ms_min']:.0f}, "
              f"{row['ms_max']:.0f}]  rmse {row['rmse']:.4g}  beyond noise {row['rmse_beyond_noise']:.4g}  "
              f"max {row['max_error']:.3g}{'  pareto' if row['pareto'] else ''}")
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("error_vs_time: matplotlib not installed: no plot", file=sys.stderr)
        return
    e0 = min(float(r["parameters"].split("e=")[1].split()[0]) for r in rows if "e=" in r["parameters"]
             and "d1=" in r["parameters"])
    fams = {}
    for r in rows:
        p = r["parameters"]
        if r["method"] == "mc":
            f = "Monte Carlo, samples per pixel"
        elif "d1=" in p:
            f = "ellipse2, d1"
        elif "preint" in p or float(p.split("e=")[1].split()[0]) != e0:
            f = "ellipse2, slab spacing e (preint: preintegrated)"
        else:
            f = "kernel member / compensation (e = %g)" % e0
        fams.setdefault(f, []).append(r)
    style = {"Monte Carlo": ("s", "tab:red"), "ellipse2, d1": ("^", "tab:orange"),
             "ellipse2, slab": ("D", "tab:green"), "kernel": ("o", "tab:blue")}
    fig, (ax, side) = plt.subplots(1, 2, figsize=(11, 5.5), gridspec_kw={"width_ratios": [3, 1.15]})
    y = lambda r: max(r["rmse_beyond_noise"], 1e-5)
    keys, n = [], 0
    for f, pts in fams.items():
        marker, colour = next(v for k, v in style.items() if f.startswith(k))
        ax.scatter([r["ms"] for r in pts], [y(r) for r in pts], marker=marker, color=colour, label=f,
                   zorder=3, s=28)
        for r in pts:
            # Monte Carlo by its sample count; every slab configuration by a number keyed at the side
            if r["method"] == "mc":
                label = r["parameters"]
            else:
                n += 1
                label = str(n)
                keys.append((n, r["parameters"].replace(" expected", ""), colour))
            ax.annotate(label, (r["ms"], y(r)), fontsize=7, xytext=(4, 3), textcoords="offset points")
    front = sorted((r for r in rows if r["pareto"]), key=lambda r: r["ms"])
    ax.plot([r["ms"] for r in front], [y(r) for r in front], "k--", lw=1, label="Pareto front", zorder=2)
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("time per frame, ms (median of %d; 2-core VM)" % reps)
    ax.set_ylabel("RMSE against the reference, its noise removed")
    ax.set_title("Default scene: error against run time (reference: Monte Carlo, %s spp, noise %.2g)"
                 % (ref_spp, ref_noise), fontsize=10)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7.5, loc="lower left")
    side.axis("off")
    for k, (num, text, colour) in enumerate(keys):
        side.text(0, 1 - k / max(len(keys), 22), f"{num:2d}  {text}", fontsize=7.5, color=colour,
                  family="monospace", va="top", transform=side.transAxes)
    fig.tight_layout()
    fig.savefig(path, dpi=130)
    print(f"plot: {path}")


def replot(a):
    with open(a.csv) as f:
        rows = list(csv.DictReader(f))
    for r in rows:
        for k in ("ms", "ms_min", "ms_max", "rmse", "rmse_beyond_noise", "max_error", "psnr_db"):
            r[k] = float(r[k])
    meta = rows[0]
    plot(rows, meta.get("reference_spp", "?"), float(meta.get("reference_noise", "nan")), a.reps, a.plot)


if __name__ == "__main__":
    main()
