/* ref_mpfr.h — high-precision references for the tests, in MPFR (an algorithm independent
 * of the library's: the arithmetic-geometric mean at REF_PREC bits).
 * Parameter convention: m1 = 1 - m is the complementary PARAMETER (m = k^2). */
#ifndef ICS_REF_MPFR_H
#define ICS_REF_MPFR_H

#include <mpfr.h>

#define REF_PREC 320

/* K(m) and E(m) for m = 1 - m1, m1 > 0 given exactly as an mpfr number (any m1 > 0, so
 * m1 > 1 covers negative m). Either output may be NULL. Outputs must be initialised. */
void ref_ellipke_m1(mpfr_ptr K, mpfr_ptr E, mpfr_srcptr m1);

/* Error of x against the reference in units in the last place of the double nearest to ref
 * (ulp = 2^(e-53) for |ref| in [2^(e-1), 2^e), at least 2^-1074). Infinite/NaN handling:
 * equal infinities or both NaN give 0; anything else involving them gives +inf. */
double ref_ulp_error(double x, mpfr_srcptr ref);

/* Ellipse variance functions (Patel 2013, Appendix A.7) from the closed form with parameter
 * m = 1 - b^2 evaluated through ref_ellipke_m1 (the 0/0 at b = 1 is harmless at this precision
 * except at b = 1 exactly, where the circle's 1/2 is returned). Arguments are exact MPFR values.
 *   ref_varx: var_x(b);  ref_vx / ref_vy: V_x(t), V_y(t) of the ellipse (1 - t, t);
 *   ref_ratio: V_y/V_x;  ref_dlnratio: d ln(ratio)/dt (central difference, step 2^-100 min(t,1-t));
 *   ref_ratio_to_t: t with ratio(t) = r for finite r > 0 (Newton on ln ratio from t_guess). */
void ref_varx(mpfr_ptr out, mpfr_srcptr b);
void ref_vx(mpfr_ptr out, mpfr_srcptr t);
void ref_vy(mpfr_ptr out, mpfr_srcptr t);
void ref_ratio(mpfr_ptr out, mpfr_srcptr t);
void ref_dlnratio(mpfr_ptr out, mpfr_srcptr t);
void ref_ratio_to_t(mpfr_ptr t, double r, double t_guess);

#endif
