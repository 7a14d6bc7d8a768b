#!/usr/bin/env python3
"""gallery.py — docs/gallery.md and its pictures: every example scene under scenes/ rendered by
the slab renderer, under Patel's model (render.model patel) and under render.model blocker
(what auto, the default, renders on cpu), each at the scene's own slab spacing, with their frame
times and their errors against the Monte-Carlo reference.

Per scene, from the repository root (the scene's own resolution, or --resolution fitting it into
320 x 240 where it is larger):
  icshadow render scenes/NAME.json --model patel --png docs/images/gallery/NAME.png    (REPS runs, interleaved
      over the scenes; the frame time is the median of the summaries' ms_plan + ms_render)
  icshadow render scenes/NAME.json --model blocker --png docs/images/gallery/NAME_blocker.png
      (the same, interleaved with the first)
  icshadow render scenes/NAME.json --backend mc --spp N --aov stderr -o REF.exr
  icshadow render scenes/NAME.json --model patel|blocker --compare REF.exr   (compare.rmse,
      rmse_beyond_noise, max_error, reference_noise, ms_reference; N per scene in SCENES below,
      chosen so that each reference takes under a minute on a 2-core VM; volumes.json's 512
      would pass the reference's work bound of 2e10 tracking steps)
and the machine: /proc/cpuinfo's first "model name", os.cpu_count(), and the vector path and
threads from the summary's device string. A scene whose mesh cannot be read (a binary built
without Assimp) is listed as not rendered, with the reason; its old picture is left alone.

Writes the whole page (generated: edit this script, not docs/gallery.md) and the PNGs. Standard
library only; `make gallery` runs it with the build's binary (about 6 minutes here):
  /usr/bin/python3 analysis/gallery.py --cli build/bin/icshadow
--md, --images, --reps and --ref-spp (one N for every scene) are for trying it out elsewhere.
"""
import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile
import textwrap

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
MAX_W, MAX_H = 320, 240

# name: (title, what it shows, samples per pixel of its reference). Every scenes/*.json needs an
# entry; the page lists them in this order.
SCENES = {
    "disk": ("The contract example",
             "A black disk 1 above a white square under one anisotropic light "
             "([scene-format.md](scene-format.md)); d1 = d = 1, so the slab renderer's shadow is "
             "Patel's Eq. 4 up to the discretisation (`tests/test_render_disk.c` measures it).", 4096),
    "patel_fig11": ("Patel Fig. 11: the disk under a wide light",
                    "The contract example's disk under a light of covariance 0.06 I, the figure's high "
                    "variance. `paper_figs/patel_fig11.py` reads this file and sweeps the variance "
                    "(0.004, 0.06) and the kernel members.", 4096),
    "patel_fig14": ("Patel Fig. 14: three coloured lights",
                    "The disk under a small green light, a broad red one and a thin blue line light "
                    "rotated by −70°: each light's shadow moved by −d μ and blurred by its own "
                    "covariance, coloured where the others still reach. `paper_figs/patel_fig14_scene.py`.",
                    4096),
    "patel_fig18": ("Patel Fig. 18: penumbrae widening with distance",
                    "Two thin black boxes 0.4 and 1.0 in front of a wall whose lower half recedes at 45°, "
                    "so each penumbra widens down the image; d1 = 1, Patel's (c). "
                    "`paper_figs/patel_fig18.py` also renders d1 = 0.4 and measures the isolines.", 2048),
    "patel_fig19": ("Patel Fig. 19: preintegrated smoke",
                    "A slab of Perlin smoke with a steep transfer function over a white floor, slab "
                    "spacing 0.02, preintegrated. `paper_figs/patel_fig19.py` sweeps the spacing with and "
                    "without preintegration.", 2048),
    "patel_fig20": ("Patel Fig. 15/20: a fence",
                    "A fence's shadow on a wall under a light of variance 0.002. "
                    "`paper_figs/patel_fig20.py` also renders variance 0 (integer shifts: a hard shadow) "
                    "and 0.008.", 4096),
    "patel_fig21": ("Patel Fig. 21: shading from slicing",
                    "A white sphere under an isotropic light (covariance 0.04 I) 45° from the view "
                    "direction: the slab renderer darkens the sphere's tilted parts (a sliced surface "
                    "shadows itself), the reference has the model's exact terminator. "
                    "`paper_figs/patel_fig21.py` sweeps 0 … 67.5° and point, isotropic and line lights.",
                    4096),
    "volumes": ("Volumetric detail, each function",
                "Left to right: Perlin noise (a box; no transfer function: extinction σ_t max(v, 0)), "
                "fBm (a sphere), a ridged multifractal (a sphere, an orange transfer function) and a grid "
                "(a box reading `grids/ring.raw`, a 24³ smoke ring, green, with a transport colour), "
                "over a floor before a wall, under a warm key light and a cool fill.", 256),
    "coloured": ("Coloured transport",
                 "Three translucent panes (opacity 0.6) whose transport colours let red, green and blue "
                 "through, and an fBm sphere whose transfer function runs from purple to yellow under an "
                 "orange transport colour: coloured shadows, so three channels per light buffer.", 1024),
    "perspective": ("A perspective camera",
                    "A 28° field of view onto a fence receding along z and three spheres on a floor, "
                    "before a backdrop that faces the camera; the light buffers shrink toward the "
                    "principal point from slab to slab ([renderer.md](renderer.md), \"Perspective "
                    "cameras\"). The fence's and the spheres' cast shadows come out lighter than the "
                    "reference's.", 1024),
    "mesh": ("A mesh (Assimp)",
             "A trefoil-knot tube of 576 triangles (`meshes/trefoil.ply`), scaled, rotated and moved by "
             "the scene, over a floor before a wall. Needs Assimp. The error lies on the knot's own "
             "surfaces (shading from slicing) and in its cast shadow, softer than the reference's.", 1024),
    "lights_file": ("Lights from a file",
                    "`\"lights_file\": \"lights/studio.json\"`: three lights (a warm key, a cool fill, a "
                    "dim line light low down) drawn over a dim sky into an environment map by "
                    "`icshadow make-env` and fitted back by `icshadow fit-light` "
                    "([lights_format.md](lights_format.md)), over a sphere, a turned box and a torus. "
                    "Most of the error is on the objects: under the narrow key light the reference has "
                    "a sharp terminator and attached shadows, where slicing lights the sphere almost "
                    "evenly, and grainy (the 2-sample kernel's per-pixel rotations).", 512),
}


def run(cli, args):
    """(exit status, the summary as a dict or None, stderr) of `cli args`, run from the root"""
    res = subprocess.run([cli] + args, capture_output=True, text=True, cwd=ROOT)
    summary = None
    if res.returncode == 0:
        summary = json.loads(res.stdout)
    return res.returncode, summary, res.stderr.strip()


def fit(w, h):
    """the scene's resolution, or the largest that fits MAX_W x MAX_H with its aspect"""
    if w <= MAX_W and h <= MAX_H:
        return None
    k = min(MAX_W / w, MAX_H / h)
    return max(1, int(w * k)), max(1, int(h * k))


def machine(device):
    model = "unknown"
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("model name"):
                    model = line.split(":", 1)[1].strip()
                    break
    except OSError:
        pass
    return model, os.cpu_count(), device


def fmt_ms(v):
    return f"{v:.0f}" if v >= 10 else f"{v:.1f}"


def para(text):
    """a paragraph wrapped at 96 columns, as the other pages are"""
    return textwrap.fill(text, width=96, break_long_words=False, break_on_hyphens=False)


def page(rows, mach, ref_note, load):
    model, cores, device = mach
    out = [
        "# Gallery",
        "",
        "<!-- generated by analysis/gallery.py (make gallery): edit the script, not this page -->",
        "",
        para("The example scenes under `scenes/`, each rendered by the slab renderer (the cpu backend, the "
        "scene's own settings but the model) with the command beside it, its frame time and its error against the "
        "Monte-Carlo reference ([reference.md](reference.md)) of the same scene. The scene format is "
        "[scene-format.md](scene-format.md); the files a scene reads (a mesh, a grid, a lights file) lie in "
        "subfolders of `scenes/`, written by `scripts/gen_gallery_assets.py`. `make gallery` "
        "(analysis/gallery.py) renders them again and rewrites this page; `tests/cli/gallery.sh` "
        "(CTest `cli_gallery`) renders every scene at 48 × 36."),
        "",
        para(f"Measured on {model}, {cores} cores, the device string of the summary: \"{device}\" "
             f"(1-minute load average {load[0]:.1f} before the timed runs, {load[1]:.1f} after them). "
        "**Frame** is the summary's ms_plan + ms_render, the median of "
        f"{rows[0]['reps'] if rows else 3} runs interleaved over the scenes (min–max beside it); "
        "**RMSE** is over the pixels and R, G, B against the reference of N samples per pixel "
        f"(`--compare REF.exr`{ref_note}), **beyond noise** is sqrt(RMSE² − σ_ref²), the render's own error "
        "once the reference's noise σ_ref is taken out, and **max** is the largest error of a pixel's "
        "channel. Each scene is rendered twice at its own slab spacing: under Patel's model (`--model "
        "patel`) and under `--model blocker` ([renderer.md](renderer.md) \"Models\": own terms in closed "
        "form and blocker-aware penumbrae; what `render.model` auto, the default of every scene here but "
        "Patel's figures, renders on the cpu backend), its picture on the right. "
        "Pictures are 8-bit sRGB previews (`--png`) of the float image."),
        "",
        "| scene | size | slabs | frame ms | RMSE | beyond noise | max | blocker: frame ms | beyond noise | max | reference N | σ_ref | reference s |",
        "|---|---|---|---|---|---|---|---|---|---|---|---|---|",
    ]
    for r in rows:
        if r.get("skipped"):
            out.append(f"| [{r['name']}](#{r['name']}) | — | — | not rendered: {r['skipped']} | | | | | | | | | |")
            continue
        c, b = r["compare"], r["blocker"]["compare"]
        out.append(f"| [{r['name']}](#{r['name']}) | {r['w']} × {r['h']} | {r['slabs']} | "
                   f"{fmt_ms(r['ms'])} | {c['rmse']:.4f} | {c['rmse_beyond_noise']:.4f} | {c['max_error']:.3f} | "
                   f"{fmt_ms(r['blocker']['ms'])} | {b['rmse_beyond_noise']:.4f} | {b['max_error']:.3f} | "
                   f"{c['reference_spp']} | {c['reference_noise']:.4f} | {c['ms_reference'] / 1e3:.1f} |")
    for r in rows:
        title, text, _ = SCENES[r["name"]]
        out += ["", f"## {r['name']}", "", para(f"**{title}.** {text}"), ""]
        if r.get("skipped"):
            out += [f"Not rendered by this run: {r['skipped']}.", ""]
            continue
        c, bl = r["compare"], r["blocker"]
        b = bl["compare"]
        out += [f"![{r['name']}]({r['img_rel']}) ![{r['name']}, --model blocker]({bl['img_rel']})", "",
                "```sh"] + r["commands"] + ["```", "",
                para(f"{r['w']} × {r['h']}, {r['slabs']} slabs; frame {fmt_ms(r['ms'])} ms "
                f"({fmt_ms(r['ms_min'])}–{fmt_ms(r['ms_max'])}; plan {fmt_ms(r['ms_plan'])} + render "
                f"{fmt_ms(r['ms_render'])}); against the reference at {c['reference_spp']} spp "
                f"({c['ms_reference'] / 1e3:.1f} s, σ_ref {c['reference_noise']:.4f}): RMSE {c['rmse']:.4f}, "
                f"beyond noise {c['rmse_beyond_noise']:.4f}, max {c['max_error']:.3f} at pixel "
                f"({c['max_at'][0]}, {c['max_at'][1]}). Under `--model blocker` (right): frame "
                f"{fmt_ms(bl['ms'])} ms ({fmt_ms(bl['ms_min'])}–{fmt_ms(bl['ms_max'])}), beyond noise "
                f"{b['rmse_beyond_noise']:.4f}, max {b['max_error']:.3f} at pixel ({b['max_at'][0]}, "
                f"{b['max_at'][1]}).")]
    return "\n".join(out) + "\n"


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--cli", default="build/bin/icshadow", help="the icshadow binary")
    ap.add_argument("--md", default="docs/gallery.md", help="the page to write")
    ap.add_argument("--images", default="docs/images/gallery", help="the folder of the pictures")
    ap.add_argument("--reps", type=int, default=3, help="timed runs per scene (median)")
    ap.add_argument("--ref-spp", type=int, help="one reference sample count for every scene (a quick try)")
    args = ap.parse_args()
    cli = os.path.abspath(args.cli)
    md, images = os.path.abspath(args.md), os.path.abspath(args.images)
    names = sorted(f[:-5] for f in os.listdir(os.path.join(ROOT, "scenes")) if f.endswith(".json"))
    missing = [n for n in names if n not in SCENES]
    if missing:
        sys.exit("gallery.py: scenes without an entry in SCENES (title, text, reference N): " + ", ".join(missing))
    names = [n for n in SCENES if n in names]
    os.makedirs(images, exist_ok=True)
    tmp_dir = tempfile.mkdtemp(prefix="gallery")
    tmp_png = os.path.join(tmp_dir, "timing.png")     # the runs after the first write here
    load = [os.getloadavg()[0]]
    rows = {n: {"name": n, "reps": args.reps, "times": []} for n in names}
    device = None
    for rep in range(args.reps):
        for n in names:
            r = rows[n]
            if r.get("skipped"):
                continue
            scene = os.path.join("scenes", n + ".json")
            if rep == 0:
                rc, plan, err = run(cli, ["plan", scene])
                if rc != 0:
                    if "need Assimp" in err:
                        r["skipped"] = "mesh files need Assimp, which this binary was built without"
                        print(f"gallery: {n}: skipped ({err})", file=sys.stderr)
                        continue
                    sys.exit(f"gallery.py: icshadow plan {scene} failed (exit {rc}): {err}")
                r["res"] = fit(*plan["resolution"])
            res = ["--resolution", "%dx%d" % r["res"]] if r["res"] else []
            for model, suffix in (("patel", ""), ("blocker", "_blocker")):
                png = os.path.join(images, n + suffix + ".png") if rep == 0 else tmp_png
                rc, s, err = run(cli, ["render", scene, "--png", png, "--model", model] + res)
                if rc != 0:
                    sys.exit(f"gallery.py: icshadow render {scene} (model {model}) failed "
                             f"(exit {rc}): {err}")
                times = r["times"] if model == "patel" else r.setdefault("blocker", {"times": []})["times"]
                times.append((s["ms_plan"] + s["ms_render"], s["ms_plan"], s["ms_render"]))
                if model == "patel":
                    r["w"], r["h"] = s["resolution"]
                    r["slabs"] = s["slabs"]
                    device = device or s["device"]
                print(f"gallery: {n}{suffix} run {rep + 1}/{args.reps}: {s['ms_plan'] + s['ms_render']:.0f} ms",
                      file=sys.stderr)
    if os.path.exists(tmp_png):
        os.remove(tmp_png)
    load.append(os.getloadavg()[0])
    ref_note = ""
    for n in names:
        r = rows[n]
        if r.get("skipped"):
            continue
        scene = os.path.join("scenes", n + ".json")
        spp = args.ref_spp or SCENES[n][2]
        if args.ref_spp:
            ref_note = f"; N = {spp} for every scene in this run"
        res = ["--resolution", "%dx%d" % r["res"]] if r["res"] else []
        ref = os.path.join(tmp_dir, n + "_ref.exr")
        rc, _, err = run(cli, ["render", scene, "--backend", "mc", "--spp", str(spp), "--aov", "stderr",
                               "-o", ref] + res)
        if rc != 0:
            sys.exit(f"gallery.py: icshadow render {scene} --backend mc --spp {spp} failed (exit {rc}): {err}")
        for sub_row, model, suffix in ((r, "patel", ""), (r["blocker"], "blocker", "_blocker")):
            rc, s, err = run(cli, ["render", scene, "--compare", ref, "--model", model] + res)
            if rc != 0:
                sys.exit(f"gallery.py: icshadow render {scene} --compare failed (exit {rc}): {err}")
            sub_row["compare"] = s["compare"]
            times = sorted(sub_row["times"])
            sub_row["ms"] = statistics.median(t[0] for t in times)
            mid = times[len(times) // 2]
            sub_row["ms_plan"], sub_row["ms_render"] = mid[1], mid[2]
            sub_row["ms_min"], sub_row["ms_max"] = times[0][0], times[-1][0]
            sub_row["img_rel"] = os.path.relpath(os.path.join(images, n + suffix + ".png"), os.path.dirname(md))
        os.remove(ref)
        rel_png = os.path.relpath(os.path.join(images, n + ".png"), ROOT)
        extra = " " + " ".join(res) if res else ""
        r["commands"] = [f"icshadow render {scene} --model patel --png {rel_png}{extra}",
                         f"icshadow render {scene} --model blocker --png {rel_png[:-4]}_blocker.png{extra}",
                         f"icshadow render {scene} --backend mc --spp {spp} --aov stderr -o REF.exr{extra}",
                         f"icshadow render {scene} --model patel|blocker --compare REF.exr{extra}"]
        c = r["compare"]
        print(f"gallery: {n}: {r['ms']:.0f} ms, rmse {c['rmse']:.4f} (beyond noise {c['rmse_beyond_noise']:.4f}), "
              f"max {c['max_error']:.3f}, reference {spp} spp in {c['ms_reference'] / 1e3:.1f} s", file=sys.stderr)
    os.rmdir(tmp_dir)
    text = page([rows[n] for n in names], machine(device or "no render"), ref_note, load)
    tmp = md + ".tmp"
    with open(tmp, "w") as f:
        f.write(text)
    os.replace(tmp, md)
    print(f"gallery: wrote {os.path.relpath(md, ROOT)} and {len(names)} pictures under "
          f"{os.path.relpath(images, ROOT)}", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
