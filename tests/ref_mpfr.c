/* ref_mpfr.c — AGM reference for K and E in MPFR, and the ulp-error measure (ref_mpfr.h).
 * K = pi / (2 AGM(1, sqrt(m1))),  E = K (1 - sum_{n>=0} 2^(n-1) c_n^2),  c_0^2 = m = 1 - m1,
 * c_{n+1} = (a_n - b_n) / 2 (Abramowitz & Stegun 17.6). Valid for every m1 > 0. */
#include "ref_mpfr.h"

#include <math.h>

#define P (REF_PREC + 64)

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

/* ---- MPFR reference: Patel's formula with parameter m = 1 - b^2 (m1 = b^2) ------------------ */
void ref_varx(mpfr_ptr out, mpfr_srcptr b) {
  if (mpfr_cmp_ui(b, 1) == 0) { /* 0/0: the circle */
    mpfr_set_d(out, 0.5, MPFR_RNDN);
    return;
  }
  mpfr_t m1, K, E, num, den;
  mpfr_inits2(P, m1, K, E, num, den, (mpfr_ptr)0);
  mpfr_sqr(m1, b, MPFR_RNDN); /* exact for a double b */
  if (mpfr_zero_p(m1)) {
    mpfr_set_d(out, 1.0, MPFR_RNDN);
    mpfr_div_ui(out, out, 3, MPFR_RNDN);
  } else {
    ref_ellipke_m1(K, E, m1);
    mpfr_div(num, K, E, MPFR_RNDN);
    mpfr_mul(num, num, m1, MPFR_RNDN);  /* b^2 K/E */
    mpfr_mul_2ui(den, m1, 1, MPFR_RNDN); /* 2 b^2 */
    mpfr_sub_ui(den, den, 1, MPFR_RNDN);
    mpfr_sub(num, den, num, MPFR_RNDN);  /* 2b^2 - 1 - b^2 K/E */
    mpfr_sub_ui(den, m1, 1, MPFR_RNDN);
    mpfr_mul_ui(den, den, 3, MPFR_RNDN); /* 3b^2 - 3 */
    mpfr_div(out, num, den, MPFR_RNDN);
  }
  mpfr_clears(m1, K, E, num, den, (mpfr_ptr)0);
}

/* V_x(t) = (1-t)^2 var_x(t/(1-t)), V_y(t) = t^2 var_x((1-t)/t) (= V_x(1 - t)): t in MPFR */
void ref_vx(mpfr_ptr out, mpfr_srcptr t) {
  mpfr_t om, q;
  mpfr_inits2(P, om, q, (mpfr_ptr)0);
  mpfr_ui_sub(om, 1, t, MPFR_RNDN);
  if (mpfr_zero_p(om)) {
    mpfr_set_ui(out, 0, MPFR_RNDN);
  } else {
    mpfr_div(q, t, om, MPFR_RNDN);
    ref_varx(out, q);
    mpfr_sqr(om, om, MPFR_RNDN);
    mpfr_mul(out, out, om, MPFR_RNDN);
  }
  mpfr_clears(om, q, (mpfr_ptr)0);
}
void ref_vy(mpfr_ptr out, mpfr_srcptr t) {
  mpfr_t om, q;
  mpfr_inits2(P, om, q, (mpfr_ptr)0);
  if (mpfr_zero_p(t)) {
    mpfr_set_ui(out, 0, MPFR_RNDN);
  } else {
    mpfr_ui_sub(om, 1, t, MPFR_RNDN);
    mpfr_div(q, om, t, MPFR_RNDN); /* b = (1-t)/t: > 1 for t < 1/2, negative parameter */
    ref_varx(out, q);
    mpfr_sqr(om, t, MPFR_RNDN);
    mpfr_mul(out, out, om, MPFR_RNDN);
  }
  mpfr_clears(om, q, (mpfr_ptr)0);
}
void ref_ratio(mpfr_ptr out, mpfr_srcptr t) {
  mpfr_t vx;
  mpfr_init2(vx, P);
  ref_vx(vx, t);
  ref_vy(out, t);
  mpfr_div(out, out, vx, MPFR_RNDN);
  mpfr_clear(vx);
}

/* d ln ratio / dt at t (0 < t < 1), central difference at relative step 2^-100 */
void ref_dlnratio(mpfr_ptr out, mpfr_srcptr t) {
  mpfr_t h, tp, tm, rp, rm;
  mpfr_inits2(P, h, tp, tm, rp, rm, (mpfr_ptr)0);
  mpfr_ui_sub(h, 1, t, MPFR_RNDN);
  if (mpfr_cmp(h, t) > 0) mpfr_set(h, t, MPFR_RNDN); /* min(t, 1-t) */
  mpfr_mul_2si(h, h, -100, MPFR_RNDN);
  mpfr_add(tp, t, h, MPFR_RNDN);
  mpfr_sub(tm, t, h, MPFR_RNDN);
  ref_ratio(rp, tp);
  ref_ratio(rm, tm);
  mpfr_div(rp, rp, rm, MPFR_RNDN);
  mpfr_log(rp, rp, MPFR_RNDN);
  mpfr_mul_2ui(h, h, 1, MPFR_RNDN);
  mpfr_div(out, rp, h, MPFR_RNDN);
  mpfr_clears(h, tp, tm, rp, rm, (mpfr_ptr)0);
}

/* t in (0, 1/2] with ratio(t) = r, r in (0, 1]: Newton on ln ratio from the guess t0 */
static void ref_inverse_small(mpfr_ptr t, mpfr_srcptr r, double t0) {
  mpfr_t f, d, lr;
  mpfr_inits2(P, f, d, lr, (mpfr_ptr)0);
  mpfr_log(lr, r, MPFR_RNDN);
  mpfr_set_d(t, t0, MPFR_RNDN);
  for (int it = 0; it < 12; it++) {
    ref_ratio(f, t);
    mpfr_log(f, f, MPFR_RNDN);
    mpfr_sub(f, f, lr, MPFR_RNDN);
    ref_dlnratio(d, t);
    mpfr_div(f, f, d, MPFR_RNDN); /* Newton step */
    mpfr_sub(t, t, f, MPFR_RNDN);
    mpfr_div(f, f, t, MPFR_RNDN);
    if (mpfr_zero_p(f) || mpfr_get_exp(f) < -(mpfr_exp_t)(REF_PREC - 40)) break;
  }
  mpfr_clears(f, d, lr, (mpfr_ptr)0);
}

/* reference t for ratio_to_t(r), r > 0 finite; t_out is the library's answer (used as guess) */
void ref_ratio_to_t(mpfr_ptr t, double r, double t_out) {
  mpfr_t rm;
  mpfr_init2(rm, P);
  mpfr_set_d(rm, r, MPFR_RNDN);
  if (r <= 1.0) {
    double t0 = (t_out > 0.0 && t_out <= 0.5) ? t_out : sqrt(r / 2.0);
    if (!(t0 > 0.0)) t0 = 0x1p-600;
    ref_inverse_small(t, rm, t0);
  } else {
    mpfr_ui_div(rm, 1, rm, MPFR_RNDN); /* ratio(1 - t) = 1 / ratio(t) */
    double u0 = (t_out >= 0.5 && t_out < 1.0) ? 1.0 - t_out : sqrt(0.5 / r);
    ref_inverse_small(t, rm, u0);
    mpfr_ui_sub(t, 1, t, MPFR_RNDN);
  }
  mpfr_clear(rm);
}
