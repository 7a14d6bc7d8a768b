/* ellint.c — complete elliptic integrals K and E (icshadow/ellint.h).
 *
 * CONVENTION: m is the PARAMETER, m = k^2 (k = modulus), as in mpmath/scipy/Mathematica;
 * m1 = 1 - m is the complementary parameter, taken directly by the *_m1 entry points.
 *   K(m) = int_0^{pi/2} (1 - m sin^2 t)^{-1/2} dt,   E(m) = int_0^{pi/2} (1 - m sin^2 t)^{1/2} dt.
 * Below, x denotes the complementary parameter of the argument actually evaluated.
 *
 * METHOD (all coefficients in ellint_data.c, made by scripts/gen_ellint_coeffs.py with mpmath):
 *  1. 0 < x < X0 = 1/32 (m > 31/32): logarithmic series, DLMF 19.12.1 / 19.12.2, L = ln(16/x):
 *       K = (L/2)(1 + x Pa(x)) + x Pb(x),   E = 1 + x ((L - 1)/4 + x ((L/2) Pc(x) + Pd(x))),
 *     Pa..Pd being degree-7 Chebyshev interpolants (on [0, X0]) of the exact rational series
 *     (A = 1 + x Pa = sum ((1/2)_n/n!)^2 x^n etc., see the generator).
 *     L is formed as a double-double: x = f 2^k with f in [sqrt(1/2), sqrt(2)] (subnormal x is
 *     rescaled first, so x down to 2^-1074 works and 16/x is never formed), then
 *     L = (4 - k) ln2_hi + ((4 - k) ln2_lo - log(f)); (4 - k) ln2_hi is exact.  The leading term
 *     L_hi/2 is exact, everything else is a small correction, so the last addition dominates.
 *  2. X0 <= x <= 1 (0 <= m <= 31/32): 40 pieces, 8 per binade of x ([1/32,1/16) ... [1/2,1]),
 *     selected from the exponent and top 3 mantissa bits of x.  About each piece centre c,
 *       K = k0_hi + (k0_lo + t Pk(t)),  t = x - c (exact; from m it is (1 - c) - m),
 *     with K(1 - c) = k0_hi + k0_lo stored as a double-double and Pk of degree 10 (E: degree 9);
 *     |t Pk(t)| < 1.2 % of K, so the final addition again dominates the error.
 *     The switch at x = 1/32 keeps the log-series correction x ((L-1)/4 + ...) to E below
 *     4 % of E (at 1/16 its rounding errors reached 0.08 ulp); the pieces follow the binades
 *     because K's derivative grows like 1/x.
 *  3. m < 0 (m1 > 1): imaginary-modulus transformation (DLMF 19.7.5 / A&S 17.4.17-18)
 *       K(m) = K(m') / sqrt(m1),   E(m) = sqrt(m1) E(m'),   m' = m/(m - 1), 1 - m' = 1/m1,
 *     done in double-double: m1 = 1 - m exactly (two-sum), 1/m1, sqrt(m1), the quotient and the
 *     product (Dekker/Veltkamp products, or fma() where the target has a fast one).  When
 *     1/m1 < X0 the log series takes L = ln(16 m1) straight from m1 (no 1/m1 rounding);
 *     above m1 = 2^512 the square-root correction is computed on a scaled copy (no overflow),
 *     so m down to -DBL_MAX works.
 *
 * ERROR BOUND (measured against a 320-bit MPFR AGM, tests/test_ellint.c; docs/ellint.md):
 *   K: 0.60 ulp,  E: 0.60 ulp  over the whole domain, for every entry point
 *   (the final rounding contributes 0.5 ulp; the tables' approximation error is < 0.007 ulp).
 *
 * SPECIAL CASES (no errno is ever touched):
 *   m = 1 (m1 = 0): K = +inf, E = 1.      m > 1 (m1 < 0) or NaN: NaN.
 *   m = -inf (m1 = +inf): K = 0, E = +inf.   m = 0 (m1 = 1): K = E = pi/2.
 */
#include "icshadow/ellint.h"

#include <math.h>
#include <stdint.h>
#include <string.h>

#include "ellint_data.h"

#define LN2_HI 0x1.62e42fee00000p-1 /* 21 trailing zero bits: n * LN2_HI exact, |n| < 2^21 */
#define LN2_LO 0x1.a39ef35793c76p-33

typedef struct {
  double hi, lo;
} ics_dd;

/* ---- error-free transformations ------------------------------------------------------- */
static inline ics_dd fast_two_sum(double a, double b) { /* |a| >= |b| or a == 0 */
  ics_dd r;
  r.hi = a + b;
  r.lo = b - (r.hi - a);
  return r;
}

static inline ics_dd two_sum(double a, double b) {
  ics_dd r;
  r.hi = a + b;
  double bb = r.hi - a;
  r.lo = (a - (r.hi - bb)) + (b - bb);
  return r;
}

static inline ics_dd two_prod(double a, double b) { /* |a|, |b| < 2^995 */
  ics_dd r;
  r.hi = a * b;
#ifdef FP_FAST_FMA
  r.lo = fma(a, b, -r.hi);
#else
  const double split = 134217729.0; /* 2^27 + 1 (Veltkamp) */
  double ca = split * a, cb = split * b;
  double ah = ca - (ca - a), al = a - ah;
  double bh = cb - (cb - b), bl = b - bh;
  r.lo = ((ah * bh - r.hi) + ah * bl + al * bh) + al * bl;
#endif
  return r;
}

/* ---- small helpers --------------------------------------------------------------------- */
static inline uint64_t as_u64(double x) {
  uint64_t u;
  memcpy(&u, &x, sizeof u);
  return u;
}

static inline double as_f64(uint64_t u) {
  double x;
  memcpy(&x, &u, sizeof x);
  return x;
}

/* x = f * 2^k with f in [sqrt(1/2), sqrt(2)); x > 0 finite (subnormals included). */
static inline double split_log2(double x, int *k) {
  int adj = 0;
  if (x < 0x1p-1022) {
    x *= 0x1p54;
    adj = -54;
  }
  uint64_t u = as_u64(x);
  /* subtracting the bits of sqrt(1/2) puts the binade boundary at sqrt(1/2) */
  uint64_t tmp = u - 0x3fe6a09e667f3bcdULL;
  int e = (int)((int64_t)tmp >> 52); /* f = x / 2^e lies in [sqrt(1/2), sqrt(2)) */
  *k = e + adj;
  return as_f64(u - ((uint64_t)(int64_t)e << 52));
}

static inline double horner(const double *p, int n, double t) {
  double s = p[n];
  for (int i = n - 1; i >= 0; i--) s = s * t + p[i];
  return s;
}

/* L = ln(16/x) (sign = -1) or ln(16 x) (sign = +1), as a double-double; x > 0 finite.
 * xl is a small correction to x (x + xl), used only for sign = +1. */
static inline ics_dd ln16(double x, double xl, int sign) {
  int k;
  double f = split_log2(x, &k);
  double n = 4.0 + sign * k;
  double lo = n * LN2_LO + sign * (log(f) + xl / x);
  return fast_two_sum(n * LN2_HI, lo);
}

/* ---- the two approximations in x = complementary parameter ----------------------------- */
/* Log region, 0 < x < X0, L = ln(16/x) (or ln(16 m1) for the transformed argument). */
/* The argument is x + xl (xl = 0 except for the transformed argument 1/m1 of m < 0). */
static inline ics_dd log_k(double x, double xl, ics_dd L) {
  const struct ics_ellint_log_table *T = &ics_ellint_log;
  double hl = 0.5 * L.hi;
  double corr = 0.5 * L.lo + x * (hl * horner(T->pa, ICS_ELLINT_NLOG, x) +
                                  horner(T->pb, ICS_ELLINT_NLOG, x));
  corr += xl * (0.125 * L.hi - 0.25); /* first-order term of the xl correction */
  return fast_two_sum(hl, corr);
}

/* E = 1 + x ((L - 1)/4 + x ((L/2) Pc(x) + Pd(x))); (L_hi - 1)/4 is exact (L_hi > 4). */
static inline ics_dd log_e(double x, double xl, ics_dd L) {
  const struct ics_ellint_log_table *T = &ics_ellint_log;
  double r = 0.25 * L.lo + x * (0.5 * L.hi * horner(T->pc, ICS_ELLINT_NLOG, x) +
                                horner(T->pd, ICS_ELLINT_NLOG, x));
  double b = 0.25 * (L.hi - 1.0);
  double corr = x * (b + r) + xl * b;
  return fast_two_sum(1.0, corr);
}

/* Piece index for x in [X0, 1]. */
static inline const struct ics_ellint_piece *piece_of(double x) {
  int64_t i = (int64_t)(as_u64(x) >> (52 - ICS_ELLINT_S)) -
              ((int64_t)(1023 + ICS_ELLINT_X0_LOG2) << ICS_ELLINT_S);
  if (i > ICS_ELLINT_NPIECES - 1) i = ICS_ELLINT_NPIECES - 1; /* x = 1 */
  if (i < 0) i = 0;
  return &ics_ellint_pieces.p[i];
}

static inline ics_dd piece_k(const struct ics_ellint_piece *P, double t) {
  return fast_two_sum(P->k0h, P->k0l + t * horner(P->pk, ICS_ELLINT_NK, t));
}

static inline ics_dd piece_e(const struct ics_ellint_piece *P, double t) {
  return fast_two_sum(P->e0h, P->e0l + t * horner(P->pe, ICS_ELLINT_NE, t));
}

/* ---- routes ---------------------------------------------------------------------------- */
/* 0 <= m < 1, x = 1 - m; from_m: t is formed from m (x may be rounded), else x is exact. */
static inline void route_pos(double x, double m, int from_m, int wk, int we, double *K,
                             double *E) {
  if (x < ICS_ELLINT_X0) {
    ics_dd L = ln16(x, 0.0, -1);
    if (wk) *K = log_k(x, 0.0, L).hi;
    if (we) *E = log_e(x, 0.0, L).hi;
  } else {
    const struct ics_ellint_piece *P = piece_of(x);
    double t = from_m ? (1.0 - P->c) - m : x - P->c;
    if (wk) *K = piece_k(P, t).hi;
    if (we) *E = piece_e(P, t).hi;
  }
}

/* m < 0: m1 = m1h + m1l > 1 (double-double), finite. */
static inline void route_neg(double m1h, double m1l, int wk, int we, double *K, double *E) {
  ics_dd kt = {0, 0}, et = {0, 0};
  double q = 1.0 / m1h, ql = 0.0; /* 1/m1 = q + ql */
  if (m1h < 0x1p512) { /* else ql is far below an ulp of the result (and the split overflows) */
    ics_dd p = two_prod(q, m1h);
    double r = (1.0 - p.hi) - p.lo; /* exact: 1 - q m1h */
    ql = q * (r - q * m1l);
  }
  if (q < ICS_ELLINT_X0) {
    ics_dd L = ln16(m1h, m1l, +1);
    if (wk) kt = log_k(q, ql, L);
    if (we) et = log_e(q, ql, L);
  } else {
    const struct ics_ellint_piece *P = piece_of(q);
    double t = (q - P->c) + ql;
    if (wk) kt = piece_k(P, t);
    if (we) et = piece_e(P, t);
  }
  /* s = sqrt(m1) as a double-double; scaled above 2^512 so that s^2 cannot overflow */
  double sh = sqrt(m1h), ss = sh, ms = m1h, mls = m1l, back = 1.0;
  if (m1h > 0x1p512) {
    ss = sh * 0x1p-256;
    ms = m1h * 0x1p-512;
    mls = m1l * 0x1p-512;
    back = 0x1p256;
  }
  ics_dd s2 = two_prod(ss, ss);
  double sl = (((ms - s2.hi) - s2.lo) + mls) / (2.0 * ss) * back;
  if (wk) { /* K = kt / s */
    double q1 = kt.hi / sh;
    ics_dd p = two_prod(q1, sh);
    double r = (((kt.hi - p.hi) - p.lo) + kt.lo) - q1 * sl;
    *K = q1 + r / sh;
  }
  if (we) { /* E = et * s */
    ics_dd p = two_prod(et.hi, sh);
    *E = p.hi + (p.lo + (et.hi * sl + et.lo * sh));
  }
}

/* ---- public entry points ----------------------------------------------------------------- */
static inline void ke_m(double m, int wk, int we, double *K, double *E) {
  if (!(m < 1.0)) { /* m >= 1 or NaN */
    double k = (m == 1.0) ? INFINITY : NAN, e = (m == 1.0) ? 1.0 : NAN;
    if (wk) *K = k;
    if (we) *E = e;
  } else if (m >= 0.0) {
    route_pos(1.0 - m, m, 1, wk, we, K, E);
  } else if (m == -INFINITY) {
    if (wk) *K = 0.0;
    if (we) *E = INFINITY;
  } else {
    ics_dd m1 = two_sum(1.0, -m);
    route_neg(m1.hi, m1.lo, wk, we, K, E);
  }
}

static inline void ke_m1(double m1, int wk, int we, double *K, double *E) {
  if (!(m1 > 0.0)) { /* m1 <= 0 or NaN */
    double k = (m1 == 0.0) ? INFINITY : NAN, e = (m1 == 0.0) ? 1.0 : NAN;
    if (wk) *K = k;
    if (we) *E = e;
  } else if (m1 <= 1.0) {
    route_pos(m1, 0.0, 0, wk, we, K, E);
  } else if (m1 == INFINITY) {
    if (wk) *K = 0.0;
    if (we) *E = INFINITY;
  } else {
    route_neg(m1, 0.0, wk, we, K, E);
  }
}

double ics_ellipk(double m) {
  double k = 0;
  ke_m(m, 1, 0, &k, NULL);
  return k;
}

double ics_ellipe(double m) {
  double e = 0;
  ke_m(m, 0, 1, NULL, &e);
  return e;
}

double ics_ellipk_m1(double m1) {
  double k = 0;
  ke_m1(m1, 1, 0, &k, NULL);
  return k;
}

double ics_ellipe_m1(double m1) {
  double e = 0;
  ke_m1(m1, 0, 1, NULL, &e);
  return e;
}

void ics_ellipke_m1(double m1, double *K, double *E) {
  double k = 0, e = 0;
  ke_m1(m1, K != NULL, E != NULL, &k, &e);
  if (K) *K = k;
  if (E) *E = e;
}
