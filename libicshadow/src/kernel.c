/* kernel.c — the members of the kernel equivalence classes and their taps (Patel et al. 2013,
 * Sec. 3.3-3.4, Table I). The members and their exact tap constructions are specified in
 * icshadow/kernel.h; docs/kernels.md has the derivations and the measured moments table.
 *
 * Exactness: every deterministic member is built so its taps' mean and (co)variance equal the
 * class to rounding (symmetric taps for the mean; positions rescaled by the measured raw
 * variance for GAUSS; W found by bisection on the measured discrete variance for TOPHAT).
 * Stochastic members: STOCH_DIRAC and ELLIPSE are exact in expectation (closed forms in
 * kernel.h); POISSON is whitened so it is exact for every rotation. */
#include <math.h>
#include <stdlib.h>

#include "icshadow/ellipse.h"
#include "icshadow/kernel.h"
#include "icshadow/constants.h"
#include "icshadow/rng.h"
#include "sym2.h"

#define GAUSS_DEFAULT_N1 9
#define GAUSS_DEFAULT_N2 5
#define GAUSS_DEFAULT_T 3.0
#define STOCH_DEFAULT_H 1.0
#define ELLIPSE_DEFAULT_N 2
#define POISSON_DEFAULT_N 8
#define POISSON_MIN_N 3
#define POISSON_MAX_N 64
#define POISSON_STREAM UINT64_MAX /* stream of the fixed pattern (iterations use stream i) */
#define TOPHAT_MAX_WIDTH ((double)(ICS_KERNEL_MAX_TAPS - 4))

static const char *const member_names[ICS_KERNEL_MEMBER_COUNT_] = {
    "dirac", "tophat", "stochastic-dirac", "gauss", "ellipse", "poisson"};

const char *ics_kernel_member_name(ics_kernel_member m) {
  if ((int)m < 0 || m >= ICS_KERNEL_MEMBER_COUNT_) return NULL;
  return member_names[m];
}

int ics_kernel_member_stochastic(ics_kernel_member m) {
  return m == ICS_KERNEL_STOCH_DIRAC || m == ICS_KERNEL_ELLIPSE || m == ICS_KERNEL_POISSON;
}

int ics_kernel_member_dims(ics_kernel_member m) {
  switch (m) {
  case ICS_KERNEL_DIRAC:
  case ICS_KERNEL_TOPHAT:
  case ICS_KERNEL_STOCH_DIRAC: return 1;
  case ICS_KERNEL_GAUSS: return 3;
  case ICS_KERNEL_ELLIPSE:
  case ICS_KERNEL_POISSON: return 2;
  default: return 0;
  }
}

/* ---------------------------------------------------------------- 1D members */
ics_status ics_kernel1d_init(ics_kernel1d *k, ics_kernel_member m, double mean, double var) {
  if (!k) return ICS_ERR_INVALID_ARG;
  k->member = m;
  k->cls.mean = mean;
  k->cls.var = var;
  k->nsamples = 0;
  k->param = 0;
  k->seed = 0;
  if (!(ics_kernel_member_dims(m) & 1)) return ICS_ERR_INVALID_ARG;
  return ics_class1d_check(&k->cls);
}

static ics_status check1d(const ics_kernel1d *k) {
  if (!k) return ICS_ERR_INVALID_ARG;
  if (!(ics_kernel_member_dims(k->member) & 1)) return ICS_ERR_INVALID_ARG;
  ics_status st = ics_class1d_check(&k->cls);
  if (st != ICS_OK) return st;
  if (isnan(k->param)) return ICS_ERR_NAN;
  if (k->param < 0 || isinf(k->param)) return ICS_ERR_RANGE;
  if (k->nsamples < 0 || k->nsamples > ICS_KERNEL_MAX_TAPS) return ICS_ERR_RANGE;
  if (k->member == ICS_KERNEL_TOPHAT) {
    if (k->param != 0 && k->param != 1) return ICS_ERR_RANGE;
    if (sqrt(12.0 * k->cls.var) > TOPHAT_MAX_WIDTH) return ICS_ERR_RANGE;
  }
  if (k->member == ICS_KERNEL_GAUSS) {
    int n = k->nsamples ? k->nsamples : GAUSS_DEFAULT_N1;
    if (n == 1 && k->cls.var > 0) return ICS_ERR_RANGE;
  }
  /* positions must stay representable and the mean not dominate them completely */
  if (fabs(k->cls.mean) > 0x1p40 || k->cls.var > 0x1p80) return ICS_ERR_RANGE;
  return ICS_OK;
}

/* hat antiderivative: H(u) = integral_{-inf}^{u} max(0, 1 - |t|) dt */
static double hat_cdf(double u) {
  if (u <= -1) return 0;
  if (u < 0) return 0.5 * (u + 1) * (u + 1);
  if (u < 1) return 1 - 0.5 * (1 - u) * (1 - u);
  return 1;
}

/* integer-grid weights of the box [m - W/2, m + W/2] (m in [0, 1) local coordinates) applied to
 * linearly interpolated data; taps at base + j. Returns the count. */
static int tophat_grid(double base, double m, double W, ics_tap1d *t) {
  int n = 0;
  /* W -> 0 limit: the weights (hat_cdf(b - j) - hat_cdf(a - j)) / W lose all precision to
   * cancellation for tiny W (all 0 below ~1e-16); under 1e-6 px the box is applied as its limit,
   * whose variance differs by W^2/12 < 1e-13 px^2 */
  if (W < 1e-6) {
    double f = m - floor(m);
    double i = floor(m);
    if (1 - f > 0) t[n].x = base + i, t[n].w = 1 - f, n++;
    if (f > 0) t[n].x = base + i + 1, t[n].w = f, n++;
    return n;
  }
  double a = m - 0.5 * W, b = m + 0.5 * W;
  double j0 = floor(a), j1 = ceil(b);
  for (double j = j0; j <= j1; j++) {
    double w = (hat_cdf(b - j) - hat_cdf(a - j)) / W;
    if (w > 0) t[n].x = base + j, t[n].w = w, n++;
  }
  return n;
}

static double tophat_grid_var(double m, double W, ics_tap1d *scratch) {
  int n = tophat_grid(0, m, W, scratch);
  double v;
  ics_taps1d_moments(scratch, n, NULL, NULL, &v);
  return v;
}

/* periodic antiderivative of g(t) = f (1 - f), f = frac(t): G(t) = floor(t)/6 + f^2/2 - f^3/3 */
static double g_anti(double t) {
  double i = floor(t), f = t - i;
  return i / 6.0 + f * f * (0.5 - f / 3.0);
}

/* E_box[f (1 - f)] for the box [m - W/2, m + W/2] (closed form) */
static double box_interp_mean(double m, double W) {
  if (W == 0) {
    double f = m - floor(m);
    return f * (1 - f);
  }
  return (g_anti(m + 0.5 * W) - g_anti(m - 0.5 * W)) / W;
}

static int tophat_width(const ics_kernel1d *k, double *Wout) {
  double var = k->cls.var, m = k->cls.mean - floor(k->cls.mean);
  double Wraw = sqrt(12.0 * var);
  if (k->param == 1) {
    *Wout = Wraw;
    return 1;
  }
  ics_tap1d *scratch = malloc(sizeof *scratch * ((size_t)ceil(Wraw) + 4));
  if (!scratch) return -1;
  double lo = 0, hi = Wraw;
  double vlo = tophat_grid_var(m, 0, scratch);
  int ok = 1;
  if (vlo > var) {
    ok = 0;
  } else if (vlo == var) {
    hi = 0;
  } else {
    for (int it = 0; it < 200 && hi - lo > 0; it++) {
      double mid = 0.5 * (lo + hi);
      if (mid <= lo || mid >= hi) break;
      if (tophat_grid_var(m, mid, scratch) < var)
        lo = mid;
      else
        hi = mid;
    }
    /* pick the end whose variance is closer */
    if (fabs(tophat_grid_var(m, lo, scratch) - var) < fabs(tophat_grid_var(m, hi, scratch) - var))
      hi = lo;
  }
  free(scratch);
  *Wout = hi;
  return ok;
}

int ics_kernel1d_max_taps(const ics_kernel1d *k) {
  if (check1d(k) != ICS_OK) return 0;
  switch (k->member) {
  case ICS_KERNEL_DIRAC:
  case ICS_KERNEL_STOCH_DIRAC: return k->cls.var > 0 ? 2 : 1;
  case ICS_KERNEL_TOPHAT: return (int)ceil(sqrt(12.0 * k->cls.var)) + 3;
  case ICS_KERNEL_GAUSS: return k->cls.var > 0 ? (k->nsamples ? k->nsamples : GAUSS_DEFAULT_N1) : 1;
  default: return 0;
  }
}

/* standardised truncated-Gaussian abscissae and weights (variance 1 exactly up to rounding) */
static void gauss_std(int n, double T, double *z, double *w) {
  double sw = 0;
  for (int k = 0; k < n; k++) {
    z[k] = n > 1 ? -T + 2.0 * T * k / (n - 1) : 0;
    w[k] = exp(-0.5 * z[k] * z[k]);
    sw += w[k];
  }
  double v = 0;
  for (int k = 0; k < n; k++) {
    w[k] /= sw;
    v += w[k] * z[k] * z[k];
  }
  double s = n > 1 ? 1 / sqrt(v) : 0;
  for (int k = 0; k < n; k++) z[k] *= s;
  /* symmetrise exactly: z[n-1-k] = -z[k], w[n-1-k] = w[k] (mean 0 to rounding) */
  for (int k = 0; k < n / 2; k++) {
    z[n - 1 - k] = -z[k];
    w[n - 1 - k] = w[k];
  }
  if (n % 2) z[n / 2] = 0;
}

ics_status ics_kernel1d_taps(const ics_kernel1d *k, uint64_t iter, ics_tap1d *taps, int cap,
                             int *ntaps) {
  ics_status st = check1d(k);
  if (st != ICS_OK) return st;
  if (!taps || !ntaps) return ICS_ERR_INVALID_ARG;
  double mu = k->cls.mean, var = k->cls.var, sd = sqrt(var);
  int need = ics_kernel1d_max_taps(k);
  if (cap < need) return ICS_ERR_SIZE;
  int n = 0;
  switch (k->member) {
  case ICS_KERNEL_DIRAC:
    if (var == 0) {
      taps[0].x = mu, taps[0].w = 1, n = 1;
    } else {
      taps[0].x = mu - sd, taps[1].x = mu + sd;
      taps[0].w = taps[1].w = 0.5;
      n = 2;
    }
    break;
  case ICS_KERNEL_STOCH_DIRAC: {
    if (var == 0) {
      taps[0].x = mu, taps[0].w = 1, n = 1;
      break;
    }
    double h = k->param ? k->param : STOCH_DEFAULT_H;
    if (h > sqrt(3.0) * sd) h = sqrt(3.0) * sd;
    double rho2 = var - h * h / 3.0;
    double rho = rho2 > 0 ? sqrt(rho2) : 0;
    double u = h * (2.0 * ics_rng_uniform_at(k->seed, iter, 0) - 1.0);
    double r = rho + u;
    taps[0].x = mu - r, taps[1].x = mu + r;
    taps[0].w = taps[1].w = 0.5;
    n = 2;
    break;
  }
  case ICS_KERNEL_TOPHAT: {
    double W;
    int ok = tophat_width(k, &W);
    if (ok < 0) return ICS_ERR_NOMEM;
    if (!ok) return ICS_ERR_RANGE;
    double base = floor(mu);
    n = tophat_grid(base, mu - base, W, taps);
    break;
  }
  case ICS_KERNEL_GAUSS: {
    if (var == 0) {
      taps[0].x = mu, taps[0].w = 1, n = 1;
      break;
    }
    int N = k->nsamples ? k->nsamples : GAUSS_DEFAULT_N1;
    double T = k->param ? k->param : GAUSS_DEFAULT_T;
    double *z = malloc(sizeof(double) * 2 * (size_t)N);
    if (!z) return ICS_ERR_NOMEM;
    gauss_std(N, T, z, z + N);
    for (int j = 0; j < N; j++) taps[j].x = mu + sd * z[j], taps[j].w = z[N + j];
    free(z);
    for (int j = 0; j < N; j++) /* a truncation T so small that the scale overflows */
      if (!isfinite(taps[j].x) || !isfinite(taps[j].w)) return ICS_ERR_RANGE;
    n = N;
    break;
  }
  default: return ICS_ERR_INVALID_ARG;
  }
  *ntaps = n;
  return ICS_OK;
}

ics_status ics_kernel1d_expected(const ics_kernel1d *k, double *mean, double *var) {
  ics_status st = check1d(k);
  if (st != ICS_OK) return st;
  double v = k->cls.var;
  if (k->member == ICS_KERNEL_TOPHAT && k->param == 1) {
    double W = sqrt(12.0 * v), m = k->cls.mean - floor(k->cls.mean);
    v = W * W / 12.0 + box_interp_mean(m, W);
  }
  if (mean) *mean = k->cls.mean;
  if (var) *var = v;
  return ICS_OK;
}

/* ---------------------------------------------------------------- 2D members */
ics_status ics_kernel2d_init(ics_kernel2d *k, ics_kernel_member m, const ics_class2d *cls) {
  if (!k || !cls) return ICS_ERR_INVALID_ARG;
  k->member = m;
  k->cls = *cls;
  k->nsamples = 0;
  k->param = 0;
  k->seed = 0;
  if (!(ics_kernel_member_dims(m) & 2)) return ICS_ERR_INVALID_ARG;
  return ics_class2d_check(cls);
}

static int nsamples2d(const ics_kernel2d *k) {
  if (k->nsamples) return k->nsamples;
  switch (k->member) {
  case ICS_KERNEL_GAUSS: return GAUSS_DEFAULT_N2;
  case ICS_KERNEL_ELLIPSE: return ELLIPSE_DEFAULT_N;
  default: return POISSON_DEFAULT_N;
  }
}

static ics_status check2d(const ics_kernel2d *k) {
  if (!k) return ICS_ERR_INVALID_ARG;
  if (!(ics_kernel_member_dims(k->member) & 2)) return ICS_ERR_INVALID_ARG;
  ics_status st = ics_class2d_check(&k->cls);
  if (st != ICS_OK) return st;
  if (isnan(k->param)) return ICS_ERR_NAN;
  if (k->param < 0 || isinf(k->param)) return ICS_ERR_RANGE;
  if (fabs(k->cls.mean[0]) > 0x1p40 || fabs(k->cls.mean[1]) > 0x1p40) return ICS_ERR_RANGE;
  if (k->cls.cxx > 0x1p80 || k->cls.cyy > 0x1p80) return ICS_ERR_RANGE;
  int n = nsamples2d(k);
  switch (k->member) {
  case ICS_KERNEL_GAUSS:
    if (n < 1 || n > 256) return ICS_ERR_RANGE;
    if (n == 1 && (k->cls.cxx > 0 || k->cls.cyy > 0)) return ICS_ERR_RANGE;
    break;
  case ICS_KERNEL_ELLIPSE:
    if (n < 1 || n > ICS_ELLIPSE_MAX_SAMPLES) return ICS_ERR_RANGE;
    break;
  case ICS_KERNEL_POISSON:
    if (n < POISSON_MIN_N || n > POISSON_MAX_N) return ICS_ERR_RANGE;
    break;
  default: return ICS_ERR_INVALID_ARG;
  }
  return ICS_OK;
}

int ics_kernel2d_max_taps(const ics_kernel2d *k) {
  if (check2d(k) != ICS_OK) return 0;
  int n = nsamples2d(k);
  if (k->member == ICS_KERNEL_GAUSS) return n * n;
  return n;
}

/* Poisson-disk pattern by dart throwing in the unit disk (fixed per seed): min distance starts at
 * 1.2 / sqrt(N) and shrinks by 10% after 200 rejected candidates in a row. Then centred and
 * whitened: second moment c I with c = 1 (so p = S^(-1/2) (q - mean q)). */
static void poisson_pattern(uint64_t seed, int N, double *px, double *py) {
  ics_rng r;
  ics_rng_init(&r, seed, POISSON_STREAM);
  double dmin = 1.2 / sqrt((double)N);
  int have = 0, fails = 0;
  while (have < N) {
    double x = 2 * ics_rng_uniform(&r) - 1, y = 2 * ics_rng_uniform(&r) - 1;
    if (x * x + y * y > 1) continue;
    int ok = 1;
    for (int j = 0; j < have && ok; j++) {
      double dx = x - px[j], dy = y - py[j];
      if (dx * dx + dy * dy < dmin * dmin) ok = 0;
    }
    if (ok) {
      px[have] = x, py[have] = y, have++, fails = 0;
    } else if (++fails >= 200) {
      dmin *= 0.9;
      fails = 0;
    }
  }
  double mx = 0, my = 0;
  for (int j = 0; j < N; j++) mx += px[j], my += py[j];
  mx /= N, my /= N;
  double a = 0, b = 0, c = 0;
  for (int j = 0; j < N; j++) {
    px[j] -= mx, py[j] -= my;
    a += px[j] * px[j], b += px[j] * py[j], c += py[j] * py[j];
  }
  a /= N, b /= N, c /= N;
  /* S^(-1/2) = (S^(1/2))^(-1) */
  double h[3];
  ics_sym2_sqrt(a, b, c, h);
  double det = h[0] * h[2] - h[1] * h[1];
  double i0 = h[2] / det, i1 = -h[1] / det, i2 = h[0] / det;
  for (int j = 0; j < N; j++) {
    double x = px[j], y = py[j];
    px[j] = i0 * x + i1 * y;
    py[j] = i1 * x + i2 * y;
  }
  /* re-centre (the whitened mean is 0 up to rounding) */
  mx = my = 0;
  for (int j = 0; j < N; j++) mx += px[j], my += py[j];
  mx /= N, my /= N;
  for (int j = 0; j < N; j++) px[j] -= mx, py[j] -= my;
}

ics_status ics_kernel2d_taps(const ics_kernel2d *k, uint64_t iter, ics_tap2d *taps, int cap,
                             int *ntaps) {
  ics_status st = check2d(k);
  if (st != ICS_OK) return st;
  if (!taps || !ntaps) return ICS_ERR_INVALID_ARG;
  if (cap < ics_kernel2d_max_taps(k)) return ICS_ERR_SIZE;
  int N = nsamples2d(k);
  const ics_class2d *c = &k->cls;
  double L[3];
  ics_sym2_sqrt(c->cxx, c->cxy, c->cyy, L);
  int n = 0;
  switch (k->member) {
  case ICS_KERNEL_GAUSS: {
    double T = k->param ? k->param : GAUSS_DEFAULT_T;
    if (c->cxx == 0 && c->cyy == 0) N = 1;
    double *z = malloc(sizeof(double) * 2 * (size_t)N);
    if (!z) return ICS_ERR_NOMEM;
    gauss_std(N, T, z, z + N);
    for (int i = 0; i < N; i++)
      for (int j = 0; j < N; j++) {
        double u = z[j], v = z[i];
        taps[n].x = c->mean[0] + L[0] * u + L[1] * v;
        taps[n].y = c->mean[1] + L[1] * u + L[2] * v;
        taps[n].w = z[N + i] * z[N + j];
        n++;
      }
    free(z);
    break;
  }
  case ICS_KERNEL_ELLIPSE: {
    double vx, vy, ang;
    st = ics_class2d_to_axes(c, &vx, &vy, &ang);
    if (st != ICS_OK) return st;
    double *xy = malloc(sizeof(double) * 2 * (size_t)N);
    if (!xy) return ICS_ERR_NOMEM;
    ics_ellipse_shape shape;
    st = ics_ellipse_kernel(vx, vy, ang, N, ics_rng_uniform_at(k->seed, iter, 0), &shape, xy);
    if (st == ICS_OK) {
      n = shape.nsamples;
      for (int j = 0; j < n; j++) {
        taps[j].x = c->mean[0] + xy[2 * j];
        taps[j].y = c->mean[1] + xy[2 * j + 1];
        taps[j].w = 1.0 / n;
      }
    }
    free(xy);
    if (st != ICS_OK) return st;
    break;
  }
  case ICS_KERNEL_POISSON: {
    double *p = malloc(sizeof(double) * 2 * (size_t)N);
    if (!p) return ICS_ERR_NOMEM;
    poisson_pattern(k->seed, N, p, p + N);
    double th = 2 * ICS_PI * ics_rng_uniform_at(k->seed, iter, 0);
    double s = sin(th), co = cos(th);
    for (int j = 0; j < N; j++) {
      double u = co * p[j] - s * p[N + j], v = s * p[j] + co * p[N + j];
      taps[j].x = c->mean[0] + L[0] * u + L[1] * v;
      taps[j].y = c->mean[1] + L[1] * u + L[2] * v;
      taps[j].w = 1.0 / N;
    }
    free(p);
    n = N;
    break;
  }
  default: return ICS_ERR_INVALID_ARG;
  }
  *ntaps = n;
  return ICS_OK;
}

ics_status ics_kernel2d_expected(const ics_kernel2d *k, double mean[2], double cov[3]) {
  ics_status st = check2d(k);
  if (st != ICS_OK) return st;
  if (mean) mean[0] = k->cls.mean[0], mean[1] = k->cls.mean[1];
  if (cov) cov[0] = k->cls.cxx, cov[1] = k->cls.cxy, cov[2] = k->cls.cyy;
  return ICS_OK;
}
