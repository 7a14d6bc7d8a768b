/* vec3.h — dot and cross products and the finiteness test of 3-vectors of doubles (private to
 * libicshadow): the one copy for the CSAT, the SSAT, the volume references, the epipolar frame
 * (epipolar.c) and the height-field scene (heightfield.c). */
#ifndef ICS_VEC3_H
#define ICS_VEC3_H

#include <math.h>

static inline double ics_dot3(const double a[3], const double b[3]) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static inline void ics_cross3(const double a[3], const double b[3], double c[3]) {
  c[0] = a[1] * b[2] - a[2] * b[1];
  c[1] = a[2] * b[0] - a[0] * b[2];
  c[2] = a[0] * b[1] - a[1] * b[0];
}

static inline int ics_finite3(const double a[3]) {
  return isfinite(a[0]) && isfinite(a[1]) && isfinite(a[2]);
}

#endif
