/* icshadow/class.h — kernel equivalence classes (Patel et al. 2013, Sec. 3.3-3.4): a class is a
 * mean and a (co)variance in pixels, the moments every member of the class (kernel.h) shares
 * and to which its iterations converge (mean n mu, variance n sigma^2 after n steps). Their
 * checks, and a 2D class from and to its axes (eigenvalues and rotation). */
#ifndef ICSHADOW_CLASS_H
#define ICSHADOW_CLASS_H

#include "icshadow/status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* 1D class: mean and variance (pixels, pixels^2). */
typedef struct ics_class1d {
  double mean, var;
} ics_class1d;

/* 2D class: mean vector and covariance [[cxx, cxy], [cxy, cyy]]. */
typedef struct ics_class2d {
  double mean[2];
  double cxx, cxy, cyy;
} ics_class2d;

/* ICS_OK, or ICS_ERR_INVALID_ARG (NULL), ICS_ERR_NAN, ICS_ERR_INFINITE, ICS_ERR_NEGATIVE_VARIANCE
 * (var < 0; 2D: an eigenvalue < -1e-12 * trace, i.e. not positive semi-definite). */
ICS_API ics_status ics_class1d_check(const ics_class1d *c);
ICS_API ics_status ics_class2d_check(const ics_class2d *c);
/* Fills *out with the class of mean (mx, my) and eigenvalues varx, vary and the rotation alpha
 * (degrees ccw from +x) of the x axis: Sigma = R(alpha) diag(varx, vary) R(alpha)^T, computed by
 * light.h's ics_light_cov_from_eig (exact at multiples of 90 degrees); the mean is checked here and
 * the result by ics_class2d_check. */
ICS_API ics_status ics_class2d_init_axes(ics_class2d *out, double mx, double my, double varx,
                                         double vary, double angle_deg);
/* Inverse: varx = the larger eigenvalue, angle_deg = direction of its eigenvector in (-90, 90]
 * (0 when cxy = 0 and cxx = cyy); vary = the smaller eigenvalue (clamped to >= 0), formed as
 * det / varx so it keeps its relative accuracy for huge ratios. The same algorithm as light.h's
 * ics_light_cov_to_eig, on any class ics_class2d_check accepts (its tolerance, -1e-12 trace). */
ICS_API ics_status ics_class2d_to_axes(const ics_class2d *c, double *varx, double *vary,
                                       double *angle_deg);

#ifdef __cplusplus
}
#endif
#endif
