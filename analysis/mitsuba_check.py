#!/usr/bin/env python3
"""mitsuba_check.py — the Monte-Carlo reference (icshadow render --backend mc) against an outside
renderer, Mitsuba 3 (PyPI `mitsuba`, variant scalar_rgb), on scenes both can express.

Method (docs/results.md "The outside check"):
- Two scenes in icshadow's world frame (camera along -z, lights behind the viewer, dz > 0):
  `disk`, an opaque disk over a white receiver; `medium`, a box of heterogeneous absorbing medium
  (a 6 x 6 x 4 grid of extinctions, trilinear between cell centres, clamped at the edges, as
  icshadow's grid detail; Mitsuba's gridvolume is checked to do the same) over the receiver. One
  Gaussian light each.
- icshadow: the scene file with the light in a lights file, rendered by `mc` with the visibility
  and depth AOVs and their standard errors. The visibility of light 0 at each pixel's first
  surface is the fraction of the light reaching the receiver there, V = int L V dw / int L dw.
- Mitsuba: the same light as the environment map `icshadow make-env` writes from the same lights
  file, put on Mitsuba's lattice (columns reversed: Mitsuba's phi = 2 pi u with direction
  (sin t sin phi, cos t, -sin t cos phi), icshadow's phi = 2 pi u - pi with (sin t sin phi, cos t,
  sin t cos phi); rows interpolated in theta: Mitsuba's row k is at pi k / (H - 1), icshadow's row
  j at pi (j + 1/2) / H), checked on the map's brightest pixel, and divided by cos(w, n) = w_z
  (icshadow's surfaces have no cosine factor; a diffuse receiver of reflectance 1 under L / cos
  returns (1/pi) int L V dw). One radiance meter per icshadow pixel centre, below the occluder and
  looking down (camera rays never cross the medium or the disk), integrator `volpath`:
  V = I / I0, I0 the same meters without the occluder (the mean over all meters and passes). The
  standard errors come from K independent passes (seeds). The absolute scale is checked too:
  pi I0 must be the map's power int L dw within 4 standard errors (a misplaced row shows there).
- Compared over the penumbra (the receiver is the first surface, 0.02 < V_ics < 0.98; at least
  100 points): z = (V_mi - V_ics) / sqrt(se_mi^2 + se_ics^2). Agreement: mean z^2 in [0.75, 1.3],
  |mean z| sqrt(n) <= 4 (no bias) and max |z| <= 5 (64 passes: t-distributed z, nearly normal);
  and a control (icshadow with the light's covariance x 1.25) must fail that agreement, so the
  check can see an error of that size.

Python is the driver only: both images come from the two renderers.
Exit status: 0 pass, 1 a check failed, 2 Mitsuba or the tool is missing (77 with --skip-code).
"""
import argparse
import json
import math
import os
import subprocess
import sys
import tempfile

import numpy as np

RECEIVER_Z, EYE_Z = -1.0, 2.0
RES, HEIGHT = 20, 1.6  # icshadow's camera: RES x RES pixels over HEIGHT world units

SCENES = {
    "disk": {
        "light": {"mean": [0.6, 0.2], "cov": [[0.04, 0.01], [0.01, 0.02]]},
        "centre": [-0.6, -0.2],  # the shadow's centre: disk centre - d mean, d = 1
    },
    "medium": {
        "light": {"mean": [0.3, -0.2], "cov": [[0.03, 0.0], [0.0, 0.01]]},
        "centre": [-0.15, 0.1],
    },
}
GRID = (6, 6, 4)  # nx, ny, nz
BOX_CENTRE, BOX_SIZE, EXTINCTION = [0.0, 0.0, 0.0], [1.0, 1.0, 0.5], 4.0


def die(msg, code):
    print(f"mitsuba_check: {msg}", file=sys.stderr)
    sys.exit(code)


def run(cmd):
    p = subprocess.run(cmd, capture_output=True, text=True)
    if p.returncode != 0:
        die(f"{' '.join(cmd)} failed ({p.returncode}): {p.stderr.strip()}", 1)
    return p.stdout


def grid_values():
    rng = np.random.RandomState(20261202)
    nx, ny, nz = GRID
    return rng.uniform(0.0, 1.0, size=(nz, ny, nx)).astype(np.float32)  # x fastest


def icshadow_scene(name, lights_file, grid_file):
    s = SCENES[name]
    cx, cy = s["centre"]
    scene = {
        "camera": {"projection": "orthographic", "eye": [cx, cy, EYE_Z], "target": [cx, cy, 0],
                   "up": [0, 1, 0], "height": HEIGHT, "resolution": [RES, RES]},
        "render": {"slab_spacing": 0.01, "d1": 1.0, "seed": 5},
        "lights_file": lights_file,
        "materials": {"black": {"color": [0, 0, 0]}, "white": {}},
        "objects": [{"shape": "rect", "center": [0, 0, RECEIVER_Z], "normal": [0, 0, 1],
                     "size": [8, 8], "material": "white"}],
    }
    if name == "disk":
        scene["objects"].insert(0, {"shape": "disk", "center": [0, 0, 0], "normal": [0, 0, 1],
                                    "radius": 0.3, "material": "black"})
    else:
        scene["materials"]["medium"] = {
            "extinction": EXTINCTION,
            "detail": {"function": "grid", "file": grid_file, "size": list(GRID)}}
        scene["objects"].insert(0, {"shape": "box", "center": BOX_CENTRE, "size": BOX_SIZE,
                                    "material": "medium"})
    return scene


def pixel_centres(name):
    """World (x, y) of icshadow's pixel centres, row 0 at the top (+y)."""
    cx, cy = SCENES[name]["centre"]
    h = HEIGHT / RES
    xs = cx - HEIGHT / 2 + (np.arange(RES) + 0.5) * h
    ys = cy + HEIGHT / 2 - (np.arange(RES) + 0.5) * h
    return np.meshgrid(xs, ys)


def read_channels(mi, path):
    bm = mi.Bitmap(path)
    data, st = np.array(bm, dtype=np.float64), bm.struct_()
    return {st[k].name: data[:, :, k] for k in range(bm.channel_count())}


def mitsuba_env(mi, env_path):
    """The make-env map on Mitsuba's lattice, divided by cos(w, +z). Columns: Mitsuba's column i
    is at u = (i + 1/2) / W as icshadow's, running the other way (reversed). Rows: Mitsuba puts
    row k at theta = pi k / (H - 1), pole rows on the poles; icshadow's row j is at pi (j + 1/2) / H,
    so each column is interpolated linearly in theta onto Mitsuba's rows (the poles take the
    nearest rows' values). Returns the map for Mitsuba and icshadow's own, with its integral of
    L dw (channel R, exact pixel solid angles)."""
    img = np.array(mi.Bitmap(env_path), dtype=np.float64)[:, :, :3]
    H, W = img.shape[:2]
    th_mi = math.pi * np.arange(H) / (H - 1)
    pos = np.clip((th_mi / math.pi) * H - 0.5, 0, H - 1)  # fractional icshadow row of each theta
    j0 = np.minimum(np.floor(pos).astype(int), H - 2)
    w = (pos - j0)[:, None, None]
    rows = (1 - w) * img[j0] + w * img[j0 + 1]
    phi = 2 * math.pi * (np.arange(W) + 0.5) / W - math.pi
    dz = np.sin(th_mi)[:, None] * np.cos(phi)[None, :]
    out = np.where(dz[:, :, None] > 1e-3, rows / np.maximum(dz, 1e-3)[:, :, None], 0.0)
    edges = math.pi * np.arange(H + 1) / H
    d_omega = (np.cos(edges[:-1]) - np.cos(edges[1:])) * 2 * math.pi / W
    power = float(np.sum(img[:, :, 0] * d_omega[:, None]))
    return np.ascontiguousarray(out[:, ::-1, :]).astype(np.float32), img, power


def check_env_orientation(mi, env, img):
    """Mitsuba's radiance toward the direction of the map's brightest pixel (icshadow's formula for
    its centre) times cos must be that pixel's value: the reversal and the cosine are right."""
    H, W = img.shape[:2]
    j, i = np.unravel_index(np.argmax(img[:, :, 0]), img.shape[:2])
    theta, phi = math.pi * (j + 0.5) / H, 2 * math.pi * (i + 0.5) / W - math.pi
    w = np.array([math.sin(theta) * math.sin(phi), math.cos(theta), math.sin(theta) * math.cos(phi)])
    emitter = mi.load_dict({"type": "envmap", "bitmap": mi.Bitmap(env)})
    si = mi.SurfaceInteraction3f()
    si.wi = mi.Vector3f(-w)
    got, want = emitter.eval(si)[0] * w[2], img[j, i, 0]
    if abs(got - want) > 1e-3 * abs(want):
        die(f"Mitsuba's envmap is not oriented as icshadow's: {got} toward the peak, map {want}", 1)


def check_grid_convention(mi, grid):
    """Cell-centred values, trilinear, clamped: Mitsuba's gridvolume at cell centres and midway."""
    vol = mi.load_dict({"type": "gridvolume", "grid": mi.VolumeGrid(grid[..., None])})
    nz, ny, nx = grid.shape
    # (x, y, z) in cell units, x fastest: a cell centre, then midway between two along x
    for (x, y, z, want) in [(1, 2, 1, grid[1, 2, 1]), (1.5, 2, 1, 0.5 * (grid[1, 2, 1] + grid[1, 2, 2]))]:
        it = mi.Interaction3f()
        it.p = mi.Point3f((x + 0.5) / nx, (y + 0.5) / ny, (z + 0.5) / nz)
        got = vol.eval_1(it)
        if abs(got - want) > 1e-5:
            die(f"Mitsuba's gridvolume is not cell-centred trilinear: {got}, expected {want}", 1)


def mitsuba_scene(mi, name, env, grid, xs, ys, spp, occluder=True):
    T = mi.ScalarTransform4f
    film = lambda w: {"type": "hdrfilm", "width": w, "height": 1, "rfilter": {"type": "box"},
                      "pixel_format": "rgb"}
    meters = {f"m{k:04d}": {"type": "radiancemeter", "origin": [float(x), float(y), -0.9],
                            "direction": [0, 0, -1], "film": film(1)}
              for k, (x, y) in enumerate(zip(xs.ravel(), ys.ravel()))}
    sc = {
        "type": "scene",
        "integrator": {"type": "volpath", "max_depth": 8},
        "sensor": dict({"type": "batch", "film": film(len(meters)),
                        "sampler": {"type": "independent", "sample_count": spp}}, **meters),
        "env": {"type": "envmap", "bitmap": mi.Bitmap(env)},
        "receiver": {"type": "rectangle", "to_world": T().translate([0, 0, RECEIVER_Z]).scale([4, 4, 1]),
                     "bsdf": {"type": "diffuse", "reflectance": {"type": "rgb", "value": 1.0}}},
    }
    if occluder and name == "disk":
        sc["occluder"] = {"type": "disk", "to_world": T().scale([0.3, 0.3, 1]),
                          "bsdf": {"type": "diffuse", "reflectance": {"type": "rgb", "value": 0.0}}}
    elif occluder:
        lo = [BOX_CENTRE[i] - BOX_SIZE[i] / 2 for i in range(3)]
        sc["occluder"] = {
            "type": "cube",
            "to_world": T().translate(BOX_CENTRE).scale([s / 2 for s in BOX_SIZE]),
            "bsdf": {"type": "null"},
            "interior": {"type": "heterogeneous", "albedo": 0.0, "scale": EXTINCTION,
                         "sigma_t": {"type": "gridvolume", "grid": mi.VolumeGrid(grid[..., None]),
                                     "to_world": T().translate(lo).scale(BOX_SIZE)}}}
    return mi.load_dict(sc)


def mitsuba_visibility(mi, name, env, grid, xs, ys, passes, spp):
    """V = I / I0 at the meters with its standard error from the passes, and I0 with its own."""
    scene = mitsuba_scene(mi, name, env, grid, xs, ys, spp)
    free = mitsuba_scene(mi, name, env, grid, xs, ys, spp, occluder=False)
    I = np.array([np.array(mi.render(scene, spp=spp, seed=1000 + k))[0, :, 0] for k in range(passes)])
    I0 = np.array([np.array(mi.render(free, spp=spp, seed=5000 + k))[0, :, 0] for k in range(passes)])
    i0, i0_se = float(I0.mean()), float(I0.std(ddof=1)) / math.sqrt(I0.size)
    V = I.mean(axis=0) / i0
    se = I.std(axis=0, ddof=1) / math.sqrt(passes) / i0
    return V.reshape(xs.shape), se.reshape(xs.shape), i0, i0_se


def z_scores(v_mi, se_mi, v_ics, se_ics, mask):
    return (v_mi - v_ics)[mask] / np.sqrt(se_mi[mask] ** 2 + se_ics[mask] ** 2)


def judge(z):
    """Mean z^2 in [0.75, 1.3], |mean z| sqrt(n) <= 4 (no bias), max |z| <= 5."""
    m2, mz, zmax = float(np.mean(z * z)), float(np.mean(z) * math.sqrt(z.size)), float(np.max(np.abs(z)))
    return m2, mz, zmax, 0.75 <= m2 <= 1.3 and abs(mz) <= 4 and zmax <= 5


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--icshadow", default="build/bin/icshadow")
    ap.add_argument("--spp", type=int, default=4096, help="icshadow mc samples per pixel")
    ap.add_argument("--passes", type=int, default=64, help="Mitsuba passes (standard error)")
    ap.add_argument("--pass-spp", type=int, default=64, help="Mitsuba samples per pass")
    ap.add_argument("--scenes", default="disk,medium", help="comma-separated: " + ", ".join(SCENES))
    ap.add_argument("--json", help="write the summary here")
    ap.add_argument("--plot", help="PNG: V from both renderers and z per scene")
    ap.add_argument("--workdir", help="keep the intermediate files here")
    ap.add_argument("--control-scale", type=float, default=1.25,
                    help="the control's factor on the light's covariance (default 1.25)")
    ap.add_argument("--skip-code", action="store_true", help="exit 77 (skip) when Mitsuba is missing")
    a = ap.parse_args()
    names = a.scenes.split(",")
    for name in names:
        if name not in SCENES:
            die(f"--scenes: {name!r} is not a scene ({', '.join(SCENES)})", 2)
    if a.passes < 8 or a.spp < 2 or a.pass_spp < 1:
        die("--passes must be >= 8, --spp >= 2 and --pass-spp >= 1", 2)
    try:
        import mitsuba as mi
        mi.set_variant("scalar_rgb")
    except Exception as e:  # ImportError, or a variant that does not load
        die(f"Mitsuba 3 (scalar_rgb) is not available: {e}", 77 if a.skip_code else 2)
    if not os.access(a.icshadow, os.X_OK):
        die(f"{a.icshadow}: not an executable (build icshadow first)", 2)
    work = os.path.abspath(a.workdir or tempfile.mkdtemp(prefix="mitsuba_check"))
    os.makedirs(work, exist_ok=True)
    grid = grid_values()
    grid_file = os.path.join(work, "grid.raw")
    grid.tofile(grid_file)
    check_grid_convention(mi, grid)
    summary, ok, panels = {"mitsuba": mi.__version__, "variant": "scalar_rgb", "scenes": {}}, True, []
    for name in names:
        light = SCENES[name]["light"]
        lights = os.path.join(work, f"{name}_lights.json")
        with open(lights, "w") as f:
            json.dump({"lights": [light]}, f)
        env_path = os.path.join(work, f"{name}_env.exr")
        run([a.icshadow, "make-env", "--lights", lights, "--size", "1024x512", "-o", env_path])
        env, img, power = mitsuba_env(mi, env_path)
        check_env_orientation(mi, env, img)
        xs, ys = pixel_centres(name)
        v_mi, se_mi, i0, i0_se = mitsuba_visibility(mi, name, env, grid, xs, ys, a.passes, a.pass_spp)
        # the absolute scale: a white diffuse receiver under L / cos returns (1/pi) int L dw
        z_i0 = (math.pi * i0 - power) / (math.pi * i0_se)
        result = {"mitsuba_spp": a.passes * a.pass_spp, "icshadow_spp": a.spp, "pi_I0": math.pi * i0,
                  "map_power": power, "pi_I0_z": z_i0}
        for tag, scale in (("", 1.0), ("control", a.control_scale)):
            lt = dict(light, cov=[[c * scale for c in row] for row in light["cov"]])
            lf = os.path.join(work, f"{name}_lights{tag}.json")
            with open(lf, "w") as f:
                json.dump({"lights": [lt]}, f)
            sf = os.path.join(work, f"{name}{tag}.json")
            with open(sf, "w") as f:
                json.dump(icshadow_scene(name, lf, grid_file), f)
            exr = os.path.join(work, f"{name}{tag}.exr")
            run([a.icshadow, "render", sf, "--backend", "mc", "--spp", str(a.spp),
                 "--aov", "visibility,depth,stderr", "-o", exr])
            ch = read_channels(mi, exr)
            v, se = ch["light0.V"], ch["stderr.light0.V"]
            # the penumbra: where the receiver is the first surface and the light partly blocked
            # (fully lit or umbra points carry no information and would dilute a bias)
            pen = (np.abs(ch["Z"] - (EYE_Z - RECEIVER_Z)) < 1e-4) & (v > 0.02) & (v < 0.98)
            if pen.sum() < 100:
                die(f"{name}{tag}: only {int(pen.sum())} penumbra points (0.02 < V < 0.98); need 100", 1)
            m2, mz, zmax, good = judge(z_scores(v_mi, se_mi, v, se, pen))
            if tag:
                result.update(control_mean_z2=m2, control_mean_z_sqrt_n=mz, control_seen=not good)
            else:
                result.update(points=int(pen.sum()), mean_z2=m2, mean_z_sqrt_n=mz, max_z=zmax,
                              max_abs_diff=float(np.max(np.abs(v_mi - v)[pen])),
                              median_se=float(np.median(np.sqrt(se_mi ** 2 + se ** 2)[pen])), agree=good)
                panels.append((name, v_mi, v, pen,
                               np.where(pen, (v_mi - v) / np.sqrt(se_mi ** 2 + se ** 2 + 1e-30), np.nan)))
        passed = bool(result["agree"] and result["control_seen"] and abs(z_i0) <= 4)
        result["pass"] = passed
        ok &= passed
        summary["scenes"][name] = result
        print(f"{name}: {result['points']} penumbra points, mean z^2 {result['mean_z2']:.3f} (window "
              f"[0.75, 1.3]), mean z sqrt(n) {result['mean_z_sqrt_n']:+.2f} (|.| <= 4), max |z| "
              f"{result['max_z']:.2f} (<= 5), max |dV| {result['max_abs_diff']:.4f}, median combined "
              f"standard error {result['median_se']:.4f}; control (covariance x {a.control_scale:g}): mean z^2 "
              f"{result['control_mean_z2']:.2f}, mean z sqrt(n) {result['control_mean_z_sqrt_n']:+.1f} "
              f"({'seen' if result['control_seen'] else 'NOT seen'}); pi I0 {math.pi * i0:.5f} vs the "
              f"map's power {power:.5f} (z {z_i0:+.2f}, |.| <= 4) -> {'pass' if passed else 'FAIL'}")
    if a.json:
        with open(a.json, "w") as f:
            json.dump(summary, f, indent=1)
    if a.plot:
        plot(panels, a.plot)
    sys.exit(0 if ok else 1)


def plot(panels, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(len(panels), 3, figsize=(10, 3.0 * len(panels)), squeeze=False,
                           constrained_layout=True)
    for r, (name, v_mi, v_ics, _, z) in enumerate(panels):
        for c, (img, title) in enumerate(((v_mi, f"{name}: Mitsuba 3 V"), (v_ics, f"{name}: icshadow mc V"))):
            im = ax[r][c].imshow(img, vmin=0, vmax=1, cmap="gray")
            ax[r][c].set_title(title)
        im2 = ax[r][2].imshow(z, vmin=-4, vmax=4, cmap="coolwarm")
        ax[r][2].set_title(f"{name}: z over the penumbra")
        fig.colorbar(im, ax=ax[r][:2].tolist(), shrink=0.8)
        fig.colorbar(im2, ax=ax[r][2], shrink=0.8)
        for c in range(3):
            ax[r][c].set_xticks([]), ax[r][c].set_yticks([])
    fig.savefig(path, dpi=90)


if __name__ == "__main__":
    main()
