"""numerics.py: the elliptic integrals and the ellipse functions of libicshadow over numpy
arrays (docs/ellint.md, docs/ellipse.md), each value computed by the C library's own function,
so bit for bit what C gets; and the elliptical kernel's taps."""
from dataclasses import dataclass

import numpy as np

from ._lib import check, ffi, lib, real_array


def map_function(cname, x, name):
    """The library's double -> double function cname over x (a number or an array of real
    numbers): an array of x's shape, a float for a number."""
    a = real_array(x, name)
    out = np.empty(a.shape, dtype=np.float64)
    if a.size:
        lib.icspy_map(ffi.addressof(lib, cname), ffi.from_buffer("double[]", a),
                      ffi.from_buffer("double[]", out), a.size)
    return out if np.ndim(x) else float(out)


def _mapped(cname, doc):
    def f(x):
        return map_function(cname, x, cname[4:])

    f.__name__ = cname[4:]
    f.__doc__ = doc + "\n\nx: a number or an array of real numbers; returns the same shape (a float for a number)."
    return f


ellint_k = _mapped("ics_ellint_k", "K(m), the complete elliptic integral of the first kind (parameter m = k^2).")
ellint_e = _mapped("ics_ellint_e", "E(m), the complete elliptic integral of the second kind.")
ellint_k_m1 = _mapped("ics_ellint_k_m1", "K as a function of the complementary parameter m1 = 1 - m.")
ellint_e_m1 = _mapped("ics_ellint_e_m1", "E as a function of the complementary parameter m1 = 1 - m.")
ellipse_varx = _mapped("ics_ellipse_varx", "varx(b): the x variance of the unit-perimeter-parameter ellipse with radii (1, b).")
ellipse_vx = _mapped("ics_ellipse_vx", "V_x(t): the x variance of the ellipse a = 1 - t, b = t (Patel Sec. 3.4).")
ellipse_vy = _mapped("ics_ellipse_vy", "V_y(t) = V_x(1 - t).")
ellipse_ratio = _mapped("ics_ellipse_ratio", "V_y(t) / V_x(t).")
ellipse_ratio_to_t = _mapped("ics_ellipse_ratio_to_t", "t from the ratio vary / varx (ratioToab's t).")


@dataclass
class EllipseKernel:
    """The N-sample elliptical kernel: xy (N, 2) tap offsets, each of weight 1/N; a, b the
    radii along the kernel's rotated axes, angle_deg its rotation, t the unit-ellipse parameter."""
    xy: np.ndarray
    a: float
    b: float
    angle_deg: float
    t: float


def ellipse_kernel(varx, vary, angle_deg=0.0, nsamples=2, offset=0.0):
    """Taps of covariance R(angle) diag(varx, vary) R(angle)^T (docs/ellipse.md): nsamples points
    equidistant in arc length on the ellipse, the first at arc-length fraction `offset`. A point
    light (both variances 0) gives one tap at the origin. Raises icshadow.Error for NaN, negative
    or infinite variances and nsamples out of range, as the C library does."""
    n = int(nsamples)
    shape = ffi.new("ics_ellipse_shape *")
    args = (float(varx), float(vary), float(angle_deg), n, float(offset), shape)
    check(lib.ics_ellipse_kernel(*args, ffi.NULL), context="ellipse_kernel: ")  # checked first
    xy = np.zeros((n, 2))
    check(lib.ics_ellipse_kernel(*args, ffi.from_buffer("double[]", xy)), context="ellipse_kernel: ")
    return EllipseKernel(xy[: shape.nsamples].copy(), shape.a, shape.b, shape.angle_deg, shape.t)
