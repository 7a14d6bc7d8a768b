#!/usr/bin/env python3
"""Patel et al. 2013, Fig. 18: two thin boxes (Heaviside occluders) at different distances in front
of a wall whose lower half is angled at 45 degrees, so that each shadow's penumbra can be followed
at increasing distance behind its caster. The Monte-Carlo reference is rendered once, the slab
renderer twice: d1 = 1.0 (the right box's distance to the upright wall, Patel's (c)) and d1 = 0.4
(the left box's, Patel's (d)), and once more under render.model blocker (blocker-aware penumbrae,
d1 = 2.5: its sets at 0.625 and 2.5 cover the boxes' distances, 0.4 to 2.6), measured against the
correct lines. The isolines are measured on the
images, not drawn from a model.

The scene (scenes/patel_fig18.json; the constants below are read from it): an orthographic view
along -z, 200 x 150 pixels of 0.02; the wall at z = 0 for y >= 0 and z = y below (45 degrees,
receding); black boxes 0.5 wide and 0.02 deep reaching 1.2 beyond the image above and below (so
no row sees light past a box's end: the closed forms below are an infinite edge's), front faces at
z = 0.40 (x in [-1.7, -1.2]) and z = 1.00 (x in [0, 0.5]); one light of mean (-0.3, 0) and
variance 0.003 on each axis, so each shadow is cast to the right by 0.3 d and a row at height y
sees both boxes from one distance d(y) = z_box - z_wall(y). Every light direction leans left
(|mean| / sigma = 5.5), so the edge that casts a shadow's right side is the box's right front
edge: d is measured from the front face.

Measurement: V = the render with boxes / the same render without boxes (the ratio takes out any
shading of the tilted wall by slicing, Patel Sec. 7; the script prints what the wall alone
renders at). Along each row, the isoline of shadow level S (blocked fraction) beside a box's
right edge x_r is at x_0 + px * #{pixels in a window from x_0 whose V < 1 - S}, x_0 in the
umbra (x_r, or the shadow's middle once the shadow has moved clear of its box): exact for a
monotone profile, unbiased under symmetric noise; refined linearly between the two pixel
centres that bracket the level. Predictions (closed forms, independent of the
library): correct (Eq. 9) x = x_r + 0.3 d - d sigma Phi^-1(S); iterative in the CLT limit
(Eq. 8, A.4) x = x_r + 0.3 d - sqrt(d d1) sigma Phi^-1(S) — linear against square root in d.
Levels S = 0.1, 0.3, 0.5, 0.7, 0.9 (equal steps, the same for both boxes, as in Patel's figure).

Commands: `icshadow render SCENE --backend mc --spp 512 -o REF.exr --png REF.png` (and 16 spp
without boxes: there every ray is unblocked), `icshadow render SCENE --compare REF.exr --png
SLAB.png` per d1 (and without boxes). Writes patel_fig18.png, patel_fig18.csv (image, box, level,
measured against correct and against CLT: RMS and worst difference in pixels, rows measured) and
patel_fig18_isolines.csv (every measured position with its predictions).
"""
import json
import os
import sys
import tempfile
from statistics import NormalDist

import numpy as np

import matplotlib

matplotlib.use("Agg")
import matplotlib.image as mpimg  # noqa: E402
import matplotlib.pyplot as plt  # noqa: E402

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "lib"))
from figutil import load_scene, parse_args, run_cli, save_fig, write_csv  # noqa: E402

SCENE = load_scene("patel_fig18")             # the figure's main configuration: d1 = 1.0, (c)
W, H = SCENE["camera"]["resolution"]
HEIGHT = SCENE["camera"]["height"]
PX = HEIGHT / H
X0, Y0 = -0.5 * W * PX, 0.5 * HEIGHT          # the image's left and top edges
MEAN_X, VAR = SCENE["lights"][0]["mean"][0], SCENE["lights"][0]["var"][0]
SIGMA = VAR ** 0.5
# (name, x of the left side, x_r of the right side, z of the front face), left to right
_BOXES = sorted((o for o in SCENE["objects"] if o["shape"] == "box"), key=lambda o: o["center"][0])
BOXES = tuple((name, o["center"][0] - 0.5 * o["size"][0], o["center"][0] + 0.5 * o["size"][0],
               o["center"][2] + 0.5 * o["size"][2]) for name, o in zip(("left", "right"), _BOXES))
BOX_W = _BOXES[0]["size"][0]
LEVELS = (0.1, 0.3, 0.5, 0.7, 0.9)
D1S = (1.0, 0.4)                               # Patel's (c): the right box, (d): the left box
BLOCKER_D1 = 2.5                               # render.model blocker: its sets at d1 / 4 and d1, d1 the
#                                               farthest box-to-wall distance (2.6)
SPP = 512


def scene(with_boxes, d1):
    """scenes/patel_fig18.json with d1, and without its boxes for the ratio's denominator."""
    s = load_scene("patel_fig18")
    s["render"]["d1"] = d1
    if not with_boxes:
        s["objects"] = [o for o in s["objects"] if o["shape"] != "box"]
    return s


def linear(png):
    v = mpimg.imread(png)[:, :, 0].astype(np.float64)
    return np.where(v <= 0.04045, v / 12.92, ((v + 0.055) / 1.055) ** 2.4)


def row_distance(j, zf):
    """d behind a box with front face at zf for image row j, or None near the wall's fold."""
    y = Y0 - (j + 0.5) * PX
    if abs(y) < 3 * PX:
        return None
    return zf - (0.0 if y > 0 else y)


def predict(xr, d, s, spread):
    return xr - MEAN_X * d - spread * SIGMA * NormalDist().inv_cdf(s)


def measure(v, j, x_start, x_end, s):
    """Position of the level-s isoline on row j: x_start plus the width of the pixels in
    [x_start, x_end) with V < 1 - s, refined between the two pixel centres around it where they
    bracket the level."""
    i0, i1 = int(round((x_start - X0) / PX)), int(round((x_end - X0) / PX))
    level = 1.0 - s
    k = i0 + np.count_nonzero(v[j, i0:i1] < level)
    if i0 < k < i1 and v[j, k - 1] < level <= v[j, k]:
        return X0 + (k - 0.5) * PX + PX * (level - v[j, k - 1]) / (v[j, k] - v[j, k - 1])
    return X0 + k * PX


def isolines(v, d1):
    """{(box, level): [(row, d, measured, correct, clt)]} for one ratio image (d1 None: the
    reference, whose CLT column is not used)."""
    out = {}
    for k, (name, _, xr, zf) in enumerate(BOXES):
        nxt = BOXES[k + 1][1] if k + 1 < len(BOXES) else X0 + W * PX
        for s in LEVELS:
            rows = []
            for j in range(H):
                d = row_distance(j, zf)
                if d is None:
                    continue
                spread = (d * d1) ** 0.5 if d1 else d          # the image's own model
                x_end = xr - MEAN_X * d + 4.5 * SIGMA * max(d, spread)
                # the window starts in the umbra: at the box's edge or, once the shadow has moved
                # clear of the box (0.3 d > its width), at the shadow's middle
                x_start = max(xr, xr - 0.5 * BOX_W - MEAN_X * d)
                correct, clt = predict(xr, d, s, d), predict(xr, d, s, spread)
                lit_at_start = NormalDist().cdf((xr - BOX_W - MEAN_X * d - x_start) / (spread * SIGMA))
                if x_end > nxt - 2 * PX or (clt if d1 else correct) < x_start + 2 * PX or lit_at_start > 0.02:
                    continue        # the window would reach the next box, miss the isoline or the umbra
                rows.append((j, d, measure(v, j, x_start, x_end, s), correct, clt))
            out[(name, s)] = rows
    return out


def stats(rows, col):
    e = np.array([(r[2] - r[col]) / PX for r in rows])
    return float(np.sqrt(np.mean(e * e))), float(e[np.argmax(np.abs(e))])


def main():
    args = parse_args(__doc__)
    tmp = tempfile.mkdtemp(prefix="fig18")

    def render(name, with_boxes, d1, extra):
        sf = os.path.join(tmp, name + ".json")
        with open(sf, "w") as f:
            json.dump(scene(with_boxes, d1), f)
        png = os.path.join(tmp, name + ".png")
        out = json.loads(run_cli(args.cli, ["render", sf, "--png", png] + extra))
        return linear(png), out

    ref_exr = os.path.join(tmp, "ref.exr")
    ref, ref_sum = render("ref", True, D1S[0], ["--backend", "mc", "--spp", str(SPP), "-o", ref_exr])
    ref0, _ = render("ref0", False, D1S[0], ["--backend", "mc", "--spp", "16"])
    images = [("reference", ref / np.maximum(ref0, 1e-6), None, ref, ref_sum["ms_render"], None)]
    for d1 in D1S:
        sl, sl_sum = render(f"slab{d1:g}", True, d1, ["--compare", ref_exr])
        sl0, _ = render(f"slab0_{d1:g}", False, d1, [])
        images.append((f"slab d1 = {d1:g}", sl / np.maximum(sl0, 1e-6), d1, sl,
                       sl_sum["ms_plan"] + sl_sum["ms_render"], sl_sum["compare"]))
        tilt = sl0[H // 2 + 5:, :]
        print(f"slab d1 = {d1:g}: rmse {sl_sum['compare']['rmse']:.4f} against the reference, max "
              f"{sl_sum['compare']['max_error']:.3f}; the tilted wall alone renders at {tilt.mean():.3f} "
              f"(min {tilt.min():.3f}; the reference: 1)")
    # the blocker-aware model (docs/renderer.md "Models"), measured against the correct lines only
    bl, bl_sum = render("blocker", True, BLOCKER_D1, ["--model", "blocker", "--compare", ref_exr])
    bl0, _ = render("blocker0", False, BLOCKER_D1, ["--model", "blocker"])
    images.append((f"blocker d1 = {BLOCKER_D1:g}", bl / np.maximum(bl0, 1e-6), None, bl,
                   bl_sum["ms_plan"] + bl_sum["ms_render"], bl_sum["compare"]))
    print(f"blocker d1 = {BLOCKER_D1:g}: rmse {bl_sum['compare']['rmse']:.4f} against the reference")

    rows, lines, measured = [], [], {}
    for label, v, d1, _, _, _ in images:
        iso = isolines(v, d1)
        measured[label] = iso
        for (box, s), rs in iso.items():
            rc, wc = stats(rs, 3)
            rl, wl = stats(rs, 4) if d1 else (float("nan"), float("nan"))
            rows.append([label, box, s, rc, wc, rl, wl, len(rs)])
            lines += [[label, box, s, j, d, x, c, l] for j, d, x, c, l in rs]
            print(f"{label:16s} {box:5s} S = {s:.1f}: against correct rms {rc:5.2f} px (worst {wc:+6.2f})"
                  + (f", against CLT rms {rl:5.2f} px (worst {wl:+6.2f})" if d1 else "") + f", {len(rs)} rows")
    write_csv(os.path.join(args.out, "patel_fig18.csv"),
              ["image", "box", "level", "rms_vs_correct_px", "worst_vs_correct_px", "rms_vs_clt_px",
               "worst_vs_clt_px", "rows"], rows)
    write_csv(os.path.join(args.out, "patel_fig18_isolines.csv"),
              ["image", "box", "level", "row", "distance", "x_measured", "x_correct", "x_clt"], lines)

    fig, ax = plt.subplots(1, 5, figsize=(20, 3.9), gridspec_kw={"width_ratios": [1, 1, 1, 1, 0.9]})
    ext = (X0, X0 + W * PX, Y0 - H * PX, Y0)
    for k, (label, v, d1, img, ms, cmp_) in enumerate(images):
        a = ax[k]
        a.imshow(img, cmap="gray", vmin=0, vmax=1, extent=ext)
        for (box, s), rs in measured[label].items():
            if not rs:
                continue
            y = [Y0 - (r[0] + 0.5) * PX for r in rs]
            a.plot([r[3] for r in rs], y, color="tab:blue", lw=0.8, ls="--")
            colour = "tab:red" if d1 else "tab:green" if label.startswith("blocker") else "tab:cyan"
            a.plot([r[2] for r in rs], y, color=colour, lw=0.9)
        title = f"{label}: {ms:.0f} ms" + (f", rmse {cmp_['rmse']:.3f}" if cmp_ else f" ({SPP} spp)")
        a.set_title(title, fontsize=8)
        a.set_xticks([]), a.set_yticks([])
        a.set_xlim(ext[0], ext[1]), a.set_ylim(ext[2], ext[3])
    a = ax[4]
    for label, _, d1, _, _, _ in images:
        for box, _, _, _ in BOXES:
            lo, hi = measured[label][(box, 0.1)], measured[label][(box, 0.9)]
            common = {r[0]: r for r in lo}
            pts = sorted((r[1], common[r[0]][2] - r[2]) for r in hi if r[0] in common)
            if pts:
                a.plot(*zip(*pts), ".", ms=2.5, label=f"{label}, {box} box")
    dd = np.linspace(0.3, 2.6, 100)
    width = SIGMA * (NormalDist().inv_cdf(0.9) - NormalDist().inv_cdf(0.1))
    a.plot(dd, width * dd, "k--", lw=0.8, label="correct: linear in d")
    for d1 in D1S:
        a.plot(dd, width * np.sqrt(dd * d1), "k:", lw=0.8)
    a.plot([], [], "k:", lw=0.8, label="CLT: sqrt(d d1), d1 = 1, 0.4")
    a.set_xlabel("distance d behind the box", fontsize=8)
    a.set_ylabel("penumbra width: x(S=0.1) - x(S=0.9)", fontsize=8)
    a.tick_params(labelsize=7)
    a.legend(fontsize=6, loc="upper left")
    fig.suptitle("Patel Fig. 18: isolines S = 0.1 ... 0.9 measured on the images (solid; cyan: reference, red: slab, "
                 "green: slab under render.model blocker) and the correct ones (dashed blue)", fontsize=9)
    fig.tight_layout()
    save_fig(fig, os.path.join(args.out, "patel_fig18.png"), 100)


if __name__ == "__main__":
    main()
