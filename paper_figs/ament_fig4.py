#!/usr/bin/env python3
"""Reproduce Ament et al. 2014, Fig. 4 (chirp occluder: box vs Gaussian filtering) from the CLI.

A directional light straight above a volumetric occluder whose extinction is a linear chirp in
x casts a shadow on the receiver plane below. `icshadow bench sat2d --chirp-csv` writes, per
receiver column: the extinction sigma(x), the unfiltered optical depth tau(x) (single
scattering), the box-filtered tau (SAT box sum, filter width 9 voxels = 37 columns) and the
Gaussian-filtered tau (same variance, brute-force convolution), with their transmittances.
This script checks the SAT box filter against an independent numpy moving sum, then plots
(a) the occluder, (b) the transmittance on the receiver, (c) the spectra: the box filter's
transfer function (a sinc) has zeros at k/37 cycles per column; the chirp frequencies there
are erased (and between zeros of odd order the contrast is inverted), while the Gaussian damps
steadily. The positions where the local chirp frequency hits a zero are marked in (b).
Writes ament_fig4_chirp.csv, ament_fig4_zeros.csv and ament_fig4.png into --out.
"""
import os
import sys

import numpy as np

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "lib"))
from figutil import parse_args, run_cli, save_fig, write_csv  # noqa: E402

# the set-up of cli/bench_sat.c (chirp_csv): 4 columns per voxel
W, H, Y0, Y1, HALF = 708, 64, 24, 40, 18
F0, F1 = 1.0 / 96, 1.0 / 6


def main():
    args = parse_args(__doc__)
    path = os.path.join(args.out, "ament_fig4_chirp.csv")
    run_cli(args.cli, ["bench", "sat2d", "--chirp-csv", path])
    d = np.genfromtxt(path, delimiter=",", names=True)
    if len(d) != W:
        sys.exit("fig4: expected %d rows, got %d" % (W, len(d)))
    sigma, tau = d["sigma"], d["tau"]

    # independent check of the SAT box filter: numpy moving sum of tau (zero outside)
    box_np = np.convolve(tau, np.ones(2 * HALF + 1), mode="same") / (2 * HALF + 1)
    worst = float(np.max(np.abs(box_np - d["tau_box"])))
    print("fig4: SAT box filter vs numpy moving sum, max abs difference %.3g" % worst)
    if worst > 1e-9 * max(1.0, float(np.max(tau))):
        sys.exit("fig4: SAT box filter disagrees with the moving sum (%.3g)" % worst)
    # tau is the column sum of the slab: (Y1 - Y0) * sigma
    if np.max(np.abs(tau - (Y1 - Y0) * sigma)) > 1e-5 * np.max(tau):
        sys.exit("fig4: tau is not the column integral of sigma")

    # spectra (per receiver column; frequency in cycles per column)
    n = 4 * W
    f = np.fft.rfftfreq(n)
    spec = np.abs(np.fft.rfft(tau - tau.mean(), n))
    Lb = 2 * HALF + 1
    hb = np.abs(np.sinc(f * Lb))  # box transfer function (np.sinc(x) = sin(pi x)/(pi x))
    gs = Lb / np.sqrt(12.0)
    hg = np.exp(-2 * (np.pi * f * gs) ** 2)
    # the zeros of the box response inside the chirp band and where the chirp hits them
    ks = np.arange(1, 20)
    fz = ks / Lb
    fz = fz[(fz > F0) & (fz < F1)]
    xz = (fz - F0) / (F1 - F0) * W  # local frequency f0 + (f1 - f0) x / W (in columns)
    write_csv(os.path.join(args.out, "ament_fig4_zeros.csv"), ["zero_freq_cycles_per_column", "x_voxels"], zip(fz, xz / 4.0))
    # at those positions the box-filtered shadow is flat: its local contrast vs the unfiltered one
    x = d["x"]
    print("fig4: box-filter zeros at %s cycles/column -> x = %s voxels"
          % (np.array2string(fz, precision=4), np.array2string(xz / 4.0, precision=1)))

    fig, ax = plt.subplots(3, 1, figsize=(10, 9))
    img = np.zeros((H, W))
    img[Y0:Y1, :] = sigma[None, :]
    ax[0].imshow(img, origin="lower", aspect="auto", cmap="Greys", extent=[0, W / 4.0, 0, H / 4.0])
    ax[0].axhline(0, color="k", lw=3)
    ax[0].set_title("(a) chirp occluder (extinction), light from above, receiver at the bottom")
    ax[0].set_ylabel("height [voxels]")
    ax[1].plot(x, d["T_none"], color="0.6", lw=0.8, label="unfiltered (single scattering)")
    ax[1].plot(x, d["T_box"], "b-", label="box filter, 9 voxels (CSAT / SAT)")
    ax[1].plot(x, d["T_gauss"], "r-", label="Gaussian, same variance (brute force)")
    for xv in xz / 4.0:
        ax[1].axvline(xv, color="b", ls=":", lw=0.8)
    ax[1].set_xlim(0, W / 4.0)
    ax[1].set_xlabel("x [voxels]")
    ax[1].set_ylabel("transmittance on the receiver")
    ax[1].set_title("(b) shadow on the receiver; dotted: chirp frequency at a zero of the box response")
    ax[1].set_ylim(0, 1.3)
    ax[1].legend(loc="upper center", ncol=3, fontsize=8)
    ax[2].semilogy(f, spec + 1e-12, color="0.6", lw=0.8, label="|F(tau)|")
    ax[2].semilogy(f, spec * hb + 1e-12, "b-", lw=0.8, label="|F(tau) x sinc| (box)")
    ax[2].semilogy(f, spec * hg + 1e-12, "r-", lw=0.8, label="|F(tau) x Gaussian|")
    for fv in fz:
        ax[2].axvline(fv, color="b", ls=":", lw=0.8)
    ax[2].set_xlim(0, 0.2)
    ax[2].set_ylim(1e-3, None)
    ax[2].set_xlabel("frequency [cycles per column]")
    ax[2].set_title("(c) spectra: the box filter erases the chirp at its zeros, the Gaussian damps steadily")
    ax[2].legend(loc="upper right", fontsize=8)
    fig.tight_layout()
    png = os.path.join(args.out, "ament_fig4.png")
    save_fig(fig, png, 110)
    print("fig4: wrote %s" % png)


if __name__ == "__main__":
    main()
