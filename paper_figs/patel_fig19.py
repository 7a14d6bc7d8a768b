#!/usr/bin/env python3
"""Patel et al. 2013, Fig. 19: preintegrated compositing. A slab of smoke whose transfer function
has a steep ramp (the detail value of improved noise, v in [-1, 1], mapped to nothing below 0.1
and to a dense, coloured medium above 0.2) over a white floor, rendered by the slab renderer at
slab spacings 0.04, 0.02, 0.01 and 0.005, with and without preintegration, against the Monte-Carlo
reference. With point samples of the transfer function per slab piece, a thin dense layer is hit
or missed (banding, error falling slowly with the slab count); preintegration integrates the
transfer function over each piece's range of detail values. The scene: scenes/patel_fig19.json
(the figure's images: e = 0.02, preintegrated), its slab spacing and preintegration swept.

Commands: `icshadow render SCENE --backend mc --spp 256 --aov stderr -o REF.exr --png REF.png`, then
`icshadow render SCENE --slab-spacing E [--preintegrate via the scene] --compare REF.exr`.
Writes patel_fig19.png (error against slabs, and the images at e = 0.02) and patel_fig19.csv
(slab spacing, preintegrated, slabs, rmse, rmse beyond the reference's noise, max error, ms), and
prints the slabs saved at equal error (log-log interpolation of the plain curve).
"""
import json
import math
import os
import sys
import tempfile

import numpy as np

import matplotlib

matplotlib.use("Agg")
import matplotlib.image as mpimg  # noqa: E402
import matplotlib.pyplot as plt  # noqa: E402

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "lib"))
from figutil import load_scene, parse_args, run_cli, save_fig, write_csv  # noqa: E402

SPACINGS = (0.04, 0.02, 0.01, 0.005)


def scene(e, pre):
    """scenes/patel_fig19.json (e = 0.02, preintegrated) at slab spacing e, preintegrated or not."""
    s = load_scene("patel_fig19")
    s["render"]["slab_spacing"] = e
    s["render"]["preintegrate"] = pre
    return s


def main():
    args = parse_args(__doc__)
    tmp = tempfile.mkdtemp(prefix="fig19")
    sf = os.path.join(tmp, "ref.json")
    with open(sf, "w") as f:
        json.dump(scene(SPACINGS[-1], False), f)
    ref, ref_png = os.path.join(tmp, "ref.exr"), os.path.join(tmp, "ref.png")
    mc = json.loads(run_cli(args.cli, ["render", sf, "--backend", "mc", "--spp", "256", "--aov", "stderr",
                                       "-o", ref, "--png", ref_png]))
    rows, pngs = [], {}
    for e in SPACINGS:
        for pre in (False, True):
            sfe = os.path.join(tmp, f"s{e}{pre}.json")
            with open(sfe, "w") as f:
                json.dump(scene(e, pre), f)
            png = os.path.join(tmp, f"slab{e}{pre}.png")
            s = json.loads(run_cli(args.cli, ["render", sfe, "--compare", ref, "--png", png]))
            c = s["compare"]
            rows.append([e, int(pre), s["slabs"], c["rmse"], c["rmse_beyond_noise"], c["max_error"],
                         s["ms_plan"] + s["ms_render"]])
            pngs[(e, pre)] = png
            print(f"e {e:g}{' preintegrated' if pre else '              '}: {s['slabs']:4d} slabs, rmse "
                  f"{c['rmse']:.4f} (beyond noise {c['rmse_beyond_noise']:.4f}), max {c['max_error']:.3f}, "
                  f"{s['ms_plan'] + s['ms_render']:.0f} ms")
    write_csv(os.path.join(args.out, "patel_fig19.csv"),
              ["slab_spacing", "preintegrated", "slabs", "rmse", "rmse_beyond_noise", "max_error", "ms"], rows)
    plain = [(r[2], r[4]) for r in rows if not r[1]]
    pre = [(r[2], r[4]) for r in rows if r[1]]
    # slabs the plain renderer needs for each preintegrated error (log-log interpolation)
    ls, le = np.log([p[0] for p in plain]), np.log([p[1] for p in plain])
    saved = []
    for n, err in pre:
        if min(le) <= math.log(err) <= max(le):
            need = math.exp(np.interp(math.log(err), le[::-1], ls[::-1]))
            saved.append((n, err, need))
            print(f"preintegrated {n} slabs (error {err:.4f}) = plain {need:.0f} slabs: {need / n:.2f}x")
    fig, ax = plt.subplots(1, 4, figsize=(15, 3.6), gridspec_kw={"width_ratios": [1.3, 1, 1, 1]})
    ax[0].loglog([p[0] for p in plain], [p[1] for p in plain], "o-", label="point samples per slab piece")
    ax[0].loglog([p[0] for p in pre], [p[1] for p in pre], "s-", label="preintegrated")
    ax[0].set_xlabel("slabs", fontsize=8), ax[0].set_ylabel("RMSE beyond the reference's noise", fontsize=8)
    ax[0].legend(fontsize=7), ax[0].grid(True, which="both", alpha=0.3), ax[0].tick_params(labelsize=7)
    for k, (img, t) in enumerate(((pngs[(0.02, False)], "e = 0.02, point samples"),
                                  (pngs[(0.02, True)], "e = 0.02, preintegrated"),
                                  (ref_png, f"reference, 256 spp ({mc['ms_render'] / 1e3:.1f} s)"))):
        ax[k + 1].imshow(mpimg.imread(img))
        ax[k + 1].set_title(t, fontsize=8)
        ax[k + 1].axis("off")
    fig.suptitle("Patel Fig. 19: preintegration against slab count (a steep transfer function)", fontsize=9)
    fig.tight_layout()
    save_fig(fig, os.path.join(args.out, "patel_fig19.png"), 100)


if __name__ == "__main__":
    main()
