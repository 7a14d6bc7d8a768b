/* test_light.c — lights on the virtual light plane (libicshadow/src/light.c): tilt angles and
 * their precision near 90 degrees, covariance <-> (varx, vary, alpha), the Eq. 7/15 mapping,
 * and 1D light functions (moments, cdf / quantile round trips). Expected values are derived
 * independently: closed-form moments of the box, the triangular density and Gaussian mixtures,
 * published normal quantiles, the series cot x = 1/x - x/3 - x^3/45 - 2x^5/945, and
 * trapezoid quadrature of the pdf. */
#include <errno.h>
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "icshadow.h"
#include "testutil.h"

static double rel(double a, double b) { return fabs(a - b) / fmax(fabs(b), DBL_MIN); }

/* moments of the pdf by the trapezoid rule on [lo, hi] (independent of the closed forms) */
static void quad_moments(const ics_light1d *l, double lo, double hi, double m[4]) {
  const int n = 400000;
  double h = (hi - lo) / n, s0 = 0, s1 = 0, s2 = 0, s3 = 0;
  for (int i = 0; i <= n; i++) {
    double x = lo + i * h, w = (i == 0 || i == n) ? 0.5 : 1.0;
    double p = w * ics_light1d_pdf(l, x);
    s0 += p, s1 += p * x;
  }
  double mean = s1 / s0;
  for (int i = 0; i <= n; i++) {
    double x = lo + i * h, w = (i == 0 || i == n) ? 0.5 : 1.0;
    double p = w * ics_light1d_pdf(l, x), dx = x - mean;
    s2 += p * dx * dx, s3 += p * dx * dx * dx;
  }
  m[0] = s0 * h, m[1] = mean, m[2] = s2 / s0, m[3] = (s3 / s0) / pow(s2 / s0, 1.5);
}

static void round_trips(const char *name, const ics_light1d *l, double tol) {
  double worst = 0, worst_p = 0;
  for (int k = 1; k <= 60; k++) {
    double p = pow(10.0, -k / 4.0); /* 10^-0.25 .. 1e-15 */
    double ps[2] = {p, 1.0 - p};
    for (int j = 0; j < 2; j++) {
      double q = ics_light1d_quantile(l, ps[j]);
      /* compare the smaller tail: cdf below 1/2, sf above */
      double e = ps[j] <= 0.5 ? rel(ics_light1d_cdf(l, q), ps[j])
                              : rel(ics_light1d_sf(l, q), 1.0 - ps[j]);
      double x = ics_light1d_isf(l, p); /* upper quantile: sf(x) = p */
      double e2 = rel(ics_light1d_sf(l, x), p);
      if (e > worst) worst = e, worst_p = ps[j];
      if (e2 > worst) worst = e2, worst_p = -p;
    }
  }
  CHECK(worst <= tol, "%s: cdf(quantile(p)) relative error %.3g at p = %.17g (bound %.3g)", name,
        worst, worst_p, tol);
}

static void test_normal(void) {
  /* published: Phi^-1(0.975) = 1.959963984540054, Phi^-1(1e-10) = -6.361340902404056,
   * Phi^-1(0.5) = 0, Phi(-10) = 7.619853024160527e-24 */
  CHECK(rel(ics_normal_quantile(0.975), 1.959963984540054) < 4e-15, "%.17g",
        ics_normal_quantile(0.975));
  CHECK(rel(ics_normal_quantile(1e-10), -6.361340902404056) < 4e-15, "%.17g",
        ics_normal_quantile(1e-10));
  CHECK(ics_normal_quantile(0.5) == 0, "%.17g", ics_normal_quantile(0.5));
  CHECK(rel(ics_normal_cdf(-10), 7.619853024160527e-24) < 1e-14, "%.17g", ics_normal_cdf(-10));
  CHECK(rel(ics_normal_sf(10), 7.619853024160527e-24) < 1e-14, "%.17g", ics_normal_sf(10));
  CHECK(isnan(ics_normal_quantile(-0.1)) && isnan(ics_normal_quantile(1.5)) &&
            isnan(ics_normal_quantile(NAN)),
        "phiinv outside [0, 1] must be NaN");
  CHECK(ics_normal_quantile(0) == -INFINITY && ics_normal_quantile(1) == INFINITY, "phiinv ends");
  /* subnormal and tiny p (Phi(x) subnormal, exp(x^2/2) overflows: once NaN). Reference: mpmath
   * 1.2.1 at 50 digits, x = findroot(log(ncdf(t)) - log(p), -sqrt(-2 log p)) for p the exact
   * double; ncdf(x)/p - 1 < 2e-51 at each. */
  static const double tiny[][2] = {
      {0x1p-1074, -38.467405617144346251},  {0x3p-1074, -38.438854734569955022},
      {1e-315, -37.967300351067357735},     {1e-310, -37.663060331949523732},
      {0x1p-1022, -37.519379347144499821},  {1e-300, -37.047096299361199237},
      {1e-200, -30.205594179579643063}};
  for (size_t j = 0; j < sizeof tiny / sizeof tiny[0]; j++) {
    double x = ics_normal_quantile(tiny[j][0]);
    CHECK(rel(x, tiny[j][1]) < 4e-16, "phiinv(%a) = %.17g, mpmath %.17g", tiny[j][0], x,
          tiny[j][1]);
  }
}

static void test_gauss(void) {
  ics_light1d *l = NULL, *bad = NULL;
  CHECK(ics_light1d_create_gauss(&l, 0.3, 2.0) == ICS_OK, "gauss");
  CHECK(ics_light1d_mean(l) == 0.3 && ics_light1d_var(l) == 2.0, "moments");
  CHECK(ics_light1d_quantile(l, 0.5) == 0.3, "median %.17g", ics_light1d_quantile(l, 0.5));
  round_trips("gauss", l, 1e-13);
  bad = l; /* a failed create leaves *out NULL, whatever it held */
  CHECK(ics_light1d_create_gauss(&bad, 0, -1) == ICS_ERR_NEGATIVE_VARIANCE && !bad,
        "negative var");
  CHECK(ics_light1d_create_gauss(&bad, NAN, 1) == ICS_ERR_NAN && !bad, "NaN mean");
  CHECK(ics_light1d_create_gauss(&bad, 0, INFINITY) == ICS_ERR_INFINITE && !bad, "inf var");
  CHECK(ics_light1d_create_gauss(NULL, 0, 1) == ICS_ERR_INVALID_ARG, "NULL out");
  ics_light1d_destroy(l);
  /* a point light: the cdf steps at the mean */
  CHECK(ics_light1d_create_gauss(&l, 1.5, 0) == ICS_OK, "point");
  CHECK(ics_light1d_cdf(l, 1.4999) == 0 && ics_light1d_cdf(l, 1.5) == 1 &&
            ics_light1d_quantile(l, 0.3) == 1.5,
        "point light cdf / quantile");
  ics_light1d_destroy(l);
}

static void test_box(void) {
  ics_light1d *l = NULL, *bad = NULL;
  CHECK(ics_light1d_create_box(&l, -1.0, 3.0) == ICS_OK, "box");
  CHECK(ics_light1d_mean(l) == 1.0, "box mean");
  CHECK(rel(ics_light1d_var(l), 16.0 / 12.0) < 1e-15, "box var %.17g", ics_light1d_var(l));
  CHECK(ics_light1d_quantile(l, 0.25) == 0.0 && ics_light1d_quantile(l, 0.75) == 2.0,
        "box quantiles");
  CHECK(ics_light1d_cdf(l, 0.0) == 0.25 && ics_light1d_sf(l, 2.0) == 0.25, "box cdf");
  CHECK(ics_light1d_skewness(l) == 0, "box skewness");
  CHECK(ics_light1d_create_box(&bad, 1, 1) == ICS_ERR_RANGE &&
            ics_light1d_create_box(&bad, 2, 1) == ICS_ERR_RANGE && !bad,
        "empty box rejected");
  for (int k = 1; k < 100; k++) {
    double p = k / 100.0, q = ics_light1d_quantile(l, p);
    /* absolute: q - lo cancels, so p comes back to within 2 ulp of |q| / (hi - lo) */
    CHECK(fabs(ics_light1d_cdf(l, q) - p) <= 2 * DBL_EPSILON, "box round trip p = %g", p);
  }
  ics_light1d_destroy(l);
}

static void test_mix(void) {
  ics_light1d *l = NULL, *bad = NULL;
  /* weights (1, 3) -> (1/4, 3/4); means (-1, 2); variances (0.5, 2):
   * mean = -1/4 + 3/2 = 1.25; var = 1/4 (0.5 + 2.25^2) + 3/4 (2 + 0.75^2) = 3.3125;
   * third central moment = 1/4 (-2.25^3 - 3*2.25*0.5) + 3/4 (0.75^3 + 3*0.75*2) = -0.140625
   * ... computed term by term: 1/4 (-11.390625 - 3.375) + 3/4 (0.421875 + 4.5) = -0.0 ...
   * = -3.69140625 + 3.69140625 = 0: this particular mixture has zero skewness. */
  double w[2] = {1, 3}, mu[2] = {-1, 2}, var[2] = {0.5, 2};
  CHECK(ics_light1d_create_mix(&l, 2, w, mu, var) == ICS_OK, "mix");
  CHECK(rel(ics_light1d_mean(l), 1.25) < 1e-15, "mix mean %.17g", ics_light1d_mean(l));
  CHECK(rel(ics_light1d_var(l), 3.3125) < 1e-15, "mix var %.17g", ics_light1d_var(l));
  CHECK(fabs(ics_light1d_skewness(l)) < 1e-15, "mix skew %.17g", ics_light1d_skewness(l));
  round_trips("mix", l, 1e-12);
  ics_light1d_destroy(l);
  /* a skewed mixture: 0.8 N(0, 0.25) + 0.2 N(2, 0.25): checked against quadrature */
  double w2[2] = {0.8, 0.2}, mu2[2] = {0, 2}, var2[2] = {0.25, 0.25};
  CHECK(ics_light1d_create_mix(&l, 2, w2, mu2, var2) == ICS_OK, "mix2");
  double m[4];
  quad_moments(l, -10, 12, m);
  CHECK(fabs(m[0] - 1) < 1e-12, "mass %.17g", m[0]);
  CHECK(rel(ics_light1d_mean(l), m[1]) < 1e-12 && rel(ics_light1d_mean(l), 0.4) < 1e-15,
        "mean %.17g vs quadrature %.17g", ics_light1d_mean(l), m[1]);
  CHECK(rel(ics_light1d_var(l), m[2]) < 1e-10, "var %.17g vs %.17g", ics_light1d_var(l), m[2]);
  CHECK(rel(ics_light1d_skewness(l), m[3]) < 1e-9, "skew %.17g vs %.17g",
        ics_light1d_skewness(l), m[3]);
  round_trips("mix2", l, 1e-12);
  ics_light1d_destroy(l);
  CHECK(ics_light1d_create_mix(&bad, 0, w, mu, var) == ICS_ERR_SIZE && !bad, "empty mixture");
  double wz[2] = {0, 0};
  CHECK(ics_light1d_create_mix(&bad, 2, wz, mu, var) == ICS_ERR_INVALID_ARG && !bad,
        "zero weights");
  double wn[2] = {1, -1};
  CHECK(ics_light1d_create_mix(&bad, 2, wn, mu, var) == ICS_ERR_INVALID_ARG && !bad,
        "negative weight");
}

/* derived quantities that overflow are rejected (ICS_ERR_RANGE), not returned as inf */
static void test_overflow(void) {
  ics_light1d *l = NULL;
  CHECK(ics_light1d_create_box(&l, -1e308, 1e308) == ICS_ERR_RANGE && !l, "box width 2e308");
  CHECK(ics_light1d_create_box(&l, 0, 1.5e154) == ICS_ERR_RANGE && !l,
        "box variance (1.5e154)^2 / 12");
  CHECK(ics_light1d_create_box(&l, -1e153, 1e153) == ICS_OK && isfinite(ics_light1d_var(l)),
        "box 2e153 wide is fine");
  ics_light1d_destroy(l);
  double w[2] = {1e308, 1e308}, mu[2] = {0, 1}, var[2] = {1, 1};
  CHECK(ics_light1d_create_mix(&l, 2, w, mu, var) == ICS_ERR_RANGE && !l, "weights' sum 2e308");
  double w1[2] = {1, 1}, mu1[2] = {1e308, -1e308};
  CHECK(ics_light1d_create_mix(&l, 2, w1, mu1, var) == ICS_ERR_RANGE && !l,
        "mixture variance 1e616");
  double w0[2] = {0, 0};
  CHECK(ics_light1d_create_mix(&l, 2, w0, mu, var) == ICS_ERR_INVALID_ARG && !l,
        "weights sum to 0");
  double x[2] = {-1e308, 1e308}, p[2] = {1, 1};
  CHECK(ics_light1d_create_tab(&l, 2, x, p) != ICS_OK && !l, "table 2e308 wide");
}

static void test_tab(void) {
  /* triangular density a = 0, c = 1, b = 3: mean 4/3, var 7/18,
   * skewness sqrt2 (a+b-2c)(2a-b-c)(a-2b+c) / (5 (7)^1.5) = sqrt2 * 20 / (5 * 7^1.5),
   * cdf x^2/3 on [0, 1], quantile 3 - sqrt(6 (1 - p)) for p >= 1/3 */
  ics_light1d *l = NULL;
  double x[3] = {0, 1, 3}, p[3] = {0, 7, 0}; /* unnormalised on purpose */
  CHECK(ics_light1d_create_tab(&l, 3, x, p) == ICS_OK, "tab");
  CHECK(rel(ics_light1d_mean(l), 4.0 / 3.0) < 1e-15, "tab mean %.17g", ics_light1d_mean(l));
  CHECK(rel(ics_light1d_var(l), 7.0 / 18.0) < 1e-14, "tab var %.17g", ics_light1d_var(l));
  double skew = sqrt(2.0) * 20.0 / (5.0 * pow(7.0, 1.5));
  CHECK(rel(ics_light1d_skewness(l), skew) < 1e-13, "tab skew %.17g vs %.17g",
        ics_light1d_skewness(l), skew);
  CHECK(rel(ics_light1d_cdf(l, 0.5), 0.25 / 3.0) < 1e-15, "tab cdf");
  CHECK(rel(ics_light1d_pdf(l, 2.0), 1.0 / 3.0) < 1e-15, "tab pdf %.17g", ics_light1d_pdf(l, 2));
  for (int k = 1; k < 100; k++) {
    double pp = k / 100.0;
    double q = ics_light1d_quantile(l, pp);
    double ref = pp <= 1.0 / 3.0 ? sqrt(3.0 * pp) : 3.0 - sqrt(6.0 * (1.0 - pp));
    CHECK(fabs(q - ref) < 4e-15 * 3, "tab quantile(%g) = %.17g, expected %.17g", pp, q, ref);
  }
  ics_light1d_destroy(l);
  double xb[2] = {0, 1}, pb[2] = {1, -1};
  CHECK(ics_light1d_create_tab(&l, 2, xb, pb) == ICS_ERR_INVALID_ARG && !l, "negative density");
  double xc[2] = {1, 1}, pc[2] = {1, 1};
  CHECK(ics_light1d_create_tab(&l, 2, xc, pc) == ICS_ERR_INVALID_ARG && !l,
        "non-increasing nodes");
}

/* cot x by its series, x small (|x| < 1e-2: the next term 2x^7/4725... is below 1 ulp) */
static double cot_series(double x) {
  double x2 = x * x;
  return 1.0 / x - x * (1.0 / 3.0 + x2 * (1.0 / 45.0 + x2 * (2.0 / 945.0)));
}

static void test_tilt(void) {
  CHECK(ics_light_tan_deg(0) == 0, "tan 0");
  CHECK(rel(ics_light_tan_deg(45), 1.0) <= DBL_EPSILON, "tan 45 = %.17g", ics_light_tan_deg(45));
  CHECK(rel(ics_light_tan_deg(-60), -sqrt(3.0)) <= 2 * DBL_EPSILON, "tan -60 = %.17g",
        ics_light_tan_deg(-60));
  CHECK(isnan(ics_light_tan_deg(90)) && isnan(ics_light_tan_deg(-90)) &&
            isnan(ics_light_tan_deg(135)) && isnan(ics_light_tan_deg(NAN)) &&
            isnan(ics_light_tan_deg(INFINITY)),
        "tilt at or beyond 90 degrees must be NaN");
  CHECK(!isnan(ics_light_tan_deg(nextafter(90.0, 0))), "largest angle below 90 is accepted");
  CHECK(rel(ics_light_tilt_condition(45), ICS_PI / 2) < 4e-16, "cond(45) = %.17g",
        ics_light_tilt_condition(45));
  CHECK(ics_light_tilt_condition(0) == 1 && isnan(ics_light_tilt_condition(90)), "cond ends");

  /* precision near 90: eps = 2^-k degrees, reference cot(eps pi/180) by series */
  double worst = 0, worst_naive = 0;
  printf("  90-w [deg]      cond(tan)    rel.err ics_light_tan_deg  rel.err naive tan(w*pi/180)  "
         "rel.change per 1-ulp angle step\n");
  for (int k = 6; k <= 46; k += 4) {
    double eps = ldexp(1.0, -k), w = 90.0 - eps; /* exact */
    double ref = cot_series(eps * (ICS_PI / 180.0));
    double got = ics_light_tan_deg(w), naive = tan(w * (ICS_PI / 180.0));
    double e1 = rel(got, ref), e2 = rel(naive, ref);
    double step = rel(ics_light_tan_deg(nextafter(w, 0)), got);
    printf("  %-14.6g  %-12.4g %-20.3g %-28.3g %.3g\n", eps, ics_light_tilt_condition(w), e1, e2,
           step);
    if (e1 > worst) worst = e1;
    if (e2 > worst_naive) worst_naive = e2;
    /* 1-ulp angle step: predicted relative change = cond * ulp(w) / w */
    double pred = ics_light_tilt_condition(w) * (w - nextafter(w, 0)) / w;
    /* linearisation holds while the step is small against 90 - w (k <= 38) */
    if (k <= 38)
      CHECK(rel(step, pred) < 0.01, "1-ulp step at 90 - 2^-%d: %.3g vs predicted %.3g", k, step,
          pred);
  }
  CHECK(worst <= 4 * DBL_EPSILON, "ics_light_tan_deg near 90: worst relative error %.3g", worst);
  printf("  worst: ics_light_tan_deg %.3g, naive %.3g\n", worst, worst_naive);

  ics_light L;
  double col[3] = {1, 0.5, 0.25};
  CHECK(ics_light_init_tilt(&L, 90, 0, 1, 1, 0, col, 1) == ICS_ERR_RANGE, "x-tilt 90 rejected");
  CHECK(ics_light_init_tilt(&L, 0, -91, 1, 1, 0, col, 1) == ICS_ERR_RANGE, "y-tilt -91 rejected");
  CHECK(ics_light_init_tilt(&L, NAN, 0, 1, 1, 0, col, 1) == ICS_ERR_NAN, "NaN tilt");
  CHECK(ics_light_init_tilt(&L, 0, 0, -1, 1, 0, col, 1) == ICS_ERR_NEGATIVE_VARIANCE, "neg var");
  CHECK(ics_light_init_tilt(&L, 0, 0, 1, 1, 0, col, -1) == ICS_ERR_INVALID_ARG, "neg weight");
  CHECK(ics_light_init_tilt(&L, 45, -30, 2, 0.5, 30, col, 0.7) == ICS_OK, "light");
  CHECK(rel(L.mean[0], 1.0) <= DBL_EPSILON && rel(L.mean[1], -1 / sqrt(3.0)) <= 2 * DBL_EPSILON,
        "mean (%.17g, %.17g)", L.mean[0], L.mean[1]);
  /* cov: cxx = 2 cos^2 30 + 0.5 sin^2 30 = 1.625, cxy = 1.5 cos30 sin30 = 1.5 sqrt3/4,
   * cyy = 2 sin^2 30 + 0.5 cos^2 30 = 0.875 */
  CHECK(rel(L.cov[0], 1.625) < 4e-16 && rel(L.cov[1], 1.5 * sqrt(3.0) / 4) < 4e-16 &&
            rel(L.cov[2], 0.875) < 4e-16,
        "cov %.17g %.17g %.17g", L.cov[0], L.cov[1], L.cov[2]);
  CHECK(L.color[1] == 0.5 && L.weight == 0.7, "colour and weight");
  double vx, vy, a;
  CHECK(ics_light_cov_to_eig(L.cov, &vx, &vy, &a) == ICS_OK, "to_eig");
  /* eigenvalue errors are bounded relative to the largest eigenvalue */
  CHECK(rel(vx, 2) < 4e-16 && fabs(vy - 0.5) < 4 * DBL_EPSILON * vx && rel(a, 30) < 1e-14,
        "eig back: %.17g %.17g %.17g", vx, vy, a);
  double bad[3] = {1, 2, 1}; /* eigenvalues 3, -1 */
  CHECK(ics_light_cov_to_eig(bad, &vx, &vy, &a) == ICS_ERR_INVALID_ARG, "indefinite rejected");
  double c90[3];
  CHECK(ics_light_cov_from_eig(3, 1, 90, c90) == ICS_OK && c90[0] == 1 && c90[1] == 0 &&
            c90[2] == 3,
        "alpha = 90 swaps the axes exactly");
}

static void test_mapping(void) {
  double mk, vk;
  CHECK(ics_light_kernel_map_1d(0.3, 2.0, 0.01, 4.0, &mk, &vk) == ICS_OK, "map");
  CHECK(rel(mk, -0.003) < 1e-15 && rel(vk, 0.08) < 1e-15, "mu_k %.17g var_k %.17g", mk, vk);
  /* n = d1/e steps reproduce the correct shadow's moments at d1: mean -d1 mu_l, var d1^2 var_l */
  double n = 4.0 / 0.01;
  CHECK(rel(n * mk, -4.0 * 0.3) < 1e-14 && rel(n * vk, 16.0 * 2.0) < 1e-14,
        "n steps: %.17g %.17g", n * mk, n * vk);
  CHECK(ics_light_kernel_map_1d(0.3, 2.0, 0, 4, &mk, &vk) == ICS_ERR_RANGE, "e = 0");
  CHECK(ics_light_kernel_map_1d(0.3, 2.0, 0.1, -4, &mk, &vk) == ICS_ERR_RANGE, "d1 < 0");
  CHECK(ics_light_kernel_map_1d(0.3, -2.0, 0.1, 4, &mk, &vk) == ICS_ERR_NEGATIVE_VARIANCE,
        "var < 0");
  CHECK(ics_light_kernel_map_1d(NAN, 2.0, 0.1, 4, &mk, &vk) == ICS_ERR_NAN, "NaN");
  ics_light L;
  CHECK(ics_light_init_tilt(&L, 30, 0, 1, 0.25, 45, NULL, 1) == ICS_OK, "light");
  double m2[2], c2[3];
  CHECK(ics_light_kernel_map_2d(&L, 0.05, 2.0, m2, c2) == ICS_OK, "map 2d");
  CHECK(rel(m2[0], -0.05 / sqrt(3.0)) < 4e-16 && m2[1] == 0, "mean_k (%.17g, %.17g)", m2[0],
        m2[1]);
  /* cov of (1, 0.25) at 45 degrees: cxx = cyy = 0.625, cxy = 0.375; times d1 e = 0.1 */
  CHECK(rel(c2[0], 0.0625) < 1e-15 && rel(c2[1], 0.0375) < 1e-15 && rel(c2[2], 0.0625) < 1e-15,
        "cov_k %.17g %.17g %.17g", c2[0], c2[1], c2[2]);
  {
    ics_light B = L; /* {1, 5, 1}: eigenvalues 6 and -4, not a covariance */
    B.cov[0] = 1, B.cov[1] = 5, B.cov[2] = 1;
    CHECK(ics_light_kernel_map_2d(&B, 0.05, 2.0, m2, c2) == ICS_ERR_NEGATIVE_VARIANCE,
          "non-PSD {1, 5, 1}");
    B.cov[1] = 1; /* {1, 1, 1}: singular, PSD */
    CHECK(ics_light_kernel_map_2d(&B, 0.05, 2.0, m2, c2) == ICS_OK, "singular PSD {1, 1, 1}");
  }
}

/* docs/architecture.md "Contracts": math functions never touch errno (glibc's erfc, exp set ERANGE on
 * underflow/overflow: Phi far in the tails, the pdf, Phi^-1's Halley step for subnormal p). */
static void test_errno(void) {
  const double xs[] = {0.0,  0x1p-1074, DBL_MIN, 1e-300, 0.5,     1.0 - 0x1p-53, 1.0,
                       40.0, 1e10,      1e300,   DBL_MAX, INFINITY, -INFINITY,    NAN,
                       -40.0, -1e10,    -DBL_MAX, 89.999999999, -89.999999999};
  ics_light1d *g = NULL, *mx = NULL;
  const double w[2] = {0.5, 0.5}, mu[2] = {-1, 1}, v[2] = {0.5, 2};
  CHECK(ics_light1d_create_gauss(&g, 0, 1) == ICS_OK &&
            ics_light1d_create_mix(&mx, 2, w, mu, v) == ICS_OK,
        "lights");
  for (size_t j = 0; j < sizeof xs / sizeof xs[0]; j++) {
    double x = xs[j], y[13];
    errno = 0;
    y[0] = ics_normal_cdf(x), y[1] = ics_normal_sf(x), y[2] = ics_normal_quantile(x);
    y[3] = ics_light_tan_deg(x), y[4] = ics_light_tilt_condition(x);
    y[5] = ics_light1d_pdf(g, x), y[6] = ics_light1d_cdf(g, x), y[7] = ics_light1d_sf(g, x);
    y[8] = ics_light1d_quantile(g, x), y[9] = ics_light1d_isf(g, x);
    y[10] = ics_light1d_pdf(mx, x), y[11] = ics_light1d_cdf(mx, x), y[12] = ics_light1d_sf(mx, x);
    int err = errno;
    CHECK(err == 0, "phi/phic/phiinv/tan_deg/tilt_condition/pdf/cdf/sf/quantile/isf(%a) set errno = %d (%s); phi %g",
          x, err, strerror(err), y[0]);
  }
  ics_light1d_destroy(g);
  ics_light1d_destroy(mx);
}

/* ics_light_cov_sqrt: R R = cov for PSD matrices; a nearly singular one the readers accept keeps
 * its large variance (a Cholesky factor with the pivot 1e-10 would make the y-variance 1e4) */
static void test_cov_sqrt(void) {
  const double covs[4][3] = {{0.02, 0.005, 0.01}, {1, 0, 0}, {0, 0, 0.3}, {4e-6, -1.9e-6, 1e-6}};
  double worst = 0;
  for (int k = 0; k < 4; k++) {
    double r[3];
    CHECK(ics_light_cov_sqrt(covs[k], r) == 1, "PSD %d", k);
    double sq[3] = {r[0] * r[0] + r[1] * r[1], r[0] * r[1] + r[1] * r[2], r[1] * r[1] + r[2] * r[2]};
    double tr = covs[k][0] + covs[k][2];
    for (int i = 0; i < 3; i++) worst = fmax(worst, fabs(sq[i] - covs[k][i]) / tr);
  }
  CHECK(worst < 4e-16, "R R = cov: worst relative %g", worst);
  const double near[3] = {1e-20, 1e-8, 0.01};
  double r[3];
  int psd = ics_light_cov_sqrt(near, r);
  double vy = r[1] * r[1] + r[2] * r[2], vx = r[0] * r[0] + r[1] * r[1];
  CHECK(psd == 0 && fabs(vy - 0.01) < 1e-9 && vx < 1e-12, "nearly singular: psd %d, (R R)yy %.17g, xx %g",
        psd, vy, vx);
  const double bad[3] = {NAN, 0, 1};
  CHECK(ics_light_cov_sqrt(bad, r) == -1, "NaN refused");
}

int main(void) {
  test_cov_sqrt();
  test_overflow();
  test_normal();
  test_gauss();
  test_box();
  test_mix();
  test_tab();
  test_tilt();
  test_mapping();
  test_errno();
  return test_summary("test_light");
}
