#!/usr/bin/env python3
"""blocker_blend.py — the blend weight of render.model blocker against its least-squares optimum
(docs/renderer.md "Models": blocker-aware penumbrae).

Behind a straight edge at distance d the two light-buffer sets give penumbrae that are normal
cdfs of standard deviation sqrt(d d1 s) sigma (the sharp set, s = 1/4) and sqrt(d d1) sigma (the
first set); the correct one has d sigma. The blend (1 - t) sharp + t first is linear in t, so the
t whose profile fits the correct one best in least squares over the penumbra (x in [-6, 6]
correct standard deviations) is closed form: t* = <C - A, B - A> / <B - A, B - A> with A, B, C
the sharp, first and correct profiles. Printed for r = d / (d1 s) beside the renderer's
t = log(r) / log(1 / s) (0 below r = 1, 1 above r = 1 / s) and the blend linear in d, with each
one's RMS misfit. Standard library only.

usage: python3 analysis/blocker_blend.py
"""
import math
from statistics import NormalDist

S = 0.25  # ICS_BLOCKER_SHARP (gpu/core/plan_internal.h)
XS = [-6 + 12 * i / 4000 for i in range(4001)]  # in units of the correct standard deviation


def profiles(r):
    """the sharp, first and correct penumbrae at d = r d1 s, sampled at XS"""
    s_sharp, s_first = math.sqrt(1 / r), math.sqrt(1 / (r * S))  # over the correct sd
    cdf = NormalDist().cdf
    return ([cdf(x / s_sharp) for x in XS], [cdf(x / s_first) for x in XS], [cdf(x) for x in XS])


def misfit(t, a, b, c):
    return math.sqrt(sum((ai + t * (bi - ai) - ci) ** 2 for ai, bi, ci in zip(a, b, c)) / len(XS))


def main():
    print("r = d/(d1 s)  t least squares (RMS)   t renderer (RMS)   t linear in d (RMS)")
    for r in (0.25, 0.5, 0.75, 1.5, 2, 2.5, 3, 3.5):
        a, b, c = profiles(r)
        ba = [bi - ai for ai, bi in zip(a, b)]
        t_opt = sum((ci - ai) * d for ai, ci, d in zip(a, c, ba)) / sum(d * d for d in ba)
        t_log = min(max(math.log(r) / math.log(1 / S), 0), 1)
        t_lin = (r - 1) / (1 / S - 1)
        print(f"{r:11.2f}  {t_opt:7.3f} ({misfit(t_opt, a, b, c):.4f})     {t_log:6.3f} ({misfit(t_log, a, b, c):.4f})"
              f"     {t_lin:6.3f} ({misfit(t_lin, a, b, c):.4f})")


if __name__ == "__main__":
    main()
