"""theory.py: the shadow behind an edge for a 1D light, as `icshadow isoline` computes it
(docs/theory.md): 1D lights and the isolines of the correct, CLT and iterated shadows."""
import math

import numpy as np

from ._lib import check, ffi, lib, msg_buffer


class Light1D:
    """A 1D light (its cdata freed when collected): Light1D.gauss(mean, var),
    Light1D.box(lo, hi) or Light1D.mix(weights, means, variances) (`icshadow isoline --light
    gauss:MU,VAR | box:LO,HI | mix:W,MU,VAR;...`)."""

    def __init__(self, create, what):
        out = ffi.new("ics_light1d **")
        check(create(out), context=f"{what}: ")
        self._c = ffi.gc(out[0], lib.ics_light1d_destroy)

    @classmethod
    def gauss(cls, mean, var):
        return cls(lambda out: lib.ics_light1d_create_gauss(out, float(mean), float(var)), "gauss")

    @classmethod
    def box(cls, lo, hi):
        return cls(lambda out: lib.ics_light1d_create_box(out, float(lo), float(hi)), "box")

    @classmethod
    def mix(cls, weights, means, variances):
        w, mu, var = (np.require(np.asarray(v, dtype=np.float64), requirements="C")
                      for v in (weights, means, variances))
        if not (w.ndim == mu.ndim == var.ndim == 1 and len(w) == len(mu) == len(var)):
            raise ValueError("mix: weights, means and variances must be three lists of one length")
        if not 1 <= len(w) <= lib.ICS_LIGHT1D_MAX_MIX:
            raise ValueError(f"mix: 1..{lib.ICS_LIGHT1D_MAX_MIX} components, got {len(w)}")
        return cls(lambda out: lib.ics_light1d_create_mix(
            out, len(w), ffi.from_buffer("double[]", w), ffi.from_buffer("double[]", mu),
            ffi.from_buffer("double[]", var)), "mix")


def isoline(light, level, distance, model="correct", d1=None, slab=None):
    """The position x of shadow level `level` in (0, 1) at distance `distance` >= 0 behind the
    edge (opaque for x > 0) under `light` (a Light1D): model "correct" (Eq. 16), "clt" (the CLT
    model, needs d1) or "iterative" (the shadow actually iterated with the Dirac kernel over
    distance / slab slabs, needs d1 and slab; its work bounded as the CLI's). Bit for bit what
    `icshadow isoline` prints."""
    if not isinstance(light, Light1D):
        raise TypeError(f"isoline: expected a Light1D, got {type(light).__name__}")
    if model not in ("correct", "clt", "iterative"):
        raise ValueError(f"isoline: model: unknown {model!r} (correct, clt, iterative)")
    level, distance = float(level), float(distance)
    if not 0 < level < 1:
        raise ValueError(f"isoline: level must be in (0, 1), got {level!r}")
    if not distance >= 0:
        raise ValueError(f"isoline: distance must be >= 0, got {distance!r}")
    if model != "correct" and not (d1 is not None and float(d1) > 0):
        raise ValueError(f"isoline: model {model} needs d1 > 0, got {d1!r}")
    if model == "correct":
        x = lib.ics_isoline_correct(light._c, level, distance)
    elif model == "clt":
        x = lib.ics_isoline_clt(light._c, level, distance, float(d1))
    else:
        if not (slab is not None and float(slab) > 0):
            raise ValueError(f"isoline: model iterative needs slab > 0, got {slab!r}")
        opts, out, msg = ffi.new("ics_iter1d_opts *"), ffi.new("double *"), msg_buffer()
        lib.ics_iter1d_opts_init(opts)
        check(lib.ics_isoline_iterative_bounded(light._c, level, distance, float(d1), float(slab),
                                                opts, out, ffi.NULL, msg, len(msg)), msg,
              context="isoline: ")
        x = out[0]
    if not math.isfinite(x):
        raise ValueError(f"isoline: the position is not finite ({x}): distance, d1 and the light's "
                         "mean or variance overflow double precision together")
    return x
