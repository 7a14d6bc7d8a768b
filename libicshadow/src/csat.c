/* csat.c — the light-aligned 3D summed-area table (CSAT) of Ament et al. 2014 for directional
 * lights (icshadow/csat.h). The volume is resampled at the cell centres of a light-aligned
 * grid — piecewise-constant per cell — and summed with the 3D SAT of sat.c (double-float or
 * any other precision mode). A filtered optical depth is one continuous box integral:
 * 8 multilinear SAT lookups, independent of the filter size. */
#include "icshadow/csat.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "vec3.h"
#include "volume_check.h"

struct ics_csat {
  ics_sat3d *sat;
  double r[3][3]; /* r_u, r_v, r_w */
  double centre[3];
  size_t n[3];
  double h;
};

ics_status ics_csat_create_frame(ics_csat **out, const ics_volume *vol, const double r_u[3],
                                 const double r_v[3], double h, ics_sat_precision mode) {
  if (!out) return ICS_ERR_INVALID_ARG;
  *out = NULL;
  if (!ics_volume_ok(vol) || !r_u || !r_v) return ICS_ERR_INVALID_ARG;
  if (isnan(h) || !ics_finite3(r_u) || !ics_finite3(r_v)) return ICS_ERR_NAN;
  if (!(h > 0.0) || !isfinite(h)) return ICS_ERR_INVALID_ARG;
  if (fabs(ics_dot3(r_u, r_u) - 1) > 1e-9 || fabs(ics_dot3(r_v, r_v) - 1) > 1e-9 ||
      fabs(ics_dot3(r_u, r_v)) > 1e-9)
    return ICS_ERR_INVALID_ARG;
  ics_csat *c = calloc(1, sizeof *c);
  if (!c) return ICS_ERR_NOMEM;
  memcpy(c->r[0], r_u, sizeof c->r[0]);
  memcpy(c->r[1], r_v, sizeof c->r[1]);
  ics_cross3(r_u, r_v, c->r[2]);
  c->h = h;
  double dims[3] = {(double)vol->nx, (double)vol->ny, (double)vol->nz};
  for (int k = 0; k < 3; k++) c->centre[k] = dims[k] / 2;
  double cells = 1.0;
  for (int a = 0; a < 3; a++) { /* h beyond the volume's extent: cells mostly outside it */
    double e = fabs(c->r[a][0]) * dims[0] + fabs(c->r[a][1]) * dims[1] + fabs(c->r[a][2]) * dims[2];
    if (h > e * (1 + 1e-12)) {
      free(c);
      return ICS_ERR_RANGE;
    }
  }
  for (int a = 0; a < 3; a++) {
    double e = fabs(c->r[a][0]) * dims[0] + fabs(c->r[a][1]) * dims[1] + fabs(c->r[a][2]) * dims[2];
    double na = ceil(e / h - 1e-9);
    if (na < 1) na = 1;
    if (na > 2147483648.0) {
      free(c);
      return ICS_ERR_SIZE;
    }
    c->n[a] = (size_t)na;
    cells *= na;
  }
  if (cells > 2147483648.0 || cells * 4.0 > (double)ICS_SAT_MAX_BYTES) {
    free(c);
    return ICS_ERR_SIZE;
  }
  float *grid = malloc((size_t)cells * sizeof(float));
  if (!grid) {
    free(c);
    return ICS_ERR_NOMEM;
  }
  double h3 = h * h * h;
  for (size_t k = 0; k < c->n[2]; k++)
    for (size_t j = 0; j < c->n[1]; j++)
      for (size_t i = 0; i < c->n[0]; i++) {
        double q[3] = {((double)i + 0.5) * h - (double)c->n[0] * h / 2,
                       ((double)j + 0.5) * h - (double)c->n[1] * h / 2,
                       ((double)k + 0.5) * h - (double)c->n[2] * h / 2};
        double p[3];
        for (int a = 0; a < 3; a++)
          p[a] = c->centre[a] + q[0] * c->r[0][a] + q[1] * c->r[1][a] + q[2] * c->r[2][a];
        grid[(k * c->n[1] + j) * c->n[0] + i] = (float)(ics_volume_sample(vol, p) * h3);
      }
  ics_status st = ics_sat3d_create(&c->sat, grid, c->n[0], c->n[1], c->n[2], mode);
  free(grid);
  if (st != ICS_OK) {
    free(c);
    return st;
  }
  *out = c;
  return ICS_OK;
}

ics_status ics_csat_create(ics_csat **out, const ics_volume *vol, const double l[3], double h,
                           ics_sat_precision mode) {
  if (!out) return ICS_ERR_INVALID_ARG;
  *out = NULL;
  if (!l) return ICS_ERR_INVALID_ARG;
  if (!ics_finite3(l)) return ICS_ERR_NAN;
  double len = sqrt(ics_dot3(l, l));
  if (!(len > 0.0)) return ICS_ERR_INVALID_ARG;
  double w[3] = {l[0] / len, l[1] / len, l[2] / len};
  /* r_u: the world axis least aligned with l, made orthogonal (deterministic). */
  int k = 0;
  for (int a = 1; a < 3; a++)
    if (fabs(w[a]) < fabs(w[k])) k = a;
  double e[3] = {0, 0, 0}, u[3], v[3];
  e[k] = 1.0;
  double d = ics_dot3(e, w);
  for (int a = 0; a < 3; a++) u[a] = e[a] - d * w[a];
  double ul = sqrt(ics_dot3(u, u));
  for (int a = 0; a < 3; a++) u[a] /= ul;
  ics_cross3(w, u, v); /* u x v = u x (w x u) = w */
  return ics_csat_create_frame(out, vol, u, v, h, mode);
}

void ics_csat_destroy(ics_csat *csat) {
  if (!csat) return;
  ics_sat3d_destroy(csat->sat);
  free(csat);
}

void ics_csat_frame(const ics_csat *csat, double r_u[3], double r_v[3], double r_w[3],
                    size_t n[3]) {
  if (r_u) memcpy(r_u, csat->r[0], sizeof csat->r[0]);
  if (r_v) memcpy(r_v, csat->r[1], sizeof csat->r[1]);
  if (r_w) memcpy(r_w, csat->r[2], sizeof csat->r[2]);
  if (n) memcpy(n, csat->n, sizeof csat->n);
}

ics_status ics_csat_light_dir(const ics_csat *csat, ics_csat_light which, double dir[3]) {
  if (!csat || !dir || (unsigned)which > ICS_CSAT_MINUS_V) return ICS_ERR_INVALID_ARG;
  static const int axis[6] = {2, 2, 0, 0, 1, 1};
  double s = (which & 1) ? -1.0 : 1.0;
  for (int a = 0; a < 3; a++) dir[a] = s * csat->r[axis[which]][a];
  return ICS_OK;
}

ics_status ics_csat_tau(const ics_csat *csat, ics_csat_light which, const double p[3],
                        double half_width, double *tau) {
  if (!csat || !p || !tau || (unsigned)which > ICS_CSAT_MINUS_V) return ICS_ERR_INVALID_ARG;
  if (isnan(half_width) || isnan(p[0]) || isnan(p[1]) || isnan(p[2])) return ICS_ERR_NAN;
  if (!(half_width >= 0.0) || !isfinite(half_width) || !ics_finite3(p)) return ICS_ERR_INVALID_ARG;
  double h = csat->h;
  double U = half_width > 0.0 ? half_width : h / 2;
  double g[3], lo[3], hi[3];
  for (int a = 0; a < 3; a++) {
    double q[3] = {p[0] - csat->centre[0], p[1] - csat->centre[1], p[2] - csat->centre[2]};
    g[a] = (ics_dot3(q, csat->r[a]) + (double)csat->n[a] * h / 2) / h;
    lo[a] = g[a] - U / h;
    hi[a] = g[a] + U / h;
  }
  static const int axis[6] = {2, 2, 0, 0, 1, 1};
  int ax = axis[which];
  if (which & 1) {
    lo[ax] = -1.0;
    hi[ax] = g[ax];
  } else {
    lo[ax] = g[ax];
    hi[ax] = (double)csat->n[ax] + 1.0;
  }
  if (hi[ax] < lo[ax]) { /* p beyond the grid on the light's side: nothing in between */
    *tau = 0.0;
    return ICS_OK;
  }
  double s;
  ics_status st = ics_sat3d_integral(csat->sat, lo, hi, &s);
  if (st != ICS_OK) return st;
  *tau = s / (4.0 * U * U);
  return ICS_OK;
}

ics_status ics_csat_transmittance(const ics_csat *csat, ics_csat_light which, const double p[3],
                                  double half_width, double *transmittance) {
  if (!transmittance) return ICS_ERR_INVALID_ARG;
  double tau;
  ics_status st = ics_csat_tau(csat, which, p, half_width, &tau);
  if (st == ICS_OK) *transmittance = exp(-tau);
  return st;
}
