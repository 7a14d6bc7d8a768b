/* icshadow/light.h — lights on the virtual light plane (Patel et al. 2013, Sec. 3.2, 3.4,
 * Eq. 7/15) and 1D light functions for the analysis of shadows behind an edge.
 *
 * Frame (docs/architecture.md "Frames and file formats"): a distant light behind the viewer,
 * direction toward the light (dx, dy, dz) with dz > 0, maps to the virtual light plane point
 * (dx/dz, dy/dz) = (tan wx, tan wy); wx, wy are the x-tilt and y-tilt angles in DEGREES.
 * |w| >= 90 degrees has no point on the plane: rejected (NaN / ICS_ERR_RANGE).
 *
 * Precision near 90 degrees: ics_light_tan_deg reduces |w| > 45 to cot(90 - |w|) where 90 - |w| is
 * exact (Sterbenz), so its error is ~1 ulp of the result at every representable angle (the
 * naive tan(w * pi / 180) loses up to 1/(90 - w) ulps-of-degree: ~1e-12 relative at
 * 90 - 2^-20). The problem itself is ill-conditioned: the condition number of w -> tan w is
 * ics_light_tilt_condition(w) = 2 w / sin(2 w) (w in radians), ~ pi/2 / (90 - w in rad), so an
 * angle known to 1 ulp gives a relative error of ulp(w) * cond / |w|. See docs/theory.md.
 *
 * Covariance: [[cxx, cxy], [cxy, cyy]] = R(alpha) diag(varx, vary) R(alpha)^T, alpha in degrees
 * counter-clockwise from +x (varx is the variance along the rotated x axis).
 *
 * Kernel mapping (Eq. 7/15): slab spacing e > 0, optimal distance d1 > 0:
 *   mu_k = -e mu_l,  Sigma_k = d1 e Sigma_l.
 * Then n = d/e iterations have mean -d mu_l and covariance d d1 Sigma_l, which equals the
 * correct shadow's d^2 Sigma_l at d = d1 (Eq. 8). */
#ifndef ICSHADOW_LIGHT_H
#define ICSHADOW_LIGHT_H

#include <stddef.h>
#include <stdio.h>

#include "icshadow/status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ---- tilt angles ---- */

/* tan of an angle in degrees, accurate near +-90 (see above); NaN for |w| >= 90 or NaN/inf. */
ICS_API double ics_light_tan_deg(double w_deg);
/* Condition number |w tan'(w) / tan(w)| = 2w/sin(2w) of the tilt map (1 at w = 0);
 * NaN for |w| >= 90. */
ICS_API double ics_light_tilt_condition(double w_deg);

/* ---- 2D Gaussian lights ---- */

/* The one Gaussian light type of the library (lights files, ics_lightfit, ics_envmap_render;
 * docs/lights_format.md "What weight and colour mean"). Light k contributes
 * weight_k color_k g(x; mean_k, cov_k) to the light function on the plane, so weight * color is
 * its RGB power (map units x steradian). Fitted lights (and the default white colour, whose
 * luminance 0.2126 + 0.7152 + 0.0722 is 1) have Y(color) = 1, so weight is the luminance power. */
typedef struct ics_light {
  double mean[2];  /* (mu_x, mu_y) on the virtual light plane */
  double cov[3];   /* cxx, cxy, cyy */
  double color[3]; /* linear RGB power per unit weight (>= 0; luminance 1 for fitted lights) */
  double weight;   /* >= 0; the luminance power when Y(color) = 1 */
} ics_light;

/* R(alpha) diag(varx, vary) R(alpha)^T (cos, sin of alpha exact at multiples of 90 degrees and
 * ~1 ulp relative near them). ICS_ERR_NAN / ICS_ERR_INFINITE / ICS_ERR_NEGATIVE_VARIANCE on bad
 * input. */
ICS_API ics_status ics_light_cov_from_eig(double varx, double vary, double alpha_deg,
                                          double cov[3]);
/* Inverse: varx >= vary, alpha in (-90, 90]; ICS_ERR_INVALID_ARG if cov is not symmetric
 * positive semidefinite (up to rounding: eigenvalues >= -8 eps * trace are clamped to 0). */
ICS_API ics_status ics_light_cov_to_eig(const double cov[3], double *varx, double *vary,
                                        double *alpha_deg);

/* The symmetric positive-semidefinite square root R of a covariance {cxx, cxy, cyy} (R R = cov,
 * so mu + R z with z ~ N(0, I) samples N(mu, cov)), with eigenvalues below 0 taken as 0: a
 * nearly singular matrix that the readers accept (determinant slightly below 0) gets the root of
 * its nearest PSD matrix, not a Cholesky factor blown up by a tiny pivot. Returns 1 when cov is
 * PSD as computed, 0 when an eigenvalue was raised to 0; -1 (root unset) for a non-finite entry. */
ICS_API int ics_light_cov_sqrt(const double cov[3], double root[3]);

/* Writes n lights as a lights file (docs/lights_format.md): {"lights": [{"mean": [mx, my],
 * "cov": [[cxx, cxy], [cxy, cyy]], "color": [r, g, b], "weight": w}, ...]}, one light per line,
 * numbers in %.17g (read back bit for bit). Returns 0, or -1 when the stream reports an error. */
ICS_API int ics_light_write_json(FILE *f, const ics_light *l, int n);

/* Fills *out with a Gaussian light from tilt angles, (varx, vary, alpha), colour (NULL: white) and
 * weight. ICS_ERR_RANGE when a tilt is at or beyond +-90 degrees; ICS_ERR_NAN, ICS_ERR_INFINITE,
 * ICS_ERR_NEGATIVE_VARIANCE, ICS_ERR_INVALID_ARG (negative weight or colour) otherwise. */
ICS_API ics_status ics_light_init_tilt(ics_light *out, double wx_deg, double wy_deg, double varx,
                                       double vary, double alpha_deg, const double color[3],
                                       double weight);

/* Eq. 7/15 in 1D: mu_k = -e mu_l, var_k = d1 e var_l. ICS_ERR_RANGE unless e > 0, d1 > 0;
 * ICS_ERR_NEGATIVE_VARIANCE for var_l < 0; NaN/inf rejected. */
ICS_API ics_status ics_light_kernel_map_1d(double mu_l, double var_l, double e, double d1,
                                           double *mu_k, double *var_k);
/* Eq. 7/15 in 2D: mean_k = -e mean_l, cov_k = d1 e cov_l (cov as cxx, cxy, cyy).
 * ICS_ERR_NEGATIVE_VARIANCE unless cov_l is positive semidefinite (the check of
 * ics_light_cov_to_eig). */
ICS_API ics_status ics_light_kernel_map_2d(const ics_light *l, double e, double d1,
                                           double mean_k[2], double cov_k[3]);

/* ---- 1D light functions (densities on the light-plane x axis, integral 1) ---- */

#define ICS_LIGHT1D_MAX_MIX 16 /* components of a mixture */

/* A 1D light: an opaque object, made by one of the ics_light1d_create_* below (*out NULL on
 * failure) and freed by ics_light1d_destroy (NULL is fine). The constructors reject NaN/inf
 * inputs (ICS_ERR_NAN / ICS_ERR_INFINITE) and inputs whose derived quantities overflow
 * (ICS_ERR_RANGE: a box width hi - lo or its variance, a mixture's weight sum, mean or
 * variance, a table's mean or variance not finite, e.g. box:-1e308,1e308); a NULL out is
 * ICS_ERR_INVALID_ARG, and ICS_ERR_NOMEM. */
typedef struct ics_light1d ics_light1d;

/* Gaussian of that mean and variance (variance 0: a point light, a Dirac at the mean). */
ICS_API ics_status ics_light1d_create_gauss(ics_light1d **out, double mean, double var);
/* Uniform on [lo, hi], lo < hi (else ICS_ERR_RANGE). */
ICS_API ics_status ics_light1d_create_box(ics_light1d **out, double lo, double hi);
/* Gaussian mixture of n in 1..ICS_LIGHT1D_MAX_MIX components (else ICS_ERR_SIZE); weights >= 0
 * with a positive sum (ICS_ERR_INVALID_ARG when it is 0), normalised to sum 1; var > 0. */
ICS_API ics_status ics_light1d_create_mix(ics_light1d **out, int n, const double *w,
                                          const double *mu, const double *var);
/* Piecewise-linear density through (x_i, p_i), normalised: n >= 2 strictly increasing nodes
 * (else ICS_ERR_SIZE / ICS_ERR_INVALID_ARG), densities >= 0 with positive integral (copied). */
ICS_API ics_status ics_light1d_create_tab(ics_light1d **out, int n, const double *x,
                                          const double *p);
ICS_API void ics_light1d_destroy(ics_light1d *l);

/* pdf, cdf L(x), survival 1 - L(x) (computed without cancellation), quantile L^-1(p) for p in
 * [0, 1] (NaN otherwise; the smallest x with L(x) >= p for flat parts), upper quantile
 * x with 1 - L(x) = q. A point light's pdf is +inf at the mean and 0 elsewhere; its cdf
 * steps at the mean (L(mean) = 1). */
ICS_API double ics_light1d_pdf(const ics_light1d *l, double x);
ICS_API double ics_light1d_cdf(const ics_light1d *l, double x);
ICS_API double ics_light1d_sf(const ics_light1d *l, double x);
ICS_API double ics_light1d_quantile(const ics_light1d *l, double p);
ICS_API double ics_light1d_isf(const ics_light1d *l, double q);
ICS_API double ics_light1d_mean(const ics_light1d *l);
ICS_API double ics_light1d_var(const ics_light1d *l);
/* Third standardised moment E[(X - mu)^3] / sigma^3 (0 for a point light). */
ICS_API double ics_light1d_skewness(const ics_light1d *l);

#ifdef __cplusplus
}
#endif
#endif
