/* ellipse.c — variances of points uniform in arc length on an ellipse, and the N-sample
 * elliptical kernel (Patel et al. 2013, Sec. 3.4 and Appendix A.7). See docs/ellipse.md.
 *
 * CONVENTION (settled, see docs/ellipse.md): in Patel's Appendix A.7
 *   var_x(b) = (2b^2 - 1 - b^2 K(.)/E(.)) / (3b^2 - 3),  argument sqrt(1 - b^2),
 * sqrt(1 - b^2) is the MODULUS k, i.e. the parameter is m = k^2 = 1 - b^2 (complementary
 * parameter m1 = b^2). Direct quadrature of the arc-length density agrees to the last digit with
 * that reading and disagrees already in the 3rd digit with m = sqrt(1 - b^2); for b > 1 the same
 * formula holds with the negative parameter m = 1 - b^2 (tests/test_ellipse.c checks all three).
 *
 * METHOD. For an ellipse with major radius A and minor radius beta A (0 <= beta <= 1), parameter
 * m = 1 - beta^2, write K = B + D and E = B + beta^2 D with the (cancellation-free, positive)
 *   B(m) = int_0^{pi/2} cos^2 / Delta,  D(m) = int_0^{pi/2} sin^2 / Delta,  Delta = sqrt(1-m sin^2).
 * Then, with rho = beta^2 D / B in [0, 1] (rho = 0 for a segment, 1 for a circle),
 *   variance along the major axis  = A^2     (1 + 2 rho) / (3 (1 + rho)) = A^2     (1/3 + w),
 *   variance along the minor axis  = (beta A)^2 (2 + rho) / (3 (1 + rho)) = (beta A)^2 (2/3 - w),
 *   w = rho / (3 (1 + rho)) in [0, 1/6].
 * This is Patel's formula rearranged: no 0/0 at b = 1, no cancellation as b -> 1, and b > 1 is
 * the same function with the axes swapped (var_x(b) = 2/3 - w(1/b) for b > 1, so var_x -> 2/3 as
 * b -> inf, not 0: the x-radius stays 1 while the ellipse becomes a segment along y).
 * rho needs no K at all: with S = D/K = 1/2 + p and T = B/K = 1/2 - p,
 *   p = sum_{n>=1} 2^(n-1) r_n,  r_n = c_n^2 / (1 - beta^2)   (Gauss AGM: a_0 = 1, b_0 = beta,
 *   c_1 = (1 - beta)/2, c_{n+1} = c_n^2 / (4 a_{n+1}), so r_1 = (1-beta)/(4(1+beta)) and
 *   r_{n+1} = r_n (c_n / (4 a_{n+1}))^2: products only, all terms positive, no 1 - beta^2 formed,
 *   exact at beta = 1 where r_1 = 0). With X, Y the squared major and minor radii (double-double,
 *   never rounding beta = sqrt(Y/X)):  w = Y S / (3 (X T + Y S)), every term positive.
 *   T = 1/2 - p is exact while p <= 1/4; beyond (beta small) T = (1 + 3 beta)/(4 (1 + beta)) -
 *   sum_{n>=2} cancels by ~log2 K bits, but there rho ~ beta^2 K is small and the results'
 *   sensitivity to rho is at most 1/3, so the loss does not show (measured, below).
 *   V_x(t): unit ellipse a = 1 - t, b = t. For t <= 1/2 the x axis is the major one (beta =
 *   t/(1-t), X = (1-t)^2, Y = t^2), for t > 1/2 the minor one (beta = (1-t)/t, 1 - t exact).
 *   V_y is the same with the roles swapped, so V_y(t) = t^2 (2/3 - w) for small t is accurate
 *   down to t ~ 1e-154 (below, the square is taken on the mantissa and the exponent applied last)
 *   and never forms 1 - t on the small side. (1 - t)^2, t^2, w, 1/3 + w and 2/3 - w are kept in
 *   double-double; each result is rounded once at the end.
 *   ratio(t) = Y (2/3 - w) / (X (1/3 + w)) (for t > 1/2 with the roles swapped: ratio(1 - t) =
 *   1/ratio(t) holds by construction).
 *   ratio_to_t(r): r < 1 solves beta^2 g(beta) = r, g = (2/3 - w)/(1/3 + w) in [1, 2], by secant
 *   iteration on the residual of the contraction beta = sqrt(r / g(beta)), one polishing step and
 *   a double-double Newton correction of the square root; t = beta/(1 + beta) in double-double.
 *   r > 1 solves the mirrored problem for beta' = (1 - t)/t with 1/r: t = 1/(1 + beta').
 *   r < 2^-600: t = sqrt(r/2) (rho < 2^-590 is negligible), by exact power-of-2 scaling so that
 *   subnormal r keep all their bits; r > 2^600: t = 1 (1 - t < 2^-300).
 * SWITCH POINTS: b = 1 (var_x: x axis major below, minor above), t = 1/2 (V_x, V_y, ratio),
 *   p = 1/4 (T formula, beta ~ 0.24), r = 1 and r = 2^-600 / 2^600 (ratio_to_t); t = 2^-480 (the
 *   scaled square). Both sides of each are tested.
 * ACCURACY (max error against Patel's closed form in MPFR at 320 bits, tests/test_ellipse.c,
 *   which asserts these same numbers; worst inputs in docs/ellipse.md; "worst found" is the worst
 *   found so far by random runs and probes, not a proof):
 *   ics_ellipse_varx        <= 0.75 ulp    (worst found 0.6272)
 *   ics_ellipse_vx          <= 0.75 ulp    (worst found 0.652)
 *   ics_ellipse_vy          <= 0.75 ulp    (worst found 0.656)
 *   ics_ellipse_ratio       <= 1.0 ulp     (worst found 0.7695)
 *   ics_ellipse_ratio_to_t  <= 1.0 ulp     (worst found 0.737)
 *   vy and ratio with a subnormal result: <= 1.0 ulp of 2^-1074 (worst found 0.74997; the
 *   exponent is applied last, so such results are rounded twice).
 *
 * KERNEL: t, scale and radii as in Patel Sec. 3.4, but always computed from the MAJOR variance
 * (s = ratio_to_t(minor/major) <= 1/2, sc = major / V_x(s)), so the minor radius keeps full
 * relative accuracy for any ratio (Patel's a = (1 - t) sqrt(sc) loses it when vary > varx).
 * Taps at equal arc-length fractions, offset 0 at the end of the MAJOR axis ((a, 0) if varx >= vary,
 * else (0, b)), counter-clockwise: the arc within a quadrant, measured from the major-axis end,
 * is an incomplete elliptic integral of the second kind in Carlson form with both terms positive
 * (arc_from_major), inverted by Newton from an upper bound (monotone: the arc is convex in the
 * angle) with a bisection guard. Measured (tests/test_ellipse_kernel.c): taps on the ellipse to
 * 6.7e-16, arc spacing equal to 3.7e-16 of the perimeter, covariance averaged over the offset
 * exact to 8.9e-16 relative for ratios 1e+-12, lines and vary > varx. */
#include "icshadow/ellipse.h"
#include "icshadow/constants.h"

#include <float.h>
#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include "dd.h"
#include "degtrig.h"

/* 1/3 and 2/3 as double-double */
static const double THIRD_HI = 0x1.5555555555555p-2, THIRD_LO = 0x1.5555555555555p-56;
static const double TWO3_HI = 0x1.5555555555555p-1, TWO3_LO = 0x1.5555555555555p-55;

/* ---- the core: w = rho / (3 (1 + rho)), rho = beta^2 D/B ------------------------------------
 * beta in [0, 1] is minor/major radius; dm = 1 - beta and sp = 1 + beta are passed in (callers
 * form them more accurately than from the rounded beta). X and Y are the squared major and
 * minor radii (any common scale, double-double), so that Y/X = beta^2 without rounding beta:
 *   w = Y S / (3 (X T + Y S)),  S = D/K = 1/2 + p,  T = B/K = 1/2 - p,
 * every term positive. p = sum_{n>=1} 2^(n-1) r_n from the AGM (see the file header). */
static ics_dd ellipse_w(double beta, double dm, double sp, ics_dd X, ics_dd Y) {
  if (beta == 0.0 || Y.hi == 0.0) return (ics_dd){0.0, 0.0};
  double r1 = dm / (4.0 * sp); /* r_1 = c_1^2 / (1 - beta^2), c_1 = (1 - beta)/2 */
  double sum = 0.0;            /* sum_{n>=2} 2^(n-1) r_n */
  if (dm != 0.0) {
    double a = 0.5 * sp;  /* a_1 */
    double b = sqrt(beta); /* b_1 = sqrt(a_0 b_0) */
    double c = 0.5 * dm;  /* c_1 */
    double r = r1, pw = 1.0;
    for (int n = 1; n < 64; n++) {
      double an = 0.5 * (a + b); /* a_{n+1} */
      double q = c / (4.0 * an);
      double cn = c * q; /* c_{n+1} = c_n^2 / (4 a_{n+1}) */
      r = r * q * q;     /* r_{n+1} = r_n (c_n / (4 a_{n+1}))^2 */
      pw *= 2.0;
      double term = pw * r;
      sum += term;
      if (term <= 0x1p-70 * sum || term == 0.0) break;
      b = sqrt(a * b);
      a = an;
      c = cn;
    }
  }
  double p = r1 + sum;
  ics_dd S = ics_dd_two_sum(0.5, p);
  ics_dd T;
  if (p <= 0.25) {
    T = ics_dd_two_sum(0.5, -p);
  } else { /* beta small: T = 1/2 - r_1 - sum = (1 + 3 beta)/(4 (1 + beta)) - sum, rho small */
    ics_dd num = {3.0 * beta, fma(3.0, beta, -3.0 * beta)};
    num = ics_dd_add((ics_dd){1.0, 0.0}, num);
    T = ics_dd_add(ics_dd_div_dd(num, (ics_dd){4.0 * sp, 0.0}), (ics_dd){-sum, 0.0});
  }
  ics_dd ys = ics_dd_mul(Y, S);
  ics_dd den = ics_dd_add(ics_dd_mul(X, T), ys);
  double h3 = 3.0 * den.hi; /* times 3 in double-double (3 den.hi is not exact) */
  den = ics_dd_two_sum(h3, fma(3.0, den.hi, -h3) + 3.0 * den.lo);
  return ics_dd_div_dd(ys, den);
}

/* 1/3 + w and 2/3 - w in double-double */
static ics_dd third_plus(ics_dd w) { return ics_dd_add((ics_dd){THIRD_HI, THIRD_LO}, w); }
static ics_dd two3_minus(ics_dd w) { return ics_dd_add((ics_dd){TWO3_HI, TWO3_LO}, (ics_dd){-w.hi, -w.lo}); }

/* (1 - t)^2 exactly enough as double-double, t in [0, 1] */
static ics_dd one_minus_sq(double t) {
  double h = 1.0 - t;
  double l = (1.0 - h) - t; /* exact: 1 - t = h + l */
  ics_dd s = ics_dd_sqr(h);
  s.lo += 2.0 * h * l;
  return ics_dd_two_sum(s.hi, s.lo);
}

/* Parameters of the unit ellipse (1 - t, t), t in [0, 1/2]: beta = t / (1 - t). */
static ics_dd unit_w_small(double t) {
  double om = 1.0 - t;
  return ellipse_w(t / om, (1.0 - 2.0 * t) / om, 1.0 / om, one_minus_sq(t), ics_dd_sqr(t));
}
/* t in [1/2, 1]: beta = (1 - t)/t, 1 - t exact. */
static ics_dd unit_w_large(double t) {
  double u = 1.0 - t;
  return ellipse_w(u / t, (2.0 * t - 1.0) / t, 1.0 / t, ics_dd_sqr(t), ics_dd_sqr(u));
}

double ics_ellipse_varx(double b) {
  if (isnan(b) || b < 0.0) return NAN;
  if (b == 0.0) return THIRD_HI;
  if (isinf(b)) return TWO3_HI;
  if (b <= 1.0) {
    ics_dd one = {1.0, 0.0};
    ics_dd w = ellipse_w(b, 1.0 - b, 1.0 + b, one, ics_dd_sqr(b));
    ics_dd v = third_plus(w);
    return v.hi + v.lo;
  }
  ics_dd one = {1.0, 0.0};
  double bi = 1.0 / b;
  ics_dd w = b < 0x1p500 ? ellipse_w(bi, (b - 1.0) / b, (b + 1.0) / b, ics_dd_sqr(b), one)
                         : ellipse_w(bi, 1.0 - bi, 1.0 + bi, one, ics_dd_sqr(bi));
  ics_dd v = two3_minus(w);
  return v.hi + v.lo;
}

double ics_ellipse_vx(double t) {
  if (isnan(t) || t < 0.0 || t > 1.0) return NAN;
  if (t == 1.0) return 0.0;
  if (t <= 0.5) {
    ics_dd v = ics_dd_mul(one_minus_sq(t), third_plus(unit_w_small(t)));
    return v.hi + v.lo;
  }
  double u = 1.0 - t;
  ics_dd v = ics_dd_mul(ics_dd_sqr(u), two3_minus(unit_w_large(t)));
  return v.hi + v.lo;
}

/* 2^k for -1022 <= k <= 1023, built from its bits (no libm call, so no errno) */
static double pow2i(int k) {
  uint64_t u = (uint64_t)(k + 1023) << 52;
  double d;
  memcpy(&d, &u, sizeof d);
  return d;
}

/* t^2 * f for f in double-double, f in [1/2, 2]. Below t = 2^-480 the square is formed on the
 * mantissa of t and the exponent applied last, so every normal result is rounded once (subnormal
 * results twice: <= 1 ulp of 2^-1074). The exponent is applied by two multiplications, the first
 * exact (x 2^-600 is normal), the second rounding once: the same result as ldexp(x, 2e), which
 * would set errno = ERANGE on underflow (the math functions never touch errno). */
static double sq_times(double t, ics_dd f) {
  if (t >= 0x1p-480) {
    ics_dd v = ics_dd_mul(ics_dd_sqr(t), f);
    return v.hi + v.lo;
  }
  int e;
  double m = frexp(t, &e); /* m in [1/2, 1), e <= -479 */
  ics_dd v = ics_dd_mul(ics_dd_sqr(m), f);
  double x = v.hi + v.lo; /* in [1/8, 2] */
  int k = 2 * e;          /* <= -958 */
  if (k <= -1077) return 0.0; /* x 2^k <= 2^-1076 < 2^-1075: rounds to +0 */
  return (x * 0x1p-600) * pow2i(k + 600); /* k + 600 in [-476, -358] */
}

double ics_ellipse_vy(double t) {
  if (isnan(t) || t < 0.0 || t > 1.0) return NAN;
  if (t == 0.0) return 0.0;
  if (t <= 0.5) return sq_times(t, two3_minus(unit_w_small(t)));
  ics_dd v = ics_dd_mul(ics_dd_sqr(t), third_plus(unit_w_large(t)));
  return v.hi + v.lo;
}

double ics_ellipse_ratio(double t) {
  if (isnan(t) || t < 0.0 || t > 1.0) return NAN;
  if (t == 0.0) return 0.0;
  if (t == 1.0) return INFINITY;
  if (t <= 0.5) {
    ics_dd w = unit_w_small(t);
    ics_dd g_num = two3_minus(w), g_den = third_plus(w);
    if (t < 0x1p-480) { /* 1 - t rounds to 1 (relative 2^-479): ratio = t^2 g, t^2 may underflow */
      return sq_times(t, ics_dd_div_dd(g_num, g_den));
    }
    return ics_dd_div_d(ics_dd_mul(ics_dd_sqr(t), g_num), ics_dd_mul(one_minus_sq(t), g_den));
  }
  ics_dd w = unit_w_large(t);
  double u = 1.0 - t;
  return ics_dd_div_d(ics_dd_mul(ics_dd_sqr(t), third_plus(w)), ics_dd_mul(ics_dd_sqr(u), two3_minus(w)));
}

/* g(beta) = (2/3 - w)/(1/3 + w) */
static ics_dd g_of_beta(double beta) {
  ics_dd one = {1.0, 0.0};
  ics_dd w = ellipse_w(beta, 1.0 - beta, 1.0 + beta, one, ics_dd_sqr(beta));
  return ics_dd_div_dd(two3_minus(w), third_plus(w));
}

/* Solve beta^2 g(beta) = r for beta in (0, 1], r = fr 2^(2 e2) <= 1 (fr in [1/4, 1)):
 * secant iteration on the residual of the contraction beta = G(beta) = sqrt(r / g(beta)),
 * then one polishing step G and a Newton correction of the square root in double-double
 * (so the result's error is that of g alone, halved). */
static ics_dd solve_beta(double fr, int e2) {
  ics_dd gl;
#define G_OF(bt) (gl = g_of_beta(bt), ldexp(sqrt(fr / gl.hi), e2))
  double x0 = ldexp(sqrt(fr * 0.5), e2);
  if (x0 > 1.0) x0 = 1.0;
  double x1 = G_OF(x0);
  if (x1 > 1.0) x1 = 1.0;
  double f0 = x1 - x0;
  double f1 = G_OF(x1) - x1;
  for (int it = 0; it < 60 && f1 != 0.0 && f1 != f0; it++) {
    double x2 = x1 - f1 * (x1 - x0) / (f1 - f0);
    if (!(x2 > 0.0)) x2 = 0.5 * x1;
    if (x2 > 1.0) x2 = 1.0;
    x0 = x1;
    f0 = f1;
    x1 = x2;
    f1 = G_OF(x1) - x1;
    if (fabs(x1 - x0) <= 0x1p-60 * x1) break;
  }
  double y = G_OF(x1); /* y ~ sqrt(r / g), g = gl */
#undef G_OF
  /* Newton for the square root on the scaled mantissas: ys^2 gl = fr, ys = y 2^-e2 */
  double ys = ldexp(y, -e2);
  ics_dd y2 = ics_dd_sqr(ys);
  ics_dd y2g = ics_dd_mul(y2, gl);
  double res = (fr - y2g.hi) - y2g.lo; /* fr - y2g.hi is exact (Sterbenz) near the root */
  double corr = res / (2.0 * ys * gl.hi);
  ics_dd beta = ics_dd_two_sum(ys, corr);
  beta.hi = ldexp(beta.hi, e2);
  beta.lo = ldexp(beta.lo, e2);
  if (beta.hi >= 1.0) beta = (ics_dd){1.0, 0.0};
  return beta;
}

double ics_ellipse_ratio_to_t(double rat) {
  if (isnan(rat) || rat < 0.0) return NAN;
  if (rat == 0.0) return 0.0;
  if (isinf(rat)) return 1.0;
  if (rat == 1.0) return 0.5;
  if (rat > 0x1p600) return 1.0; /* 1 - t < 2^-300 */
  int inverse = rat > 1.0;
  /* r > 1: beta' = (1 - t)/t solves beta'^2 g(beta') = 1/r (ratio(1 - t) = 1/ratio(t)) */
  double r = inverse ? 1.0 / rat : rat;
  int e;
  double fr = frexp(r, &e); /* r = fr 2^e, fr in [1/2, 1) */
  if (e & 1) {
    fr *= 0.5;
    e += 1;
  }
  if (r < 0x1p-600) /* beta = sqrt(r/2) (rho < 2^-590), t = beta/(1 + beta) = beta */
    return ldexp(sqrt(fr * 0.5), e / 2);
  ics_dd beta = solve_beta(fr, e / 2);
  ics_dd den = ics_dd_two_sum(1.0, beta.hi);
  den.lo += beta.lo;
  den = ics_dd_two_sum(den.hi, den.lo);
  if (inverse) return ics_dd_div_d((ics_dd){1.0, 0.0}, den); /* t = 1 / (1 + beta') */
  return ics_dd_div_d(beta, den);                          /* t = beta / (1 + beta) */
}

/* ==== the elliptical kernel ================================================================= */

/* Carlson's symmetric integrals by duplication (Carlson 1995, Numer. Algorithms 10:13-26),
 * stopping rule with r = 2^-53: truncation error below the rounding error. x, y, z >= 0, at most
 * one of them zero (R_D: z > 0). */
static double carlson_rf(double x, double y, double z) {
  double A0 = (x + y + z) / 3.0;
  double Q = 0x1.4p+8 * fmax(fabs(A0 - x), fmax(fabs(A0 - y), fabs(A0 - z))); /* (3r)^(-1/6) */
  double A = A0, x0 = x, y0 = y, pw = 1.0;
  for (int n = 0; n < 200 && pw * Q >= fabs(A); n++) {
    double sx = sqrt(x), sy = sqrt(y), sz = sqrt(z);
    double lam = sx * sy + sx * sz + sy * sz;
    x = 0.25 * (x + lam);
    y = 0.25 * (y + lam);
    z = 0.25 * (z + lam);
    A = 0.25 * (A + lam);
    pw *= 0.25;
  }
  double X = pw * (A0 - x0) / A, Y = pw * (A0 - y0) / A, Z = -(X + Y);
  double E2 = X * Y - Z * Z, E3 = X * Y * Z;
  return (1.0 - E2 / 10.0 + E3 / 14.0 + E2 * E2 / 24.0 - 3.0 * E2 * E3 / 44.0) / sqrt(A);
}

static double carlson_rd(double x, double y, double z) {
  double A0 = (x + y + 3.0 * z) / 5.0;
  double Q = 0x1.cp+9 * fmax(fabs(A0 - x), fmax(fabs(A0 - y), fabs(A0 - z))); /* (r/4)^(-1/6) */
  double A = A0, x0 = x, y0 = y, pw = 1.0, sum = 0.0;
  for (int n = 0; n < 200 && pw * Q >= fabs(A); n++) {
    double sx = sqrt(x), sy = sqrt(y), sz = sqrt(z);
    double lam = sx * sy + sx * sz + sy * sz;
    sum += pw / (sz * (z + lam));
    x = 0.25 * (x + lam);
    y = 0.25 * (y + lam);
    z = 0.25 * (z + lam);
    A = 0.25 * (A + lam);
    pw *= 0.25;
  }
  double X = pw * (A0 - x0) / A, Y = pw * (A0 - y0) / A, Z = -(X + Y) / 3.0;
  double XY = X * Y, Z2 = Z * Z;
  double E2 = XY - 6.0 * Z2, E3 = (3.0 * XY - 8.0 * Z2) * Z, E4 = 3.0 * (XY - Z2) * Z2,
         E5 = XY * Z2 * Z;
  double s = 1.0 - 3.0 * E2 / 14.0 + E3 / 6.0 + 9.0 * E2 * E2 / 88.0 - 3.0 * E4 / 22.0 -
             9.0 * E2 * E3 / 52.0 + 3.0 * E5 / 26.0;
  return pw * s / (A * sqrt(A)) + 3.0 * sum;
}

/* Arc length on the ellipse (cos psi, beta sin psi), 0 < beta <= 1, from the major-axis end
 * (psi = 0) to psi in [0, pi/2]:
 *   int_0^psi sqrt(sin^2 + beta^2 cos^2) = beta^2 [ s R_F(X, Y, Z) + (1 - beta^2)/3 s^3 R_D(X, Y, Z) ]
 * with s = sin psi, c = cos psi, X = beta^2 c^2, Y = beta^2 c^2 + s^2, Z = beta^2: both terms
 * positive (measured from the major end there is no cancellation), relative error ~1e-16. */
static double arc_from_major(double beta, double psi) {
  double s = sin(psi), c = cos(psi);
  double b2 = beta * beta;
  double X = b2 * c * c, Y = X + s * s;
  if (s == 0.0) return 0.0;
  return b2 * (s * carlson_rf(X, Y, b2) + (1.0 - b2) / 3.0 * s * s * s * carlson_rd(X, Y, b2));
}

/* psi in [0, pi/2] with arc_from_major(beta, psi) = sigma, 0 <= sigma <= Q (quarter arc).
 * f(psi) = arc - sigma is increasing and convex, so Newton from an upper bound converges
 * monotonically; upper bounds: arc >= 1 - cos psi and arc >= beta psi. */
static double arc_invert(double beta, double sigma, double Q) {
  if (sigma <= 0.0) return 0.0;
  if (sigma >= Q) return ICS_PI / 2;
  double psi = ICS_PI / 2;
  if (sigma < 2.0) psi = fmin(psi, 2.0 * asin(sqrt(0.5 * sigma))); /* 1 - cos psi = sigma */
  psi = fmin(psi, sigma / beta);
  double lo = 0.0, hi = psi; /* the root is in [lo, hi] */
  for (int it = 0; it < 100; it++) {
    double f = arc_from_major(beta, psi) - sigma;
    if (f == 0.0) break;
    if (f > 0.0)
      hi = fmin(hi, psi);
    else
      lo = fmax(lo, psi);
    double sn = sin(psi), cs = cos(psi);
    double d = sqrt(sn * sn + beta * beta * cs * cs);
    double next = psi - f / d;
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi); /* roundoff: safeguard */
    if (fabs(next - psi) <= 0x1p-52 * psi) {
      psi = next;
      break;
    }
    psi = next;
  }
  return psi;
}

/* cos and sin of an angle in degrees, exact at multiples of 90 (degtrig.h) */
void ics_sincos_deg(double deg, double *s, double *c) {
  double r = fmod(deg, 360.0); /* exact */
  double q = nearbyint(r / 90.0);
  double rem = r - 90.0 * q; /* exact: |rem| <= 45 */
  double x = rem * (ICS_PI / 180.0);
  double sx = sin(x), cx = cos(x);
  int k = ((int)q % 4 + 4) % 4;
  switch (k) {
  case 0: *s = sx, *c = cx; break;
  case 1: *s = cx, *c = -sx; break;
  case 2: *s = -sx, *c = -cx; break;
  default: *s = -cx, *c = sx; break;
  }
}

ics_status ics_ellipse_kernel(double varx, double vary, double angle_deg, int nsamples,
                              double offset, ics_ellipse_shape *shape, double *xy) {
  if (!shape) return ICS_ERR_INVALID_ARG;
  if (isnan(varx) || isnan(vary) || isnan(angle_deg) || isnan(offset)) return ICS_ERR_NAN;
  if (varx < 0.0 || vary < 0.0) return ICS_ERR_NEGATIVE_VARIANCE;
  if (isinf(varx) || isinf(vary) || isinf(angle_deg)) return ICS_ERR_INFINITE;
  if (isinf(offset) || nsamples < 1 || nsamples > ICS_ELLIPSE_MAX_SAMPLES) return ICS_ERR_RANGE;

  varx += 0.0; /* -0 -> +0: no negative zero radii or t */
  vary += 0.0;
  shape->angle_deg = angle_deg;
  if (varx == 0.0 && vary == 0.0) { /* point light: one tap at the origin */
    shape->a = shape->b = 0.0;
    shape->t = 0.5;
    shape->nsamples = 1;
    if (xy) xy[0] = xy[1] = 0.0;
    return ICS_OK;
  }
  /* major variance vM along axis "maj" (x if varx >= vary), minor vm; s = unit-ellipse parameter
   * of the minor radius: minor = s sqrt(sc), major = (1 - s) sqrt(sc), sc = vM / V_x(s) */
  int x_major = varx >= vary;
  double vM = x_major ? varx : vary, vm = x_major ? vary : varx;
  double r = vm / vM, s;
  if (r < 0x1p-600) /* ratio_to_t(r) = sqrt(r/2) here; formed without underflow, and without
                     * halving a subnormal vm (exact scaling: vm 2^199 is normal, < 2^623) */
    s = ldexp(sqrt(ldexp(vm, 199)) / sqrt(vM), -100);
  else
    s = ics_ellipse_ratio_to_t(r);
  double root = sqrt(vM) / sqrt(ics_ellipse_vx(s)); /* sqrt(sc), no overflow for vM ~ DBL_MAX */
  double rmaj = (1.0 - s) * root, rmin = s * root;
  shape->a = x_major ? rmaj : rmin;
  shape->b = x_major ? rmin : rmaj;
  shape->t = x_major ? s : 1.0 - s;
  shape->nsamples = nsamples;
  if (!xy) return ICS_OK;

  /* taps: arc fraction u_j = offset + j/N (mod 1) of the perimeter from the end of the MAJOR
   * axis, counter-clockwise: from (a, 0) when x is major, from (0, b) when y is (so a line light
   * has its extreme taps at offset 0 in either orientation). The taps are computed in a frame
   * whose first axis is the major one, then turned by +90 degrees ((M, N) -> (-N, M), exact) when
   * y is major. Quadrant k = floor(4u) by symmetry; within a quadrant, the arc is measured from
   * the major-axis end (no cancellation, see arc_from_major) on the normalised ellipse. */
  double beta = s / (1.0 - s); /* minor / major */
  int segment = beta < 0x1p-500; /* beta^2 would underflow: a segment to O(beta^2) relative */
  double Q = segment ? 1.0 : arc_from_major(beta, ICS_PI / 2);
  double sa, ca;
  ics_sincos_deg(angle_deg, &sa, &ca);
  double u0 = offset - floor(offset);
  for (int j = 0; j < nsamples; j++) {
    double u = u0 + (double)j / nsamples;
    u -= floor(u);
    double q4 = 4.0 * u;
    int k = (int)q4;
    if (k > 3) k = 3;
    double lam = (q4 - k) * Q; /* arc within the quadrant, from its start */
    /* quadrants 1 and 3 run from the minor axis to the major one: mirror to "from the major" */
    double sigma = (k & 1) ? Q - lam : lam;
    double pm, pn; /* coordinates along the major and minor axes (normalised), first quadrant */
    if (segment) { /* |major| = 1 - sigma (arc = 1 - cos psi to O(beta^2)), on the ellipse */
      pm = 1.0 - sigma;
      pn = beta * sqrt(sigma * (2.0 - sigma));
    } else {
      double psi = arc_invert(beta, sigma, Q);
      pm = cos(psi);
      pn = beta * sin(psi);
    }
    pm *= rmaj;
    pn *= rmaj;
    if (k == 1 || k == 2) pm = -pm;
    if (k >= 2) pn = -pn;
    double px = x_major ? pm : -pn, py = x_major ? pn : pm;
    xy[2 * j] = (px * ca - py * sa) + 0.0; /* + 0.0: no negative zeros */
    xy[2 * j + 1] = (px * sa + py * ca) + 0.0;
  }
  return ICS_OK;
}
