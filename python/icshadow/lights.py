"""lights.py: Gaussian lights (docs/lights_format.md): lights files read and written, and lights
fitted to an environment map (docs/lightfit.md), through the C library."""
import os
from dataclasses import dataclass, field

import numpy as np

from ._lib import check, ffi, image_from_array, lib, msg_buffer, take_string, write_replacing


@dataclass
class Light:
    """A Gaussian light on the virtual light plane: mean (mx, my), covariance 2x2, linear RGB
    colour and weight (its luminance power when Y(colour) = 1)."""
    mean: np.ndarray
    cov: np.ndarray
    color: np.ndarray = field(default_factory=lambda: np.ones(3))
    weight: float = 1.0


def _from_c(c):
    return Light(np.array(list(c.mean)), np.array([[c.cov[0], c.cov[1]], [c.cov[1], c.cov[2]]]),
                 np.array(list(c.color)), c.weight)


def _to_c(lights):
    arr = ffi.new("ics_light[]", max(len(lights), 1))
    for k, l in enumerate(lights):
        m = np.asarray(l.mean, dtype=float).reshape(2)
        cv = np.asarray(l.cov, dtype=float).reshape(2, 2)
        values = np.concatenate([m, cv.ravel(), np.asarray(l.color, dtype=float).ravel(), [l.weight]])
        if not np.isfinite(values).all():
            raise ValueError(f"lights[{k}]: a NaN or infinite value (a lights file holds finite numbers)")
        arr[k].mean = list(m)
        arr[k].cov = [cv[0, 0], cv[0, 1], cv[1, 1]]
        arr[k].color = list(np.asarray(l.color, dtype=float).reshape(3))
        arr[k].weight = float(l.weight)
    return arr


def read_lights(path):
    """The lights of a lights file; icshadow.Error with the file, line and key at fault."""
    out, n, msg = ffi.new("ics_light **"), ffi.new("int *"), msg_buffer()
    check(lib.ics_lightsfile_read(os.fsencode(path), out, n, msg, len(msg)), msg)
    try:
        return [_from_c(out[0][k]) for k in range(n[0])]
    finally:
        lib.icspy_free(out[0])


def lights_json(lights):
    """The lights file text `icshadow fit-light` writes for these lights."""
    return take_string(lib.icspy_lights_json(_to_c(lights), len(lights)), "lights_json")


def write_lights(path, lights):
    """Writes a lights file: the whole file or, on an error, nothing (a temporary file in the same
    folder renamed over path)."""
    text = lights_json(lights)

    def write(tmp):
        with open(tmp, "w", encoding="utf-8") as f:
            f.write(text)

    write_replacing(path, "write_lights", write)


def _env_image(env):
    if isinstance(env, (str, bytes, os.PathLike)):
        out, msg = ffi.new("ics_image **"), msg_buffer()
        check(lib.ics_exr_read(os.fsencode(env), out, msg, len(msg)), msg)
        return ffi.gc(out[0], lib.ics_image_destroy)
    return image_from_array(env, "fit_light: env")


def _lights_arg(lights):
    """(K, auto): lights is K, "auto" or "auto:KMAX" (the CLI's --lights)"""
    if isinstance(lights, str):
        if lights == "auto":
            return lib.ICS_LIGHTFIT_AUTO_KMAX, True
        if lights.startswith("auto:") and lights[5:].isdigit():
            kmax = int(lights[5:])
            if 1 <= kmax <= lib.ICS_LIGHTFIT_MAX_K:
                return kmax, True
        raise ValueError(f"fit_light: lights: expected 1..{lib.ICS_LIGHTFIT_MAX_K}, \"auto\" or "
                         f"\"auto:KMAX\", got {lights!r}")
    if not 1 <= int(lights) <= lib.ICS_LIGHTFIT_MAX_K:
        raise ValueError(f"fit_light: lights: expected 1..{lib.ICS_LIGHTFIT_MAX_K}, got {lights}")
    return int(lights), False


_REPORT_KEYS = ("k_fit", "iterations", "samples", "pixels", "energy_total", "energy_front",
                "energy_cutoff", "energy_kept", "cutoff_loss", "loglik", "l1", "l2", "edge")


def _report(rep):
    out = {k: getattr(rep, k) for k in _REPORT_KEYS}
    out["converged"] = bool(rep.converged)
    return out


def fit_light(env, lights=3, max_angle=80.0, seed=1, max_samples=0, max_iter=300, tol=1e-9):
    """Fits Gaussian lights to a latitude-longitude environment map (a path to an EXR, or an
    array (height, width, 3 or 4) of linear RGB, row 0 at the top), as `icshadow fit-light`
    does. lights: K, or "auto" / "auto:KMAX": every K = 1..KMAX fitted and the fewest lights
    within max(1 %, 2 x the best L1) kept (docs/lightfit.md "How many lights"). Returns (lights,
    report): report is a dict of the kept fit's numbers (k_fit, iterations, l1, l2, edge,
    converged, the energies); with auto also "k" (the K kept) and "fits" (every K's report)."""
    kmax, auto = _lights_arg(lights)
    img = _env_image(env)
    p = ffi.new("ics_lightfit_params *")
    lib.ics_lightfit_params_init(p)
    p.max_angle_deg, p.seed = float(max_angle), int(seed)
    p.max_samples, p.max_iter, p.tol = int(max_samples), int(max_iter), float(tol)
    reps = ffi.new("ics_lightfit_report[]", kmax)
    fits = []
    for k in (range(1, kmax + 1) if auto else [kmax]):
        p.k = k
        out = ffi.new("ics_light[]", k)
        check(lib.ics_lightfit(img, p, out, reps + (k - 1)), context=f"fit_light: K = {k}: ")
        fits.append([_from_c(out[i]) for i in range(reps[k - 1].k_fit)])
    if not auto:
        return fits[0], _report(reps[kmax - 1])
    kc = lib.ics_lightfit_auto_choice(reps, kmax)
    report = _report(reps[kc - 1])
    report["k"] = kc
    report["fits"] = [_report(reps[k]) for k in range(kmax)]
    return fits[kc - 1], report
