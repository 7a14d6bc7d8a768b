/* slab_kernel.c — per-light slab kernels (see slab_kernel.h and docs/renderer.md).
 *
 * Class (Eq. 7/15): mean -e mu, covariance d1 e Sigma in world units, expressed along the
 * buffer axes (x = camera right, y = down the rows: y components change sign), then divided by
 * the pixel size q (mean) and q^2 (covariance).
 * Members: ellipse = ics_ellipse_kernel with M = ICS_SLAB_TABLE_M points equidistant in arc
 * length; tap j of entry k is point (k + j M / N) mod M (exact covariance averaged over the M
 * entries: the trapezoid rule on a smooth periodic integrand). LUT radii rescale the points in
 * the kernel's own frame by (a_lut / a, b_lut / b). Poisson = ics_kernel2d_taps with iteration k
 * for entry k (exact covariance for each rotation). Gauss = the core's N x N grid. Top-hat = an
 * N x N uniform grid z_k = -T + 2 T k / (N - 1), T = sqrt(3 (N - 1) / (N + 1)) (unit variance) in
 * the whitened frame, mapped by Sigma^(1/2).
 * Compensation: "expected" solves C' + D(C') = C by fixed-point iteration, D = the bilinear
 * interpolation variance w f (1 - f) per axis averaged over the table (f = fraction of the tap
 * offset including the mean); "integer" = the integer-shift schedule (shift = round(cum + m) -
 * round(cum), round half up) with the exact integer taps of the core's NONNEG compensation
 * centred on 0; "nonneg" / "signed" = the core's compensation of the per-slab taps. */
#include "slab_kernel.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "icshadow/constants.h"
#include "icshadow/conv.h"
#include "icshadow/ellipse.h"
#include "icshadow/light.h"
#include "icshadow/lut.h"
#include "icshadow/rng.h"

/* the taps of the member that runs (sk->run_member, sk->run_samples) for class covariance cls
 * (pixels^2), zero mean: entries * n into out */
static ics_status member_taps(const ics_slab_kernel *sk, const double cls[3], ics_tap2d *out) {
  int n = sk->run_samples, M = sk->entries;
  ics_render_kernel member = sk->run_member;
  if (member == ICS_RK_ELLIPSE) {
    double vx, vy, ang;
    if (ics_light_cov_to_eig(cls, &vx, &vy, &ang) != ICS_OK) return ICS_ERR_NEGATIVE_VARIANCE;
    double *xy = malloc(sizeof *xy * 2 * (size_t)M);
    if (!xy) return ICS_ERR_NOMEM;
    ics_ellipse_shape sh;
    ics_status st = ics_ellipse_kernel(vx, vy, ang, M, 0.0, &sh, xy);
    if (st != ICS_OK) {
      free(xy);
      return st;
    }
    if (sh.nsamples == 1)
      for (int i = 1; i < M; i++) xy[2 * i] = xy[2 * i + 1] = 0;
    if (sk->lut_radii && sh.nsamples > 1) {
      double al, bl;
      ics_lut_ellipse_radii(vx, vy, &al, &bl);
      double fx = sh.a > 0 ? al / sh.a : 1, fy = sh.b > 0 ? bl / sh.b : 1;
      double a = sh.angle_deg * (ICS_PI / 180), co = cos(a), si = sin(a);
      for (int i = 0; i < M; i++) {
        double x = xy[2 * i], y = xy[2 * i + 1];
        double u = co * x + si * y, v = -si * x + co * y; /* kernel frame */
        u *= fx, v *= fy;
        xy[2 * i] = co * u - si * v;
        xy[2 * i + 1] = si * u + co * v;
      }
    }
    for (int k = 0; k < M; k++)
      for (int j = 0; j < n; j++) {
        int p = (k + j * (M / n)) % M;
        out[k * n + j] = (ics_tap2d){xy[2 * p], xy[2 * p + 1], 1.0 / n};
      }
    free(xy);
    return ICS_OK;
  }
  if (member == ICS_RK_POISSON || member == ICS_RK_GAUSS) {
    ics_class2d c = {{0, 0}, cls[0], cls[1], cls[2]};
    ics_kernel2d kk;
    ics_status st = ics_kernel2d_init(
        &kk, member == ICS_RK_POISSON ? ICS_KERNEL_POISSON : ICS_KERNEL_GAUSS, &c);
    if (st != ICS_OK) return st;
    kk.nsamples = n;
    kk.seed = sk->seed;
    int per = member == ICS_RK_POISSON ? n : n * n;
    for (int k = 0; k < M; k++) {
      int got;
      st = ics_kernel2d_taps(&kk, (uint64_t)k, out + (size_t)k * per, per, &got);
      if (st != ICS_OK) return st;
      for (int j = got; j < per; j++) out[k * per + j] = (ics_tap2d){0, 0, 0};
    }
    return ICS_OK;
  }
  /* tophat */
  /* the grid in the whitened frame mapped by the class's symmetric root R (R R = cls; not PSD
   * beyond rounding: refused) */
  double vx, vy, ang, R[3];
  if (ics_light_cov_to_eig(cls, &vx, &vy, &ang) != ICS_OK || ics_light_cov_sqrt(cls, R) < 0)
    return ICS_ERR_NEGATIVE_VARIANCE;
  double T = sqrt(3.0 * (n - 1) / (n + 1));
  for (int a = 0; a < n; a++)
    for (int b = 0; b < n; b++) {
      double zx = -T + 2 * T * a / (n - 1), zy = -T + 2 * T * b / (n - 1);
      out[a * n + b] = (ics_tap2d){R[0] * zx + R[1] * zy, R[1] * zx + R[2] * zy, 1.0 / (n * n)};
    }
  return ICS_OK;
}

/* max over a 33 x 33 grid of frequencies in [-pi, pi]^2 of |sum_j w_j exp(i w . x_j)|: 1 for
 * non-negative weights summing to 1, more when signed weights amplify a frequency */
double ics_taps_amplification(const ics_tap2d *t, int n) {
  /* for integer taps (what compensation returns) the phase pi a x / 16 lives on 32 values (a
   * table of the call's own: the plan builds its lights' kernels on several threads, and 64
   * sines and cosines are little beside the 33 x 33 x n sums below) */
  double ct[32], st[32];
  for (int i = 0; i < 32; i++) ct[i] = cos(ICS_PI * i / 16), st[i] = sin(ICS_PI * i / 16);
  int integer = 1;
  for (int j = 0; j < n && integer; j++) integer = t[j].x == floor(t[j].x) && t[j].y == floor(t[j].y);
  double worst = 0;
  for (int a = -16; a <= 16; a++)
    for (int b = -16; b <= 16; b++) {
      double re = 0, im = 0;
      for (int j = 0; j < n; j++) {
        if (integer) {
          long ph = ((long)a * (long)t[j].x + (long)b * (long)t[j].y) & 31;
          re += t[j].w * ct[ph];
          im += t[j].w * st[ph];
        } else {
          double ph = ICS_PI * (a * t[j].x + b * t[j].y) / 16;
          re += t[j].w * cos(ph);
          im += t[j].w * sin(ph);
        }
      }
      worst = fmax(worst, sqrt(re * re + im * im));
    }
  return worst;
}

static double frac_var(double x) {
  double f = x - floor(x);
  return f * (1 - f);
}

/* bilinear interpolation variance averaged over the table, per axis */
static void interp_var(const ics_tap2d *t, int count, const double mean[2], double D[2]) {
  double sx = 0, sy = 0, sw = 0;
  for (int i = 0; i < count; i++) {
    sx += t[i].w * frac_var(t[i].x + mean[0]);
    sy += t[i].w * frac_var(t[i].y + mean[1]);
    sw += t[i].w;
  }
  D[0] = sx / sw;
  D[1] = sy / sw;
}

static int psd(const double c[3]) {
  return c[0] > 0 && c[2] > 0 && c[0] * c[2] - c[1] * c[1] > 1e-12 * (c[0] + c[2]) * (c[0] + c[2]);
}

/* exact integer taps of covariance cov (pixels^2) about 0: the core's NONNEG compensation of a
 * 5 x 5 Gaussian grid on an integer mean (always exact: residual 0 up to rounding) */
static ics_status integer_taps(const double cov[3], ics_tap2d **out, int *n, double resid[3]) {
  ics_class2d c = {{0, 0}, cov[0], cov[1], cov[2]};
  ics_kernel2d kk;
  ics_status st = ics_kernel2d_init(&kk, ICS_KERNEL_GAUSS, &c);
  if (st != ICS_OK) return st;
  kk.nsamples = 5;
  ics_tap2d g[25];
  int ng;
  st = ics_kernel2d_taps(&kk, 0, g, 25, &ng);
  if (st != ICS_OK) return st;
  int cap = 4 * ng + 9;
  ics_tap2d *t = malloc(sizeof *t * (size_t)cap);
  if (!t) return ICS_ERR_NOMEM;
  st = ics_taps2d_compensate(g, ng, ICS_COMP_NONNEG, t, cap, n, resid);
  if (st != ICS_OK) {
    free(t);
    return st;
  }
  *out = t;
  return ICS_OK;
}

static int member_stochastic(ics_render_kernel m) {
  return m == ICS_RK_ELLIPSE || m == ICS_RK_POISSON;
}

static int member_taps_per_entry(ics_render_kernel m, int n) {
  return m == ICS_RK_GAUSS || m == ICS_RK_TOPHAT ? n * n : n;
}

static ics_status set_integer(ics_slab_kernel *sk, const char *why) {
  free(sk->base);
  sk->base = NULL;
  sk->mode = ICS_SLAB_INTEGER;
  sk->entries = 1;
  sk->integer = 1;
  snprintf(sk->why, sizeof sk->why, "%s", why);
  ics_status st = integer_taps(sk->cov_px, &sk->base, &sk->base_taps, sk->residual);
  sk->taps = sk->base_taps;
  sk->cap = 4 * 25 + 9; /* integer_taps' largest output (perspective recomputes per depth) */
  memcpy(sk->class_px, sk->cov_px, sizeof sk->class_px);
  return st;
}

/* light k's kernel from the scene's settings at pixel size q (its member, mode and taps) */
static ics_status kernel_from_scene(ics_slab_kernel *sk, const ics_scene *s, int k, double q,
                                    char *msg, size_t msg_size);

/* pixels any read of this kernel can reach at the reference depth: the farthest tap plus the
 * mean, the bilinear neighbour and the integer schedule's rounding */
static int reach_bound(const ics_slab_kernel *sk) {
  double r = 0;
  const ics_tap2d *t = sk->fixed ? sk->fixed : sk->base;
  int n = sk->fixed ? sk->nfixed : sk->base ? sk->entries * sk->base_taps : 0;
  for (int j = 0; j < n; j++) r = fmax(r, fmax(fabs(t[j].x), fabs(t[j].y)));
  double m = fmax(fabs(sk->mean_px[0]), fabs(sk->mean_px[1]));
  return (int)ceil(r + (sk->fixed ? 0 : m)) + 3;
}

/* mode TAPS with the core's per-slab compensation (sk->comp NONNEG or SIGNED); a deterministic
 * member's compensated taps are the same every slab at the reference depth: computed once */
static ics_status per_slab_compensation(ics_slab_kernel *sk, double q, char *msg, size_t msg_size,
                                        int k) {
  sk->mode = ICS_SLAB_TAPS;
  sk->taps = sk->cap = 4 * sk->base_taps + 9; /* the compensated set's capacity */
  if (member_stochastic(sk->run_member)) return ICS_OK;
  ics_tap2d *fixed = malloc(sizeof *fixed * (size_t)sk->cap);
  if (!fixed) return ICS_ERR_NOMEM;
  double cum[2] = {0, 0};
  int nfixed;
  ics_status st = ics_slab_kernel_taps(sk, 0, q, cum, fixed, &nfixed); /* sk->fixed NULL: computes */
  if (st != ICS_OK) {
    free(fixed);
    if (msg) snprintf(msg, msg_size, "light %d: compensation: %s", k, ics_status_str(st));
    return st;
  }
  sk->fixed = fixed;
  sk->nfixed = sk->taps = nfixed;
  return ICS_OK;
}

ics_status ics_slab_kernel_init(ics_slab_kernel *sk, const ics_scene *s, int k, double q,
                                char *msg, size_t msg_size) {
  ics_status st = kernel_from_scene(sk, s, k, q, msg, msg_size);
  sk->out_entries = 1;
  if (sk->mode == ICS_SLAB_TABLE && ics_scene_camera(s)->projection != ICS_PROJ_PERSPECTIVE) {
    int K = ics_scene_settings(s)->pixel_rotations;
    sk->out_entries = K > 0 && K <= sk->entries && sk->entries % K == 0 ? K : sk->entries;
  }
  sk->reach_bound = reach_bound(sk);
  return st;
}

static ics_status kernel_from_scene(ics_slab_kernel *sk, const ics_scene *s, int k, double q,
                                    char *msg, size_t msg_size) {
  memset(sk, 0, sizeof *sk);
  const ics_render_settings *rs = ics_scene_settings(s);
  const ics_light *L = ics_scene_light(s, k);
  double e = rs->slab_spacing, d1 = rs->d1;
  sk->light = k;
  sk->member = sk->run_member = rs->kernel;
  sk->samples = sk->run_samples = rs->samples;
  sk->lut_radii = rs->lut_radii;
  sk->seed = rs->seed;
  sk->comp = rs->compensate;
  if (sk->comp == ICS_RC_DEFAULT)
    sk->comp = member_stochastic(sk->member) ? ICS_RC_EXPECTED : ICS_RC_NONNEG;
  sk->mean_w[0] = -e * L->mean[0];
  sk->mean_w[1] = e * L->mean[1];
  sk->cov_w[0] = d1 * e * L->cov[0];
  sk->cov_w[1] = -d1 * e * L->cov[1];
  sk->cov_w[2] = d1 * e * L->cov[2];
  sk->q_ref = q;
  sk->mean_px[0] = sk->mean_w[0] / q;
  sk->mean_px[1] = sk->mean_w[1] / q;
  for (int i = 0; i < 3; i++) sk->cov_px[i] = sk->cov_w[i] / (q * q);
  if (sk->cov_px[0] == 0 && sk->cov_px[1] == 0 && sk->cov_px[2] == 0) {
    sk->mode = ICS_SLAB_SHIFT;
    sk->entries = 1;
    sk->taps = sk->cap = 1;
    sk->integer = 1;
    snprintf(sk->why, sizeof sk->why, "zero variance: one integer shift per slab, no taps");
    return ICS_OK;
  }
  if (sk->comp == ICS_RC_INTEGER) {
    ics_status st = set_integer(sk, "compensate = integer: integer shifts and exact integer taps");
    if (st != ICS_OK && msg)
      snprintf(msg, msg_size, "light %d: integer taps: %s", k, ics_status_str(st));
    return st;
  }
  int stoch = member_stochastic(sk->member);
  int per_slab = sk->comp == ICS_RC_NONNEG || sk->comp == ICS_RC_SIGNED;
  sk->entries = stoch ? ICS_SLAB_TABLE_M : 1;
  sk->base_taps = member_taps_per_entry(sk->member, sk->samples);
  sk->taps = sk->cap = sk->base_taps;
  sk->base = malloc(sizeof *sk->base * (size_t)sk->entries * (size_t)sk->base_taps);
  if (!sk->base) return ICS_ERR_NOMEM;
  double cls[3] = {sk->cov_px[0], sk->cov_px[1], sk->cov_px[2]};
  ics_status st;
  if (sk->comp == ICS_RC_EXPECTED && ics_scene_camera(s)->projection == ICS_PROJ_PERSPECTIVE) {
    /* perspective: the backend compensates each slab's set per class of the magnification's
     * fraction (propagate.h), which needs the full class */
    st = member_taps(sk, cls, sk->base);
    if (st != ICS_OK) return st;
    memcpy(sk->class_px, cls, sizeof cls);
    sk->mode = stoch ? ICS_SLAB_TABLE : ICS_SLAB_TAPS;
    snprintf(sk->why, sizeof sk->why, "perspective: %s, compensated per class of the "
             "magnification's fraction", stoch ? "one random tap set per slab" : "one tap set per slab");
    return ICS_OK;
  }
  if (sk->comp == ICS_RC_EXPECTED) {
    int ok = 0;
    for (int it = 0; it < 60; it++) {
      st = member_taps(sk, cls, sk->base);
      if (st != ICS_OK) break;
      double D[2];
      interp_var(sk->base, sk->entries * sk->base_taps, sk->mean_px, D);
      double nc[3] = {sk->cov_px[0] - D[0], sk->cov_px[1], sk->cov_px[2] - D[1]};
      if (!psd(nc)) break;
      double change = fabs(nc[0] - cls[0]) + fabs(nc[2] - cls[2]);
      memcpy(cls, nc, sizeof cls);
      if (change <= 1e-13 * (sk->cov_px[0] + sk->cov_px[2])) {
        st = member_taps(sk, cls, sk->base);
        ok = st == ICS_OK;
        break;
      }
    }
    if (!ok) {
      /* too narrow for per-pixel random taps: a deterministic 3 x 3 Gaussian with the core's
       * non-negative compensation per slab keeps the exact mean and covariance when it can (the
       * variance above the mean's fraction's f (1 - f)); else the integer-shift schedule does */
      sk->run_member = ICS_RK_GAUSS;
      sk->run_samples = 3;
      sk->comp = ICS_RC_NONNEG;
      sk->entries = 1;
      sk->base_taps = 9;
      ics_tap2d *b = realloc(sk->base, sizeof *b * 9);
      if (!b) return ICS_ERR_NOMEM;
      sk->base = b;
      memcpy(cls, sk->cov_px, sizeof cls);
      st = member_taps(sk, cls, sk->base);
      double resid[3] = {0, 0, 0};
      if (st == ICS_OK) {
        ics_tap2d raw[9], out[4 * 9 + 9];
        int nout;
        for (int j = 0; j < 9; j++)
          raw[j] = (ics_tap2d){sk->base[j].x + sk->mean_px[0], sk->base[j].y + sk->mean_px[1], sk->base[j].w};
        st = ics_taps2d_compensate(raw, 9, ICS_COMP_NONNEG, out, 4 * 9 + 9, &nout, resid);
      }
      double tr = sk->cov_px[0] + sk->cov_px[2];
      if (st == ICS_OK && fabs(resid[0]) + fabs(resid[1]) + fabs(resid[2]) <= 1e-9 * tr) {
        st = per_slab_compensation(sk, q, msg, msg_size, k);
        snprintf(sk->why, sizeof sk->why, "per-slab variance (%.3g, %.3g) px^2 is too small for "
                 "expected compensation: 3 x 3 Gaussian taps, non-negative compensation (exact)",
                 sk->cov_px[0], sk->cov_px[2]);
        return st;
      }
      char why[160];
      snprintf(why, sizeof why, "per-slab variance (%.3g, %.3g) px^2 is below what non-negative "
               "taps reach at this mean: integer shifts and exact integer taps",
               sk->cov_px[0], sk->cov_px[2]);
      sk->run_member = sk->member;
      sk->run_samples = sk->samples;
      sk->comp = ICS_RC_INTEGER;
      return set_integer(sk, why);
    }
    memcpy(sk->class_px, cls, sizeof cls);
    sk->mode = stoch ? ICS_SLAB_TABLE : ICS_SLAB_TAPS;
    snprintf(sk->why, sizeof sk->why, "%s; class reduced by the expected interpolation "
             "variance (%.3g, %.3g) px^2", stoch ? "random tap set per slab and pixel" :
             "one tap set per slab", sk->cov_px[0] - cls[0], sk->cov_px[2] - cls[2]);
    return ICS_OK;
  }
  st = member_taps(sk, cls, sk->base);
  if (st != ICS_OK) {
    if (msg) snprintf(msg, msg_size, "light %d: kernel taps: %s", k, ics_status_str(st));
    return st;
  }
  memcpy(sk->class_px, cls, sizeof cls);
  if (sk->comp == ICS_RC_NONE) {
    sk->mode = stoch ? ICS_SLAB_TABLE : ICS_SLAB_TAPS;
    snprintf(sk->why, sizeof sk->why, "%s; no compensation (interpolation adds its variance)",
             stoch ? "random tap set per slab and pixel" : "one tap set per slab");
    return ICS_OK;
  }
  (void)per_slab;
  st = per_slab_compensation(sk, q, msg, msg_size, k);
  snprintf(sk->why, sizeof sk->why, "%s; %s compensation of each slab's taps",
           stoch ? "one random tap set per slab (compensation needs one set per slab)"
                 : "one tap set per slab",
           sk->comp == ICS_RC_NONNEG ? "non-negative" : "signed");
  return st;
}

void ics_slab_kernel_release(ics_slab_kernel *sk) {
  free(sk->base);
  free(sk->fixed);
  sk->base = sk->fixed = NULL;
}

void ics_slab_kernel_key_of(const ics_scene *s, int k, double q, ics_slab_kernel_key *key) {
  const ics_render_settings *rs = ics_scene_settings(s);
  const ics_light *L = ics_scene_light(s, k);
  memset(key, 0, sizeof *key);
  memcpy(key->mean, L->mean, sizeof key->mean);
  memcpy(key->cov, L->cov, sizeof key->cov);
  key->q = q, key->slab_spacing = rs->slab_spacing, key->d1 = rs->d1, key->seed = rs->seed;
  key->light = k, key->projection = (int)ics_scene_camera(s)->projection;
  key->kernel = (int)rs->kernel, key->samples = rs->samples, key->lut_radii = rs->lut_radii;
  key->compensate = (int)rs->compensate, key->pixel_rotations = rs->pixel_rotations;
}

/* n taps of src in a new array (NULL for none), *ok 0 when out of memory */
static ics_tap2d *taps_copy(const ics_tap2d *src, size_t n, int *ok) {
  if (!src || !n) return NULL;
  ics_tap2d *t = malloc(sizeof *t * n);
  if (t) memcpy(t, src, sizeof *t * n);
  else *ok = 0;
  return t;
}

ics_status ics_slab_kernel_copy(ics_slab_kernel *dst, const ics_slab_kernel *src) {
  int ok = 1;
  *dst = *src;
  dst->base = taps_copy(src->base, (size_t)src->entries * (size_t)src->base_taps, &ok);
  dst->fixed = taps_copy(src->fixed, (size_t)src->nfixed, &ok);
  if (ok) return ICS_OK;
  ics_slab_kernel_release(dst);
  return ICS_ERR_NOMEM;
}

static double round_half_up(double x) { return floor(x + 0.5); }

ics_status ics_slab_kernel_taps(const ics_slab_kernel *sk, uint64_t slab, double q,
                                double cum_mean[2], ics_tap2d *out, int *nout) {
  double m[2] = {sk->mean_w[0] / q, sk->mean_w[1] / q};
  if (sk->mode == ICS_SLAB_SHIFT || sk->mode == ICS_SLAB_INTEGER) {
    double sh[2];
    for (int i = 0; i < 2; i++) {
      sh[i] = round_half_up(cum_mean[i] + m[i]) - round_half_up(cum_mean[i]);
      cum_mean[i] += m[i];
    }
    if (sk->mode == ICS_SLAB_SHIFT) {
      out[0] = (ics_tap2d){sh[0], sh[1], 1};
      *nout = 1;
      return ICS_OK;
    }
    if (q != sk->q_ref) {
      /* perspective: the exact integer taps of this depth's covariance */
      double cov[3] = {sk->cov_w[0] / (q * q), sk->cov_w[1] / (q * q), sk->cov_w[2] / (q * q)};
      ics_tap2d *t;
      int n;
      double r[3];
      ics_status st = integer_taps(cov, &t, &n, r);
      if (st != ICS_OK) return st;
      if (n > sk->cap) { /* cannot happen: integer_taps returns at most 4 * 25 + 9 */
        free(t);
        return ICS_ERR_SIZE;
      }
      for (int j = 0; j < n; j++) out[j] = (ics_tap2d){t[j].x + sh[0], t[j].y + sh[1], t[j].w};
      free(t);
      *nout = n;
      return ICS_OK;
    }
    for (int j = 0; j < sk->base_taps; j++)
      out[j] = (ics_tap2d){sk->base[j].x + sh[0], sk->base[j].y + sh[1], sk->base[j].w};
    *nout = sk->base_taps;
    return ICS_OK;
  }
  double scale = sk->q_ref / q;
  if (sk->mode == ICS_SLAB_TABLE) {
    /* the slab's candidates: K table entries spaced M / K apart from a random first one (all M
     * entries when K = M); each pixel takes one of them (ics_slab_entry's word) */
    int M = sk->entries, K = sk->out_entries, nb = sk->base_taps;
    int k0 = K == M ? 0 : (int)ics_slab_entry(sk->seed, (uint32_t)sk->light, (uint32_t)slab, UINT32_MAX - 1);
    int step = ics_slab_candidate_step(sk);
    for (int e = 0; e < K; e++) {
      const ics_tap2d *b = sk->base + (size_t)((k0 + e * step) % M) * (size_t)nb;
      for (int j = 0; j < nb; j++)
        out[e * nb + j] = (ics_tap2d){b[j].x * scale + m[0], b[j].y * scale + m[1], b[j].w};
    }
    *nout = K * nb;
    return ICS_OK;
  }
  if (sk->mode == ICS_SLAB_TAPS && (sk->comp == ICS_RC_EXPECTED || sk->comp == ICS_RC_NONE)) {
    int n = sk->entries * sk->base_taps;
    for (int j = 0; j < n; j++)
      out[j] = (ics_tap2d){sk->base[j].x * scale + m[0], sk->base[j].y * scale + m[1], sk->base[j].w};
    *nout = n;
    return ICS_OK;
  }
  /* nonneg / signed: this slab's tap set, compensated by the core (deterministic members at the
   * reference depth: the same every slab, computed once in init) */
  if (sk->fixed && q == sk->q_ref) {
    memcpy(out, sk->fixed, sizeof *out * (size_t)sk->nfixed);
    *nout = sk->nfixed;
    return ICS_OK;
  }
  int entry = 0;
  if (member_stochastic(sk->run_member))
    entry = (int)ics_slab_entry(sk->seed, (uint32_t)sk->light, (uint32_t)slab, UINT32_MAX);
  ics_tap2d *raw = malloc(sizeof *raw * (size_t)sk->base_taps);
  if (!raw) return ICS_ERR_NOMEM;
  const ics_tap2d *b = sk->base + (size_t)entry * (size_t)sk->base_taps;
  for (int j = 0; j < sk->base_taps; j++)
    raw[j] = (ics_tap2d){b[j].x * scale + m[0], b[j].y * scale + m[1], b[j].w};
  ics_status st = ics_taps2d_compensate(raw, sk->base_taps,
                                        sk->comp == ICS_RC_NONNEG ? ICS_COMP_NONNEG : ICS_COMP_SIGNED,
                                        out, sk->cap, nout, NULL);
  /* signed weights can amplify some frequency (|sum w e^{i w.x}| > 1), and then the slabs
   * multiply it into an explosion: such a set is replaced by the non-negative compensation */
  if (st == ICS_OK && sk->comp == ICS_RC_SIGNED && ics_taps_amplification(out, *nout) > 1 + 1e-9)
    st = ics_taps2d_compensate(raw, sk->base_taps, ICS_COMP_NONNEG, out, sk->cap, nout, NULL);
  free(raw);
  return st;
}

int ics_slab_candidate_step(const ics_slab_kernel *sk) {
  int M = sk->entries, K = sk->out_entries, N = sk->run_samples;
  if (K == M) return 1;
  int step = M / (K * (sk->run_member == ICS_RK_ELLIPSE ? N : 1));
  return step > 0 ? step : 1;
}
