/* light.c — lights on the virtual light plane, the Eq. 7/15 kernel mapping, and 1D light
 * functions (Patel et al. 2013, Sec. 3.2, 3.4, Appendix A.2).
 *
 * Method and accuracy:
 * - ics_light_tan_deg: |w| <= 45: tan(w * pi/180) (argument rounding costs <= 1 ulp relative);
 *   45 < |w| < 90: 1 / tan((90 - |w|) * pi/180), where 90 - |w| is exact (Sterbenz), so the
 *   result keeps ~2 ulp up to the last representable angle below 90 (measured in
 *   tests/test_light.c against the series cot x = 1/x - x/3 - x^3/45 - 2x^5/945).
 * - Gaussian and mixture cdf/sf: (weighted sums of) Phi/Phi^c of normal.c (no cancellation).
 *   Mixture quantile: bracket [min_i q_i(p), max_i q_i(p)] of the component quantiles (L is
 *   between them), then safeguarded Newton (bisection fallback) to 4 ulp in x.
 * - Table lights: piecewise-linear density; cdf is piecewise quadratic, its inverse is solved in
 *   the cancellation-free form u = 2r / (p_i + sqrt(p_i^2 + 2 s r)); moments by 3-point
 *   Gauss-Legendre per segment (exact for the degree-4 integrands). */
#include "icshadow/light.h"
#include "icshadow/constants.h"
#include "icshadow/normal.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "check_finite.h"
#include "degtrig.h"
#include "noerrno.h"
#include "sym2.h"

/* ---- tilt ---- */

double ics_light_tan_deg(double w) {
  if (!(fabs(w) < 90.0)) return NAN; /* NaN, inf, |w| >= 90 */
  double a = fabs(w);
  double t;
  if (a <= 45.0)
    t = tan(a * (ICS_PI / 180.0));
  else
    t = 1.0 / tan((90.0 - a) * (ICS_PI / 180.0));
  return w < 0 ? -t : t;
}

double ics_light_tilt_condition(double w) {
  if (!(fabs(w) < 90.0)) return NAN;
  if (w == 0) return 1.0;
  double r = fabs(w) * (ICS_PI / 180.0);
  /* sin(2r) = 2 sin r cos r; near 90 degrees use cos r = sin((90 - w) deg) (exact argument) */
  double c = fabs(w) <= 45.0 ? cos(r) : sin((90.0 - fabs(w)) * (ICS_PI / 180.0));
  return r / (sin(r) * c);
}

/* ---- 2D lights ---- */

static ics_status check_var(double v) {
  ics_status s = ics_check_finite(v);
  if (s != ICS_OK) return s;
  return v < 0 ? ICS_ERR_NEGATIVE_VARIANCE : ICS_OK;
}

ics_status ics_light_cov_from_eig(double varx, double vary, double alpha, double cov[3]) {
  ics_status s;
  if ((s = check_var(varx)) != ICS_OK || (s = check_var(vary)) != ICS_OK ||
      (s = ics_check_finite(alpha)) != ICS_OK)
    return s;
  double c, sn;
  ics_sincos_deg(alpha, &sn, &c);
  cov[0] = varx * c * c + vary * sn * sn;
  cov[1] = (varx - vary) * c * sn;
  cov[2] = varx * sn * sn + vary * c * c;
  return ICS_OK;
}

ics_status ics_light_cov_to_eig(const double cov[3], double *varx, double *vary, double *alpha) {
  ics_status s;
  for (int i = 0; i < 3; i++)
    if ((s = ics_check_finite(cov[i])) != ICS_OK) return s;
  double a = cov[0], d = cov[2];
  double tol = 8 * DBL_EPSILON * fabs(a + d);
  if (a < -tol || d < -tol) return ICS_ERR_INVALID_ARG;
  double l1, l2, ang;
  ics_sym2_eig(a, cov[1], d, &l1, &l2, &ang);
  if (l2 < -tol) return ICS_ERR_INVALID_ARG;
  if (l2 < 0) l2 = 0;
  *varx = l1;
  *vary = l2;
  *alpha = ang;
  return ICS_OK;
}

int ics_light_cov_sqrt(const double cov[3], double root[3]) {
  for (int i = 0; i < 3; i++)
    if (!isfinite(cov[i])) return -1;
  return ics_sym2_sqrt(cov[0], cov[1], cov[2], root);
}

ics_status ics_light_init_tilt(ics_light *out, double wx, double wy, double varx, double vary,
                               double alpha, const double color[3], double weight) {
  ics_status s;
  if ((s = ics_check_finite(wx)) != ICS_OK || (s = ics_check_finite(wy)) != ICS_OK) return s;
  if (!(fabs(wx) < 90.0) || !(fabs(wy) < 90.0)) return ICS_ERR_RANGE;
  if ((s = ics_check_finite(weight)) != ICS_OK) return s;
  if (weight < 0) return ICS_ERR_INVALID_ARG;
  double cov[3];
  if ((s = ics_light_cov_from_eig(varx, vary, alpha, cov)) != ICS_OK) return s;
  double col[3] = {1, 1, 1};
  if (color)
    for (int i = 0; i < 3; i++) {
      if ((s = ics_check_finite(color[i])) != ICS_OK) return s;
      if (color[i] < 0) return ICS_ERR_INVALID_ARG;
      col[i] = color[i];
    }
  out->mean[0] = ics_light_tan_deg(wx);
  out->mean[1] = ics_light_tan_deg(wy);
  memcpy(out->cov, cov, sizeof cov);
  memcpy(out->color, col, sizeof col);
  out->weight = weight;
  return ICS_OK;
}

static ics_status check_e_d1(double e, double d1) {
  ics_status s;
  if ((s = ics_check_finite(e)) != ICS_OK || (s = ics_check_finite(d1)) != ICS_OK) return s;
  return (e > 0 && d1 > 0) ? ICS_OK : ICS_ERR_RANGE;
}

ics_status ics_light_kernel_map_1d(double mu_l, double var_l, double e, double d1, double *mu_k,
                                   double *var_k) {
  ics_status s;
  if ((s = ics_check_finite(mu_l)) != ICS_OK || (s = check_var(var_l)) != ICS_OK) return s;
  if ((s = check_e_d1(e, d1)) != ICS_OK) return s;
  *mu_k = -e * mu_l;
  *var_k = d1 * e * var_l;
  return ICS_OK;
}

ics_status ics_light_kernel_map_2d(const ics_light *l, double e, double d1, double mean_k[2],
                                   double cov_k[3]) {
  ics_status s;
  if (!l) return ICS_ERR_INVALID_ARG;
  for (int i = 0; i < 2; i++)
    if ((s = ics_check_finite(l->mean[i])) != ICS_OK) return s;
  for (int i = 0; i < 3; i++)
    if ((s = ics_check_finite(l->cov[i])) != ICS_OK) return s;
  if (l->cov[0] < 0 || l->cov[2] < 0) return ICS_ERR_NEGATIVE_VARIANCE;
  double vx, vy, ang; /* positive semidefinite (ics_light_cov_to_eig's check, -8 eps trace) */
  if (ics_light_cov_to_eig(l->cov, &vx, &vy, &ang) != ICS_OK) return ICS_ERR_NEGATIVE_VARIANCE;
  if ((s = check_e_d1(e, d1)) != ICS_OK) return s;
  mean_k[0] = -e * l->mean[0];
  mean_k[1] = -e * l->mean[1];
  for (int i = 0; i < 3; i++) cov_k[i] = d1 * e * l->cov[i];
  return ICS_OK;
}

/* ---- 1D lights ---- */

typedef enum light1d_kind {
  LIGHT1D_GAUSS, /* mean, variance (variance 0: a point light, a Dirac at the mean) */
  LIGHT1D_BOX,   /* uniform on [lo, hi], lo < hi */
  LIGHT1D_MIX,   /* Gaussian mixture, weights normalised to sum 1, each variance > 0 */
  LIGHT1D_TAB    /* piecewise-linear density through (x_i, p_i), normalised */
} light1d_kind;

struct ics_light1d {
  light1d_kind kind;
  int n;       /* mixture components or table nodes */
  double a, b; /* GAUSS: mean, variance; BOX: lo, hi */
  double w[ICS_LIGHT1D_MAX_MIX], mu[ICS_LIGHT1D_MAX_MIX], var[ICS_LIGHT1D_MAX_MIX];
  double *x, *p, *c;  /* TAB (owned): nodes, normalised density, cdf at the nodes */
  double mean_, var_; /* cached moments */
};

/* The fill_* functions set up a zeroed light; on an error the caller destroys it. */

static ics_status fill_gauss(ics_light1d *l, double mean, double var) {
  ics_status s;
  if ((s = ics_check_finite(mean)) != ICS_OK || (s = check_var(var)) != ICS_OK) return s;
  l->kind = LIGHT1D_GAUSS;
  l->n = 1;
  l->a = mean;
  l->b = var;
  l->mean_ = mean;
  l->var_ = var;
  return ICS_OK;
}

static ics_status fill_box(ics_light1d *l, double lo, double hi) {
  ics_status s;
  if ((s = ics_check_finite(lo)) != ICS_OK || (s = ics_check_finite(hi)) != ICS_OK) return s;
  if (!(lo < hi)) return ICS_ERR_RANGE;
  l->kind = LIGHT1D_BOX;
  l->a = lo;
  l->b = hi;
  l->mean_ = 0.5 * lo + 0.5 * hi;
  double w = hi - lo;
  l->var_ = w * w / 12.0;
  if (!isfinite(w) || !isfinite(l->var_)) return ICS_ERR_RANGE; /* hi - lo or its square */
  return ICS_OK;
}

static ics_status fill_mix(ics_light1d *l, int n, const double *w, const double *mu,
                           const double *var) {
  if (n < 1 || n > ICS_LIGHT1D_MAX_MIX) return ICS_ERR_SIZE;
  ics_status s;
  double sw = 0;
  for (int i = 0; i < n; i++) {
    if ((s = ics_check_finite(w[i])) != ICS_OK || (s = ics_check_finite(mu[i])) != ICS_OK ||
        (s = check_var(var[i])) != ICS_OK)
      return s;
    if (w[i] < 0) return ICS_ERR_INVALID_ARG;
    if (var[i] == 0) return ICS_ERR_RANGE;
    sw += w[i];
  }
  if (!(sw > 0)) return ICS_ERR_INVALID_ARG;
  if (isinf(sw)) return ICS_ERR_RANGE; /* the weights' sum overflows */
  l->kind = LIGHT1D_MIX;
  l->n = n;
  double m = 0;
  for (int i = 0; i < n; i++) {
    l->w[i] = w[i] / sw;
    l->mu[i] = mu[i];
    l->var[i] = var[i];
    m += l->w[i] * mu[i];
  }
  double v = 0;
  for (int i = 0; i < n; i++) v += l->w[i] * (var[i] + (mu[i] - m) * (mu[i] - m));
  l->mean_ = m;
  l->var_ = v;
  if (!isfinite(m) || !isfinite(v)) return ICS_ERR_RANGE; /* the mixture's mean or variance */
  return ICS_OK;
}

/* 3-point Gauss-Legendre on [0, 1] */
static const double GL_X[3] = {0.11270166537925831148, 0.5, 0.88729833462074168852};
static const double GL_W[3] = {5.0 / 18.0, 8.0 / 18.0, 5.0 / 18.0};

/* integral over the table of (x - c)^k p(x) dx */
static double tab_moment(const ics_light1d *l, int k, double c) {
  double sum = 0;
  for (int i = 0; i + 1 < l->n; i++) {
    double h = l->x[i + 1] - l->x[i];
    for (int j = 0; j < 3; j++) {
      double t = GL_X[j];
      double x = l->x[i] + t * h;
      double p = l->p[i] + t * (l->p[i + 1] - l->p[i]);
      sum += GL_W[j] * h * p * pow(x - c, k);
    }
  }
  return sum;
}

static ics_status fill_tab(ics_light1d *l, int n, const double *x, const double *p) {
  if (n < 2) return ICS_ERR_SIZE;
  ics_status s;
  for (int i = 0; i < n; i++) {
    if ((s = ics_check_finite(x[i])) != ICS_OK || (s = ics_check_finite(p[i])) != ICS_OK) return s;
    if (p[i] < 0) return ICS_ERR_INVALID_ARG;
    if (i && !(x[i] > x[i - 1])) return ICS_ERR_INVALID_ARG;
  }
  double area = 0;
  for (int i = 0; i + 1 < n; i++) area += 0.5 * (p[i] + p[i + 1]) * (x[i + 1] - x[i]);
  if (!(area > 0) || isinf(area)) return ICS_ERR_INVALID_ARG;
  l->kind = LIGHT1D_TAB;
  l->n = n;
  l->x = malloc((size_t)n * sizeof *l->x);
  l->p = malloc((size_t)n * sizeof *l->p);
  l->c = malloc((size_t)n * sizeof *l->c);
  if (!l->x || !l->p || !l->c) return ICS_ERR_NOMEM;
  for (int i = 0; i < n; i++) {
    l->x[i] = x[i];
    l->p[i] = p[i] / area;
  }
  l->c[0] = 0;
  for (int i = 0; i + 1 < n; i++)
    l->c[i + 1] = l->c[i] + 0.5 * (l->p[i] + l->p[i + 1]) * (x[i + 1] - x[i]);
  l->mean_ = tab_moment(l, 1, 0.0);
  l->var_ = tab_moment(l, 2, l->mean_);
  if (!isfinite(l->mean_) || !isfinite(l->var_)) return ICS_ERR_RANGE; /* moments overflow */
  return ICS_OK;
}

/* The start of every ics_light1d_create_*: *out NULL and a zeroed light in *l. */
static ics_status light1d_start(ics_light1d **out, ics_light1d **l) {
  if (!out) return ICS_ERR_INVALID_ARG;
  *out = NULL;
  *l = calloc(1, sizeof **l);
  return *l ? ICS_OK : ICS_ERR_NOMEM;
}

/* The end: *out = l when the fill succeeded, else l is destroyed. */
static ics_status light1d_finish(ics_light1d **out, ics_light1d *l, ics_status filled) {
  if (filled == ICS_OK)
    *out = l;
  else
    ics_light1d_destroy(l);
  return filled;
}

ics_status ics_light1d_create_gauss(ics_light1d **out, double mean, double var) {
  ics_light1d *l;
  ics_status s = light1d_start(out, &l);
  return s != ICS_OK ? s : light1d_finish(out, l, fill_gauss(l, mean, var));
}

ics_status ics_light1d_create_box(ics_light1d **out, double lo, double hi) {
  ics_light1d *l;
  ics_status s = light1d_start(out, &l);
  return s != ICS_OK ? s : light1d_finish(out, l, fill_box(l, lo, hi));
}

ics_status ics_light1d_create_mix(ics_light1d **out, int n, const double *w, const double *mu,
                                  const double *var) {
  ics_light1d *l;
  ics_status s = light1d_start(out, &l);
  return s != ICS_OK ? s : light1d_finish(out, l, fill_mix(l, n, w, mu, var));
}

ics_status ics_light1d_create_tab(ics_light1d **out, int n, const double *x, const double *p) {
  ics_light1d *l;
  ics_status s = light1d_start(out, &l);
  return s != ICS_OK ? s : light1d_finish(out, l, fill_tab(l, n, x, p));
}

void ics_light1d_destroy(ics_light1d *l) {
  if (!l) return;
  free(l->x); /* NULL unless a table light */
  free(l->p);
  free(l->c);
  free(l);
}

/* index i with x[i] <= v < x[i+1], v inside the table */
static int tab_seg(const ics_light1d *l, double v) {
  int lo = 0, hi = l->n - 1;
  while (hi - lo > 1) {
    int mid = (lo + hi) / 2;
    if (l->x[mid] <= v)
      lo = mid;
    else
      hi = mid;
  }
  return lo;
}

double ics_light1d_pdf(const ics_light1d *l, double x) {
  if (isnan(x)) return NAN;
  switch (l->kind) {
  case LIGHT1D_GAUSS:
    if (l->b == 0) return x == l->a ? INFINITY : 0.0;
    return ics_exp_noerrno(-0.5 * (x - l->a) * (x - l->a) / l->b) / sqrt(2 * ICS_PI * l->b);
  case LIGHT1D_BOX:
    return (x >= l->a && x <= l->b) ? 1.0 / (l->b - l->a) : 0.0;
  case LIGHT1D_MIX: {
    double s = 0;
    for (int i = 0; i < l->n; i++)
      s += l->w[i] * ics_exp_noerrno(-0.5 * (x - l->mu[i]) * (x - l->mu[i]) / l->var[i]) /
           sqrt(2 * ICS_PI * l->var[i]);
    return s;
  }
  case LIGHT1D_TAB: {
    if (x < l->x[0] || x > l->x[l->n - 1]) return 0.0;
    if (x == l->x[l->n - 1]) return l->p[l->n - 1];
    int i = tab_seg(l, x);
    double t = (x - l->x[i]) / (l->x[i + 1] - l->x[i]);
    return l->p[i] + t * (l->p[i + 1] - l->p[i]);
  }
  }
  return NAN;
}

static double tab_cdf(const ics_light1d *l, double x) {
  if (x <= l->x[0]) return 0.0;
  if (x >= l->x[l->n - 1]) return 1.0;
  int i = tab_seg(l, x);
  double h = l->x[i + 1] - l->x[i], u = x - l->x[i];
  double v = l->c[i] + u * (l->p[i] + 0.5 * (l->p[i + 1] - l->p[i]) * u / h);
  return v > 1.0 ? 1.0 : v;
}

double ics_light1d_cdf(const ics_light1d *l, double x) {
  if (isnan(x)) return NAN;
  switch (l->kind) {
  case LIGHT1D_GAUSS:
    if (l->b == 0) return x >= l->a ? 1.0 : 0.0;
    return ics_normal_cdf((x - l->a) / sqrt(l->b));
  case LIGHT1D_BOX:
    if (x <= l->a) return 0.0;
    if (x >= l->b) return 1.0;
    return (x - l->a) / (l->b - l->a);
  case LIGHT1D_MIX: {
    double s = 0;
    for (int i = 0; i < l->n; i++) s += l->w[i] * ics_normal_cdf((x - l->mu[i]) / sqrt(l->var[i]));
    return s > 1.0 ? 1.0 : s;
  }
  case LIGHT1D_TAB:
    return tab_cdf(l, x);
  }
  return NAN;
}

double ics_light1d_sf(const ics_light1d *l, double x) {
  if (isnan(x)) return NAN;
  switch (l->kind) {
  case LIGHT1D_GAUSS:
    if (l->b == 0) return x >= l->a ? 0.0 : 1.0;
    return ics_normal_sf((x - l->a) / sqrt(l->b));
  case LIGHT1D_BOX:
    if (x <= l->a) return 1.0;
    if (x >= l->b) return 0.0;
    return (l->b - x) / (l->b - l->a);
  case LIGHT1D_MIX: {
    double s = 0;
    for (int i = 0; i < l->n; i++)
      s += l->w[i] * ics_normal_sf((x - l->mu[i]) / sqrt(l->var[i]));
    return s > 1.0 ? 1.0 : s;
  }
  case LIGHT1D_TAB:
    return 1.0 - tab_cdf(l, x);
  }
  return NAN;
}

/* x with cdf(x) = t (upper = 0) or sf(x) = t (upper = 1), for a mixture */
static double mix_solve(const ics_light1d *l, double t, int upper) {
  double lo = INFINITY, hi = -INFINITY;
  for (int i = 0; i < l->n; i++) {
    if (l->w[i] == 0) continue;
    double z = upper ? -ics_normal_quantile(t) : ics_normal_quantile(t);
    double q = l->mu[i] + sqrt(l->var[i]) * z;
    if (q < lo) lo = q;
    if (q > hi) hi = q;
  }
  if (lo == hi) return lo;
  double x = 0.5 * (lo + hi);
  for (int it = 0; it < 200; it++) {
    double f = upper ? t - ics_light1d_sf(l, x) : ics_light1d_cdf(l, x) - t; /* increasing */
    if (f == 0) return x;
    if (f > 0)
      hi = x;
    else
      lo = x;
    double pd = ics_light1d_pdf(l, x);
    double xn = pd > 0 ? x - f / pd : 0.5 * (lo + hi);
    if (!(xn > lo && xn < hi)) xn = 0.5 * (lo + hi);
    if (fabs(xn - x) <= 4 * DBL_EPSILON * fabs(x) || hi - lo <= 4 * DBL_EPSILON * fabs(x) ||
        hi - lo < DBL_MIN) {
      x = xn;
      break;
    }
    x = xn;
  }
  return x;
}

static double tab_quantile(const ics_light1d *l, double t) {
  if (t <= 0) {
    /* leftmost point with positive density to its right */
    for (int i = 0; i + 1 < l->n; i++)
      if (l->c[i + 1] > 0) return l->x[i];
    return l->x[0];
  }
  /* first segment whose upper cdf reaches t */
  int lo = 0, hi = l->n - 1;
  while (hi - lo > 1) {
    int mid = (lo + hi) / 2;
    if (l->c[mid] < t)
      lo = mid;
    else
      hi = mid;
  }
  int i = lo;
  double h = l->x[i + 1] - l->x[i];
  double r = t - l->c[i];
  double s = (l->p[i + 1] - l->p[i]) / h;
  double disc = l->p[i] * l->p[i] + 2 * s * r;
  if (disc < 0) disc = 0;
  double den = l->p[i] + sqrt(disc);
  double u = den > 0 ? 2 * r / den : 0;
  if (u > h) u = h;
  return l->x[i] + u;
}

double ics_light1d_quantile(const ics_light1d *l, double p) {
  if (isnan(p) || p < 0 || p > 1) return NAN;
  switch (l->kind) {
  case LIGHT1D_GAUSS:
    if (l->b == 0) return l->a;
    return l->a + sqrt(l->b) * ics_normal_quantile(p);
  case LIGHT1D_BOX:
    return p <= 0.5 ? l->a + p * (l->b - l->a) : l->b - (1.0 - p) * (l->b - l->a);
  case LIGHT1D_MIX:
    if (p == 0) return -INFINITY;
    if (p == 1) return INFINITY;
    return p <= 0.5 ? mix_solve(l, p, 0) : mix_solve(l, 1.0 - p, 1);
  case LIGHT1D_TAB:
    return tab_quantile(l, p);
  }
  return NAN;
}

double ics_light1d_isf(const ics_light1d *l, double q) {
  if (isnan(q) || q < 0 || q > 1) return NAN;
  switch (l->kind) {
  case LIGHT1D_GAUSS:
    if (l->b == 0) return l->a;
    return l->a - sqrt(l->b) * ics_normal_quantile(q);
  case LIGHT1D_BOX:
    return q <= 0.5 ? l->b - q * (l->b - l->a) : l->a + (1.0 - q) * (l->b - l->a);
  case LIGHT1D_MIX:
    if (q == 0) return INFINITY;
    if (q == 1) return -INFINITY;
    return q <= 0.5 ? mix_solve(l, q, 1) : mix_solve(l, 1.0 - q, 0);
  case LIGHT1D_TAB:
    return tab_quantile(l, 1.0 - q);
  }
  return NAN;
}

double ics_light1d_mean(const ics_light1d *l) { return l->mean_; }
double ics_light1d_var(const ics_light1d *l) { return l->var_; }

double ics_light1d_skewness(const ics_light1d *l) {
  if (l->var_ == 0) return 0.0;
  double m3 = 0;
  switch (l->kind) {
  case LIGHT1D_GAUSS:
  case LIGHT1D_BOX:
    return 0.0;
  case LIGHT1D_MIX:
    for (int i = 0; i < l->n; i++) {
      double dm = l->mu[i] - l->mean_;
      m3 += l->w[i] * (dm * dm * dm + 3 * dm * l->var[i]);
    }
    break;
  case LIGHT1D_TAB:
    m3 = tab_moment(l, 3, l->mean_);
    break;
  }
  return m3 / (l->var_ * sqrt(l->var_));
}

int ics_light_write_json(FILE *f, const ics_light *l, int n) {
  fprintf(f, "{\"lights\": [");
  for (int k = 0; k < n; k++)
    fprintf(f,
            "%s\n  {\"mean\": [%.17g, %.17g], \"cov\": [[%.17g, %.17g], [%.17g, %.17g]], "
            "\"color\": [%.17g, %.17g, %.17g], \"weight\": %.17g}",
            k ? "," : "", l[k].mean[0], l[k].mean[1], l[k].cov[0], l[k].cov[1], l[k].cov[1],
            l[k].cov[2], l[k].color[0], l[k].color[1], l[k].color[2], l[k].weight);
  fprintf(f, "\n]}\n");
  return ferror(f) ? -1 : 0;
}
