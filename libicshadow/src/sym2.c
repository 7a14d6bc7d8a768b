/* sym2.c — eigen-decomposition and square root of a symmetric 2x2 matrix (method and contract
 * in sym2.h). */
#include "sym2.h"

#include <math.h>
#include <stddef.h>

#include "icshadow/constants.h"

void ics_sym2_eig(double a, double b, double d, double *l1, double *l2, double *alpha_deg) {
  double h = 0.5 * (a - d);
  double r = hypot(h, b);
  double m = 0.5 * (a + d);
  double big = m + r;
  *l1 = big;
  *l2 = (big > 0) ? (a * d - b * b) / big : m - r; /* no cancellation in the small one */
  if (alpha_deg) {
    double ang = (r == 0) ? 0.0 : 0.5 * atan2(b, h) * (180.0 / ICS_PI);
    if (ang <= -90.0) ang += 180.0;
    *alpha_deg = ang;
  }
}

int ics_sym2_sqrt(double a, double b, double d, double out[3]) {
  double l1, l2;
  ics_sym2_eig(a, b, d, &l1, &l2, NULL);
  int psd = l2 >= 0;
  if (l1 < 0) l1 = 0;
  if (l2 < 0) l2 = 0;
  double s = sqrt(l1) * sqrt(l2), t = sqrt(l1) + sqrt(l2);
  if (t == 0) {
    out[0] = out[1] = out[2] = 0;
    return psd;
  }
  out[0] = (a + s) / t;
  out[1] = b / t;
  out[2] = (d + s) / t;
  return psd;
}
