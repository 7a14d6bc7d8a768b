/* volume.c — extinction volumes (icshadow/volume.h): trilinear sampling and the brute-force
 * shadow-ray marching (midpoint rule, the ray clipped to the volume box by raybox.h) of the
 * box-filtered optical depth of a directional and of a point light, the references of the CSAT
 * and the SSAT; the point light's rays cover the SSAT's own angular box (ssat_frame.h). */
#include "icshadow/volume.h"

#include <math.h>
#include <stddef.h>

#include "raybox.h"
#include "ssat_frame.h"
#include "vec3.h"
#include "volume_check.h"

double ics_volume_sample(const ics_volume *vol, const double p[3]) {
  size_t n[3] = {vol->nx, vol->ny, vol->nz};
  long i0[3], i1[3];
  double f[3];
  for (int a = 0; a < 3; a++) {
    if (!(p[a] >= 0.0 && p[a] <= (double)n[a])) return 0.0;
    double g = p[a] - 0.5, fl = floor(g);
    f[a] = g - fl;
    long i = (long)fl, last = (long)n[a] - 1;
    i0[a] = i < 0 ? 0 : i > last ? last : i;
    i1[a] = i + 1 < 0 ? 0 : i + 1 > last ? last : i + 1;
  }
  const float *d = vol->data;
  size_t sx = 1, sy = vol->nx, sz = vol->nx * vol->ny;
#define V_(i, j, k) ((double)d[(size_t)(i) * sx + (size_t)(j) * sy + (size_t)(k) * sz])
  double c00 = V_(i0[0], i0[1], i0[2]) * (1 - f[0]) + V_(i1[0], i0[1], i0[2]) * f[0];
  double c10 = V_(i0[0], i1[1], i0[2]) * (1 - f[0]) + V_(i1[0], i1[1], i0[2]) * f[0];
  double c01 = V_(i0[0], i0[1], i1[2]) * (1 - f[0]) + V_(i1[0], i0[1], i1[2]) * f[0];
  double c11 = V_(i0[0], i1[1], i1[2]) * (1 - f[0]) + V_(i1[0], i1[1], i1[2]) * f[0];
#undef V_
  double c0 = c00 * (1 - f[1]) + c10 * f[1], c1 = c01 * (1 - f[1]) + c11 * f[1];
  return c0 * (1 - f[2]) + c1 * f[2];
}

/* Optical depth along o + t dir, t in [tmin, tmax] clipped to the volume box, midpoint rule. */
static double march(const ics_volume *vol, const double o[3], const double dir[3], double tmin,
                    double tmax, double step) {
  const double lo[3] = {0.0, 0.0, 0.0};
  const double hi[3] = {(double)vol->nx, (double)vol->ny, (double)vol->nz};
  double a = tmin, b = tmax;
  if (!ics_ray_box_clip(o, dir, lo, hi, &a, &b) || !(a < b)) return 0.0;
  double len = b - a;
  long k = (long)ceil(len / step);
  if (k < 1) k = 1;
  double dt = len / (double)k, tau = 0.0;
  for (long i = 0; i < k; i++) {
    double t = a + ((double)i + 0.5) * dt;
    double p[3] = {o[0] + t * dir[0], o[1] + t * dir[1], o[2] + t * dir[2]};
    tau += ics_volume_sample(vol, p);
  }
  return tau * dt;
}

ics_status ics_volume_tau_directional(const ics_volume *vol, const double r_u[3],
                                      const double r_v[3], const double dir[3], const double p[3],
                                      double half_width, int n_patch, double step, double *tau) {
  if (!ics_volume_ok(vol) || !r_u || !r_v || !dir || !p || !tau) return ICS_ERR_INVALID_ARG;
  if (isnan(half_width) || isnan(step) || !ics_finite3(p) || !ics_finite3(dir)) return ICS_ERR_NAN;
  if (!(half_width >= 0.0) || !(step > 0.0) || n_patch < 1) return ICS_ERR_INVALID_ARG;
  int n = half_width > 0.0 ? n_patch : 1;
  double acc = 0.0;
  for (int j = 0; j < n; j++)
    for (int i = 0; i < n; i++) {
      double u = half_width > 0.0 ? -half_width + ((double)i + 0.5) * 2 * half_width / n : 0.0;
      double v = half_width > 0.0 ? -half_width + ((double)j + 0.5) * 2 * half_width / n : 0.0;
      double o[3];
      for (int a = 0; a < 3; a++) o[a] = p[a] + u * r_u[a] + v * r_v[a];
      acc += march(vol, o, dir, 0.0, INFINITY, step);
    }
  *tau = acc / ((double)n * n);
  return ICS_OK;
}

ics_status ics_volume_tau_point(const ics_volume *vol, const double light_pos[3],
                                const double p[3], double half_width, int n_patch, double step,
                                double *tau) {
  if (!ics_volume_ok(vol) || !light_pos || !p || !tau) return ICS_ERR_INVALID_ARG;
  if (isnan(half_width) || isnan(step) || !ics_finite3(p) || isnan(light_pos[0]) ||
      isnan(light_pos[1]) || isnan(light_pos[2]))
    return ICS_ERR_NAN;
  if (!(half_width > 0.0) || !(step > 0.0) || n_patch < 1) return ICS_ERR_INVALID_ARG;
  double ph0, ph1, th0, th1, R, e[3][3], rm;
  ics_status st0 = ics_ssat_max_radius(vol, light_pos, &rm); /* ics_ssat_create's light limit */
  if (st0 != ICS_OK) return st0;
  ics_ssat_make_frame(vol, light_pos, e);
  ics_status st = ics_ssat_patch_box(light_pos, e, p, half_width, &ph0, &ph1, &th0, &th1, &R);
  if (st != ICS_OK) return st;
  double c0 = cos(th0), c1 = cos(th1), acc = 0.0;
  for (int j = 0; j < n_patch; j++) {
    double ct = c0 + ((double)j + 0.5) * (c1 - c0) / n_patch;
    double stt = sqrt(fmax(0.0, 1.0 - ct * ct));
    for (int i = 0; i < n_patch; i++) {
      double ph = ph0 + ((double)i + 0.5) * (ph1 - ph0) / n_patch;
      double dir[3];
      for (int a = 0; a < 3; a++)
        dir[a] = stt * cos(ph) * e[0][a] + stt * sin(ph) * e[1][a] + ct * e[2][a];
      acc += march(vol, light_pos, dir, 0.0, R, step);
    }
  }
  *tau = acc / ((double)n_patch * n_patch);
  return ICS_OK;
}
