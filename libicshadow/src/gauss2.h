/* gauss2.h — a bivariate Gaussian density in log form (mean, inverse covariance, log of the
 * normalisation), evaluated by the light fit (lightfit.c) and the synthetic maps (envmap.c)
 * (private to libicshadow). */
#ifndef ICS_GAUSS2_H
#define ICS_GAUSS2_H

#include <math.h>

#include "icshadow/constants.h"

typedef struct gauss {
  double mx, my, ixx, ixy, iyy, lnorm; /* inverse covariance, log(1 / (2 pi sqrt det)) */
} gauss;

static inline int gauss_make(gauss *g, double mx, double my, const double c[3]) {
  double det = c[0] * c[2] - c[1] * c[1];
  if (!(det > 0) || !isfinite(det)) return -1;
  g->mx = mx;
  g->my = my;
  g->ixx = c[2] / det;
  g->ixy = -c[1] / det;
  g->iyy = c[0] / det;
  g->lnorm = -log(2 * ICS_PI) - 0.5 * log(det);
  return 0;
}

static inline double gauss_log(const gauss *g, double x, double y) {
  double dx = x - g->mx, dy = y - g->my;
  return g->lnorm - 0.5 * (g->ixx * dx * dx + 2 * g->ixy * dx * dy + g->iyy * dy * dy);
}

#endif
