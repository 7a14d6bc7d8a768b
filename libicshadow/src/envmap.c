/* envmap.c — latitude-longitude environment maps on the virtual light plane (see
 * icshadow/envmap.h): a pixel's plane point and solid angle, its footprint covariance on the
 * plane, the kept-pixel rule of the fit's cut-off, the plane density, and synthetic maps drawn
 * from Gaussian lights (each light's density times (1 + |x|^2)^(3/2), supersampled; lights
 * narrower than a quarter pixel drawn into one pixel). */
#include "icshadow/envmap.h"
#include "icshadow/constants.h"

#include <math.h>
#include <stdlib.h>

#include "envmap_pixel.h"
#include "gauss2.h"
#include "sym2.h"

int ics_envmap_pixel(int width, int height, int i, int j, double *x, double *y, double *domega) {
  double th = ICS_PI * (j + 0.5) / height, ph = 2 * ICS_PI * (i + 0.5) / width - ICS_PI;
  double st = sin(th), dz = st * cos(ph);
  if (!(dz > 0)) return -1;
  if (x) *x = tan(ph);
  if (y) *y = cos(th) / dz;
  if (domega)
    *domega = (cos(ICS_PI * j / height) - cos(ICS_PI * (j + 1.0) / height)) * (2 * ICS_PI / width);
  return 0;
}

int ics_envmap_plane_density(const ics_image *env, int i, int j, double *x, double *y,
                             double rgb[3]) {
  if (!env || !env->data || !rgb || (env->channels != 3 && env->channels != 4) || i < 0 ||
      i >= env->width || j < 0 || j >= env->height)
    return -1;
  double px, py;
  if (ics_envmap_pixel(env->width, env->height, i, j, &px, &py, NULL)) return -1;
  double dw_da = pow(1 + px * px + py * py, -1.5);
  const float *c = env->data + ((size_t)j * env->width + i) * env->channels;
  for (int k = 0; k < 3; k++) rgb[k] = c[k] * dw_da;
  if (x) *x = px;
  if (y) *y = py;
  return 0;
}

/* the smallest dz = sin(theta) cos(phi) over pixel (i, j): a product of two functions that are
 * positive and unimodal on the pixel when the pixel is behind the viewer, so its minimum is at
 * the corner farthest from the equator and from phi = 0 */
static double pixel_min_dz(int w, int h, int i, int j) {
  double t0 = ICS_PI * j / h, t1 = ICS_PI * (j + 1.0) / h;
  double p0 = 2 * ICS_PI * i / w - ICS_PI, p1 = 2 * ICS_PI * (i + 1.0) / w - ICS_PI;
  double st = fmin(sin(t0), sin(t1)), cp = fmin(cos(p0), cos(p1));
  return st > 0 && cp > 0 ? st * cp : 0;
}

int ics_envmap_kept_at(int w, int h, int i, int j, double dzc, double cosmax) {
  return dzc >= cosmax && pixel_min_dz(w, h, i, j) >= 0.5 * dzc;
}

int ics_envmap_pixel_kept(int width, int height, int i, int j, double max_angle_deg) {
  if (width < 1 || height < 1 || i < 0 || i >= width || j < 0 || j >= height ||
      !(max_angle_deg > 0 && max_angle_deg < 90))
    return 0;
  double th = ICS_PI * (j + 0.5) / height, ph = 2 * ICS_PI * (i + 0.5) / width - ICS_PI;
  double dzc = sin(th) * cos(ph);
  return dzc > 0 &&
         ics_envmap_kept_at(width, height, i, j, dzc, cos(max_angle_deg * ICS_PI / 180));
}

void ics_envmap_footprint(int w, int h, int i, int j, double s[3]) {
  double th = ICS_PI * (j + 0.5) / h, ph = 2 * ICS_PI * (i + 0.5) / w - ICS_PI;
  double cp = cos(ph), sp = sin(ph), st = sin(th), ct = cos(th);
  double dph = 2 * ICS_PI / w, dth = ICS_PI / h;
  double a = dph * dph / 12, b = dth * dth / 12;
  double j00 = 1 / (cp * cp), j10 = ct / st * sp / (cp * cp), j11 = -1 / (st * st * cp);
  s[0] = j00 * j00 * a;
  s[1] = j00 * j10 * a;
  s[2] = j10 * j10 * a + j11 * j11 * b;
}

/* ---- synthetic maps ---- */

ics_status ics_envmap_render(ics_image *env, const double sky_rgb[3], const ics_light *lights,
                             int n, int supersample) {
  return ics_envmap_render_progress(env, sky_rgb, lights, n, supersample, NULL, NULL);
}

ics_status ics_envmap_render_progress(ics_image *env, const double sky_rgb[3],
                                      const ics_light *lights, int n, int supersample,
                                      void (*progress)(void *ctx, int rows_done, int rows),
                                      void *ctx) {
  if (!env || !env->data || (env->channels != 3 && env->channels != 4) || n < 0 ||
      (n > 0 && !lights) || supersample < 1 || supersample > 16)
    return ICS_ERR_INVALID_ARG;
  if (env->width < 4 || env->height < 2) return ICS_ERR_SIZE;
  const int w = env->width, h = env->height, s = supersample;
  double sky[3] = {0, 0, 0};
  if (sky_rgb)
    for (int c = 0; c < 3; c++) {
      if (!(sky_rgb[c] >= 0) || !isfinite(sky_rgb[c])) return ICS_ERR_INVALID_ARG;
      sky[c] = sky_rgb[c];
    }
  gauss *g = malloc((size_t)(n ? n : 1) * sizeof *g);
  int *delta = malloc((size_t)(n ? n : 1) * sizeof *delta);
  if (!g || !delta) {
    free(g);
    free(delta);
    return ICS_ERR_NOMEM;
  }
  for (int k = 0; k < n; k++) {
    const ics_light *l = &lights[k];
    int ok = isfinite(l->mean[0]) && isfinite(l->mean[1]) && l->weight >= 0 &&
             isfinite(l->weight);
    for (int c = 0; c < 3; c++) ok = ok && l->cov[c] == l->cov[c] && isfinite(l->cov[c]);
    for (int c = 0; c < 3; c++) ok = ok && l->color[c] >= 0 && isfinite(l->color[c]);
    double l1 = 0, l2 = 0, ang = 0;
    if (ok) {
      ics_sym2_eig(l->cov[0], l->cov[1], l->cov[2], &l1, &l2, &ang);
      double tr = l->cov[0] + l->cov[2];
      ok = l->cov[0] >= 0 && l->cov[2] >= 0 && l2 >= -1e-12 * tr;
    }
    if (!ok) {
      free(g);
      free(delta);
      return ICS_ERR_INVALID_ARG;
    }
    /* pixel size on the plane at the mean */
    double r2 = l->mean[0] * l->mean[0] + l->mean[1] * l->mean[1], nr = sqrt(1 + r2);
    double dx = l->mean[0] / nr, dy = l->mean[1] / nr, dz = 1 / nr;
    double th = acos(dy), ph = atan2(dx, dz);
    int pi = (int)floor((ph + ICS_PI) / (2 * ICS_PI) * w), pj = (int)floor(th / ICS_PI * h);
    pi = pi < 0 ? 0 : pi >= w ? w - 1 : pi;
    pj = pj < 0 ? 0 : pj >= h ? h - 1 : pj;
    double fs[3], f1, f2;
    ics_envmap_footprint(w, h, pi, pj, fs);
    ics_sym2_eig(fs[0], fs[1], fs[2], &f1, &f2, NULL);
    double floor_var = 12 * f2 / 16; /* (smallest pixel extent / 4)^2 */
    delta[k] = -1;
    if (l1 < floor_var) {
      delta[k] = pj * w + pi;
      continue;
    }
    if (l2 < floor_var) l2 = floor_var;
    double cv[3];
    if (ics_light_cov_from_eig(l1, l2, ang, cv) != ICS_OK) { /* eigenvalues overflowed */
      free(g);
      free(delta);
      return ICS_ERR_INVALID_ARG;
    }
    gauss_make(&g[k], l->mean[0], l->mean[1], cv);
  }
  for (int j = 0; j < h; j++) {
    if (progress && j) progress(ctx, j, h);
    for (int i = 0; i < w; i++) {
      double acc[3] = {0, 0, 0};
      for (int b = 0; b < s; b++)
        for (int a = 0; a < s; a++) {
          double th = ICS_PI * (j + (b + 0.5) / s) / h;
          double ph = 2 * ICS_PI * (i + (a + 0.5) / s) / w - ICS_PI;
          double st = sin(th), dz = st * cos(ph);
          if (!(dz > 0)) continue;
          double x = st * sin(ph) / dz, y = cos(th) / dz, r2 = x * x + y * y;
          double jac = pow(1 + r2, 1.5);
          for (int k = 0; k < n; k++) {
            if (delta[k] >= 0 || !(lights[k].weight > 0)) continue;
            double v = lights[k].weight * exp(gauss_log(&g[k], x, y)) * jac;
            for (int c = 0; c < 3; c++) acc[c] += v * lights[k].color[c];
          }
        }
      float *p = env->data + ((size_t)j * w + i) * env->channels;
      for (int c = 0; c < 3; c++) p[c] = (float)(sky[c] + acc[c] / (s * s));
      if (env->channels == 4) p[3] = 1;
    }
  }
  if (progress) progress(ctx, h, h);
  for (int k = 0; k < n; k++) {
    if (delta[k] < 0) continue;
    int pi = delta[k] % w, pj = delta[k] / w;
    double dw = (cos(ICS_PI * pj / h) - cos(ICS_PI * (pj + 1.0) / h)) * (2 * ICS_PI / w);
    float *p = env->data + ((size_t)pj * w + pi) * env->channels;
    for (int c = 0; c < 3; c++) p[c] += (float)(lights[k].weight * lights[k].color[c] / dw);
  }
  free(g);
  free(delta);
  for (size_t q = 0; q < (size_t)w * h * env->channels; q++)
    if (!isfinite(env->data[q])) return ICS_ERR_RANGE; /* a light too bright for float */
  return ICS_OK;
}
