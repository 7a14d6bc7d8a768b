/* icshadow/ellipse.h — ellipse variance functions and the N-sample elliptical kernel
 * (Patel et al. 2013, Sec. 3.4 and Appendix A.7).
 *
 * Points equidistant in arc length on an ellipse, averaged over a uniform rotational offset,
 * are distributed uniformly in arc length; their x-variance is what the functions below give.
 *   ics_ellipse_varx(b): ellipse with x-radius 1 and y-radius b >= 0 (b > 1 allowed).
 *   ics_ellipse_vx(t)  : unit ellipse a = 1 - t, b = t, t in [0, 1]  (paper's abToVarx).
 *   ics_ellipse_vy(t)  : its y-variance, = vx(1 - t).
 *   ics_ellipse_ratio(t)      = vy(t) / vx(t), increasing from 0 (t = 0) to +inf (t = 1).
 *   ics_ellipse_ratio_to_t(r) : inverse of ratio for r in [0, +inf] (paper's ratioToab).
 * Outside the domain (or NaN) they return NaN; errno is never touched.
 * ACCURACY (measured against Patel's closed form in 320-bit MPFR, not proved; tests/test_ellipse.c
 * asserts these same numbers; method and worst inputs in ellipse.c and docs/ellipse.md):
 *   ics_ellipse_varx, ics_ellipse_vx, ics_ellipse_vy   <= 0.75 ulp
 *   ics_ellipse_ratio, ics_ellipse_ratio_to_t          <= 1.0 ulp
 *   exception: when the result of ics_ellipse_vy or ics_ellipse_ratio is subnormal (t below
 *   ~1.5e-154), the bound is 1.0 ulp of 2^-1074 (the smallest subnormal): the exponent is applied
 *   last, so such results are rounded twice.
 * Patel's closed form (Appendix A.7) takes EllipticK/E of the MODULUS sqrt(1 - b^2), i.e. the
 * parameter m = 1 - b^2 (settled by quadrature, docs/ellipse.md). var_x(0) = 1/3, var_x(1) = 1/2,
 * var_x(b) + var_x(1/b) = 1, var_x(+inf) = 2/3. */
#ifndef ICSHADOW_ELLIPSE_H
#define ICSHADOW_ELLIPSE_H

#include "icshadow/status.h"

#ifdef __cplusplus
extern "C" {
#endif

ICS_API double ics_ellipse_varx(double b);
ICS_API double ics_ellipse_vx(double t);
ICS_API double ics_ellipse_vy(double t);
ICS_API double ics_ellipse_ratio(double t);
ICS_API double ics_ellipse_ratio_to_t(double rat);

#define ICS_ELLIPSE_MAX_SAMPLES 4096

/* Shape of an elliptical kernel for a target covariance (sigma_x^2, sigma_y^2, rotation alpha). */
typedef struct ics_ellipse_shape {
  double a;         /* radius along the kernel's rotated x axis */
  double b;         /* radius along the kernel's rotated y axis */
  double angle_deg; /* rotation alpha of the x axis, degrees counter-clockwise from +x */
  double t;         /* unit-ellipse parameter: a = (1 - t) s, b = t s */
  int nsamples;     /* taps actually produced: 1 for a point light (both variances 0) */
} ics_ellipse_shape;

/* The N-sample elliptical kernel of covariance R(alpha) diag(varx, vary) R(alpha)^T:
 * N points equidistant in arc length on the ellipse with radii a, b, the first at arc-length
 * fraction `offset` (in [0, 1); any finite value is reduced mod 1) of the perimeter measured
 * counter-clockwise in the kernel's own frame from the end of the MAJOR axis, (a, 0) when
 * varx >= vary and (0, b) when vary > varx, then rotated by alpha. So at offset 0 a line light's
 * 2 taps are its segment's ends in either orientation ((+-sqrt(3 varx), 0) for vary = 0,
 * (0, +-sqrt(3 vary)) for varx = 0), and kernel(vy, vx, alpha) = kernel(vx, vy, alpha + 90)
 * exactly for every offset. Averaged over a
 * uniform offset the taps have exactly that covariance (zero mean). vary = 0 gives a segment
 * (t = 0, b = 0, a = sqrt(3 varx)), varx = 0 the segment along y (t = 1); both 0 a point light:
 * one tap at the origin, shape->nsamples = 1, a = b = 0, t = 1/2. xy must hold 2 * nsamples
 * doubles; 2 * shape->nsamples are written (x0, y0, x1, y1, ...) when xy != NULL.
 * Errors: ICS_ERR_NAN (any argument NaN), ICS_ERR_NEGATIVE_VARIANCE, ICS_ERR_INFINITE (variance
 * or angle infinite), ICS_ERR_RANGE (nsamples outside 1..ICS_ELLIPSE_MAX_SAMPLES, offset not
 * finite), ICS_ERR_INVALID_ARG (shape NULL). */
ICS_API ics_status ics_ellipse_kernel(double varx, double vary, double angle_deg, int nsamples,
                                      double offset, ics_ellipse_shape *shape, double *xy);

#ifdef __cplusplus
}
#endif
#endif
