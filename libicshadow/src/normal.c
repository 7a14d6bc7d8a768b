/* normal.c — the normal distribution (icshadow/normal.h).
 *
 * Method and accuracy:
 * - Phi, Phi^c: 0.5 erfc(-z/sqrt2), 0.5 erfc(z/sqrt2) (libm erfc; relative error ~1e-15 in both
 *   tails). Phi^-1: Acklam's rational approximation (rel. error 1.15e-9) refined by one Halley
 *   step on erfc, giving ~1e-15 relative; subnormal p by Newton on the asymptotic series of
 *   log Phi (phiinv_subnormal). tests/test_light.c checks the three, errno included.
 * - Bivariate normal cdf (ics_normal_bvn_cdf): Plackett's identity dPhi2/dr = phi2(a, b; r)
 *   with r = sin(t): Phi2(a, b; r) = Phi(a) Phi(b) + (1/2pi) int_0^asin(r) f(t) dt for
 *   |r| < 0.925, and Phi(min(a, b)) - (1/2pi) int_asin(r)^(pi/2) f(t) dt for r >= 0.925
 *   (r <= -0.925: Phi(a) - Phi2(a, -b; -r)), f(t) = exp(-(a - b)^2 / (2 cos^2 t) - a b /
 *   (1 + sin t)) (the same exponent (a^2 + b^2 - 2 a b sin t) / (2 cos^2 t) written without
 *   cancellation near t = pi/2). Integrated by adaptive 20-point Gauss-Legendre (node table
 *   from mpmath, 20 digits), panel split until two halves agree with the whole to 1e-15.
 *   tests/test_clt_convergence.c checks it against the closed form
 *   Phi2(0, 0; r) = 1/4 + asin(r)/(2 pi), against Phi(a) Phi(b) at r = 0 and against an
 *   independent adaptive Simpson quadrature of phi(x) Phi((b - r x)/sqrt(1 - r^2)) (max
 *   difference asserted 1e-12). */
#include "icshadow/normal.h"

#include <float.h>
#include <math.h>

#include "icshadow/constants.h"
#include "noerrno.h"

double ics_normal_cdf(double z) {
  if (isnan(z)) return NAN;
  return 0.5 * ics_erfc_noerrno(-z * 0.70710678118654752440);
}

double ics_normal_sf(double z) {
  if (isnan(z)) return NAN;
  return 0.5 * ics_erfc_noerrno(z * 0.70710678118654752440);
}

/* Phi^-1 for subnormal p (x < -37.5), where Phi(x) itself is subnormal (the Halley residual keeps
 * too few bits) and exp(x^2/2) overflows: Newton on log Phi(x) = log p with the asymptotic series
 *   log Phi(x) = -x^2/2 - log(-x) - log(2 pi)/2 + log1p(S),  S = sum_{k=1..8} (-1)^k (2k-1)!! / x^{2k}
 * (truncation < 2e-19 relative for x^2 > 1369), d/dx log Phi = -x / (1 + S). Start: Acklam's tail
 * approximation (relative error ~1e-9), so two or three steps reach rounding. */
static double phiinv_subnormal(double p) {
  double lp = log(p); /* finite: p >= 2^-1074 */
  double q = sqrt(-2 * lp);
  double x = -(((((-7.784894002430293e-03 * q - 3.223964580411365e-01) * q - 2.400758277161838e+00) * q -
                 2.549732539343734e+00) * q + 4.374664141464968e+00) * q + 2.938163982698783e+00) /
             ((((7.784695709041462e-03 * q + 3.224671290700398e-01) * q + 2.445134137142996e+00) * q +
               3.754408661907416e+00) * q + 1);
  x = -fabs(x);
  for (int it = 0; it < 6; it++) {
    double r = 1 / (x * x), term = 1, s = 0;
    for (int k = 1; k <= 8; k++) {
      term *= -(2 * k - 1) * r;
      s += term;
    }
    double g = (-0.5 * x * x - lp) - log(-x) - 0.91893853320467274178 + log1p(s);
    double step = g * (1 + s) / (-x);
    x -= step;
    if (fabs(step) <= 1e-16 * fabs(x)) break;
  }
  return x;
}

double ics_normal_quantile(double p) {
  if (isnan(p) || p < 0 || p > 1) return NAN;
  if (p == 0) return -INFINITY;
  if (p == 1) return INFINITY;
  static const double a[] = {-3.969683028665376e+01, 2.209460984245205e+02,
                             -2.759285104469687e+02, 1.383577518672690e+02,
                             -3.066479806614716e+01, 2.506628277459239e+00};
  static const double b[] = {-5.447609879822406e+01, 1.615858368580409e+02,
                             -1.556989798598866e+02, 6.680131188771972e+01,
                             -1.328068155288572e+01};
  static const double c[] = {-7.784894002430293e-03, -3.223964580411365e-01,
                             -2.400758277161838e+00, -2.549732539343734e+00,
                             4.374664141464968e+00,  2.938163982698783e+00};
  static const double d[] = {7.784695709041462e-03, 3.224671290700398e-01,
                             2.445134137142996e+00, 3.754408661907416e+00};
  double q, x;
  double pl = p < 0.5 ? p : 1.0 - p; /* tail mass on the near side (exact for p >= 0.5 near 1) */
  if (p < DBL_MIN) return phiinv_subnormal(p);
  if (pl < 0.02425) {
    q = sqrt(-2 * log(pl));
    x = (((((c[0] * q + c[1]) * q + c[2]) * q + c[3]) * q + c[4]) * q + c[5]) /
        ((((d[0] * q + d[1]) * q + d[2]) * q + d[3]) * q + 1);
    if (p >= 0.5) x = -x;
  } else {
    q = p - 0.5;
    double r = q * q;
    x = (((((a[0] * r + a[1]) * r + a[2]) * r + a[3]) * r + a[4]) * r + a[5]) * q /
        (((((b[0] * r + b[1]) * r + b[2]) * r + b[3]) * r + b[4]) * r + 1);
  }
  /* one Halley step; the residual is taken in the tail nearest to x to avoid cancellation */
  double e, u;
  if (x < 0) {
    e = ics_normal_cdf(x) - p;
  } else {
    e = -(ics_normal_sf(x) - (1.0 - p)); /* 1 - p exact for p >= 0.5 */
  }
  u = e * 2.50662827463100050242 * ics_exp_noerrno(0.5 * x * x);
  x = x - u / (1 + 0.5 * x * u);
  return x;
}

/* 20-point Gauss-Legendre on [-1, 1]: the positive nodes and their weights (mpmath, 40 digits,
 * Newton on P_20; the weights sum to 2 to 1e-17) */
static const double GL20[10][2] = {
    {0.076526521133497333755, 0.1527533871307258507},
    {0.22778585114164507808, 0.14917298647260374679},
    {0.37370608871541956067, 0.14209610931838205133},
    {0.510867001950827098, 0.1316886384491766269},
    {0.63605368072651502545, 0.11819453196151841731},
    {0.74633190646015079261, 0.10193011981724043504},
    {0.83911697182221882339, 0.083276741576704748725},
    {0.91223442825132590587, 0.06267204833410906357},
    {0.96397192727791379127, 0.040601429800386941331},
    {0.99312859918509492479, 0.017614007139152118312},
};

static double plackett_f(double a, double b, double t) {
  double s = sin(t), c = cos(t);
  double d = a - b;
  double e = (c > 0 ? d * d / (2 * c * c) : (d == 0 ? 0 : INFINITY)) + a * b / (1 + s);
  return exp(-e);
}

static double gl20(double a, double b, double t0, double t1) {
  double m = 0.5 * (t0 + t1), h = 0.5 * (t1 - t0), s = 0;
  for (int i = 0; i < 10; i++)
    s += GL20[i][1] * (plackett_f(a, b, m - h * GL20[i][0]) + plackett_f(a, b, m + h * GL20[i][0]));
  return s * h;
}

static double gl_adapt(double a, double b, double t0, double t1, double whole, int depth) {
  double m = 0.5 * (t0 + t1);
  double l = gl20(a, b, t0, m), r = gl20(a, b, m, t1);
  if (depth >= 40 || fabs(l + r - whole) <= 1e-15) return l + r;
  return gl_adapt(a, b, t0, m, l, depth + 1) + gl_adapt(a, b, m, t1, r, depth + 1);
}

static double plackett_int(double a, double b, double t0, double t1) {
  if (t0 == t1) return 0;
  return gl_adapt(a, b, t0, t1, gl20(a, b, t0, t1), 0);
}

double ics_normal_bvn_cdf(double a, double b, double r) {
  if (isnan(a) || isnan(b) || isnan(r) || r < -1 || r > 1) return NAN;
  if (a == -INFINITY || b == -INFINITY) return 0;
  if (a == INFINITY) return ics_normal_cdf(b);
  if (b == INFINITY) return ics_normal_cdf(a);
  if (r <= -0.925) { /* P(X < a, Y < b) = P(X < a) - P(X < a, -Y < -b) */
    double v = ics_normal_cdf(a) - ics_normal_bvn_cdf(a, -b, -r);
    return v < 0 ? 0 : v;
  }
  if (r < 0.925) {
    double v = ics_normal_cdf(a) * ics_normal_cdf(b) + plackett_int(a, b, 0, asin(r)) / (2 * ICS_PI);
    return v < 0 ? 0 : (v > 1 ? 1 : v);
  }
  double v = ics_normal_cdf(fmin(a, b)) - plackett_int(a, b, asin(r), ICS_PI / 2) / (2 * ICS_PI);
  return v < 0 ? 0 : (v > 1 ? 1 : v);
}
