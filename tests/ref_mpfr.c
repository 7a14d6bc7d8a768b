/* ref_mpfr.c — AGM reference for K and E in MPFR, and the ulp-error measure (ref_mpfr.h).
 * K = pi / (2 AGM(1, sqrt(m1))),  E = K (1 - sum_{n>=0} 2^(n-1) c_n^2),  c_0^2 = m = 1 - m1,
 * c_{n+1} = (a_n - b_n) / 2 (Abramowitz & Stegun 17.6). Valid for every m1 > 0. */
#include "ref_mpfr.h"

#include <math.h>

void ref_ellipke_m1(mpfr_ptr K, mpfr_ptr E, mpfr_srcptr m1) {
  const mpfr_prec_t p = REF_PREC + 64;
  mpfr_t a, b, c, t, sum, pw, kk;
  mpfr_inits2(p, a, b, c, t, sum, pw, kk, (mpfr_ptr)0);
  mpfr_set_ui(a, 1, MPFR_RNDN);
  mpfr_sqrt(b, m1, MPFR_RNDN);
  mpfr_ui_sub(c, 1, m1, MPFR_RNDN); /* c_0^2 = m */
  mpfr_div_2ui(sum, c, 1, MPFR_RNDN); /* 2^-1 c_0^2 */
  mpfr_set_ui(pw, 1, MPFR_RNDN);      /* 2^(n-1) for n = 1 */
  for (int it = 0; it < 200; it++) {
    mpfr_sub(c, a, b, MPFR_RNDN);
    mpfr_div_2ui(c, c, 1, MPFR_RNDN);
    if (mpfr_zero_p(c)) break;
    mpfr_sqr(t, c, MPFR_RNDN);
    mpfr_mul(t, t, pw, MPFR_RNDN);
    mpfr_add(sum, sum, t, MPFR_RNDN);
    mpfr_mul_2ui(pw, pw, 1, MPFR_RNDN);
    mpfr_mul(t, a, b, MPFR_RNDN);
    mpfr_add(a, a, b, MPFR_RNDN);
    mpfr_div_2ui(a, a, 1, MPFR_RNDN);
    mpfr_sqrt(b, t, MPFR_RNDN);
    /* stop once c is negligible at this precision relative to a */
    if (mpfr_get_exp(c) < mpfr_get_exp(a) - (mpfr_exp_t)p) break;
  }
  mpfr_const_pi(kk, MPFR_RNDN);
  mpfr_div(kk, kk, a, MPFR_RNDN);
  mpfr_div_2ui(kk, kk, 1, MPFR_RNDN);
  if (E) {
    mpfr_ui_sub(t, 1, sum, MPFR_RNDN);
    mpfr_mul(E, kk, t, MPFR_RNDN);
  }
  if (K) mpfr_set(K, kk, MPFR_RNDN);
  mpfr_clears(a, b, c, t, sum, pw, kk, (mpfr_ptr)0);
}

double ref_ulp_error(double x, mpfr_srcptr ref) {
  if (mpfr_nan_p(ref)) return isnan(x) ? 0.0 : INFINITY;
  if (isnan(x)) return INFINITY;
  if (mpfr_inf_p(ref)) return (isinf(x) && (x > 0) == (mpfr_sgn(ref) > 0)) ? 0.0 : INFINITY;
  if (isinf(x)) return INFINITY;
  mpfr_t d;
  mpfr_init2(d, REF_PREC + 64);
  mpfr_sub_d(d, ref, x, MPFR_RNDN);
  mpfr_abs(d, d, MPFR_RNDN);
  long e = mpfr_zero_p(ref) ? -2000 : (long)mpfr_get_exp(ref); /* |ref| in [2^(e-1), 2^e) */
  long ulp_exp = e - 53;
  if (ulp_exp < -1074) ulp_exp = -1074;
  mpfr_mul_2si(d, d, -ulp_exp, MPFR_RNDN);
  double r = mpfr_get_d(d, MPFR_RNDU);
  mpfr_clear(d);
  return r;
}
