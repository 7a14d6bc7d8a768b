/* test_conv.c — the iterative convolution engine: impulse responses (binomial weights), moments
 * add, linearity, shift and its sign, boundaries, 2D covariance of propagated impulses for the
 * elliptical and Poisson kernels, interpolation variance and its compensation, mixed schedules.
 *
 * Expected values are derived here: binomial coefficients, sum of w f (1 - f) over the tap
 * positions, n times the class variance, the normal cdf. Tolerances: double 1D runs to 1e-12
 * relative (sums of ~100 positive terms per step over <= 200 steps); float 2D runs to 1e-4
 * relative (float storage, ~1e-7 per step); statistical checks at 5 standard deviations. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "icshadow.h"
#include "testutil.h"

#define CAP 4096
static ics_tap1d ta[CAP], tb[CAP];
static ics_tap2d tc[CAP];

/* moments of a 1D buffer as a distribution (index = position) */
static void line_moments(const double *b, size_t n, double *mass, double *mean, double *var) {
  double s0 = 0, s1 = 0;
  for (size_t i = 0; i < n; i++) s0 += b[i], s1 += b[i] * (double)i;
  double m = s1 / s0, s2 = 0;
  for (size_t i = 0; i < n; i++) s2 += b[i] * ((double)i - m) * ((double)i - m);
  *mass = s0, *mean = m, *var = s2 / s0;
}

static void image_moments(const float *b, size_t w, size_t h, double *mass, double m[2],
                          double c[3]) {
  double s0 = 0, sx = 0, sy = 0;
  for (size_t y = 0; y < h; y++)
    for (size_t x = 0; x < w; x++) {
      double v = b[y * w + x];
      s0 += v, sx += v * (double)x, sy += v * (double)y;
    }
  m[0] = sx / s0, m[1] = sy / s0;
  double a = 0, bb = 0, cc = 0;
  for (size_t y = 0; y < h; y++)
    for (size_t x = 0; x < w; x++) {
      double v = b[y * w + x], dx = (double)x - m[0], dy = (double)y - m[1];
      a += v * dx * dx, bb += v * dx * dy, cc += v * dy * dy;
    }
  *mass = s0, c[0] = a / s0, c[1] = bb / s0, c[2] = cc / s0;
}

/* sum w f (1 - f) / sum w, computed here from the positions */
static double my_interp(const ics_tap1d *t, int n) {
  double s = 0, sw = 0;
  for (int j = 0; j < n; j++) {
    double f = t[j].x - floor(t[j].x);
    s += t[j].w * f * (1 - f), sw += t[j].w;
  }
  return s / sw;
}

static double binom(int n, int k) { /* exact in double for n <= 60 */
  double r = 1;
  for (int i = 1; i <= k; i++) r = r * (n - k + i) / i;
  return r;
}

static void test_binomial(void) {
  /* Dirac mean 0, var 1: taps -1, +1, weights 1/2 -> after n steps C(n, k) / 2^n at 2k - n */
  enum { N = 201, C0 = 100, STEPS = 40 };
  static double b[N];
  memset(b, 0, sizeof b);
  b[C0] = 1;
  ics_kernel1d k;
  ics_kernel1d_init(&k, ICS_KERNEL_DIRAC, 0, 1);
  ics_schedule1d s = {&k, 1};
  ics_conv_opts o = {0};
  o.boundary = ICS_BOUNDARY_CONSTANT;
  CHECK(ics_conv1d_run(b, N, &s, 0, STEPS, &o, NULL) == ICS_OK, "run");
  double maxerr = 0;
  for (int i = 0; i < N; i++) {
    int d = i - C0;
    double want = 0;
    if ((d + STEPS) % 2 == 0 && abs(d) <= STEPS) want = binom(STEPS, (d + STEPS) / 2) / ldexp(1, STEPS);
    double e = fabs(b[i] - want);
    if (e > maxerr) maxerr = e;
  }
  CHECK(maxerr < 1e-15, "integer Dirac impulse = binomial, max error %g", maxerr);

  /* Dirac var 1/4: taps +-1/2 interpolate to (1/4, 1/2, 1/4): C(2n, k) / 4^n at k - n;
   * variance n (1/4 + 1/4) (kernel + interpolation) */
  memset(b, 0, sizeof b);
  b[C0] = 1;
  ics_kernel1d_init(&k, ICS_KERNEL_DIRAC, 0, 0.25);
  ics_conv_stats st;
  ics_conv1d_run(b, N, &s, 0, STEPS, &o, &st);
  maxerr = 0;
  for (int i = 0; i < N; i++) {
    int d = i - C0;
    double want = abs(d) <= STEPS ? binom(2 * STEPS, d + STEPS) / ldexp(1, 2 * STEPS) : 0;
    if (fabs(b[i] - want) > maxerr) maxerr = fabs(b[i] - want);
  }
  CHECK(maxerr < 1e-15, "half-pixel Dirac impulse = binomial(2n), max error %g", maxerr);
  double M, mean, var;
  line_moments(b, N, &M, &mean, &var);
  CHECK(fabs(var - STEPS * 0.5) < 1e-12 * STEPS, "variance n (1/4 + 1/4): %.15g", var);
  CHECK(fabs(st.kernel_var[0] - STEPS * 0.25) < 1e-12 && fabs(st.interp_var[0] - STEPS * 0.25) < 1e-12,
        "stats: kernel %.15g interp %.15g", st.kernel_var[0], st.interp_var[0]);
}

static void test_moments_add(void) {
  /* any member: after n steps mean = n mu, var = n (var + interp) (interp summed per step) */
  enum { N = 600, C0 = 150, STEPS = 60 };
  static double b[N];
  const ics_kernel_member mem[] = {ICS_KERNEL_GAUSS, ICS_KERNEL_DIRAC, ICS_KERNEL_STOCH_DIRAC,
                                   ICS_KERNEL_TOPHAT};
  for (int q = 0; q < 4; q++) {
    ics_kernel1d k;
    ics_kernel1d_init(&k, mem[q], 0.37, 2.3);
    k.seed = 5;
    double sum_interp = 0, sum_var = 0;
    for (int i = 0; i < STEPS; i++) {
      int n;
      ics_kernel1d_taps(&k, (uint64_t)i, ta, CAP, &n);
      double W, m, v;
      ics_taps1d_moments(ta, n, &W, &m, &v);
      sum_var += v;
      sum_interp += my_interp(ta, n);
    }
    memset(b, 0, sizeof b);
    b[C0] = 1;
    ics_schedule1d s = {&k, 1};
    ics_conv_opts o = {0};
    o.boundary = ICS_BOUNDARY_CONSTANT;
    ics_conv1d_run(b, N, &s, 0, STEPS, &o, NULL);
    double M, mean, var;
    line_moments(b, N, &M, &mean, &var);
    CHECK(fabs(M - 1) < 1e-13, "%s mass %.17g", ics_kernel_member_name(mem[q]), M);
    CHECK(fabs(mean - (C0 + STEPS * 0.37)) < 1e-11, "%s mean %.15g (shift +n mu)",
          ics_kernel_member_name(mem[q]), mean);
    CHECK(fabs(var - (sum_var + sum_interp)) < 1e-11 * var, "%s var %.15g vs %.15g",
          ics_kernel_member_name(mem[q]), var, sum_var + sum_interp);
    if (mem[q] != ICS_KERNEL_STOCH_DIRAC)
      CHECK(fabs(sum_var - STEPS * 2.3) < 1e-11, "%s: n var", ics_kernel_member_name(mem[q]));
    if (mem[q] == ICS_KERNEL_TOPHAT) CHECK(sum_interp == 0, "tophat taps are on the grid");
  }
}

static void test_linear_shift_boundary(void) {
  enum { N = 64 };
  double x[N], y[N], z[N], ox[N], oy[N], oz[N];
  for (int i = 0; i < N; i++) {
    x[i] = sin(0.3 * i) + 0.1 * i;
    y[i] = (i % 7) * 0.25 - 1;
    z[i] = 2.5 * x[i] - 0.75 * y[i];
  }
  ics_tap1d t[3] = {{-1.3, 0.2}, {0.45, 0.5}, {2.8, 0.3}};
  ics_conv_opts o = {0};
  ics_conv1d_step(x, ox, N, t, 3, &o);
  ics_conv1d_step(y, oy, N, t, 3, &o);
  ics_conv1d_step(z, oz, N, t, 3, &o);
  double e = 0;
  for (int i = 0; i < N; i++) e = fmax(e, fabs(oz[i] - (2.5 * ox[i] - 0.75 * oy[i])));
  CHECK(e < 1e-13, "linearity: %g", e);
  /* shift: input shifted by 5 -> output shifted by 5 (away from the edges) */
  double xs[N], oxs[N];
  for (int i = 0; i < N; i++) xs[i] = i >= 5 ? x[i - 5] : x[0];
  ics_conv1d_step(xs, oxs, N, t, 3, &o);
  e = 0;
  for (int i = 10; i < N - 5; i++) e = fmax(e, fabs(oxs[i] - ox[i - 5]));
  CHECK(e == 0, "shift invariance: %g", e);
  /* sign: a Dirac of mean +3 moves an impulse from 10 to 13 */
  double imp[N] = {0}, out[N];
  imp[10] = 1;
  ics_tap1d d3 = {3.0, 1.0};
  ics_conv1d_step(imp, out, N, &d3, 1, &o);
  CHECK(out[13] == 1 && out[10] == 0, "tap +3 shifts content by +3");
  /* linear interpolation value: tap 0.25 -> out[x] = 0.75 in[x] + 0.25 in[x - 1] */
  ics_tap1d q = {0.25, 1};
  ics_conv1d_step(x, ox, N, &q, 1, &o);
  CHECK(fabs(ox[20] - (0.75 * x[20] + 0.25 * x[19])) < 1e-15, "linear interpolation weights");
  /* boundaries: clamp keeps a constant line, constant mode pads with the constant */
  for (int i = 0; i < N; i++) x[i] = 0.7;
  ics_tap1d wide[2] = {{-40.5, 0.5}, {40.25, 0.5}};
  ics_conv1d_step(x, ox, N, wide, 2, &o);
  e = 0;
  for (int i = 0; i < N; i++) e = fmax(e, fabs(ox[i] - 0.7));
  CHECK(e < 1e-15, "clamp keeps a constant: %g", e);
  o.boundary = ICS_BOUNDARY_CONSTANT;
  o.constant = 1;
  for (int i = 0; i < N; i++) x[i] = 0;
  ics_tap1d far = {-100, 1};
  ics_conv1d_step(x, ox, N, &far, 1, &o);
  CHECK(ox[0] == 1 && ox[N - 1] == 1, "constant boundary value read");
  o.boundary = ICS_BOUNDARY_CLAMP;
  x[0] = 3, x[N - 1] = 5;
  ics_tap1d l2 = {2, 1}, r2 = {-2, 1};
  ics_conv1d_step(x, ox, N, &l2, 1, &o);
  ics_conv1d_step(x, oy, N, &r2, 1, &o);
  CHECK(ox[0] == 3 && ox[1] == 3 && ox[2] == 3 && oy[N - 1] == 5 && oy[N - 3] == 5,
        "clamp reads the edge pixel");
}

/* 2D impulse covariance: Poisson exact per step, ellipse in expectation (statistical). */
static void test_2d_impulse(void) {
  enum { W = 160, H = 160, STEPS = 100 };
  float *img = calloc(W * H, sizeof *img);
  ics_class2d c;
  ics_class2d_init_axes(&c, 0, 0, 3, 1, 30);
  ics_conv_opts o = {0};
  o.boundary = ICS_BOUNDARY_CONSTANT;
  o.compensate = ICS_COMP_NONNEG;
  const ics_kernel_member mem[2] = {ICS_KERNEL_POISSON, ICS_KERNEL_ELLIPSE};
  for (int q = 0; q < 2; q++) {
    ics_kernel2d k;
    ics_kernel2d_init(&k, mem[q], &c);
    k.seed = 2013;
    k.nsamples = q ? 3 : 8;
    memset(img, 0, W * H * sizeof *img);
    img[80 * W + 80] = 1;
    ics_schedule2d s = {&k, 1};
    ics_conv_stats st;
    ics_status rc = ics_conv2d_run(img, W, H, &s, 0, STEPS, &o, &st);
    CHECK(rc == ICS_OK, "2d run %s", ics_status_str(rc));
    double mass, m[2], cv[3];
    image_moments(img, W, H, &mass, m, cv);
    CHECK(fabs(mass - 1) < 1e-4, "%s mass %g", ics_kernel_member_name(mem[q]), mass);
    double want[3] = {STEPS * c.cxx, STEPS * c.cxy, STEPS * c.cyy};
    double sc = want[0] + want[2];
    double tol[3];
    if (mem[q] == ICS_KERNEL_POISSON) {
      CHECK(fabs(m[0] - 80) < 1e-4 && fabs(m[1] - 80) < 1e-4, "%s mean (%g, %g)",
            ics_kernel_member_name(mem[q]), m[0], m[1]);
      for (int a = 0; a < 3; a++) tol[a] = 1e-4 * sc;
    } else {
      /* sd of one step's realised second moment, from 20000 draws of the kernel (other iterations) */
      double s1[3] = {0}, s2[3] = {0};
      const int M = 20000;
      for (int i = 0; i < M; i++) {
        int n;
        ics_kernel2d_taps(&k, 1000000 + (uint64_t)i, tc, CAP, &n);
        double Wt, mm[2], cc[3];
        ics_taps2d_moments(tc, n, &Wt, mm, cc);
        double v[3] = {cc[0] + mm[0] * mm[0], cc[1] + mm[0] * mm[1], cc[2] + mm[1] * mm[1]};
        for (int a = 0; a < 3; a++) s1[a] += v[a], s2[a] += v[a] * v[a];
      }
      for (int a = 0; a < 3; a++) {
        double mu = s1[a] / M, sd = sqrt(fmax(s2[a] / M - mu * mu, 0));
        tol[a] = 5 * sd * sqrt((double)STEPS) + 1e-4 * sc;
      }
    }
    /* the engine keeps every step's realised tap covariance (compensated: nothing added), so
     * the image covariance is their sum; that sum is n Sigma exactly (Poisson) or in
     * expectation (ellipse, N = 3: its realised mean also varies, which the covariance absorbs
     * only in expectation; the tolerance uses second moments about the class mean) */
    double realcov[3] = {0, 0, 0}, msum[2] = {0, 0};
    for (int i = 0; i < STEPS; i++) {
      int n;
      ics_kernel2d_taps(&k, (uint64_t)i, tc, CAP, &n);
      double Wt, mm[2], cc[3];
      ics_taps2d_moments(tc, n, &Wt, mm, cc);
      for (int a = 0; a < 3; a++) realcov[a] += cc[a];
      msum[0] += mm[0], msum[1] += mm[1];
    }
    CHECK(fabs(m[0] - 80 - msum[0]) < 1e-4 && fabs(m[1] - 80 - msum[1]) < 1e-4,
          "%s: image mean moves by the sum of the steps' means", ics_kernel_member_name(mem[q]));
    for (int a = 0; a < 3; a++) {
      CHECK(fabs(cv[a] - realcov[a]) <= 1e-4 * sc,
            "%s cov[%d] %.8g vs sum of realised %.8g", ics_kernel_member_name(mem[q]), a, cv[a],
            realcov[a]);
      CHECK(fabs(cv[a] - want[a]) <= tol[a], "%s cov[%d] %.8g vs n Sigma %.8g (tol %.3g)",
            ics_kernel_member_name(mem[q]), a, cv[a], want[a], tol[a]);
    }
    printf("2D impulse, %s N=%d, %d steps, compensated: cov (%.6f %.6f %.6f), realised sum "
           "(%.6f %.6f %.6f), n Sigma (%.6f %.6f %.6f), residual (%.3g, %.3g)\n",
           ics_kernel_member_name(mem[q]), k.nsamples, STEPS, cv[0], cv[1], cv[2], realcov[0],
           realcov[1], realcov[2], want[0], want[1], want[2], st.residual[0], st.residual[1]);
  }
  /* uncompensated Poisson and 2-sample ellipse: realised covariances + the per-axis bilinear
   * variance sum w f (1 - f) (both computed here from the taps) */
  for (int q = 0; q < 2; q++) {
  ics_kernel2d k;
  ics_kernel2d_init(&k, mem[q], &c);
  k.seed = 2013;
  k.nsamples = q ? 2 : 8;
  double ix = 0, iy = 0, rc[3] = {0, 0, 0};
  for (int i = 0; i < STEPS; i++) {
    int n;
    ics_kernel2d_taps(&k, (uint64_t)i, tc, CAP, &n);
    for (int j = 0; j < n; j++) {
      double fx = tc[j].x - floor(tc[j].x), fy = tc[j].y - floor(tc[j].y);
      ix += tc[j].w * fx * (1 - fx), iy += tc[j].w * fy * (1 - fy);
    }
    double Wt, mm[2], cc[3];
    ics_taps2d_moments(tc, n, &Wt, mm, cc);
    for (int a = 0; a < 3; a++) rc[a] += cc[a];
  }
  memset(img, 0, W * H * sizeof *img);
  img[80 * W + 80] = 1;
  o.compensate = ICS_COMP_NONE;
  ics_schedule2d s = {&k, 1};
  ics_conv2d_run(img, W, H, &s, 0, STEPS, &o, NULL);
  double mass, m[2], cv[3];
  image_moments(img, W, H, &mass, m, cv);
  double sc = STEPS * (c.cxx + c.cyy);
  CHECK(fabs(cv[0] - (rc[0] + ix)) < 1e-4 * sc && fabs(cv[1] - rc[1]) < 1e-4 * sc &&
            fabs(cv[2] - (rc[2] + iy)) < 1e-4 * sc,
        "uncompensated %s: cov (%g %g %g), want (%g %g %g)", ics_kernel_member_name(mem[q]), cv[0],
        cv[1], cv[2], rc[0] + ix, rc[1], rc[2] + iy);
  if (q == 0)
    CHECK(fabs(rc[0] - STEPS * c.cxx) < 1e-10 * sc && fabs(rc[2] - STEPS * c.cyy) < 1e-10 * sc,
          "poisson: realised covariance sum is n Sigma");
  printf("2D impulse, %s N=%d, %d steps, uncompensated: cov (%.6f %.6f %.6f), realised sum "
         "(%.6f %.6f %.6f), interpolation added (%.6f, %.6f)\n", ics_kernel_member_name(mem[q]),
         k.nsamples, STEPS, cv[0], cv[1], cv[2], rc[0], rc[1], rc[2], ix, iy);
  }
  free(img);
}

/* Compensation table: Dirac class (mean, var), n steps, effective variance per step. */
static void test_compensation(void) {
  enum { N = 400, C0 = 100, STEPS = 50 };
  static double b[N];
  const double vars[] = {0, 0.05, 0.25, 1};
  const double shifts[] = {0, 0.3, 0.5};
  for (int member = 0; member < 2; member++) {
  printf("compensation (%s member, %d steps; effective variance per step = var(impulse)/n)\n",
         member ? "gauss N=9" : "dirac", STEPS);
  printf("%8s %6s | %12s %12s | %12s %12s | %12s %8s\n", "target", "shift", "none", "predicted",
         "nonneg", "residual", "signed", "sum|w|");
  for (int i = 0; i < 4; i++)
    for (int j = 0; j < 3; j++) {
      double var = vars[i], mu = shifts[j];
      ics_kernel1d k;
      ics_kernel1d_init(&k, member ? ICS_KERNEL_GAUSS : ICS_KERNEL_DIRAC, mu, var);
      ics_schedule1d s = {&k, 1};
      int n;
      ics_kernel1d_taps(&k, 0, ta, CAP, &n);
      double pred_none = var + my_interp(ta, n);
      double f = mu - floor(mu), vmin = f * (1 - f);
      double eff[3], mean[3];
      for (int mode = 0; mode < 3; mode++) {
        memset(b, 0, sizeof b);
        b[C0] = 1;
        ics_conv_opts o = {0};
        o.boundary = ICS_BOUNDARY_CONSTANT;
        o.compensate = (ics_comp_mode)mode;
        ics_conv1d_run(b, N, &s, 0, STEPS, &o, NULL);
        double M, m, v;
        line_moments(b, N, &M, &m, &v);
        eff[mode] = v / STEPS;
        mean[mode] = (m - C0) / STEPS;
        CHECK(fabs(mean[mode] - mu) < 1e-12, "mode %d mean per step %.15g vs %g", mode,
              mean[mode], mu);
      }
      /* signed-weights L1 norm of one compensated step */
      int nc;
      ics_taps1d_compensate(ta, n, ICS_COMP_SIGNED, tb, CAP, &nc, NULL);
      double l1 = 0;
      for (int q = 0; q < nc; q++) l1 += fabs(tb[q].w);
      double want_nonneg = var >= vmin ? var : vmin;
      printf("%8.3g %6.2g | %12.9f %12.9f | %12.9f %12.3g | %12.9f %8.4f\n", var, mu, eff[0],
             pred_none, eff[1], eff[1] - var, eff[2], l1);
      CHECK(fabs(eff[0] - pred_none) < 1e-12, "none: %.15g vs %.15g", eff[0], pred_none);
      CHECK(fabs(eff[1] - want_nonneg) < 1e-12, "nonneg: %.15g vs %.15g", eff[1], want_nonneg);
      CHECK(fabs(eff[2] - var) < 1e-12, "signed: %.15g vs %.15g", eff[2], var);
      if (var >= vmin) CHECK(fabs(l1 - 1) < 1e-15, "signed mode uses non-negative taps when it can");
    }
  }
  /* residual reported by the tap-level function for the hard-shadow case */
  ics_tap1d hard = {0.3, 1};
  int nc;
  double res;
  ics_taps1d_compensate(&hard, 1, ICS_COMP_NONNEG, tb, CAP, &nc, &res);
  CHECK(nc == 2 && fabs(res - 0.21) < 1e-15, "zero variance, shift 0.3: residual %.17g", res);
  /* 2D compensation, rotated anisotropic Poisson class with sub-pixel mean: exact */
  ics_class2d c;
  ics_class2d_init_axes(&c, 0.3, 0.5, 0.6, 0.3, 30);
  ics_kernel2d k;
  ics_kernel2d_init(&k, ICS_KERNEL_POISSON, &c);
  int n;
  ics_kernel2d_taps(&k, 4, tc, CAP, &n);
  static ics_tap2d out[CAP];
  double r3[3];
  ics_status st = ics_taps2d_compensate(tc, n, ICS_COMP_NONNEG, out, CAP, &nc, r3);
  double Wt, mm[2], cc[3];
  ics_taps2d_moments(out, nc, &Wt, mm, cc);
  int grid = 1;
  for (int q = 0; q < nc; q++) grid &= out[q].x == floor(out[q].x) && out[q].y == floor(out[q].y);
  CHECK(st == ICS_OK && grid, "2D compensated taps on the grid");
  CHECK(fabs(mm[0] - 0.3) < 1e-14 && fabs(mm[1] - 0.5) < 1e-14 && fabs(cc[0] - c.cxx) < 1e-13 &&
            fabs(cc[1] - c.cxy) < 1e-13 && fabs(cc[2] - c.cyy) < 1e-13,
        "2D compensation exact: cov (%.17g %.17g %.17g) vs (%.17g %.17g %.17g)", cc[0], cc[1], cc[2],
        c.cxx, c.cxy, c.cyy);
  /* 2D zero variance, mean (0.3, 0.5): non-negative residual diag(0.21, 0.25); signed exact */
  ics_tap2d p = {0.3, 0.5, 1};
  ics_taps2d_compensate(&p, 1, ICS_COMP_NONNEG, out, CAP, &nc, r3);
  CHECK(fabs(r3[0] - 0.21) < 1e-15 && fabs(r3[1]) < 1e-15 && fabs(r3[2] - 0.25) < 1e-15,
        "2D hard-shadow residual (%g %g %g)", r3[0], r3[1], r3[2]);
  ics_tap2d pc[2] = {{0.3 - 0.1, 0.5 - 0.05, 0.5}, {0.3 + 0.1, 0.5 + 0.05, 0.5}};
  ics_taps2d_compensate(pc, 2, ICS_COMP_SIGNED, out, CAP, &nc, r3);
  ics_taps2d_moments(out, nc, &Wt, mm, cc);
  CHECK(fabs(Wt - 1) < 1e-15 && fabs(mm[0] - 0.3) < 1e-15 && fabs(mm[1] - 0.5) < 1e-15 &&
            fabs(cc[0] - 0.01) < 1e-15 && fabs(cc[1] - 0.005) < 1e-15 && fabs(cc[2] - 0.0025) < 1e-15,
        "2D signed exact: mean (%g %g) cov (%g %g %g)", mm[0], mm[1], cc[0], cc[1], cc[2]);
}

/* Lyapunov mixing: a schedule cycling through all 1D members of one class converges to the same
 * Gaussian as a single member; compensated, the variance is exactly n sigma^2. */
static double ncdf(double z) { return 0.5 * erfc(-z / sqrt(2.0)); }

/* ICS_COMP_INTEGER (the integer-shift schedule). Derived expectations: step i shifts by
 * round((i+1) mu) - round(i mu) whole pixels, so after n steps from step 0 the total shift is
 * round(n mu) (telescoping), |round(n mu) - n mu| <= 1/2, and with an integer mean the class
 * variance is met exactly by non-negative integer taps. */
static void test_integer_shift(void) {
  enum { N = 512 };
  static double buf[N];
  ics_conv_opts o = {0};
  o.boundary = ICS_BOUNDARY_CONSTANT;
  o.compensate = ICS_COMP_INTEGER;
  /* zero variance, mean 0.3 px (Dirac class): an impulse stays ONE pixel (variance exactly 0)
   * at round(0.3 n), for every n = 1..200; NONNEG would add 0.21 px^2 per step */
  ics_kernel1d k;
  CHECK(ics_kernel1d_init(&k, ICS_KERNEL_DIRAC, 0.3, 0) == ICS_OK, "dirac 0.3, 0");
  ics_schedule1d sch = {&k, 1};
  for (int i = 0; i < N; i++) buf[i] = 0;
  buf[100] = 1;
  double worst_pos = 0, worst_var = 0;
  for (int n = 1; n <= 200; n++) {
    CHECK(ics_conv1d_run(buf, N, &sch, (uint64_t)(n - 1), 1, &o, NULL) == ICS_OK, "run %d", n);
    double w = 0, m = 0, v = 0;
    for (int i = 0; i < N; i++) w += buf[i], m += buf[i] * (i - 100);
    m /= w;
    for (int i = 0; i < N; i++) v += buf[i] * (i - 100 - m) * (i - 100 - m);
    v /= w;
    worst_pos = fmax(worst_pos, fabs(m - 0.3 * n));
    worst_var = fmax(worst_var, v);
    if (m != floor(0.3 * n + 0.5) || v != 0 || w != 1) {
      CHECK(0, "integer shift, n = %d: mean %.17g (want %g), var %g, weight %.17g", n, m,
            floor(0.3 * n + 0.5), v, w);
      break;
    }
  }
  CHECK(worst_pos <= 0.5 && worst_var == 0, "hard shadow: position error %g, variance %g",
        worst_pos, worst_var);
  printf("  integer shift, sigma^2 = 0, mu = 0.3, n = 1..200: variance %g, position error <= %g px\n",
         worst_var, worst_pos);
  /* a Heaviside edge stays a hard 0/1 edge after 100 steps */
  for (int i = 0; i < N; i++) buf[i] = i >= 100 ? 1.0 : 0.0;
  o.boundary = ICS_BOUNDARY_CLAMP;
  CHECK(ics_conv1d_run(buf, N, &sch, 0, 100, &o, NULL) == ICS_OK, "edge run");
  int hard = 1;
  for (int i = 0; i < N; i++) hard &= (buf[i] == 0.0 || buf[i] == 1.0) && (buf[i] == 1.0) == (i >= 130);
  CHECK(hard, "edge after 100 steps of 0.3 px: hard at 130");
  /* variance > 0: class (0.3, 2): impulse variance 2 n exactly (1e-12 relative), mean round(0.3 n) */
  CHECK(ics_kernel1d_init(&k, ICS_KERNEL_TOPHAT, 0.3, 2.0) == ICS_OK, "tophat 0.3, 2");
  o.boundary = ICS_BOUNDARY_CONSTANT;
  for (int i = 0; i < N; i++) buf[i] = 0;
  buf[100] = 1;
  ics_conv_stats st;
  CHECK(ics_conv1d_run(buf, N, &sch, 0, 50, &o, &st) == ICS_OK, "tophat run");
  double w = 0, m = 0, v = 0;
  for (int i = 0; i < N; i++) w += buf[i], m += buf[i] * (i - 100);
  m /= w;
  for (int i = 0; i < N; i++) v += buf[i] * (i - 100 - m) * (i - 100 - m);
  v /= w;
  CHECK(fabs(m - 15) <= 1e-9 && fabs(v / 100 - 1) <= 1e-12, "tophat integer: mean %.17g var %.17g", m, v);
  CHECK(fabs(st.residual[0]) <= 1e-12, "residual %g", st.residual[0]);
  /* check_opts: a non-finite constant is rejected */
  {
    ics_conv_opts c = {0};
    c.boundary = ICS_BOUNDARY_CONSTANT;
    c.constant = INFINITY;
    double a[4] = {0, 0, 1, 1}, b[4];
    ics_tap1d t1 = {0.5, 1};
    CHECK(ics_conv1d_step(a, b, 4, &t1, 1, &c) == ICS_ERR_INFINITE, "constant = inf");
    c.constant = -INFINITY;
    CHECK(ics_conv1d_step(a, b, 4, &t1, 1, &c) == ICS_ERR_INFINITE, "constant = -inf");
    /* NaN pixels propagate (documented): a NaN reaches the pixels whose taps read it */
    double an[4] = {0, NAN, 1, 1};
    c.constant = 0;
    CHECK(ics_conv1d_step(an, b, 4, &t1, 1, &c) == ICS_OK && isnan(b[1]) && isnan(b[2]) &&
              !isnan(b[0]) && !isnan(b[3]),
          "NaN propagation: %g %g %g %g", b[0], b[1], b[2], b[3]);
  }
  /* 2D: not supported */
  float img[16] = {0}, out[16];
  ics_tap2d t2 = {0.3, 0, 1};
  CHECK(ics_conv2d_step(img, out, 4, 4, &t2, 1, &o) == ICS_ERR_UNSUPPORTED, "2D integer mode");
}

/* 2D Lyapunov mixing: a schedule alternating the elliptical (N = 2) and Poisson-disk (N = 8)
 * members of one class (ellipse with N = 4: two diameters, a full-rank step; integer class mean,
 * so no lattice bound applies), propagated from an impulse with non-negative compensation: the
 * applied integer taps have exactly each step's tap moments (residual 0). Moments add: the image's mean and
 * covariance must equal the sums over the steps of the taps' own moments (computed from
 * ics_schedule2d_taps, independently of the engine), to float storage (1e-6 relative). */
static void test_mixed_2d(void) {
  enum { W = 256, H = 256, STEPS = 20, CAP2 = 4096 }; /* mean (20, -40) from (96, 176) */
  static float img[W * H];
  static ics_tap2d t2[CAP2];
  ics_class2d cls;
  CHECK(ics_class2d_init_axes(&cls, 1, -2, 6, 2, 30) == ICS_OK, "class");
  ics_kernel2d m[2];
  CHECK(ics_kernel2d_init(&m[0], ICS_KERNEL_ELLIPSE, &cls) == ICS_OK, "ellipse");
  CHECK(ics_kernel2d_init(&m[1], ICS_KERNEL_POISSON, &cls) == ICS_OK, "poisson");
  m[0].seed = 5, m[1].seed = 9;
  m[0].nsamples = 4;
  ics_schedule2d s = {m, 2};
  double sm[2] = {0, 0}, sc[3] = {0, 0, 0};
  for (int i = 0; i < STEPS; i++) {
    int n = 0;
    CHECK(ics_schedule2d_taps(&s, (uint64_t)i, t2, CAP2, &n) == ICS_OK, "taps %d", i);
    double w, mm[2], cv[3];
    ics_taps2d_moments(t2, n, &w, mm, cv);
    sm[0] += mm[0], sm[1] += mm[1];
    for (int j = 0; j < 3; j++) sc[j] += cv[j];
  }
  for (int i = 0; i < W * H; i++) img[i] = 0;
  img[176 * W + 96] = 1;
  ics_conv_opts o = {0};
  o.boundary = ICS_BOUNDARY_CONSTANT;
  o.compensate = ICS_COMP_NONNEG;
  ics_conv_stats st;
  CHECK(ics_conv2d_run(img, W, H, &s, 0, STEPS, &o, &st) == ICS_OK, "2D mixed run");
  double s0 = 0, sx = 0, sy = 0;
  for (int y = 0; y < H; y++)
    for (int x = 0; x < W; x++) s0 += img[y * W + x], sx += img[y * W + x] * (x - 96.0), sy += img[y * W + x] * (y - 176.0);
  double mx = sx / s0, my = sy / s0, c[3] = {0, 0, 0};
  for (int y = 0; y < H; y++)
    for (int x = 0; x < W; x++) {
      double v = img[y * W + x], dx = x - 96.0 - mx, dy = y - 176.0 - my;
      c[0] += v * dx * dx, c[1] += v * dx * dy, c[2] += v * dy * dy;
    }
  for (int j = 0; j < 3; j++) c[j] /= s0;
  double tr = sc[0] + sc[2], dev = fmax(fabs(mx - sm[0]), fabs(my - sm[1])) / sqrt(tr);
  for (int j = 0; j < 3; j++) dev = fmax(dev, fabs(c[j] - sc[j]) / tr);
  CHECK(dev <= 1e-6 && fabs(st.residual[0]) + fabs(st.residual[1]) <= 1e-9,
        "2D mixed: moments off the sums by %.3g (residual %g %g)", dev, st.residual[0], st.residual[1]);
  /* the Poisson steps are exact every step and the ellipse steps in expectation: the sums are
   * near n Sigma (10 ellipse draws: within 35 %) */
  CHECK(fabs(sc[0] / (STEPS * cls.cxx) - 1) < 0.35, "sum cxx %.4g vs n cxx %.4g", sc[0], STEPS * cls.cxx);
  printf("2D mixed (ellipse 4, poisson 8), %d steps: mean (%.6g, %.6g) vs sums (%.6g, %.6g), cov "
         "(%.6g, %.6g, %.6g) vs sums (%.6g, %.6g, %.6g): max rel dev %.2g\n", STEPS, mx, my, sm[0],
         sm[1], c[0], c[1], c[2], sc[0], sc[1], sc[2], dev);
}

static void test_mixed(void) {
  enum { N = 500, X0 = 250, STEPS = 100 };
  static double b[N];
  double mu = 0.25, var = 2;
  ics_kernel1d m[4];
  ics_kernel1d_init(&m[0], ICS_KERNEL_DIRAC, mu, var);
  ics_kernel1d_init(&m[1], ICS_KERNEL_TOPHAT, mu, var);
  ics_kernel1d_init(&m[2], ICS_KERNEL_STOCH_DIRAC, mu, var);
  ics_kernel1d_init(&m[3], ICS_KERNEL_GAUSS, mu, var);
  m[2].seed = 77;
  for (int cfg = 0; cfg < 2; cfg++) {
    ics_schedule1d s = {cfg ? m : m + 3, cfg ? 4 : 1};
    /* impulse: moments add, exactly n var with compensation (stochastic member: its taps'
     * realised variances, summed here) */
    double sumv = 0, f = mu - floor(mu), vmin = f * (1 - f);
    for (int i = 0; i < STEPS; i++) {
      int n;
      ics_schedule1d_taps(&s, (uint64_t)i, ta, CAP, &n);
      double W, mm, v;
      ics_taps1d_moments(ta, n, &W, &mm, &v);
      /* non-negative compensation reaches v unless v < f(1 - f) (a stochastic-Dirac draw can
       * be that narrow): then f(1 - f) */
      sumv += v > vmin ? v : vmin;
    }
    memset(b, 0, sizeof b);
    b[X0] = 1;
    ics_conv_opts o = {0};
    o.boundary = ICS_BOUNDARY_CONSTANT;
    o.compensate = ICS_COMP_NONNEG;
    ics_conv1d_run(b, N, &s, 0, STEPS, &o, NULL);
    double M, mean, v;
    line_moments(b, N, &M, &mean, &v);
    CHECK(fabs(mean - (X0 + STEPS * mu)) < 1e-10 && fabs(v - sumv) < 1e-10 * v,
          "%s schedule: mean %.12g var %.12g (sum of max(taps' variance, f(1-f)) %.12g)", cfg ? "mixed" : "gauss",
          mean, v, sumv);
    /* Heaviside: compare with the Gaussian cdf of mean n mu, variance sum v (with continuity
     * correction 1/2 for the lattice). Edgeworth: symmetric kernels, error O(kurtosis / n);
     * the Dirac's excess kurtosis -2 gives |err| <= 2 / (24 n) * max|He3 phi| (~0.55) < 5e-4. */
    for (int i = 0; i < N; i++) b[i] = i >= X0 ? 1 : 0;
    o.boundary = ICS_BOUNDARY_CLAMP;
    ics_conv1d_run(b, N, &s, 0, STEPS, &o, NULL);
    double err = 0;
    for (int i = 100; i < 400; i++) {
      double z = ((double)i - X0 - STEPS * mu + 0.5) / sqrt(sumv);
      err = fmax(err, fabs(b[i] - ncdf(z)));
    }
    CHECK(err < 5e-4, "%s schedule vs Gaussian cdf: max |diff| %.3g", cfg ? "mixed" : "gauss", err);
    printf("%s schedule, %d steps, Heaviside vs Gaussian cdf: max |diff| %.3g\n",
           cfg ? "mixed (dirac, tophat, stoch-dirac, gauss)" : "gauss", STEPS, err);
  }
}

static void test_errors(void) {
  double a[4] = {0}, b[4];
  ics_tap1d t = {0.5, 1};
  CHECK(ics_conv1d_step(NULL, b, 4, &t, 1, NULL) == ICS_ERR_INVALID_ARG, "NULL in");
  CHECK(ics_conv1d_step(a, a, 4, &t, 1, NULL) == ICS_ERR_INVALID_ARG, "in == out");
  CHECK(ics_conv1d_step(a, b, 0, &t, 1, NULL) == ICS_ERR_SIZE, "zero size");
  CHECK(ics_conv1d_step(a, b, (size_t)1 << 40, &t, 1, NULL) == ICS_ERR_SIZE, "huge size");
  CHECK(ics_conv1d_step(a, b, 4, &t, 0, NULL) == ICS_ERR_INVALID_ARG, "no taps");
  ics_tap1d bad = {NAN, 1};
  CHECK(ics_conv1d_step(a, b, 4, &bad, 1, NULL) == ICS_ERR_NAN, "NaN tap");
  bad.x = INFINITY;
  CHECK(ics_conv1d_step(a, b, 4, &bad, 1, NULL) == ICS_ERR_INFINITE, "inf tap");
  bad.x = 1e12;
  CHECK(ics_conv1d_step(a, b, 4, &bad, 1, NULL) == ICS_ERR_RANGE, "huge offset");
  ics_conv_opts o = {0};
  o.constant = NAN;
  CHECK(ics_conv1d_step(a, b, 4, &t, 1, &o) == ICS_ERR_NAN, "NaN constant");
  o = (ics_conv_opts){0};
  o.boundary = (ics_boundary)7;
  CHECK(ics_conv1d_step(a, b, 4, &t, 1, &o) == ICS_ERR_RANGE, "bad boundary");
  float f[4] = {0}, g[4];
  ics_tap2d t2 = {0.5, 0.5, 1};
  CHECK(ics_conv2d_step(f, g, 0, 4, &t2, 1, NULL) == ICS_ERR_SIZE, "2D zero width");
  CHECK(ics_conv2d_step(f, g, (size_t)1 << 20, (size_t)1 << 20, &t2, 1, NULL) == ICS_ERR_SIZE,
        "2D huge");
  ics_kernel1d k;
  ics_kernel1d_init(&k, ICS_KERNEL_DIRAC, 0, 1);
  k.cls.var = -1;
  ics_schedule1d s = {&k, 1};
  CHECK(ics_conv1d_run(a, 4, &s, 0, 3, NULL, NULL) == ICS_ERR_NEGATIVE_VARIANCE, "bad kernel in run");
  ics_kernel1d two_k[2];
  ics_kernel1d_init(&two_k[0], ICS_KERNEL_DIRAC, 0, 1);
  ics_kernel1d_init(&two_k[1], ICS_KERNEL_GAUSS, 0, 1);
  two_k[1].cls.mean = NAN;
  ics_schedule1d s2 = {two_k, 2};
  CHECK(ics_conv1d_run(a, 4, &s2, 0, 3, NULL, NULL) == ICS_ERR_NAN, "second member invalid");
  ics_class2d c2;
  ics_class2d_init_axes(&c2, 0, 0, 1, 1, 0);
  ics_kernel2d k2;
  ics_kernel2d_init(&k2, ICS_KERNEL_POISSON, &c2);
  k2.nsamples = 1;
  ics_schedule2d s3 = {&k2, 1};
  float im[4] = {0};
  CHECK(ics_conv2d_run(im, 2, 2, &s3, 0, 1, NULL, NULL) == ICS_ERR_RANGE, "2D run, bad member");
  ics_tap1d zw[2] = {{0, 1}, {1, -1}};
  int n;
  CHECK(ics_taps1d_compensate(zw, 2, ICS_COMP_NONNEG, b == NULL ? NULL : ta, CAP, &n, NULL) ==
            ICS_ERR_RANGE, "zero total weight");
  ics_tap1d two[2] = {{0.5, 0.5}, {3.5, 0.5}};
  CHECK(ics_taps1d_discretize(two, 2, ta, 3, &n) == ICS_ERR_SIZE, "discretize cap");
  CHECK(isnan(ics_taps1d_interp_var(NULL, 2)), "interp of nothing is NaN");
}

int main(void) {
  test_mixed_2d();
  test_integer_shift();
  test_binomial();
  test_moments_add();
  test_linear_shift_boundary();
  test_2d_impulse();
  test_compensation();
  test_mixed();
  test_errors();
  return test_summary("test_conv");
}
