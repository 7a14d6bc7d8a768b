/* class.c — kernel equivalence classes (see icshadow/class.h): their checks and a 2D class from
 * and to its axes, through the library's 2x2 covariance code (light.c's ics_light_cov_from_eig,
 * the symmetric eigen-decomposition of sym2.c). */
#include "icshadow/class.h"

#include <math.h>

#include "icshadow/light.h"
#include "sym2.h"

ics_status ics_class1d_check(const ics_class1d *c) {
  if (!c) return ICS_ERR_INVALID_ARG;
  if (isnan(c->mean) || isnan(c->var)) return ICS_ERR_NAN;
  if (c->var < 0) return ICS_ERR_NEGATIVE_VARIANCE;
  if (isinf(c->mean) || isinf(c->var)) return ICS_ERR_INFINITE;
  return ICS_OK;
}

ics_status ics_class2d_check(const ics_class2d *c) {
  if (!c) return ICS_ERR_INVALID_ARG;
  if (isnan(c->mean[0]) || isnan(c->mean[1]) || isnan(c->cxx) || isnan(c->cxy) || isnan(c->cyy))
    return ICS_ERR_NAN;
  if (c->cxx < 0 || c->cyy < 0) return ICS_ERR_NEGATIVE_VARIANCE;
  if (isinf(c->mean[0]) || isinf(c->mean[1]) || isinf(c->cxx) || isinf(c->cxy) || isinf(c->cyy))
    return ICS_ERR_INFINITE;
  if (c->cxx > 0x1p500 || c->cyy > 0x1p500 || fabs(c->cxy) > 0x1p500) return ICS_ERR_RANGE;
  double l1, l2;
  ics_sym2_eig(c->cxx, c->cxy, c->cyy, &l1, &l2, NULL);
  if (l2 < -1e-12 * (c->cxx + c->cyy)) return ICS_ERR_NEGATIVE_VARIANCE;
  return ICS_OK;
}

ics_status ics_class2d_init_axes(ics_class2d *out, double mx, double my, double varx, double vary,
                                 double angle_deg) {
  if (!out) return ICS_ERR_INVALID_ARG;
  if (isnan(mx) || isnan(my) || isnan(varx) || isnan(vary) || isnan(angle_deg)) return ICS_ERR_NAN;
  if (varx < 0 || vary < 0) return ICS_ERR_NEGATIVE_VARIANCE;
  if (isinf(mx) || isinf(my) || isinf(varx) || isinf(vary) || isinf(angle_deg))
    return ICS_ERR_INFINITE;
  double cov[3];
  ics_status st = ics_light_cov_from_eig(varx, vary, angle_deg, cov); /* inputs checked above */
  if (st != ICS_OK) return st;
  out->mean[0] = mx;
  out->mean[1] = my;
  out->cxx = cov[0];
  out->cxy = cov[1];
  out->cyy = cov[2];
  return ics_class2d_check(out);
}

ics_status ics_class2d_to_axes(const ics_class2d *c, double *varx, double *vary,
                               double *angle_deg) {
  ics_status st = ics_class2d_check(c);
  if (st != ICS_OK) return st;
  double l1, l2, ang;
  ics_sym2_eig(c->cxx, c->cxy, c->cyy, &l1, &l2, &ang); /* the algorithm of ics_light_cov_to_eig */
  if (l2 < 0) l2 = 0;
  if (varx) *varx = l1;
  if (vary) *vary = l2;
  if (angle_deg) *angle_deg = ang;
  return ICS_OK;
}
