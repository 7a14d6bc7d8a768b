/* clt.c — the convergence-rate fit of CLT measurements, 1D and 2D (see icshadow/clt.h). */
#include "icshadow/clt.h"

#include <math.h>

double ics_clt_rate(const ics_clt_point *p, int np, int nmin) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  int m = 0;
  for (int k = 0; k < np; k++) {
    if (p[k].steps < nmin || !(p[k].sup_err > 0)) continue;
    double x = log((double)p[k].steps), y = log(p[k].sup_err);
    sx += x, sy += y, sxx += x * x, sxy += x * y, m++;
  }
  if (m < 2) return NAN;
  return (m * sxy - sx * sy) / (m * sxx - sx * sx);
}
