/* tap_cases.h — test cases for the generated headers' ics_tab_ellipse_tap: variances from 0 to
 * 100 (ratios 0 to 1e10 both ways, so both major axes, segments and circles), angles over
 * [-90, 100] (with multiples of 90), 1 to 5 taps, offsets in [0, 1) and outside; each with the
 * library's tap (ics_ellipse_kernel) and the kernel's larger radius. */
#ifndef ICS_TEST_TAP_CASES_H
#define ICS_TEST_TAP_CASES_H

#include <float.h>
#include <math.h>

#include "icshadow.h"

/* what float adds to a header's tap beyond its radii' error: the arc by Carlson's R_F and R_D in
 * float and its Newton inversion to 2^-22, the quadrant fold, sin / cos (OpenCL: 4 ulp) and the
 * rotation; 64 float epsilons of the radius (test_lut_opencl.c, test_lut_glsl.c) */
#define TAP_FLOAT_ARC (64 * FLT_EPSILON)

typedef struct tap_case {
  double varx, vary, angle, u;
  int n, k;
  double x, y;  /* ics_ellipse_kernel's tap k */
  double scale; /* max(a, b): errors are relative to it */
} tap_case;

#define TAP_VARS 10
#define TAP_CASES_MAX (TAP_VARS * TAP_VARS * 5 * 5 * 4 * 5)

/* fills c (TAP_CASES_MAX entries) and returns the count */
static inline int tap_cases(tap_case *c) {
  static const double vars[TAP_VARS] = {0, 1e-8, 1e-3, 0.05, 0.3, 1, 2, 7, 31.5, 100};
  static const double angles[5] = {-90, -42.5, 0, 30, 100};
  static const double offsets[4] = {0, 0.13, 0.71, -1.3};
  int m = 0;
  for (int i = 0; i < TAP_VARS; i++)
    for (int j = 0; j < TAP_VARS; j++)
      for (int a = 0; a < 5; a++)
        for (int n = 1; n <= 5; n++)
          for (int o = 0; o < 4; o++) {
            ics_ellipse_shape sh;
            double xy[10];
            if (ics_ellipse_kernel(vars[i], vars[j], angles[a], n, offsets[o], &sh, xy) != ICS_OK)
              continue;
            for (int k = 0; k < sh.nsamples; k++)
              c[m++] = (tap_case){vars[i], vars[j], angles[a], offsets[o], n, k, xy[2 * k],
                                  xy[2 * k + 1], fmax(sh.a, sh.b)};
          }
  return m;
}

/* |tap - reference| (both coordinates' sum) relative to the case's scale (absolute at a point) */
static inline double tap_error(const tap_case *c, double x, double y) {
  double d = fabs(x - c->x) + fabs(y - c->y);
  if (isnan(d)) return INFINITY;
  return c->scale > 0 ? d / c->scale : d;
}

#endif
