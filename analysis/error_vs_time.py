#!/usr/bin/env python3
"""error_vs_time.py — error against run time for the slab renderer's configurations and for the
Monte-Carlo reference itself, on one scene (default: the embedded default scene).

Method (docs/results.md "Error against run time"):
1. References: the Monte-Carlo reference (`icshadow.render(SCENE, backend="mc", spp=REF_SPP,
   seed=1001, aovs=["stderr"])`, written with `write_exr`), one per resolution swept (written once with what they were made from beside them, REF.exr.json;
   reused when that matches, refused when not; `--refs-only` makes them and stops).
   Their own noise (RMS standard error of R, G, B) is reported; every comparison states
   `rmse_beyond_noise` = sqrt(max(rmse^2 - noise^2, 0)), the render's error with the reference's
   noise taken out (E[rmse^2] = error^2 + noise^2).
2. Tasks, in a fixed order (the `task` column): the configurations (kernel member, samples,
   compensation, slab spacing with and without preintegration, rotation runs, d1, LUT radii
   against exact ones, render.model surface at three slab spacings and blocker at five, resolution) and Monte-Carlo
   renders at 4..256 samples per pixel under the
   seed 7 + task, each run REPS times in an interleaved order (task by task, round by round) so
   load drifts spread over all of them; a frame on the sweep's `icshadow.Renderer` for the
   backend (one for the slab renderer's tasks, one per Monte-Carlo sample count, kept across the
   sweep as an application keeps its renderer; a slab task's timed frame follows an untimed
   frame of the same task, so that it takes no fresh memory) renders the configuration as
   overrides of the scene's render settings, and
   `icshadow.compare(render, REF.exr)` gives the error, the render's summary the time. Time is ms_plan + ms_render (the frame: plan with its geometry pass,
   then the render) for the slab renderer and ms_render for Monte Carlo (it uses no plan).
3. CSV (task, method, parameters, resolution, ms median / min / max, rmse, rmse_beyond_noise,
   max_error, psnr, the reference's samples and noise, n_tasks) and a log-log plot of error
   against time with the Pareto front marked.
4. Shards: `--shard i/N` runs the tasks k with k mod N = i (seeds depend on k only, so a task's
   result does not depend on N) and writes their rows; `--merge A.csv B.csv ... --csv OUT`
   joins shards and refuses a missing or duplicated task or shards of different sweeps.
   `--no-times` leaves the time columns out: what is left is a function of the inputs alone, so
   merged shards equal the unsharded run byte for byte (tests/analysis.cmake checks that).

Python is only the driver and the plot; all numbers come from the C libraries, through the
icshadow Python package (docs/python.md; `make python` installs it into build/python-pkg, and
`make error-vs-time` puts it on PYTHONPATH).
Exit status: 0 done, 1 a render failed, 2 bad arguments or shards that do not merge.
"""
import argparse
import csv
import hashlib
import json
import os
import shutil
import statistics
import sys
import tempfile

import numpy as np

try:
    import icshadow
except ImportError as e:
    sys.exit(f"error_vs_time: cannot import the icshadow package ({e}): `make python` installs it "
             "into build/python-pkg; run with PYTHONPATH=build/python-pkg (docs/python.md)")

TIME_COLUMNS = ("ms", "ms_min", "ms_max")


REF_TIME_S = 14400  # the references' hard stop, seconds


def die(msg, code=2):
    print(f"error_vs_time: {msg}", file=sys.stderr)
    sys.exit(code)


def render(what, **kw):
    """icshadow.render(**kw); a failure ends the run (exit 1) with the library's message."""
    try:
        return icshadow.render(**kw)
    except (icshadow.Error, MemoryError) as e:
        die(f"{what}: {e}", 1)


def shard_spec(text):
    try:
        i, n = (int(v) for v in text.split("/"))
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r}: expected I/N, e.g. 0/3")
    if n < 1 or not 0 <= i < n:
        raise argparse.ArgumentTypeError(f"{text!r}: need N >= 1 and 0 <= I < N")
    return i, n


def resolution_spec(text):
    try:
        w, h = (int(v) for v in text.split("x"))
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r}: expected WxH, e.g. 320x240")
    if not (1 <= w <= 16384 and 1 <= h <= 16384):
        raise argparse.ArgumentTypeError(f"{text!r}: sides in 1..16384")
    return f"{w}x{h}"


def resolutions_spec(text):
    return ",".join(resolution_spec(r) for r in text.split(",") if r)


def write_csv(path, rows, fields):
    """Atomically: a temporary file beside the target, renamed over it when complete."""
    d = os.path.dirname(os.path.abspath(path))
    fd, tmp = tempfile.mkstemp(prefix=".evt", suffix=".csv", dir=d)
    try:
        with os.fdopen(fd, "w", newline="") as f:
            w = csv.DictWriter(f, fieldnames=fields, lineterminator="\n")
            w.writeheader()
            for row in rows:
                w.writerow({k: (f"{row[k]:.6g}" if isinstance(row[k], float) else row[k]) for k in fields})
        os.replace(tmp, path)
    except BaseException:
        os.unlink(tmp)
        raise


def merge(a):
    rows, fields, n_tasks, sweep = {}, None, None, None
    for path in a.merge:
        try:
            with open(path, newline="") as f:
                r = csv.DictReader(f)
                got = list(r)
                fs = r.fieldnames
        except OSError as e:
            die(f"--merge: {path}: {e.strerror}")
        if not fs or not {"task", "n_tasks", "sweep"} <= set(fs):
            die(f"--merge: {path} is not a sweep's CSV (no task / n_tasks / sweep columns)")
        if fields is not None and fs != fields:
            die(f"--merge: {path} has other columns than {a.merge[0]}")
        fields = fs
        for row in got:
            k, n = int(row["task"]), int(row["n_tasks"])
            if n_tasks is not None and (n != n_tasks or row["sweep"] != sweep):
                die(f"--merge: {path}: task {k} is from another sweep (sweep {row['sweep']}, {n} tasks; "
                    f"the others: sweep {sweep}, {n_tasks} tasks)")
            n_tasks, sweep = n, row["sweep"]
            if k in rows:
                die(f"--merge: task {k} is in two shards ({rows[k][1]} and {path})")
            rows[k] = (row, path)
    if n_tasks is None:
        die("--merge: no rows")
    missing = [k for k in range(n_tasks) if k not in rows]
    if missing:
        die(f"--merge: {len(missing)} of {n_tasks} tasks missing: {', '.join(map(str, missing[:20]))}")
    write_csv(a.csv, [rows[k][0] for k in range(n_tasks)], fields)
    print(f"merged {len(a.merge)} shards, {n_tasks} tasks -> {a.csv}", file=sys.stderr)
    if a.plot and "ms" in fields:
        replot(a)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--scene", default=None, help="scene file (default: the embedded default scene)")
    ap.add_argument("--ref", default="out/error_vs_time_ref.exr",
                    help="reference EXR (made if absent); other resolutions: REF_WxH.exr")
    ap.add_argument("--ref-spp", type=int, default=1024)
    ap.add_argument("--resolution", type=resolution_spec, help="WxH for every task (default: the scene's)")
    ap.add_argument("--resolutions", type=resolutions_spec, default=None,
                    help="WxH,... swept with ellipse2 (default: half and twice the scene's)")
    ap.add_argument("--reps", type=int, default=3)
    ap.add_argument("--csv", default="out/error_vs_time.csv")
    ap.add_argument("--plot", default=None)
    ap.add_argument("--images", help="PNG: the default configuration, the reference, the difference")
    ap.add_argument("--quick", action="store_true", help="fewer configurations (a smoke run)")
    ap.add_argument("--shard", type=shard_spec, help="I/N: run the tasks k with k mod N = I")
    ap.add_argument("--merge", nargs="+", metavar="CSV", help="join shards' CSVs into --csv")
    ap.add_argument("--no-times", action="store_true", help="leave the time columns out")
    ap.add_argument("--refs-only", action="store_true", help="make the references and stop")
    ap.add_argument("--replot", action="store_true", help="only redraw the plot from --csv")
    a = ap.parse_args()
    if a.reps < 1 or a.ref_spp < 2:
        die("--reps must be >= 1 and --ref-spp >= 2")
    if a.replot:
        return replot(a)
    if a.merge:
        return merge(a)
    os.makedirs(os.path.dirname(os.path.abspath(a.csv)), exist_ok=True)
    tmp = tempfile.mkdtemp(prefix="evt")
    if a.scene is None:
        # the default scene at Patel's spacing, the table's baseline since issue 26 (it ships with
        # 0.045 under render.model auto); each task names its model and spacing (run_task: patel
        # at e0 unless it says)
        base = icshadow.default_scene()
        shipped_e = base["render"]["slab_spacing"]
        base["render"]["slab_spacing"] = 0.015
        base["render"].pop("model")
    else:
        try:
            with open(a.scene) as f:
                base = json.load(f)
        except (OSError, ValueError) as e:
            die(f"--scene: {a.scene}: {e}")
        shipped_e = base["render"]["slab_spacing"]
    if a.resolution:
        base["camera"]["resolution"] = [int(v) for v in a.resolution.split("x")]
    W0, H0 = base["camera"]["resolution"]
    res0 = f"{W0}x{H0}"
    if a.resolutions is None:
        a.resolutions = "" if a.quick else f"{W0 // 2}x{H0 // 2},{2 * W0}x{2 * H0}"
    resolutions = [r for r in a.resolutions.split(",") if r and r != res0]

    def scene_with(res=res0):
        """the scene at res, as rendered (what a reference records it was made from)"""
        s = json.loads(json.dumps(base))
        s["camera"]["resolution"] = [int(v) for v in res.split("x")]
        return s

    renderers = {}  # its options: a Renderer kept across the sweep, as an application keeps one

    def run_task(res, overrides, what):
        """a render of the scene (its file, so that its own files resolve, or the default) at res
        with the overrides of its render settings (backend, spp, time, noise: the renderer's own
        options), a frame on the sweep's renderer for those options"""
        kw = {"model": "patel", "slab_spacing": e0, **overrides}
        opts = {k: kw.pop(k) for k in ("backend", "spp", "time", "noise") if k in kw}
        key = tuple(sorted(opts.items()))
        try:
            if key not in renderers:
                renderers[key] = icshadow.Renderer(**opts)
            return renderers[key].render(scene=a.scene, resolution=tuple(int(v) for v in res.split("x")),
                                         **kw)
        except (icshadow.Error, MemoryError) as e:
            die(f"{what}: {e}", 1)

    def ref_path(res):
        return a.ref if res == res0 else os.path.splitext(a.ref)[0] + f"_{res}.exr"

    e0, d10 = base["render"]["slab_spacing"], base["render"]["d1"]
    tasks = []  # (method, parameters, resolution, overrides)
    members = [("ellipse", 2, "expected"), ("ellipse", 3, "expected"), ("poisson", 8, "expected"),
               ("poisson", 16, "expected"), ("gauss", 19, "nonneg"), ("gauss", 19, "signed"),
               ("tophat", 5, "nonneg"), ("ellipse", 2, "signed"), ("ellipse", 2, "integer")]
    if a.quick:
        members = members[:1] + members[4:5]
    for k, n, comp in members:
        tasks.append(("slab", f"{k}{n} {comp} e={e0:g}", res0,
                      {"kernel": k, "samples": n, "compensate": comp}))
    if not a.quick:
        tasks.append(("slab", f"ellipse2 expected e={e0:g} run16", res0, {"rotation_run": 16}))
        for f in (0.5, 2, 3, 4):
            for pre in (False, True):
                tasks.append(("slab", f"ellipse2 expected e={e0 * f:g}{' preint' if pre else ''}", res0,
                              {"slab_spacing": e0 * f, "preintegrate": pre}))
        tasks.append(("slab", f"ellipse2 expected e={e0:g} preint", res0, {"preintegrate": True}))
        for f in (0.25, 0.5, 2):
            tasks.append(("slab", f"ellipse2 expected e={e0:g} d1={d10 * f:g}", res0, {"d1": d10 * f}))
        tasks.append(("slab", f"ellipse2 expected e={e0:g} lut", res0, {"radii": "lut"}))
        # the other model (render.model surface: solid objects, a solid's own term), at three
        # slab spacings
        for f in (0.5, 1, 2):
            tasks.append(("slab", f"ellipse2 expected e={e0 * f:g} model surface", res0,
                          {"slab_spacing": e0 * f, "model": "surface"}))
        # render.model blocker (+ blocker-aware penumbrae), at five slab spacings (the issue's
        # "<= 0.015 at <= 1.3 x Patel's frame" lies between 2 and 4)
        for f in (1, 2, 7 / 3, 3, 4):
            tasks.append(("slab", f"ellipse2 expected e={e0 * f:g} model blocker", res0,
                          {"slab_spacing": e0 * f, "model": "blocker"}))
    for res in resolutions:
        tasks.append(("slab", f"ellipse2 expected e={e0:g} {res}", res, {}))
    for spp in ([4, 16] if a.quick else [4, 16, 64, 256]):
        tasks.append(("mc", f"{spp} spp", res0, {"backend": "mc", "spp": spp}))
    n_tasks = len(tasks)
    # what makes two shards parts of one sweep: the scene, the tasks and the references
    sweep_id = hashlib.sha256(json.dumps([base, tasks, a.ref, a.ref_spp],
                                         sort_keys=True).encode()).hexdigest()[:16]
    mine = [k for k in range(n_tasks) if a.shard is None or k % a.shard[1] == a.shard[0]]

    ref_png = os.path.splitext(a.ref)[0] + ".png"
    for res in sorted({tasks[k][2] for k in mine} | ({res0} if a.refs_only or a.images else set())):
        # what a reference was made from, kept beside it (REF.exr.json): a reference of another
        # scene, resolution or sample count is refused, not reused
        made = {"scene": scene_with(res), "spp": a.ref_spp, "seed": 1001}
        side = ref_path(res) + ".json"
        if os.path.exists(ref_path(res)):
            try:
                with open(side) as f:
                    known = json.load(f)
            except (OSError, ValueError):
                known = None
            if known != made:
                die(f"{ref_path(res)} was not made for this scene and --ref-spp ({side} "
                    f"{'differs' if known else 'is missing'}): remove it (it is remade) or give another --ref")
            continue
        print(f"reference: mc {res}, {a.ref_spp} spp -> {ref_path(res)}", file=sys.stderr, flush=True)
        # time: a hard stop far beyond what the references take (6 min at 640 x 480 here), which
        # lifts the reference's work budget (its estimate for the smoke's tracking steps is loose,
        # docs/reference.md); a reference cut short by it is refused, not used
        ref = run_task(res, {"backend": "mc", "spp": a.ref_spp, "seed": 1001, "time": REF_TIME_S,
                             "aovs": ["stderr"]}, f"reference {res}")
        if ref.summary.get("spp") != a.ref_spp:
            die(f"{ref_path(res)}: the reference stopped at {ref.summary.get('spp')} of {a.ref_spp} "
                f"samples per pixel after {REF_TIME_S} s", 1)
        ref.write_exr(ref_path(res))
        if res == res0:
            ref.write_png(ref_png)
        fd, tmp_side = tempfile.mkstemp(prefix=".evt", suffix=".json", dir=os.path.dirname(os.path.abspath(side)))
        with os.fdopen(fd, "w") as f:
            json.dump(made, f, sort_keys=True)
        os.replace(tmp_side, side)
    if a.refs_only:
        shutil.rmtree(tmp, ignore_errors=True)
        return

    times = {k: [] for k in mine}
    result = {}
    for r in range(a.reps):
        for k in mine:
            method, params, res, overrides = tasks[k]
            print(f"round {r + 1}/{a.reps}: task {k}: {method} {params}", file=sys.stderr, flush=True)
            seed = {"seed": 7 + k} if method == "mc" else {}
            if method == "slab":  # a warm-up frame: the timed one takes no fresh memory
                run_task(res, overrides, f"task {k}")
            got = run_task(res, {**overrides, **seed}, f"task {k}")
            s = got.summary
            times[k].append(s["ms_render"] + (0 if method == "mc" else s["ms_plan"]))
            try:
                result[k] = icshadow.compare(got, ref_path(res))
            except (icshadow.Error, ValueError) as e:
                die(f"task {k}: {e}", 1)
            if result[k].get("reference_spp") != a.ref_spp:
                die(f"{ref_path(res)} was made with {result[k].get('reference_spp')} samples per pixel, "
                    f"not --ref-spp {a.ref_spp}: remove it (it is remade) or give its --ref-spp")
    rows = []
    for k in mine:
        method, params, res, _ = tasks[k]
        c, t = result[k], times[k]
        rows.append({"task": k, "method": method, "parameters": params, "resolution": res,
                     "ms": statistics.median(t), "ms_min": min(t), "ms_max": max(t), "rmse": c["rmse"],
                     "rmse_beyond_noise": c["rmse_beyond_noise"], "max_error": c["max_error"],
                     "psnr_db": c["psnr_db"], "reference_spp": c.get("reference_spp"),
                     "reference_noise": c["reference_noise"], "n_tasks": n_tasks, "sweep": sweep_id})
    fields = [f for f in rows[0] if not (a.no_times and f in TIME_COLUMNS)] if rows else ["task", "n_tasks"]
    write_csv(a.csv, rows, fields)
    print(f"{len(rows)} of {n_tasks} tasks -> {a.csv}", file=sys.stderr)
    if a.shard is None and not a.no_times:
        ref_info = result[mine[0]]
        print(f"reference: {a.ref}, {ref_info.get('reference_spp')} spp, noise {ref_info['reference_noise']:.3g}, "
              f"{ref_info['ms_reference']:.0f} ms")
        if a.plot:
            plot(rows, ref_info.get("reference_spp"), ref_info["reference_noise"], a.reps, a.plot)
        if a.images and os.path.exists(ref_png):
            slab_png, diff_png = os.path.join(tmp, "slab.png"), os.path.join(tmp, "diff.png")
            got = render("the scene's own settings", scene=a.scene, resolution=(W0, H0))
            got.write_png(slab_png)
            ref_rgb = np.stack([icshadow.read_exr(a.ref)[0][c] for c in "RGB"], -1)
            icshadow.write_png(diff_png, difference_image(got.rgba[:, :, :3], ref_rgb, 4))
            what = f"slab renderer (the scene's settings: model {got.summary['model']}, e = {shipped_e:g})"
            images(slab_png, ref_png, diff_png, icshadow.compare(got, a.ref), a.images, what)
    shutil.rmtree(tmp, ignore_errors=True)


def difference_image(rgb, ref, scale):
    """render minus reference, mean over R, G, B, times scale: red where the render is brighter,
    blue where darker (the picture `icshadow render --diff-png` writes)"""
    d = (rgb.astype(np.float64) - ref).mean(axis=2) * scale
    out = np.zeros(rgb.shape, np.float32)
    out[:, :, 0], out[:, :, 2] = np.clip(d, 0, 1), np.clip(-d, 0, 1)
    return out


def images(slab_png, ref_png, diff_png, c, path, what):
    """The scene as it ships, the reference and their difference side by side."""
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        import matplotlib.image as mpimg
    except ImportError:
        print("error_vs_time: matplotlib not installed: no images", file=sys.stderr)
        return
    fig, ax = plt.subplots(1, 3, figsize=(12, 3.4))
    titles = (what, "Monte-Carlo reference (%s spp)" % c.get("reference_spp"),
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
    """The Pareto front (no other row at the same resolution at least as fast and as accurate and
    better in one) and error against time."""
    res0 = rows[0].get("resolution")
    same = [r for r in rows if r.get("resolution") == res0]  # other resolutions: other references
    for row in rows:
        row["pareto"] = row in same and not any(
            o["ms"] <= row["ms"] and o["rmse_beyond_noise"] <= row["rmse_beyond_noise"] and
            (o["ms"] < row["ms"] or o["rmse_beyond_noise"] < row["rmse_beyond_noise"]) for o in same if o is not row)
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
    e0 = next(float(r["parameters"].split("e=")[1].split()[0]) for r in rows if "e=" in r["parameters"])
    fams = {}
    for r in rows:
        p = r["parameters"]
        if r["method"] == "mc":
            f = "Monte Carlo, samples per pixel"
        elif "model surface" in p:
            f = "ellipse2, model surface (slab spacing e)"
        elif "model blocker" in p:
            f = "ellipse2, model blocker (slab spacing e)"
        elif r.get("resolution") != res0:
            f = "ellipse2, resolution (against its own reference)"
        elif "d1=" in p:
            f = "ellipse2, d1"
        elif "preint" in p or float(p.split("e=")[1].split()[0]) != e0:
            f = "ellipse2, slab spacing e (preint: preintegrated)"
        else:
            f = "kernel member / compensation (e = %g)" % e0
        fams.setdefault(f, []).append(r)
    style = {"Monte Carlo": ("s", "tab:red"), "ellipse2, d1": ("^", "tab:orange"),
             "ellipse2, resolution": ("v", "tab:purple"),
             "ellipse2, slab": ("D", "tab:green"), "kernel": ("o", "tab:blue"),
             "ellipse2, model surface": ("P", "tab:brown"),
             "ellipse2, model blocker": ("X", "tab:pink")}
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
    ax.set_xlabel("time per frame, ms (median of %d runs, %d cores)" % (reps, os.cpu_count() or 1))
    ax.set_ylabel("RMSE against the reference, its noise removed")
    ax.set_title("Error against run time, %s (reference: Monte Carlo, %s spp, noise %.2g)"
                 % (res0, ref_spp, ref_noise), fontsize=10)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7.5, loc="upper right")
    side.axis("off")
    for k, (num, text, colour) in enumerate(keys):
        side.text(0, 1 - k / max(len(keys), 22), f"{num:2d}  {text}", fontsize=7.5, color=colour,
                  family="monospace", va="top", transform=side.transAxes)
    fig.tight_layout()
    fig.savefig(path, dpi=130)
    print(f"plot: {path}")


def replot(a):
    if not a.plot:
        die("--replot needs --plot PNG")
    with open(a.csv) as f:
        rows = list(csv.DictReader(f))
    for r in rows:
        for k in ("ms", "ms_min", "ms_max", "rmse", "rmse_beyond_noise", "max_error", "psnr_db"):
            r[k] = float(r[k])
    meta = rows[0]
    plot(rows, meta.get("reference_spp", "?"), float(meta.get("reference_noise", "nan")), a.reps, a.plot)


if __name__ == "__main__":
    main()
