/* epipolar.c — epipolar rectification for a directional light (see icshadow/epipolar.h): the
 * frame, a point's and a camera ray's slice and depth, and the resampling of a shadow map. */
#include "icshadow/epipolar.h"
#include "icshadow/constants.h"

#include <math.h>
#include <string.h>

#include "vec3.h"

ics_status ics_epipolar_frame_init(ics_epipolar_frame *out, const double eye[3],
                                   const double to_light[3], size_t rows, size_t d, double dgamma) {
  if (!out || !eye || !to_light) return ICS_ERR_INVALID_ARG;
  for (int i = 0; i < 3; i++) {
    if (isnan(eye[i]) || isnan(to_light[i])) return ICS_ERR_NAN;
    if (isinf(eye[i]) || isinf(to_light[i])) return ICS_ERR_INFINITE;
  }
  if (isnan(dgamma)) return ICS_ERR_NAN;
  if (!(dgamma > 0) || isinf(dgamma)) return ICS_ERR_RANGE;
  if (rows == 0 || d == 0 || rows > ICS_MINMAX_MAX_ROWS || d > ICS_MINMAX_MAX_SAMPLES)
    return ICS_ERR_SIZE;
  double nl = sqrt(ics_dot3(to_light, to_light));
  if (!(nl > 0)) return ICS_ERR_INVALID_ARG;
  memset(out, 0, sizeof *out);
  for (int i = 0; i < 3; i++) {
    out->eye[i] = eye[i];
    out->L[i] = to_light[i] / nl;
  }
  /* U: the world axis least aligned with L, made perpendicular; V = L x U */
  double a[3] = {0, 0, 0};
  int k = 0;
  for (int i = 1; i < 3; i++)
    if (fabs(out->L[i]) < fabs(out->L[k])) k = i;
  a[k] = 1.0;
  double pr = ics_dot3(a, out->L);
  for (int i = 0; i < 3; i++) out->U[i] = a[i] - pr * out->L[i];
  double nu = sqrt(ics_dot3(out->U, out->U));
  for (int i = 0; i < 3; i++) out->U[i] /= nu;
  out->V[0] = out->L[1] * out->U[2] - out->L[2] * out->U[1];
  out->V[1] = out->L[2] * out->U[0] - out->L[0] * out->U[2];
  out->V[2] = out->L[0] * out->U[1] - out->L[1] * out->U[0];
  out->eu = ics_dot3(eye, out->U);
  out->ev = ics_dot3(eye, out->V);
  out->depth_eye = -ics_dot3(eye, out->L);
  out->dgamma = dgamma;
  out->rows = rows;
  out->d = d;
  return ICS_OK;
}

ics_status ics_epipolar_locate(const ics_epipolar_frame *f, const double p[3], double *alpha,
                               double *gamma, double *depth) {
  if (!f || !p || !alpha || !gamma || !depth) return ICS_ERR_INVALID_ARG;
  for (int i = 0; i < 3; i++)
    if (isnan(p[i])) return ICS_ERR_NAN;
  /* relative to the eye first: the slice of E + s v is then exact up to rounding of s v */
  double r[3] = {p[0] - f->eye[0], p[1] - f->eye[1], p[2] - f->eye[2]};
  double du = ics_dot3(r, f->U), dv = ics_dot3(r, f->V);
  double a = atan2(dv, du);
  if (a < 0) a += 2 * ICS_PI;
  *alpha = a;
  *gamma = hypot(du, dv) / f->dgamma;
  *depth = f->depth_eye - ics_dot3(r, f->L);
  return ICS_OK;
}

ics_status ics_epipolar_ray(const ics_epipolar_frame *f, const double dir[3], double *alpha,
                            size_t *row, ics_minmax_ray *ray) {
  if (!f || !dir || !alpha || !row || !ray) return ICS_ERR_INVALID_ARG;
  for (int i = 0; i < 3; i++) {
    if (isnan(dir[i])) return ICS_ERR_NAN;
    if (isinf(dir[i])) return ICS_ERR_INFINITE;
  }
  double du = ics_dot3(dir, f->U), dv = ics_dot3(dir, f->V), dl = ics_dot3(dir, f->L);
  double perp = hypot(du, dv);
  double n = sqrt(du * du + dv * dv + dl * dl);
  if (!(perp > 1e-12 * n)) return ICS_ERR_RANGE;
  double a = atan2(dv, du);
  if (a < 0) a += 2 * ICS_PI;
  *alpha = a;
  double x = a / (2 * ICS_PI) * (double)f->rows; /* row r is centred at x = r + 1/2 */
  size_t r = (size_t)floor(x);
  if (r >= f->rows) r = f->rows - 1;
  *row = r;
  ray->beta0 = f->depth_eye;
  ray->slope = -f->dgamma * dl / perp;
  return ICS_OK;
}

ics_status ics_epipolar_ray_dir(const ics_epipolar_frame *f, size_t row, double beta,
                                double dir[3]) {
  if (!f || !dir) return ICS_ERR_INVALID_ARG;
  if (isnan(beta)) return ICS_ERR_NAN;
  if (row >= f->rows) return ICS_ERR_RANGE;
  if (!(beta > 0 && beta < ICS_PI)) return ICS_ERR_RANGE;
  double a = 2 * ICS_PI * ((double)row + 0.5) / (double)f->rows;
  double ca = cos(a), sa = sin(a), sb = sin(beta), cb = cos(beta);
  for (int i = 0; i < 3; i++) dir[i] = sb * (ca * f->U[i] + sa * f->V[i]) + cb * f->L[i];
  return ICS_OK;
}

ics_status ics_epipolar_rectify(const ics_epipolar_frame *f, const float *smap, size_t w, size_t h,
                                double u0, double v0, double texel, float *out) {
  if (!f || !smap || !out) return ICS_ERR_INVALID_ARG;
  if (w == 0 || h == 0 || w > ICS_MINMAX_MAX_SAMPLES || h > ICS_MINMAX_MAX_SAMPLES)
    return ICS_ERR_SIZE;
  if (isnan(u0) || isnan(v0) || isnan(texel)) return ICS_ERR_NAN;
  if (!(texel > 0) || isinf(texel) || isinf(u0) || isinf(v0)) return ICS_ERR_RANGE;
  for (size_t r = 0; r < f->rows; r++) {
    double a = 2 * ICS_PI * ((double)r + 0.5) / (double)f->rows;
    double ca = cos(a), sa = sin(a);
    for (size_t g = 0; g < f->d; g++) {
      double rad = (double)g * f->dgamma;
      double x = (f->eu + rad * ca - u0) / texel, y = (f->ev + rad * sa - v0) / texel;
      float val = INFINITY;
      if (x >= 0 && y >= 0 && x < (double)w && y < (double)h)
        val = smap[(size_t)y * w + (size_t)x];
      out[r * f->d + g] = val;
    }
  }
  return ICS_OK;
}
