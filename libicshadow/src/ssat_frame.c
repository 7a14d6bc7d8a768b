/* ssat_frame.c — the spherical frame, the light limit and the angular patch box of a point
 * light over a volume (contracts in ssat_frame.h), shared by the SSAT and its brute-force
 * reference so that both derive the same geometry from the same inputs. */
#include "ssat_frame.h"

#include <math.h>
#include <string.h>

#include "icshadow/constants.h"
#include "clamp.h"
#include "vec3.h"

void ics_ssat_make_frame(const ics_volume *vol, const double light[3], double e[3][3]) {
  double a[3] = {(double)vol->nx / 2 - light[0], (double)vol->ny / 2 - light[1],
                 (double)vol->nz / 2 - light[2]};
  double len = sqrt(ics_dot3(a, a));
  memset(e, 0, 9 * sizeof(double));
  if (!(len > 0.0) || !isfinite(len)) {
    e[0][0] = e[1][1] = e[2][2] = 1.0;
    return;
  }
  for (int k = 0; k < 3; k++) e[0][k] = a[k] / len;
  int m = 0;
  for (int k = 1; k < 3; k++)
    if (fabs(e[0][k]) < fabs(e[0][m])) m = k;
  double d = e[0][m];
  for (int k = 0; k < 3; k++) e[2][k] = (k == m ? 1.0 : 0.0) - d * e[0][k];
  double l2 = sqrt(ics_dot3(e[2], e[2]));
  for (int k = 0; k < 3; k++) e[2][k] /= l2;
  ics_cross3(e[2], e[0], e[1]);
}

ics_status ics_ssat_max_radius(const ics_volume *vol, const double light[3], double *rmax) {
  double dims[3] = {(double)vol->nx, (double)vol->ny, (double)vol->nz};
  double rm = 0.0;
  for (int c = 0; c < 8; c++) {
    double q[3];
    for (int a = 0; a < 3; a++) q[a] = ((c >> a) & 1 ? dims[a] : 0.0) - light[a];
    double r = hypot(hypot(q[0], q[1]), q[2]);
    if (!(r <= rm)) rm = r;
  }
  double diag = sqrt(ics_dot3(dims, dims));
  if (!isfinite(rm) || rm > ICS_SSAT_MAX_DISTANCE * diag) return ICS_ERR_RANGE;
  *rmax = rm;
  return ICS_OK;
}

ics_status ics_ssat_patch_box(const double light[3], const double e[3][3], const double p[3],
                              double U, double *ph0, double *ph1, double *th0, double *th1,
                              double *R) {
  double q[3] = {p[0] - light[0], p[1] - light[1], p[2] - light[2]};
  double r = hypot(hypot(q[0], q[1]), q[2]);
  if (!(r > 0.0) || !isfinite(r)) return ICS_ERR_RANGE;
  double x = ics_dot3(q, e[0]), y = ics_dot3(q, e[1]), z = ics_dot3(q, e[2]);
  double th = atan2(hypot(x, y), z), ph = atan2(y, x);
  double al = atan(U / r);
  double sn = sin(th);
  double be = sn > 0.0 ? al / sn : INFINITY; /* phi half-width */
  *th0 = ics_clampd(th - al, 0.0, ICS_PI);
  *th1 = ics_clampd(th + al, 0.0, ICS_PI);
  if (!(be < ICS_PI)) { /* clamped to pi: the whole ring (then th0 = 0 or th1 = pi) */
    *ph0 = -ICS_PI, *ph1 = ICS_PI;
  } else {
    *ph0 = ph - be, *ph1 = ph + be;
  }
  *R = r;
  return ICS_OK;
}
