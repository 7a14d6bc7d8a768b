/* ssat.c — the spherical 3D summed-area table (SSAT) of Ament et al. 2014 for point lights
 * (icshadow/ssat.h). The volume is resampled at the cell centres of a (phi, theta, r) grid
 * around the light in the frame of ssat_frame.c — piecewise-constant per cell, weighted by the
 * cell's solid angle — and summed with the 3D SAT of sat.c (any precision mode). A filtered
 * optical depth is one or two continuous box integrals (8 multilinear SAT lookups each),
 * independent of the filter size. */
#include "icshadow/ssat.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "icshadow/constants.h"
#include "clamp.h"
#include "sat_limits.h"
#include "ssat_frame.h"
#include "vec3.h"
#include "volume_check.h"

struct ics_ssat {
  ics_sat3d *sat;
  double light[3];
  double e[3][3]; /* ics_ssat_make_frame */
  size_t n[3];    /* phi, theta, r */
  double r_max;
};

ics_status ics_ssat_create(ics_ssat **out, const ics_volume *vol, const double light_pos[3],
                           size_t n_phi, size_t n_theta, size_t n_r, ics_sat_precision mode) {
  if (!out) return ICS_ERR_INVALID_ARG;
  *out = NULL;
  if (!ics_volume_ok(vol) || !light_pos) return ICS_ERR_INVALID_ARG;
  if (isnan(light_pos[0]) || isnan(light_pos[1]) || isnan(light_pos[2])) return ICS_ERR_NAN;
  if (!ics_finite3(light_pos)) return ICS_ERR_RANGE;
  ics_status st = ics_sat_check_size(n_phi, n_theta, n_r, mode);
  if (st != ICS_OK) return st;
  if ((double)n_phi * (double)n_theta * (double)n_r * 4.0 > (double)ICS_SAT_MAX_BYTES)
    return ICS_ERR_SIZE;
  double rm;
  st = ics_ssat_max_radius(vol, light_pos, &rm);
  if (st != ICS_OK) return st;
  ics_ssat *s = calloc(1, sizeof *s);
  if (!s) return ICS_ERR_NOMEM;
  memcpy(s->light, light_pos, sizeof s->light);
  ics_ssat_make_frame(vol, light_pos, s->e);
  s->n[0] = n_phi, s->n[1] = n_theta, s->n[2] = n_r;
  s->r_max = rm;
  float *grid = malloc(n_phi * n_theta * n_r * sizeof(float));
  if (!grid) {
    free(s);
    return ICS_ERR_NOMEM;
  }
  double dphi = 2 * ICS_PI / (double)n_phi, dth = ICS_PI / (double)n_theta, dr = rm / (double)n_r;
  for (size_t k = 0; k < n_r; k++) {
    double r = ((double)k + 0.5) * dr;
    for (size_t j = 0; j < n_theta; j++) {
      double th = ((double)j + 0.5) * dth;
      double omega = dphi * (cos((double)j * dth) - cos((double)(j + 1) * dth));
      double st_ = sin(th), ct = cos(th);
      for (size_t i = 0; i < n_phi; i++) {
        double ph = -ICS_PI + ((double)i + 0.5) * dphi;
        double c1 = r * st_ * cos(ph), c2 = r * st_ * sin(ph), c3 = r * ct, p[3];
        for (int a = 0; a < 3; a++)
          p[a] = light_pos[a] + c1 * s->e[0][a] + c2 * s->e[1][a] + c3 * s->e[2][a];
        grid[(k * n_theta + j) * n_phi + i] = (float)(ics_volume_sample(vol, p) * omega * dr);
      }
    }
  }
  st = ics_sat3d_create(&s->sat, grid, n_phi, n_theta, n_r, mode);
  free(grid);
  if (st != ICS_OK) {
    free(s);
    return st;
  }
  *out = s;
  return ICS_OK;
}

void ics_ssat_destroy(ics_ssat *ssat) {
  if (!ssat) return;
  ics_sat3d_destroy(ssat->sat);
  free(ssat);
}

void ics_ssat_frame(const ics_ssat *ssat, double e_x[3], double e_y[3], double e_z[3],
                    size_t n[3]) {
  if (!ssat) return;
  if (e_x) memcpy(e_x, ssat->e[0], sizeof ssat->e[0]);
  if (e_y) memcpy(e_y, ssat->e[1], sizeof ssat->e[1]);
  if (e_z) memcpy(e_z, ssat->e[2], sizeof ssat->e[2]);
  if (n) memcpy(n, ssat->n, sizeof ssat->n);
}

/* SAT coordinate of polar angle theta: cell j covers [j dth, (j+1) dth] and holds the solid
 * angle dphi (cos(j dth) - cos((j+1) dth)) of the cell-wise constant field, so the part of it
 * above theta is the fraction (cos(j dth) - cos(theta)) / (cos(j dth) - cos((j+1) dth)) — the
 * SAT's continuous integral, linear inside a cell, is then exact in solid angle. */
static double theta_coord(double th, size_t n, double dth) {
  if (!(th > 0.0)) return 0.0;
  double j = floor(th / dth);
  if (j >= (double)n) return (double)n;
  double c0 = cos(j * dth), c1 = cos((j + 1) * dth);
  double f = (c0 - cos(th)) / (c0 - c1);
  return j + ics_clampd(f, 0.0, 1.0);
}

ics_status ics_ssat_tau(const ics_ssat *s, const double p[3], double half_width, double *tau) {
  if (!s || !p || !tau) return ICS_ERR_INVALID_ARG;
  if (isnan(half_width) || isnan(p[0]) || isnan(p[1]) || isnan(p[2])) return ICS_ERR_NAN;
  if (!(half_width > 0.0) || !isfinite(half_width) || !ics_finite3(p)) return ICS_ERR_INVALID_ARG;
  double ph0, ph1, th0, th1, R;
  ics_status st = ics_ssat_patch_box(s->light, s->e, p, half_width, &ph0, &ph1, &th0, &th1, &R);
  if (st != ICS_OK) return st;
  double dphi = 2 * ICS_PI / (double)s->n[0], dth = ICS_PI / (double)s->n[1];
  double dr = s->r_max / (double)s->n[2];
  double lo[3] = {0, theta_coord(th0, s->n[1], dth), 0.0};
  double hi[3] = {0, theta_coord(th1, s->n[1], dth), R / dr};
  double sum = 0.0;
  /* phi intervals inside [-pi, pi]: the whole ring, or one interval that wraps at most once */
  double seg[2][2];
  int ns = 0;
  if (ph1 - ph0 >= 2 * ICS_PI) {
    seg[ns][0] = -ICS_PI, seg[ns++][1] = ICS_PI;
  } else if (ph0 < -ICS_PI) {
    seg[ns][0] = ph0 + 2 * ICS_PI, seg[ns++][1] = ICS_PI;
    seg[ns][0] = -ICS_PI, seg[ns++][1] = ph1;
  } else if (ph1 > ICS_PI) {
    seg[ns][0] = ph0, seg[ns++][1] = ICS_PI;
    seg[ns][0] = -ICS_PI, seg[ns++][1] = ph1 - 2 * ICS_PI;
  } else {
    seg[ns][0] = ph0, seg[ns++][1] = ph1;
  }
  for (int k = 0; k < ns; k++) {
    lo[0] = (seg[k][0] + ICS_PI) / dphi;
    hi[0] = (seg[k][1] + ICS_PI) / dphi;
    double v;
    st = ics_sat3d_integral(s->sat, lo, hi, &v);
    if (st != ICS_OK) return st;
    sum += v;
  }
  double omega = (ph1 - ph0) * (cos(th0) - cos(th1));
  *tau = omega > 0.0 ? sum / omega : 0.0;
  return ICS_OK;
}

ics_status ics_ssat_transmittance(const ics_ssat *ssat, const double p[3], double half_width,
                                  double *transmittance) {
  if (!transmittance) return ICS_ERR_INVALID_ARG;
  double tau;
  ics_status st = ics_ssat_tau(ssat, p, half_width, &tau);
  if (st == ICS_OK) *transmittance = exp(-tau);
  return st;
}
