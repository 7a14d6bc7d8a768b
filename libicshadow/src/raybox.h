/* raybox.h — ray / axis-aligned box clipping by slabs (private to libicshadow). The one
 * implementation behind the height-field scene's ray hits (heightfield.c) and the brute-force
 * reference of occtex.c (exact visibility of a rectangular light).
 *
 * Clips the parameter interval [*t0, *t1] of the ray o + t d to the closed box [lo, hi] (per
 * axis: (lo - o)/d and (hi - o)/d, ordered; an axis with d = 0 keeps the interval when o lies
 * inside the slab and empties it otherwise). Returns 1 with the clipped interval when it is not
 * empty, 0 otherwise (then *t0, *t1 are unspecified). */
#ifndef ICS_RAYBOX_H
#define ICS_RAYBOX_H

static inline int ics_ray_box_clip(const double o[3], const double d[3], const double lo[3],
                                   const double hi[3], double *t0, double *t1) {
  for (int i = 0; i < 3; i++) {
    if (d[i] == 0) {
      if (o[i] < lo[i] || o[i] > hi[i]) return 0;
      continue;
    }
    double a = (lo[i] - o[i]) / d[i], c = (hi[i] - o[i]) / d[i];
    if (a > c) {
      double tmp = a;
      a = c;
      c = tmp;
    }
    if (a > *t0) *t0 = a;
    if (c < *t1) *t1 = c;
    if (*t0 > *t1) return 0;
  }
  return 1;
}

#endif
