/* test_ellipse_kernel.c — ics_ellipse_kernel: status codes, degenerate lights, and the defining
 * property: averaged over a uniform rotational offset u in [0, 1) the taps have exactly the
 * target covariance R(alpha) diag(varx, vary) R(alpha)^T and zero mean. Plus, for single offsets,
 * taps on the ellipse and equal arc lengths between consecutive taps, with arc lengths from an
 * independent adaptive Gauss-Legendre quadrature of the arc-length integrand.
 *
 * The average over u: within each piece of [0, 1) between the points where some tap crosses
 * a quadrant boundary (u + j/N in {0, 1/4, 1/2, 3/4}) every tap moves smoothly, but for flat
 * ellipses it turns sharply at the tips (at a scale b^2/a in arc length; exactly a kink for
 * a segment). The periodic trapezoid rule is only O(h^2) there, so each piece is integrated by
 * tanh-sinh (double-exponential) quadrature, whose nodes crowd double-exponentially at the piece
 * ends, where the tips are. Sums are compensated. */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "icshadow.h"
#include "testutil.h"

/* documented bounds (docs/ellipse.md): relative error of the averaged covariance entries
 * (xy relative to sqrt(xx yy)), of |mean| relative to sqrt(trace), of equal arc spacing
 * relative to the perimeter / N, and of (x/a)^2 + (y/b)^2 - 1 for the taps. */
#define BOUND_COV 1e-14
#define BOUND_MEAN 1e-15
#define BOUND_ARC 1e-14
#define BOUND_ON_ELLIPSE 1e-14

#ifndef TS_LEVEL
#define TS_LEVEL 24 /* tanh-sinh nodes per unit of tau (12 is not converged at b/a ~ 0.1) */
#endif


static int cmp_double(const void *a, const void *b) {
  double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

/* Average over u in [0,1) of the N taps' first and second moments. */
typedef struct {
  double mx, my, xx, yy, xy;
} moments;

static moments average_moments(double varx, double vary, double alpha, int N) {
  /* breakpoints */
  double bp[4 * ICS_ELLIPSE_MAX_SAMPLES + 2];
  int nb = 0;
  for (int j = 0; j < N; j++)
    for (int k = 0; k < 4; k++) {
      double u = k / 4.0 - (double)j / N;
      bp[nb++] = u - floor(u);
    }
  bp[nb++] = 1.0;
  qsort(bp, nb, sizeof bp[0], cmp_double);
  ksum S[5] = {{0, 0}};
  double *xy = malloc(2 * N * sizeof *xy);
  const double h = 1.0 / TS_LEVEL; /* tanh-sinh step; |tau| <= 3.34 */
  double lo = 0.0;
  for (int p = 0; p < nb; p++) {
    double hi = bp[p];
    if (hi - lo <= 0.0) continue;
    double half = 0.5 * (hi - lo);
    for (int k = -(int)(3.34 * TS_LEVEL); k <= (int)(3.34 * TS_LEVEL); k++) {
      double tau = k * h;
      double sh = 0.5 * ICS_PI * sinh(tau);
      double ch = cosh(sh);
      double w = half * h * 0.5 * ICS_PI * cosh(tau) / (ch * ch);
      /* distance to the nearer end, computed without cancellation: 1 - tanh(|sh|) */
      double e = exp(-2.0 * fabs(sh));
      double d = half * 2.0 * e / (1.0 + e);
      double u = sh < 0 ? lo + d : hi - d;
      if (w < 1e-300) continue;
      ics_ellipse_shape shape;
      ics_status st = ics_ellipse_kernel(varx, vary, alpha, N, u, &shape, xy);
      if (st != ICS_OK) {
        CHECK(st == ICS_OK, "kernel(%g, %g, %g, %d, %g): %s", varx, vary, alpha, N, u,
              ics_status_str(st));
        free(xy);
        return (moments){NAN, NAN, NAN, NAN, NAN};
      }
      for (int j = 0; j < shape.nsamples; j++) {
        double x = xy[2 * j], y = xy[2 * j + 1];
        kadd(&S[0], w * x);
        kadd(&S[1], w * y);
        kadd(&S[2], w * x * x);
        kadd(&S[3], w * y * y);
        kadd(&S[4], w * x * y);
      }
    }
    lo = hi;
  }
  free(xy);
  moments m = {kval(&S[0]) / N, kval(&S[1]) / N, kval(&S[2]) / N, kval(&S[3]) / N,
               kval(&S[4]) / N};
  return m;
}

static double worst_cov = 0, worst_mean = 0, worst_arc = 0, worst_on = 0;
static char worst_cov_at[160];

static void test_moments(double varx, double vary, double alpha, int N) {
  moments m = average_moments(varx, vary, alpha, N);
  double c = cos(alpha * ICS_PI / 180.0), s = sin(alpha * ICS_PI / 180.0);
  double txx = varx * c * c + vary * s * s, tyy = varx * s * s + vary * c * c;
  double txy = (varx - vary) * s * c;
  double exx = fabs(m.xx - txx) / txx, eyy = fabs(m.yy - tyy) / tyy;
  double exy = fabs(m.xy - txy) / (sqrt(txx) * sqrt(tyy));
  double emean = fmax(fabs(m.mx), fabs(m.my)) / sqrt(txx + tyy);
  double e = fmax(exx, fmax(eyy, exy));
  if (e > worst_cov) {
    worst_cov = e;
    snprintf(worst_cov_at, sizeof worst_cov_at, "varx=%g vary=%g alpha=%g N=%d", varx, vary, alpha,
             N);
  }
  if (emean > worst_mean) worst_mean = emean;
  CHECK(e <= BOUND_COV,
        "kernel(%g, %g, %g deg, N=%d): averaged cov xx %.17g (target %.17g, %.2e), yy %.17g "
        "(%.17g, %.2e), xy %.17g (%.17g, %.2e)",
        varx, vary, alpha, N, m.xx, txx, exx, m.yy, tyy, eyy, m.xy, txy, exy);
  CHECK(emean <= BOUND_MEAN, "kernel(%g, %g, %g deg, N=%d): mean (%.3g, %.3g)", varx, vary, alpha,
        N, m.mx, m.my);
}

/* ---- independent arc length: adaptive Gauss-Legendre (7 points) of sqrt(a^2 s^2 + b^2 c^2) -- */
static const double GLX[7] = {-0.9491079123427585, -0.7415311855993945, -0.4058451513773972, 0.0,
                              0.4058451513773972,  0.7415311855993945,  0.9491079123427585};
static const double GLW[7] = {0.1294849661688697, 0.2797053914892766, 0.3818300505051189,
                              0.4179591836734694, 0.3818300505051189, 0.2797053914892766,
                              0.1294849661688697};
static double gl7(double a, double b, double t0, double t1) {
  double m = 0.5 * (t0 + t1), h = 0.5 * (t1 - t0), s = 0;
  for (int i = 0; i < 7; i++) {
    double th = m + h * GLX[i], sn = sin(th), cs = cos(th);
    s += GLW[i] * sqrt(a * a * sn * sn + b * b * cs * cs);
  }
  return s * h;
}
static double arc_adaptive(double a, double b, double t0, double t1, double whole, double tol,
                           int depth) {
  double tm = 0.5 * (t0 + t1);
  double l = gl7(a, b, t0, tm), r = gl7(a, b, tm, t1);
  if (depth > 60 || fabs(l + r - whole) <= tol) return l + r;
  return arc_adaptive(a, b, t0, tm, l, tol, depth + 1) + arc_adaptive(a, b, tm, t1, r, tol, depth + 1);
}
static double arc(double a, double b, double t0, double t1, double tol) {
  return arc_adaptive(a, b, t0, t1, gl7(a, b, t0, t1), tol, 0);
}

/* single offsets: taps on the ellipse, equal arc spacing (rotated back by -alpha) */
static void test_single(double varx, double vary, double alpha, int N, double offset) {
  ics_ellipse_shape sh;
  double xy[2 * 64];
  ics_status st = ics_ellipse_kernel(varx, vary, alpha, N, offset, &sh, xy);
  CHECK(st == ICS_OK, "kernel: %s", ics_status_str(st));
  if (st != ICS_OK || !(sh.a > 0 && sh.b > 0)) return;
  double c = cos(alpha * ICS_PI / 180.0), s = sin(alpha * ICS_PI / 180.0);
  double th[65];
  for (int j = 0; j < N; j++) {
    double x = xy[2 * j] * c + xy[2 * j + 1] * s, y = -xy[2 * j] * s + xy[2 * j + 1] * c;
    double on = fabs((x / sh.a) * (x / sh.a) + (y / sh.b) * (y / sh.b) - 1.0);
    if (on > worst_on) worst_on = on;
    CHECK(on <= BOUND_ON_ELLIPSE, "kernel(%g, %g, %g, N=%d, u=%g): tap %d (%.17g, %.17g) off the "
          "ellipse a=%.17g b=%.17g by %.3g", varx, vary, alpha, N, offset, j, x, y, sh.a, sh.b, on);
    th[j] = atan2(y / sh.b, x / sh.a);
  }
  /* first tap at arc fraction `offset` from the end of the MAJOR axis: (a, 0) when varx >= vary,
   * (0, b) (parameter angle pi/2) when vary > varx */
  double P = 4.0 * arc(sh.a, sh.b, 0.0, ICS_PI / 2, 1e-17 * (sh.a + sh.b));
  double th_start = varx >= vary ? 0.0 : ICS_PI / 2;
  double t0 = th[0];
  while (t0 < th_start) t0 += 2 * ICS_PI;
  double u0 = offset - floor(offset);
  double d0 = fabs(arc(sh.a, sh.b, th_start, t0, 1e-17 * P) - u0 * P) / P;
  double e0 = fmin(d0, 1.0 - d0); /* modulo the perimeter */
  CHECK(e0 <= BOUND_ARC, "kernel(%g, %g, %g, N=%d, u=%g): first tap at arc fraction %.17g",
        varx, vary, alpha, N, offset, e0);
  for (int j = 0; j < N; j++) {
    double a0 = th[j], a1 = th[(j + 1) % N];
    while (a1 <= a0) a1 += 2 * ICS_PI;
    if (N == 1) a1 = a0 + 2 * ICS_PI;
    double L = arc(sh.a, sh.b, a0, a1, 1e-17 * P);
    double e = fabs(L - P / N) / (P / N) / N; /* relative to the perimeter */
    if (e > worst_arc) worst_arc = e;
    CHECK(e <= BOUND_ARC, "kernel(%g, %g, %g, N=%d, u=%g): arc tap %d->%d = %.17g, P/N = %.17g",
          varx, vary, alpha, N, offset, j, (j + 1) % N, L, P / N);
  }
}

static void test_status(void) {
  ics_ellipse_shape sh;
  double xy[8];
  CHECK(ics_ellipse_kernel(1, 1, 0, 2, 0, NULL, xy) == ICS_ERR_INVALID_ARG, "shape NULL");
  CHECK(ics_ellipse_kernel(NAN, 1, 0, 2, 0, &sh, xy) == ICS_ERR_NAN, "varx NaN");
  CHECK(ics_ellipse_kernel(1, NAN, 0, 2, 0, &sh, xy) == ICS_ERR_NAN, "vary NaN");
  CHECK(ics_ellipse_kernel(1, 1, NAN, 2, 0, &sh, xy) == ICS_ERR_NAN, "angle NaN");
  CHECK(ics_ellipse_kernel(1, 1, 0, 2, NAN, &sh, xy) == ICS_ERR_NAN, "offset NaN");
  CHECK(ics_ellipse_kernel(-1e-300, 1, 0, 2, 0, &sh, xy) == ICS_ERR_NEGATIVE_VARIANCE, "varx < 0");
  CHECK(ics_ellipse_kernel(1, -1, 0, 2, 0, &sh, xy) == ICS_ERR_NEGATIVE_VARIANCE, "vary < 0");
  CHECK(ics_ellipse_kernel(-INFINITY, 1, 0, 2, 0, &sh, xy) == ICS_ERR_NEGATIVE_VARIANCE, "-inf");
  CHECK(ics_ellipse_kernel(INFINITY, 1, 0, 2, 0, &sh, xy) == ICS_ERR_INFINITE, "varx inf");
  CHECK(ics_ellipse_kernel(1, INFINITY, 0, 2, 0, &sh, xy) == ICS_ERR_INFINITE, "vary inf");
  CHECK(ics_ellipse_kernel(1, 1, INFINITY, 2, 0, &sh, xy) == ICS_ERR_INFINITE, "angle inf");
  CHECK(ics_ellipse_kernel(1, 1, 0, 0, 0, &sh, xy) == ICS_ERR_RANGE, "N = 0");
  CHECK(ics_ellipse_kernel(1, 1, 0, -3, 0, &sh, xy) == ICS_ERR_RANGE, "N < 0");
  CHECK(ics_ellipse_kernel(1, 1, 0, ICS_ELLIPSE_MAX_SAMPLES + 1, 0, &sh, NULL) == ICS_ERR_RANGE,
        "N too large");
  CHECK(ics_ellipse_kernel(1, 1, 0, ICS_ELLIPSE_MAX_SAMPLES, 0, &sh, NULL) == ICS_OK, "N max");
  CHECK(ics_ellipse_kernel(1, 1, 0, 2, INFINITY, &sh, xy) == ICS_ERR_RANGE, "offset inf");
  CHECK(ics_ellipse_kernel(1, 1, 0, 2, -2.75, &sh, xy) == ICS_OK, "offset negative is reduced");
}

static void test_degenerate(void) {
  ics_ellipse_shape sh;
  double xy[2 * 8];
  /* point light */
  memset(xy, 0x7f, sizeof xy);
  CHECK(ics_ellipse_kernel(0, 0, 33, 8, 0.3, &sh, xy) == ICS_OK, "point light");
  CHECK(sh.nsamples == 1 && sh.a == 0 && sh.b == 0 && xy[0] == 0 && xy[1] == 0,
        "point light: nsamples %d a %g b %g tap (%g, %g)", sh.nsamples, sh.a, sh.b, xy[0], xy[1]);
  /* line light along x: t = 0, a = sqrt(3 varx), taps on the segment */
  CHECK(ics_ellipse_kernel(2.0, 0, 0, 8, 0.1, &sh, xy) == ICS_OK, "line light");
  CHECK(sh.t == 0 && sh.b == 0 && fabs(sh.a / sqrt(6.0) - 1) < 1e-15 && sh.nsamples == 8,
        "line light: t %g a %.17g b %g", sh.t, sh.a, sh.b);
  for (int j = 0; j < 8; j++)
    CHECK(xy[2 * j + 1] == 0 && fabs(xy[2 * j]) <= sh.a, "line tap %d (%g, %g)", j, xy[2 * j],
          xy[2 * j + 1]);
  /* the line taps at u: x = a (1 - 4u) for u <= 1/2, on the way back x = a (4u - 3) */
  for (int j = 0; j < 8; j++) {
    double u = 0.1 + j / 8.0, x = u <= 0.5 ? sh.a * (1 - 4 * u) : sh.a * (4 * u - 3);
    CHECK(fabs(xy[2 * j] - x) <= 1e-15 * sh.a, "line tap %d x %.17g expected %.17g", j, xy[2 * j],
          x);
  }
  /* line light along y (varx = 0): t = 1, a = 0, b = sqrt(3 vary) */
  CHECK(ics_ellipse_kernel(0, 5.0, 0, 3, 0, &sh, xy) == ICS_OK, "vertical line light");
  CHECK(sh.t == 1 && sh.a == 0 && fabs(sh.b / sqrt(15.0) - 1) < 1e-15, "vertical line: t %g a %g "
        "b %.17g", sh.t, sh.a, sh.b);
  for (int j = 0; j < 3; j++) CHECK(xy[2 * j] == 0, "vertical line tap %d x = %g", j, xy[2 * j]);
  /* offset 0 is the end of the MAJOR axis: the 2-tap kernel of a line light has its taps at the
   * segment's ends for both orientations. A uniform density on [-c, c] has variance c^2/3, so
   * var 1 gives c = sqrt(3) and varx = 3 gives c = 3 (values derived by hand, not from the code) */
  CHECK(ics_ellipse_kernel(0, 1.0, 0, 2, 0, &sh, xy) == ICS_OK, "vertical line, 2 taps");
  CHECK(xy[0] == 0 && fabs(xy[1] / sqrt(3.0) - 1) <= 0x1p-52 && xy[2] == 0 &&
            fabs(xy[3] / -sqrt(3.0) - 1) <= 0x1p-52,
        "vertical line (varx 0, vary 1) at offset 0: taps (%.17g, %.17g), (%.17g, %.17g), "
        "expected (0, +-sqrt 3)", xy[0], xy[1], xy[2], xy[3]);
  CHECK(ics_ellipse_kernel(3.0, 0, 0, 2, 0, &sh, xy) == ICS_OK, "horizontal line, 2 taps");
  CHECK(fabs(xy[0] / 3.0 - 1) <= 0x1p-52 && xy[1] == 0 && fabs(xy[2] / -3.0 - 1) <= 0x1p-52 &&
            xy[3] == 0,
        "horizontal line (varx 3, vary 0) at offset 0: taps (%.17g, %.17g), (%.17g, %.17g), "
        "expected (+-3, 0)", xy[0], xy[1], xy[2], xy[3]);
  /* the vertical line's taps at u: y = b (1 - 4u) for u <= 1/2, on the way back y = b (4u - 3) */
  CHECK(ics_ellipse_kernel(0, 2.0, 0, 8, 0.1, &sh, xy) == ICS_OK, "vertical line, 8 taps");
  for (int j = 0; j < 8; j++) {
    double u = 0.1 + j / 8.0, y = u <= 0.5 ? sh.b * (1 - 4 * u) : sh.b * (4 * u - 3);
    CHECK(xy[2 * j] == 0 && fabs(xy[2 * j + 1] - y) <= 1e-15 * sh.b,
          "vertical line tap %d (%.17g, %.17g) expected (0, %.17g)", j, xy[2 * j], xy[2 * j + 1], y);
  }
  /* -0 variances: no negative zero radii, t or taps */
  CHECK(ics_ellipse_kernel(-0.0, 1.0, 0, 2, 0, &sh, xy) == ICS_OK && !signbit(sh.a) &&
            !signbit(xy[0]) && !signbit(xy[2]),
        "kernel(-0, 1): a %g taps x %g %g", sh.a, xy[0], xy[2]);
  CHECK(ics_ellipse_kernel(1.0, -0.0, 0, 2, 0, &sh, xy) == ICS_OK && !signbit(sh.b) &&
            !signbit(sh.t) && !signbit(xy[1]) && !signbit(xy[3]),
        "kernel(1, -0): b %g t %g taps y %g %g", sh.b, sh.t, xy[1], xy[3]);
  /* swapping the variances is a quarter turn: kernel(vy, vx, 0) = kernel(vx, vy, 90) exactly,
   * for every offset (both start at the major axis' end) */
  for (int c = 0; c < 3; c++) {
    const double vv[3][2] = {{1.0, 0.3}, {2.0, 0.0}, {1.0, 1e-9}};
    const double offs[3] = {0.0, 0.2, 0.77};
    double xa[2 * 5], xb[2 * 5];
    ics_ellipse_shape sa, sb;
    ics_ellipse_kernel(vv[c][1], vv[c][0], 0, 5, offs[c], &sa, xa);
    ics_ellipse_kernel(vv[c][0], vv[c][1], 90, 5, offs[c], &sb, xb);
    for (int j = 0; j < 10; j++)
      CHECK(xa[j] == xb[j], "kernel(%g, %g, 0) vs kernel(%g, %g, 90), u = %g: coordinate %d "
            "%.17g vs %.17g", vv[c][1], vv[c][0], vv[c][0], vv[c][1], offs[c], j, xa[j], xb[j]);
  }
  /* rotated by 90 degrees: exactly the swapped kernel */
  double xy2[2 * 8];
  ics_ellipse_shape sh2;
  ics_ellipse_kernel(1.0, 0.3, 0, 4, 0.2, &sh, xy);
  ics_ellipse_kernel(1.0, 0.3, 90, 4, 0.2, &sh2, xy2);
  for (int j = 0; j < 4; j++)
    CHECK(xy2[2 * j] == -xy[2 * j + 1] && xy2[2 * j + 1] == xy[2 * j], "90 deg rotation tap %d", j);
  /* circle: a = b = sqrt(2 var), t = 1/2 */
  CHECK(ics_ellipse_kernel(0.7, 0.7, 10, 2, 0, &sh, xy) == ICS_OK, "circle");
  CHECK(sh.t == 0.5 && fabs(sh.a / sqrt(1.4) - 1) < 2e-16 && sh.a == sh.b, "circle: t %.17g a %.17g "
        "b %.17g", sh.t, sh.a, sh.b);
  /* the radii follow Patel's a = (1 - t) sqrt(sc), b = t sqrt(sc): b/a = t/(1 - t) */
  CHECK(ics_ellipse_kernel(1.0, 0.2, 0, 2, 0, &sh, NULL) == ICS_OK, "shape only");
  CHECK(fabs(sh.b / sh.a - sh.t / (1 - sh.t)) < 4e-16 * sh.b / sh.a, "b/a %.17g vs t/(1-t) %.17g",
        sh.b / sh.a, sh.t / (1 - sh.t));
  /* extreme scales: variances near the overflow and underflow thresholds */
  CHECK(ics_ellipse_kernel(DBL_MAX, DBL_MAX / 4, 0, 2, 0, &sh, xy) == ICS_OK && isfinite(sh.a) &&
            isfinite(xy[0]),
        "DBL_MAX variance: a %g", sh.a);
  CHECK(ics_ellipse_kernel(1e300, 1e-300, 0, 2, 0.125, &sh, xy) == ICS_OK && sh.b > 0 &&
            fabs(sh.b / sqrt(1.5e-300) - 1) < 1e-14,
        "ratio 1e-600: b %.17g vs sqrt(3/2 vary) %.17g", sh.b, sqrt(1.5e-300));
}

/* random extreme inputs (variances 1e-321 .. 1e308, zeros, any angle, offsets outside [0, 1)):
 * status OK, finite taps inside the ellipse's bounding circle, and radii whose unit ellipse has
 * the target variance ratio minor/major */
static void test_random(void) {
  unsigned long long st = 0x2545F4914F6CDD1Dull;
  double xy[2 * 16];
  for (int i = 0; i < 3000; i++) {
    st ^= st << 13, st ^= st >> 7, st ^= st << 17;
    double u1 = (double)(st >> 11) * 0x1p-53;
    st ^= st << 13, st ^= st >> 7, st ^= st << 17;
    double u2 = (double)(st >> 11) * 0x1p-53;
    double vx = exp(-740 + 1450 * u1), vy = exp(-740 + 1450 * u2);
    if (i % 7 == 0) vy = 0;
    if (i % 11 == 0) vx = 0;
    int N = 1 + i % 16;
    double alpha = 720 * u1 - 360, off = 3 * u2 - 1;
    ics_ellipse_shape sh;
    ics_status r = ics_ellipse_kernel(vx, vy, alpha, N, off, &sh, xy);
    CHECK(r == ICS_OK, "kernel(%g, %g, %g, %d, %g): %s", vx, vy, alpha, N, off, ics_status_str(r));
    if (r != ICS_OK) continue;
    double R = fmax(sh.a, sh.b);
    for (int j = 0; j < sh.nsamples; j++) {
      double d = hypot(xy[2 * j], xy[2 * j + 1]);
      CHECK(isfinite(d) && d <= R * (1 + 1e-15), "kernel(%g, %g, %g, %d, %g): tap %d at %g, R %g",
            vx, vy, alpha, N, off, j, d, R);
    }
    double mn = fmin(vx, vy), mx = fmax(vx, vy);
    if (mn > 0 && mn / mx >= 1e-250) {
      /* the unit ellipse (minor/(a+b) = s) reproduces the variance ratio minor/major */
      double s = fmin(sh.a, sh.b) / (sh.a + sh.b), rat = ics_ellipse_ratio(s), want = mn / mx;
      CHECK(fabs(rat / want - 1) <= 1e-14, "kernel(%g, %g): ratio(s = %.17g) = %.17g vs %.17g", vx,
            vy, s, rat, want);
    }
  }
}

int main(void) {
  test_random();
  test_status();
  test_degenerate();
  const double cfg[][3] = {
      {1.0, 0.25, 0.0},    {1.0, 0.25, 30.0},   {0.8, 3.2, 70.0},    {0.3, 1.7, -15.0},
      {1.0, 1.0, 10.0},    {1.0, 1e-2, 0.0},    {1.0, 1e-4, 45.0},   {2.0, 2e-12, 30.0},
      {2.0, 2e-12, 0.0},   {1e-12, 1.0, 0.0},   {1e-12, 1.0, 60.0},  {1.0, 0.0, 20.0},
      {0.0, 1.0, 0.0},     {1e200, 3e199, 5.0}, {1e-200, 5e-201, 95.0},
  };
  const int Ns[] = {2, 3, 8};
  for (size_t c = 0; c < sizeof cfg / sizeof cfg[0]; c++)
    for (size_t n = 0; n < sizeof Ns / sizeof Ns[0]; n++)
      test_moments(cfg[c][0], cfg[c][1], cfg[c][2], Ns[n]);
  for (size_t c = 0; c < sizeof cfg / sizeof cfg[0]; c++) {
    /* rotating back multiplies the minor coordinate's error by a/b: single-offset geometry is
     * checked unrotated for the flat ellipses */
    double alpha = (cfg[c][1] / cfg[c][0] < 1e-3 || cfg[c][0] / cfg[c][1] < 1e-3) ? 0.0 : cfg[c][2];
    for (size_t n = 0; n < sizeof Ns / sizeof Ns[0]; n++) {
      test_single(cfg[c][0], cfg[c][1], alpha, Ns[n], 0.0);
      test_single(cfg[c][0], cfg[c][1], alpha, Ns[n], 0.37);
      test_single(cfg[c][0], cfg[c][1], alpha, Ns[n], 0.249999);
    }
  }
  test_single(1.0, 0.1, 0.0, 1, 0.61);
  test_single(1.0, 0.1, 0.0, 64, 0.61);
  printf("averaged covariance: max rel error %.3g (%s)\n", worst_cov, worst_cov_at);
  printf("mean: max %.3g; arc spacing: max rel %.3g; on ellipse: max %.3g\n", worst_mean,
         worst_arc, worst_on);
  return test_summary("test_ellipse_kernel");
}
