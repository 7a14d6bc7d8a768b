/* dd.h — double-double arithmetic (private to libicshadow): a value hi + lo with |lo| <= ulp(hi)/2
 * and its error-free transformations, the one copy for the elliptic integrals (ellint.c) and
 * the ellipse variance functions (ellipse.c). Products use fma (exact remainders); the sum
 * has no multiplication, so FMA contraction cannot change it. */
#ifndef ICS_DD_H
#define ICS_DD_H

#include <math.h>

typedef struct {
  double hi, lo;
} ics_dd;

/* TwoSum: hi + lo = a + b exactly (any order of magnitudes). */
static inline ics_dd ics_dd_two_sum(double a, double b) {
  ics_dd r;
  r.hi = a + b;
  double bb = r.hi - a;
  r.lo = (a - (r.hi - bb)) + (b - bb);
  return r;
}

/* exact a^2 */
static inline ics_dd ics_dd_sqr(double a) {
  ics_dd r;
  r.hi = a * a;
  r.lo = fma(a, a, -r.hi);
  return r;
}

static inline ics_dd ics_dd_mul(ics_dd a, ics_dd b) {
  ics_dd r;
  double p = a.hi * b.hi;
  double e = fma(a.hi, b.hi, -p);
  e += a.hi * b.lo + a.lo * b.hi;
  r.hi = p + e;
  r.lo = e - (r.hi - p);
  return r;
}

/* (a.hi + a.lo) / (b.hi + b.lo), one final rounding */
static inline double ics_dd_div_d(ics_dd a, ics_dd b) {
  double q = a.hi / b.hi;
  double r = fma(-q, b.hi, a.hi); /* exact remainder */
  r += a.lo - q * b.lo;
  return q + r / b.hi;
}

/* quotient to ~2^-100 relative */
static inline ics_dd ics_dd_div_dd(ics_dd a, ics_dd b) {
  double q = a.hi / b.hi;
  double r = fma(-q, b.hi, a.hi);
  r += a.lo - q * b.lo;
  return ics_dd_two_sum(q, r / b.hi);
}

static inline ics_dd ics_dd_add(ics_dd a, ics_dd b) {
  ics_dd s = ics_dd_two_sum(a.hi, b.hi);
  s.lo += a.lo + b.lo;
  return ics_dd_two_sum(s.hi, s.lo);
}

#endif
