#!/usr/bin/env python3
"""Patel et al. 2013, Fig. 11: the kernel members at low and high light variance, with the
Monte-Carlo reference beside them. The contract example's disk (radius 0.5, 1 above a white
receiver; d1 = d = 1, where the slab renderer's shadow is the correct one up to its
discretisation) under a light of mean (0.3, -0.1) and covariance 0.004 I (low) or 0.06 I (high),
128 x 128, slab spacing 0.01; members: 2- and 3-sample ellipse, Poisson 8, 19 x 19 Gaussian,
5 x 5 top-hat (each with its default compensation).

Commands: `icshadow render SCENE --backend mc --spp 256 --aov stderr -o REF.exr --png REF.png`, then
`icshadow render SCENE --kernel K --samples N --compare REF.exr --png SLAB.png` per member.
Writes patel_fig11.png (rows: members and the reference; columns: low, high) and patel_fig11.csv
(variance, member, rmse, rmse beyond the reference's noise, max error, ms).
"""
import json
import os
import sys
import tempfile

import matplotlib

matplotlib.use("Agg")
import matplotlib.image as mpimg  # noqa: E402
import matplotlib.pyplot as plt  # noqa: E402

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "lib"))
from fig11_setup import HIGH_VAR, LOW_VAR, scene  # noqa: E402
from figutil import parse_args, run_cli, save_fig, write_csv  # noqa: E402

VARIANCES = (("low", LOW_VAR), ("high", HIGH_VAR))
MEMBERS = (("ellipse", 2), ("ellipse", 3), ("poisson", 8), ("gauss", 19), ("tophat", 5))


def main():
    args = parse_args(__doc__)
    tmp = tempfile.mkdtemp(prefix="fig11")
    rows, pngs, refs = [], {}, {}
    for name, var in VARIANCES:
        sf = os.path.join(tmp, f"{name}.json")
        with open(sf, "w") as f:
            json.dump(scene(var), f)
        ref, ref_png = os.path.join(tmp, f"{name}_ref.exr"), os.path.join(tmp, f"{name}_ref.png")
        mc = json.loads(run_cli(args.cli, ["render", sf, "--backend", "mc", "--spp", "256", "--aov", "stderr",
                                           "-o", ref, "--png", ref_png]))
        refs[name] = (ref_png, mc)
        for kernel, n in MEMBERS:
            png = os.path.join(tmp, f"{name}_{kernel}{n}.png")
            s = json.loads(run_cli(args.cli, ["render", sf, "--kernel", kernel, "--samples", str(n),
                                              "--compare", ref, "--png", png]))
            c = s["compare"]
            rows.append([var, f"{kernel}{n}", c["rmse"], c["rmse_beyond_noise"], c["max_error"],
                         s["ms_plan"] + s["ms_render"]])
            pngs[(name, kernel, n)] = (png, c)
            print(f"{name} variance {var:g}, {kernel}{n}: rmse {c['rmse']:.4f} (beyond noise "
                  f"{c['rmse_beyond_noise']:.4f}), max {c['max_error']:.3f}, {s['ms_plan'] + s['ms_render']:.0f} ms "
                  f"(reference {mc['ms_render']:.0f} ms)")
    write_csv(os.path.join(args.out, "patel_fig11.csv"),
              ["variance", "member", "rmse", "rmse_beyond_noise", "max_error", "ms"], rows)
    fig, ax = plt.subplots(len(VARIANCES), len(MEMBERS) + 1, figsize=(2.3 * (len(MEMBERS) + 1), 2.6 * len(VARIANCES)))
    for r, (name, var) in enumerate(VARIANCES):
        for k, (kernel, n) in enumerate(MEMBERS):
            png, c = pngs[(name, kernel, n)]
            ax[r][k].imshow(mpimg.imread(png))
            ax[r][k].set_title(f"{kernel}{n}: rmse {c['rmse_beyond_noise']:.4f}", fontsize=8)
            ax[r][k].axis("off")
        ax[r][-1].imshow(mpimg.imread(refs[name][0]))
        ax[r][-1].set_title(f"reference, {name} variance {var:g}", fontsize=8)
        ax[r][-1].axis("off")
    fig.suptitle("Patel Fig. 11: kernel members at low and high variance against the reference "
                 "(rmse beyond its noise)", fontsize=9)
    fig.tight_layout()
    save_fig(fig, os.path.join(args.out, "patel_fig11.png"), 100)


if __name__ == "__main__":
    main()
