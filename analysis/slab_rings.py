#!/usr/bin/env python3
"""slab_rings.py — the rings that coarse slabs draw on dense smoke (docs/renderer.md "Which
model"): a uniform smoke sphere (radius 0.62, extinction 14, transport 0.25) seen head-on under
the default scene's first light (variance 0.012 x 0.004, turned 30 degrees) placed on the view
axis, rendered by the slab renderer under each model and slab spacing. Its pixels (within 0.8 of
the radius) are binned by where the ray enters the sphere within its slab, frac(z_entry / e): a
render without rings has the same mean in every bin. Prints, per model and spacing, the bins'
means, their peak-to-peak spread and their standard deviation. With a point light (variance 0)
every bin is equal: the rings come from the per-slab blur of light attenuated at a piece whose
depth within the slab varies across the sphere.

usage: slab_rings.py [--models patel,blocker] [--spacings 0.015,0.03,0.045] [--bins 9]
(the Python package: PYTHONPATH=build/python-pkg, docs/python.md)
"""
import argparse

import numpy as np

import icshadow

RADIUS, SIZE = 0.62, 400


def scene(e):
    return {"camera": {"projection": "orthographic", "eye": [0, 0, 3], "target": [0, 0, 0],
                       "up": [0, 1, 0], "height": 2.0, "resolution": [SIZE, SIZE]},
            "render": {"slab_spacing": e, "d1": 1.0, "seed": 1},
            "lights": [{"mean": [0.0, 0.0], "var": [0.012, 0.004], "angle_deg": 30}],
            "materials": {"smoke": {"color": [1, 1, 1], "extinction": 14,
                                    "transport": [0.25, 0.25, 0.25]}},
            "objects": [{"shape": "sphere", "center": [0, 0, 0], "radius": RADIUS,
                         "material": "smoke"}]}


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--models", default="patel,blocker")
    ap.add_argument("--spacings", default="0.015,0.03,0.045")
    ap.add_argument("--bins", type=int, default=9)
    a = ap.parse_args()
    x = (np.arange(SIZE) + 0.5) / SIZE * 2 - 1
    X, Y = np.meshgrid(x, -x)
    r = np.hypot(X, Y)
    inside = r < 0.8 * RADIUS
    z_entry = (3 - np.sqrt(np.maximum(RADIUS ** 2 - r ** 2, 0)))[inside]  # view depth
    print("model,spacing,bin_means,peak_to_peak,sd")
    for e in (float(v) for v in a.spacings.split(",")):
        b = np.minimum((np.mod(z_entry / e, 1.0) * a.bins).astype(int), a.bins - 1)
        for m in a.models.split(","):
            g = icshadow.render(scene(e), model=m).rgba[:, :, 0][inside]
            means = np.array([g[b == k].mean() for k in range(a.bins)])
            print(f"{m},{e:g},{' '.join(f'{v:.4f}' for v in means)},"
                  f"{means.max() - means.min():.4f},{means.std():.4f}", flush=True)


if __name__ == "__main__":
    main()
