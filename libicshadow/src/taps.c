/* taps.c — tap lists (see icshadow/taps.h): moments by compensated sums, the interpolation
 * variance, discretisation into the integer taps the engine applies, and variance compensation.
 *
 * Sums: moments use Neumaier-compensated sums and a two-pass (mean, then central) variance.
 *
 * Compensation (ics_taps1d_compensate): the discrete variance of the shrunk taps
 * D(s) = sum w [s^2 (x - m)^2 + f(1 - f)] / sum w, f = frac(m + s (x - m)), is continuous in s,
 * D(1) >= V (interpolation only adds) and D(0) = f_m (1 - f_m). If D(0) <= V a root exists and
 * is found by bisection to the last bit of s; otherwise no non-negative integer taps reach V
 * (f_m (1 - f_m) is the least variance of any distribution on the integers with mean m).
 * 2D: A = T^(1/2) Sigma^(-1/2), T = Sigma - D(A) by a damped fixed-point iteration; falls back to
 * an isotropic shrink matching the trace (residual reported) when Sigma is singular or T leaves
 * the PSD cone. */
#include "icshadow/taps.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "icshadow/kernel.h"
#include "sym2.h"
#include "taps_check.h"

#define MAX_OFFSET 0x1p30

/* ---------------------------------------------------------------- compensated sums */
typedef struct ksum {
  double s, c;
} ksum;

static void kadd(ksum *k, double x) {
  double t = k->s + x;
  if (fabs(k->s) >= fabs(x))
    k->c += (k->s - t) + x;
  else
    k->c += (x - t) + k->s;
  k->s = t;
}

static double kval(const ksum *k) { return k->s + k->c; }

void ics_taps1d_moments(const ics_tap1d *t, int n, double *wsum, double *mean, double *var) {
  double W = NAN, M = NAN, V = NAN;
  if (t && n > 0) {
    ksum sw = {0, 0}, sx = {0, 0};
    for (int j = 0; j < n; j++) {
      kadd(&sw, t[j].w);
      kadd(&sx, t[j].w * t[j].x);
    }
    W = kval(&sw);
    M = kval(&sx) / W;
    ksum sv = {0, 0};
    for (int j = 0; j < n; j++) {
      double d = t[j].x - M;
      kadd(&sv, t[j].w * d * d);
    }
    V = kval(&sv) / W;
  }
  if (wsum) *wsum = W;
  if (mean) *mean = M;
  if (var) *var = V;
}

void ics_taps2d_moments(const ics_tap2d *t, int n, double *wsum, double mean[2], double cov[3]) {
  double W = NAN, mx = NAN, my = NAN, cxx = NAN, cxy = NAN, cyy = NAN;
  if (t && n > 0) {
    ksum sw = {0, 0}, sx = {0, 0}, sy = {0, 0};
    for (int j = 0; j < n; j++) {
      kadd(&sw, t[j].w);
      kadd(&sx, t[j].w * t[j].x);
      kadd(&sy, t[j].w * t[j].y);
    }
    W = kval(&sw);
    mx = kval(&sx) / W;
    my = kval(&sy) / W;
    ksum a = {0, 0}, b = {0, 0}, c = {0, 0};
    for (int j = 0; j < n; j++) {
      double dx = t[j].x - mx, dy = t[j].y - my;
      kadd(&a, t[j].w * dx * dx);
      kadd(&b, t[j].w * dx * dy);
      kadd(&c, t[j].w * dy * dy);
    }
    cxx = kval(&a) / W;
    cxy = kval(&b) / W;
    cyy = kval(&c) / W;
  }
  if (wsum) *wsum = W;
  if (mean) mean[0] = mx, mean[1] = my;
  if (cov) cov[0] = cxx, cov[1] = cxy, cov[2] = cyy;
}

ics_status ics_taps1d_check(const ics_tap1d *t, int n) {
  if (!t || n <= 0) return ICS_ERR_INVALID_ARG;
  if (n > 4 * ICS_KERNEL_MAX_TAPS) return ICS_ERR_SIZE;
  for (int j = 0; j < n; j++) {
    if (isnan(t[j].x) || isnan(t[j].w)) return ICS_ERR_NAN;
    if (isinf(t[j].x) || isinf(t[j].w)) return ICS_ERR_INFINITE;
    if (fabs(t[j].x) > MAX_OFFSET) return ICS_ERR_RANGE;
  }
  return ICS_OK;
}

static ics_status check_taps2d(const ics_tap2d *t, int n) {
  if (!t || n <= 0) return ICS_ERR_INVALID_ARG;
  if (n > 4 * ICS_KERNEL_MAX_TAPS) return ICS_ERR_SIZE;
  for (int j = 0; j < n; j++) {
    if (isnan(t[j].x) || isnan(t[j].y) || isnan(t[j].w)) return ICS_ERR_NAN;
    if (isinf(t[j].x) || isinf(t[j].y) || isinf(t[j].w)) return ICS_ERR_INFINITE;
    if (fabs(t[j].x) > MAX_OFFSET || fabs(t[j].y) > MAX_OFFSET) return ICS_ERR_RANGE;
  }
  return ICS_OK;
}

double ics_taps1d_interp_var(const ics_tap1d *t, int n) {
  if (!t || n <= 0) return NAN;
  double s = 0, sw = 0;
  for (int j = 0; j < n; j++) {
    double f = t[j].x - floor(t[j].x);
    s += t[j].w * f * (1 - f);
    sw += t[j].w;
  }
  return s / sw;
}

void ics_taps2d_interp_var(const ics_tap2d *t, int n, double out[2]) {
  if (!out) return;
  if (!t || n <= 0) {
    out[0] = out[1] = NAN;
    return;
  }
  double sx = 0, sy = 0, sw = 0;
  for (int j = 0; j < n; j++) {
    double fx = t[j].x - floor(t[j].x), fy = t[j].y - floor(t[j].y);
    sx += t[j].w * fx * (1 - fx);
    sy += t[j].w * fy * (1 - fy);
    sw += t[j].w;
  }
  out[0] = sx / sw;
  out[1] = sy / sw;
}

static int cmp1(const void *a, const void *b) {
  double x = ((const ics_tap1d *)a)->x, y = ((const ics_tap1d *)b)->x;
  return (x > y) - (x < y);
}

static int cmp2(const void *a, const void *b) {
  const ics_tap2d *p = a, *q = b;
  if (p->x != q->x) return (p->x > q->x) - (p->x < q->x);
  return (p->y > q->y) - (p->y < q->y);
}

/* sort, merge equal offsets, drop zero weights; returns new count */
static int merge1(ics_tap1d *t, int n) {
  qsort(t, (size_t)n, sizeof *t, cmp1);
  int m = 0;
  for (int j = 0; j < n; j++) {
    if (m > 0 && t[m - 1].x == t[j].x)
      t[m - 1].w += t[j].w;
    else
      t[m++] = t[j];
  }
  int k = 0;
  for (int j = 0; j < m; j++)
    if (t[j].w != 0) t[k++] = t[j];
  return k;
}

static int merge2(ics_tap2d *t, int n) {
  qsort(t, (size_t)n, sizeof *t, cmp2);
  int m = 0;
  for (int j = 0; j < n; j++) {
    if (m > 0 && t[m - 1].x == t[j].x && t[m - 1].y == t[j].y)
      t[m - 1].w += t[j].w;
    else
      t[m++] = t[j];
  }
  int k = 0;
  for (int j = 0; j < m; j++)
    if (t[j].w != 0) t[k++] = t[j];
  return k;
}

/* split without the capacity check: out must hold 2 n */
static int split1(const ics_tap1d *in, int n, ics_tap1d *out) {
  int m = 0;
  for (int j = 0; j < n; j++) {
    double i = floor(in[j].x), f = in[j].x - i;
    out[m].x = i, out[m].w = in[j].w * (1 - f), m++;
    if (f > 0) out[m].x = i + 1, out[m].w = in[j].w * f, m++;
  }
  return merge1(out, m);
}

static int split2(const ics_tap2d *in, int n, ics_tap2d *out) {
  int m = 0;
  for (int j = 0; j < n; j++) {
    double ix = floor(in[j].x), fx = in[j].x - ix;
    double iy = floor(in[j].y), fy = in[j].y - iy;
    double w = in[j].w;
    out[m++] = (ics_tap2d){ix, iy, w * (1 - fx) * (1 - fy)};
    if (fx > 0) out[m++] = (ics_tap2d){ix + 1, iy, w * fx * (1 - fy)};
    if (fy > 0) out[m++] = (ics_tap2d){ix, iy + 1, w * (1 - fx) * fy};
    if (fx > 0 && fy > 0) out[m++] = (ics_tap2d){ix + 1, iy + 1, w * fx * fy};
  }
  return merge2(out, m);
}

ics_status ics_taps1d_discretize(const ics_tap1d *in, int n, ics_tap1d *out, int cap, int *nout) {
  ics_status st = ics_taps1d_check(in, n);
  if (st != ICS_OK) return st;
  if (!out || !nout) return ICS_ERR_INVALID_ARG;
  ics_tap1d *tmp = malloc(sizeof *tmp * 2 * (size_t)n);
  if (!tmp) return ICS_ERR_NOMEM;
  int m = split1(in, n, tmp);
  if (m > cap) {
    free(tmp);
    return ICS_ERR_SIZE;
  }
  memcpy(out, tmp, sizeof *tmp * (size_t)m);
  free(tmp);
  *nout = m;
  return ICS_OK;
}

ics_status ics_taps2d_discretize(const ics_tap2d *in, int n, ics_tap2d *out, int cap, int *nout) {
  ics_status st = check_taps2d(in, n);
  if (st != ICS_OK) return st;
  if (!out || !nout) return ICS_ERR_INVALID_ARG;
  ics_tap2d *tmp = malloc(sizeof *tmp * 4 * (size_t)n);
  if (!tmp) return ICS_ERR_NOMEM;
  int m = split2(in, n, tmp);
  if (m > cap) {
    free(tmp);
    return ICS_ERR_SIZE;
  }
  memcpy(out, tmp, sizeof *tmp * (size_t)m);
  free(tmp);
  *nout = m;
  return ICS_OK;
}

/* ---------------------------------------------------------------- compensation, 1D */
/* discrete variance of taps m + s (x - m) after linear interpolation */
static double dvar1(const ics_tap1d *t, int n, double m, double s, double W) {
  double acc = 0, c = 0;
  for (int j = 0; j < n; j++) {
    double d = s * (t[j].x - m), p = m + d, f = p - floor(p);
    double term = t[j].w * (d * d + f * (1 - f));
    double y = term - c, z = acc + y; /* Kahan */
    c = (z - acc) - y;
    acc = z;
  }
  return acc / W;
}

ics_status ics_taps1d_compensate(const ics_tap1d *in, int n, ics_comp_mode mode, ics_tap1d *out,
                                 int cap, int *nout, double *residual) {
  ics_status st = ics_taps1d_check(in, n);
  if (st != ICS_OK) return st;
  if (!out || !nout) return ICS_ERR_INVALID_ARG;
  if (mode != ICS_COMP_NONE && mode != ICS_COMP_NONNEG && mode != ICS_COMP_SIGNED)
    return ICS_ERR_RANGE;
  double W, m, V;
  ics_taps1d_moments(in, n, &W, &m, &V);
  if (!(W > 0)) return ICS_ERR_RANGE; /* weights must sum to a positive total */
  ics_tap1d *tmp = malloc(sizeof *tmp * (2 * (size_t)n + 3));
  if (!tmp) return ICS_ERR_NOMEM;
  double fm = m - floor(m), vmin = fm * (1 - fm);
  int cnt;
  if (mode == ICS_COMP_NONE) {
    cnt = split1(in, n, tmp);
  } else if (vmin > V && mode == ICS_COMP_SIGNED) {
    /* three integer taps k-1, k, k+1 around k = round(m), d = m - k in [-1/2, 1/2]:
     * w+ - w- = d, w+ + w- = V + d^2, w0 = 1 - V - d^2 (times the total weight) */
    double k = floor(m + 0.5), d = m - k;
    tmp[0] = (ics_tap1d){k - 1, W * 0.5 * (V + d * d - d)};
    tmp[1] = (ics_tap1d){k, W * (1 - V - d * d)};
    tmp[2] = (ics_tap1d){k + 1, W * 0.5 * (V + d * d + d)};
    cnt = merge1(tmp, 3);
  } else {
    double s;
    if (vmin >= V) {
      s = 0; /* collapse onto floor / ceil of the mean: the least variance reachable */
    } else if (dvar1(in, n, m, 1, W) <= V) {
      s = 1; /* already on the grid */
    } else {
      double lo = 0, hi = 1;
      for (int it = 0; it < 200; it++) {
        double mid = 0.5 * (lo + hi);
        if (mid <= lo || mid >= hi) break;
        if (dvar1(in, n, m, mid, W) < V)
          lo = mid;
        else
          hi = mid;
      }
      s = fabs(dvar1(in, n, m, lo, W) - V) < fabs(dvar1(in, n, m, hi, W) - V) ? lo : hi;
    }
    for (int j = 0; j < n; j++) tmp[j] = (ics_tap1d){m + s * (in[j].x - m), in[j].w};
    ics_tap1d *tmp2 = malloc(sizeof *tmp2 * 2 * (size_t)n);
    if (!tmp2) {
      free(tmp);
      return ICS_ERR_NOMEM;
    }
    cnt = split1(tmp, n, tmp2);
    memcpy(tmp, tmp2, sizeof *tmp * (size_t)cnt);
    free(tmp2);
  }
  if (cnt > cap) {
    free(tmp);
    return ICS_ERR_SIZE;
  }
  if (residual) {
    double v2;
    ics_taps1d_moments(tmp, cnt, NULL, NULL, &v2);
    *residual = v2 - V;
  }
  memcpy(out, tmp, sizeof *tmp * (size_t)cnt);
  *nout = cnt;
  free(tmp);
  return ICS_OK;
}

/* ---------------------------------------------------------------- compensation, 2D */
/* apply x -> m + A (x - m) (A symmetric or general 2x2 {a00, a01, a10, a11}) */
static void shrink2(const ics_tap2d *in, int n, const double m[2], const double A[4],
                    ics_tap2d *out) {
  for (int j = 0; j < n; j++) {
    double dx = in[j].x - m[0], dy = in[j].y - m[1];
    out[j].x = m[0] + A[0] * dx + A[1] * dy;
    out[j].y = m[1] + A[2] * dx + A[3] * dy;
    out[j].w = in[j].w;
  }
}

/* covariance of the bilinearly discretized taps (exact identity: shape cov + diag(interp)) */
static void dcov2(const ics_tap2d *t, int n, double cov[3]) {
  double W, mm[2], c[3], iv[2];
  ics_taps2d_moments(t, n, &W, mm, c);
  ics_taps2d_interp_var(t, n, iv);
  cov[0] = c[0] + iv[0];
  cov[1] = c[1];
  cov[2] = c[2] + iv[1];
}

ics_status ics_taps2d_compensate(const ics_tap2d *in, int n, ics_comp_mode mode, ics_tap2d *out,
                                 int cap, int *nout, double residual[3]) {
  ics_status st = check_taps2d(in, n);
  if (st != ICS_OK) return st;
  if (!out || !nout) return ICS_ERR_INVALID_ARG;
  if (mode != ICS_COMP_NONE && mode != ICS_COMP_NONNEG && mode != ICS_COMP_SIGNED)
    return ICS_ERR_RANGE;
  double W, m[2], S[3];
  ics_taps2d_moments(in, n, &W, m, S);
  if (!(W > 0)) return ICS_ERR_RANGE;
  ics_tap2d *sh = malloc(sizeof *sh * (size_t)n);
  ics_tap2d *tmp = malloc(sizeof *tmp * (4 * (size_t)n + 9));
  if (!sh || !tmp) {
    free(sh);
    free(tmp);
    return ICS_ERR_NOMEM;
  }
  int cnt = 0, done = 0;
  double scale = (S[0] + S[2]) + 1.0;
  if (mode == ICS_COMP_NONE) {
    cnt = split2(in, n, tmp);
    done = 1;
  }
  /* exact route: fixed point for A = T^(1/2) S^(-1/2) */
  double l1, l2;
  ics_sym2_eig(S[0], S[1], S[2], &l1, &l2, NULL);
  if (!done && l2 > 1e-9 * l1 && l2 > 0) {
    double R[3], Ri[3];
    ics_sym2_sqrt(S[0], S[1], S[2], R);
    double det = R[0] * R[2] - R[1] * R[1];
    Ri[0] = R[2] / det, Ri[1] = -R[1] / det, Ri[2] = R[0] / det;
    double T[3] = {S[0], S[1], S[2]}, beta = 1.0, prev = INFINITY;
    for (int it = 0; it < 400; it++) {
      double Th[3];
      if (!ics_sym2_sqrt(T[0], T[1], T[2], Th)) break;
      double A[4] = {Th[0] * Ri[0] + Th[1] * Ri[1], Th[0] * Ri[1] + Th[1] * Ri[2],
                     Th[1] * Ri[0] + Th[2] * Ri[1], Th[1] * Ri[1] + Th[2] * Ri[2]};
      shrink2(in, n, m, A, sh);
      double C[3];
      dcov2(sh, n, C);
      double e[3] = {C[0] - S[0], C[1] - S[1], C[2] - S[2]};
      double err = fabs(e[0]) + fabs(e[1]) + fabs(e[2]);
      if (err <= 4 * DBL_EPSILON * scale) {
        cnt = split2(sh, n, tmp);
        done = 1;
        break;
      }
      if (err > prev) beta *= 0.5;
      if (beta < 1e-6) break;
      prev = err;
      T[0] -= beta * e[0], T[1] -= beta * e[1], T[2] -= beta * e[2];
    }
  }
  if (!done && mode == ICS_COMP_SIGNED) {
    /* 3 x 3 signed taps around k = round(m): product of the 1D three-tap solutions for x and y
     * (cross moment d_x d_y) plus +-c/4 on the corners for the covariance c_xy. */
    double k[2], d[2], wm[2][3];
    for (int a = 0; a < 2; a++) {
      k[a] = floor(m[a] + 0.5), d[a] = m[a] - k[a];
      double V = a ? S[2] : S[0];
      wm[a][0] = 0.5 * (V + d[a] * d[a] - d[a]);
      wm[a][1] = 1 - V - d[a] * d[a];
      wm[a][2] = 0.5 * (V + d[a] * d[a] + d[a]);
    }
    int c = 0;
    for (int i = 0; i < 3; i++)
      for (int j = 0; j < 3; j++) {
        double corner = (i != 1 && j != 1) ? ((i == j) ? 0.25 : -0.25) * S[1] : 0;
        tmp[c++] = (ics_tap2d){k[0] + j - 1, k[1] + i - 1, W * (wm[0][j] * wm[1][i] + corner)};
      }
    cnt = merge2(tmp, c);
    done = 1;
  }
  if (!done) {
    /* best effort: isotropic shrink s in [0, 1] matching the trace */
    double lo = 0, hi = 1, target = S[0] + S[2];
    double A1[4] = {1, 0, 0, 1}, C[3];
    shrink2(in, n, m, A1, sh);
    dcov2(sh, n, C);
    if (C[0] + C[2] > target) {
      for (int it = 0; it < 200; it++) {
        double mid = 0.5 * (lo + hi);
        if (mid <= lo || mid >= hi) break;
        double A[4] = {mid, 0, 0, mid};
        shrink2(in, n, m, A, sh);
        dcov2(sh, n, C);
        if (C[0] + C[2] < target)
          lo = mid;
        else
          hi = mid;
      }
      double A[4] = {lo, 0, 0, lo};
      shrink2(in, n, m, A, sh);
    }
    cnt = split2(sh, n, tmp);
  }
  free(sh);
  if (cnt > cap) {
    free(tmp);
    return ICS_ERR_SIZE;
  }
  if (residual) {
    double c2[3];
    ics_taps2d_moments(tmp, cnt, NULL, NULL, c2);
    residual[0] = c2[0] - S[0];
    residual[1] = c2[1] - S[1];
    residual[2] = c2[2] - S[2];
  }
  memcpy(out, tmp, sizeof *tmp * (size_t)cnt);
  *nout = cnt;
  free(tmp);
  return ICS_OK;
}
