/* vec_math.h — exp, expm1 and log over vectors of doubles (vec_double.h), for the batched volume
 * pieces (piece_vec.h), where libm's one call per value cost more than the rest of a piece.
 * Written with separate multiplies and adds (the including files are compiled without
 * contraction), so every vector build gives the same bits; the error against a long double
 * reference is measured by test_render_vec_math (docs/renderer.md "Volume pieces in batches").
 * Method:
 *   exp, expm1: x = n ln2 + r, n = rint(x / ln2), |r| <= ln2 / 2 (ln2 in two parts, the first
 *     with 11 trailing zero bits so that n ln2_hi is exact); p = expm1(r) = r + r^2/2! + ... +
 *     r^13/13! by Horner (the first term left out: 8e-18 relative); exp(x) = 2^n (1 + p),
 *     expm1(x) = p where n = 0, ((2^n - 1) + 2^n r) + 2^n (p - r) up to n = 56, 2^n (1 + p)
 *     above; 2^n as 2^(n/2) 2^(n - n/2) so that subnormal results come out right; x is clamped
 *     to [-746, 710] first (0 or -1 below, +inf above); NaN gives NaN, expm1(+-0) +-0.
 *   log: x = 2^e m, m in [sqrt(1/2), sqrt(2)) (subnormals scaled by 2^54 first); f = m - 1
 *     (exact), s = f / (2 + f), log m = 2 atanh s = f - h + s (h + R), h = f^2 / 2,
 *     R = 2 s^2/3 + 2 s^4/5 + ... + 2 s^20/21 (|s| <= 0.1716: the first term left out is 2e-18
 *     relative; fdlibm's arrangement, in which the exact f dominates); log x = e ln2_hi -
 *     ((h - (s (h + R) + e ln2_lo)) - f). 0: -inf, < 0 and NaN: NaN, +inf: +inf. */
#ifndef ICS_RENDER_VEC_MATH_H
#define ICS_RENDER_VEC_MATH_H

#include <math.h>

#include "vec_double.h"

#define VM_LN2_HI 0x1.62e42fefa3800p-1 /* ln 2's first 42 bits */
#define VM_LN2_LO 0x1.ef35793c76730p-45
#define VM_ROUND 0x1.8p52 /* x + 1.5 2^52 - 1.5 2^52: x rounded to an integer, |x| < 2^51 */

/* n = rint(x / ln2) (as a double and an integer) and r = x - n ln2, x in [-746, 710] */
static inline vd vm_reduce(vd x, vd *n, vl *ni) {
  vd t = x * 0x1.71547652b82fep0 + VM_ROUND;
  *ni = (vl)t - (vl)splat(VM_ROUND);
  *n = t - VM_ROUND;
  return (x - *n * VM_LN2_HI) - *n * VM_LN2_LO;
}

/* c[0] x^(n-1) + ... + c[n-1] by Horner's rule */
static inline vd vm_poly(vd x, const double *c, int n) {
  vd p = splat(c[0]);
  for (int i = 1; i < n; i++) p = p * x + c[i];
  return p;
}

/* (expm1(r) - r) / r^2 for |r| <= ln2 / 2: 1/2! + r/3! + ... + r^11/13! */
static inline vd vm_expm1_tail(vd r) {
  static const double c[] = {1.0 / 6227020800.0, 1.0 / 479001600.0, 1.0 / 39916800.0,
                             1.0 / 3628800.0,    1.0 / 362880.0,    1.0 / 40320.0,
                             1.0 / 5040.0,       1.0 / 720.0,       1.0 / 120.0,
                             1.0 / 24.0,         1.0 / 6.0,         0.5};
  return vm_poly(r, c, (int)(sizeof c / sizeof *c));
}

/* 2^n1 and 2^n2 with n1 + n2 = n, each a normal double for n in [-1077, 1025] */
static inline void vm_pow2(vl n, vd *a, vd *b) {
  vl n1 = n >> 1, n2 = n - n1;
  *a = (vd)((n1 + 1023) << 52);
  *b = (vd)((n2 + 1023) << 52);
}

/* x in [-746, 710], NaN as 0 (the callers put it back) */
static inline vd vm_clamp(vd x) {
  x = blend(x < -746.0, splat(-746.0), x);
  x = blend(x > 710.0, splat(710.0), x);
  return blend(x != x, splat(0), x);
}

static inline vd vexp(vd x) {
  vd n, a, b;
  vl ni;
  vd r = vm_reduce(vm_clamp(x), &n, &ni), p = r + (r * r) * vm_expm1_tail(r);
  vm_pow2(ni, &a, &b);
  return blend(x != x, x, ((1 + p) * a) * b);
}

/* 2^n (1 + p) - 1 as ((2^n - 1) + 2^n r) + 2^n r^2 tail(r): the first two terms exact (2^n a
 * power of two), so only their sum and the small last term round; above n = 56 the 1 is below
 * half an ulp and 2^n overflows first at n = 1024: exp's 2^n1 (2^n2 (1 + p)); x = 0 keeps its
 * sign */
static inline vd vexpm1(vd x) {
  vd n, a, b;
  vl ni;
  vd r = vm_reduce(vm_clamp(x), &n, &ni), t = (r * r) * vm_expm1_tail(r);
  vm_pow2(ni, &a, &b);
  vd s = a * b; /* 2^n: 0 only where the result is -1 to the last bit */
  vd big = ((1 + (r + t)) * a) * b, mid = ((s - 1) + s * r) + s * t;
  vd y = blend(ni == 0, r + t, blend(ni > 56, big, mid));
  return blend((x != x) | (x == 0), x, y);
}

static inline vd vlog(vd x) {
  vl sub = (x > 0) & (x < 0x1p-1022);
  vd xs = blend(sub, x * 0x1p54, x);
  vl ix = (vl)xs;
  vl e = ((ix >> 52) & 0x7ff) - 1023 - (sub & 54);
  vd m = (vd)((ix & 0x000fffffffffffffLL) | 0x3ff0000000000000LL); /* [1, 2) */
  vl big = m > 1.4142135623730951;
  m = blend(big, m * 0.5, m);
  e -= big; /* a mask: -1 where set */
  vd f = m - 1, s = f / (2 + f), z = s * s, hfsq = 0.5 * f * f; /* f exact */
  static const double c[] = {2.0 / 21, 2.0 / 19, 2.0 / 17, 2.0 / 15, 2.0 / 13,
                             2.0 / 11, 2.0 / 9,  2.0 / 7,  2.0 / 5,  2.0 / 3};
  vd R = vm_poly(z, c, (int)(sizeof c / sizeof *c)) * z;
  vd ed = __builtin_convertvector(e, vd);
  vd r = ed * VM_LN2_HI - ((hfsq - (s * (hfsq + R) + ed * VM_LN2_LO)) - f);
  r = blend(x == 0, splat(-HUGE_VAL), r);
  r = blend(x == HUGE_VAL, x, r);
  return blend((x < 0) | (x != x), splat(NAN), r);
}

#endif
