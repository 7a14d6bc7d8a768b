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
 *     done in double-double: m1 = 1 - m exactly (two-sum), x' = 1/m1 (one division plus its
 *     exact residual), sqrt(m1) and 1/sqrt(m1) = sqrt(m1)/m1 (each with one Newton correction),
 *     and the two final products
 *     (Dekker/Veltkamp products, or fma() where the target has a fast one).  When x' < X0 the
 *     log series takes L = ln(16 m1) straight from m1 (no rounding of 1/m1 inside the log);
 *     above m1 = 2^512 the square roots are taken of m1 2^-600 (exact scaling: no overflow,
 *     no subnormal 1/m1), so m down to -DBL_MAX works.
 *
 * SWITCH POINTS (all tested from both sides): x = 1/32 (log series / pieces); the piece
 * boundaries x = 2^-j (1 + i/8); m = 0 (m1 = 1: direct / transformed); m1 = 32 (x' = 1/32 on
 * the transformed route); m1 = 2^512 (scaled square roots); x = 2^-64 (polynomials evaluated at
 * 0 below it: Estrin's x^8 must not go subnormal, which is slow); x = 2^-1022 (subnormal x
 * rescaled before the exponent is read).
 *
 * ERROR BOUND (measured against a 320-bit MPFR AGM, tests/test_ellint.c; docs/ellint.md):
 *   K: 0.60 ulp,  E: 0.60 ulp  over the whole domain, for every entry point
 *   (the final rounding contributes 0.5 ulp; the tables' approximation error is < 0.007 ulp;
 *   largest errors found in 6e6 random inputs: K 0.556 ulp at m1 = 0x1.4c0a15965244p-7,
 *   E 0.557 ulp at m = -0x1.2dbd6187e79d4p+5).
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

/* The routes are specialised per entry point (K only, E only, both): force inlining. */
#if defined(__GNUC__) || defined(__clang__)
#define ICS_INLINE static inline __attribute__((always_inline))
#else
#define ICS_INLINE static inline
#endif

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

static inline ics_dd two_sqr(double a) { /* |a| < 2^995 */
  ics_dd r;
  r.hi = a * a;
#ifdef FP_FAST_FMA
  r.lo = fma(a, a, -r.hi);
#else
  double ca = 134217729.0 * a;
  double ah = ca - (ca - a), al = a - ah;
  r.lo = ((ah * ah - r.hi) + 2.0 * ah * al) + al * al;
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

/* Estrin's scheme (shorter dependency chains than Horner; n is a compile-time constant). */
static inline double poly(const double *p, int n, double t) {
  double t2 = t * t, t4 = t2 * t2;
  double a = (p[0] + p[1] * t) + t2 * (p[2] + p[3] * t);
  double b = (p[4] + p[5] * t) + t2 * (p[6] + (n >= 7 ? p[7] * t : 0.0));
  if (n <= 7) return a + t4 * b;
  double c = n == 8 ? p[8] : n == 9 ? p[8] + p[9] * t : (p[8] + p[9] * t) + t2 * p[10];
  return a + t4 * (b + t4 * c);
}

/* L = ln(16/x) as a double-double; x > 0 finite. */
static inline ics_dd ln16_over(double x) {
  int k;
  double f = split_log2(x, &k);
  double n = 4.0 - k;
  return fast_two_sum(n * LN2_HI, n * LN2_LO - log(f));
}

/* L = ln(16 (x + xl)) as a double-double; x > 1 finite, |xl| <= ulp(x)/2, xinv ~ 1/x. */
static inline ics_dd ln16_times(double x, double xl, double xinv) {
  int k;
  double f = split_log2(x, &k);
  double n = 4.0 + k;
  return fast_two_sum(n * LN2_HI, n * LN2_LO + (log(f) + xl * xinv));
}

/* ---- the two approximations in x = complementary parameter ----------------------------- */
/* Log region, 0 < x < X0, L = ln(16/x) (or ln(16 m1) for the transformed argument).
 * log_k, log_e, piece_k, piece_e return {leading term, correction}: the leading term is exact
 * (a table double or L_hi/2 or 1), the correction is at most 4 % of the result, and the caller
 * adds them in one final rounding (or keeps them apart for the m < 0 products). */
/* The argument is x + xl (xl = 0 except for the transformed argument 1/m1 of m < 0). */
/* The polynomials get xp = 0 below 2^-64 (their x-dependence is then far below an ulp): this
 * keeps x^8 in Estrin's scheme from going subnormal, which is very slow on x86. */
static inline double poly_arg(double x) { return x > 0x1p-64 ? x : 0.0; }

static inline ics_dd log_k(double x, double xl, ics_dd L) {
  const struct ics_ellint_log_table *T = &ics_ellint_log;
  double hl = 0.5 * L.hi, xp = poly_arg(x);
  double corr = 0.5 * L.lo + x * (hl * poly(T->pa, ICS_ELLINT_NLOG, xp) +
                                  poly(T->pb, ICS_ELLINT_NLOG, xp));
  corr += xl * (0.125 * L.hi - 0.25); /* first-order term of the xl correction */
  return (ics_dd){hl, corr};
}

/* E = 1 + x ((L - 1)/4 + x ((L/2) Pc(x) + Pd(x))); (L_hi - 1)/4 is exact (L_hi > 4). */
static inline ics_dd log_e(double x, double xl, ics_dd L) {
  const struct ics_ellint_log_table *T = &ics_ellint_log;
  double xp = poly_arg(x);
  double r = 0.25 * L.lo + x * (0.5 * L.hi * poly(T->pc, ICS_ELLINT_NLOG, xp) +
                                poly(T->pd, ICS_ELLINT_NLOG, xp));
  double b = 0.25 * (L.hi - 1.0);
  double corr = x * (b + r) + xl * b;
  return (ics_dd){1.0, corr};
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
  return (ics_dd){P->k0h, P->k0l + t * poly(P->pk, ICS_ELLINT_NK, t)};
}

static inline ics_dd piece_e(const struct ics_ellint_piece *P, double t) {
  return (ics_dd){P->e0h, P->e0l + t * poly(P->pe, ICS_ELLINT_NE, t)};
}

/* ---- routes ---------------------------------------------------------------------------- */
/* 0 <= m < 1, x = 1 - m; from_m: t is formed from m (x may be rounded), else x is exact. */
ICS_INLINE void route_pos(double x, double m, int from_m, int wk, int we, double *K,
                             double *E) {
  if (x < ICS_ELLINT_X0) {
    ics_dd L = ln16_over(x);
    if (wk) {
      ics_dd k = log_k(x, 0.0, L);
      *K = k.hi + k.lo;
    }
    if (we) {
      ics_dd e = log_e(x, 0.0, L);
      *E = e.hi + e.lo;
    }
  } else {
    const struct ics_ellint_piece *P = piece_of(x);
    double t = from_m ? (1.0 - P->c) - m : x - P->c;
    if (wk) {
      ics_dd k = piece_k(P, t);
      *K = k.hi + k.lo;
    }
    if (we) {
      ics_dd e = piece_e(P, t);
      *E = e.hi + e.lo;
    }
  }
}

/* m < 0: m1 = m1h + m1l > 1 (double-double), finite.
 * With x' = 1/m1 (the complementary parameter of m' = m/(m-1)) and r = sqrt(x') = 1/sqrt(m1):
 *   K(m) = K(m') r,   E(m) = E(m') sqrt(m1),
 * all as double-double products (no division but 1/m1).  Above m1 = 2^512 the square roots are
 * taken of m1 2^-600 (exact scaling) so that no product overflows and 1/m1 stays normal. */
ICS_INLINE void route_neg(double m1h, double m1l, int wk, int we, double *K, double *E) {
  ics_dd kt = {0, 0}, et = {0, 0};
  double sc = 1.0, rsc = 1.0, ssc = 1.0;
  if (m1h > 0x1p512) {
    sc = 0x1p-600;
    rsc = 0x1p-300;
    ssc = 0x1p300;
  }
  double ms = m1h * sc, mls = m1l * sc; /* exact */
  double qs = 1.0 / ms;
  ics_dd p = two_prod(qs, ms);
  double qsl = qs * (((1.0 - p.hi) - p.lo) - qs * mls); /* 1/(ms + mls) = qs + qsl */
  double q = qs * sc, ql = qsl * sc;                     /* x' = q + ql (exact scaling) */
  double sh = sqrt(ms), rh = sh * qs; /* rh ~ 1/sqrt(ms) within 2 ulps: corrected below */
  if (q < ICS_ELLINT_X0) {
    ics_dd L = ln16_times(m1h, m1l, q);
    if (wk) kt = log_k(q, ql, L);
    if (we) et = log_e(q, ql, L);
  } else {
    const struct ics_ellint_piece *P = piece_of(q);
    double t = (q - P->c) + ql;
    if (wk) kt = piece_k(P, t);
    if (we) et = piece_e(P, t);
  }
  if (wk) { /* r = sqrt(qs + qsl) = rh + rl;  K = kt r 2^-300 (or 1) */
    ics_dd r2 = two_sqr(rh); /* one Newton step: rl absorbs rh's error and qsl */
    double rl = (((qs - r2.hi) - r2.lo) + qsl) * (0.5 * sh);
    ics_dd pk = two_prod(kt.hi, rh); /* kt.hi is the exact leading term, kt.lo < 1.2 % */
    *K = (pk.hi + (pk.lo + (kt.hi * rl + kt.lo * rh))) * rsc;
  }
  if (we) { /* s = sqrt(ms + mls) = sh + sl;  E = et s 2^300 (or 1) */
    et = fast_two_sum(et.hi, et.lo);
    ics_dd s2 = two_sqr(sh);
    double sl = (((ms - s2.hi) - s2.lo) + mls) * (0.5 * rh);
    ics_dd pe = two_prod(et.hi, sh);
    *E = (pe.hi + (pe.lo + (et.hi * sl + et.lo * sh))) * ssc;
  }
}

/* ---- public entry points ----------------------------------------------------------------- */
ICS_INLINE void ke_m(double m, int wk, int we, double *K, double *E) {
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

ICS_INLINE void ke_m1(double m1, int wk, int we, double *K, double *E) {
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
